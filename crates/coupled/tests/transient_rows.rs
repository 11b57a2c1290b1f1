//! The transient model's rows in the plan: interpolated values with their error estimates,
//! and the status flags of an unfinished impact and of an estimate above its tolerance.

mod common;

use analytic::{Elastic, Plate, RockStrength, Sphere};
use common::{body, con, plate, strike};
use coupled::supports::SupportSet;
use coupled::transient::estimate::Budget;
use coupled::transient::{TransientCase, TransientSettings};

#[test]
fn the_plan_reports_interpolated_values_with_their_errors() {
    use coupled::plan::{run_transient, Evidence};
    use coupled::scene::{Analysis, Points, Scene};
    let p = plate();
    let scene = Scene {
        name: "one case".into(),
        description: String::new(),
        plate: p,
        bodies: vec![body("coal")],
        restitution: 0.65,
        contact_law: coupled::transient::LawKind::Flores,
        conditions: vec![con(2)],
        points: Points::Pairs { pairs: vec![(p.length() / 2.0, p.width() / 2.0)] },
        transient_points: vec![(p.length() / 2.0, p.width() / 2.0)],
        velocities: vec![0.008],
        analyses: vec![Analysis::Responses],
        solver: analytic::Method::default(),
        signals: Default::default(),
        ensemble: None,
        transient_discretisation: coupled::transient::Discretisation::Fixed { settings: TransientSettings::default() },
        main_contact_share: coupled::transient::chatter::MAIN_CONTACT_SHARE,
        tail_beam: None,
        shell_mesh: None,
        measurement: None,
        stream: None,
        stream_law_sweep: Vec::new(),
        stream_plate_sweep: Vec::new(),
        gravity: 0.0,
        plate_damping: None,
    };
    let r = run_transient(&scene).unwrap();
    let v = r.responses[0].values().unwrap();
    let s = strike("coal");
    let o = TransientCase::new(&p, TransientSettings::default())
        .unwrap()
        .run(&con(2), &s, p.length() / 2.0, p.width() / 2.0)
        .unwrap();
    assert_eq!(v.compression, o.compression_max_interpolated);
    assert_eq!(v.contact_force, s.k * o.compression_max_interpolated.powf(1.5));
    let (fe, ce) = (v.contact_force_error.unwrap(), v.compression_error.unwrap());
    assert!(fe > 0.0 && fe < 1e-3 * v.contact_force && ce > 0.0 && ce < 1e-3 * v.compression);
    match v.evidence {
        Evidence::Transient {
            contacts,
            left_for_good,
            peak_force,
            peak_force_error,
            contact_time_error,
            restitution_error,
            ..
        } => {
            assert!(contacts == 1 && left_for_good);
            assert_eq!(peak_force, o.force_max_interpolated);
            assert!(
                peak_force_error.unwrap() > 0.0
                    && contact_time_error.unwrap() > 0.0
                    && restitution_error.unwrap() > 0.0
            );
        }
        e => panic!("{e:?}"),
    }
}

/// A scene of one case on `plate`: `b` under `set` at `point` and `v`, discretised by `disc`.
fn one_case(
    plate: Plate,
    b: Sphere,
    set: SupportSet,
    point: (f64, f64),
    v: f64,
    disc: coupled::transient::Discretisation,
) -> coupled::scene::Scene {
    use coupled::scene::{Analysis, Points, Scene};
    Scene {
        name: "one case".into(),
        description: String::new(),
        plate,
        bodies: vec![b],
        restitution: 0.65,
        contact_law: coupled::transient::LawKind::Flores,
        conditions: vec![set],
        points: Points::Pairs { pairs: vec![point] },
        transient_points: vec![point],
        velocities: vec![v],
        analyses: vec![Analysis::Responses],
        solver: analytic::Method::default(),
        signals: Default::default(),
        ensemble: None,
        transient_discretisation: disc,
        main_contact_share: coupled::transient::chatter::MAIN_CONTACT_SHARE,
        tail_beam: None,
        shell_mesh: None,
        measurement: None,
        stream: None,
        stream_law_sweep: Vec::new(),
        stream_plate_sweep: Vec::new(),
        gravity: 0.0,
        plate_damping: None,
    }
}

