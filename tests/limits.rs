//! Hand-derived limits of the beam model through the whole pipeline (scene -> run).

use analytic::{beam_compliance, Condition};
use approx::assert_relative_eq;
use coupled::plan::{fundamental_periods, impact_of, run, ModelKind, Results};
use coupled::BeamModel;
use impact::scene::{Scene, SceneSource};

fn beam(scene: &Scene) -> Results {
    run(scene, &BeamModel { plate: &scene.plate }, ModelKind::Beam, &fundamental_periods(scene).unwrap()).unwrap()
}

/// At x = 0 and x = L of Con 1 the plate takes no energy: the rigid Hertz-Flores result
/// δ = (5e m v² / 4K)^{2/5} (eq. 14 with C = 0).
#[test]
fn ends_of_con1_are_a_rigid_target() {
    let scene = Scene::default_scene();
    let results = beam(&scene);
    let l = scene.plate.length();
    let mut n = 0;
    for r in results.responses.iter().filter(|r| r.condition == "Con 1" && (r.x == 0.0 || r.x == l)) {
        let body = scene.bodies.iter().find(|b| b.name == r.body).unwrap();
        let imp = impact_of(&scene, body, r.velocity);
        let delta = (5.0 * scene.restitution * imp.mass * r.velocity.powi(2) / (4.0 * imp.contact_stiffness)).powf(0.4);
        let v = r.values().unwrap();
        assert_relative_eq!(v.compression, delta, max_relative = 1e-13);
        assert_relative_eq!(v.rock_total_ratio, 1.0, max_relative = 1e-13);
        assert_eq!(v.plate_ratio, 0.0);
        n += 1;
    }
    assert_eq!(n, 2 * 3 * 2, "two ends x three bodies x two velocities");
}

/// At x = 0 in Con 2 the load sits on the left spring pair: each spring carries P/2 and the
/// compliance is 1/(2k_T); the right pair carries nothing.
#[test]
fn con2_end_loads_one_spring_pair() {
    let scene = Scene::default_scene();
    let results = beam(&scene);
    for r in results.responses.iter().filter(|r| r.condition == "Con 2" && r.x == 0.0) {
        let k_t = 5.11545e8;
        let v = r.values().unwrap();
        assert_relative_eq!(v.compliance.unwrap(), 0.5 / k_t, max_relative = 1e-14);
        assert_relative_eq!(v.spring_forces[0].force, v.contact_force / 2.0, max_relative = 1e-14);
        assert_eq!(v.spring_forces[1].force, 0.0);
    }
}

/// k_T → ∞: Con 2 and Con 3 reach Con 1 at every point of the default scene, with the gap
/// in P falling as 1/k_T (the spring compliances are O(1/k_T)).
#[test]
fn stiff_springs_reach_fixed_ends_everywhere() {
    let scene = Scene::default_scene();
    let p = scene.plate;
    for (x, _) in scene.point_pairs() {
        let c1 = beam_compliance(&p, Condition::BothFixed, x).unwrap().total();
        for k in [1e12, 1e16] {
            for cond in [Condition::BothSprings { k_t: k }, Condition::FixedAndSprings { k_t: k }] {
                let c = beam_compliance(&p, cond, x).unwrap().total();
                assert!((c - c1).abs() <= 1.0 / k, "x = {x}, k = {k}: {c} vs {c1}");
            }
        }
    }
}
