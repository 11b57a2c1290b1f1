//! The plan: compute exactly what a scene asks for, with any model, and say of every
//! result whether it is inside the model's assumptions.
//!
//! A [`ComplianceModel`] turns (support set, x, z) into an [`Estimate`]; the energy balance,
//! the responses and the yield model are the `analytic` crate's and do not know which model
//! produced C. The transient model ([`crate::transient`]) answers the same questions by
//! integrating the impact in time. Every model fills the same rows, so a table, a CSV file
//! or a JSON document has one schema with a `model` column.

use crate::compliance::plate::corner_weights;
use crate::compliance::{ComplianceModel, Estimate};
use crate::error::ModelError;
use crate::scene::{Analysis, Scene};
use crate::supports::SupportSet;
use crate::transient::estimate::{Discretisation, Estimated, Ladder};
use crate::transient::{case::striker, LawKind, Outcome, Striker, TransientCase, TransientSettings};
use crate::validity::{self, Validity};
use analytic::{
    contact_stiffness, respond, yield_velocity, DruckerPrager, Impact, Method, PointCompliance, Response, Sphere,
};
use plate_fem::Corner;
use serde::Serialize;

/// Which model answers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ModelKind {
    /// The paper's beam (section II): closed form, Con 1-3 only.
    Beam,
    /// Kirchhoff plate finite elements, quasi-static, Richardson-extrapolated.
    Plate,
    /// The plate finite elements in time with the Flores contact: no quasi-static assumption.
    Transient,
}

impl ModelKind {
    /// Every model, in the order tables list them.
    pub const ALL: [ModelKind; 3] = [ModelKind::Beam, ModelKind::Plate, ModelKind::Transient];

    /// The name in tables and files.
    pub fn key(self) -> &'static str {
        match self {
            ModelKind::Beam => "beam",
            ModelKind::Plate => "plate",
            ModelKind::Transient => "transient",
        }
    }
}

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
        /// The impulse of all of them, N·s.
        total_impulse: f64,
        /// Its estimated absolute error where the impact is one contact that ended (v₀ times
        /// the restitution's error, impulse m(v₀ - v_f)); None after several contacts, whose
        /// later ones the estimate's runs do not follow.
        total_impulse_error: Option<f64>,
        /// Sphere velocity at the end of the run, m/s (negative: away from the plate).
        final_velocity: f64,
        /// Its estimated absolute error, m/s (v₀ times the restitution's; one contact only).
        final_velocity_error: Option<f64>,
        /// Whether the run proved that no further contact can occur (else the window ended).
        left_for_good: bool,
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

/// The impact of `body` on the scene's plate at `velocity`.
pub fn impact_of(scene: &Scene, body: &Sphere, velocity: f64) -> Impact {
    Impact {
        contact_stiffness: contact_stiffness(body, scene.plate.material()),
        mass: body.mass(),
        restitution: scene.restitution,
        velocity,
    }
}

/// The fundamental period T₁ of the plate on each of the scene's support sets (plate FE on
/// the transient model's mesh), for the quasi-static criterion.
pub fn fundamental_periods(scene: &Scene) -> Result<Vec<f64>, ModelError> {
    let case = TransientCase::new(&scene.plate, TransientSettings::default())?;
    scene.conditions.iter().map(|c| case.fundamental_period(&c.supports)).collect()
}

/// Hertz's contact time on a rigid target, a lower bound of the contact time on any plate.
fn hertz_time(imp: &Impact) -> f64 {
    crate::transient::HERTZ_TIME
        * (imp.mass * imp.mass / (imp.contact_stiffness * imp.contact_stiffness * imp.velocity)).powf(0.2)
}

/// The closed-form regime rule ([`crate::regimes`]) for the impact `imp` at a point of
/// compliance `c` of `set`.
fn regime_rule(scene: &Scene, set: &SupportSet, imp: &Impact, c: f64) -> validity::Criterion {
    let s = Striker {
        k: imp.contact_stiffness,
        restitution: imp.restitution,
        mass: imp.mass,
        velocity: imp.velocity,
        law: crate::transient::ContactLaw::Flores(crate::transient::law::Flores),
    };
    crate::regimes::rule(crate::regimes::RuleInputs::of(&s, &scene.plate, set, c))
}

fn thin_plate(scene: &Scene) -> validity::Criterion {
    let p = &scene.plate;
    validity::thin_plate(p.thickness(), p.length(), p.width())
}

