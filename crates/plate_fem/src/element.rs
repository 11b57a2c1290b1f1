//! The Bogner-Fox-Schmit rectangle: a conforming C¹ Kirchhoff plate element.
//!
//! On an a x b rectangle the deflection is the tensor product of cubic Hermite
//! polynomials, w(ξ, η) = Σ F_p(ξ) G_q(η) d_pq, with nodal values (w, w_x, w_z, w_xz) at the
//! four corners. Along every element side w and its normal slope are cubics fixed by the
//! two end nodes, so w is C¹ across elements on a rectangular grid and the element is
//! conforming: the discrete energy bounds the exact one from below (the FE compliance
//! approaches from below). It is exact for bicubic fields; its energy error is O(h²)
//! for smooth solutions. Integration by 4 x 4 Gauss points is exact for the stiffness
//! (degree ≤ 6 per direction) and the consistent mass (degree 6).
//!
//! This module holds the element's basis ([`shape`], [`curvature`], [`basis`]); its
//! matrices are the plate's bilinear forms integrated by [`crate::assembly`]
//! ([`stiffness`] and [`mass`] name the two the plate always has).

use nalgebra::{SMatrix, SVector};

/// An element matrix over the 16 local DOFs (four nodes x (w, w_x, w_z, w_xz)).
pub type Mat16 = SMatrix<f64, 16, 16>;
/// An element vector over the 16 local DOFs.
pub type Vec16 = SVector<f64, 16>;

/// Cubic Hermite functions on [0, 1] for a side of length `h`: value at 0, slope at 0,
/// value at 1, slope at 1; with their first and second derivatives in the physical
/// coordinate.
fn hermite(t: f64, h: f64) -> ([f64; 4], [f64; 4], [f64; 4]) {
    let (t2, t3) = (t * t, t * t * t);
    let f = [1.0 - 3.0 * t2 + 2.0 * t3, h * (t - 2.0 * t2 + t3), 3.0 * t2 - 2.0 * t3, h * (t3 - t2)];
    let d1 = [(-6.0 * t + 6.0 * t2) / h, 1.0 - 4.0 * t + 3.0 * t2, (6.0 * t - 6.0 * t2) / h, 3.0 * t2 - 2.0 * t];
    let d2 = [(-6.0 + 12.0 * t) / (h * h), (-4.0 + 6.0 * t) / h, (6.0 - 12.0 * t) / (h * h), (6.0 * t - 2.0) / h];
    (f, d1, d2)
}

/// nᵀ B n for an element block `b` (16 x 16, row-major): a point compliance N(p)ᵀ K⁻¹ N(p)
/// when `b` is K⁻¹'s block and `n` the shape functions at p.
pub fn quadratic(b: &[f64; 256], n: &Vec16) -> f64 {
    (0..16).map(|k| n[k] * (0..16).map(|l| b[k * 16 + l] * n[l]).sum::<f64>()).sum()
}

/// For local DOF k: which 1-D Hermite function along x and along z it uses.
/// Local node n = (e, f) in the order (0,0), (1,0), (0,1), (1,1); DOFs (w, w_x, w_z, w_xz).
fn factors(k: usize) -> (usize, usize) {
    let (n, q) = (k / 4, k % 4);
    let (e, f) = [(0, 0), (1, 0), (0, 1), (1, 1)][n];
    let dx = usize::from(q == 1 || q == 3);
    let dz = usize::from(q == 2 || q == 3);
    (2 * e + dx, 2 * f + dz)
}

/// Shape functions at (ξ, η) ∈ [0, 1]² of an a x b element: N_k with w = N · d.
pub fn shape(a: f64, b: f64, xi: f64, eta: f64) -> Vec16 {
    let (fx, _, _) = hermite(xi, a);
    let (fz, _, _) = hermite(eta, b);
    Vec16::from_fn(|k, _| {
        let (p, q) = factors(k);
        fx[p] * fz[q]
    })
}

/// Curvature operator at (ξ, η): rows w_xx, w_zz, 2w_xz.
pub fn curvature(a: f64, b: f64, xi: f64, eta: f64) -> SMatrix<f64, 3, 16> {
    let (fx, dx, ddx) = hermite(xi, a);
    let (fz, dz, ddz) = hermite(eta, b);
    SMatrix::<f64, 3, 16>::from_fn(|r, k| {
        let (p, q) = factors(k);
        match r {
            0 => ddx[p] * fz[q],
            1 => fx[p] * ddz[q],
            _ => 2.0 * dx[p] * dz[q],
        }
    })
}

