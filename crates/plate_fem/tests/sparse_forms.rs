//! The sparse products a Newmark step uses (M y, ẇᵀMẇ, wᵀKw from the stored upper
//! triangles) against the dense symmetric matrices they stand for: the reference is a plain
//! dense product of the full matrix, which shares nothing with the one-pass loops but the
//! stored values.

use faer::Mat;
use plate_fem::model::{
    mass_stiffness_pass, symmetric_upper_apply, symmetric_upper_apply_into, symmetric_upper_quadratic,
};
use plate_fem::{CornerSupport, EdgeSupport, Mesh, Model, PlateProperties, Supports};

fn model() -> Model {
    let props = PlateProperties {
        length: 0.4584,
        width: 0.36,
        thickness: 0.008,
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
        density: 7850.0,
    };
    Model::new(props, Mesh::uniform(0.4584, 0.36, 6, 4).unwrap()).unwrap()
}

/// Corner springs, a held corner and an elastic edge: every kind of entry the supports add.
fn supports() -> Supports {
    let mut s = Supports::corners([
        CornerSupport::Fixed,
        CornerSupport::Spring(5e8),
        CornerSupport::Spring(2e7),
        CornerSupport::Free,
    ]);
    s.edges[1] = EdgeSupport::Elastic(3e9);
    s
}

/// The full symmetric matrix of a stored upper triangle.
fn dense(a: &faer::sparse::SparseColMat<usize, f64>) -> Mat<f64> {
    let n = a.ncols();
    let mut d = Mat::<f64>::zeros(n, n);
    let (cp, ri, v) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
    for j in 0..n {
        for p in cp[j]..cp[j + 1] {
            d[(ri[p], j)] += v[p];
            if ri[p] != j {
                d[(j, ri[p])] += v[p];
            }
        }
    }
    d
}

/// A deterministic vector with entries of both signs and several magnitudes.
fn vector(n: usize, seed: f64) -> Vec<f64> {
    (0..n).map(|i| ((i as f64 + 1.0) * seed).sin() * 10f64.powi((i % 5) as i32 - 2)).collect()
}

fn dense_apply(d: &Mat<f64>, x: &[f64]) -> Vec<f64> {
    (0..d.nrows()).map(|i| (0..d.ncols()).map(|j| d[(i, j)] * x[j]).sum()).collect()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Relative agreement to 1e-12: the sums run over at most a few hundred terms of mixed sign,
/// so rounding leaves about n·ε·max|term|/|sum| ≈ 1e-13 at worst on these vectors.
#[test]
fn products_and_energies_match_the_dense_matrices() {
    let m = model();
    let s = supports();
    let (mass, stiffness) = (m.supported_mass(&s).unwrap(), m.supported_matrix(&s, 1.0, 0.0, false).unwrap());
    let (dm, dk) = (dense(&mass), dense(&stiffness));
    let n = m.dofs();
    let (y, v, w) = (vector(n, 0.37), vector(n, 1.13), vector(n, 2.71));
    let scale = |x: &[f64]| x.iter().fold(0.0f64, |a, b| a.max(b.abs()));

    let reference = dense_apply(&dm, &y);
    let my = symmetric_upper_apply(&mass, &y);
    let worst = my.iter().zip(&reference).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    assert!(worst <= 1e-12 * scale(&reference), "M y off by {worst:e}");

    let kinetic = dot(&v, &dense_apply(&dm, &v));
    let strain = dot(&w, &dense_apply(&dk, &w));
    let q = (symmetric_upper_quadratic(&mass, &v), symmetric_upper_quadratic(&stiffness, &w));
    assert!((q.0 - kinetic).abs() <= 1e-12 * kinetic.abs(), "vᵀMv {} against {kinetic}", q.0);
    assert!((q.1 - strain).abs() <= 1e-12 * strain.abs(), "wᵀKw {} against {strain}", q.1);

    let mut fused = vec![f64::NAN; n];
    let (k2, s2) = mass_stiffness_pass((&mass, &stiffness), (&y, &v, &w), &mut fused);
    assert!((k2 - kinetic).abs() <= 1e-12 * kinetic.abs(), "fused vᵀMv {k2} against {kinetic}");
    assert!((s2 - strain).abs() <= 1e-12 * strain.abs(), "fused wᵀKw {s2} against {strain}");
    // The fused pass forms M y with the apply's own operations in its order, so a step
    // takes the same right-hand side either way.
    let mut into = vec![f64::NAN; n];
    symmetric_upper_apply_into(&mass, &y, &mut into);
    assert!(fused.iter().zip(&into).all(|(a, b)| a.to_bits() == b.to_bits()));
    assert!(into.iter().zip(&my).all(|(a, b)| a.to_bits() == b.to_bits()));
}
