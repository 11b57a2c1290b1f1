//! The flat shell quadrilateral of any convex shape: the rectangle of [`super::element`] on an
//! isoparametric bilinear map.
//!
//! A flat quadrilateral with corners x_k = (x_k, y_k) in its own plane is the image of the unit
//! square under x(ξ, η) = Σ N_k(ξ, η) x_k, with the bilinear N_k and the nodes in the order
//! (0,0), (1,0), (0,1), (1,1) of [`super::element`]. The Jacobian J, whose rows are the
//! covariant base vectors g_ξ = ∂x/∂ξ and g_η = ∂x/∂η, turns parameter derivatives into
//! Cartesian ones, ∇N = J⁻¹ ∂N/∂(ξ, η), and dA = det J dξ dη. Each part is then the
//! rectangle's:
//!
//! - **membrane**: bilinear u with the incompatible modes 4ξ(1-ξ), 4η(1-η) in the form QM6 of
//!   Taylor, Beresford & Wilson (*Int. J. Numer. Meth. Eng.* 10, 1211-1219, 1976): their
//!   Cartesian derivatives use the Jacobian J₀ at the centre, scaled by det J₀/det J,
//!   ∇φ = (det J₀/det J) J₀⁻¹ ∂φ/∂(ξ, η), so that ∫ ∇φ dA = det J₀ J₀⁻¹ ∫ ∂φ/∂(ξ, η) dξ dη = 0
//!   and the element passes the patch test on any shape;
//! - **plate**: MITC4 in Bathe and Dvorkin's covariant form (*Int. J. Numer. Meth. Eng.* 21,
//!   367-383, 1985). The covariant transverse shear strains e_ξ = ∂w/∂ξ - θ·g_ξ and
//!   e_η = ∂w/∂η - θ·g_η are tied at the midsides, e_ξ at (½, 0) and (½, 1) and interpolated
//!   in η, e_η at (0, ½) and (1, ½) and interpolated in ξ; the Cartesian shear is
//!   γ = J⁻¹ (ê_ξ, ê_η), since e = J γ. The bending strains use ∇N;
//! - **drilling**: the penalty α G h ∫ (ω₃ - Ω)² dA with Ω = ½(∂u₂/∂x - ∂u₁/∂y) from ∇N.
//!
//! On a rectangle J = diag(a, b) everywhere, ∇φ is the rectangle's, e_ξ = a γ_x at the same
//! tying points, and each part is the rectangle element's to rounding (tested). All parts are
//! integrated by 2 x 2 Gauss points, exact on a parallelogram (constant J) and the element's
//! standard rule on other shapes, where the integrands are rational in (ξ, η).

use super::element::{condense, membrane_rigidity, Parts};
use crate::mindlin::element::{bilinear, shear_rigidity, Mat12, GAUSS2};
use crate::FemError;
use nalgebra::{Matrix2, SMatrix, Vector2};

/// The parameter corners of the nodes, in their order.
const CORNERS: [(f64, f64); 4] = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)];

/// A convex quadrilateral in its own plane: corners (x, y), m, in the order (0,0), (1,0),
/// (0,1), (1,1) of the parameter square (so its boundary runs 0, 1, 3, 2 counter-clockwise).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quad {
    xy: [[f64; 2]; 4],
}

/// The map at one parameter point: N, ∇N and the Jacobian with its determinant.
struct At {
    n: [f64; 4],
    grad: [Vector2<f64>; 4],
    jac: Matrix2<f64>,
    det: f64,
}

impl Quad {
    /// The quadrilateral with corners `xy`; refused unless finite, counter-clockwise (0, 1,
    /// 3, 2) and convex: det J > 0 at every corner, where the bilinear map's det J takes its
    /// extremes.
    pub fn new(xy: [[f64; 2]; 4]) -> Result<Self, FemError> {
        let quad = Self { xy };
        let size = quad.diameter();
        let convex = CORNERS.iter().all(|&(xi, eta)| quad.jacobian(xi, eta).determinant() > 1e-9 * size * size);
        if !(size.is_finite() && size > 0.0 && convex) {
            return Err(FemError::Mesh(format!(
                "quadrilateral with corners {xy:?} (in the order (0,0), (1,0), (0,1), (1,1) of its parameters) is not convex and counter-clockwise: det J must be positive at every corner"
            )));
        }
        Ok(quad)
    }

    /// The longer diagonal (m).
    fn diameter(&self) -> f64 {
        let [p0, p1, p2, p3] = self.xy.map(Vector2::from);
        (p3 - p0).norm().max((p2 - p1).norm())
    }

