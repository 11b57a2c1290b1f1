//! Where to put the sensors for a window detector: given a budget of B sensors of one
//! quantity and the candidate points of `[ensemble.placement]`, the points whose window
//! features together detect the turn to gangue-rich best, chosen one at a time
//! ([`identify::design::forward_selection`]).
//!
//! The study's streams are run again with a sensor at every candidate point (the same lumps,
//! the same chain and background), one stream at a time so that only one stream's channels
//! are held. A set of sensors is scored as the main run's groups are: the logistic detector
//! on every window feature of its channels, out of fold by the study's time blocks, its AUC
//! over the scored windows with the block-bootstrap interval, and its delay and false alarms.
//! Each step's gain over the step before is paired: both sets' AUCs on the same resampled
//! blocks. The cautions of the impact-level design hold here too: greedy selection need not
//! find the best set of more than one sensor, and each step's AUC is the largest of many
//! scored on the same folds (the winner's curse), so a gain means something only where its
//! interval excludes zero.

use super::recorder::Recorder;
use super::run::{features_of, record_one, select, simulate_one};
use super::score::{Score, Windows};
use super::segments;
use crate::identify::sensors::{channel_infos, spec};
use crate::progress::Progress;
use crate::Failure;
use coupled::identification::{quantity_of, Instrument};
use coupled::reduced::ReducedModel;
use identify::classify::{Logistic, RIDGE};
use identify::design::{forward_selection, Chosen};
use identify::detector::scale_flags;
use identify::features::FEATURES;
use identify::stream::StreamStudy;
use scene::Scene;
use serde::Serialize;

/// A support set's window-level sensor design.
#[derive(Debug, Clone, Serialize)]
pub struct WindowDesign {
    /// What each sensor records ("acceleration", ...).
    pub quantity: &'static str,
    /// The candidate grid's x, mm.
    pub x_mm: Vec<f64>,
    /// The candidate grid's z, mm.
    pub z_mm: Vec<f64>,
    /// Every step, in the order the sensors were added.
    pub steps: Vec<WindowDesignStep>,
    /// The features the chosen sensors' detector reads, by the size of their weight: the
    /// logistic model fitted on every window of the main run's streams, its weights on the
    /// standardised features (scale features as logarithms), largest magnitude first.
    pub features: Vec<FeatureWeight>,
}

/// One feature of one designed sensor in the detector fitted on every window.
#[derive(Debug, Clone, Serialize)]
pub struct FeatureWeight {
    /// The sensor, (x, z) mm.
    pub at_mm: (f64, f64),
    /// The feature's key ("peak", ...).
    pub feature: &'static str,
    /// Its weight on the standardised feature (0: a column without spread, dropped).
    pub weight: f64,
}

/// One sensor added to the window detector.
#[derive(Debug, Clone, Serialize)]
pub struct WindowDesignStep {
    /// Where, (x, z) mm.
    pub at_mm: (f64, f64),
    /// The detector on the sensors so far: window AUC with its interval, delay, false alarms.
    pub score: Score,
    /// Its AUC's gain over the step before (the first's over chance, 0.5).
    pub gain: f64,
    /// The gain's 95 % paired block-bootstrap interval.
    pub gain_interval: (f64, f64),
    /// The AUC had each grid point been added instead, `[x][z]` (None: already chosen).
    pub map: Vec<Vec<Option<f64>>>,
}