/// A heavy sphere on a thin plate rides the plate for about one plate period and is struck
/// several times: the paper's plate at 3 mm, a 60 mm gangue sphere (2.2 kg against the plate's
/// 3.9 kg) at the middle of a free edge, 0.008 m/s. The plate's period is 22 Hertz times, and
/// a window of 20 Hertz times ends while the sphere is still among its contacts: the row must
/// say so in its validity status (and count in the summary), not read as a finished impact.
/// With the default window the stopping rule proves the sphere gone (its final velocity away
/// from the plate, beyond the plate's reach), and the flag is gone.
#[test]
fn an_impact_cut_by_its_window_is_flagged_unfinished() {
    use coupled::plan::{run_transient, Evidence};
    use coupled::transient::Discretisation;
    use coupled::validity::FLAG_UNFINISHED;
    let p = Plate::new(0.4584, 0.360, 0.003, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap();
    let big = Sphere::new(
        "big gangue",
        2400.0,
        0.060,
        Elastic::new(16e9, 0.28).unwrap(),
        RockStrength::new(37.68e6, 37.0).unwrap(),
    )
    .unwrap();
    let point = (0.2292, 0.0);
    let short = TransientSettings { window_contacts: 20.0, ..TransientSettings::default() };
    let run = |settings| {
        let scene = one_case(p, big.clone(), con(1), point, 0.008, Discretisation::Fixed { settings });
        run_transient(&scene).unwrap()
    };
    let cut = run(short);
    let v = cut.responses[0].values().unwrap();
    let Evidence::Transient { left_for_good, contacts, .. } = v.evidence else { panic!("{:?}", v.evidence) };
    assert!(!left_for_good, "the 20 Hertz-time window should end first ({contacts} contacts)");
    assert!(v.validity.flags().contains(&FLAG_UNFINISHED), "{:?}", v.validity.flags());
    assert!(!v.validity.all_valid());
    assert_eq!(cut.summary().unfinished, 1);

    let whole = run(TransientSettings::default());
    let v = whole.responses[0].values().unwrap();
    let Evidence::Transient { left_for_good, contacts, final_velocity, .. } = v.evidence else {
        panic!("{:?}", v.evidence)
    };
    assert!(left_for_good && contacts >= 2 && final_velocity < 0.0, "{contacts} contacts, v_end {final_velocity}");
    assert!(!v.validity.flags().contains(&FLAG_UNFINISHED), "{:?}", v.validity.flags());
    assert_eq!(whole.summary().unfinished, 0);
    // The first contact is the same in both runs: only the window differs.
    assert_eq!(cut.responses[0].values().unwrap().compression, v.compression);
}

/// A case whose error estimate the budget cannot bring within the tolerance carries the
/// discretisation flag in its status, beside the "budget reached" of its discretisation.
#[test]
fn a_case_above_its_tolerance_is_flagged() {
    use coupled::plan::{run_transient, Evidence};
    use coupled::transient::Discretisation;
    use coupled::validity::FLAG_DISCRETISATION;
    let p = plate();
    let centre = (p.length() / 2.0, p.width() / 2.0);
    // The starting mesh and step (20 elements, 200 steps per Hertz time) are the whole
    // budget, and their estimate (about 1e-4 at the centre) is far above 1e-7.
    let tight = Discretisation::Tolerance {
        tolerance: 1e-7,
        budget: Budget { max_elements: 20, max_steps_per_contact: 200.0 },
    };
    let loose = Discretisation::Tolerance { tolerance: 0.05, budget: Budget::default() };
    for (disc, flagged) in [(tight, true), (loose, false)] {
        let r = run_transient(&one_case(p, body("coal"), con(1), centre, 0.008, disc)).unwrap();
        let v = r.responses[0].values().unwrap();
        let Evidence::Transient { met_tolerance, relative_error, .. } = v.evidence else { panic!() };
        assert_eq!(met_tolerance, !flagged);
        assert_eq!(v.validity.flags().contains(&FLAG_DISCRETISATION), flagged, "{:?} {relative_error:?}", v.validity);
        assert_eq!(r.summary().above_tolerance, usize::from(flagged));
        let c = v.validity.discretisation.expect("a tolerance gives the criterion");
        assert_eq!((c.value, c.limit), (relative_error.unwrap(), if flagged { 1e-7 } else { 0.05 }));
    }
}