    /// J at (ξ, η): rows g_ξ and g_η.
    fn jacobian(&self, xi: f64, eta: f64) -> Matrix2<f64> {
        let n = bilinear(1.0, 1.0, xi, eta);
        let mut j = Matrix2::zeros();
        for (k, [_, dxi, deta]) in n.into_iter().enumerate() {
            for c in 0..2 {
                j[(0, c)] += dxi * self.xy[k][c];
                j[(1, c)] += deta * self.xy[k][c];
            }
        }
        j
    }

    fn at(&self, xi: f64, eta: f64) -> At {
        let jac = self.jacobian(xi, eta);
        let det = jac.determinant();
        // Convex by construction: det J > 0 inside.
        let inv = jac.try_inverse().unwrap_or_else(Matrix2::zeros);
        let shape = bilinear(1.0, 1.0, xi, eta);
        At { n: shape.map(|s| s[0]), grad: shape.map(|[_, dxi, deta]| inv * Vector2::new(dxi, deta)), jac, det }
    }

    /// ∫ f dA by 2 x 2 Gauss points, with the map at each.
    fn integrate<const R: usize, const C: usize>(
        &self,
        f: impl Fn(f64, f64, &At) -> SMatrix<f64, R, C>,
    ) -> SMatrix<f64, R, C> {
        let mut k = SMatrix::<f64, R, C>::zeros();
        for &(xi, wx) in &GAUSS2 {
            for &(eta, wz) in &GAUSS2 {
                let at = self.at(xi, eta);
                k += f(xi, eta, &at) * (wx * wz * at.det);
            }
        }
        k
    }

    /// The parameters (ξ, η) of the point `p` of the element's plane, by Newton's iteration on
    /// the bilinear map from the centre; None if it does not converge to 1e-12 of the element's
    /// size in 30 steps or lands outside [-1e-9, 1 + 1e-9]² (the point is not on the element).
    pub fn locate(&self, p: [f64; 2]) -> Option<(f64, f64)> {
        let size = self.diameter();
        let (mut xi, mut eta) = (0.5, 0.5);
        for _ in 0..30 {
            let n = bilinear(1.0, 1.0, xi, eta);
            let x: Vector2<f64> = (0..4).map(|k| Vector2::from(self.xy[k]) * n[k][0]).sum();
            let r = Vector2::from(p) - x;
            if r.norm() <= 1e-12 * size {
                let inside = |t: f64| (-1e-9..=1.0 + 1e-9).contains(&t);
                return (inside(xi) && inside(eta)).then_some((xi.clamp(0.0, 1.0), eta.clamp(0.0, 1.0)));
            }
            // r = Jᵀ (Δξ, Δη): J's rows are ∂x/∂ξ and ∂x/∂η.
            let step = self.jacobian(xi, eta).transpose().try_inverse()? * r;
            (xi, eta) = (xi + step.x, eta + step.y);
        }
        None
    }

    /// The shape functions N_k at (ξ, η).
    pub fn shape(xi: f64, eta: f64) -> [f64; 4] {
        bilinear(1.0, 1.0, xi, eta).map(|s| s[0])
    }

    /// The area (m²): exact, det J being linear in (ξ, η).
    pub fn area(&self) -> f64 {
        self.nodal_areas().iter().sum()
    }

    /// ∫ N_k dA for each node (m²): its share of a uniform load or of a lumped mass. Exact
    /// (the integrand is quadratic in each parameter).
    pub fn nodal_areas(&self) -> [f64; 4] {
        let v = self.integrate(|_, _, at| SMatrix::<f64, 4, 1>::from_column_slice(&at.n));
        [v[0], v[1], v[2], v[3]]
    }

