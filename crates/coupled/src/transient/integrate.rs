//! The time integration of one impact (module docs of [`super`]): each step the sphere's
//! and the plate's Newmark predictions, the contact force solved at the step's end, the
//! energy bookkeeping; over the steps the contact sequence, the first contact's record and
//! the stopping rule.

use super::contact::contact_force_after;
use super::{interpolate, separated, Contact, Outcome, PlateFacts, Sample, StepEnd, Striker, Target};
use plate_fem::dynamics::Newmark;

/// Integrates the impact of `s` on `plate` (or a rigid target when None) with step `dt` up
/// to `t_max`. The plate's static compliance is unknown here, so nothing proves a later
/// contact impossible short of integrating to `t_max`: the run stops at the first
/// separation (`left_at` None, `contacts` the first contact only) unless the target is
/// rigid, where it has provably ended. [`simulate_with`] follows the whole sequence.
pub fn simulate(s: &Striker, plate: Option<&mut Newmark<'_>>, dt: f64, t_max: f64) -> Outcome {
    simulate_with(s, plate, PlateFacts::default(), dt, t_max)
}

/// Integrates the impact of `s` on `plate` (or a rigid target when None) with step `dt`,
/// and follows it until the sphere has left for good or `t_max`.
///
/// Every step is the same: the contact force solves the Flores law at the end of the step
/// ([`contact::contact_force`](super::contact::contact_force)); it is zero while the
/// predicted compression is negative, so after a separation the plate vibrates freely, the
/// sphere flies on ballistically (no gravity) and a later contact is found by the same
/// solve. A contact begins when the force
/// becomes positive and ends when δ crosses zero with zero force ([`separated`]).
///
/// **Stopping rule.** After a separation the plate moves freely, and its energy
/// E_p = ½ẇᵀMẇ + ½wᵀKw (kinetic, strain and springs) is constant: exactly so for the FE
/// model, and exactly so at the step ends for Newmark's average-acceleration rule, which
/// conserves this quadratic energy of a linear system. By Cauchy-Schwarz in the K inner
/// product the point deflection w_p = Nᵀw obeys |w_p| ≤ √(wᵀKw · NᵀK⁻¹N) ≤ √(2E_p C_p) = W
/// for all later time, C_p the static compliance at the point. The sphere's displacement u
/// (toward the plate, from the first touch) is linear in time once free. Contact needs
/// δ = u - w_p > δ_p, the permanent set of the largest compression so far (0 for the elastic
/// laws; a yielded lump unloads to δ_p and reloads along its elastic branch from there), so
/// once u - δ_p < -W with u̇ ≤ 0 no contact can ever occur again: the run stops there. A rigid target has W = 0, so it stops at the first separation. Without C_p
/// the run stops at the first separation or, with [`PlateFacts::follow_unbounded`], follows
/// the free motion to `t_max`; either way [`Outcome::left_at`] is None. A target that knows a
/// tighter bound on its later free motion gives it by [`Target::free_reach`] (the modal
/// plate does: Σᵢ|φᵢ(p)| times each mode's amplitude), and the smaller bound is used.
///
/// The first-contact fields of [`Outcome`] (and its `history`) are exactly those of a run
/// that stops at the first separation; the later samples go to `later_history`.
pub fn simulate_with<T: Target + ?Sized>(
    s: &Striker,
    mut plate: Option<&mut T>,
    facts: PlateFacts,
    dt: f64,
    t_max: f64,
) -> Outcome {
    let e0 = 0.5 * s.mass * s.velocity * s.velocity;
    let g = plate.as_ref().map_or(0.0, |p| p.point_flexibility());
    // At the touch no force acts yet: the sphere accelerates at g alone.
    let mut sphere = SphereState { u: 0.0, v: s.velocity, a: s.gravity, dmax: 0.0, approach: s.velocity };
    // Room for the steps of about two rigid-target contact times, so that the histories of
    // a first contact seldom grow by copying.
    let expected = (2.0 * s.hertz_time() / dt).clamp(16.0, 4096.0) as usize;
    let mut first = FirstContact::new(s, expected);
    let mut later = Later {
        history: Vec::with_capacity(expected),
        max_energy_error: 0.0,
        left_at: None,
        returns_at: None,
        steps: 0,
    };
    let mut sequence = Sequence { gravity: s.gravity, ..Sequence::default() };
    let mut prev = first.ends[0];
    let mut t = 0.0;
    let conserves = s.conserves();
    while t < t_max {
        t += dt;
        later.steps += 1;
        let (end, sample, stored) = step(s, plate.as_deref_mut(), &mut sphere, &prev, (g, dt, t));
        let set = s.permanent_set(sphere.dmax);
        let energy_error = conserves.then(|| (stored - e0).abs() / e0);
        if let Some(err) = energy_error {
            later.max_energy_error = later.max_energy_error.max(err);
        }
        sequence.advance(&prev, &end, set, dt);
        if first.done {
            later.history.push(sample);
        } else {
            first.record(sample, end, set, energy_error, (later.steps, dt));
        }
        prev = end;
        if first.done && sequence.current.is_none() {
            // A contact opens at δ = δ_p, the permanent set: the sphere's reach is u - δ_p.
            match stopping_rule(plate.as_deref(), &facts, &end, sphere.u - set, (s.gravity, t_max - t)) {
                Verdict::Left(returns) => {
                    later.left_at = Some(t);
                    later.returns_at = returns.map(|tau| t + tau);
                    break;
                }
                Verdict::Stop => break,
                Verdict::Continue => {}
            }
        }
    }
    outcome(s, first, sequence, later, (sphere.v, facts.corner_springs, dt))
}