/// The quasi-static responses of one case, with the errors that follow from the
/// compliance's error estimate (the balance re-solved at C + error).
fn quasi_static_values(
    scene: &Scene,
    set: &SupportSet,
    imp: &Impact,
    estimate: &Estimate,
    delta_my: f64,
    period: f64,
) -> Result<(Response, ResponseValues), analytic::NotConverged> {
    let r = respond(imp, &estimate.compliance, scene.solver)?;
    // The energy identity of eq. 14: the rock's and the plate's shares of E₀ sum to one
    // within the balance's own residual. A result that fails it is not a root, whatever
    // the solver reported.
    let shares = r.rock_total_ratio + r.plate_ratio + r.spring_ratio;
    if (shares - 1.0).abs() > 10.0 * tolerance(scene.solver) + 1e-12 {
        return Err(analytic::NotConverged(r.solution));
    }
    let (force_error, compression_error) = if estimate.error_estimate > 0.0 && estimate.error_estimate.is_finite() {
        let c = estimate.compliance.total() + estimate.error_estimate;
        let d = imp.balance(c).solve(scene.solver)?.delta;
        let p = imp.contact_stiffness * d.powf(1.5);
        (Some((p - r.contact_force).abs()), Some((d - r.compression).abs()))
    } else {
        (Some(0.0), Some(0.0))
    };
    let validity = Validity {
        elastic: Some(validity::elastic(r.compression, delta_my)),
        quasi_static: Some(validity::quasi_static(hertz_time(imp), period)),
        thin_plate: thin_plate(scene),
        recontact: None,
        regime: Some(regime_rule(scene, set, imp, estimate.compliance.total())),
        finished: None,
        discretisation: None,
    };
    let values = ResponseValues {
        compliance: Some(estimate.compliance.total()),
        compliance_error: Some(estimate.error_estimate),
        contact_force: r.contact_force,
        contact_force_error: force_error,
        compression: r.compression,
        compression_error,
        deflection: r.deflection,
        spring_forces: r.spring_forces.clone(),
        rock_total_ratio: r.rock_total_ratio,
        rock_stored_ratio: r.rock_stored_ratio,
        plate_ratio: r.plate_ratio,
        spring_ratio: r.spring_ratio,
        sphere_kinetic_ratio: 0.0,
        state_errors: None,
        evidence: Evidence::Balance { iterations: r.solution.iterations, residual: r.solution.residual },
        validity,
    };
    Ok((r, values))
}

/// The relative residual a solver is asked to reach.
fn tolerance(m: Method) -> f64 {
    match m {
        Method::Recursion { tolerance, .. } | Method::Bracketed { tolerance, .. } => tolerance,
    }
}

/// The paper's responses (eqs. 14-20) for one case, as the `analytic` crate gives them.
pub fn response(scene: &Scene, imp: &Impact, c: &PointCompliance) -> Result<Response, analytic::NotConverged> {
    respond(imp, c, scene.solver)
}

/// Runs the scene's responses and yield velocities with a quasi-static `model`; `periods`
/// are the fundamental periods of the scene's support sets ([`fundamental_periods`]).
pub fn run(
    scene: &Scene,
    model: &dyn ComplianceModel,
    kind: ModelKind,
    periods: &[f64],
) -> Result<Results, ModelError> {
    let points = scene.point_pairs();
    let mut responses = Vec::new();
    let mut yields = Vec::new();
    for body in &scene.bodies {
        let dp = DruckerPrager::of(body);
        for (ci, set) in scene.conditions.iter().enumerate() {
            let period = periods.get(ci).copied().ok_or_else(|| ModelError::Missing("fundamental period".into()))?;
            for &(x, z) in &points {
                let estimate = match model.compliance(set, x, z) {
                    Ok(e) => Ok(e),
                    Err(ModelError::NotApplicable { reason, .. }) => Err(reason),
                    Err(e) => return Err(e),
                };
                if scene.wants(Analysis::Responses) {
                    for &v in &scene.velocities {
                        let imp = impact_of(scene, body, v);
                        let outcome =
                            match &estimate {
                                Err(reason) => RowOutcome::NotApplicable { reason: reason.clone() },
                                Ok(est) => {
                                    let d_my = dp.yield_compression(body.radius(), imp.contact_stiffness);
                                    let (_, values) = quasi_static_values(scene, set, &imp, est, d_my, period)
                                        .map_err(|source| ModelError::NotConverged {
                                            context: format!(
                                                "{} on {} at (x, z) = ({x}, {z}) m, v = {v} m/s",
                                                body.name, set.name
                                            ),
                                            source,
                                        })?;
                                    RowOutcome::Computed(values)
                                }
                            };
                        responses.push(ResponseRow {
                            model: kind,
                            body: body.name.clone(),
                            condition: set.name.clone(),
                            x,
                            z,
                            velocity: v,
                            outcome,
                        });
                    }
                }
                if scene.wants(Analysis::YieldVelocity) {
                    let outcome = match &estimate {
                        Err(reason) => RowOutcome::NotApplicable { reason: reason.clone() },
                        Ok(est) => RowOutcome::Computed(yield_values(scene, set, body, &dp, est, period)),
                    };
                    yields.push(YieldRow {
                        model: kind,
                        body: body.name.clone(),
                        condition: set.name.clone(),
                        x,
                        z,
                        outcome,
                    });
                }
            }
        }
    }
    Ok(Results { scene: scene.name.clone(), responses, yields })
}