    /// The membrane stiffness over (u₁, u₂) per node, QM6's incompatible modes condensed.
    pub fn membrane(&self, e: f64, nu: f64, h: f64) -> SMatrix<f64, 8, 8> {
        let d = membrane_rigidity(e, nu, h);
        let j0 = self.jacobian(0.5, 0.5);
        let (det0, j0_inv) = (j0.determinant(), j0.try_inverse().unwrap_or_else(Matrix2::zeros));
        let k = self.integrate(|xi, eta, at| {
            let mut m = SMatrix::<f64, 3, 12>::zeros();
            for (k, g) in at.grad.iter().enumerate() {
                m[(0, 2 * k)] = g.x;
                m[(1, 2 * k + 1)] = g.y;
                m[(2, 2 * k)] = g.y;
                m[(2, 2 * k + 1)] = g.x;
            }
            let scale = det0 / at.det;
            let g_xi = j0_inv * Vector2::new(4.0 * (1.0 - 2.0 * xi), 0.0) * scale;
            let g_eta = j0_inv * Vector2::new(0.0, 4.0 * (1.0 - 2.0 * eta)) * scale;
            // Incompatible DOFs 8..12: u₁·φ_ξ, u₁·φ_η, u₂·φ_ξ, u₂·φ_η.
            for (col, g, component) in [(8, g_xi, 0), (9, g_eta, 0), (10, g_xi, 1), (11, g_eta, 1)] {
                let (along, across) = if component == 0 { (g.x, g.y) } else { (g.y, g.x) };
                m[(component, col)] = along;
                m[(2, col)] = across;
            }
            m.transpose() * d * m
        });
        condense(&k)
    }

    /// The covariant shear strains (e_ξ, e_η) of the displacement field as it stands at
    /// (ξ, η), over (w, θ_x, θ_y) per node.
    fn covariant_shear(&self, xi: f64, eta: f64) -> SMatrix<f64, 2, 12> {
        let j = self.jacobian(xi, eta);
        let mut m = SMatrix::<f64, 2, 12>::zeros();
        for (k, [n, dxi, deta]) in bilinear(1.0, 1.0, xi, eta).into_iter().enumerate() {
            for (row, d) in [(0, dxi), (1, deta)] {
                m[(row, 3 * k)] = d;
                m[(row, 3 * k + 1)] = -n * j[(row, 0)];
                m[(row, 3 * k + 2)] = -n * j[(row, 1)];
            }
        }
        m
    }

    /// The plate's bending and MITC4 shear stiffness over (w, θ_x, θ_y) per node, for
    /// flexural rigidity `d`, Poisson ratio `nu` and shear rigidity `shear` (N/m).
    pub fn plate(&self, d: f64, nu: f64, shear: f64) -> (Mat12, Mat12) {
        let db = crate::element::bending_matrix(d, nu);
        let bending = self.integrate(|_, _, at| {
            let mut b = SMatrix::<f64, 3, 12>::zeros();
            for (k, g) in at.grad.iter().enumerate() {
                b[(0, 3 * k + 1)] = g.x;
                b[(1, 3 * k + 2)] = g.y;
                b[(2, 3 * k + 1)] = g.y;
                b[(2, 3 * k + 2)] = g.x;
            }
            b.transpose() * db * b
        });
        let [near, far] = [self.covariant_shear(0.5, 0.0), self.covariant_shear(0.5, 1.0)];
        let [left, right] = [self.covariant_shear(0.0, 0.5), self.covariant_shear(1.0, 0.5)];
        let shear_k = self.integrate(|xi, eta, at| {
            let mut e = SMatrix::<f64, 2, 12>::zeros();
            e.row_mut(0).copy_from(&(near.row(0) * (1.0 - eta) + far.row(0) * eta));
            e.row_mut(1).copy_from(&(left.row(1) * (1.0 - xi) + right.row(1) * xi));
            let gamma = at.jac.try_inverse().unwrap_or_else(Matrix2::zeros) * e;
            gamma.transpose() * gamma * shear
        });
        (symmetric(bending), symmetric(shear_k))
    }

    /// The drilling penalty α G h ∫ (ω₃ - Ω)² dA over (u₁, u₂, ω₃) per node.
    pub fn drilling(&self, shear_modulus: f64, h: f64, alpha: f64) -> SMatrix<f64, 12, 12> {
        let k = self.integrate(|_, _, at| {
            let mut row = SMatrix::<f64, 1, 12>::zeros();
            for (j, (n, g)) in at.n.iter().zip(&at.grad).enumerate() {
                row[3 * j] = 0.5 * g.y;
                row[3 * j + 1] = -0.5 * g.x;
                row[3 * j + 2] = *n;
            }
            row.transpose() * row
        });
        k * (alpha * shear_modulus * h)
    }

    /// The element's parts for Young's modulus `e`, Poisson ratio `nu`, thickness `h`,
    /// Reissner's shear correction `ks` and the drilling factor `alpha`.
    pub fn parts(&self, e: f64, nu: f64, h: f64, ks: f64, alpha: f64) -> Parts {
        let g = e / (2.0 * (1.0 + nu));
        let d = e * h.powi(3) / (12.0 * (1.0 - nu * nu));
        let (bending, shear) = self.plate(d, nu, shear_rigidity(e, nu, h, ks));
        Parts::from_local(&self.membrane(e, nu, h), &bending, &shear, &self.drilling(g, h, alpha))
    }
}

