//! A scene's impacts through the reduced model: every support set, body, transient point and
//! velocity, with the sensor signals of `[signals]`, an estimate of the truncation error and
//! the validity of each result.

use super::{ReducedModel, ReducedOutcome, ReducedSettings, SignalSpec};
use crate::error::ModelError;
use crate::scene::Scene;
use crate::transient::case::striker;
use crate::transient::Quantities;
use crate::validity::{self, Validity};
use analytic::DruckerPrager;
use serde::Serialize;

/// The reduced model of one support set, as built.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelSummary {
    /// The support set's name.
    pub condition: String,
    /// The settings.
    pub settings: ReducedSettings,
    /// Lowest and highest kept frequency, Hz.
    pub frequency_range_hz: (f64, f64),
    /// Largest relative residual ‖Kφ - ω²Mφ‖/‖Kφ‖ of the kept modes.
    pub worst_residual: f64,
}

/// One impact of a scene.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SceneImpact {
    /// Index into [`Scene::conditions`].
    pub condition: usize,
    /// Index into [`Scene::bodies`].
    pub body: usize,
    /// Impact point (x, z), m.
    pub point: (f64, f64),
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// The first-contact quantities (peak force, force and compression at maximum
    /// compression, contact time, apparent restitution).
    pub quantities: Quantities,
    /// Their truncation error estimate: the change from the model with half the modes
    /// (an upper estimate: on the paper's cases the error at N is 3 to 30 times below it).
    pub errors: Quantities,
    /// The impact with its signals.
    pub result: ReducedOutcome,
    /// Elastic range (elastic contact laws), thin plate, re-contact.
    pub validity: Validity,
}

/// Most impacts one scene may ask of [`run`]: each holds its signals in memory (10 channels
/// of 400 samples at the defaults, 32 kB) and costs about a millisecond with its error
/// estimate.
pub const MAX_IMPACTS: usize = 10_000;

/// Most memory the signals of one [`run`] may hold, bytes: every impact keeps its series
/// until the run is written (1e6 samples on 64 sensors once aborted at 6 GB).
pub const MAX_SIGNAL_BYTES: f64 = 2.0 * 1024.0 * 1024.0 * 1024.0;

/// Checks, before any work, that `count` impacts' signals fit [`MAX_SIGNAL_BYTES`]: samples
/// x channels (each sensor's quantities, up to four corners) x 8 bytes each.
fn check_memory(count: usize, spec: &SignalSpec) -> Result<(), ModelError> {
    let channels = spec.sensors.len() * spec.quantities.len() + 4;
    let bytes = count as f64 * channels as f64 * spec.samples() as f64 * 8.0;
    if bytes > MAX_SIGNAL_BYTES {
        return Err(ModelError::Missing(format!(
            "the signals would take {:.1} GB ({count} impacts x {channels} channels x {} samples, from signals.window_ms x signals.rate_hz and signals.sensors_mm); at most {:.1} GB: shorten signals.window_ms, lower signals.rate_hz, or use fewer sensors or impacts (support sets x bodies x transient points x velocities.m_per_s)",
            bytes / 1e9,
            spec.samples(),
            MAX_SIGNAL_BYTES / 1e9
        )));
    }
    Ok(())
}

/// Runs every support set x body x transient point x velocity of `scene` (built once per
/// support set, with its half-mode companion for the error estimate).
pub fn run(scene: &Scene) -> Result<(Vec<ModelSummary>, Vec<SceneImpact>), ModelError> {
    let count = scene.conditions.len() * scene.bodies.len() * scene.transient_points.len() * scene.velocities.len();
    if count == 0 {
        return Err(ModelError::Missing(
            "the signals need at least one velocity (velocities.m_per_s) and one impact point".into(),
        ));
    }
    if count > MAX_IMPACTS {
        return Err(ModelError::Missing(format!(
            "the scene asks for {count} impacts (support sets x bodies x transient points x velocities); at most {MAX_IMPACTS} are allowed"
        )));
    }
    let settings = scene.signals.reduced();
    let spec = scene.signals.spec();
    check_memory(count, &spec)?;
    let mut models = Vec::new();
    let mut impacts = Vec::with_capacity(count);
    for (ci, set) in scene.conditions.iter().enumerate() {
        let model = ReducedModel::new(&scene.plate, set, settings)?;
        let half =
            ReducedModel::new(&scene.plate, set, ReducedSettings { modes: (settings.modes / 2).max(1), ..settings })?;
        let f = model.modes().frequencies_hz();
        models.push(ModelSummary {
            condition: set.name.clone(),
            settings,
            frequency_range_hz: (f[0], f[f.len() - 1]),
            worst_residual: model.modes().residuals().iter().copied().fold(0.0, f64::max),
        });
        let probes = model.probes(&spec)?;
        let bare = half.probes(&super::SignalSpec { sensors: vec![], corners: false, ..spec.clone() })?;
        for (bi, body) in scene.bodies.iter().enumerate() {
            for &point in &scene.transient_points {
                for &v in &scene.velocities {
                    let mut s = striker(&scene.plate, body, scene.restitution, v);
                    s.law = scene.contact_law.law_for(body);
                    let result = model.impact(&s, point.0, point.1, &probes)?;
                    let coarse = half.impact(&s, point.0, point.1, &bare)?;
                    let q = Quantities::of(&result.outcome, &s);
                    let qc = Quantities::of(&coarse.outcome, &s);
                    let d_my = DruckerPrager::of(body).yield_compression(body.radius(), s.k);
                    let o = &result.outcome;
                    let validity = Validity {
                        elastic: s.law.is_elastic().then(|| validity::elastic(q.compression, d_my)),
                        quasi_static: None,
                        regime: None,
                        thin_plate: validity::thin_plate(
                            scene.plate.thickness(),
                            scene.plate.length(),
                            scene.plate.width(),
                        ),
                        recontact: Some(validity::Criterion::at_most(
                            "contacts",
                            (o.contacts.len() + usize::from(o.unfinished_contact.is_some())) as f64,
                            1.0,
                        )),
                        finished: Some(validity::finished(o.left_at.is_some())),
                        discretisation: None,
                    };
                    impacts.push(SceneImpact {
                        condition: ci,
                        body: bi,
                        point,
                        velocity: v,
                        errors: Quantities {
                            peak_force: (q.peak_force - qc.peak_force).abs(),
                            force_at_max_compression: (q.force_at_max_compression - qc.force_at_max_compression).abs(),
                            compression: (q.compression - qc.compression).abs(),
                            contact_time: (q.contact_time - qc.contact_time).abs(),
                            restitution: (q.restitution - qc.restitution).abs(),
                        },
                        quantities: q,
                        result,
                        validity,
                    });
                }
            }
        }
    }
    Ok((models, impacts))
}
