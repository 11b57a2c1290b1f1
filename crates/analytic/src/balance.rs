//! The energy balance at maximum compression and its two solvers.
//!
//! At maximum compression the sphere is at rest and the Flores damping term vanishes, so
//! the contact force is P = K δ^{3/2} and every support condition reduces to
//!
//! ```text
//! ½ m v² = (2K/5e) δ^{5/2} + ½ C K² δ³          (eqs. 14, 25, 46)
//! ```
//!
//! with C the total compliance of the supported plate at the impact point. Write
//! a = 2K/5e, b = ½CK², E₀ = ½mv²; the demand f(δ) = aδ^{5/2} + bδ³ is strictly increasing,
//! so the root is unique.
//!
//! # Example
//!
//! The paper's coal sphere (R = 25 mm, ρ = 1380 kg/m³, E₁ = 2.26 GPa, μ₁ = 0.28) striking a
//! rigid plate (C = 0) at 8 mm/s with e = 0.65: the balance reduces to
//! ½mv² = (2K/5e)δ^{5/2}, so δ_max = (5e m v²/4K)^{2/5}.
//!
//! ```
//! use analytic::{contact_stiffness, Elastic, EnergyBalance, Impact, Method, RockStrength, Sphere};
//!
//! let coal = Sphere::new(
//!     "coal",
//!     1380.0,
//!     0.025,
//!     Elastic::new(2.26e9, 0.28)?,
//!     RockStrength::new(8.39e6, 25.0)?,
//! )?;
//! let steel = Elastic::new(210e9, 0.3)?;
//! let k = contact_stiffness(&coal, steel); // K = 5.11545e8 N/m^{3/2} (section IV)
//! assert!((k / 5.11545e8 - 1.0).abs() < 1e-5);
//!
//! let (e, v) = (0.65, 0.008);
//! let impact = Impact::new(k, coal.mass(), e, v)?;
//! let rigid = impact.balance(0.0); // C = 0: no plate store
//! for method in [Method::paper(), Method::default()] {
//!     let delta = rigid.solve(method)?.delta;
//!     let closed_form = (5.0 * e * coal.mass() * v * v / (4.0 * k)).powf(0.4);
//!     assert!((delta / closed_form - 1.0).abs() < 1e-11, "{delta} vs {closed_form}");
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use serde::Serialize;

/// The scalar balance a δ^{5/2} + b δ³ = E₀.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EnergyBalance {
    /// 2K/5e (N/m^{3/2}): rock energy per δ^{5/2} (eq. 7).
    pub a: f64,
    /// ½ C K² (N/m²): plate and spring energy per δ³ (eqs. 12, 23, 42-44).
    pub b: f64,
    /// ½ m v² (J).
    pub e0: f64,
}

/// How to solve the balance.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "method", rename_all = "kebab-case")]
pub enum Method {
    /// The paper's recursion (eqs. 15-19), stopped when the relative residual ğ of eq. 18
    /// falls to `tolerance`.
    Recursion {
        /// Largest accepted relative residual ğ = |f(δ) - E₀|/E₀ (eq. 18).
        tolerance: f64,
        /// Largest number of recursion steps N.
        max_iterations: u32,
    },
    /// Newton's method in u = √δ from a bracket, safeguarded by bisection.
    Bracketed {
        /// Largest accepted relative residual |f(δ) - E₀|/E₀.
        tolerance: f64,
        /// Largest number of Newton or bisection steps.
        max_iterations: u32,
    },
}

impl Default for Method {
    fn default() -> Self {
        Self::Bracketed { tolerance: 1e-14, max_iterations: 100 }
    }
}

impl Method {
    /// The paper's recursion with the stopping residual ğ = 1e-12.
    pub fn paper() -> Self {
        Self::Recursion { tolerance: 1e-12, max_iterations: 200 }
    }
}

/// The root δ_max with the evidence of how it was found.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Solution {
    /// Maximum compression δ_max (m).
    pub delta: f64,
    /// Iterations taken (N of eq. 18).
    pub iterations: u32,
    /// |f(δ) - E₀| / E₀ at the returned δ, the ğ of eq. 18.
    pub residual: f64,
    /// Whether the residual met the tolerance within the allowed iterations.
    pub converged: bool,
}

/// The balance could not be solved to the requested tolerance, or was not posed (E₀ or a
/// not positive and finite, b negative or not finite), in which case no iteration was
/// taken and the residual is infinite.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}", not_converged_message(.0))]
pub struct NotConverged(pub Solution);

