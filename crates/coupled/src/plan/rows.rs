//! The rows every model fills: responses at maximum compression and yield velocities,
//! each computed or not applicable, with how it was found and whether it is valid.

use super::ModelKind;
use crate::validity::{self, Validity};
use serde::Serialize;

/// A row's result: computed, or the model does not describe the case.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "kebab-case")]
pub enum RowOutcome<T> {
    /// The model answered.
    Computed(T),
    /// The model does not describe this case (the beam and a general support set).
    NotApplicable {
        /// Why, in a sentence.
        reason: String,
    },
}

/// How a response was found.
// One per result row, and rows are few (cases, not steps): the transient variant's size costs
// nothing worth a box and the indirection in every pattern that reads it.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Evidence {
    /// The energy balance of eqs. 14, 25, 46.
    Balance {
        /// Iterations of the solver.
        iterations: u32,
        /// Relative residual ğ of eq. 18 at the root.
        residual: f64,
    },
    /// The time integration.
    Transient {
        /// Time steps taken.
        steps: usize,
        /// Time step, s.
        time_step: f64,
        /// Largest contact force on the in-step interpolant, N (it includes the Flores
        /// damping; the paper's P_max is Kδ_max^{3/2}).
        peak_force: f64,
        /// Its estimated absolute error, N.
        peak_force_error: Option<f64>,
        /// Duration of the first contact, s (δ's zero crossings on the interpolant).
        contact_time: Option<f64>,
        /// Its estimated absolute error, s.
        contact_time_error: Option<f64>,
        /// -v_rebound/v₀ after the first contact.
        apparent_restitution: Option<f64>,
        /// Its estimated absolute error.
        restitution_error: Option<f64>,
        /// Elements along the longer side of the plate mesh.
        elements: usize,
        /// Time steps per Hertz contact time.
        steps_per_contact: f64,
        /// The largest relative error estimate of the peak force, the force at maximum
        /// compression and the contact time.
        relative_error: Option<f64>,
        /// The relative tolerance the discretisation was chosen for (None: fixed settings).
        tolerance: Option<f64>,
        /// Whether the estimate met it (within the ladder's budget).
        met_tolerance: bool,
        /// Contacts until the sphere left for good (or the window ended).
        contacts: usize,
        /// The impact's main contacts: those whose impulse is at least the scene's
        /// `main_contact_share` of m·v₀ ([`crate::transient::chatter`]).
        main_contacts: usize,
        /// The others (chatter), whose number depends on the discretisation.
        micro_contacts: usize,
        /// Their total impulse, N·s.
        micro_impulse: f64,
        /// Whether the number of contacts differs between the error estimate's levels (None
        /// without an estimate): the count is then not converged.
        contact_count_changes: Option<bool>,
        /// The impulse of all of them, N·s.
        total_impulse: f64,
        /// Its estimated absolute error: for one contact that ended, v₀ times the
        /// restitution's error times m; after several, from the estimate's levels followed
        /// through every contact (None where their contact counts differ).
        total_impulse_error: Option<f64>,
        /// Sphere velocity at the end of the run, m/s (negative: away from the plate).
        final_velocity: f64,
        /// Its estimated absolute error, m/s (as `total_impulse_error`).
        final_velocity_error: Option<f64>,
        /// Whether the run proved that no further contact can occur (else the window ended,
        /// or, under gravity, the sphere falls back after it).
        left_for_good: bool,
        /// Under gravity: the earliest instant the sphere can touch the plate again, after
        /// the window, s (None without gravity or where the window ended first).
        returns_at: Option<f64>,
    },
}

/// Responses at maximum compression, from any model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResponseValues {
    /// Total compliance C of the supported plate at the point, m/N (quasi-static models).
    pub compliance: Option<f64>,
    /// Its estimated absolute discretisation error, m/N.
    pub compliance_error: Option<f64>,
    /// P_max = K δ_max^{3/2}, N (eq. 20).
    pub contact_force: f64,
    /// Estimated absolute error of P_max from the compliance's error, N.
    pub contact_force_error: Option<f64>,
    /// δ_max, m.
    pub compression: f64,
    /// Estimated absolute error of δ_max, m.
    pub compression_error: Option<f64>,
    /// Plate deflection at the impact point (eq. 11; eq. 41 in Con 3; for the plate, w
    /// minus the bilinear plane through the corner deflections), m.
    pub deflection: f64,
    /// Spring forces (eqs. 29-30, 36), N.
    pub spring_forces: Vec<analytic::SpringForce>,
    /// Energy absorbed and dissipated by the rock over E₀.
    pub rock_total_ratio: f64,
    /// Elastic energy of the rock, (2K/5)δ^{5/2}, over E₀.
    pub rock_stored_ratio: f64,
    /// Plate energy (strain, and kinetic in the transient model) over E₀.
    pub plate_ratio: f64,
    /// Spring energy over E₀.
    pub spring_ratio: f64,
    /// Kinetic energy the sphere still has at maximum compression over E₀ (0 when
    /// quasi-static).
    pub sphere_kinetic_ratio: f64,
    /// Estimated absolute errors of the deflection, spring forces and energy shares (the
    /// transient model, from each case's own discretisation; None for the quasi-static
    /// models, whose error is the compliance's).
    pub state_errors: Option<StateErrors>,
    /// How the values were found.
    pub evidence: Evidence,
    /// Whether the values are inside the model's assumptions.
    pub validity: Validity,
}

