//! The rows of a quasi-static compliance model: the paper's energy balance (eqs. 14-20)
//! for the responses and eqs. 51-54 for the yield velocity, with the errors that follow
//! from the compliance's error estimate.

use super::rows::{Evidence, ResponseRow, ResponseValues, Results, RowOutcome, YieldRow, YieldValues};
use super::{hertz_time, impact_of, plate_theory, regime_rule, ModelKind};
use crate::compliance::{ComplianceModel, Estimate};
use crate::error::ModelError;
use crate::scene::{Analysis, Scene};
use crate::supports::SupportSet;
use crate::validity::{self, Validity};
use analytic::{respond, yield_velocity, DruckerPrager, Impact, Method, PointCompliance, Response, Sphere};

/// The quasi-static responses of one case, with the errors that follow from the
/// compliance's error estimate (the balance re-solved at C + error).
fn quasi_static_values(
    scene: &Scene,
    set: &SupportSet,
    imp: &Impact,
    estimate: &Estimate,
    delta_my: f64,
    period: f64,
    kind: ModelKind,
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
        thin_plate: plate_theory(scene, kind),
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
/// are the fundamental periods of the scene's support sets
/// ([`fundamental_periods`](super::fundamental_periods)).
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
                        let outcome = match &estimate {
                            Err(reason) => RowOutcome::NotApplicable { reason: reason.clone() },
                            Ok(est) => {
                                let d_my = dp.yield_compression(body.radius(), imp.contact_stiffness);
                                let (_, values) = quasi_static_values(scene, set, &imp, est, d_my, period, kind)
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
                        Ok(est) => RowOutcome::Computed(yield_values(scene, set, body, &dp, est, period, kind)),
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
    kind: ModelKind,
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
            thin_plate: plate_theory(scene, kind),
            recontact: None,
            regime: Some(regime_rule(scene, set, &at_yield, c)),
            finished: None,
            discretisation: None,
        },
    }
}
