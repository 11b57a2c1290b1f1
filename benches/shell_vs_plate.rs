//! The flat shell against the BFS plate at equal accuracy: a hard simply supported 1 m square
//! plate, 10 mm thick, under a central patch of side 0.1 m. Each model runs on the coarsest
//! uniform mesh (4, 8, ..., 256 elements a side) whose compliance is within 1e-3 of its own
//! theory's series: the BFS plate against Navier's Kirchhoff part, the shell (membrane, MITC4
//! plate, drilling; six DOFs a node) against Navier's series with shear. Timed: assembly,
//! factorization and the patch response, what a compliance costs. The BFS plate is the
//! reference in the same run.

use criterion::{criterion_group, criterion_main, Criterion};
use plate_fem::mindlin::{series, Patch};
use plate_fem::shell::{Face, FaceId, Restraints, Structure};
use plate_fem::{Mesh, Model, PlateProperties, Supports};
use std::hint::black_box;

const SIDE: f64 = 1.0;
const PATCH: Patch = Patch { x: 0.5, z: 0.5, side_x: 0.1, side_z: 0.1 };

fn props() -> PlateProperties {
    PlateProperties {
        length: SIDE,
        width: SIDE,
        thickness: 0.01,
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
        density: 7850.0,
    }
}

fn bfs(n: usize) -> f64 {
    let model = Model::new(props(), Mesh::uniform(SIDE, SIDE, n, n).unwrap()).unwrap();
    model.factorize(&Supports::all_edges_simple()).unwrap().respond_patch(&PATCH).unwrap()
}

fn shell_structure(n: usize) -> (Structure, FaceId, Restraints) {
    let p = props();
    let lines: Vec<f64> = (0..=n).map(|i| SIDE * i as f64 / n as f64).collect();
    let mut s = Structure::new(p.youngs_modulus, p.poisson_ratio).unwrap();
    let face = Face::new([0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], lines.clone(), lines, p.thickness).unwrap();
    let id = s.add_face(&face).unwrap();
    let mut r = Restraints::default();
    for node in s.nodes_where(|q| q[0] == 0.0 || q[0] == SIDE) {
        r.hold(node, &[0, 1, 2, 3]);
    }
    for node in s.nodes_where(|q| q[2] == 0.0 || q[2] == SIDE) {
        r.hold(node, &[0, 1, 2, 5]);
    }
    (s, id, r)
}

fn shell(n: usize) -> f64 {
    let (s, id, r) = shell_structure(n);
    s.factorize(&r).unwrap().respond(id, &PATCH).unwrap().compliance
}

/// The coarsest mesh of `run` within 1e-3 of `exact`, with its error.
fn coarsest(run: fn(usize) -> f64, exact: f64) -> (usize, f64) {
    (2..=8)
        .map(|k| 1usize << k)
        .map(|n| (n, run(n) / exact - 1.0))
        .find(|(_, e)| e.abs() < 1e-3)
        .expect("a mesh of at most 256 elements a side meets 1e-3")
}

fn shell_vs_plate(c: &mut Criterion) {
    let navier = series::navier_patch(&props(), &PATCH).unwrap();
    let (nb, eb) = coarsest(bfs, navier.compliance - navier.shear);
    let (ns, es) = coarsest(shell, navier.compliance);
    println!(
        "BFS {nb} x {nb} ({:+.2e} from Kirchhoff's series); shell {ns} x {ns} ({:+.2e} from the series with shear)",
        eb, es
    );
    let mut g = c.benchmark_group("shell vs plate at 1e-3");
    g.sample_size(10);
    g.bench_function(format!("reference: BFS plate {nb} x {nb}"), |b| b.iter(|| black_box(bfs(nb))));
    g.bench_function(format!("flat shell {ns} x {ns}"), |b| b.iter(|| black_box(shell(ns))));
    g.finish();
}

criterion_group!(benches, shell_vs_plate);
criterion_main!(benches);
