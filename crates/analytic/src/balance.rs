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
    Recursion { tolerance: f64, max_iterations: u32 },
    /// Newton's method in u = √δ from a bracket, safeguarded by bisection.
    Bracketed { tolerance: f64, max_iterations: u32 },
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

/// The balance could not be solved to the requested tolerance.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("energy balance did not converge: residual {} after {} iterations", .0.residual, .0.iterations)]
pub struct NotConverged(pub Solution);

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

    /// Runs `method` and returns its last iterate, converged or not.
    pub fn attempt(&self, method: Method) -> Solution {
        match method {
            Method::Recursion { tolerance, max_iterations } => self.recursion(tolerance, max_iterations),
            Method::Bracketed { tolerance, max_iterations } => self.bracketed(tolerance, max_iterations),
        }
    }

    /// Solves by `method`; a result that missed its tolerance is an error carrying it.
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
    pub fn recursion(&self, tolerance: f64, max_iterations: u32) -> Solution {
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
    pub fn bracketed(&self, tolerance: f64, max_iterations: u32) -> Solution {
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
