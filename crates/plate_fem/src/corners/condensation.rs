//! Condensation onto the corners with free edges (module docs of [`super`]): C = C_fix +
//! fᵀc with the rank-1 corner stiffness S = s t tᵀ inverted by Sherman-Morrison, every term
//! non-negative, so that no stiffness in (0, ∞] loses accuracy.

use super::{Audit, BasePoint, CornerFamily, TWIST};
use crate::model::{CornerResponse, PointResponse};
use crate::supports::CornerSupport;
use crate::FemError;
use nalgebra::{DMatrix, DVector, Vector4};

impl CornerFamily<'_> {
    /// The fixed-corner compliance C_fix and reactions f = G⁻¹u, by the update to four
    /// fixed corners (the same operations as [`update`](Self::update) for Con 1, so C_fix
    /// is bit for bit the update's Con 1 value), with the size of the terms that cancel.
    fn fixed_corners(&self, p: &BasePoint) -> Result<(f64, Vector4<f64>, f64), FemError> {
        let mat = DMatrix::from_fn(4, 4, |a, b| self.g[(a, b)]);
        let rhs = DVector::from_fn(4, |a, _| p.u[a]);
        let f = mat.lu().solve(&rhs).ok_or_else(|| FemError::Singular("base corner flexibility is singular".into()))?;
        let mut c = p.compliance;
        let mut scale = p.compliance.abs();
        for i in 0..4 {
            c -= p.u[i] * f[i];
            scale += (p.u[i] * f[i]).abs();
        }
        Ok((c, Vector4::from_fn(|i, _| f[i]), scale))
    }

    /// Condensation onto the corners (module docs) with twist stiffness `s`. Needs free
    /// edges and at most one free corner (checked by the caller).
    pub(super) fn condensed(&self, p: &BasePoint, corners: [CornerSupport; 4], s: f64) -> (PointResponse, Audit) {
        let (c_fix, f, scale) = match self.fixed_corners(p) {
            Ok(v) => v,
            Err(_) => (f64::NAN, Vector4::repeat(f64::NAN), f64::NAN),
        };
        let mesh = self.base.model().mesh();
        let f = rigid_from_statics(&f, p.x / mesh.length(), p.z / mesh.width());
        let (beta, spring_part) = match corners.iter().position(|&c| c == CornerSupport::Free) {
            Some(fc) => twist_with_free_corner(&f, &corners, s, fc),
            None => twist_on_springs(&f, &corners, s),
        };
        let r = PointResponse {
            x: p.x,
            z: p.z,
            compliance: c_fix + spring_part,
            plate_compliance: c_fix + beta * beta / s,
            corners: reactions(&f, &corners, beta),
            edge_spring_compliance: 0.0,
            residual: p.residual,
        };
        (r, Audit { scale: scale + spring_part, system: None })
    }
}

/// The fixed-corner reactions `f` with their rigid components from statics, for a load at
/// (x, z) = (ξL, ζB).
///
/// Statics fixes f in the three rigid directions exactly (the element represents the rigid
/// motions exactly, so Σ f_i (1, x_i, z_i) = (1, x, z) in algebra); only the twist
/// component τ = tᵀf/4 depends on the plate. In the orthogonal basis 1, h_x = (-1, 1, -1, 1),
/// h_z = (-1, -1, 1, 1), t of R⁴, f = 1/4 + (2ξ - 1)/4 h_x + (2ζ - 1)/4 h_z + τ t. Replacing
/// the solved rigid components (good to the base solve's residual, ~1e-11) by the exact ones
/// makes the soft-spring limits, which depend on them alone, exact to round-off.
fn rigid_from_statics(f: &Vector4<f64>, xi: f64, zeta: f64) -> Vector4<f64> {
    let t = TWIST;
    let tau = (0..4).map(|i| t[i] * f[i]).sum::<f64>() / 4.0;
    let (hx, hz) = ([-1.0, 1.0, -1.0, 1.0], [-1.0, -1.0, 1.0, 1.0]);
    Vector4::from_fn(|i, _| 0.25 + 0.25 * (2.0 * xi - 1.0) * hx[i] + 0.25 * (2.0 * zeta - 1.0) * hz[i] + tau * t[i])
}

/// The corner flexibility φ = 1/k: 0 for a fixed corner, ∞ for a free one.
fn flexibility(c: CornerSupport) -> f64 {
    match c {
        CornerSupport::Fixed => 0.0,
        CornerSupport::Spring(k) => 1.0 / k,
        CornerSupport::Free => f64::INFINITY,
    }
}

/// The twist force β and the spring part fᵀc of C with the corner `fc` free: the limit
/// φ_f → ∞, where β = t_f f_f (the free corner's reaction f_f - t_f β vanishes) and
/// fᵀc = f_f²/s + Σ_j φ_j r_j².
fn twist_with_free_corner(f: &Vector4<f64>, corners: &[CornerSupport; 4], s: f64, fc: usize) -> (f64, f64) {
    let t = TWIST;
    let beta = t[fc] * f[fc];
    let rest: f64 = (0..4)
        .filter(|&j| j != fc)
        .map(|j| {
            let r = f[j] - t[j] * beta;
            flexibility(corners[j]) * r * r
        })
        .sum();
    (beta, f[fc] * f[fc] / s + rest)
}

/// The twist force β = s Σ t_i φ_i f_i / (1 + s Σ φ_i) and the spring part
/// fᵀc = (Σ φ_i f_i² + s Σ_{i<j} φ_i φ_j (f_i t_j - f_j t_i)²) / (1 + s Σ φ_i) with no corner
/// free (Sherman-Morrison for S = s t tᵀ, the numerator by Lagrange's identity). The sums
/// are taken over ψ = φ/m, m the largest φ, so that neither 1e-300 nor 1e300 N/m overflows.
fn twist_on_springs(f: &Vector4<f64>, corners: &[CornerSupport; 4], s: f64) -> (f64, f64) {
    let t = TWIST;
    let phi = |i: usize| flexibility(corners[i]);
    let m = (0..4).map(phi).fold(0.0, f64::max);
    if m == 0.0 {
        return (0.0, 0.0);
    }
    // ψ = φ/m ∈ [0, 1]; numerator and denominator divided by s m.
    let psi: Vec<f64> = (0..4).map(|i| phi(i) / m).collect();
    let a: f64 = psi.iter().sum();
    let b: f64 = (0..4).map(|i| t[i] * psi[i] * f[i]).sum();
    let q: f64 = (0..4).map(|i| psi[i] * f[i] * f[i]).sum();
    let mut lagrange = 0.0;
    for i in 0..4 {
        for j in i + 1..4 {
            let d = f[i] * t[j] - f[j] * t[i];
            lagrange += psi[i] * psi[j] * d * d;
        }
    }
    let den = 1.0 / (s * m) + a;
    (b / den, (q / s + m * lagrange) / den)
}

/// The corner reactions r_i = f_i - t_i β and spring stores φ_i r_i² = r_i²/k_i.
fn reactions(f: &Vector4<f64>, corners: &[CornerSupport; 4], beta: f64) -> [CornerResponse; 4] {
    let t = TWIST;
    std::array::from_fn(|i| match corners[i] {
        CornerSupport::Free => CornerResponse { reaction: 0.0, spring_compliance: 0.0 },
        CornerSupport::Fixed => CornerResponse { reaction: f[i] - t[i] * beta, spring_compliance: 0.0 },
        CornerSupport::Spring(k) => {
            let r = f[i] - t[i] * beta;
            CornerResponse { reaction: r, spring_compliance: r * r / k }
        }
    })
}