fn not_converged_message(s: &Solution) -> String {
    if s.iterations == 0 && s.residual.is_infinite() {
        "energy balance not posed: it needs E₀ = ½mv² > 0, 2K/5e > 0 and ½CK² >= 0, all finite \
         (check the velocity, mass, contact stiffness, restitution and compliance)"
            .to_string()
    } else {
        format!("energy balance did not converge: residual {} after {} iterations", s.residual, s.iterations)
    }
}

/// What a solver returns for a balance that is not posed: no root to look for (E₀ = 0 has
/// the trivial δ = 0, where the relative residual 0/0 is undefined), so no iteration and
/// an infinite residual instead of a NaN one.
const NOT_POSED: Solution = Solution { delta: 0.0, iterations: 0, residual: f64::INFINITY, converged: false };

impl EnergyBalance {
    /// The balance for contact stiffness `k`, restitution `e`, total compliance `c`, sphere
    /// mass `m` and impact velocity `v`.
    pub fn new(k: f64, e: f64, c: f64, m: f64, v: f64) -> Self {
        Self { a: 2.0 * k / (5.0 * e), b: 0.5 * c * k * k, e0: 0.5 * m * v * v }
    }

    /// Energy needed to reach compression δ: f(δ) = aδ^{5/2} + bδ³ (right side of eq. 14).
    pub fn demand(&self, delta: f64) -> f64 {
        let u = delta.sqrt();
        let u5 = u * u * u * u * u;
        u5 * (self.a + self.b * u)
    }

    /// The relative residual |f(δ) - E₀|/E₀ of eq. 18.
    pub fn relative_residual(&self, delta: f64) -> f64 {
        ((self.demand(delta) - self.e0) / self.e0).abs()
    }

    /// One step of the paper's recursion, δ ← {E₀ / [a + b δ^{1/2}]}^{2/5} (eqs. 15-17).
    pub fn recursion_step(&self, delta: f64) -> f64 {
        (self.e0 / (self.a + self.b * delta.sqrt())).powf(0.4)
    }

    /// Whether the balance has one positive root that the solvers can find: E₀ > 0 and
    /// a > 0 finite, b ≥ 0 finite.
    pub fn is_posed(&self) -> bool {
        let positive = |v: f64| v.is_finite() && v > 0.0;
        positive(self.e0) && positive(self.a) && self.b.is_finite() && self.b >= 0.0
    }

    /// Runs `method` and returns its last iterate, converged or not.
    pub fn attempt(&self, method: Method) -> Solution {
        match method {
            Method::Recursion { tolerance, max_iterations } => self.recursion(tolerance, max_iterations),
            Method::Bracketed { tolerance, max_iterations } => self.bracketed(tolerance, max_iterations),
        }
    }

    /// Solves by `method`; a result that missed its tolerance, or a balance that is not
    /// posed (see [`is_posed`](Self::is_posed)), is an error carrying the last iterate.
    pub fn solve(&self, method: Method) -> Result<Solution, NotConverged> {
        let s = self.attempt(method);
        if s.converged {
            Ok(s)
        } else {
            Err(NotConverged(s))
        }
    }

    /// The paper's recursion from δ₀ = 0 (eqs. 16-19).
    ///
    /// The map g(δ) = {E₀/[a + bδ^{1/2}]}^{2/5} is decreasing with |g'(δ*)| =
    /// ⅕ bδ*^{1/2}/(a + bδ*^{1/2}) < ⅕ at the root, so the iterates alternate around δ*
    /// and the error falls by at least 5x per step, for every valid input.
    ///
    /// A balance that is not posed returns without iterating, unconverged.
    pub fn recursion(&self, tolerance: f64, max_iterations: u32) -> Solution {
        if !self.is_posed() {
            return NOT_POSED;
        }
        let mut delta = 0.0;
        let mut residual = f64::INFINITY;
        let mut n = 0;
        while n < max_iterations {
            let next = self.recursion_step(delta);
            n += 1;
            residual = self.relative_residual(next);
            // Stalling in the last bits of f64 is the attainable accuracy, not divergence.
            let stalled = next == delta;
            delta = next;
            if residual <= tolerance || stalled {
                break;
            }
        }
        Solution { delta, iterations: n, residual, converged: residual <= tolerance }
    }