/// The design on `model` (a support set's), scored on the main run's windows `w`; None if the
/// scene asks for none.
pub(super) fn window_design(
    scene: &Scene,
    (ensemble, study): (&identify::Study, &StreamStudy),
    (model, w): (&ReducedModel, &Windows),
    progress: &dyn Progress,
) -> Result<Option<WindowDesign>, Failure> {
    let Some(design) = study.design else { return Ok(None) };
    let candidates = ensemble.candidates();
    let mut grid = spec(scene, candidates.clone());
    let quantity =
        quantity_of(design.measurand).ok_or("stream.design_quantity: a support's force is not placed on the plate")?;
    grid.quantities = vec![quantity];
    grid.corners = false;
    let instrument = Instrument::new(model, &scene.plate, &grid, scene)?;
    let infos = channel_infos(&instrument, &candidates, &scene.plate);
    let channel_of: Vec<usize> = (0..candidates.len())
        .map(|s| infos.iter().position(|i| i.sensor == Some(s)))
        .collect::<Option<_>>()
        .ok_or("the design's instrument records no channel at some candidate point")?;
    let rows = grid_rows(&instrument, (ensemble, study), w, progress)?;
    let score = |set: &[usize]| -> Result<(Score, Vec<Option<f64>>), String> {
        let members: Vec<usize> = set.iter().map(|&k| channel_of[k]).collect();
        w.score("design", &select(&rows, &members), &scale_flags(members.len())).map_err(|e| e.to_string())
    };
    let chosen = forward_selection(candidates.len(), design.sensors, score, |s: &(Score, _)| s.0.auc)?;
    let mut steps = Vec::with_capacity(chosen.len());
    let mut before: Option<&Vec<Option<f64>>> = None;
    for Chosen { added, score: (score, p), map } in &chosen {
        let (gain, gain_interval) = match before {
            None => (score.auc - 0.5, (score.interval.0 - 0.5, score.interval.1 - 0.5)),
            Some(q) => w.paired_gain(q, p),
        };
        let (x, z) = candidates[*added];
        steps.push(WindowDesignStep {
            at_mm: (x * 1e3, z * 1e3),
            score: Score {
                group: format!("{} sensor{}", steps.len() + 1, if steps.is_empty() { "" } else { "s" }),
                ..score.clone()
            },
            gain,
            gain_interval,
            map: ensemble.by_x_and_z(map),
        });
        before = Some(p);
    }
    let chosen_channels: Vec<usize> = chosen.iter().map(|c| channel_of[c.added]).collect();
    let at: Vec<(f64, f64)> = steps.iter().map(|s| s.at_mm).collect();
    let features = weights(&select(&rows, &chosen_channels), &w.labels, &at)?;
    Ok(Some(WindowDesign {
        features,
        quantity: design.measurand.key(),
        x_mm: ensemble.candidates_x.iter().map(|x| x * 1e3).collect(),
        z_mm: ensemble.candidates_z.iter().map(|z| z * 1e3).collect(),
        steps,
    }))
}

/// Every window's features at every candidate channel of `instrument`: the study's streams
/// (the main run's seeds, so the same lumps) simulated, recorded and cut into windows one at a
/// time, each stream's signals let go before the next.
fn grid_rows(
    instrument: &dyn Recorder,
    (ensemble, study): (&identify::Study, &StreamStudy),
    w: &Windows,
    progress: &dyn Progress,
) -> Result<Vec<Vec<f64>>, Failure> {
    let cutting = segments::cutting(instrument, study)?;
    let mut rows = vec![Vec::new(); w.windows.len()];
    for r in 0..study.streams {
        let sim = simulate_one(instrument, ensemble, study, (study.spec.rate_per_s, r), cutting)?;
        let recorded = record_one(instrument, r, &sim, 1.0);
        drop(sim);
        let rate = instrument.chain().map_or_else(|| instrument.model_rate_hz(), |c| c.spec().rate_hz);
        for (i, row) in features_of(r, &recorded, rate, &w.windows, study) {
            rows[i] = row;
        }
        progress.advance(1);
    }
    Ok(rows)
}

/// The weights of the logistic detector fitted on every window's `rows` (the designed sensors'
/// features, sensor-major, at `at`) against `labels`, largest magnitude first.
fn weights(rows: &[Vec<f64>], labels: &[bool], at: &[(f64, f64)]) -> Result<Vec<FeatureWeight>, Failure> {
    let model = Logistic::fit(rows, labels, &scale_flags(at.len()), RIDGE).map_err(|e| e.to_string())?;
    let names = at.iter().flat_map(|&a| FEATURES.iter().map(move |f| (a, f.key())));
    let mut out: Vec<FeatureWeight> =
        names.zip(&model.weights).map(|((at_mm, feature), &weight)| FeatureWeight { at_mm, feature, weight }).collect();
    out.sort_by(|a, b| b.weight.abs().total_cmp(&a.weight.abs()));
    Ok(out)
}
