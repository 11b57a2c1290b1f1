//! Classical series solutions for a point load (Timoshenko & Woinowsky-Krieger, ch. 5-6).
//!
//! Lévy's method: with the edges x = 0 and x = a simply supported, expand
//! w = Σ_m Y_m(y) sin(α_m x), α_m = mπ/a. A point load P at (ξ, η) gives each harmonic the
//! line load q_m = (2P/a) sin(α_m ξ) at y = η, and
//!
//! ```text
//! D (Y'''' - 2α² Y'' + α⁴ Y) = q_m δ(y - η)
//! ```
//!
//! whose infinite-strip solution is G(s) = q_m/(4Dα³) (1 + α|s|) e^{-α|s|}, s = y - η. The
//! edges y = ±b/2 (simply supported, clamped or free) are met by adding four homogeneous
//! solutions, chosen to decay away from each edge so that no term overflows:
//! e^{α(y-b/2)}, α(y-b/2) e^{α(y-b/2)}, e^{-α(y+b/2)}, α(y+b/2) e^{-α(y+b/2)}.
//! With simply supported y-edges this is Navier's plate (its centre coefficient is
//! 0.01160 P a²/D for a square); with free y-edges, Lévy's plate strip.
//!
//! An elastically supported y-edge (a Winkler line spring of k per length) is a free edge
//! whose Kirchhoff shear meets the spring: M_y = 0 and D(w_yyy + (2 - ν) w_xxy) = ±k w at
//! y = ±b/2 (the natural boundary conditions of the energy with ½k∮w² added; Timoshenko &
//! Woinowsky-Krieger, §24 and §47 for the edge shear). It spans the free edge (k = 0) and
//! the simply supported one (k → ∞).

use nalgebra::{Matrix4, Vector4};

/// Boundary condition on the edges y = ±b/2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum YEdge {
    /// w = 0 and M_y = 0: Y = Y'' = 0.
    Simple,
    /// w = 0 and w_y = 0: Y = Y' = 0.
    Clamped,
    /// M_y = 0 and the Kirchhoff shear V_y = 0.
    Free,
    /// M_y = 0 and the Kirchhoff shear balancing a line spring of stiffness k per length
    /// (N/m², k ≥ 0): D(w_yyy + (2 - ν) w_xxy) = ±k w at y = ±b/2.
    Elastic(f64),
}

/// Y and its first three derivatives.
type Derivs = [f64; 4];

/// The infinite-strip Green's function (per unit q/(4Dα³)) and derivatives at s.
fn strip(alpha: f64, s: f64) -> Derivs {
    let t = s.abs();
    let e = (-alpha * t).exp();
    // The sign of s, with the sign of zero: a load on an edge lies just inside the plate,
    // so at the lower edge the strip is evaluated at s = -0 (see `harmonic`).
    let sign = if s.is_sign_negative() { -1.0 } else { 1.0 };
    let a2 = alpha * alpha;
    [(1.0 + alpha * t) * e, -sign * a2 * t * e, -a2 * (1.0 - alpha * t) * e, sign * a2 * alpha * (2.0 - alpha * t) * e]
}

/// The four homogeneous solutions and derivatives at y.
fn homogeneous(alpha: f64, b: f64, y: f64) -> [Derivs; 4] {
    let t = y - b / 2.0; // ≤ 0 inside
    let u = y + b / 2.0; // ≥ 0 inside
    let (et, eu) = ((alpha * t).exp(), (-alpha * u).exp());
    let (a, a2, a3) = (alpha, alpha * alpha, alpha * alpha * alpha);
    [
        [et, a * et, a2 * et, a3 * et],
        [a * t * et, a * (1.0 + a * t) * et, a2 * (2.0 + a * t) * et, a3 * (3.0 + a * t) * et],
        [eu, -a * eu, a2 * eu, -a3 * eu],
        [a * u * eu, a * (1.0 - a * u) * eu, a2 * (-2.0 + a * u) * eu, a3 * (3.0 - a * u) * eu],
    ]
}

/// The two boundary operators of an edge applied to Y, for a plate of rigidity `d` and an
/// edge whose outward normal is `outward` (+1 at y = b/2, -1 at y = -b/2).
fn edge_rows(kind: YEdge, alpha: f64, nu: f64, d: f64, outward: f64, y: &Derivs) -> [f64; 2] {
    let a2 = alpha * alpha;
    match kind {
        YEdge::Simple => [y[0], y[2]],
        YEdge::Clamped => [y[0], y[1]],
        // M_y ∝ Y'' - ν α² Y; V_y ∝ Y''' - (2 - ν) α² Y'.
        YEdge::Free => [y[2] - nu * a2 * y[0], y[3] - (2.0 - nu) * a2 * y[1]],
        // The shear carries the spring: Y''' - (2 - ν) α² Y' = ±(k/D) Y (w_xx = -α² w).
        YEdge::Elastic(k) => [y[2] - nu * a2 * y[0], y[3] - (2.0 - nu) * a2 * y[1] - outward * k / d * y[0]],
    }
}