/// Plane-stress bending constitutive matrix D [[1, ν, 0], [ν, 1, 0], [0, 0, (1-ν)/2]]:
/// moments (M_x, M_z, M_xz) = -D κ with κ = (w_xx, w_zz, 2w_xz).
pub fn bending_matrix(d: f64, nu: f64) -> SMatrix<f64, 3, 3> {
    SMatrix::<f64, 3, 3>::new(d, d * nu, 0.0, d * nu, d, 0.0, 0.0, 0.0, d * (1.0 - nu) / 2.0)
}

/// The values at one point of one basis function N_k: what a bilinear form's integrand
/// reads ([`crate::assembly`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Basis {
    /// Deflection N_k.
    pub w: f64,
    /// Curvature (∂²N_k/∂x², ∂²N_k/∂z², 2∂²N_k/∂x∂z), the rows of [`curvature`].
    pub curvature: [f64; 3],
}

/// All 16 basis functions at (ξ, η) of an a x b element: the same products as [`shape`] and
/// [`curvature`], from one evaluation of the Hermite functions.
pub fn basis(a: f64, b: f64, xi: f64, eta: f64) -> [Basis; 16] {
    let (fx, dx, ddx) = hermite(xi, a);
    let (fz, dz, ddz) = hermite(eta, b);
    std::array::from_fn(|k| {
        let (p, q) = factors(k);
        Basis { w: fx[p] * fz[q], curvature: [ddx[p] * fz[q], fx[p] * ddz[q], 2.0 * dx[p] * dz[q]] }
    })
}

/// Element stiffness K_e = ∫ κᵀ D κ dA for flexural rigidity `d` and Poisson ratio `nu`:
/// the bending form [`crate::assembly::bending`] on the element.
pub fn stiffness(a: f64, b: f64, d: f64, nu: f64) -> Mat16 {
    crate::assembly::bending(d, nu).element(a, b)
}

/// Consistent mass M_e = ∫ ρh Nᵀ N dA for mass per area `rho_h`: the inertia form
/// [`crate::assembly::inertia`] on the element.
pub fn mass(a: f64, b: f64, rho_h: f64) -> Mat16 {
    crate::assembly::inertia(rho_h).element(a, b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Nodal DOFs of a polynomial field w(x, z) given with its derivatives.
    fn interpolate(a: f64, b: f64, w: impl Fn(f64, f64) -> [f64; 4]) -> Vec16 {
        let mut d = Vec16::zeros();
        for (n, (e, f)) in [(0, 0), (1, 0), (0, 1), (1, 1)].into_iter().enumerate() {
            let v = w(e as f64 * a, f as f64 * b);
            for q in 0..4 {
                d[4 * n + q] = v[q];
            }
        }
        d
    }

    #[test]
    fn stiffness_is_symmetric_with_three_rigid_modes() {
        let k = stiffness(0.3, 0.2, 2.0, 0.3);
        assert!((k - k.transpose()).abs().max() < 1e-12 * k.abs().max());
        let eig = k.symmetric_eigenvalues();
        let mut ev: Vec<f64> = eig.iter().copied().collect();
        ev.sort_by(f64::total_cmp);
        let scale = ev[15];
        assert!(ev[..3].iter().all(|v| v.abs() < 1e-10 * scale), "{ev:?}");
        assert!(ev[3] > 1e-6 * scale, "only three zero-energy modes: {ev:?}");
    }

    /// A bicubic field is reproduced exactly, and its energy ½dᵀKd equals the integral of
    /// the energy density of that field (here w = x²z: κ = (2z, 0, 4x), done by hand).
    #[test]
    fn energy_of_a_polynomial_field_is_exact() {
        let (a, b, d, nu) = (0.4, 0.25, 3.0, 0.3);
        let dofs = interpolate(a, b, |x, z| [x * x * z, 2.0 * x * z, x * x, 2.0 * x]);
        let n = shape(a, b, 0.3, 0.7);
        assert_relative_eq!(n.dot(&dofs), (0.3 * a).powi(2) * 0.7 * b, max_relative = 1e-13);
        let k = stiffness(a, b, d, nu);
        let energy = 0.5 * dofs.dot(&(k * dofs));
        // U = ½D∫[(2z)² + 0 + 2ν·0 + 2(1-ν)(2x)²] dA = ½D[4ab³/3 + 8(1-ν)a³b/3].
        let exact = 0.5 * d * (4.0 * a * b.powi(3) / 3.0 + 8.0 * (1.0 - nu) * a.powi(3) * b / 3.0);
        assert_relative_eq!(energy, exact, max_relative = 1e-13);
    }

    #[test]
    fn mass_integrates_total_mass() {
        let (a, b, rho_h) = (0.4, 0.25, 7.0);
        let m = mass(a, b, rho_h);
        // Rigid translation w = 1: dᵀMd = ρh a b.
        let one = interpolate(a, b, |_, _| [1.0, 0.0, 0.0, 0.0]);
        assert_relative_eq!(one.dot(&(m * one)), rho_h * a * b, max_relative = 1e-13);
    }
}
