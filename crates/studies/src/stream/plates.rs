//! The plates a support set's streams strike, built and checked before any stream runs: the
//! scene's plate and each plate of its `plate_sweep`, every one its own reduced model (the
//! modes the scene's rule gives that plate), its segments' warm-up against its own slowest
//! decay ([`super::segments`]), and the chain's band against its highest kept mode.
//!
//! The band: the modes left out answer above the highest kept mode f_N, so a recording
//! through a chain of gain |H(f)| misses at most what the chain passes there,
//! max_{f ≥ f_N} |H(f)| ([`identify::measurement::Chain::gain_above`]). Where that is within
//! the chain's band tolerance the recorded features are resolved by the modes; beyond it they
//! carry the truncation, and the stream page flags the plate.

use super::segments;
use crate::identify::sensors::{reduced_settings, spec};
use crate::progress::Progress;
use crate::Failure;
use coupled::identification::Instrument;
use coupled::reduced::ReducedModel;
use identify::stream::StreamStudy;
use scene::{Scene, SupportSet};
use serde::Serialize;

/// What the band table calls the scene's own plate.
pub const SCENE_PLATE: &str = "the scene's plate";

/// One support set's reduced models: the scene's plate's, then each swept plate's in the
/// order of the scene's `plate_sweep`, with the scene as it stands on that plate.
pub(super) struct Plates {
    pub main: ReducedModel,
    pub swept: Vec<(Scene, ReducedModel)>,
}

/// How far one plate's kept modes resolve what the chain records.
#[derive(Debug, Clone, Serialize)]
pub struct Band {
    /// The plate: [`SCENE_PLATE`], or a swept plate's shift ("plate 12 mm thick").
    pub plate: String,
    /// The support set.
    pub support_set: String,
    /// Modes kept.
    pub modes: usize,
    /// The highest kept mode's frequency f_N, Hz.
    pub highest_mode_hz: f64,
    /// The chain's largest gain at or above f_N (None without a chain): what the modes left
    /// out could pass into the recording.
    pub gain_above_highest: Option<f64>,
    /// Whether that gain is within the chain's band tolerance (None without a chain).
    pub resolved: Option<bool>,
}

/// Every support set's plates, built and checked in the scene's order, with their bands:
/// what goes wrong on a swept plate names it, and nothing has run yet when it does.
pub(super) fn every_set(
    scene: &Scene,
    study: &StreamStudy,
    progress: &dyn Progress,
) -> Result<Vec<(Plates, Vec<Band>)>, Failure> {
    progress.start(scene.conditions.len() * (1 + scene.stream_plate_sweep.len()), "stream: the plates' models");
    let built = scene.conditions.iter().map(|set| of_set(scene, study, set, progress)).collect();
    progress.finish();
    built
}

/// The plates of support set `set` and their bands.
fn of_set(
    scene: &Scene,
    study: &StreamStudy,
    set: &SupportSet,
    progress: &dyn Progress,
) -> Result<(Plates, Vec<Band>), Failure> {
    let main = model_on(scene, set)?;
    let mut bands = vec![checked(scene, study, (set, &main), SCENE_PLATE)?];
    progress.advance(1);
    let mut swept = Vec::with_capacity(scene.stream_plate_sweep.len());
    for other in &scene.stream_plate_sweep {
        let on = Scene { plate: other.plate, ..scene.clone() };
        let named = |e: Failure| -> Failure { format!("stream.plate_sweep, the {}: {e}", other.shift).into() };
        let model = model_on(&on, set).map_err(named)?;
        bands.push(checked(&on, study, (set, &model), &other.shift).map_err(named)?);
        swept.push((on, model));
        progress.advance(1);
    }
    Ok((Plates { main, swept }, bands))
}

/// The reduced model of `scene`'s plate on `set`, with the modes the scene's rule gives it.
fn model_on(scene: &Scene, set: &SupportSet) -> Result<ReducedModel, Failure> {
    Ok(ReducedModel::new(&scene.plate, set, reduced_settings(scene, set)?)?)
}

/// The band of `model` (on `scene`'s plate) as the scene's sensors and chain record it, once
/// its segments' warm-up passes.
fn checked(
    scene: &Scene,
    study: &StreamStudy,
    (set, model): (&SupportSet, &ReducedModel),
    plate: &str,
) -> Result<Band, Failure> {
    let instrument = Instrument::new(model, &scene.plate, &spec(scene, scene.signals.sensors.clone()), scene)?;
    segments::cutting(&instrument, study)?;
    let highest = instrument.highest_mode_hz();
    let chain = instrument.chain();
    let gain = chain.map(|c| c.gain_above(highest));
    Ok(Band {
        plate: plate.to_string(),
        support_set: set.name.clone(),
        modes: instrument.modes(),
        highest_mode_hz: highest,
        gain_above_highest: gain,
        resolved: chain.zip(gain).map(|(c, g)| g <= c.spec().band_tolerance),
    })
}
