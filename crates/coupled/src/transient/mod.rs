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
//! let s = Striker { k: 5.11545e8, restitution: 1.0, mass: 0.0903, velocity: 0.008, law: ContactLaw::Flores(Flores), gravity: 0.0 };
//! let tc = s.hertz_time();
//! let o = simulate(&s, None, tc / 200.0, 3.0 * tc);
//! assert!((o.force_max / s.hertz_force() - 1.0).abs() < 1e-4);
//! assert!((o.contact_time.unwrap() / tc - 1.0).abs() < 1e-4);
//! // One contact, and on a rigid target the sphere has left for good at its end.
//! assert_eq!(o.contacts.len(), 1);
//! assert!(o.left_at.is_some());
//! ```

pub mod case;
pub mod chatter;
pub mod contact;
pub mod estimate;
pub mod frames;
mod integrate;
pub mod interpolate;
pub mod law;
pub mod reference;
pub mod sequence_estimate;
pub mod target;

pub use case::{first_contact_on, TransientCase, TransientSettings};
pub use contact::{contact_force, contact_force_after, Striker, HERTZ_TIME};
pub use estimate::{
    choose, choose_on, estimate, Budget, Discretisation, Estimated, Ladder, Quantities, DEFAULT_TOLERANCE,
};
pub(crate) use integrate::approach_velocity;
pub use integrate::{simulate, simulate_with};
pub use law::thornton::thornton_restitution;
pub use law::{ContactLaw, ContactState, Law, LawKind};
pub use reference::zener;
pub use target::{SpringMass, Target};

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
    /// Under gravity the sphere always falls back: the earliest instant it could touch the
    /// plate again, beyond the window (`left_at` then says no contact can occur within the
    /// window, not that none ever will), s. None without gravity.
    pub returns_at: Option<f64>,
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
