//! The MITC4 rectangle: a bilinear Reissner-Mindlin plate element free of shear locking.
//!
//! On an a x b rectangle the deflection w and the two section rotations θ = (θ_x, θ_z) are
//! bilinear, with nodal values (w, θ_x, θ_z) at the four corners. The strains are
//!
//! ```text
//! bending  κ = (∂θ_x/∂x, ∂θ_z/∂z, ∂θ_x/∂z + ∂θ_z/∂x)
//! shear    γ = (∂w/∂x - θ_x, ∂w/∂z - θ_z)
//! energy   U = ½ ∫ κᵀ D_b κ dA + ½ k_s G h ∫ γᵀγ dA
//! ```
//!
//! so that θ = ∇w, γ = 0 is Kirchhoff's plate, with κ the curvature (w_xx, w_zz, 2w_xz) of
//! [`crate::element`]. Integrated as it stands, the bilinear shear cannot vanish under a
//! bending field and the element locks: its stiffness grows like (L/h)² as the plate thins.
//! MITC4 (Bathe & Dvorkin 1985, *Int. J. Numer. Meth. Eng.* 21, 367-383) replaces γ by an
//! assumed strain: γ_x is sampled at the midpoints of the two sides along x and interpolated
//! linearly across, γ_z at the midpoints of the two sides along z,
//!
//! ```text
//! γ_x(ξ, η) = (1 - η) γ_x(½, 0) + η γ_x(½, 1)
//! γ_z(ξ, η) = (1 - ξ) γ_z(0, ½) + ξ γ_z(1, ½)
//! ```
//!
//! At those tying points ∂w/∂x along the side and θ_x at its midpoint are both exact for a
//! bending field, so the element represents pure bending without shear and converges to
//! Kirchhoff's plate as h → 0. It passes the patch test, has exactly the three rigid-body
//! zero-energy modes, and is integrated exactly by 2 x 2 Gauss points (κ is linear in each
//! coordinate, the assumed γ_x constant in ξ and linear in η).

use nalgebra::{SMatrix, SVector};

/// An element matrix over the 12 local DOFs (four nodes x (w, θ_x, θ_z)).
pub type Mat12 = SMatrix<f64, 12, 12>;
/// An element vector over the 12 local DOFs.
pub type Vec12 = SVector<f64, 12>;

/// Degrees of freedom per node: (w, θ_x, θ_z).
pub const DOFS_PER_NODE: usize = 3;

/// The 2-point Gauss-Legendre rule on [0, 1], (node, weight): exact for degree ≤ 3.
pub const GAUSS2: [(f64, f64); 2] = [(0.211_324_865_405_187_1, 0.5), (0.788_675_134_594_812_9, 0.5)];

/// Local nodes (0,0), (1,0), (0,1), (1,1), the order of [`crate::element`].
const NODES: [(usize, usize); 4] = [(0, 0), (1, 0), (0, 1), (1, 1)];

/// Bilinear shape functions at (ξ, η) ∈ [0, 1]² and their derivatives in x and z on an
/// a x b element: (N, ∂N/∂x, ∂N/∂z) per local node.
pub fn bilinear(a: f64, b: f64, xi: f64, eta: f64) -> [[f64; 3]; 4] {
    NODES.map(|(e, f)| {
        let (fx, dfx) = if e == 0 { (1.0 - xi, -1.0) } else { (xi, 1.0) };
        let (fz, dfz) = if f == 0 { (1.0 - eta, -1.0) } else { (eta, 1.0) };
        [fx * fz, dfx * fz / a, fx * dfz / b]
    })
}

/// The deflection's shape functions at (ξ, η): w = N · d (rotations get no weight).
pub fn deflection(a: f64, b: f64, xi: f64, eta: f64) -> Vec12 {
    let n = bilinear(a, b, xi, eta);
    Vec12::from_fn(|k, _| if k % 3 == 0 { n[k / 3][0] } else { 0.0 })
}

/// The bending operator at (ξ, η): rows ∂θ_x/∂x, ∂θ_z/∂z, ∂θ_x/∂z + ∂θ_z/∂x.
pub fn bending_operator(a: f64, b: f64, xi: f64, eta: f64) -> SMatrix<f64, 3, 12> {
    let n = bilinear(a, b, xi, eta);
    let mut m = SMatrix::<f64, 3, 12>::zeros();
    for (k, [_, dx, dz]) in n.into_iter().enumerate() {
        m[(0, 3 * k + 1)] = dx;
        m[(1, 3 * k + 2)] = dz;
        m[(2, 3 * k + 1)] = dz;
        m[(2, 3 * k + 2)] = dx;
    }
    m
}