/// The yield velocity of eqs. 51-54 for a compliance estimate, with the error that follows
/// from the compliance's error.
fn yield_values(
    scene: &Scene,
    set: &SupportSet,
    body: &Sphere,
    dp: &DruckerPrager,
    est: &Estimate,
    period: f64,
) -> YieldValues {
    // The velocity does not enter v_y; any positive value builds the balance.
    let imp = impact_of(scene, body, 1.0);
    let d = dp.yield_compression(body.radius(), imp.contact_stiffness);
    let c = est.compliance.total();
    let v_y = yield_velocity(body, &imp, c, d);
    let error = if est.error_estimate.is_finite() {
        (yield_velocity(body, &imp, c + est.error_estimate, d) - v_y).abs()
    } else {
        0.0
    };
    let at_yield = Impact { velocity: v_y, ..imp };
    YieldValues {
        compliance: Some(c),
        compliance_error: Some(est.error_estimate),
        yield_compression: d,
        yield_velocity: v_y,
        yield_velocity_error: Some(error),
        validity: Validity {
            elastic: None,
            quasi_static: Some(validity::quasi_static(hertz_time(&at_yield), period)),
            thin_plate: thin_plate(scene),
            recontact: None,
            regime: Some(regime_rule(scene, set, &at_yield, c)),
            finished: None,
            discretisation: None,
        },
    }
}

