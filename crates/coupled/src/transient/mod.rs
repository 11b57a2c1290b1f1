//! Transient impact: the sphere, the contact force (by default the Flores law with its
//! damping, eqs. 1-2; Hertz and Thornton's elastic-plastic law in [`law`]) and the plate FE
//! dynamics, integrated together in time. This tests the paper's
//! quasi-static assumption, that the plate deforms statically during contact.
//!
//! Both bodies use Newmark's average-acceleration rule (`plate_fem::dynamics`). Each step
//! has three named parts: the contact solve ([`contact::contact_force`]), the energy
//! bookkeeping (`energies`) and the separation test ([`separated`]). The run follows the
//! impact past the first separation, through every later contact, until the sphere has
//! provably left ([`simulate_with`]). Maxima between step ends come from the integrator's
//! own interpolant ([`interpolate`]); [`mod@estimate`] puts an error estimate on every number
//! from the case's own discretisation. [`target::SpringMass`] replaces the plate by one
//! mass on a spring, for checks against an ODE solution.
//!
//! ```
//! use coupled::transient::{law::Flores, simulate, ContactLaw, Striker};
//! // A coal sphere (Table 1) on a rigid target with e = 1 is Hertz's impact.
//! let s = Striker { k: 5.11545e8, restitution: 1.0, mass: 0.0903, velocity: 0.008, law: ContactLaw::Flores(Flores) };
//! let tc = s.hertz_time();
//! let o = simulate(&s, None, tc / 200.0, 3.0 * tc);
//! assert!((o.force_max / s.hertz_force() - 1.0).abs() < 1e-4);
//! assert!((o.contact_time.unwrap() / tc - 1.0).abs() < 1e-4);
//! // One contact, and on a rigid target the sphere has left for good at its end.
//! assert_eq!(o.contacts.len(), 1);
//! assert!(o.left_at.is_some());
//! ```

pub mod case;
pub mod contact;
pub mod estimate;
pub mod frames;
pub mod interpolate;
pub mod law;
pub mod reference;
pub mod target;

pub use case::{first_contact_on, TransientCase, TransientSettings};
pub use contact::{contact_force, contact_force_after, Striker, HERTZ_TIME};
pub use estimate::{
    choose, choose_on, estimate, Budget, Discretisation, Estimated, Ladder, Quantities, DEFAULT_TOLERANCE,
};
pub use law::thornton::thornton_restitution;
pub use law::{ContactLaw, ContactState, Law, LawKind};
pub use reference::zener;
pub use target::{SpringMass, Target};

use plate_fem::dynamics::Newmark;
use serde::Serialize;

/// One sample of the history.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Sample {
    /// Time at the end of the step, s.
    pub t: f64,
    /// Contact force, N.
    pub force: f64,
    /// Compression δ, m.
    pub compression: f64,
    /// Sphere velocity (positive toward the plate), m/s.
    pub sphere_velocity: f64,
    /// Plate deflection at the impact point.
    pub plate_displacement: f64,
    /// Kinetic energy of the sphere, J.
    pub sphere_kinetic: f64,
    /// Elastic energy in the contact, (2/5)Kδ^{5/2} for an elastic law (what unloading would
    /// return, [`ContactLaw::stored_energy`]), J.
    pub contact: f64,
    /// Kinetic energy of the plate, J.
    pub plate_kinetic: f64,
    /// Strain energy of the plate, J.
    pub plate_strain: f64,
    /// Energy of the corner springs, J.
    pub springs: f64,
    /// E₀ minus everything stored or moving: the Flores damping or the plastic work (and the
    /// numerical) loss.
    pub dissipated: f64,
}