/// The shear strain of the displacement field as it stands at (ξ, η): rows
/// ∂w/∂x - θ_x and ∂w/∂z - θ_z. Sampled at the tying points by [`assumed_shear`].
pub fn displacement_shear(a: f64, b: f64, xi: f64, eta: f64) -> SMatrix<f64, 2, 12> {
    let n = bilinear(a, b, xi, eta);
    let mut m = SMatrix::<f64, 2, 12>::zeros();
    for (k, [v, dx, dz]) in n.into_iter().enumerate() {
        m[(0, 3 * k)] = dx;
        m[(0, 3 * k + 1)] = -v;
        m[(1, 3 * k)] = dz;
        m[(1, 3 * k + 2)] = -v;
    }
    m
}

/// The MITC4 assumed shear strain at (ξ, η): γ_x from the tying points (½, 0) and (½, 1),
/// γ_z from (0, ½) and (1, ½), each interpolated linearly across.
pub fn assumed_shear(a: f64, b: f64, xi: f64, eta: f64) -> SMatrix<f64, 2, 12> {
    let (near, far) = (displacement_shear(a, b, 0.5, 0.0), displacement_shear(a, b, 0.5, 1.0));
    let (left, right) = (displacement_shear(a, b, 0.0, 0.5), displacement_shear(a, b, 1.0, 0.5));
    let mut m = SMatrix::<f64, 2, 12>::zeros();
    m.row_mut(0).copy_from(&(near.row(0) * (1.0 - eta) + far.row(0) * eta));
    m.row_mut(1).copy_from(&(left.row(1) * (1.0 - xi) + right.row(1) * xi));
    m
}

/// Shear rigidity k_s G h per unit length (N/m), with G = E / 2(1 + ν).
pub fn shear_rigidity(youngs_modulus: f64, poisson_ratio: f64, thickness: f64, shear_correction: f64) -> f64 {
    shear_correction * youngs_modulus / (2.0 * (1.0 + poisson_ratio)) * thickness
}

/// Element stiffness K_e = ∫ Bᵀ D_b B dA + k_s G h ∫ B_sᵀ B_s dA with the assumed shear B_s,
/// for flexural rigidity `d`, Poisson ratio `nu` and shear rigidity `shear` (N/m); 2 x 2
/// Gauss points, exact for both integrands.
pub fn stiffness(a: f64, b: f64, d: f64, nu: f64, shear: f64) -> Mat12 {
    integrate(a, b, |xi, eta| {
        let bb = bending_operator(a, b, xi, eta);
        let bs = assumed_shear(a, b, xi, eta);
        bb.transpose() * crate::element::bending_matrix(d, nu) * bb + bs.transpose() * bs * shear
    })
}

/// Element consistent mass M_e = ∫ [ρh N_wᵀN_w + (ρh³/12)(N_θxᵀN_θx + N_θzᵀN_θz)] dA for mass
/// per area `rho_h` (kg/m²) and rotary inertia per area `rho_i` = ρh³/12 (kg): translation
/// and the rotation of the sections (Mindlin 1951); 2 x 2 Gauss points, exact (the integrand is
/// biquadratic).
pub fn mass(a: f64, b: f64, rho_h: f64, rho_i: f64) -> Mat12 {
    integrate(a, b, |xi, eta| {
        let n = bilinear(a, b, xi, eta);
        Mat12::from_fn(|p, q| {
            let (np, nq) = (n[p / 3][0], n[q / 3][0]);
            match (p % 3, q % 3) {
                (0, 0) => rho_h * np * nq,
                (1, 1) | (2, 2) => rho_i * np * nq,
                _ => 0.0,
            }
        })
    })
}

/// ∫ f(ξ, η) dA over the a x b element by 2 x 2 Gauss points, symmetrised.
pub(crate) fn integrate(a: f64, b: f64, f: impl Fn(f64, f64) -> Mat12) -> Mat12 {
    let mut k = Mat12::zeros();
    for &(xi, wx) in &GAUSS2 {
        for &(eta, wz) in &GAUSS2 {
            k += f(xi, eta) * (wx * wz * a * b);
        }
    }
    0.5 * (k + k.transpose())
}

