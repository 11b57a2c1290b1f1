//! The flat shell rectangle: membrane, bending with transverse shear, and drilling.
//!
//! An a x b rectangle in its own plane, with the local frame (e₁, e₂, e₃ = e₁ x e₂) and six
//! DOFs a node: the translations (u₁, u₂, u₃) and the rotation vector (ω₁, ω₂, ω₃). A flat
//! element's energy splits into parts that do not couple:
//!
//! ```text
//! membrane  ½ ∫ εᵀ (h D_σ) ε dA,         ε = (∂u₁/∂x₁, ∂u₂/∂x₂, ∂u₁/∂x₂ + ∂u₂/∂x₁)
//! plate     the MITC4 energy of (w, θ) = (u₃, -ω₂, ω₁)            (crate::mindlin::element)
//! drilling  ½ α G h ∫ (ω₃ - Ω)² dA,      Ω = ½(∂u₂/∂x₁ - ∂u₁/∂x₂)
//! ```
//!
//! with D_σ the plane-stress matrix. The plate's section rotations θ are slopes (θ = ∇w where
//! the shear vanishes); a rotation vector ω turns the normal e₃ into e₃ + ω x e₃ = e₃ + (ω₂,
//! -ω₁, 0), and the normal of the bent surface is e₃ - ∇w, hence θ = (-ω₂, ω₁).
//!
//! **Membrane.** Bilinear u with Wilson's incompatible modes 4ξ(1-ξ) and 4η(1-η) in each
//! component (Wilson, Taylor, Doherty & Ghaboussi 1973), condensed out of the element. On a
//! rectangle their strains integrate to zero, so the element passes the patch test, and it
//! represents in-plane bending exactly: the webs and flanges of a box beam bend in their own
//! plane, where plain bilinear elements lock by parasitic shear.
//!
//! **Drilling.** A flat element has no stiffness for ω₃, and where several elements meet in one
//! plane the global rotation about their normal would be free. The penalty ties ω₃ to the
//! membrane's own rotation Ω (Hughes & Brezzi 1989), so it holds no rigid rotation; its factor
//! α ([`DRILLING_FACTOR`]) is small; the tests measure how little the results depend on it.

use crate::mindlin::element::{self as plate, Mat12, GAUSS2};
use nalgebra::{SMatrix, SVector};

/// An element matrix over the 24 local DOFs (four nodes x (u₁, u₂, u₃, ω₁, ω₂, ω₃)).
pub type Mat24 = SMatrix<f64, 24, 24>;
/// An element vector over the 24 local DOFs.
pub type Vec24 = SVector<f64, 24>;

/// DOFs per node: three translations and three rotations.
pub const DOFS_PER_NODE: usize = 6;

/// The drilling penalty's factor α on G h. Where walls meet at right angles the drilling
/// rotation of one is the bending rotation of the other, and α hardly matters (a box
/// cantilever moves by 1.2e-4 between α = 1e-2 and 1e-1). On a faceted curved shell the
/// facets' drilling rotations are held only by the penalty and by the small kink angles: a
/// penalty too small leaves them soft (the Scordelis-Lo roof on 64 x 64 facets deflects 6 %
/// too much at α = 1e-5 and 0.07 % at 1e-3), one too large stiffens the membrane (0.3 % at
/// α = 1 on 32 x 32). Between 1e-2 and 1e-1 the roof moves by 3e-4.
pub const DRILLING_FACTOR: f64 = 1e-2;

/// The plate DOF k of [`plate`]'s ordering (w, θ_x, θ_z per node) as (shell DOF, sign).
fn plate_dof(k: usize) -> (usize, f64) {
    let node = k / 3;
    match k % 3 {
        0 => (6 * node + 2, 1.0),
        1 => (6 * node + 4, -1.0),
        _ => (6 * node + 3, 1.0),
    }
}

