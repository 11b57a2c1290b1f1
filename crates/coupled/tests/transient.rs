//! The transient model's contact sequence, in-step maxima and error estimates.

use analytic::{Elastic, Plate, RockStrength, Sphere};
use coupled::supports::SupportSet;
use coupled::transient::case::striker;
use coupled::transient::{Striker, TransientCase, TransientSettings};
use plate_fem::Supports;

fn plate() -> Plate {
    Plate::new(0.4584, 0.360, 0.008, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap()
}

fn body(name: &str) -> Sphere {
    let (rho, r, e) = match name {
        "coal" => (1380.0, 0.025, 2.26e9),
        "gangue 1" => (2400.0, 0.0207888, 16e9),
        _ => (2400.0, 0.025, 16e9),
    };
    Sphere::new(name, rho, r, Elastic::new(e, 0.28).unwrap(), RockStrength::new(10e6, 30.0).unwrap()).unwrap()
}

fn con(i: usize) -> SupportSet {
    match i {
        1 => SupportSet::new("Con 1", Supports::con1()),
        _ => SupportSet::new("Con 2", Supports::con2(5.11545e8)),
    }
}

fn strike(name: &str) -> Striker {
    striker(&plate(), &body(name), 0.65, 0.008)
}

#[test]
#[ignore]
fn explore_end_midpoint() {
    let p = plate();
    for (n, steps) in [(20, 200.0), (20, 400.0), (40, 200.0)] {
        let case = TransientCase::new(&p, TransientSettings { elements: n, ..Default::default() }).unwrap();
        for b in ["gangue 1", "gangue 2", "coal"] {
            let s = strike(b);
            let t0 = std::time::Instant::now();
            let o = case.run_steps(&con(1), &s, 0.0, p.width() / 2.0, steps).unwrap();
            println!(
                "n {n} N {steps} {b}: t_c {:e} e {:?} contacts {} left {:?} final v {} impulse {} steps {} {:.2}s",
                s.hertz_time(),
                o.apparent_restitution,
                o.contacts.len(),
                o.left_at.map(|t| t / s.hertz_time()),
                o.final_velocity,
                o.total_impulse,
                o.steps_total,
                t0.elapsed().as_secs_f64()
            );
            for c in &o.contacts {
                println!("   {:?}", c);
            }
        }
    }
}

#[test]
#[ignore]
fn explore_thin() {
    for h in [0.002, 0.004, 0.008] {
        for scale in [1.0, 2.0] {
            let p = Plate::new(0.4584 * scale, 0.360 * scale, h, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap();
            let case = TransientCase::new(&p, TransientSettings::default()).unwrap();
            for b in ["gangue 2", "coal"] {
                for (ci, pt) in [(1, (p.length() / 2.0, p.width() / 2.0)), (1, (0.0, p.width() / 2.0)), (2, (p.length() / 2.0, 0.0))] {
                    let s = striker(&p, &body(b), 0.65, 0.008);
                    let o = case.run_steps(&con(ci), &s, pt.0, pt.1, 200.0).unwrap();
                    println!(
                        "h {h} x{scale} {b} Con {ci} {:?}: e {:?} contacts {} unfinished {} left {:?} v {}",
                        pt,
                        o.apparent_restitution,
                        o.contacts.len(),
                        o.unfinished_contact.is_some(),
                        o.left_at.map(|t| t / s.hertz_time()),
                        o.final_velocity
                    );
                }
            }
        }
    }
}