/// The transient responses of one case, at the instant of maximum compression on the
/// integrator's interpolant, with the error estimates of `errors` when given.
#[allow(clippy::too_many_arguments)]
pub fn transient_values(
    scene: &Scene,
    set: &SupportSet,
    body: &Sphere,
    o: &Outcome,
    s: &crate::transient::Striker,
    dt: f64,
    (x, z): (f64, f64),
    errors: Option<&Estimated>,
) -> ResponseValues {
    let e0 = 0.5 * s.mass * s.velocity * s.velocity;
    let m = o.at_max_compression_interpolated;
    let corners = o.corners_at_max_compression_interpolated;
    let (l, b) = (scene.plate.length(), scene.plate.width());
    let delta = o.compression_max_interpolated;
    let p = s.force_at_max_compression(delta);
    let dp = DruckerPrager::of(body);
    let d_my = dp.yield_compression(body.radius(), s.k);
    // The plate's own deflection: w at the point minus the bilinear plane through the
    // corner deflections (zero at held corners), as in the quasi-static plate model.
    let weights = corner_weights(x, z, l, b);
    let mut support_plane = 0.0;
    let mut spring_forces = Vec::new();
    let mut springs = Vec::new();
    for c in Corner::ALL {
        let i = c.index();
        if let plate_fem::CornerSupport::Spring(k) = set.supports.corners[i] {
            spring_forces
                .push(analytic::SpringForce { name: format!("spring at {}", c.name()), force: k * corners[i] });
            support_plane += weights[i] * corners[i];
            springs.push((i, k));
        }
    }
    let state_errors = errors.map(|e| {
        let se = e.state_error;
        StateErrors {
            deflection: se.plate_displacement
                + springs.iter().map(|&(i, _)| weights[i].abs() * se.corners[i]).sum::<f64>(),
            spring_forces: springs.iter().map(|&(i, k)| k * se.corners[i]).collect(),
            rock_total_ratio: se.rock_total / e0,
            rock_stored_ratio: se.rock_stored / e0,
            plate_ratio: se.plate / e0,
            spring_ratio: se.springs / e0,
            sphere_kinetic_ratio: se.sphere_kinetic / e0,
        }
    });
    // One contact that ended: the rebound is the first contact's, -e v₀, so the final
    // velocity and the impulse m(v₀ - v_f) carry v₀ times the restitution's error.
    let single = o.contacts.len() == 1 && o.unfinished_contact.is_none() && o.left_at.is_some();
    let final_velocity_error = errors.filter(|_| single).map(|e| s.velocity * e.error.restitution.abs());
    // The first contact's numbers describe the whole impact only if there is no other.
    let recontact = Some(validity::Criterion::at_most("contacts", o.contacts.len() as f64, 1.0));
    ResponseValues {
        compliance: None,
        compliance_error: None,
        contact_force: p,
        contact_force_error: errors.map(|e| e.error.force_at_max_compression),
        compression: delta,
        compression_error: errors.map(|e| e.error.compression),
        deflection: m.plate_displacement - support_plane,
        spring_forces,
        rock_total_ratio: (m.contact + m.dissipated) / e0,
        rock_stored_ratio: m.contact / e0,
        plate_ratio: (m.plate_kinetic + m.plate_strain) / e0,
        spring_ratio: m.springs / e0,
        sphere_kinetic_ratio: m.sphere_kinetic / e0,
        state_errors,
        evidence: Evidence::Transient {
            steps: o.steps,
            time_step: dt,
            peak_force: o.force_max_interpolated,
            peak_force_error: errors.map(|e| e.error.peak_force),
            contact_time: o.contacts.first().map(|c| c.duration),
            contact_time_error: errors.map(|e| e.error.contact_time),
            apparent_restitution: o.apparent_restitution,
            restitution_error: errors.map(|e| e.error.restitution),
            elements: errors.map_or(0, |e| e.elements),
            steps_per_contact: s.hertz_time() / dt,
            relative_error: errors.map(|e| e.relative_error()),
            tolerance: errors.and_then(|e| e.tolerance),
            met_tolerance: errors.is_none_or(|e| e.met_tolerance),
            contacts: o.contacts.len() + usize::from(o.unfinished_contact.is_some()),
            total_impulse: o.total_impulse,
            total_impulse_error: final_velocity_error.map(|dv| s.mass * dv),
            final_velocity: o.final_velocity,
            final_velocity_error,
            left_for_good: o.left_at.is_some(),
        },
        validity: Validity {
            // Compressions beyond δ_my leave an elastic law's range; Thornton's law describes
            // the plastic contact beyond it (its yield onset is δ_my), so it carries no flag.
            elastic: s.law.is_elastic().then(|| validity::elastic(delta, d_my)),
            quasi_static: None,
            thin_plate: thin_plate(scene),
            recontact,
            regime: None,
            finished: Some(validity::finished(o.left_at.is_some())),
            // Where the ladder's budget ran out before the estimate met the tolerance, the
            // numbers are less accurate than asked: the status says so, not only the
            // discretisation column.
            discretisation: errors
                .and_then(|e| e.tolerance.map(|tol| validity::discretisation(e.relative_error(), tol))),
        },
    }
}

/// The striker of `body` on the scene's plate at `velocity`, with the scene's restitution and
/// contact law.
pub fn scene_striker(scene: &Scene, body: &Sphere, velocity: f64) -> Striker {
    law_striker(scene, body, velocity, scene.contact_law)
}

/// The striker of `body` on the scene's plate at `velocity` with the scene's restitution and
/// the contact law `law` in place of the scene's: the same sphere under Hertz, Flores or
/// Thornton, for comparing the laws on one impact.
pub fn law_striker(scene: &Scene, body: &Sphere, velocity: f64, law: LawKind) -> Striker {
    Striker { law: law.law_for(body), ..striker(&scene.plate, body, scene.restitution, velocity) }
}