/// Plane-stress elasticity of a sheet of thickness h: h E/(1-ν²) [[1, ν, 0], [ν, 1, 0],
/// [0, 0, (1-ν)/2]] (N/m).
pub(crate) fn membrane_rigidity(e: f64, nu: f64, h: f64) -> SMatrix<f64, 3, 3> {
    let c = e * h / (1.0 - nu * nu);
    SMatrix::<f64, 3, 3>::new(c, c * nu, 0.0, c * nu, c, 0.0, 0.0, 0.0, c * (1.0 - nu) / 2.0)
}

/// The membrane strain operator at (ξ, η) over the 8 bilinear DOFs (u₁, u₂ per node) and
/// the 4 incompatible ones (u₁ and u₂ each times 4ξ(1-ξ) and 4η(1-η)).
fn membrane_operator(a: f64, b: f64, xi: f64, eta: f64) -> SMatrix<f64, 3, 12> {
    let n = plate::bilinear(a, b, xi, eta);
    let mut m = SMatrix::<f64, 3, 12>::zeros();
    for (k, [_, dx, dz]) in n.into_iter().enumerate() {
        m[(0, 2 * k)] = dx;
        m[(1, 2 * k + 1)] = dz;
        m[(2, 2 * k)] = dz;
        m[(2, 2 * k + 1)] = dx;
    }
    let (dxi, deta) = (4.0 * (1.0 - 2.0 * xi) / a, 4.0 * (1.0 - 2.0 * eta) / b);
    // Incompatible DOFs 8..12: u₁·φ_ξ, u₁·φ_η, u₂·φ_ξ, u₂·φ_η.
    m[(0, 8)] = dxi;
    m[(2, 9)] = deta;
    m[(1, 11)] = deta;
    m[(2, 10)] = dxi;
    m
}

/// The membrane stiffness over the 8 bilinear DOFs, the incompatible modes condensed out:
/// K = K_cc - K_ci K_ii⁻¹ K_ic, each block by 2 x 2 Gauss points (exact: the strains are
/// linear in each coordinate).
pub fn membrane(a: f64, b: f64, e: f64, nu: f64, h: f64) -> SMatrix<f64, 8, 8> {
    let d = membrane_rigidity(e, nu, h);
    let mut k = SMatrix::<f64, 12, 12>::zeros();
    for &(xi, wx) in &GAUSS2 {
        for &(eta, wz) in &GAUSS2 {
            let bm = membrane_operator(a, b, xi, eta);
            k += bm.transpose() * d * bm * (wx * wz * a * b);
        }
    }
    condense(&k)
}

/// The membrane stiffness over the 8 bilinear DOFs of one over the 8 bilinear and the 4
/// incompatible DOFs, the incompatible ones condensed out: K = K_cc - K_ci K_ii⁻¹ K_ic.
pub(crate) fn condense(k: &SMatrix<f64, 12, 12>) -> SMatrix<f64, 8, 8> {
    let kcc = k.fixed_view::<8, 8>(0, 0).into_owned();
    let kci = k.fixed_view::<8, 4>(0, 8).into_owned();
    let kii = k.fixed_view::<4, 4>(8, 8).into_owned();
    // K_ii is the energy of the four bubbles alone: positive definite for h, E > 0.
    let kii_inv = kii.try_inverse().unwrap_or_else(SMatrix::<f64, 4, 4>::zeros);
    let out = kcc - kci * kii_inv * kci.transpose();
    0.5 * (out + out.transpose())
}

/// The drilling penalty α G h ∫ (ω₃ - Ω)² dA (α = `alpha`) over (u₁, u₂, ω₃) per node (12 DOFs, in that
/// order), by 2 x 2 Gauss points.
pub fn drilling(a: f64, b: f64, shear_modulus: f64, h: f64, alpha: f64) -> SMatrix<f64, 12, 12> {
    let mut k = SMatrix::<f64, 12, 12>::zeros();
    for &(xi, wx) in &GAUSS2 {
        for &(eta, wz) in &GAUSS2 {
            let n = plate::bilinear(a, b, xi, eta);
            let mut row = SMatrix::<f64, 1, 12>::zeros();
            for (j, [v, dx, dz]) in n.into_iter().enumerate() {
                row[3 * j] = 0.5 * dz;
                row[3 * j + 1] = -0.5 * dx;
                row[3 * j + 2] = v;
            }
            k += row.transpose() * row * (alpha * shear_modulus * h * wx * wz * a * b);
        }
    }
    k
}

