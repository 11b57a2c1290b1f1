use impact::dynamic::*;
use impact::run::impact_of;
use impact::scene::Scene;
fn main() {
    let scene = Scene::default_scene();
    let imp = impact_of(&scene, &scene.bodies[0], 0.008);
    for e in [0.99, 0.95, 0.9, 0.8, 0.65, 0.5, 0.3] {
        let s = Striker { k: imp.contact_stiffness, restitution: e, mass: imp.mass, velocity: 0.008 };
        let o = simulate(&s, None, s.hertz_time() / 800.0, 5.0 * s.hertz_time());
        println!("e {e}: apparent {:.5} rel {:+.4}", o.apparent_restitution, o.apparent_restitution / e - 1.0);
    }
}