/// The sphere under Newmark's average-acceleration rule, and the largest compression so far
/// (with the permanent set it leaves, a plastic contact opens at δ = δ_p, not at δ = 0, so
/// the contact sequence is followed on δ - δ_p; δ_p = 0 for the elastic laws).
struct SphereState {
    /// Displacement toward the plate from the first touch, m.
    u: f64,
    /// Velocity toward the plate, m/s.
    v: f64,
    /// Acceleration, m/s².
    a: f64,
    /// Largest compression so far, m.
    dmax: f64,
    /// The approach velocity δ̇⁻ of the current (or last) contact, m/s: the scale of the
    /// Flores damping, which Flores et al. define per contact as the relative normal
    /// velocity at its onset (v₀ for the first).
    approach: f64,
}

/// One step of `dt` ending at `t`: both bodies predicted, the contact force solved at the
/// step's end with the plate's point flexibility `g` (δ and δ̇ are linear in the force,
/// δ = d₀ - d₁P, δ̇ = r₀ - r₁P), both committed; the step end with its sample and the sum of
/// the stores.
fn step<T: Target + ?Sized>(
    s: &Striker,
    mut plate: Option<&mut T>,
    sphere: &mut SphereState,
    prev: &StepEnd,
    (g, dt, t): (f64, f64, f64),
) -> (StepEnd, Sample, f64) {
    let m = s.mass;
    let (wp, vp) = plate.as_mut().map_or((0.0, 0.0), |p| p.predict());
    let SphereState { u, v, a, dmax, .. } = *sphere;
    let (mut u_hat, mut v_hat) = (u + dt * v + 0.25 * dt * dt * a, v + 0.5 * dt * a);
    // The end-of-step acceleration is g - P/m: its known part g enters the force-free
    // prediction (skipped at g = 0, so that the paper's impact is unchanged to the bit).
    if s.gravity != 0.0 {
        u_hat += 0.25 * dt * dt * s.gravity;
        v_hat += 0.5 * dt * s.gravity;
    }
    let (d0, d1) = (u_hat - wp, 0.25 * dt * dt / m + g);
    let (r0, r1) = (v_hat - vp, 0.5 * dt / m + 2.0 * g / dt);
    if prev.force == 0.0 {
        sphere.approach =
            approach_velocity(s.permanent_set(dmax), (prev.delta, prev.rate), d0, r0).unwrap_or(sphere.approach);
    }
    let approach = sphere.approach;
    let p = contact_force_after(s, &s.state_in(dmax, approach), d0, d1, r0, r1);
    // The contact's part of the step-end acceleration; gravity's is in the prediction.
    let a_contact = -p / m;
    sphere.u = u_hat + 0.25 * dt * dt * a_contact;
    sphere.v = v_hat + 0.5 * dt * a_contact;
    sphere.a = if s.gravity != 0.0 { s.gravity + a_contact } else { a_contact };
    if let Some(pl) = plate.as_mut() {
        pl.commit(p);
    }
    let delta = d0 - d1 * p;
    let rate = r0 - r1 * p;
    sphere.dmax = dmax.max(delta);
    let (sample, stored) = energies(s, plate.as_deref(), t, p, (delta, sphere.dmax), (sphere.u, sphere.v));
    let (wp_now, vp_now) = plate.as_ref().map_or((0.0, 0.0), |p| p.point_state());
    let corners = plate.as_ref().map_or([0.0; 4], |p| p.corner_displacements());
    // Trapezoidal rule: c_{n+1} - c_n = Δt/2 (ċ_n + ċ_{n+1}) gives the corner rates exactly.
    let corner_rates: [f64; 4] =
        std::array::from_fn(|i| 2.0 * (corners[i] - prev.corners[i]) / dt - prev.corner_rates[i]);
    let end = StepEnd {
        t,
        v: sphere.v,
        delta,
        rate,
        force: p,
        wp: wp_now,
        vp: vp_now,
        corners,
        corner_rates,
        plate_kinetic: sample.plate_kinetic,
        plate_strain: sample.plate_strain,
        springs: sample.springs,
    };
    (end, sample, stored)
}