/// Y_m(y) per unit q_m/(4Dα³) for the load line at η, edges `kind` at y = ±b/2, on a plate
/// of rigidity `d` and Poisson ratio `nu`.
fn harmonic(alpha: f64, b: f64, (d, nu): (f64, f64), kind: YEdge, eta: f64, y: f64) -> f64 {
    let edges = [b / 2.0, -b / 2.0];
    let mut m = Matrix4::zeros();
    let mut r = Vector4::zeros();
    for (e, &ye) in edges.iter().enumerate() {
        // A load on the edge itself is inside the plate: seen from the lower edge it lies
        // above (s = ye - η = -0), from the upper edge below (s = +0). Without this the
        // shear jump of the point load would fall outside the lower edge and cancel.
        let s = if ye == eta && ye < 0.0 { -0.0 } else { ye - eta };
        let g = strip(alpha, s);
        let outward = ye.signum();
        let rows_g = edge_rows(kind, alpha, nu, d, outward, &g);
        let h = homogeneous(alpha, b, ye);
        for k in 0..4 {
            let rows_h = edge_rows(kind, alpha, nu, d, outward, &h[k]);
            m[(2 * e, k)] = rows_h[0];
            m[(2 * e + 1, k)] = rows_h[1];
        }
        r[2 * e] = -rows_g[0];
        r[2 * e + 1] = -rows_g[1];
    }
    // Scale rows: the derivative orders differ by powers of α.
    for i in 0..4 {
        let s = m.row(i).iter().fold(0.0f64, |a, v| a.max(v.abs())).max(f64::MIN_POSITIVE);
        for k in 0..4 {
            m[(i, k)] /= s;
        }
        r[i] /= s;
    }
    let c = m.lu().solve(&r).unwrap_or_else(Vector4::zeros);
    let h = homogeneous(alpha, b, y);
    strip(alpha, y - eta)[0] + (0..4).map(|k| c[k] * h[k][0]).sum::<f64>()
}

/// A plate a x b, simply supported at x = 0 and x = a, with edges `y_edges` at y = ±b/2
/// (y measured from the centreline), of flexural rigidity `d` and Poisson ratio `nu`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevyPlate {
    /// Span a between the simply supported edges x = 0 and x = a (m).
    pub a: f64,
    /// Width b between the edges y = ±b/2 (m).
    pub b: f64,
    /// Flexural rigidity D = E h³ / 12(1 - ν²) (N·m).
    pub d: f64,
    /// Poisson's ratio ν (enters only through free and elastic edges).
    pub nu: f64,
    /// Condition on both edges y = ±b/2.
    pub y_edges: YEdge,
}

impl LevyPlate {
    /// Deflection (m/N) at `at` = (x, y) under a unit load at `load` = (ξ, η), summed over
    /// `terms` harmonics. The omitted tail is O(terms⁻²) at the load point.
    pub fn deflection(&self, load: (f64, f64), at: (f64, f64), terms: usize) -> f64 {
        let (xi, eta) = load;
        let (x, y) = at;
        let mut w = 0.0;
        for m in 1..=terms {
            let alpha = m as f64 * std::f64::consts::PI / self.a;
            let qm = 2.0 / self.a * (alpha * xi).sin();
            let sx = (alpha * x).sin();
            if qm == 0.0 || sx == 0.0 {
                continue;
            }
            w += qm / (4.0 * self.d * alpha.powi(3))
                * harmonic(alpha, self.b, (self.d, self.nu), self.y_edges, eta, y)
                * sx;
        }
        w
    }

    /// The series summed to convergence: partial sums at M and 2M harmonics extrapolated
    /// with the M⁻² tail, doubling M until two extrapolations agree to `rtol`.
    pub fn converged(&self, load: (f64, f64), at: (f64, f64), rtol: f64) -> f64 {
        let mut m = 200;
        let extrap = |m: usize| {
            let (w1, w2) = (self.deflection(load, at, m), self.deflection(load, at, 2 * m));
            (4.0 * w2 - w1) / 3.0
        };
        let mut prev = extrap(m);
        loop {
            m *= 2;
            let next = extrap(m);
            if (next - prev).abs() <= rtol * next.abs() || m > 200_000 {
                return next;
            }
            prev = next;
        }
    }
}

