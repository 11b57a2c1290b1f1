//! The contact between sphere and plate in the transient model: the striker's contact law
//! ([`super::law`]: Flores, eqs. 1-2, by default) and its solution within one Newmark step.
//!
//! Within a step the plate's point displacement and velocity are affine in the step-end
//! force P, and so is the sphere's, so the compression δ and its rate δ̇ at the end of the
//! step are δ(P) = δ̂ - (Δt²/4m + g)P and δ̇(P) = δ̇̂ - (Δt/2m + 2g/Δt)P. The contact law then
//! reduces to one scalar equation h(P) = P - F(δ(P), δ̇(P)) = 0, e.g. F = max(0, Kδ^{3/2}(1 +
//! 8(1-e)/(5e) δ̇/v₀)) for Flores; every law's F is nondecreasing in δ and (Flores) in δ̇,
//! both of which fall as P grows, so h is increasing and the root in [0, F(δ̂, δ̇̂)] is
//! unique; it is found by safeguarded secant steps. A history-dependent law (Thornton's)
//! enters with the largest compression before the step: within the step it is loading if
//! δ(P) exceeds it and unloading otherwise, one continuous nondecreasing F either way.

use super::law::{ContactLaw, ContactState};
use serde::Serialize;

/// The Hertz time constant 2 · 0.4 B(2/5, 1/2) · (5/4)^{2/5} = 3.21800, from
/// Γ(0.4) = 2.218159543757688, Γ(0.5) = √π, Γ(0.9) = 1.068628702119319. design.md (and some
/// texts) round it to 3.2145, which is 0.11 % low; the simulation confirms 3.2180.
pub const HERTZ_TIME: f64 = {
    let integral = 0.4 * 2.218_159_543_757_688 * 1.772_453_850_905_516 / 1.068_628_702_119_319;
    // (5/4)^{2/5} = 1.0933620739432781 (no const powf).
    2.0 * integral * 1.093_362_073_943_278_1
};

/// The sphere and the contact law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Striker {
    /// Contact stiffness K (eq. 3), N/m^{3/2}.
    pub k: f64,
    /// Restitution e of the Flores law.
    pub restitution: f64,
    /// Sphere mass, kg.
    pub mass: f64,
    /// Impact velocity v₀ > 0, m/s.
    pub velocity: f64,
    /// The contact law (Flores by default).
    pub law: ContactLaw,
    /// The body force on the sphere per unit mass toward the plate, m/s²: gravity's
    /// component normal to the plate for a lump falling onto it, 0 for the paper's impact
    /// (which has none). With it the free sphere flies on a parabola and comes back.
    pub gravity: f64,
}

impl Striker {
    /// Hertz contact time on a rigid target (e = 1): t_c = 2 (δ_max/v₀) ∫₀¹ dx/√(1 - x^{5/2})
    /// with δ_max = (5mv₀²/4K)^{2/5}, i.e. t_c = [HERTZ_TIME] (m²/(K² v₀))^{1/5}.
    pub fn hertz_time(&self) -> f64 {
        HERTZ_TIME * (self.mass * self.mass / (self.k * self.k * self.velocity)).powf(0.2)
    }
    /// Hertz maximum force on a rigid target, K δ_max^{3/2} with δ_max = (5mv²/4K)^{2/5}.
    pub fn hertz_force(&self) -> f64 {
        self.k * (5.0 * self.mass * self.velocity.powi(2) / (4.0 * self.k)).powf(0.6)
    }
    /// The law's force at compression δ and rate δ̇ with δ the largest compression so far
    /// (a plastic law on its loading branch), never negative (no adhesion).
    pub fn force(&self, delta: f64, rate: f64) -> f64 {
        self.force_after(delta, rate, delta)
    }
    /// The force at maximum compression δ_max, where δ̇ = 0: the law's own force there on its
    /// loading branch (Kδ^{3/2} for Hertz and Flores, whose damping vanishes with δ̇;
    /// Thornton's plastic branch beyond its yield compression). The paper's P_max (eq. 20).
    pub fn force_at_max_compression(&self, delta: f64) -> f64 {
        self.force(delta.max(0.0), 0.0)
    }
    /// What the law sees of this striker after a largest compression `dmax` so far.
    #[inline]
    pub fn state(&self, dmax: f64) -> ContactState {
        ContactState { k: self.k, restitution: self.restitution, velocity: self.velocity, max_compression: dmax }
    }
    /// What the law sees in a contact that began at approach velocity `approach` (δ̇ at
    /// its onset: v₀ for the first contact, the relative velocity at touch for a later one),
    /// after a largest compression `dmax` so far.
    #[inline]
    pub fn state_in(&self, dmax: f64, approach: f64) -> ContactState {
        ContactState { velocity: approach, ..self.state(dmax) }
    }
    /// The law's force at δ, δ̇ after a largest compression `dmax` so far, in the first
    /// contact (approach velocity v₀).
    #[inline]
    pub fn force_after(&self, delta: f64, rate: f64, dmax: f64) -> f64 {
        self.law.force(&self.state(dmax), delta, rate)
    }
    /// The elastic energy in the contact at δ after a largest compression `dmax`.
    #[inline]
    pub fn stored_energy(&self, delta: f64, dmax: f64) -> f64 {
        self.law.stored_energy(&self.state(dmax), delta)
    }
    /// The permanent compression after a largest compression `dmax` (zero if elastic).
    #[inline]
    pub fn permanent_set(&self, dmax: f64) -> f64 {
        self.law.permanent_set(&self.state(dmax))
    }
    /// Whether the law stores all the work done on it whatever the compression (Hertz,
    /// Flores at e ≥ 1), so that the run's energy error is measured.
    pub fn conserves(&self) -> bool {
        self.law.conserves(&self.state(0.0))
    }
}

/// Solves h(P) = P - F(δ(P), δ̇(P)) = 0 for P ≥ 0 (h increasing): Illinois false position
/// on the bracket [0, F(δ̂, δ̇̂)], for a contact never compressed before.
pub fn contact_force(s: &Striker, d0: f64, d1: f64, r0: f64, r1: f64) -> f64 {
    contact_force_after(s, &s.state(0.0), d0, d1, r0, r1)
}

/// As [`contact_force`] in the contact `c` (its largest compression in earlier steps and its
/// approach velocity, [`Striker::state_in`]).
pub fn contact_force_after(s: &Striker, c: &ContactState, d0: f64, d1: f64, r0: f64, r1: f64) -> f64 {
    let f = |p: f64| s.law.force(c, d0 - d1 * p, r0 - r1 * p);
    let hi0 = f(0.0);
    if hi0 <= 0.0 {
        return 0.0;
    }
    let h = |p: f64| p - f(p);
    let (mut a, mut b) = (0.0, hi0);
    let (mut ha, mut hb) = (h(a), h(b));
    if hb <= 0.0 {
        return b;
    }
    let mut side = 0;
    for _ in 0..200 {
        let c = (a * hb - b * ha) / (hb - ha);
        let hc = h(c);
        if hc.abs() <= 1e-15 * hi0 || (b - a) <= 1e-15 * hi0 {
            return c;
        }
        if hc < 0.0 {
            a = c;
            ha = hc;
            if side == -1 {
                hb *= 0.5;
            }
            side = -1;
        } else {
            b = c;
            hb = hc;
            if side == 1 {
                ha *= 0.5;
            }
            side = 1;
        }
    }
    0.5 * (a + b)
}