/// The element load of a uniform pressure `p` (Pa) over the part [x0, x1] x [z0, z1] of
/// the a x b element, in its local coordinates (0 ≤ x0 ≤ x1 ≤ a, 0 ≤ z0 ≤ z1 ≤ b):
/// f = p ∫ N_w dA, exact by 2 x 2 Gauss points on the part (N_w is bilinear).
pub fn pressure_load(a: f64, b: f64, part: [f64; 4], p: f64) -> Vec12 {
    let [x0, x1, z0, z1] = part;
    let mut f = Vec12::zeros();
    for &(s, ws) in &GAUSS2 {
        for &(t, wt) in &GAUSS2 {
            let (x, z) = (x0 + s * (x1 - x0), z0 + t * (z1 - z0));
            f += deflection(a, b, x / a, z / b) * (p * ws * wt * (x1 - x0) * (z1 - z0));
        }
    }
    f
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Nodal DOFs of a field given as (w, θ_x, θ_z) at (x, z).
    fn nodal(a: f64, b: f64, field: impl Fn(f64, f64) -> [f64; 3]) -> Vec12 {
        let mut d = Vec12::zeros();
        for (k, (e, f)) in NODES.into_iter().enumerate() {
            let v = field(e as f64 * a, f as f64 * b);
            for q in 0..3 {
                d[3 * k + q] = v[q];
            }
        }
        d
    }

    /// Exactly three zero-energy modes (rigid translation and two rotations), no spurious
    /// ones, on a long and a square element, thick and thin.
    #[test]
    fn three_rigid_modes_and_no_spurious_ones() {
        // Shear rigidities within a few decades of D/a², so that a zero eigenvalue stands
        // out from the thin plate's own small bending ones.
        for (a, b, shear) in [(0.3, 0.2, 1e5), (0.1, 0.1, 1e3), (0.05, 0.4, 1e7)] {
            let k = stiffness(a, b, 2.0e4, 0.3, shear);
            let mut ev: Vec<f64> = k.symmetric_eigenvalues().iter().copied().collect();
            ev.sort_by(f64::total_cmp);
            let scale = ev[11];
            assert!(ev[..3].iter().all(|v| v.abs() < 1e-11 * scale), "{a} x {b}: {ev:?}");
            assert!(ev[3] > 1e-9 * scale, "{a} x {b}: a fourth zero-energy mode, {ev:?}");
            // A rigid motion w = c₀ + c₁x + c₂z with θ = ∇w stores nothing.
            let rigid = nodal(a, b, |x, z| [0.3 + 2.0 * x - z, 2.0, -1.0]);
            assert!((rigid.dot(&(k * rigid))).abs() < 1e-11 * scale * rigid.norm_squared());
        }
    }

    /// A pure bending field w = ½(A x² + B z²) + C xz with θ = ∇w has no shear at the
    /// tying points, so its assumed shear vanishes everywhere and the element's energy is the
    /// bending energy alone, ½ κᵀD_bκ a b with the constant κ = (A, B, 2C), at any shear
    /// rigidity: the source of the absence of locking. The displacement shear as it stands
    /// does not vanish inside (w is bilinear, ∂w/∂x is not linear in x): that is the locking
    /// MITC removes.
    #[test]
    fn pure_bending_carries_no_shear_energy() {
        let (a, b, d, nu) = (0.4, 0.25, 3.0, 0.3);
        let (ca, cb, cc) = (1.5, -0.7, 0.4);
        let field =
            nodal(a, b, |x, z| [0.5 * (ca * x * x + cb * z * z) + cc * x * z, ca * x + cc * z, cb * z + cc * x]);
        let kappa = nalgebra::Vector3::new(ca, cb, 2.0 * cc);
        let exact = 0.5 * kappa.dot(&(crate::element::bending_matrix(d, nu) * kappa)) * a * b;
        for (xi, eta) in [(0.2, 0.3), (0.9, 0.1), (0.5, 0.5)] {
            assert!((assumed_shear(a, b, xi, eta) * field).norm() < 1e-15, "({xi}, {eta})");
        }
        assert!((displacement_shear(a, b, 0.2, 0.3) * field).norm() > 1e-3);
        // Energies of order 1 from entries of order `shear`: rounding of about 1e-16 · shear.
        for shear in [1.0, 1e3, 1e6] {
            let k = stiffness(a, b, d, nu, shear);
            assert_relative_eq!(0.5 * field.dot(&(k * field)), exact, max_relative = 1e-12 * shear.max(1.0));
        }
    }

    /// A constant shear state (w = γ₀ x, θ = 0) stores ½ k_s G h γ₀² a b.
    #[test]
    fn constant_shear_energy() {
        let (a, b, shear, g0) = (0.4, 0.25, 7.0e5, 1e-3);
        let field = nodal(a, b, |x, _| [g0 * x, 0.0, 0.0]);
        let k = stiffness(a, b, 3.0, 0.3, shear);
        assert_relative_eq!(0.5 * field.dot(&(k * field)), 0.5 * shear * g0 * g0 * a * b, max_relative = 1e-12);
    }

    /// The pressure load integrates to the force on the part, and its first moments are
    /// the force's: for a bilinear basis Σ f_w(node) x(node) = ∫ p x dA.
    #[test]
    fn pressure_load_has_the_force_and_its_moment() {
        let (a, b, p) = (0.4, 0.25, 2.0);
        let part = [0.1, 0.3, 0.05, 0.2];
        let f = pressure_load(a, b, part, p);
        let area = 0.2 * 0.15;
        let total: f64 = (0..4).map(|k| f[3 * k]).sum();
        assert_relative_eq!(total, p * area, max_relative = 1e-13);
        let moment: f64 = NODES.iter().enumerate().map(|(k, (e, _))| f[3 * k] * (*e as f64) * a).sum();
        assert_relative_eq!(moment, p * area * 0.2, max_relative = 1e-13);
        assert!((0..4).all(|k| f[3 * k + 1] == 0.0 && f[3 * k + 2] == 0.0));
    }
}
