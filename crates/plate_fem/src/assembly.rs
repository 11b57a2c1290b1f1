//! One quadrature assembler: the plate's weak form written as its integrands.
//!
//! A bilinear form a(u, v) is written as what it integrates at one point, a small function
//! of the values of two basis functions there ([`Basis`]: w and the curvature κ), times a
//! constant coefficient, as scikit-fem writes its `BilinearForm`s. The assembler integrates
//! any such form over an element ([`BilinearForm::element`]) or over one side of it
//! ([`BilinearForm::side`]); the plate's energy is the sum of its forms:
//!
//! ```text
//! bending    a(u, v) = ∫ κ(u)ᵀ D κ(v) dA      stiffness   (strain energy ½ a(w, w))
//! inertia    m(u, v) = ρh ∫ u v dA            consistent mass
//! winkler    s(u, v) = k ∮ u v ds             an elastic line support of stiffness k
//!                                             per length (N/m²) along an edge
//! ```
//!
//! **Exactness.** The Bogner-Fox-Schmit basis is bicubic, so along each direction u v has
//! degree 6 and κ(u)ᵀ D κ(v) at most 6; along a side w is a cubic of the arc length, so the
//! Winkler integrand has degree 6 there. The 4-point Gauss rule integrates degree 7 exactly:
//! 4 x 4 points on the element, 4 on a side, and every matrix is the exact integral of its
//! form (to rounding), not an approximation of it.
//!
//! **Order of operations.** The coefficient multiplies the quadrature weight (once per
//! point), and the integrand's products follow the matrix products Bᵀ D B and N Nᵀ term
//! by term, so that the element matrices are the ones the plate always had, to the bit.
//!
//! ```
//! use plate_fem::assembly::{bending, inertia, winkler};
//! use plate_fem::element::Vec16;
//! use plate_fem::Edge;
//! let (a, b) = (0.4, 0.25);
//! // A rigid translation w = 1 (the w DOFs of the four nodes): no strain energy, mass
//! // ρh a b, and a spring of k per length along the side z = 0 stores k a.
//! let one = Vec16::from_fn(|k, _| if k % 4 == 0 { 1.0 } else { 0.0 });
//! let energy = |m: plate_fem::element::Mat16| one.dot(&(m * one));
//! assert!(energy(bending(2.0, 0.3).element(a, b)).abs() < 1e-12);
//! assert!((energy(inertia(7.0).element(a, b)) - 7.0 * a * b).abs() < 1e-12);
//! assert!((energy(winkler(3.0).side(a, b, Edge::Near)) - 3.0 * a).abs() < 1e-12);
//! ```

use crate::element::{basis, bending_matrix, Basis, Mat16};
use crate::supports::Edge;

/// The 4-point Gauss-Legendre rule on [0, 1], (node, weight): exact for degree ≤ 7.
pub const GAUSS: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_9),
    (0.330_009_478_207_571_9, 0.326_072_577_431_273_1),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_1),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_9),
];

/// A symmetric bilinear form c ∫ f(u, v): its integrand f at one point, a function of the
/// two basis functions' values there, and the constant coefficient c.
#[derive(Debug, Clone, Copy)]
pub struct BilinearForm<F> {
    coefficient: f64,
    integrand: F,
}

impl<F: Fn(&Basis, &Basis) -> f64> BilinearForm<F> {
    /// The form c ∫ f(u, v) with f symmetric, f(u, v) = f(v, u).
    pub const fn new(coefficient: f64, integrand: F) -> Self {
        Self { coefficient, integrand }
    }

    /// The form on an a x b element, ∫ over [0, a] x [0, b] by 4 x 4 Gauss points.
    pub fn element(&self, a: f64, b: f64) -> Mat16 {
        let mut m = Mat16::zeros();
        for &(xi, wx) in &GAUSS {
            for &(eta, wz) in &GAUSS {
                self.add_point(&mut m, &basis(a, b, xi, eta), wx * wz * a * b);
            }
        }
        Self::symmetric(m)
    }

    /// The form on one side of an a x b element, ∫ along it by 4 Gauss points; the side
    /// is named as the plate edge it would lie on (`Left` is ξ = 0, `Near` is η = 0).
    pub fn side(&self, a: f64, b: f64, side: Edge) -> Mat16 {
        let mut m = Mat16::zeros();
        for &(t, wt) in &GAUSS {
            let (xi, eta, length) = match side {
                Edge::Left => (0.0, t, b),
                Edge::Right => (1.0, t, b),
                Edge::Near => (t, 0.0, a),
                Edge::Far => (t, 1.0, a),
            };
            self.add_point(&mut m, &basis(a, b, xi, eta), wt * length);
        }
        Self::symmetric(m)
    }

    /// Adds one quadrature point of weight `weight` (the rule's weight times the Jacobian).
    fn add_point(&self, m: &mut Mat16, u: &[Basis; 16], weight: f64) {
        let scale = weight * self.coefficient;
        for j in 0..16 {
            for i in 0..16 {
                m[(i, j)] += (self.integrand)(&u[i], &u[j]) * scale;
            }
        }
    }

    /// ½(M + Mᵀ): the form is symmetric, and so, exactly, is its matrix.
    fn symmetric(m: Mat16) -> Mat16 {
        0.5 * (m + m.transpose())
    }
}

