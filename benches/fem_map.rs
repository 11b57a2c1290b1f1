//! The plate FE compliance map: the paper's plate on the 40 x 32 mesh (the
//! coarsest of the ladder within 1e-4 at the centre), 101 x 21 impact points, Con 1-3:
//! one factorization, blocked solves, rank-4 updates. The reference in the same run is
//! one fresh factorization per condition with a single solve per point, on a coarser
//! 21 x 11 grid of points to keep the bench short (compare per point).

use coupled::discretisation::{mesh_for, plate_properties};
use coupled::supports::corner_supports;
use criterion::{criterion_group, criterion_main, Criterion};
use impact::scene::{even_points, Scene, SceneSource};
use plate_fem::{CornerFamily, EdgeSupport, Model};
use std::hint::black_box;

fn grid(l: f64, b: f64, nx: usize, nz: usize) -> Vec<(f64, f64)> {
    even_points(l, nx).into_iter().flat_map(|x| even_points(b, nz).into_iter().map(move |z| (x, z))).collect()
}

fn fem_map(c: &mut Criterion) {
    let scene = Scene::default_scene();
    let props = plate_properties(&scene.plate);
    let conds = [
        analytic::Condition::BothFixed,
        analytic::Condition::BothSprings { k_t: 5.11545e8 },
        analytic::Condition::FixedAndSprings { k_t: 5.11545e8 },
    ];
    let mut g = c.benchmark_group("fem map");
    g.sample_size(10);
    let points = grid(props.length, props.width, 101, 21);
    g.bench_function("101x21 points x 3 conditions, one factorization + updates", |b| {
        b.iter(|| {
            let model = Model::new(props, mesh_for(&props, 40).unwrap()).unwrap();
            let fam = CornerFamily::new(&model, [EdgeSupport::Free; 4], CornerFamily::default_base_stiffness(&model))
                .unwrap();
            let base = fam.probe_map(black_box(&points)).unwrap();
            for cnd in conds {
                for p in &base {
                    black_box(fam.respond(p, corner_supports(cnd).corners).unwrap());
                }
            }
        })
    });
    let few = grid(props.length, props.width, 21, 11);
    g.bench_function("reference: 21x11 points x 3 conditions, fresh factorizations + single solves", |b| {
        b.iter(|| {
            let model = Model::new(props, mesh_for(&props, 40).unwrap()).unwrap();
            for cnd in conds {
                let f = model.factorize(&corner_supports(cnd)).unwrap().with_refinement(0);
                for &(x, z) in &few {
                    black_box(f.respond(x, z).unwrap());
                }
            }
        })
    });
    g.finish();
}

criterion_group!(benches, fem_map);
criterion_main!(benches);