/// Shorthand for [`LevyPlate::converged`].
pub fn levy_converged(plate: LevyPlate, load: (f64, f64), at: (f64, f64), rtol: f64) -> f64 {
    plate.converged(load, at, rtol)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Timoshenko & Woinowsky-Krieger Table 23: square plate, simply supported, centre load:
    /// w = 0.01160 P a²/D (four digits).
    #[test]
    fn navier_square_centre_coefficient() {
        let w = levy_converged(
            LevyPlate { a: 1.0, b: 1.0, d: 1.0, nu: 0.3, y_edges: YEdge::Simple },
            (0.5, 0.0),
            (0.5, 0.0),
            1e-10,
        );
        assert_relative_eq!(w, 0.01160, max_relative = 5e-5 / 0.0116);
    }

    /// Independent check of the Lévy machinery: the Navier double series for a simply
    /// supported plate off-centre, summed directly (3000² terms, tail ~1e-7 relative).
    #[test]
    fn levy_simple_edges_equals_navier_double_series() {
        let (a, b) = (1.0, 0.7);
        let (xi, eta) = (0.3, 0.2); // from the corner
        let (x, y) = (0.6, 0.45);
        let n = 3000;
        let pi = std::f64::consts::PI;
        let sx: Vec<f64> = (1..=n).map(|m| (m as f64 * pi * xi / a).sin() * (m as f64 * pi * x / a).sin()).collect();
        let sy: Vec<f64> = (1..=n).map(|k| (k as f64 * pi * eta / b).sin() * (k as f64 * pi * y / b).sin()).collect();
        let mut w = 0.0;
        for m in 1..=n {
            for k in 1..=n {
                let den = ((m as f64 / a).powi(2) + (k as f64 / b).powi(2)).powi(2);
                w += sx[m - 1] * sy[k - 1] / den;
            }
        }
        w *= 4.0 / (pi.powi(4) * a * b);
        let levy = levy_converged(
            LevyPlate { a, b, d: 1.0, nu: 0.3, y_edges: YEdge::Simple },
            (xi, eta - b / 2.0),
            (x, y - b / 2.0),
            1e-10,
        );
        assert_relative_eq!(levy, w, max_relative = 1e-6);
    }

    /// An elastic y-edge spans the free and the simply supported edges: k = 0 is the free
    /// edge to rounding, and the deflection falls monotonically with k towards Navier's
    /// plate, its distance from it shrinking like 1/k (the edge deflection is the edge
    /// reaction over k).
    #[test]
    fn elastic_edges_span_free_and_simple() {
        let (a, b, d, nu) = (1.0, 0.6, 2.0, 0.3);
        let w = |y_edges| LevyPlate { a, b, d, nu, y_edges }.deflection((0.4, 0.1), (0.4, 0.1), 400);
        let free = w(YEdge::Free);
        assert_relative_eq!(w(YEdge::Elastic(0.0)), free, max_relative = 1e-14);
        let simple = w(YEdge::Simple);
        let mut last = free;
        let mut gaps = Vec::new();
        for e in 0..12 {
            let k = 10f64.powi(e) * d / b.powi(3);
            let wk = w(YEdge::Elastic(k));
            assert!(wk < last && wk > simple, "k = {k:e}: {wk:e} not in ({simple:e}, {last:e})");
            last = wk;
            gaps.push((wk - simple) * k);
        }
        // (w_k - w_simple) k tends to a constant: the first-order term in 1/k.
        let (g10, g11) = (gaps[10], gaps[11]);
        assert!((g11 / g10 - 1.0).abs() < 1e-3, "{gaps:?}");
        assert_relative_eq!(w(YEdge::Elastic(1e20)), simple, max_relative = 1e-12);
    }

    /// A long plate strip (b ≫ a) under a centre load approaches the infinite strip, whose
    /// centre deflection is Σ q_m/(4Dα³): P a²/(2π³D) Σ_{m odd} 1/m³ = P a²/(2π³D) · 7ζ(3)/8.
    #[test]
    fn wide_plate_tends_to_infinite_strip() {
        let zeta3 = 1.202_056_903_159_594_2;
        let exact = 1.0 / (2.0 * std::f64::consts::PI.powi(3)) * 7.0 * zeta3 / 8.0;
        for kind in [YEdge::Simple, YEdge::Free, YEdge::Clamped] {
            let w = levy_converged(
                LevyPlate { a: 1.0, b: 20.0, d: 1.0, nu: 0.3, y_edges: kind },
                (0.5, 0.0),
                (0.5, 0.0),
                1e-11,
            );
            assert_relative_eq!(w, exact, max_relative = 1e-8);
        }
    }
}
