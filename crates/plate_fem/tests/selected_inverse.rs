//! The selected inverse (Takahashi's equations on the supernodal factor) against K⁻¹ from a
//! dense Cholesky factorization (nalgebra), which shares no code with it.

use plate_fem::nalgebra::DMatrix;
use plate_fem::{EdgeSupport, Mesh, Model, PlateProperties, Supports};

fn model(nx: usize, nz: usize) -> Model {
    let props = PlateProperties {
        length: 0.4584,
        width: 0.36,
        thickness: 0.008,
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
        density: 7850.0,
    };
    Model::new(props, Mesh::uniform(0.4584, 0.36, nx, nz).unwrap()).unwrap()
}

/// K⁻¹ on the free DOFs by a dense Cholesky factorization; held rows and columns zero.
fn dense_inverse(model: &Model, supports: &Supports) -> DMatrix<f64> {
    let n = model.dofs();
    let k = model.supported_stiffness(supports).unwrap();
    let held = supports.constrained_dofs(model.mesh());
    let free: Vec<usize> = (0..n).filter(|d| !held.contains(d)).collect();
    let mut index = vec![usize::MAX; n];
    for (i, &d) in free.iter().enumerate() {
        index[d] = i;
    }
    let mut dense = DMatrix::<f64>::zeros(free.len(), free.len());
    for c in 0..n {
        let rows = k.as_ref().row_idx_of_col_raw(c);
        let values = k.as_ref().val_of_col(c);
        for (&r, &v) in rows.iter().zip(values) {
            if index[r] != usize::MAX && index[c] != usize::MAX {
                dense[(index[r], index[c])] = v;
                dense[(index[c], index[r])] = v;
            }
        }
    }
    let inv = dense.cholesky().expect("the supported stiffness is positive definite").inverse();
    let mut out = DMatrix::<f64>::zeros(n, n);
    for (i, &di) in free.iter().enumerate() {
        for (j, &dj) in free.iter().enumerate() {
            out[(di, dj)] = inv[(i, j)];
        }
    }
    out
}

/// Every element block of K⁻¹, on corner, spring and edge supports: the two agree to
/// 1e-10 of the largest entry. The dense factorization's own error is about ε·cond(K)
/// relative to that entry, cond(K) ≈ 1e5-1e7 on these meshes, so both are within 1e-9 of
/// the exact inverse; a wrong equation (a sign, a transposed U, a missing Z_RR term) is
/// off by O(1) of the entries it touches.
#[test]
fn element_blocks_equal_the_dense_inverse() {
    let simple = Supports {
        edges: [EdgeSupport::Simple, EdgeSupport::Clamped, EdgeSupport::Free, EdgeSupport::Free],
        ..Supports::FREE
    };
    for (nx, nz) in [(4, 3), (9, 7)] {
        let m = model(nx, nz);
        for supports in [Supports::con1(), Supports::con3(5.11545e8), simple] {
            let reference = dense_inverse(&m, &supports);
            let scale = reference.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let z = m.factorize(&supports).unwrap().selected_inverse().unwrap();
            let mut worst = 0.0f64;
            for ez in 0..nz {
                for ex in 0..nx {
                    let dofs = m.mesh().element_dofs(ex, ez);
                    let block = z.block(&dofs).expect("an element's pairs lie on the factor's pattern");
                    for k in 0..16 {
                        for l in 0..16 {
                            worst = worst.max((block[k * 16 + l] - reference[(dofs[k], dofs[l])]).abs());
                        }
                    }
                }
            }
            assert!(worst < 1e-10 * scale, "{nx} x {nz}, {supports:?}: worst {worst:e} of {scale:e}");
        }
    }
}

/// A held DOF reads as zero, as a solve leaves it, though the factor keeps it with its
/// assembled diagonal.
#[test]
fn held_dofs_read_as_zero() {
    let m = model(4, 3);
    let s = Supports::con1();
    let z = m.factorize(&s).unwrap().selected_inverse().unwrap();
    let held = s.constrained_dofs(m.mesh());
    assert!(!held.is_empty());
    for &d in &held {
        assert_eq!(z.get(d, d), Some(0.0));
    }
    assert_eq!(z.get(m.dofs(), 0), None, "a DOF beyond the model");
}