/// The approach velocity δ̇⁻ of a contact that opens within the step from (δ, δ̇) = `prev`, whose
/// force-free prediction ends at compression `d0` and rate `r0`: the rate at the crossing of
/// δ - δ_p = 0 (permanent set `set`), interpolated linearly in time between the step's ends,
/// where δ is also taken as linear (both to O(Δt²) of the rate at touch). `None` if no contact
/// opens in the step. A contact opening at the step's start (the first, from δ = 0) gets
/// exactly the rate there, v₀ for the first contact.
pub(crate) fn approach_velocity(set: f64, prev: (f64, f64), d0: f64, r0: f64) -> Option<f64> {
    let (before, after) = (prev.0 - set, d0 - set);
    if before > 0.0 || after <= 0.0 {
        return None;
    }
    let theta = before / (before - after);
    let rate = prev.1 + theta * (r0 - prev.1);
    (rate > 0.0).then_some(rate)
}

/// The energy bookkeeping of one step: every store of the sphere, the contact and the
/// plate, and the energy put in (E₀, plus gravity's work m·g·u on the sphere at `u` from
/// the first touch) minus their sum (the Flores damping, the plate's damping and numerical
/// loss). Returns the sample and the sum of the stores and the plate damping's count of its
/// loss, less gravity's work: what the caller compares with E₀, where only numerical loss
/// and the contact law's own remain.
fn energies<T: Target + ?Sized>(
    s: &Striker,
    plate: Option<&T>,
    t: f64,
    p: f64,
    (delta, dmax): (f64, f64),
    (u, v): (f64, f64),
) -> (Sample, f64) {
    let m = s.mass;
    let e0 = 0.5 * m * s.velocity * s.velocity;
    let en = plate.map(|p| p.energy());
    let (pk, ps, sp) = en.map_or((0.0, 0.0, 0.0), |e| (e.kinetic, e.strain, e.springs));
    let contact = s.stored_energy(delta, dmax);
    let kin = 0.5 * m * v * v;
    let mut stored = kin + contact + pk + ps + sp;
    if s.gravity != 0.0 {
        stored -= m * s.gravity * u;
    }
    let counted = stored + plate.map_or(0.0, |p| p.damping_loss());
    let sample = Sample {
        t,
        force: p,
        compression: delta,
        sphere_velocity: v,
        plate_displacement: plate.map_or(0.0, |p| p.point_state().0),
        sphere_kinetic: kin,
        contact,
        plate_kinetic: pk,
        plate_strain: ps,
        springs: sp,
        dissipated: e0 - stored,
    };
    (sample, counted)
}

