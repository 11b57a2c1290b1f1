use impact::dynamic::*;
use impact::fem::{mesh_for, plate_properties};
use impact::run::impact_of;
use impact::scene::Scene;
use plate_fem::dynamics::{fundamental_frequency, Newmark};
use plate_fem::{Mesh, Model, PlateProperties, Supports};
use std::time::Instant;

fn main() {
    let scene = Scene::default_scene();
    let coal = &scene.bodies[0];
    let imp = impact_of(&scene, coal, 0.008);
    let s = Striker { k: imp.contact_stiffness, restitution: 1.0, mass: imp.mass, velocity: 0.008 };
    let tc = s.hertz_time();
    println!("Hertz tc {tc:e} Fmax {}", s.hertz_force());
    for n in [50, 100, 200, 400] {
        let o = simulate(&s, None, tc / n as f64, 3.0 * tc);
        println!(
            "rigid n {n}: Fmax {:.8} ({:+.2e}) tc {:.6e} ({:+.2e}) e_app {:.6} energy err {:.2e}",
            o.force_max,
            o.force_max / s.hertz_force() - 1.0,
            o.contact_time,
            o.contact_time / tc - 1.0,
            o.apparent_restitution,
            o.max_energy_error
        );
    }
    let props = plate_properties(&scene);
    let model = Model::new(props, mesh_for(&props, 40).unwrap()).unwrap();
    let (w1, ch) = fundamental_frequency(&model, &Supports::con1(), 200).unwrap();
    println!(
        "paper plate Con1: omega1 {w1:.3} rad/s, f1 {:.3} Hz, T1 {:.4e} s, tc/T1 {:.3}, change {ch:e}",
        w1 / 6.2832,
        6.2832 / w1,
        tc / (6.2832 / w1)
    );
    for n in [50, 100, 200, 400] {
        let t = Instant::now();
        let mut nm =
            Newmark::new(&model, Supports::con1(), tc / n as f64, props.length / 2.0, props.width / 2.0).unwrap();
        let o = simulate(&s, Some(&mut nm), tc / n as f64, 5.0 * tc);
        println!(
            "plate n {n}: Fmax {:.8} tc {:.6e} e_app {:.6} energy err {:.2e} steps {} time {:?}",
            o.force_max,
            o.contact_time,
            o.apparent_restitution,
            o.max_energy_error,
            o.steps,
            t.elapsed()
        );
    }
    // Zener
    let thin = PlateProperties { length: 1.2, width: 1.2, thickness: 0.002, ..props };
    let g2 = &scene.bodies[2];
    let imp2 = impact_of(&scene, g2, 0.5);
    let s2 = Striker { k: imp2.contact_stiffness, restitution: 1.0, mass: imp2.mass, velocity: 0.5 };
    let z = 8.0 * (thin.rigidity() * thin.density * thin.thickness).sqrt();
    let (zp, zt) = zener(&s2, z, 20000);
    println!("Zener: Z {z:.3} Hertz F {:.4} tc {:.4e}; Zener F {zp:.5} tc {zt:.5e}", s2.hertz_force(), s2.hertz_time());
    for ne in [24, 48, 96] {
        let t = Instant::now();
        let m2 = Model::new(thin, Mesh::uniform(1.2, 1.2, ne, ne).unwrap()).unwrap();
        let dt = s2.hertz_time() / 200.0;
        let mut nm = Newmark::new(&m2, Supports::all_edges_simple(), dt, 0.6, 0.6).unwrap();
        let o = simulate(&s2, Some(&mut nm), dt, 20.0 * s2.hertz_time());
        println!(
            "FE {ne}: F {:.5} ({:+.2e}) tc {:.5e} ({:+.2e}) e_app {:.4} energy err {:.2e} time {:?}",
            o.force_max,
            o.force_max / zp - 1.0,
            o.contact_time,
            o.contact_time / zt - 1.0,
            o.apparent_restitution,
            o.max_energy_error,
            t.elapsed()
        );
    }
}
