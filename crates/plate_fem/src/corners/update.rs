//! The rank-4 Woodbury update from the base to a corner set (module docs of [`super`]):
//! (Δ⁻¹ + G_SS) λ = u_S, C = Nᵀ K_b⁻¹ N - u_Sᵀ λ, w_corners = u - G_{·S} λ.

use super::{Audit, BasePoint, CornerFamily};
use crate::model::{CornerResponse, PointResponse};
use crate::supports::{Corner, CornerSupport};
use crate::FemError;
use nalgebra::{DMatrix, DVector};

impl CornerFamily<'_> {
    /// The rank-4 update, operation for operation as it always was (results reproduced bit
    /// for bit), plus what the check needs.
    pub(super) fn update(
        &self,
        p: &BasePoint,
        corners: [CornerSupport; 4],
    ) -> Result<(PointResponse, Audit), FemError> {
        let s: Vec<usize> = (0..4).filter(|&i| corners[i] != CornerSupport::Spring(self.k_base)).collect();
        let inv_delta = |i: usize| match corners[i] {
            CornerSupport::Fixed => 0.0,
            CornerSupport::Free => -1.0 / self.k_base,
            CornerSupport::Spring(k) => 1.0 / (k - self.k_base),
        };
        let m = s.len();
        let mut system = None;
        let lambda = if m == 0 {
            DVector::zeros(0)
        } else {
            let mat = DMatrix::from_fn(m, m, |a, b| self.g[(s[a], s[b])] + if a == b { inv_delta(s[a]) } else { 0.0 });
            let rhs = DVector::from_fn(m, |a, _| p.u[s[a]]);
            let lambda = mat
                .clone()
                .lu()
                .solve(&rhs)
                .ok_or_else(|| FemError::Singular("corner update matrix is singular".into()))?;
            let norm1 = |x: &DMatrix<f64>| x.column_iter().map(|c| c.abs().sum()).fold(0.0, f64::max);
            let cond = mat.clone().try_inverse().map_or(f64::INFINITY, |inv| norm1(&mat) * norm1(&inv));
            let res = (&mat * &lambda - &rhs).amax()
                / (norm1(&mat.transpose()) * lambda.amax() + rhs.amax()).max(f64::MIN_POSITIVE);
            system = Some((cond, res));
            lambda
        };
        let mut compliance = p.compliance;
        let mut scale = p.compliance.abs();
        let mut w = p.u;
        for (a, &i) in s.iter().enumerate() {
            compliance -= p.u[i] * lambda[a];
            scale += (p.u[i] * lambda[a]).abs();
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
        let r = PointResponse {
            x: p.x,
            z: p.z,
            compliance,
            plate_compliance: compliance - springs,
            corners: out,
            edge_spring_compliance: 0.0,
            residual: p.residual,
        };
        Ok((r, Audit { scale, system }))
    }
}