/// One transient response row's values with their error estimate, and the estimate itself
/// (its `outcome` is the run the values come from, with its history), on the discretisation
/// `disc` over the plate's mesh `ladder` ([`Discretisation::estimate`]). What
/// [`run_transient`] computes for each of its rows.
#[allow(clippy::too_many_arguments)]
pub fn transient_response(
    scene: &Scene,
    disc: Discretisation,
    ladder: &mut Ladder,
    set: &SupportSet,
    body: &Sphere,
    (x, z): (f64, f64),
    velocity: f64,
) -> Result<(ResponseValues, Estimated), ModelError> {
    let s = scene_striker(scene, body, velocity);
    let e = disc.estimate(ladder, set, &s, (x, z))?;
    let dt = s.hertz_time() / e.steps_per_contact;
    let values = transient_values(scene, set, body, &e.outcome, &s, dt, (x, z), Some(&e));
    Ok((values, e))
}

/// Runs the scene's responses with the transient model (yield velocities by the transient
/// model are the velocity at which the transient δ_max reaches δ_my). Every response carries
/// the error estimate of [`mod@crate::transient::estimate`] on the discretisation the scene asks
/// for ([`Scene::transient_discretisation`]): fixed settings, or per case the coarsest mesh
/// and step whose estimate meets a tolerance.
pub fn run_transient(scene: &Scene) -> Result<Results, ModelError> {
    run_transient_observed(scene, &mut || {})
}

/// How many cases [`run_transient`] computes for `scene`: one per body, support set, point
/// and velocity for the responses, and one per body, support set and point for the yield
/// velocities, as the scene asks.
pub fn transient_case_count(scene: &Scene) -> usize {
    let per_point = if scene.wants(Analysis::Responses) { scene.velocities.len() } else { 0 }
        + usize::from(scene.wants(Analysis::YieldVelocity));
    scene.bodies.len() * scene.conditions.len() * scene.points.len() * per_point
}

/// [`run_transient`], calling `done` after each of its [`transient_case_count`] cases (a
/// caller's progress display).
pub fn run_transient_observed(scene: &Scene, done: &mut dyn FnMut()) -> Result<Results, ModelError> {
    let disc = scene.transient_discretisation;
    let mut ladder = Ladder::new(&scene.plate, disc.start())?;
    let points = scene.point_pairs();
    let mut responses = Vec::new();
    let mut yields = Vec::new();
    for body in &scene.bodies {
        for set in &scene.conditions {
            for &(x, z) in &points {
                if scene.wants(Analysis::Responses) {
                    for &v in &scene.velocities {
                        let (values, _) = transient_response(scene, disc, &mut ladder, set, body, (x, z), v)?;
                        responses.push(ResponseRow {
                            model: ModelKind::Transient,
                            body: body.name.clone(),
                            condition: set.name.clone(),
                            x,
                            z,
                            velocity: v,
                            outcome: RowOutcome::Computed(values),
                        });
                        done();
                    }
                }
                if scene.wants(Analysis::YieldVelocity) {
                    // The discretisation is chosen at the root search's start, the rigid-target
                    // yield velocity, and its relative error in δ_max carried to v_y through
                    // d ln δ_max/d ln v ≈ 0.8.
                    let k = contact_stiffness(body, scene.plate.material());
                    let d_my = DruckerPrager::of(body).yield_compression(body.radius(), k);
                    let v_rigid = yield_velocity(body, &impact_of(scene, body, 1.0), 0.0, d_my);
                    let s = Striker {
                        law: scene.contact_law.law_for(body),
                        ..striker(&scene.plate, body, scene.restitution, v_rigid)
                    };
                    let e = disc.estimate(&mut ladder, set, &s, (x, z))?;
                    let level = (e.elements / disc.start().elements).max(1).trailing_zeros() as usize;
                    let case = ladder.levels(level)?.0;
                    let mut y = dynamic_yield_with(scene, case, e.steps_per_contact, set, body, x, z)?;
                    let relative = e.error.compression / e.values.compression;
                    if let Some(w) = y.yield_velocity_error.as_mut() {
                        *w += y.yield_velocity * relative / HERTZ_SLOPE;
                    }
                    yields.push(YieldRow {
                        model: ModelKind::Transient,
                        body: body.name.clone(),
                        condition: set.name.clone(),
                        x,
                        z,
                        outcome: RowOutcome::Computed(y),
                    });
                    done();
                }
            }
        }
    }
    Ok(Results { scene: scene.name.clone(), responses, yields })
}

/// Relative width to which the transient yield velocity is found.
pub const YIELD_ROOT_TOLERANCE: f64 = 1e-6;

