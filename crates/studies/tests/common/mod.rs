//! Independent references for the studies' tests, written here from the textbook formulas and
//! sharing no code with the crates under test: Hertz's contact stiffness, the energy balance
//! at maximum compression solved by bisection, the simply supported beam and Navier's double
//! series.

#![allow(dead_code)]

use std::f64::consts::PI;

/// Table 1 of the paper, as the tests use it (SI): the plate (L, B, h, E, ν), coal (ρ, E, ν, R),
/// the restitution e.
pub const PLATE: (f64, f64, f64, f64, f64) = (0.4584, 0.36, 0.008, 210e9, 0.3);
/// Coal: density, Young's modulus, Poisson's ratio, radius.
pub const COAL: (f64, f64, f64, f64) = (1380.0, 2.26e9, 0.28, 0.025);
/// Gangue 1 (the coal sphere's mass) and gangue 2 (its size).
pub const GANGUE_1: (f64, f64, f64, f64) = (2400.0, 16e9, 0.28, 0.0207888);
/// Gangue 2.
pub const GANGUE_2: (f64, f64, f64, f64) = (2400.0, 16e9, 0.28, 0.025);
/// The paper's coefficient of restitution.
pub const RESTITUTION: f64 = 0.65;

/// Hertz's contact stiffness K = 4/3 √R E* of a sphere (E₁, ν₁, R) on a half-space (E₂, ν₂),
/// 1/E* = (1 - ν₁²)/E₁ + (1 - ν₂²)/E₂, so that P = K δ^{3/2}.
pub fn hertz_stiffness(sphere: (f64, f64, f64, f64), plate: (f64, f64)) -> f64 {
    let (_, e1, nu1, r) = sphere;
    let (e2, nu2) = plate;
    let e_star = 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
    4.0 / 3.0 * r.sqrt() * e_star
}

/// The sphere's mass ρ 4/3 π R³.
pub fn mass(sphere: (f64, f64, f64, f64)) -> f64 {
    sphere.0 * 4.0 / 3.0 * PI * sphere.3.powi(3)
}

/// δ_max of the energy balance at maximum compression, ½mv² = (2K/5e) δ^{5/2} + ½ C K² δ³,
/// by bisection to the last bit: bracketed by 0 and the rigid plate's root
/// (5 e m v²/(4K))^{2/5}, which the plate's store can only lower.
pub fn delta_max(k: f64, c: f64, m: f64, e: f64, v: f64) -> f64 {
    let e0 = 0.5 * m * v * v;
    let demand = |d: f64| 2.0 * k / (5.0 * e) * d.powf(2.5) + 0.5 * c * k * k * d.powi(3);
    let (mut lo, mut hi) = (0.0f64, (5.0 * e * m * v * v / (4.0 * k)).powf(0.4) * (1.0 + 1e-12));
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if demand(mid) < e0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// P_max = K δ_max^{3/2} of a sphere on Table 1's plate with compliance `c` at velocity `v`.
pub fn contact_force(sphere: (f64, f64, f64, f64), c: f64, v: f64) -> f64 {
    let k = hertz_stiffness(sphere, (PLATE.3, PLATE.4));
    k * delta_max(k, c, mass(sphere), RESTITUTION, v).powf(1.5)
}

/// The simply supported Euler-Bernoulli beam's compliance at x: x²(L - x)²/(3 E I L), with
/// I = B h³/12 (Table 1's plate as the paper's beam).
pub fn beam_compliance(x: f64) -> f64 {
    let (l, b, h, e, _) = PLATE;
    let ei = e * b * h.powi(3) / 12.0;
    (x * (l - x)).powi(2) / (3.0 * ei * l)
}

/// Navier's double series for the deflection at (x, y) of the simply supported a x b plate of
/// rigidity D under a unit point load at the same point:
/// w = 4/(π⁴ a b D) Σ sin²(mπx/a) sin²(nπy/b) / ((m/a)² + (n/b)²)², over m, n ≤ `terms`.
pub fn navier(a: f64, b: f64, d: f64, (x, y): (f64, f64), terms: usize) -> f64 {
    let sy: Vec<f64> = (1..=terms).map(|n| (n as f64 * PI * y / b).sin().powi(2)).collect();
    let mut sum = 0.0;
    for m in 1..=terms {
        let sx = (m as f64 * PI * x / a).sin().powi(2);
        let mm = (m as f64 / a).powi(2);
        // Inner sums run from the small terms up, for accuracy.
        sum += (1..=terms).rev().map(|n| sx * sy[n - 1] / (mm + (n as f64 / b).powi(2)).powi(2)).sum::<f64>();
    }
    4.0 / (PI.powi(4) * a * b * d) * sum
}

/// The flexural rigidity E h³/(12(1 - ν²)).
pub fn rigidity(e: f64, nu: f64, h: f64) -> f64 {
    e * h.powi(3) / (12.0 * (1.0 - nu * nu))
}
