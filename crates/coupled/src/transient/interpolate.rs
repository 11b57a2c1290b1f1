//! Quantities between the step ends, from the integrator's own interpolant.
//!
//! Newmark's average-acceleration rule takes the acceleration inside a step as the mean of
//! its end values, so within the step every displacement is the quadratic
//! x(τ) = x₀ + ẋ₀τ + ½ā τ², ā = (ẋ₁ - ẋ₀)/Δt, and every velocity is linear. This quadratic
//! also meets x₁, because the rule's displacement update is the trapezoid
//! x₁ - x₀ = Δt(ẋ₀ + ẋ₁)/2. The cubic Hermite interpolant on (x, ẋ) at the two ends has
//! cubic coefficient proportional to Δt(ẋ₀ + ẋ₁)/2 - (x₁ - x₀) = 0, so it is the same
//! quadratic: the two natural choices coincide. The compression δ = u - w_p is a
//! difference of two such quadratics and is one itself; its maximum inside a step is where
//! the linear δ̇ vanishes, τ* = Δt δ̇₀/(δ̇₀ - δ̇₁), with δ(τ*) = δ₀ + ½δ̇₀τ*.
//!
//! Energies are quadratic forms of the whole field, which the stepping does not keep from
//! step to step. The plate's total energy (kinetic, strain, springs) is interpolated by a
//! cubic Hermite polynomial on its end values and its rate P ẇ_p, the power of the contact
//! force (the only external force); the springs from the interpolated corner deflections
//! when their stiffnesses are known; the split between kinetic and strain energy linearly.

use super::{Sample, StepEnd, Striker};

/// Displacement on the quadratic interpolant, τ into the step.
pub fn quadratic(x0: f64, v0: f64, v1: f64, dt: f64, tau: f64) -> f64 {
    x0 + v0 * tau + 0.5 * (v1 - v0) / dt * tau * tau
}

/// Velocity on the interpolant (linear), τ into the step.
pub fn linear(v0: f64, v1: f64, dt: f64, tau: f64) -> f64 {
    v0 + (v1 - v0) * tau / dt
}

/// Cubic Hermite interpolation of a value with known end rates, τ into the step.
pub fn hermite(e0: f64, r0: f64, e1: f64, r1: f64, dt: f64, tau: f64) -> f64 {
    let s = tau / dt;
    let (s2, s3) = (s * s, s * s * s);
    (2.0 * s3 - 3.0 * s2 + 1.0) * e0 + (s3 - 2.0 * s2 + s) * dt * r0 + (-2.0 * s3 + 3.0 * s2) * e1 + (s3 - s2) * dt * r1
}

/// δ on the interpolant of the step from `a` to `b`, τ into it.
fn delta_at(a: &StepEnd, b: &StepEnd, dt: f64, tau: f64) -> f64 {
    quadratic(a.delta, a.rate, b.rate, dt, tau)
}

/// The time at which δ crosses zero inside the step from `a` to `b` (their δ differ in
/// sign or one is zero): bisection on the quadratic interpolant.
pub(super) fn crossing(a: &StepEnd, b: &StepEnd, dt: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, dt);
    let up = a.delta < b.delta;
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if (delta_at(a, b, dt, mid) <= 0.0) == up {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    a.t + 0.5 * (lo + hi)
}

/// The first contact's maxima on the interpolant.
pub(super) struct Maxima {
    pub force_max: f64,
    pub at_max: Sample,
    pub corners: [f64; 4],
}