/// d ln δ_max / d ln v of Hertz's contact on a rigid target (δ_max ∝ v^{4/5}): the first
/// step of the root search.
pub const HERTZ_SLOPE: f64 = 0.8;

/// The root of an increasing f(ln v) from `start`: (ln lo, ln hi) with f(lo) < 0 ≤ f(hi)
/// and hi/lo - 1 ≤ `tol`. Bracketed by secant steps from the slope [`HERTZ_SLOPE`], closed
/// by Illinois false position kept at least ~tol/2 inside the bracket (so the bracket
/// closes from both sides).
pub fn log_root(
    f: &mut impl FnMut(f64) -> Result<f64, ModelError>,
    start: f64,
    tol: f64,
) -> Result<(f64, f64), ModelError> {
    let width = tol.ln_1p();
    let lost = || ModelError::Missing("the transient yield velocity could not be bracketed".into());
    let (mut a, mut fa) = (start, f(start)?);
    let mut b = a - fa / HERTZ_SLOPE;
    let mut fb = f(b)?;
    let mut n = 0;
    while (fa < 0.0) == (fb < 0.0) {
        n += 1;
        if n > 60 || !fb.is_finite() {
            return Err(lost());
        }
        let slope = (fb - fa) / (b - a);
        let slope = if slope.is_finite() && slope > 0.1 { slope } else { HERTZ_SLOPE };
        let step = (-fb / slope).clamp(-std::f64::consts::LN_2, std::f64::consts::LN_2);
        // Overshoot a little so that the next point straddles the root.
        let step = step * 1.001 + step.signum() * width;
        (a, fa) = (b, fb);
        b += step;
        fb = f(b)?;
    }
    let (mut lo, mut flo, mut hi, mut fhi) = if fa < 0.0 { (a, fa, b, fb) } else { (b, fb, a, fa) };
    let mut side = 0;
    while hi - lo > width {
        n += 1;
        if n > 200 {
            return Err(lost());
        }
        let gap = (0.45 * width).min(0.5 * (hi - lo));
        let c = (lo * fhi - hi * flo) / (fhi - flo);
        let c = if c.is_finite() { c } else { 0.5 * (lo + hi) };
        let c = c.clamp(lo + gap, hi - gap);
        let fc = f(c)?;
        if fc < 0.0 {
            (lo, flo) = (c, fc);
            if side == -1 {
                fhi *= 0.5;
            }
            side = -1;
        } else {
            (hi, fhi) = (c, fc);
            if side == 1 {
                flo *= 0.5;
            }
            side = 1;
        }
    }
    Ok((lo, hi))
}

/// The dynamic yield velocity: the v at which the transient δ_max reaches δ_my of eq. 51
/// ([`crate::yield_root`]). The error is the final bracket's width, to a relative
/// [`YIELD_ROOT_TOLERANCE`].
pub fn dynamic_yield(
    scene: &Scene,
    case: &TransientCase,
    set: &SupportSet,
    body: &Sphere,
    x: f64,
    z: f64,
) -> Result<YieldValues, ModelError> {
    dynamic_yield_with(scene, case, case.settings().steps_per_contact, set, body, x, z)
}

/// [`dynamic_yield`] with `steps_per_contact` steps per Hertz time on `case`'s mesh.
pub fn dynamic_yield_with(
    scene: &Scene,
    case: &TransientCase,
    steps_per_contact: f64,
    set: &SupportSet,
    body: &Sphere,
    x: f64,
    z: f64,
) -> Result<YieldValues, ModelError> {
    let root = crate::yield_root::transient_yield_with(scene, case, steps_per_contact, set, body, x, z)?;
    Ok(YieldValues {
        compliance: None,
        compliance_error: None,
        yield_compression: root.yield_compression,
        yield_velocity: root.velocity,
        yield_velocity_error: Some(root.width),
        validity: Validity {
            elastic: None,
            quasi_static: None,
            thin_plate: thin_plate(scene),
            recontact: None,
            regime: None,
            finished: None,
            discretisation: None,
        },
    })
}

/// Solves one case with the paper's recursion and with the bracketed solver, converged or
/// not, for the solver study.
pub fn both_solvers(imp: &Impact, c: f64) -> (analytic::Solution, analytic::Solution) {
    let bal = imp.balance(c);
    (bal.attempt(Method::paper()), bal.attempt(Method::default()))
}
