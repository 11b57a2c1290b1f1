//! The plan: compute exactly what a scene asks for, with any plate model.
//!
//! A [`ComplianceModel`] turns (condition, x, z) into a [`PointCompliance`]; everything
//! downstream (energy balance, responses, yield) is the analytic crate and does not know
//! which model produced C.

use crate::scene::{Analysis, NamedCondition, Scene};
use analytic::{
    beam_compliance, contact_stiffness, respond, yield_velocity, DruckerPrager, Impact, Method, NotConverged,
    PointCompliance, Response, Sphere,
};
use serde::Serialize;

/// A source of plate compliance at impact points.
pub trait ComplianceModel {
    /// Short name for tables ("beam", "plate FE").
    fn name(&self) -> &str;
    /// Whether the model resolves the width coordinate z.
    fn resolves_width(&self) -> bool;
    /// Compliance of the plate under `condition` at (x, z), metres.
    fn compliance(&self, condition: &NamedCondition, x: f64, z: f64) -> Result<PointCompliance, RunError>;
}

/// The paper's beam model (section II).
pub struct BeamModel<'a> {
    pub plate: &'a analytic::Plate,
}

impl ComplianceModel for BeamModel<'_> {
    fn name(&self) -> &str {
        "beam"
    }
    fn resolves_width(&self) -> bool {
        false
    }
    fn compliance(&self, condition: &NamedCondition, x: f64, _z: f64) -> Result<PointCompliance, RunError> {
        Ok(beam_compliance(self.plate, condition.condition, x)?)
    }
}

/// A failure while computing a scene.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    #[error(transparent)]
    Outside(#[from] analytic::OutsideBeam),
    #[error("{context}: {source}")]
    NotConverged { context: String, source: NotConverged },
    #[error("{0}")]
    Model(String),
}

/// One impact point of a condition: where, and the compliance there.
#[derive(Debug, Clone, Serialize)]
pub struct PointRow {
    pub condition: String,
    /// m.
    pub x: f64,
    /// m; absent for models that do not resolve the width.
    pub z: Option<f64>,
    pub compliance: PointCompliance,
}

/// Responses of one body at one point and velocity.
#[derive(Debug, Clone, Serialize)]
pub struct ResponseRow {
    pub body: String,
    pub condition: String,
    pub x: f64,
    pub z: Option<f64>,
    pub velocity: f64,
    pub compliance: f64,
    pub response: Response,
}

/// The yield velocity of one body at one point.
#[derive(Debug, Clone, Serialize)]
pub struct YieldRow {
    pub body: String,
    pub condition: String,
    pub x: f64,
    pub z: Option<f64>,
    pub compliance: f64,
    /// δ_my of eq. 51, m.
    pub yield_compression: f64,
    /// v_y of eqs. 52-54, m/s.
    pub yield_velocity: f64,
}

/// Everything computed for a scene by one model.
#[derive(Debug, Clone, Serialize)]
pub struct Results {
    pub model: String,
    pub scene: String,
    pub responses: Vec<ResponseRow>,
    pub yields: Vec<YieldRow>,
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

/// Compliances at every point of every condition (z only where the model resolves it).
pub fn compliances(scene: &Scene, model: &dyn ComplianceModel) -> Result<Vec<PointRow>, RunError> {
    let zs: Vec<Option<f64>> =
        if model.resolves_width() { scene.points.z.iter().map(|&z| Some(z)).collect() } else { vec![None] };
    let mut rows = Vec::new();
    for cond in &scene.conditions {
        for &z in &zs {
            for &x in &scene.points.x {
                let compliance = model.compliance(cond, x, z.unwrap_or(scene.plate.width() / 2.0))?;
                rows.push(PointRow { condition: cond.name.clone(), x, z, compliance });
            }
        }
    }
    Ok(rows)
}

/// Runs the scene's analyses with `model`.
pub fn run(scene: &Scene, model: &dyn ComplianceModel) -> Result<Results, RunError> {
    let points = compliances(scene, model)?;
    let mut responses = Vec::new();
    let mut yields = Vec::new();
    for body in &scene.bodies {
        let dp = DruckerPrager::of(body);
        for pt in &points {
            let c = pt.compliance.total();
            if scene.wants(Analysis::Responses) {
                for &v in &scene.velocities {
                    let imp = impact_of(scene, body, v);
                    let response =
                        respond(&imp, &pt.compliance, scene.solver).map_err(|source| RunError::NotConverged {
                            context: format!("{} on {} at x = {} m, v = {} m/s", body.name, pt.condition, pt.x, v),
                            source,
                        })?;
                    responses.push(ResponseRow {
                        body: body.name.clone(),
                        condition: pt.condition.clone(),
                        x: pt.x,
                        z: pt.z,
                        velocity: v,
                        compliance: c,
                        response,
                    });
                }
            }
            if scene.wants(Analysis::YieldVelocity) {
                // The velocity does not enter v_y; any positive value builds the balance.
                let imp = impact_of(scene, body, 1.0);
                let d = dp.yield_compression(body.radius(), imp.contact_stiffness);
                yields.push(YieldRow {
                    body: body.name.clone(),
                    condition: pt.condition.clone(),
                    x: pt.x,
                    z: pt.z,
                    compliance: c,
                    yield_compression: d,
                    yield_velocity: yield_velocity(body, &imp, c, d),
                });
            }
        }
    }
    Ok(Results { model: model.name().to_string(), scene: scene.name.clone(), responses, yields })
}

/// Solves one case with the paper's recursion and with the bracketed solver, converged or
/// not, for the solver study.
pub fn both_solvers(imp: &Impact, c: f64) -> (analytic::Solution, analytic::Solution) {
    let bal = imp.balance(c);
    (bal.attempt(Method::paper()), bal.attempt(Method::default()))
}