/// The outcome of one impact.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Outcome {
    /// Largest contact force over the samples, N.
    pub force_max: f64,
    /// Largest compression over the samples, m.
    pub compression_max: f64,
    /// When it occurred, s.
    pub time_of_max_compression: f64,
    /// Duration of the first contact, s; None if the sphere had not separated at t_max.
    pub contact_time: Option<f64>,
    /// Sphere velocity at separation (negative: rebound), m/s.
    pub rebound_velocity: Option<f64>,
    /// Velocity of the struck point at separation, m/s (positive into the plate).
    pub plate_velocity_at_separation: Option<f64>,
    /// -v_rebound / v₀.
    pub apparent_restitution: Option<f64>,
    /// The state at maximum compression.
    pub at_max_compression: Sample,
    /// Deflections of the four corners at maximum compression (zero where held).
    pub corners_at_max_compression: [f64; 4],
    /// Time steps taken up to the first separation (all of them if there was none).
    pub steps: usize,
    /// Largest |E_total - E₀|/E₀ over the first contact counting dissipation as lost: only
    /// meaningful as an error when e = 1.
    pub max_energy_error: f64,
    /// Every step's sample up to the first separation.
    pub history: Vec<Sample>,
    /// Largest contact force on the in-step interpolant during the first contact, N
    /// ([`interpolate`]).
    pub force_max_interpolated: f64,
    /// Largest compression of the first contact, where δ̇ = 0 on the interpolant, m.
    pub compression_max_interpolated: f64,
    /// When it occurred, s.
    pub time_of_max_compression_interpolated: f64,
    /// The state at that instant, from the same interpolant.
    pub at_max_compression_interpolated: Sample,
    /// Corner deflections at that instant, m.
    pub corners_at_max_compression_interpolated: [f64; 4],
    /// Every completed contact in order, the first included (its start and end from the
    /// interpolant of δ, so its duration differs from `contact_time` by O(Δt²)).
    pub contacts: Vec<Contact>,
    /// A contact still going on at the end of the window.
    pub unfinished_contact: Option<Contact>,
    /// The sum of the contacts' impulses, N·s.
    pub total_impulse: f64,
    /// Sphere velocity at the end of the run, m/s (negative: away from the plate); the final
    /// rebound velocity when `left_at` is Some.
    pub final_velocity: f64,
    /// When the stopping rule of [`simulate_with`] proved that no further contact can
    /// occur, s; None if the run reached the end of its window first.
    pub left_at: Option<f64>,
    /// Time steps taken over the whole run.
    pub steps_total: usize,
    /// As `max_energy_error`, over the whole run.
    pub max_energy_error_total: f64,
    /// The samples after the first separation.
    pub later_history: Vec<Sample>,
}

/// One contact of the sequence.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Contact {
    /// When δ became positive, s.
    pub start: f64,
    /// How long δ stayed positive, s.
    pub duration: f64,
    /// Largest sampled contact force, N.
    pub peak_force: f64,
    /// ∫P dt by the trapezoid over the steps, N·s: for Newmark's rule exactly m times the
    /// sphere's loss of velocity over the contact.
    pub impulse: f64,
    /// Sphere velocity after the contact, m/s (negative: away from the plate).
    pub rebound_velocity: f64,
    /// Steps the contact spans.
    pub steps: usize,
}

/// The energy bookkeeping of one step: every store of the sphere, the contact and the
/// plate, and E₀ minus their sum (the Flores damping and numerical loss). Returns the
/// sample and the sum of the stores.
fn energies<T: Target + ?Sized>(
    s: &Striker,
    plate: Option<&T>,
    t: f64,
    p: f64,
    (delta, dmax): (f64, f64),
    v: f64,
) -> (Sample, f64) {
    let m = s.mass;
    let e0 = 0.5 * m * s.velocity * s.velocity;
    let en = plate.map(|p| p.energy());
    let (pk, ps, sp) = en.map_or((0.0, 0.0, 0.0), |e| (e.kinetic, e.strain, e.springs));
    let contact = s.stored_energy(delta, dmax);
    let kin = 0.5 * m * v * v;
    let stored = kin + contact + pk + ps + sp;
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
    (sample, stored)
}

/// The separation test: contact has been made, the force is zero and the compression
/// crossed zero inside this step. Returns the crossing as a fraction of the step (linear
/// interpolation of δ).
pub fn separated(started: bool, p: f64, delta: f64, prev_delta: f64) -> Option<f64> {
    (started && p == 0.0 && delta <= 0.0 && prev_delta > 0.0).then(|| prev_delta / (prev_delta - delta))
}

/// What [`simulate_with`] may know of the plate beyond its `Newmark` state.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct PlateFacts {
    /// C_p = Nᵀ K⁻¹ N, the supported plate's static compliance at the struck point, m/N.
    /// With it the run stops as soon as no further contact is possible (see [`simulate_with`]);
    /// without it nothing bounds the plate's later excursions, and a run on a plate either
    /// stops at the first separation or follows the free motion to the end of the window
    /// (`follow_unbounded`).
    pub static_compliance: Option<f64>,
    /// Corner spring stiffnesses in [`plate_fem::Corner::ALL`] order, N/m (0 where the corner
    /// is free or held); used for the spring energy at the interpolated instant. Without
    /// them that energy is interpolated linearly within the step.
    pub corner_springs: Option<[f64; 4]>,
    /// Without `static_compliance`: follow the free motion to the end of the window (true)
    /// or stop at the first separation (false, the default).
    pub follow_unbounded: bool,
}

/// Integrates the impact of `s` on `plate` (or a rigid target when None) with step `dt` up
/// to `t_max`. The plate's static compliance is unknown here, so nothing proves a later
/// contact impossible short of integrating to `t_max`: the run stops at the first
/// separation (`left_at` None, `contacts` the first contact only) unless the target is
/// rigid, where it has provably ended. [`simulate_with`] follows the whole sequence.
pub fn simulate(s: &Striker, plate: Option<&mut Newmark<'_>>, dt: f64, t_max: f64) -> Outcome {
    simulate_with(s, plate, PlateFacts::default(), dt, t_max)
}

