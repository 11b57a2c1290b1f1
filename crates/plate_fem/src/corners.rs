//! Any set of corner supports from one factorization: a rank-≤4 update.
//!
//! Factorize once with all four corners on base springs k_b (stiff, so that the base is
//! close to the fixed plate). A target set differs from the base only at the four corner
//! w DOFs: K = K_b + U_S Δ U_Sᵀ with Δ_i = k_i - k_b (k_i = ∞ for a fixed corner, 0 for a
//! free one) on the corners S that change. With u = Uᵀ K_b⁻¹ N (the base deflection of the
//! corners under the unit load, by reciprocity) and G = Uᵀ K_b⁻¹ U (the 4 x 4 corner
//! flexibility of the base), the Woodbury identity gives
//!
//! ```text
//! (Δ⁻¹ + G_SS) λ = u_S,    C = N ᵀ K_b⁻¹ N - u_Sᵀ λ,    w_corners = u - G_{·S} λ
//! ```
//!
//! where λ are the extra corner forces; a fixed corner has Δ⁻¹ = 0, so rigid supports need
//! no large number. One solve per impact point serves every corner set, and a k_T sweep is
//! 4 x 4 algebra.

use crate::model::{CornerResponse, Factorization, Model, PointResponse};
use crate::supports::{Corner, CornerSupport, EdgeSupport, Supports};
use crate::FemError;
use faer::Mat;
use nalgebra::{DMatrix, DVector, Matrix4, Vector4};

/// The base factorization and its corner flexibility.
pub struct CornerFamily<'m> {
    base: Factorization<'m>,
    k_base: f64,
    edges: [EdgeSupport; 4],
    /// G = Uᵀ K_b⁻¹ U.
    g: Matrix4<f64>,
}

/// A point solved on the base: what every corner set needs of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BasePoint {
    pub x: f64,
    pub z: f64,
    /// N ᵀ K_b⁻¹ N.
    pub compliance: f64,
    /// Base deflections of the four corners under the unit load.
    pub u: Vector4<f64>,
    /// Relative residual of the base solve.
    pub residual: f64,
}

impl<'m> CornerFamily<'m> {
    /// A base stiffness stiff against the plate's own corner stiffness, ~1e4 D/(L B): the
    /// update from base to fixed corners then changes C by ~1e-3 of itself, so little is
    /// lost to cancellation.
    pub fn default_base_stiffness(model: &Model) -> f64 {
        let p = model.props();
        1e4 * p.rigidity() / (p.length * p.width)
    }

    /// Factorizes the base (edges as given, corners on springs `k_base`).
    pub fn new(model: &'m Model, edges: [EdgeSupport; 4], k_base: f64) -> Result<Self, FemError> {
        // The base is well conditioned (stiff springs at all corners); its residuals are
        // reported with every probe, and refinement is left to the caller.
        let base =
            model.factorize(&Supports { corners: [CornerSupport::Spring(k_base); 4], edges })?.with_refinement(0);
        let n = model.dofs();
        let mut rhs = Mat::<f64>::zeros(n, 4);
        let dofs: Vec<usize> = (0..4).map(|c| model.mesh().corner_w_dof(c)).collect();
        for (j, &d) in dofs.iter().enumerate() {
            rhs[(d, j)] = 1.0;
        }
        base.solve_in_place(&mut rhs);
        let g = Matrix4::from_fn(|i, j| 0.5 * (rhs[(dofs[i], j)] + rhs[(dofs[j], i)]));
        Ok(Self { base, k_base, edges, g })
    }