/// The parts of a flat shell element's stiffness, in the local frame.
#[derive(Debug, Clone)]
pub struct Parts {
    /// Membrane with the incompatible modes condensed.
    pub membrane: Mat24,
    /// MITC4 bending.
    pub bending: Mat24,
    /// MITC4 transverse shear.
    pub shear: Mat24,
    /// Drilling penalty.
    pub drilling: Mat24,
}

impl Parts {
    /// The element's parts for sides a x b, Young's modulus `e`, Poisson ratio `nu` and
    /// thickness `h`, with Reissner's shear correction `ks` and the drilling factor `alpha`
    /// ([`DRILLING_FACTOR`] unless a test varies it).
    pub fn new(a: f64, b: f64, e: f64, nu: f64, h: f64, ks: f64, alpha: f64) -> Self {
        let g = e / (2.0 * (1.0 + nu));
        let d = e * h.powi(3) / (12.0 * (1.0 - nu * nu));
        let shear_rigidity = plate::shear_rigidity(e, nu, h, ks);
        let full = plate::stiffness(a, b, d, nu, shear_rigidity);
        let shear = plate::stiffness(a, b, 0.0, nu, shear_rigidity);
        Self::from_local(&membrane(a, b, e, nu, h), &(full - shear), &shear, &drilling(a, b, g, h, alpha))
    }

    /// The parts from the element's matrices in their own DOF orders: the membrane over
    /// (u₁, u₂) per node, the plate's bending and shear over (w, θ_x, θ_z) per node, the
    /// drilling penalty over (u₁, u₂, ω₃) per node.
    pub(crate) fn from_local(
        km: &SMatrix<f64, 8, 8>,
        bending: &Mat12,
        shear: &Mat12,
        kd: &SMatrix<f64, 12, 12>,
    ) -> Self {
        let mut out =
            Self { membrane: Mat24::zeros(), bending: Mat24::zeros(), shear: Mat24::zeros(), drilling: Mat24::zeros() };
        for p in 0..12 {
            let (i, si) = plate_dof(p);
            for q in 0..12 {
                let (j, sj) = plate_dof(q);
                out.shear[(i, j)] = si * sj * shear[(p, q)];
                out.bending[(i, j)] = si * sj * bending[(p, q)];
            }
        }
        let membrane_dof = |p: usize| 6 * (p / 2) + p % 2;
        for p in 0..8 {
            for q in 0..8 {
                out.membrane[(membrane_dof(p), membrane_dof(q))] = km[(p, q)];
            }
        }
        let drill_dof = |p: usize| 6 * (p / 3) + [0, 1, 5][p % 3];
        for p in 0..12 {
            for q in 0..12 {
                out.drilling[(drill_dof(p), drill_dof(q))] = kd[(p, q)];
            }
        }
        out
    }

    /// The whole stiffness.
    pub fn total(&self) -> Mat24 {
        self.membrane + self.bending + self.shear + self.drilling
    }
}

