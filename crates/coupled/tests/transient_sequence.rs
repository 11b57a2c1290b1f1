//! The transient model's contact sequence on the plate: one contact where the sphere
//! rebounds clear, several where the plate catches it again.

mod common;

use analytic::{Elastic, Plate};
use common::{body, con, plate, strike};
use coupled::transient::case::striker;
use coupled::transient::{simulate, TransientCase, TransientSettings};

#[test]
fn on_the_paper_plate_the_end_midpoint_is_struck_once() {
    // The 8 mm plate, Con 1, the middle of the end x = 0, 0.008 m/s: every body rebounds
    // (positive apparent restitution) and the plate never catches it again.
    let p = plate();
    let case = TransientCase::new(&p, TransientSettings::default()).unwrap();
    for b in ["coal", "gangue 1", "gangue 2"] {
        let s = strike(b);
        let o = case.run(&con(1), &s, 0.0, p.width() / 2.0).unwrap();
        println!(
            "{b}: apparent e {:.4}, {} contact(s), left for good at {:.3} t_c",
            o.apparent_restitution.unwrap(),
            o.contacts.len(),
            o.left_at.unwrap() / s.hertz_time()
        );
        assert!(o.apparent_restitution.unwrap() > 0.3 && o.contacts.len() == 1 && o.left_at.is_some());
        assert_eq!(o.final_velocity, o.rebound_velocity.unwrap());
    }
}

#[test]
fn a_thin_plate_struck_near_its_end_is_struck_again() {
    // The paper's plate at 2 mm, Con 1, the coal sphere at the middle of the end x = 0: the
    // sphere still moves toward the plate when the first contact ends (apparent restitution
    // below zero), and the plate comes back to strike it.
    let p = Plate::new(0.4584, 0.360, 0.002, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap();
    let s = striker(&p, &body("coal"), 0.65, 0.008);
    let tc = s.hertz_time();
    let (x, z) = (0.0, p.width() / 2.0);
    let case = TransientCase::new(&p, TransientSettings::default()).unwrap();
    let o = case.run(&con(1), &s, x, z).unwrap();
    // The first contact is exactly that of a run stopping at the first separation.
    let dt = tc / 200.0;
    let mut nm = plate_fem::dynamics::Newmark::new(case.model(), con(1).supports, dt, x, z).unwrap();
    let first = simulate(&s, Some(&mut nm), dt, 20.0 * tc);
    assert_eq!(first.history, o.history);
    assert_eq!(
        (first.force_max, first.compression_max, first.contact_time, first.apparent_restitution, first.steps),
        (o.force_max, o.compression_max, o.contact_time, o.apparent_restitution, o.steps)
    );
    assert_eq!(first.at_max_compression_interpolated, o.at_max_compression_interpolated);
    assert!(first.left_at.is_none() && first.contacts.len() == 1);
    assert!(o.apparent_restitution.unwrap() < 0.0);
    let left = o.left_at.expect("the sphere leaves within the window");
    assert!(o.contacts.len() >= 2 && o.unfinished_contact.is_none(), "{:?}", o.contacts);
    assert!(o.final_velocity < 0.0 && left > o.contacts.last().map_or(0.0, |c| c.start + c.duration));
    assert!((o.total_impulse - s.mass * (s.velocity - o.final_velocity)).abs() < 1e-12 * s.mass * s.velocity);
    // The sequence against a run with half the step on a mesh with h halved.
    let fine = case.refined(&p).unwrap().run_steps(&con(1), &s, x, z, 400.0).unwrap();
    assert_eq!(fine.contacts.len(), o.contacts.len());
    for (a, b) in o.contacts.iter().zip(&fine.contacts) {
        println!(
            "contact at {:.4} t_c for {:.4} t_c, peak {:.4} N, impulse {:.4e} N s (finer: {:.4}, {:.4}, {:.4}, {:.4e})",
            a.start / tc,
            a.duration / tc,
            a.peak_force,
            a.impulse,
            b.start / tc,
            b.duration / tc,
            b.peak_force,
            b.impulse
        );
        assert!((a.start - b.start).abs() < 0.02 * tc && (a.duration - b.duration).abs() < 0.02 * tc);
        assert!((a.impulse - b.impulse).abs() < 0.02 * s.mass * s.velocity);
    }
    println!("left for good at {:.3} t_c, final velocity {:.4e} m/s", left / tc, o.final_velocity);
}