    pub fn base(&self) -> &Factorization<'m> {
        &self.base
    }
    pub fn k_base(&self) -> f64 {
        self.k_base
    }

    /// Whether mesh and edges are symmetric about x = L/2 and about z = B/2, so that the
    /// base (equal springs at all corners) is too.
    pub fn symmetry(&self) -> (bool, bool) {
        let mesh = self.base.model().mesh();
        let mirrored = |v: &[f64]| {
            let end = *v.last().expect("two lines");
            v.iter().zip(v.iter().rev()).all(|(a, b)| (a + b - end).abs() <= 1e-12 * end)
        };
        let [left, right, near, far] = self.edges;
        (mirrored(mesh.xs()) && left == right, mirrored(mesh.zs()) && near == far)
    }

    /// Solves the base at `points`, once per class of mirror images: a point and its
    /// mirror images about the plate's symmetry lines share C and have their corner
    /// deflections permuted, so a doubly symmetric plate needs a quarter of the solves.
    pub fn probe_map(&self, points: &[(f64, f64)]) -> Result<Vec<BasePoint>, FemError> {
        let (sx, sz) = self.symmetry();
        let (l, b) = (self.base.model().props().length, self.base.model().props().width);
        let key = |v: f64, s: f64| (v / s * 1e9).round() as i64;
        let mut canonical: Vec<(f64, f64)> = Vec::new();
        let mut index = std::collections::HashMap::new();
        let mut plan = Vec::with_capacity(points.len());
        for &(x, z) in points {
            let (fx, fz) = (sx && x > l - x, sz && z > b - z);
            let (cx, cz) = (if fx { l - x } else { x }, if fz { b - z } else { z });
            let k = (key(cx, l), key(cz, b));
            let i = *index.entry(k).or_insert_with(|| {
                canonical.push((cx, cz));
                canonical.len() - 1
            });
            plan.push((i, fx, fz));
        }
        let solved = self.probe_many(&canonical)?;
        Ok(points
            .iter()
            .zip(plan)
            .map(|(&(x, z), (i, fx, fz))| {
                let s = solved[i];
                // Corners (0,0), (L,0), (0,B), (L,B): mirroring x swaps 0<->1 and 2<->3.
                let perm = |c: usize| {
                    let c = if fx { c ^ 1 } else { c };
                    if fz {
                        c ^ 2
                    } else {
                        c
                    }
                };
                BasePoint { x, z, u: Vector4::from_fn(|c, _| s.u[perm(c)]), ..s }
            })
            .collect())
    }

    /// Solves the base at many points, in blocks.
    pub fn probe_many(&self, points: &[(f64, f64)]) -> Result<Vec<BasePoint>, FemError> {
        let responses = self.base.respond_many(points)?;
        Ok(responses
            .into_iter()
            .map(|r| BasePoint {
                x: r.x,
                z: r.z,
                compliance: r.compliance,
                // Base springs: reaction = k_b w, so w = reaction / k_b.
                u: Vector4::from_fn(|i, _| r.corners[i].reaction / self.k_base),
                residual: r.residual,
            })
            .collect())
    }

    /// The response of the plate with corner set `corners` at a base point.
    pub fn respond(&self, p: &BasePoint, corners: [CornerSupport; 4]) -> Result<PointResponse, FemError> {
        let model = self.base.model();
        Supports { corners, edges: self.edges }.validate(model.props().length, model.props().width)?;
        let s: Vec<usize> = (0..4).filter(|&i| corners[i] != CornerSupport::Spring(self.k_base)).collect();
        let inv_delta = |i: usize| match corners[i] {
            CornerSupport::Fixed => 0.0,
            CornerSupport::Free => -1.0 / self.k_base,
            CornerSupport::Spring(k) => 1.0 / (k - self.k_base),
        };
        let m = s.len();
        let lambda = if m == 0 {
            DVector::zeros(0)
        } else {
            let mat = DMatrix::from_fn(m, m, |a, b| self.g[(s[a], s[b])] + if a == b { inv_delta(s[a]) } else { 0.0 });
            let rhs = DVector::from_fn(m, |a, _| p.u[s[a]]);
            mat.lu().solve(&rhs).ok_or_else(|| FemError::Singular("corner update matrix is singular".into()))?
        };
        let mut compliance = p.compliance;
        let mut w = p.u;
        for (a, &i) in s.iter().enumerate() {
            compliance -= p.u[i] * lambda[a];
            for r in 0..4 {
                w[r] -= self.g[(r, i)] * lambda[a];
            }
        }
        let mut out = [CornerResponse { reaction: 0.0, spring_compliance: 0.0 }; 4];
        for c in Corner::ALL {
            let i = c.index();
            let extra = s.iter().position(|&j| j == i).map_or(0.0, |a| lambda[a]);
            out[i] = match corners[i] {
                CornerSupport::Free => CornerResponse { reaction: 0.0, spring_compliance: 0.0 },
                CornerSupport::Fixed => CornerResponse { reaction: self.k_base * w[i] + extra, spring_compliance: 0.0 },
                CornerSupport::Spring(k) => CornerResponse { reaction: k * w[i], spring_compliance: k * w[i] * w[i] },
            };
        }
        let springs: f64 = out.iter().map(|c| c.spring_compliance).sum();
        Ok(PointResponse {
            x: p.x,
            z: p.z,
            compliance,
            plate_compliance: compliance - springs,
            corners: out,
            residual: p.residual,
        })
    }
}