    /// Newton's method on F(u) = a u⁵ + b u⁶ - E₀ with u = √δ, kept inside a bracket.
    ///
    /// With u_a = (E₀/a)^{1/5} and u_b = (E₀/b)^{1/6}, the root lies in
    /// [min(2^{-1/5}u_a, 2^{-1/6}u_b), min(u_a, u_b)]: each term alone cannot exceed E₀, and
    /// at the lower end each is at most E₀/2. F is convex and increasing for u > 0, so
    /// Newton from the upper end decreases monotonically to the root; bisection guards
    /// against rounding. Convergence is quadratic.
    ///
    /// A balance that is not posed returns without iterating, unconverged.
    pub fn bracketed(&self, tolerance: f64, max_iterations: u32) -> Solution {
        if !self.is_posed() {
            return NOT_POSED;
        }
        let ua = (self.e0 / self.a).powf(0.2);
        let ub = if self.b > 0.0 { (self.e0 / self.b).powf(1.0 / 6.0) } else { f64::INFINITY };
        let mut hi = ua.min(ub);
        let mut lo = (ua * 2f64.powf(-0.2)).min(ub * 2f64.powf(-1.0 / 6.0));
        let f = |u: f64| {
            let u4 = u * u * u * u;
            (u4 * u * (self.a + self.b * u) - self.e0, u4 * (5.0 * self.a + 6.0 * self.b * u))
        };
        let mut u = hi;
        let mut n = 0;
        let mut residual = (f(u).0 / self.e0).abs();
        while residual > tolerance && n < max_iterations {
            n += 1;
            let (fu, dfu) = f(u);
            if fu > 0.0 {
                hi = u;
            } else {
                lo = u;
            }
            let newton = u - fu / dfu;
            let next = if newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
            if next == u {
                break;
            }
            u = next;
            residual = (f(u).0 / self.e0).abs();
        }
        Solution { delta: u * u, iterations: n, residual, converged: residual <= tolerance }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// b = 0 (rigid support) has the closed form δ = (E₀/a)^{2/5}.
    #[test]
    fn rigid_support_closed_form() {
        let bal = EnergyBalance { a: 3.0e8, b: 0.0, e0: 2.9e-6 };
        let exact = (bal.e0 / bal.a).powf(0.4);
        for m in [Method::paper(), Method::default()] {
            assert_relative_eq!(bal.solve(m).unwrap().delta, exact, max_relative = 1e-14);
        }
    }

    /// a → 0 (negligible rock) has the closed form δ = (E₀/b)^{1/3}.
    #[test]
    fn compliance_dominated_closed_form() {
        let bal = EnergyBalance { a: 1e-30, b: 1e10, e0: 1.0 };
        let exact = (bal.e0 / bal.b).powf(1.0 / 3.0);
        assert_relative_eq!(bal.solve(Method::default()).unwrap().delta, exact, max_relative = 1e-12);
        assert_relative_eq!(bal.solve(Method::paper()).unwrap().delta, exact, max_relative = 1e-12);
    }

    /// E₀ = 0 (v = 0) has no positive root: both solvers refuse it, with an infinite residual
    /// in the evidence instead of a NaN one, and say why.
    #[test]
    fn zero_energy_is_not_converged_not_nan() {
        for bal in [
            EnergyBalance::new(5.11545e8, 0.65, 1e-7, 0.09, 0.0),
            EnergyBalance { a: 0.0, b: 1.0, e0: 1.0 },
            EnergyBalance { a: 1.0, b: f64::NAN, e0: 1.0 },
        ] {
            for m in [Method::paper(), Method::default()] {
                let e = bal.solve(m).unwrap_err();
                assert!(!e.0.converged && e.0.residual == f64::INFINITY && e.0.delta == 0.0, "{e:?}");
                assert!(e.to_string().contains("not posed"), "{e}");
            }
        }
    }

    /// The recursion gains at least log10(5) = 0.7 digits per step: ğ = 1e-12 in <= 25
    /// steps whatever the split between rock and plate.
    #[test]
    fn recursion_contracts_at_least_fivefold() {
        for ratio in [1e-12, 1e-6, 1.0, 1e6, 1e12] {
            let bal = EnergyBalance { a: 1.0, b: ratio, e0: 1.0 };
            let s = bal.solve(Method::paper()).unwrap();
            assert!(s.iterations <= 25, "ratio {ratio}: {} iterations", s.iterations);
        }
    }
}
