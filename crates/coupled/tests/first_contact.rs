//! The first contact on a plate model with the step and window given directly, and the same
//! run with the deflection field recorded.

use analytic::{Elastic, Plate, RockStrength, Sphere};
use coupled::discretisation::{mesh_for, plate_properties};
use coupled::supports::SupportSet;
use coupled::transient::case::{striker, WINDOW_HERTZ_TIMES};
use coupled::transient::frames::first_contact_frames;
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
    let o = first_contact_on(case.model(), Supports::all_edges_simple(), &s, (0.5, 0.5), tz / 200.0, 5.0 * tz).unwrap();
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
    let direct = first_contact_on(case.model(), set.supports, &s, (x, z), dt, WINDOW_HERTZ_TIMES * s.hertz_time());
    assert_eq!(direct.unwrap(), case.first_contact(&set, &s, x, z, 200.0).unwrap());
}

/// Recording leaves the run as it is, takes a frame at the touch, every fifth step and at the
/// separation, and each frame's deflection at the struck node (the centre, a node of the
/// mesh) is the point deflection of the history sample at the same step.
#[test]
fn recorded_frames_follow_the_run() {
    let p = Plate::new(0.4584, 0.360, 0.008, 7850.0, steel()).unwrap();
    let props = plate_properties(&p);
    let mesh = mesh_for(&props, 20).unwrap();
    let case = TransientCase::on_mesh(&p, mesh.clone(), TransientSettings::default()).unwrap();
    let s = striker(&p, &coal(), 0.65, 0.008);
    let (x, z) = (p.length() / 2.0, p.width() / 2.0);
    let (dt, t_max) = (s.hertz_time() / 200.0, 20.0 * s.hertz_time());
    let plain = first_contact_on(case.model(), Supports::con1(), &s, (x, z), dt, t_max).unwrap();
    let rec = first_contact_frames(case.model(), Supports::con1(), &s, (x, z), dt, t_max, 5).unwrap();
    assert_eq!(rec.outcome, plain);
    let steps = plain.steps_total;
    assert_eq!(rec.frames.len(), 1 + steps / 5 + usize::from(steps % 5 != 0));
    assert_eq!(rec.frames[0].step, 0);
    assert!(rec.frames[0].w.iter().all(|&w| w == 0.0));
    assert_eq!(rec.frames.last().unwrap().step, steps);
    let node = mesh.node(mesh.nx() / 2, mesh.nz() / 2);
    let scale = plain.history.iter().map(|h| h.plate_displacement.abs()).fold(0.0, f64::max);
    for f in &rec.frames[1..] {
        assert_eq!(f.w.len(), mesh.nodes());
        let w = plain.history[f.step - 1].plate_displacement;
        assert!((f.w[node] - w).abs() <= 1e-12 * scale, "step {}: {} against {w}", f.step, f.w[node]);
    }
}
