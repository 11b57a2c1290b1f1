//! Closed forms the integration tests check the models against, written from the textbooks
//! and sharing no code with the crates under test: Hertz's contact on a rigid target, and a
//! Rayleigh bound on the fundamental frequency of a plate held at its four corners.

use std::f64::consts::PI;

/// A sphere (density, Young's modulus, Poisson's ratio, radius) in SI.
pub type Ball = (f64, f64, f64, f64);
/// A plate (length, width, thickness, Young's modulus, Poisson's ratio, density) in SI.
pub type Sheet = (f64, f64, f64, f64, f64, f64);

/// Table 1's coal sphere.
pub const COAL: Ball = (1380.0, 2.26e9, 0.28, 0.025);
/// Table 1's gangue 1 (coal's mass, gangue's material).
pub const GANGUE_1: Ball = (2400.0, 16e9, 0.28, 0.0207888);
/// Table 1's plate.
pub const PAPER_PLATE: Sheet = (0.4584, 0.36, 0.008, 210e9, 0.3, 7850.0);

/// Hertz's contact stiffness K = 4/3 √R E*, 1/E* = (1 - ν₁²)/E₁ + (1 - ν₂²)/E₂, of `ball` on
/// a half-space of `plate`'s material.
pub fn hertz_stiffness(ball: Ball, plate: Sheet) -> f64 {
    let e_star = 1.0 / ((1.0 - ball.2 * ball.2) / ball.1 + (1.0 - plate.4 * plate.4) / plate.3);
    4.0 / 3.0 * ball.3.sqrt() * e_star
}

/// Hertz's contact time of `ball` striking a rigid target of `plate`'s material at `v`:
/// 2.94328 δ_m/v with δ_m = (5mv²/4K)^{2/5} (Johnson, Contact Mechanics, §11.4).
pub fn hertz_time(ball: Ball, plate: Sheet, v: f64) -> f64 {
    let m = ball.0 * 4.0 / 3.0 * PI * ball.3.powi(3);
    let k = hertz_stiffness(ball, plate);
    2.94328 * (5.0 * m * v * v / (4.0 * k)).powf(0.4) / v
}

/// Rayleigh's quotient of a plate held at its four corners (w = 0 there, free edges) with the
/// trial shape w = sin(πx/L) + sin(πz/B), which vanishes at every corner: with a = π/L,
/// b = π/B, the strain energy gives D L B [(a⁴ + b⁴)/2 + 8ν a²b²/π²] and the kinetic
/// ρh L B (1 + 8/π²), so
/// ω_R² = D/(ρh) [(a⁴ + b⁴)/2 + 8ν a²b²/π²] / (1 + 8/π²).
/// Rayleigh's principle makes it an upper bound of the fundamental ω₁, so 2π/ω_R is a lower
/// bound of the period T₁.
pub fn rayleigh_corner_omega(plate: Sheet) -> f64 {
    let (l, b, h, e, nu, rho) = plate;
    let d = e * h.powi(3) / (12.0 * (1.0 - nu * nu));
    let (a2, b2) = ((PI / l).powi(2), (PI / b).powi(2));
    let pi2 = PI * PI;
    (d / (rho * h) * (0.5 * (a2 * a2 + b2 * b2) + 8.0 * nu * a2 * b2 / pi2) / (1.0 + 8.0 / pi2)).sqrt()
}

/// The upper bound t_c ω_R/2π of the quasi-static measure t_c/T₁ (t_c Hertz's time on a rigid
/// target, as the criterion defines it) for `ball` at `v` on the corner-held `plate`.
pub fn contact_over_period_bound(ball: Ball, plate: Sheet, v: f64) -> f64 {
    hertz_time(ball, plate, v) * rayleigh_corner_omega(plate) / (2.0 * PI)
}