/// The local load of a uniform pressure `p` along e₃ over the part [x0, x1] x [z0, z1] of
/// the element ([`plate::pressure_load`] on u₃).
pub fn pressure_load(a: f64, b: f64, part: [f64; 4], p: f64) -> Vec24 {
    let f = plate::pressure_load(a, b, part, p);
    let mut out = Vec24::zeros();
    for k in 0..4 {
        out[6 * k + 2] = f[3 * k];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Local corner positions (x₁, x₂) in the order of the nodes.
    const CORNERS: [(f64, f64); 4] = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)];

    fn nodal(a: f64, b: f64, field: impl Fn(f64, f64) -> [f64; 6]) -> Vec24 {
        let mut d = Vec24::zeros();
        for (k, (e, f)) in CORNERS.into_iter().enumerate() {
            let v = field(e * a, f * b);
            for q in 0..6 {
                d[6 * k + q] = v[q];
            }
        }
        d
    }

    /// Six rigid-body modes (three translations, three rotations as rotation vectors with
    /// u = ω x r) store no energy, and no other mode is free.
    #[test]
    fn six_rigid_modes_and_no_spurious_ones() {
        for (a, b, h) in [(0.3, 0.2, 0.02), (0.05, 0.4, 0.005)] {
            let k = Parts::new(a, b, 210e9, 0.3, h, 5.0 / 6.0, DRILLING_FACTOR).total();
            let rigid = [
                nodal(a, b, |_, _| [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
                nodal(a, b, |_, _| [0.0, 1.0, 0.0, 0.0, 0.0, 0.0]),
                nodal(a, b, |_, _| [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]),
                // ω = e₁: u = ω x (x, y, 0) = (0, 0, y).
                nodal(a, b, |_, y| [0.0, 0.0, y, 1.0, 0.0, 0.0]),
                // ω = e₂: u = (0, 0, -x).
                nodal(a, b, |x, _| [0.0, 0.0, -x, 0.0, 1.0, 0.0]),
                // ω = e₃: u = (-y, x, 0).
                nodal(a, b, |x, y| [-y, x, 0.0, 0.0, 0.0, 1.0]),
            ];
            let scale = k.diagonal().max();
            for (i, r) in rigid.iter().enumerate() {
                assert!((k * r).norm() < 1e-9 * scale * r.norm(), "{a} x {b}: rigid mode {i} strained");
            }
            let mut ev: Vec<f64> = k.symmetric_eigenvalues().iter().copied().collect();
            ev.sort_by(f64::total_cmp);
            assert!(ev[..6].iter().all(|v| v.abs() < 1e-9 * scale), "{ev:?}");
            assert!(ev[6] > 1e-12 * scale, "a seventh zero-energy mode: {ev:?}");
        }
    }

    /// In-plane bending u₁ = -κ x₁ y, u₂ = ½κ x₁² (y = x₂ - b/2 from the mid-line; constant
    /// curvature κ, ν = 0) stores ½ E I κ² a with I = h b³/12: with the incompatible modes the
    /// element is exact (u₂'s x₁² is a bubble's), where plain bilinear elements would also store
    /// a spurious shear energy.
    #[test]
    fn membrane_bends_in_plane_exactly() {
        let (a, b, e, h, kappa) = (0.4, 0.1, 2.0e11, 0.01, 1e-3);
        let km = membrane(a, b, e, 0.0, h);
        let y0 = b / 2.0;
        let mut d = SVector::<f64, 8>::zeros();
        for (k, (s, t)) in CORNERS.into_iter().enumerate() {
            let (x, y) = (s * a, t * b - y0);
            d[2 * k] = -kappa * x * y;
            d[2 * k + 1] = 0.5 * kappa * x * x;
        }
        let exact = 0.5 * e * h * b.powi(3) / 12.0 * kappa * kappa * a;
        assert_relative_eq!(0.5 * d.dot(&(km * d)), exact, max_relative = 1e-10);
    }

    /// A constant membrane strain state stores ½ εᵀ(hD)ε A: the patch test of the element.
    #[test]
    fn constant_membrane_strain_is_exact() {
        let (a, b, e, nu, h) = (0.3, 0.2, 2.0e11, 0.3, 0.01);
        let (ex, ey, gxy) = (1e-4, -3e-5, 2e-5);
        let km = membrane(a, b, e, nu, h);
        let mut d = SVector::<f64, 8>::zeros();
        for (k, (s, t)) in CORNERS.into_iter().enumerate() {
            let (x, y) = (s * a, t * b);
            d[2 * k] = ex * x + 0.5 * gxy * y;
            d[2 * k + 1] = ey * y + 0.5 * gxy * x;
        }
        let eps = nalgebra::Vector3::new(ex, ey, gxy);
        let exact = 0.5 * eps.dot(&(membrane_rigidity(e, nu, h) * eps)) * a * b;
        assert_relative_eq!(0.5 * d.dot(&(km * d)), exact, max_relative = 1e-12);
    }
}
