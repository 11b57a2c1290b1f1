//! A full paper sweep: 101 points x 3 conditions x 3 bodies, responses at two velocities
//! and yield velocities, through the same pipeline as `impact sweep`.

use coupled::plan::{fundamental_periods, run, ModelKind};
use coupled::BeamModel;
use criterion::{criterion_group, criterion_main, Criterion};
use impact::scene::{Scene, SceneSource};
use std::hint::black_box;

fn paper_sweep(c: &mut Criterion) {
    let mut scene = Scene::default_scene().with_sweep(101);
    scene.analyses = vec![coupled::Analysis::Responses, coupled::Analysis::YieldVelocity];
    let cases = scene.points.len() * scene.conditions.len() * scene.bodies.len();
    // The fundamental periods (for the quasi-static validity) are computed once per scene,
    // outside the timed loop, as `impact sweep` does.
    let periods = fundamental_periods(&scene).unwrap();
    c.bench_function(&format!("paper sweep ({cases} point-condition-body cases)"), |b| {
        b.iter(|| run(black_box(&scene), &BeamModel { plate: &scene.plate }, ModelKind::Beam, &periods).unwrap())
    });
}

criterion_group!(benches, paper_sweep);
criterion_main!(benches);