/// The contact sequence: the completed contacts and the one going on, each from and to
/// the zero crossings of δ - δ_p on the in-step interpolant.
#[derive(Default)]
struct Sequence {
    contacts: Vec<Contact>,
    current: Option<Contact>,
    /// Gravity on the sphere, m/s²: after the crossing only it acts, so the velocity at the
    /// contact's end is the step end's less g times the rest of the step.
    gravity: f64,
}

impl Sequence {
    /// Follows the step from `prev` to `end` with permanent set `set`: a contact begins when
    /// the force becomes positive and ends when δ crosses zero with zero force
    /// ([`separated`]); its impulse is the trapezoid over the steps.
    fn advance(&mut self, prev: &StepEnd, end: &StepEnd, set: f64, dt: f64) {
        let shifted = |e: &StepEnd| StepEnd { delta: e.delta - set, ..*e };
        let p = end.force;
        match self.current.as_mut() {
            None if p > 0.0 => {
                let start = interpolate::crossing(&shifted(prev), &shifted(end), dt);
                self.current = Some(Contact {
                    start,
                    duration: 0.0,
                    peak_force: p,
                    impulse: 0.5 * dt * (prev.force + p),
                    rebound_velocity: end.v,
                    steps: 1,
                });
            }
            None => {}
            Some(c) => {
                c.peak_force = c.peak_force.max(p);
                c.impulse += 0.5 * dt * (prev.force + p);
                c.steps += 1;
                if separated(true, p, end.delta - set, prev.delta - set).is_some() {
                    let off = interpolate::crossing(&shifted(prev), &shifted(end), dt);
                    c.duration = off - c.start;
                    c.rebound_velocity = if self.gravity != 0.0 { end.v - self.gravity * (end.t - off) } else { end.v };
                    self.contacts.extend(self.current.take());
                }
            }
        }
    }
}

/// The first contact's record: its samples and step ends (for the in-step maxima), its
/// end, and the largest sampled compression.
struct FirstContact {
    history: Vec<Sample>,
    ends: Vec<StepEnd>,
    started: bool,
    done: bool,
    /// Steps up to the first separation.
    steps: usize,
    contact_time: Option<f64>,
    rebound: Option<f64>,
    plate_velocity: Option<f64>,
    max_energy_error: f64,
    prev_delta: f64,
    best_delta: f64,
    corners_at_max: [f64; 4],
    /// Gravity on the sphere (for the velocity at the separation, as in [`Sequence`]).
    gravity: f64,
}

impl FirstContact {
    /// Before the first step: the sphere at v₀ touching the plate at rest.
    fn new(s: &Striker, expected: usize) -> Self {
        let rest = StepEnd {
            t: 0.0,
            v: s.velocity,
            delta: 0.0,
            rate: s.velocity,
            force: 0.0,
            wp: 0.0,
            vp: 0.0,
            corners: [0.0; 4],
            corner_rates: [0.0; 4],
            plate_kinetic: 0.0,
            plate_strain: 0.0,
            springs: 0.0,
        };
        let mut ends = Vec::with_capacity(expected + 1);
        ends.push(rest);
        Self {
            history: Vec::with_capacity(expected),
            ends,
            started: false,
            done: false,
            steps: 0,
            contact_time: None,
            rebound: None,
            plate_velocity: None,
            max_energy_error: 0.0,
            prev_delta: 0.0,
            best_delta: f64::NEG_INFINITY,
            corners_at_max: [0.0; 4],
            gravity: s.gravity,
        }
    }

