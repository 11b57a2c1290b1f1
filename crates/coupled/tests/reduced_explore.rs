use analytic::{Elastic, Plate, RockStrength, Sphere};
use coupled::reduced::{FreeSteps, ReducedModel, ReducedSettings, SignalSpec};
use coupled::transient::case::striker;
use coupled::transient::{Quantities, TransientCase, TransientSettings};
use coupled::SupportSet;
use plate_fem::Supports;
use std::time::Instant;

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

#[test]
fn explore() {
    let p = plate();
    let full = TransientCase::new(&p, TransientSettings::default()).unwrap();
    for (ci, set) in [
        SupportSet::new("Con 1", Supports::con1()),
        SupportSet::new("Con 2", Supports::con2(5.11545e8)),
        SupportSet::new("Con 3", Supports::con3(5.11545e8)),
    ]
    .iter()
    .enumerate()
    {
        for n in [10usize, 20, 40, 80, 160] {
            let t = Instant::now();
            let red =
                ReducedModel::new(&p, set, ReducedSettings { modes: n, damping_ratio: 0.0, ..Default::default() })
                    .unwrap();
            let build = t.elapsed();
            let probes = red.probes(&SignalSpec::new(vec![(0.1, 0.1), (0.3, 0.25)])).unwrap();
            for b in ["coal", "gangue 2"] {
                for &(x, z) in &[(0.2292, 0.18), (0.2292, 0.0), (0.1146, 0.18)] {
                    let s = striker(&p, &body(b), 0.65, 0.008);
                    let t = Instant::now();
                    let r = red.impact(&s, x, z, &probes).unwrap();
                    let tr = t.elapsed();
                    let spc = s.hertz_time() / r.dt;
                    let t = Instant::now();
                    let f = if n == 10 || true { Some(full.run_steps(set, &s, x, z, spc).unwrap()) } else { None };
                    let tf = t.elapsed();
                    let qr = Quantities::of(&r.outcome, &s);
                    if let Some(f) = f {
                        let qf = Quantities::of(&f, &s);
                        println!("{} N={n} {b} ({x},{z}) build {:?} red {:?} full {:?} | P {:.3e} tc {:.3e} e {:.3e} | contacts {} {} left {:?} {:?} steps {} {}",
                            set.name, build, tr, tf,
                            qr.peak_force / qf.peak_force - 1.0, qr.contact_time / qf.contact_time - 1.0, qr.restitution / qf.restitution - 1.0,
                            r.outcome.contacts.len(), f.contacts.len(), r.outcome.left_at, f.left_at, r.outcome.steps_total, f.steps_total);
                    }
                }
            }
            let _ = (ci, FreeSteps::Exact);
        }
    }
}