fn symmetric(k: Mat12) -> Mat12 {
    0.5 * (k + k.transpose())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mindlin::SHEAR_CORRECTION;
    use crate::shell::element::{Mat24, DRILLING_FACTOR};

    const STEEL: (f64, f64) = (210e9, 0.3);

    fn largest(m: &Mat24) -> f64 {
        m.iter().fold(0.0, |a, v| a.max(v.abs()))
    }

    /// On a rectangle the isoparametric element is the rectangle element: every part agrees
    /// with [`Parts::new`] (closed-form derivatives on a x b) to 1e-13 of its largest entry,
    /// wherever the rectangle sits in its plane.
    #[test]
    fn a_rectangle_is_the_rectangle_element() {
        let (a, b, h) = (0.3, 0.17, 0.02);
        let (e, nu) = STEEL;
        let rect = Parts::new(a, b, e, nu, h, SHEAR_CORRECTION, DRILLING_FACTOR);
        let (x0, y0) = (-1.3, 0.4);
        let quad = Quad::new([[x0, y0], [x0 + a, y0], [x0, y0 + b], [x0 + a, y0 + b]]).unwrap();
        let general = quad.parts(e, nu, h, SHEAR_CORRECTION, DRILLING_FACTOR);
        for (name, r, g) in [
            ("membrane", &rect.membrane, &general.membrane),
            ("bending", &rect.bending, &general.bending),
            ("shear", &rect.shear, &general.shear),
            ("drilling", &rect.drilling, &general.drilling),
        ] {
            let diff = largest(&(r - g));
            assert!(diff <= 1e-13 * largest(r), "{name}: differs by {diff:e} of {:e}", largest(r));
        }
        assert!((quad.area() - a * b).abs() < 1e-15);
    }

    /// A distorted quadrilateral has exactly the six rigid-body motions of a flat element as
    /// zero-energy modes: the three translations and the three rotations (about the normal,
    /// u = ω x r with ω₃ = ω; about an in-plane axis, w = (ω x r)·e₃ with the nodal rotation
    /// vector ω) have no energy to 1e-12 of the stiffness, and the seventh eigenvalue is a
    /// proper stiffness (no spurious mechanism).
    #[test]
    fn a_distorted_quad_has_the_six_rigid_modes_and_no_more() {
        let (e, nu) = STEEL;
        let quad = Quad::new([[0.0, 0.0], [1.1, 0.2], [0.3, 0.9], [1.0, 1.3]]).unwrap();
        let k = quad.parts(e, nu, 0.05, SHEAR_CORRECTION, DRILLING_FACTOR).total();
        let scale = largest(&k);
        let mut rigid = Vec::new();
        for t in 0..3 {
            rigid.push(nalgebra::SVector::<f64, 24>::from_fn(|d, _| if d % 6 == t { 1.0 } else { 0.0 }));
        }
        for axis in 0..3 {
            let mut omega = nalgebra::Vector3::zeros();
            omega[axis] = 1.0;
            rigid.push(nalgebra::SVector::<f64, 24>::from_fn(|d, _| {
                let r = nalgebra::Vector3::new(quad.xy[d / 6][0], quad.xy[d / 6][1], 0.0);
                let u = omega.cross(&r);
                if d % 6 < 3 {
                    u[d % 6]
                } else {
                    omega[d % 6 - 3]
                }
            }));
        }
        for (i, r) in rigid.iter().enumerate() {
            let force = (k * r).amax();
            assert!(force <= 1e-12 * scale * r.amax(), "rigid mode {i}: force {force:e}");
        }
        let mut eig: Vec<f64> = k.symmetric_eigen().eigenvalues.iter().copied().collect();
        eig.sort_by(f64::total_cmp);
        assert!(eig[5] <= 1e-10 * scale && eig[6] > 1e-6 * scale, "eigenvalues {:e}, {:e}", eig[5], eig[6]);
    }

    /// Concave, clockwise and degenerate quadrilaterals are refused.
    #[test]
    fn bad_shapes_are_refused() {
        assert!(Quad::new([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.2, 0.2]]).is_err());
        assert!(Quad::new([[0.0, 0.0], [0.0, 1.0], [1.0, 0.0], [1.0, 1.0]]).is_err());
        assert!(Quad::new([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]]).is_err());
        assert!(Quad::new([[0.0, 0.0], [1.0, 0.0], [0.0, f64::NAN], [1.0, 1.0]]).is_err());
    }
}
