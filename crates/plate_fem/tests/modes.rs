//! The plate's modes against Navier's frequencies, inverse iteration and their own
//! definition; the residual flexibility against the static compliance.

use plate_fem::dynamics::fundamental_frequency;
use plate_fem::modes::{EigenMethod, RESIDUAL_TOLERANCE};
use plate_fem::{Mesh, Model, Modes, PlateProperties, ResidualFlexibility, Supports};
use std::time::Instant;

fn props(l: f64, b: f64) -> PlateProperties {
    PlateProperties {
        length: l,
        width: b,
        thickness: 0.008,
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
        density: 7850.0,
    }
}

#[test]
fn explore() {
    let (l, b) = (0.4584, 0.36);
    let p = props(l, b);
    let d = p.rigidity();
    let rho_h = p.density * p.thickness;
    for n in [8usize, 16, 32] {
        let model = Model::new(p, Mesh::uniform(l, b, n, n).unwrap()).unwrap();
        let s = Supports::all_edges_simple();
        let t = Instant::now();
        let modes = Modes::krylov(&model.factorize(&s).unwrap(), 12).unwrap();
        let el = t.elapsed();
        let mut navier: Vec<f64> = (1..8)
            .flat_map(|m| (1..8).map(move |k| (m, k)))
            .map(|(m, k)| {
                std::f64::consts::PI.powi(2)
                    * ((m * m) as f64 / (l * l) + (k * k) as f64 / (b * b))
                    * (d / rho_h).sqrt()
            })
            .collect();
        navier.sort_by(f64::total_cmp);
        let errs: Vec<f64> = modes.omegas().iter().zip(&navier).map(|(a, b)| a / b - 1.0).collect();
        println!("n={n} {:?} {:?} errs {:?}", el, modes.method(), errs);
    }
    for n in [20usize, 40] {
        let model =
            Model::new(p, plate_fem::Mesh::uniform(l, b, n, (n as f64 * b / l / 2.0).round() as usize * 2).unwrap())
                .unwrap();
        for count in [20usize, 60, 120] {
            let s = Supports::con1();
            let t = Instant::now();
            let fact = model.factorize(&s).unwrap();
            let modes = Modes::krylov(&fact, count).unwrap();
            let el = t.elapsed();
            let t = Instant::now();
            let rf = ResidualFlexibility::new(&fact, &modes).unwrap();
            let el2 = t.elapsed();
            let (w1, _) = fundamental_frequency(&model, &s, 200).unwrap();
            let worst = modes.residuals().iter().copied().fold(0.0, f64::max);
            let c = fact.respond(0.2292, 0.18).unwrap().compliance;
            let cr = rf.at(0.2292, 0.18).unwrap();
            let modal: f64 =
                modes.at(0.2292, 0.18).unwrap().iter().zip(modes.omegas()).map(|(f, w)| f * f / (w * w)).sum();
            println!(
                "n={n} N={count} {:?} rf {:?} {:?} f1 {} rel {:e} fN {} worst res {:e} orth {:e} Cres/C {:e} check {:e}",
                el, el2, modes.method(), modes.frequencies_hz()[0], modes.omegas()[0] / w1 - 1.0, modes.frequencies_hz()[count - 1], worst, modes.orthogonality(), cr / c, (cr + modal) / c - 1.0
            );
            let _ = (RESIDUAL_TOLERANCE, EigenMethod::Dense);
        }
    }
}