/// The bending form ∫ κ(u)ᵀ D κ(v) dA of a plate of flexural rigidity `d` and Poisson ratio
/// `nu` (D of [`bending_matrix`], which carries d, so the coefficient is 1): the stiffness.
pub fn bending(d: f64, nu: f64) -> BilinearForm<impl Fn(&Basis, &Basis) -> f64> {
    let dm = bending_matrix(d, nu);
    BilinearForm::new(1.0, move |u: &Basis, v: &Basis| {
        let (ku, kv) = (&u.curvature, &v.curvature);
        // (κ(u)ᵀ D)_r summed against κ(v)_r, in the order of the product Bᵀ D B.
        let row = |r: usize| ku[0] * dm[(0, r)] + ku[1] * dm[(1, r)] + ku[2] * dm[(2, r)];
        row(0) * kv[0] + row(1) * kv[1] + row(2) * kv[2]
    })
}

/// The inertia form ρh ∫ u v dA for mass per area `rho_h` (kg/m²): the consistent mass.
pub fn inertia(rho_h: f64) -> BilinearForm<impl Fn(&Basis, &Basis) -> f64> {
    BilinearForm::new(rho_h, |u: &Basis, v: &Basis| u.w * v.w)
}

/// The Winkler form k ∮ u v ds for a line support of stiffness `k` per length (N/m²):
/// the edge spring, integrated along an element side by [`BilinearForm::side`].
pub fn winkler(k: f64) -> BilinearForm<impl Fn(&Basis, &Basis) -> f64> {
    BilinearForm::new(k, |u: &Basis, v: &Basis| u.w * v.w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::{curvature, shape, Vec16};

    /// The element matrices as they were computed before the assembler: each its own Gauss
    /// loop over the matrix products Bᵀ D B and N Nᵀ.
    fn closed_loops(a: f64, b: f64, d: f64, nu: f64, rho_h: f64) -> (Mat16, Mat16) {
        let dm = bending_matrix(d, nu);
        let (mut k, mut m) = (Mat16::zeros(), Mat16::zeros());
        for &(xi, wx) in &GAUSS {
            for &(eta, wz) in &GAUSS {
                let bm = curvature(a, b, xi, eta);
                k += bm.transpose() * dm * bm * (wx * wz * a * b);
                let n = shape(a, b, xi, eta);
                m += n * n.transpose() * (wx * wz * a * b * rho_h);
            }
        }
        (0.5 * (k + k.transpose()), 0.5 * (m + m.transpose()))
    }

    /// The assembler's stiffness and mass are the closed loops' matrices: equal to 1e-12
    /// relative (the requirement), and in fact bit for bit, on square, long and tiny
    /// elements with different materials.
    #[test]
    fn assembler_reproduces_the_closed_loops() {
        for (a, b, d, nu, rho_h) in
            [(0.3, 0.2, 2.0, 0.3, 7.0), (0.4584 / 20.0, 0.36 / 16.0, 9856.4, 0.3, 62.8), (1e-3, 0.5, 1e-2, 0.1, 1e3)]
        {
            let (k_old, m_old) = closed_loops(a, b, d, nu, rho_h);
            let (k_new, m_new) = (bending(d, nu).element(a, b), inertia(rho_h).element(a, b));
            assert!((k_new - k_old).abs().max() <= 1e-12 * k_old.abs().max(), "stiffness, {a} x {b}");
            assert!((m_new - m_old).abs().max() <= 1e-12 * m_old.abs().max(), "mass, {a} x {b}");
            assert_eq!(k_new, k_old, "stiffness bits, {a} x {b}");
            assert_eq!(m_new, m_old, "mass bits, {a} x {b}");
        }
    }

    /// The Winkler side matrix is the exact ∮ w² ds of fields cubic along the side: for
    /// w = x³ on the side z = 0 of an a x b element, k ∫₀ᵃ x⁶ dx = k a⁷/7; and on the side
    /// x = a, w = z² a³ + z gives k ∫₀ᵇ (a³z² + z)² dz. Sides away from the field's support
    /// see nothing.
    #[test]
    fn winkler_side_integrates_cubics_exactly() {
        let (a, b, k) = (0.4, 0.25, 3.0);
        let nodal = |w: &dyn Fn(f64, f64) -> [f64; 4]| {
            let mut d = Vec16::zeros();
            for (n, (e, f)) in [(0, 0), (1, 0), (0, 1), (1, 1)].into_iter().enumerate() {
                let v = w(e as f64 * a, f as f64 * b);
                for q in 0..4 {
                    d[4 * n + q] = v[q];
                }
            }
            d
        };
        let cubic = nodal(&|x, _| [x.powi(3), 3.0 * x * x, 0.0, 0.0]);
        let store = |side, d: &Vec16| d.dot(&(winkler(k).side(a, b, side) * d));
        assert!((store(Edge::Near, &cubic) / (k * a.powi(7) / 7.0) - 1.0).abs() < 1e-13);
        assert!((store(Edge::Far, &cubic) / (k * a.powi(7) / 7.0) - 1.0).abs() < 1e-13);
        let mixed =
            nodal(&|x, z| [x.powi(3) * z * z + z, 3.0 * x * x * z * z, 2.0 * x.powi(3) * z + 1.0, 6.0 * x * x * z]);
        let a3 = a.powi(3);
        let exact = k * (a3 * a3 * b.powi(5) / 5.0 + a3 * b.powi(4) / 2.0 + b.powi(3) / 3.0);
        assert!((store(Edge::Right, &mixed) / exact - 1.0).abs() < 1e-13);
        let exact_left = k * b.powi(3) / 3.0; // w = z at x = 0
        assert!((store(Edge::Left, &mixed) / exact_left - 1.0).abs() < 1e-13);
    }
}
