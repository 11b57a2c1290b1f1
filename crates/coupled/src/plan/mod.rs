//! The plan: compute exactly what a scene asks for, with any model, and say of every
//! result whether it is inside the model's assumptions.
//!
//! A [`ComplianceModel`](crate::ComplianceModel) turns (support set, x, z) into an
//! [`Estimate`](crate::Estimate); the energy balance, the responses and the yield model are
//! the `analytic` crate's and do not know which model produced C. The transient model
//! ([`crate::transient`]) answers the same questions by integrating the impact in time.
//! Every model fills the same rows, so a table, a CSV file or a JSON document has one schema
//! with a `model` column.
//!
//! - [`rows`]: the row schema, responses and yield velocities, with their evidence;
//! - [`quasi_static`]: the rows of a compliance model, by the paper's energy balance
//!   (eqs. 14-20) and yield velocity (eqs. 51-54);
//! - [`time_domain`]: the rows of the transient model at its instant of maximum compression;
//! - [`yield_velocity`]: the transient yield velocity, a root in ln v.

use crate::error::ModelError;
use crate::scene::Scene;
use crate::supports::SupportSet;
use crate::transient::{Striker, TransientCase, TransientSettings};
use crate::validity;
use analytic::{contact_stiffness, Impact, Sphere};
use serde::Serialize;

pub mod quasi_static;
pub mod rows;
pub mod time_domain;
pub mod yield_velocity;

pub use quasi_static::{response, run};
pub use rows::{
    Evidence, ResponseRow, ResponseValues, Results, RowOutcome, StateErrors, Summary, YieldRow, YieldValues,
};
pub use time_domain::{
    law_striker, run_transient, run_transient_observed, scene_striker, transient_case_count, transient_response,
    transient_values,
};
pub use yield_velocity::{
    both_solvers, close, dynamic_yield, dynamic_yield_with, log_root, log_root_near, Guess, HERTZ_SLOPE,
    YIELD_ROOT_TOLERANCE,
};

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
    /// Reissner-Mindlin plate finite elements (MITC4): Kirchhoff's plate with transverse
    /// shear, quasi-static, Richardson-extrapolated.
    Mindlin,
}

impl ModelKind {
    /// Every model, in the order tables list them.
    pub const ALL: [ModelKind; 4] = [ModelKind::Beam, ModelKind::Plate, ModelKind::Transient, ModelKind::Mindlin];

    /// The name in tables and files.
    pub fn key(self) -> &'static str {
        match self {
            ModelKind::Beam => "beam",
            ModelKind::Plate => "plate",
            ModelKind::Transient => "transient",
            ModelKind::Mindlin => "mindlin",
        }
    }
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
        gravity: 0.0,
    };
    crate::regimes::rule(crate::regimes::RuleInputs::of(&s, &scene.plate, set, c))
}

fn thin_plate(scene: &Scene) -> validity::Criterion {
    let p = &scene.plate;
    validity::thin_plate(p.thickness(), p.length(), p.width())
}

/// The range of the plate theory of `kind`: thin for the beam and Kirchhoff's plate,
/// moderately thick for Reissner-Mindlin's.
fn plate_theory(scene: &Scene, kind: ModelKind) -> validity::Criterion {
    let p = &scene.plate;
    match kind {
        ModelKind::Mindlin => validity::moderately_thick_plate(p.thickness(), p.length(), p.width()),
        ModelKind::Beam | ModelKind::Plate | ModelKind::Transient => thin_plate(scene),
    }
}
