//! The first contact on a plate model with the step and window given directly, and the same
//! run with the deflection field recorded.

use analytic::{Elastic, Plate, RockStrength, Sphere};
use coupled::discretisation::{mesh_for, plate_properties};
use coupled::supports::SupportSet;
use coupled::transient::case::{striker, WINDOW_HERTZ_TIMES};
use coupled::transient::frames::{impact_frames, Ringing};
use coupled::transient::{first_contact_on, zener, TransientCase, TransientSettings};
use plate_fem::{Mesh, Supports};

fn steel() -> Elastic {
    Elastic::new(210e9, 0.3).unwrap()
}

fn coal() -> Sphere {
    Sphere::new("coal", 1380.0, 0.025, Elastic::new(2.26e9, 0.28).unwrap(), RockStrength::new(8.39e6, 25.0).unwrap())
        .unwrap()
}

/// A 1 m x 1 m, 4 mm plate simply supported at its edges and struck at its centre at 1 m/s
/// (e = 1) is Zener's infinite plate while bending waves have not come back from the edges:
/// the plate's point impedance 8√(Dρh) and the Hertz contact, an ODE integrated apart from the
/// FE model. On 24 x 24 elements P_max and t_c are within 1 % of it (0.5 % and 0.6 %).
#[test]
fn a_large_plate_matches_zeners_infinite_plate() {
    let thin = Plate::new(1.0, 1.0, 0.004, 7850.0, steel()).unwrap();
    let props = plate_properties(&thin);
    let s = striker(&thin, &coal(), 1.0, 1.0);
    let impedance = 8.0 * (props.rigidity() * props.density * props.thickness).sqrt();
    let (fz, tz) = zener(&s, impedance, 20000);
    let tz = tz.unwrap();
    let mesh = Mesh::uniform(1.0, 1.0, 24, 24).unwrap();
    let case = TransientCase::on_mesh(&thin, mesh, TransientSettings::default()).unwrap();
    let o = first_contact_on(case.model(), (Supports::all_edges_simple(), None), &s, (0.5, 0.5), tz / 200.0, 5.0 * tz)
        .unwrap();
    let tc = o.contact_time.unwrap();
    assert!((o.force_max / fz - 1.0).abs() < 0.01, "P_max {} against Zener's {fz}", o.force_max);
    assert!((tc / tz - 1.0).abs() < 0.01, "t_c {tc} against Zener's {tz}");
}

/// With the step of the case's Hertz time and its window, [`first_contact_on`] is the case's
/// own first contact.
#[test]
fn first_contact_on_the_cases_model_is_the_cases_first_contact() {
    let p = Plate::new(0.4584, 0.360, 0.008, 7850.0, steel()).unwrap();
    let case = TransientCase::new(&p, TransientSettings::default()).unwrap();
    let set = SupportSet::new("Con 2", Supports::con2(5.11545e8));
    let s = striker(&p, &coal(), 0.65, 0.008);
    let (x, z) = (p.length() / 2.0, p.width() / 2.0);
    let dt = s.hertz_time() / 200.0;
    let direct =
        first_contact_on(case.model(), (set.supports, None), &s, (x, z), dt, WINDOW_HERTZ_TIMES * s.hertz_time());
    assert_eq!(direct.unwrap(), case.first_contact(&set, &s, x, z, 200.0).unwrap());
}

/// Recording leaves the whole-impact run as it is, takes a frame at the touch, every fifth step and at the
/// separation, and each frame's deflection at the struck node (the centre, a node of the
/// mesh) is the point deflection of the history sample at the same step, its time that
/// sample's time. Then the free plate rings for two fundamental periods with a frame every
/// tenth step: Newmark's average-acceleration rule conserves the energy of a free linear
/// system exactly, so the plate's energy stays what it was when the sphere left (to
/// round-off, 1e-9 of it), and the sphere flies on at its final velocity.
#[test]
fn recorded_frames_follow_the_run_and_the_ringing() {
    let p = Plate::new(0.4584, 0.360, 0.008, 7850.0, steel()).unwrap();
    let props = plate_properties(&p);
    let mesh = mesh_for(&props, 20).unwrap();
    let case = TransientCase::on_mesh(&p, mesh.clone(), TransientSettings::default()).unwrap();
    let s = striker(&p, &coal(), 0.65, 0.008);
    let (x, z) = (p.length() / 2.0, p.width() / 2.0);
    let (dt, t_max) = (s.hertz_time() / 200.0, 20.0 * s.hertz_time());
    let mut nm = plate_fem::dynamics::Newmark::new(case.model(), Supports::con1(), dt, x, z).unwrap();
    let facts = case.facts(&Supports::con1(), x, z);
    let plain = coupled::transient::simulate_with(&s, Some(&mut nm), facts, dt, t_max);
    assert!(plain.left_at.is_some(), "the sphere leaves");
    let period = case.fundamental_period(&Supports::con1()).unwrap();
    let ringing = Ringing { duration: 2.0 * period, every: 10 };
    let rec = impact_frames(&case, Supports::con1(), &s, (x, z), dt, t_max, 5, ringing).unwrap();
    assert_eq!(rec.outcome, plain);
    let steps = plain.steps_total;
    let rung = (2.0 * period / dt).ceil() as usize;
    assert_eq!(rec.ringing.len(), rung);
    let in_run = 1 + steps / 5 + usize::from(steps % 5 != 0);
    assert_eq!(rec.frames.len(), in_run + rung / 10 + usize::from(rung % 10 != 0));
    assert_eq!(rec.frames[0].step, 0);
    assert!(rec.frames[0].w.iter().all(|&w| w == 0.0));
    assert_eq!(rec.frames[in_run - 1].step, steps);
    assert_eq!(rec.frames.last().unwrap().step, steps + rung);
    let node = mesh.node(mesh.nx() / 2, mesh.nz() / 2);
    let history: Vec<_> = [&plain.history[..], &plain.later_history[..], &rec.ringing[..]].concat();
    let scale = history.iter().map(|h| h.plate_displacement.abs()).fold(0.0, f64::max);
    for f in &rec.frames[1..] {
        assert_eq!((f.w.len(), f.moments.len()), (mesh.nodes(), mesh.elements()));
        let h = &history[f.step - 1];
        assert_eq!(f.t, h.t);
        assert!(
            (f.w[node] - h.plate_displacement).abs() <= 1e-12 * scale,
            "step {}: {} against {h:?}",
            f.step,
            f.w[node]
        );
    }
    let plate = |h: &coupled::transient::Sample| h.plate_kinetic + h.plate_strain + h.springs;
    let left = plate(&history[steps - 1]);
    for h in &rec.ringing {
        assert!((plate(h) - left).abs() <= 1e-9 * left, "{} against {left}", plate(h));
        assert_eq!((h.force, h.sphere_velocity), (0.0, plain.final_velocity));
    }
}
