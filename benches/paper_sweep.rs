//! A full paper sweep: 101 points x 3 conditions x 3 bodies, responses at two velocities
//! and yield velocities, through the same pipeline as `impact sweep`.

use criterion::{criterion_group, criterion_main, Criterion};
use impact::run::{run, BeamModel};
use impact::scene::Scene;
use std::hint::black_box;

fn paper_sweep(c: &mut Criterion) {
    let scene = Scene::default_scene().with_sweep(101).unwrap();
    let cases = scene.points.x.len() * scene.conditions.len() * scene.bodies.len();
    c.bench_function(&format!("paper sweep ({cases} point-condition-body cases)"), |b| {
        b.iter(|| run(black_box(&scene), &BeamModel { plate: &scene.plate }).unwrap())
    });
}

criterion_group!(benches, paper_sweep);
criterion_main!(benches);
