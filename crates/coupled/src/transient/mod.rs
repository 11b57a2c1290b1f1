//! Transient impact: the sphere, the Flores contact force with its damping (eqs. 1-2) and
//! the plate FE dynamics, integrated together in time. This tests the paper's
//! quasi-static assumption, that the plate deforms statically during contact.
//!
//! Both bodies use Newmark's average-acceleration rule (`plate_fem::dynamics`). Each step
//! has three named parts: the contact solve ([`contact::contact_force`]), the energy
//! bookkeeping ([`energies`]) and the separation test ([`separated`]).
//!
//! ```
//! use coupled::transient::{simulate, Striker};
//! // A coal sphere (Table 1) on a rigid target with e = 1 is Hertz's impact.
//! let s = Striker { k: 5.11545e8, restitution: 1.0, mass: 0.0903, velocity: 0.008 };
//! let tc = s.hertz_time();
//! let o = simulate(&s, None, tc / 200.0, 3.0 * tc);
//! assert!((o.force_max / s.hertz_force() - 1.0).abs() < 1e-4);
//! assert!((o.contact_time.unwrap() / tc - 1.0).abs() < 1e-4);
//! ```

pub mod case;
pub mod contact;
pub mod reference;

pub use case::{TransientCase, TransientSettings};
pub use contact::{contact_force, Striker, HERTZ_TIME};
pub use reference::zener;

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
    /// Elastic energy in the contact, (2/5)Kδ^{5/2}, J.
    pub contact: f64,
    /// Kinetic energy of the plate, J.
    pub plate_kinetic: f64,
    /// Strain energy of the plate, J.
    pub plate_strain: f64,
    /// Energy of the corner springs, J.
    pub springs: f64,
    /// E₀ minus everything stored or moving: the Flores damping (and numerical) loss.
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
    /// Time steps taken.
    pub steps: usize,
    /// Largest |E_total - E₀|/E₀ over the run counting dissipation as lost: only
    /// meaningful as an error when e = 1.
    pub max_energy_error: f64,
    /// Every step's sample.
    pub history: Vec<Sample>,
}

/// The energy bookkeeping of one step: every store of the sphere, the contact and the
/// plate, and E₀ minus their sum (the Flores damping and numerical loss). Returns the
/// sample and the sum of the stores.
fn energies(s: &Striker, plate: Option<&Newmark<'_>>, t: f64, p: f64, delta: f64, v: f64) -> (Sample, f64) {
    let m = s.mass;
    let e0 = 0.5 * m * s.velocity * s.velocity;
    let en = plate.map(|p| p.energy());
    let (pk, ps, sp) = en.map_or((0.0, 0.0, 0.0), |e| (e.kinetic, e.strain, e.springs));
    let contact = if delta > 0.0 { 0.4 * s.k * delta.powf(2.5) } else { 0.0 };
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

/// Integrates the impact of `s` on `plate` (or a rigid target when None) with step `dt`,
/// until the sphere separates or `t_max`.
pub fn simulate(s: &Striker, mut plate: Option<&mut Newmark<'_>>, dt: f64, t_max: f64) -> Outcome {
    let m = s.mass;
    let e0 = 0.5 * m * s.velocity * s.velocity;
    let g = plate.as_ref().map_or(0.0, |p| p.point_flexibility());
    let (mut u, mut v, mut a) = (0.0, s.velocity, 0.0);
    let mut history = Vec::new();
    let (mut started, mut t, mut steps) = (false, 0.0, 0usize);
    let (mut contact_time, mut rebound, mut plate_velocity) = (None, None, None);
    let mut max_err: f64 = 0.0;
    let mut prev_delta: f64 = 0.0;
    let (mut best_delta, mut corners_at_max) = (f64::NEG_INFINITY, [0.0; 4]);
    while t < t_max {
        let (wp, vp) = plate.as_mut().map_or((0.0, 0.0), |p| p.predict());
        let u_hat = u + dt * v + 0.25 * dt * dt * a;
        let v_hat = v + 0.5 * dt * a;
        let (d0, d1) = (u_hat - wp, 0.25 * dt * dt / m + g);
        let (r0, r1) = (v_hat - vp, 0.5 * dt / m + 2.0 * g / dt);
        let p = contact_force(s, d0, d1, r0, r1);
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
        let (sample, stored) = energies(s, plate.as_deref(), t, p, delta, v);
        if s.restitution >= 1.0 {
            max_err = max_err.max((stored - e0).abs() / e0);
        }
        history.push(sample);
        // The last of equal maxima, as a max over the history would pick.
        if delta >= best_delta {
            best_delta = delta;
            corners_at_max = plate.as_ref().map_or([0.0; 4], |p| p.corner_displacements());
        }
        if p > 0.0 {
            started = true;
        }
        if let Some(frac) = separated(started, p, delta, prev_delta) {
            contact_time = Some(t - dt + frac * dt);
            rebound = Some(v);
            plate_velocity = plate.as_ref().map(|p| p.point_state().1).or(Some(0.0));
            break;
        }
        prev_delta = delta;
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
        steps,
        max_energy_error: max_err,
        history,
    }
}