    /// Records the step ending at `end` (the `steps`-th, of `dt`) with its sample, the
    /// permanent set `set` and the energy error where the law conserves energy; closes the
    /// record at the first separation.
    fn record(&mut self, sample: Sample, end: StepEnd, set: f64, energy_error: Option<f64>, (steps, dt): (usize, f64)) {
        if let Some(err) = energy_error {
            self.max_energy_error = self.max_energy_error.max(err);
        }
        self.history.push(sample);
        self.ends.push(end);
        // The last of equal maxima, as a max over the history would pick.
        if end.delta >= self.best_delta {
            self.best_delta = end.delta;
            self.corners_at_max = end.corners;
        }
        if end.force > 0.0 {
            self.started = true;
        }
        if let Some(frac) = separated(self.started, end.force, end.delta - set, self.prev_delta - set) {
            let off = end.t - dt + frac * dt;
            self.contact_time = Some(off);
            self.rebound = Some(if self.gravity != 0.0 { end.v - self.gravity * (end.t - off) } else { end.v });
            self.plate_velocity = Some(end.vp);
            self.done = true;
            self.steps = steps;
        }
        self.prev_delta = end.delta;
    }
}

/// The run beyond the first contact: its samples, the energy error over the whole run,
/// when the sphere provably left, and the steps taken.
struct Later {
    history: Vec<Sample>,
    max_energy_error: f64,
    left_at: Option<f64>,
    returns_at: Option<f64>,
    steps: usize,
}

/// What the stopping rule decides after a step with no contact going on.
enum Verdict {
    /// The sphere has provably left: no further contact can occur (without gravity), or
    /// none within the window, the sphere falling back no sooner than the given time from
    /// now (with gravity).
    Left(Option<f64>),
    /// Nothing bounds the plate's later motion and the run is not to follow it.
    Stop,
    /// A later contact is still possible.
    Continue,
}

/// The stopping rule of [`simulate_with`]: the sphere at `u` (less the permanent set δ_p
/// of its largest compression, at which a yielded lump's contact opens again), moving at
/// `end.v`, is beyond the reach W of the free plate and moving away. W is the energy bound √(2E_p C_p) or the
/// target's own bound on its free motion, whichever is smaller (0 for a rigid target).
///
/// Under gravity g toward the plate the free sphere moves on u(τ) = u + vτ + gτ²/2 and
/// always comes back; the plate's point stays within ±W, so no contact can occur before
/// u(τ) = -W, at τ* = (-v + √(v² - 2g(u + W)))/g ([`return_time`]). The run stops when τ*
/// lies beyond the `remaining` window, and says when the sphere can be back.
fn stopping_rule<T: Target + ?Sized>(
    plate: Option<&T>,
    facts: &PlateFacts,
    end: &StepEnd,
    u: f64,
    (gravity, remaining): (f64, f64),
) -> Verdict {
    let v = end.v;
    let energy = facts.static_compliance.map(|c| (2.0 * end.plate_energy().max(0.0) * c).sqrt());
    // The target's own bound may cost it a pass over its state, so with the energy bound at
    // hand it is asked only when it could decide: the sphere moves away, is not already
    // beyond the energy bound, and is beyond the point's present deflection (which any
    // bound on the later motion exceeds, so short of it the own bound cannot stop the run
    // either).
    let undecided = |w: f64| v > 0.0 || u >= -end.wp.abs() || u < -w;
    let own = plate.map(|p| if energy.is_some_and(undecided) { None } else { p.free_reach() });
    let reach = match own {
        None => Some(0.0),
        Some(own) => match (own, energy) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        },
    };
    match reach {
        Some(w) if gravity > 0.0 && u < -w => match return_time(u + w, v, gravity) {
            tau if tau >= remaining => Verdict::Left(Some(tau)),
            _ => Verdict::Continue,
        },
        Some(w) if gravity == 0.0 && v <= 0.0 && u < -w => Verdict::Left(None),
        None if !facts.follow_unbounded => Verdict::Stop,
        _ => Verdict::Continue,
    }
}

/// The time τ* > 0 at which a free sphere `gap` < 0 short of the plate's reach, moving at `v`
/// toward it under gravity `g` > 0, closes the gap: gτ²/2 + vτ + gap = 0, the positive root
/// (written as 2|gap|/(v + √(v² - 2g·gap)) where v > 0, free of cancellation).
fn return_time(gap: f64, v: f64, g: f64) -> f64 {
    let root = (v * v - 2.0 * g * gap).sqrt();
    if v > 0.0 {
        -2.0 * gap / (v + root)
    } else {
        (root - v) / g
    }
}

