//! Drucker-Prager onset of yield in the rock sphere and the yield velocity (section III).

use crate::material::Sphere;
use crate::response::Impact;
use serde::Serialize;

/// The Drucker-Prager constants of eq. 51 for a rock of friction angle φ, cohesion ζ and
/// Poisson's ratio μ₁.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DruckerPrager {
    /// k = 6ζ cos φ / (√3 (3 - sin φ)) (Pa). The paper prints k without ζ; without it
    /// δ_my would not be a length (design.md section 2).
    pub k: f64,
    /// α = 2 sin φ / (√3 (3 - sin φ)).
    pub alpha: f64,
    /// ε₀, the paper's cubic fit in α and μ₁.
    pub epsilon0: f64,
    /// Θ₁ = α(1 + μ₁)(1 - ε₀ tan⁻¹(1/ε₀)).
    pub theta1: f64,
    /// Θ₂ = -(1 + μ₁)(1 - ε₀ tan⁻¹(1/ε₀)) + (3/2)(1 + ε₀²)⁻¹.
    pub theta2: f64,
}

impl DruckerPrager {
    /// The constants of eq. 51 for `sphere`.
    pub fn of(sphere: &Sphere) -> Self {
        let phi = sphere.strength().friction_angle_deg().to_radians();
        let zeta = sphere.strength().cohesion();
        let mu = sphere.material().poisson_ratio();
        let (s, c) = phi.sin_cos();
        let sqrt3 = 3f64.sqrt();
        let k = 6.0 * zeta * c / (sqrt3 * (3.0 - s));
        let a = 2.0 * s / (sqrt3 * (3.0 - s));
        let epsilon0 =
            0.3824 - 1.181 * a + 0.3307 * mu + 0.4646 * a * a - 1.083 * a * mu - 0.007665 * mu * mu - 3.35 * a.powi(3)
                + 0.2447 * a * a * mu
                - 0.05763 * a * mu * mu
                + 0.0101 * mu.powi(3);
        let g = (1.0 + mu) * (1.0 - epsilon0 * (1.0 / epsilon0).atan());
        Self { k, alpha: a, epsilon0, theta1: a * g, theta2: -g + 1.5 / (1.0 + epsilon0 * epsilon0) }
    }

    /// Critical compression at first yield, δ_my = [2πRk / (K(6Θ₁ + √3Θ₂))]² (eq. 51).
    pub fn yield_compression(&self, radius: f64, contact_stiffness: f64) -> f64 {
        let q = 2.0 * std::f64::consts::PI * radius * self.k
            / (contact_stiffness * (6.0 * self.theta1 + 3f64.sqrt() * self.theta2));
        q * q
    }
}

/// Yield velocity v_y = √((2/m)[(2K/5e)δ_my^{5/2} + ½CK²δ_my³]) (eqs. 52-54) for a plate of
/// total compliance `c`: the impact velocity whose maximum compression is δ_my.
pub fn yield_velocity(sphere: &Sphere, impact: &Impact, c: f64, delta_my: f64) -> f64 {
    let bal = impact.balance(c);
    (2.0 * bal.demand(delta_my) / sphere.mass()).sqrt()
}