/// The state at the end of a step, everything the in-step interpolants need.
#[derive(Debug, Clone, Copy)]
struct StepEnd {
    t: f64,
    /// Sphere velocity (toward the plate).
    v: f64,
    delta: f64,
    rate: f64,
    force: f64,
    /// Plate point displacement and velocity.
    wp: f64,
    vp: f64,
    corners: [f64; 4],
    corner_rates: [f64; 4],
    plate_kinetic: f64,
    plate_strain: f64,
    springs: f64,
}

impl StepEnd {
    fn plate_energy(&self) -> f64 {
        self.plate_kinetic + self.plate_strain + self.springs
    }
}

/// Integrates the impact of `s` on `plate` (or a rigid target when None) with step `dt`,
/// and follows it until the sphere has left for good or `t_max`.
///
/// Every step is the same: the contact force solves the Flores law at the end of the step
/// ([`contact::contact_force`]); it is zero while the predicted compression is negative, so
/// after a separation the plate vibrates freely, the sphere flies on ballistically (no
/// gravity) and a later contact is found by the same solve. A contact begins when the force
/// becomes positive and ends when δ crosses zero with zero force ([`separated`]).
///
/// **Stopping rule.** After a separation the plate moves freely, and its energy
/// E_p = ½ẇᵀMẇ + ½wᵀKw (kinetic, strain and springs) is constant: exactly so for the FE
/// model, and exactly so at the step ends for Newmark's average-acceleration rule, which
/// conserves this quadratic energy of a linear system. By Cauchy-Schwarz in the K inner
/// product the point deflection w_p = Nᵀw obeys |w_p| ≤ √(wᵀKw · NᵀK⁻¹N) ≤ √(2E_p C_p) = W
/// for all later time, C_p the static compliance at the point. The sphere's displacement u
/// (toward the plate, from the first touch) is linear in time once free. Contact needs
/// δ = u - w_p > 0, so once u < -W with u̇ ≤ 0 no contact can ever occur again: the run
/// stops there. A rigid target has W = 0, so it stops at the first separation. Without C_p
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
    let m = s.mass;
    let e0 = 0.5 * m * s.velocity * s.velocity;
    let g = plate.as_ref().map_or(0.0, |p| p.point_flexibility());
    let (mut u, mut v, mut a) = (0.0, s.velocity, 0.0);
    // Room for the steps of about two rigid-target contact times, so that the histories of
    // a first contact seldom grow by copying.
    let expected = (2.0 * s.hertz_time() / dt).clamp(16.0, 4096.0) as usize;
    let mut history = Vec::with_capacity(expected);
    let mut later_history = Vec::with_capacity(expected);
    let (mut started, mut t, mut steps) = (false, 0.0, 0usize);
    let (mut contact_time, mut rebound, mut plate_velocity) = (None, None, None);
    let (mut max_err, mut max_err_total): (f64, f64) = (0.0, 0.0);
    let mut prev_delta: f64 = 0.0;
    let (mut best_delta, mut corners_at_max) = (f64::NEG_INFINITY, [0.0; 4]);
    // The sequence: step ends of the first contact (for the in-step maxima), the contacts.
    let mut prev = StepEnd {
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
    let mut first_ends = Vec::with_capacity(expected + 1);
    first_ends.push(prev);
    let mut first_done = false;
    let mut contacts: Vec<Contact> = Vec::new();
    let mut current: Option<Contact> = None;
    let mut first_steps = 0usize;
    let mut left_at = None;
    // The largest compression so far and the permanent compression it left: a plastic
    // contact opens at δ = δ_p, not at δ = 0, so the contact sequence is followed on δ - δ_p
    // (δ_p = 0 for the elastic laws, which leaves every test unchanged).
    let mut dmax: f64 = 0.0;
    let shifted = |e: &StepEnd, set: f64| StepEnd { delta: e.delta - set, ..*e };
    let conserves = s.conserves();
    while t < t_max {
        let (wp, vp) = plate.as_mut().map_or((0.0, 0.0), |p| p.predict());
        let u_hat = u + dt * v + 0.25 * dt * dt * a;
        let v_hat = v + 0.5 * dt * a;
        let (d0, d1) = (u_hat - wp, 0.25 * dt * dt / m + g);
        let (r0, r1) = (v_hat - vp, 0.5 * dt / m + 2.0 * g / dt);
        let p = contact_force_after(s, dmax, d0, d1, r0, r1);
        let a_new = -p / m;
        u = u_hat + 0.25 * dt * dt * a_new;
        v = v_hat + 0.5 * dt * a_new;
        a = a_new;
        if let Some(pl) = plate.as_mut() {
            pl.commit(p);
        }
        t += dt;
        steps += 1;
        let delta = d0 - d1 * p;
        let rate = r0 - r1 * p;
        dmax = dmax.max(delta);
        let set = s.permanent_set(dmax);
        let (sample, stored) = energies(s, plate.as_deref(), t, p, (delta, dmax), v);
        let (wp_now, vp_now) = plate.as_ref().map_or((0.0, 0.0), |p| p.point_state());
        let corners = plate.as_ref().map_or([0.0; 4], |p| p.corner_displacements());
        // Trapezoidal rule: c_{n+1} - c_n = Δt/2 (ċ_n + ċ_{n+1}) gives the corner rates exactly.
        let corner_rates: [f64; 4] =
            std::array::from_fn(|i| 2.0 * (corners[i] - prev.corners[i]) / dt - prev.corner_rates[i]);
        let end = StepEnd {
            t,
            v,
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
        if conserves {
            max_err_total = max_err_total.max((stored - e0).abs() / e0);
        }
        // The contact sequence, with start and end on the in-step interpolant of δ.
        match current.as_mut() {
            None if p > 0.0 => {
                let start = interpolate::crossing(&shifted(&prev, set), &shifted(&end, set), dt);
                current = Some(Contact {
                    start,
                    duration: 0.0,
                    peak_force: p,
                    impulse: 0.5 * dt * (prev.force + p),
                    rebound_velocity: v,
                    steps: 1,
                });
            }
            None => {}
            Some(c) => {
                c.peak_force = c.peak_force.max(p);
                c.impulse += 0.5 * dt * (prev.force + p);
                c.steps += 1;
                if separated(true, p, delta - set, prev.delta - set).is_some() {
                    c.duration = interpolate::crossing(&shifted(&prev, set), &shifted(&end, set), dt) - c.start;
                    c.rebound_velocity = v;
                    contacts.extend(current.take());
                }
            }
        }
        if first_done {
            later_history.push(sample);
        } else {
            if conserves {
                max_err = max_err.max((stored - e0).abs() / e0);
            }
            history.push(sample);
            first_ends.push(end);
            // The last of equal maxima, as a max over the history would pick.
            if delta >= best_delta {
                best_delta = delta;
                corners_at_max = corners;
            }
            if p > 0.0 {
                started = true;
            }
            if let Some(frac) = separated(started, p, delta - set, prev_delta - set) {
                contact_time = Some(t - dt + frac * dt);
                rebound = Some(v);
                plate_velocity = plate.as_ref().map(|p| p.point_state().1).or(Some(0.0));
                first_done = true;
                first_steps = steps;
            }
            prev_delta = delta;
        }
        prev = end;
        // The stopping rule (see the doc comment): free, moving away, beyond the plate's reach.
        if first_done && current.is_none() {
            // The energy bound, or the target's own bound on its free motion if tighter.
            let energy = facts.static_compliance.map(|c| (2.0 * end.plate_energy().max(0.0) * c).sqrt());
            // The target's own bound may cost it a pass over its state, so with the energy
            // bound at hand it is asked only when it could decide: the sphere moves away, is
            // not already beyond the energy bound, and is beyond the point's present
            // deflection (which any bound on the later motion exceeds, so short of it the
            // own bound cannot stop the run either).
            let undecided = |w: f64| v > 0.0 || u >= -wp_now.abs() || u < -w;
            let own = plate.as_ref().map(|p| if energy.is_some_and(undecided) { None } else { p.free_reach() });
            let reach = match own {
                None => Some(0.0),
                Some(own) => match (own, energy) {
                    (Some(a), Some(b)) => Some(a.min(b)),
                    (a, b) => a.or(b),
                },
            };
            match reach {
                Some(w) if v <= 0.0 && u < -w => {
                    left_at = Some(t);
                    break;
                }
                None if !facts.follow_unbounded => break,
                _ => {}
            }
        }
    }
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
    let interpolated = interpolate::first_contact(s, &first_ends, facts.corner_springs, dt);
    let total_impulse = contacts.iter().map(|c| c.impulse).sum::<f64>() + current.as_ref().map_or(0.0, |c| c.impulse);
    Outcome {
        force_max: history.iter().map(|h| h.force).fold(0.0, f64::max),
        compression_max: at_max.compression,
        time_of_max_compression: at_max.t,
        contact_time,
        rebound_velocity: rebound,
        plate_velocity_at_separation: plate_velocity,
        apparent_restitution: rebound.map(|r| -r / s.velocity),
        at_max_compression: at_max,
        corners_at_max_compression: corners_at_max,
        steps: if first_done { first_steps } else { steps },
        max_energy_error: max_err,
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
        left_at,
        steps_total: steps,
        max_energy_error_total: max_err_total,
        later_history,
    }
}