/// The outcome of a run: the first contact's sampled and interpolated maxima, the
/// sequence, and how the run ended (the sphere's final velocity `v`; the corner springs
/// for the spring energy at the interpolated instant; the step `dt`).
fn outcome(
    s: &Striker,
    first: FirstContact,
    sequence: Sequence,
    later: Later,
    (v, corner_springs, dt): (f64, Option<[f64; 4]>, f64),
) -> Outcome {
    let e0 = 0.5 * s.mass * s.velocity * s.velocity;
    let history = first.history;
    let imax =
        history.iter().enumerate().max_by(|x, y| x.1.compression.total_cmp(&y.1.compression)).map_or(0, |(i, _)| i);
    let at_max = history.get(imax).copied().unwrap_or(Sample {
        t: 0.0,
        force: 0.0,
        compression: 0.0,
        sphere_velocity: s.velocity,
        plate_displacement: 0.0,
        sphere_kinetic: e0,
        contact: 0.0,
        plate_kinetic: 0.0,
        plate_strain: 0.0,
        springs: 0.0,
        dissipated: 0.0,
    });
    let interpolated = interpolate::first_contact(s, &first.ends, corner_springs, dt);
    let Sequence { contacts, current, .. } = sequence;
    let total_impulse = contacts.iter().map(|c| c.impulse).sum::<f64>() + current.as_ref().map_or(0.0, |c| c.impulse);
    Outcome {
        force_max: history.iter().map(|h| h.force).fold(0.0, f64::max),
        compression_max: at_max.compression,
        time_of_max_compression: at_max.t,
        contact_time: first.contact_time,
        rebound_velocity: first.rebound,
        plate_velocity_at_separation: first.plate_velocity,
        apparent_restitution: first.rebound.map(|r| -r / s.velocity),
        at_max_compression: at_max,
        corners_at_max_compression: first.corners_at_max,
        steps: if first.done { first.steps } else { later.steps },
        max_energy_error: first.max_energy_error,
        history,
        force_max_interpolated: interpolated.force_max,
        compression_max_interpolated: interpolated.at_max.compression,
        time_of_max_compression_interpolated: interpolated.at_max.t,
        at_max_compression_interpolated: interpolated.at_max,
        corners_at_max_compression_interpolated: interpolated.corners,
        contacts,
        unfinished_contact: current,
        total_impulse,
        final_velocity: v,
        left_at: later.left_at,
        returns_at: later.returns_at,
        steps_total: later.steps,
        max_energy_error_total: later.max_energy_error,
        later_history: later.history,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(delta: f64, rate: f64) -> (f64, f64) {
        (delta, rate)
    }

    /// The first contact opens at the step's start (δ = 0 at t = 0), so its approach velocity
    /// is v₀ to the last bit: the first contact is the paper's Flores law, eqs. 1-2, unchanged.
    #[test]
    fn the_first_contact_approaches_at_exactly_v0() {
        for v0 in [0.008, 0.1 / 3.0, 2.9] {
            assert_eq!(approach_velocity(0.0, at(0.0, v0), 1e-6, 0.97 * v0), Some(v0));
        }
    }

    /// A later contact: δ from -1 to +3 (µm) crosses zero a quarter into the step, where the
    /// rate, linear from 0.4 to 0.2 m/s, is 0.35 m/s; with a permanent set δ_p = 1 µm the
    /// contact opens at δ - δ_p = 0, half-way, at 0.3 m/s. No contact opens from a step that
    /// starts in contact or ends out of it.
    #[test]
    fn a_later_contact_approaches_at_the_rate_at_touch() {
        let close = |a: Option<f64>, b: f64| (a.unwrap() - b).abs() < 1e-15;
        assert!(close(approach_velocity(0.0, at(-1e-6, 0.4), 3e-6, 0.2), 0.35));
        assert!(close(approach_velocity(1e-6, at(-1e-6, 0.4), 3e-6, 0.2), 0.3));
        assert_eq!(approach_velocity(0.0, at(1e-6, 0.4), 3e-6, 0.2), None);
        assert_eq!(approach_velocity(0.0, at(-3e-6, 0.4), -1e-6, 0.2), None);
    }
}
