//! The signals study (`impact signals`): the scene's impacts through the reduced-order model
//! (coupled::reduced), their first-contact numbers with the truncation error and validity,
//! and the sensor and corner time series.

use crate::progress::Progress;
use crate::settings::Settings;
use crate::Failure;
use coupled::reduced::plan::{run, ModelSummary, SceneImpact};
use scene::{slug, Scene};
use serde::Serialize;

/// What `impact signals` computed.
#[derive(Debug, Serialize)]
pub struct SignalRun {
    /// The reduced model of each support set.
    pub models: Vec<ModelSummary>,
    /// Every impact, its time series left out (they are in the CSV files).
    pub impacts: Vec<ImpactRow>,
}

/// One impact's numbers (SI).
#[derive(Debug, Serialize)]
pub struct ImpactRow {
    /// Support set name.
    pub condition: String,
    /// Body name.
    pub body: String,
    /// Impact point (x, z), m.
    pub point: (f64, f64),
    /// Velocity, m/s.
    pub velocity: f64,
    /// First-contact quantities and their truncation errors.
    pub quantities: coupled::transient::Quantities,
    /// The errors.
    pub errors: coupled::transient::Quantities,
    /// Contacts in the window.
    pub contacts: usize,
    /// Validity criteria.
    pub validity: coupled::Validity,
    /// The CSV file of its time series, relative to the output directory.
    pub file: String,
}

/// What `impact signals` computes: the run's numbers (serialized) and each impact's time
/// series (written as CSV by the renderer, never serialized whole).
#[derive(Debug, Serialize)]
pub struct SignalsData {
    /// The models and the impacts' numbers.
    pub run: SignalRun,
    /// Every impact with its time series, in the order of `run.impacts`.
    #[serde(skip)]
    pub impacts: Vec<SceneImpact>,
}

/// The file of impact `k` (from 0): `signals/<support set>/<body>-<k + 1>.csv`.
pub fn series_file(scene: &Scene, k: usize, imp: &SceneImpact) -> String {
    format!(
        "signals/{}/{}-{:04}.csv",
        slug(&scene.conditions[imp.condition].name),
        slug(&scene.bodies[imp.body].name),
        k + 1
    )
}

/// The scene's impacts through the reduced-order model.
pub fn compute(scene: &Scene, _settings: &Settings, _progress: &dyn Progress) -> Result<SignalsData, Failure> {
    let (models, impacts) = run(scene)?;
    let rows = impacts
        .iter()
        .enumerate()
        .map(|(k, imp)| {
            let o = &imp.result.outcome;
            ImpactRow {
                condition: scene.conditions[imp.condition].name.clone(),
                body: scene.bodies[imp.body].name.clone(),
                point: imp.point,
                velocity: imp.velocity,
                quantities: imp.quantities,
                errors: imp.errors,
                contacts: o.contacts.len() + usize::from(o.unfinished_contact.is_some()),
                validity: imp.validity,
                file: series_file(scene, k, imp),
            }
        })
        .collect();
    Ok(SignalsData { run: SignalRun { models, impacts: rows }, impacts })
}
