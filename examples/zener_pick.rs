use impact::dynamic::*;
use impact::fem::plate_properties;
use impact::run::impact_of;
use impact::scene::Scene;
use plate_fem::dynamics::Newmark;
use plate_fem::{Mesh, Model, PlateProperties, Supports};
use std::time::Instant;
fn main() {
    let scene = Scene::default_scene();
    let props = plate_properties(&scene);
    for (h, body, v) in [(0.004, 0, 1.0), (0.003, 0, 1.0), (0.004, 1, 0.5)] {
        let thin = PlateProperties { length: 1.0, width: 1.0, thickness: h, ..props };
        let imp = impact_of(&scene, &scene.bodies[body], v);
        let s = Striker { k: imp.contact_stiffness, restitution: 1.0, mass: imp.mass, velocity: v };
        let z = 8.0 * (thin.rigidity() * thin.density * thin.thickness).sqrt();
        let (zp, zt) = zener(&s, z, 20000);
        println!(
            "h {h} body {body} v {v}: Hertz F {:.4} tc {:.4e}; Zener F {zp:.5} tc {zt:.5e}",
            s.hertz_force(),
            s.hertz_time()
        );
        for ne in [16, 24, 32, 48] {
            let t = Instant::now();
            let m2 = Model::new(thin, Mesh::uniform(1.0, 1.0, ne, ne).unwrap()).unwrap();
            let dt = zt / 200.0;
            let mut nm = Newmark::new(&m2, Supports::all_edges_simple(), dt, 0.5, 0.5).unwrap();
            let o = simulate(&s, Some(&mut nm), dt, 5.0 * zt);
            println!(
                "  FE {ne}: F {:.5} ({:+.2e}) tc {:.5e} ({:+.2e}) e_app {:.4} time {:?}",
                o.force_max,
                o.force_max / zp - 1.0,
                o.contact_time,
                o.contact_time / zt - 1.0,
                o.apparent_restitution,
                t.elapsed()
            );
        }
    }
}