/// The state at τ into the step from `a` to `b`.
fn state_at(s: &Striker, a: &StepEnd, b: &StepEnd, springs: Option<[f64; 4]>, dt: f64, tau: f64) -> (Sample, [f64; 4]) {
    let e0 = 0.5 * s.mass * s.velocity * s.velocity;
    let delta = delta_at(a, b, dt, tau);
    let rate = linear(a.rate, b.rate, dt, tau);
    let v = linear(a.v, b.v, dt, tau);
    let wp = quadratic(a.wp, a.vp, b.vp, dt, tau);
    let corners: [f64; 4] =
        std::array::from_fn(|i| quadratic(a.corners[i], a.corner_rates[i], b.corner_rates[i], dt, tau));
    let frac = tau / dt;
    let total = hermite(a.plate_energy(), a.force * a.vp, b.plate_energy(), b.force * b.vp, dt, tau);
    let spring_energy = match springs {
        Some(k) => (0..4).map(|i| 0.5 * k[i] * corners[i] * corners[i]).sum(),
        None => a.springs + frac * (b.springs - a.springs),
    };
    let kinetic = a.plate_kinetic + frac * (b.plate_kinetic - a.plate_kinetic);
    let strain = total - spring_energy - kinetic;
    // Within the first contact up to its maximum δ is the largest compression so far.
    let contact = s.stored_energy(delta, delta);
    let sphere_kinetic = 0.5 * s.mass * v * v;
    let sample = Sample {
        t: a.t + tau,
        force: s.force(delta, rate),
        compression: delta,
        sphere_velocity: v,
        plate_displacement: wp,
        sphere_kinetic,
        contact,
        plate_kinetic: kinetic,
        plate_strain: strain,
        springs: spring_energy,
        dissipated: e0 - (sphere_kinetic + contact + total),
    };
    (sample, corners)
}

/// Maximum compression (where δ̇ = 0 inside a step) and peak force (the maximum of the
/// Flores force on the interpolant next to the largest sampled force) over the step ends
/// `ends` of the first contact, `ends[0]` the touch at t = 0.
pub(super) fn first_contact(s: &Striker, ends: &[StepEnd], springs: Option<[f64; 4]>, dt: f64) -> Maxima {
    // Maximum compression: the largest δ(τ*) over the steps in which δ̇ turns negative.
    let mut best: Option<(usize, f64, f64)> = None;
    for (i, w) in ends.windows(2).enumerate() {
        let (a, b) = (&w[0], &w[1]);
        if a.rate > 0.0 && b.rate <= 0.0 {
            let tau = dt * a.rate / (a.rate - b.rate);
            let d = a.delta + 0.5 * a.rate * tau;
            if best.is_none_or(|(_, _, bd)| d > bd) {
                best = Some((i, tau, d));
            }
        }
    }
    let (at_max, corners) = match best {
        Some((i, tau, _)) => {
            let (mut smp, c) = state_at(s, &ends[i], &ends[i + 1], springs, dt, tau);
            // δ̇ = 0 here: the force is the elastic Kδ^{3/2} exactly.
            smp.force = s.force(smp.compression, 0.0);
            (smp, c)
        }
        None => {
            // No turning point in the window: the last step end is the largest δ reached.
            let last = ends.len() - 1;
            state_at(s, &ends[last.saturating_sub(1)], &ends[last], springs, dt, if last == 0 { 0.0 } else { dt })
        }
    };
    // Peak force: golden-section search on the two steps around the largest sampled force.
    let k = ends.iter().enumerate().max_by(|x, y| x.1.force.total_cmp(&y.1.force)).map_or(0, |(i, _)| i);
    let sampled = ends[k].force;
    let (lo_i, hi_i) = (k.saturating_sub(1), (k + 1).min(ends.len() - 1));
    let force_at = |t: f64| -> f64 {
        let j = (lo_i..hi_i).find(|&j| t <= ends[j + 1].t).unwrap_or(hi_i.saturating_sub(1).max(lo_i));
        if j + 1 >= ends.len() {
            return ends[j].force;
        }
        let (a, b) = (&ends[j], &ends[j + 1]);
        let tau = (t - a.t).clamp(0.0, dt);
        s.force(delta_at(a, b, dt, tau), linear(a.rate, b.rate, dt, tau))
    };
    let (mut lo, mut hi) = (ends[lo_i].t, ends[hi_i].t);
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let (mut x1, mut x2) = (hi - r * (hi - lo), lo + r * (hi - lo));
    let (mut f1, mut f2) = (force_at(x1), force_at(x2));
    for _ in 0..100 {
        if f1 < f2 {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + r * (hi - lo);
            f2 = force_at(x2);
        } else {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - r * (hi - lo);
            f1 = force_at(x1);
        }
    }
    Maxima { force_max: sampled.max(f1).max(f2), at_max, corners }
}