/// Estimated absolute errors of a transient row's values at maximum compression, from
/// [`crate::transient::estimate::State`]'s error (Richardson in h and Δt).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StateErrors {
    /// Of the deflection, m: that of w plus the weighted errors of the corner deflections the
    /// bilinear support plane subtracts (a bound: the errors add).
    pub deflection: f64,
    /// Of each spring force, N, in the order of `spring_forces` (k times the corner's error).
    pub spring_forces: Vec<f64>,
    /// Of the rock's total energy over E₀.
    pub rock_total_ratio: f64,
    /// Of the rock's stored energy over E₀.
    pub rock_stored_ratio: f64,
    /// Of the plate's energy over E₀.
    pub plate_ratio: f64,
    /// Of the springs' energy over E₀.
    pub spring_ratio: f64,
    /// Of the sphere's kinetic energy over E₀.
    pub sphere_kinetic_ratio: f64,
}

/// Responses of one body at one point and velocity, by one model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResponseRow {
    /// Which model.
    pub model: ModelKind,
    /// Body name.
    pub body: String,
    /// Support set name.
    pub condition: String,
    /// m.
    pub x: f64,
    /// m.
    pub z: f64,
    /// m/s.
    pub velocity: f64,
    /// The values, or why there are none.
    pub outcome: RowOutcome<ResponseValues>,
}

impl ResponseRow {
    /// The values, if the model answered.
    pub fn values(&self) -> Option<&ResponseValues> {
        match &self.outcome {
            RowOutcome::Computed(v) => Some(v),
            RowOutcome::NotApplicable { .. } => None,
        }
    }
}

/// The yield velocity at one point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct YieldValues {
    /// Total compliance C, m/N (quasi-static models).
    pub compliance: Option<f64>,
    /// Its estimated absolute error, m/N.
    pub compliance_error: Option<f64>,
    /// δ_my of eq. 51, m.
    pub yield_compression: f64,
    /// v_y of eqs. 52-54 (or the transient root), m/s.
    pub yield_velocity: f64,
    /// Estimated absolute error of v_y, m/s.
    pub yield_velocity_error: Option<f64>,
    /// Validity at v = v_y.
    pub validity: Validity,
}

/// The yield velocity of one body at one point, by one model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct YieldRow {
    /// Which model.
    pub model: ModelKind,
    /// Body name.
    pub body: String,
    /// Support set name.
    pub condition: String,
    /// m.
    pub x: f64,
    /// m.
    pub z: f64,
    /// The values, or why there are none.
    pub outcome: RowOutcome<YieldValues>,
}

impl YieldRow {
    /// The values, if the model answered.
    pub fn values(&self) -> Option<&YieldValues> {
        match &self.outcome {
            RowOutcome::Computed(v) => Some(v),
            RowOutcome::NotApplicable { .. } => None,
        }
    }
}

/// Everything computed for a scene.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Results {
    /// Scene name.
    pub scene: String,
    /// Responses, model by model.
    pub responses: Vec<ResponseRow>,
    /// Yield velocities, model by model.
    pub yields: Vec<YieldRow>,
}

impl Results {
    /// Appends another model's rows.
    pub fn extend(&mut self, other: Results) {
        self.responses.extend(other.responses);
        self.yields.extend(other.yields);
    }

    /// A one-line count of rows by status: computed, valid, beyond validity (by criterion),
    /// not applicable.
    pub fn summary(&self) -> Summary {
        let mut s = Summary::default();
        let validities = self
            .responses
            .iter()
            .map(|r| r.values().map(|v| v.validity))
            .chain(self.yields.iter().map(|r| r.values().map(|v| v.validity)));
        for v in validities {
            match v {
                None => s.not_applicable += 1,
                Some(v) => {
                    s.computed += 1;
                    if v.all_valid() {
                        s.valid += 1;
                    }
                    for f in v.flags() {
                        match f {
                            validity::FLAG_ELASTIC => s.beyond_elastic += 1,
                            validity::FLAG_QUASI_STATIC => s.not_quasi_static += 1,
                            validity::FLAG_THIN_PLATE => s.beyond_thin_plate += 1,
                            validity::FLAG_REGIME => s.outside_regime_rule += 1,
                            validity::FLAG_UNFINISHED => s.unfinished += 1,
                            validity::FLAG_DISCRETISATION => s.above_tolerance += 1,
                            _ => s.recontact += 1,
                        }
                    }
                }
            }
        }
        s
    }
}

/// Counts of rows by validity.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Summary {
    /// Rows with values.
    pub computed: usize,
    /// Rows inside every criterion.
    pub valid: usize,
    /// Rows beyond the elastic range.
    pub beyond_elastic: usize,
    /// Rows where the quasi-static assumption fails.
    pub not_quasi_static: usize,
    /// Rows beyond the thin-plate range.
    pub beyond_thin_plate: usize,
    /// Transient rows whose sphere must strike again.
    pub recontact: usize,
    /// Quasi-static rows the closed-form regime rule does not trust.
    pub outside_regime_rule: usize,
    /// Transient rows whose window ended before the sphere had provably left.
    pub unfinished: usize,
    /// Transient rows whose error estimate stayed above the tolerance (the budget ran out).
    pub above_tolerance: usize,
    /// Rows the model does not describe.
    pub not_applicable: usize,
}
