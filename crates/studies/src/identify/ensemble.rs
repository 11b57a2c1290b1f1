//! The ensemble thrown on an instrument: every impact drawn from its own seeded stream (so a
//! run, or any range of it, is the same on any number of threads) and reduced to features.

use super::sensors::{channel_infos, spec};
use crate::channel::ChannelInfo;
use crate::progress::Progress;
use crate::Failure;
use coupled::identification::{run_condition, ConditionRun, ImpactRecord, Impacts, Instrument, RunError};
use coupled::reduced::{ReducedModel, ReducedSettings};
use coupled::validity::QUASI_STATIC_MIN_RATIO;
use identify::{Held, Study};
use scene::{Scene, SupportSet};

/// Runs the ensemble of `study` with `held` on `instrument` as the stage `what` of `progress`,
/// handing each record to `sink` in impact order; a failed impact is named by `set` and its
/// index.
pub fn run(
    study: &Study,
    held: Held,
    instrument: &Instrument<'_>,
    set: &str,
    what: &str,
    progress: &dyn Progress,
    sink: impl FnMut(&ImpactRecord) -> Result<(), Failure>,
) -> Result<ConditionRun, Failure> {
    run_on(study, (held, Impacts::All), instrument, (set, what), progress, sink)
}

/// [`run`] on `impacts` of the ensemble.
fn run_on(
    study: &Study,
    (held, impacts): (Held, Impacts<'_>),
    instrument: &Instrument<'_>,
    (set, what): (&str, &str),
    progress: &dyn Progress,
    mut sink: impl FnMut(&ImpactRecord) -> Result<(), Failure>,
) -> Result<ConditionRun, Failure> {
    progress.start(impacts.len(study.ensemble.len()), &format!("{set}: {what}"));
    let run = run_condition(study, (held, impacts), instrument, |r: &ImpactRecord| -> Result<(), Failure> {
        sink(r)?;
        progress.advance(1);
        Ok(())
    })
    .map_err(|err| match err {
        RunError::Model { index, source } => format!("{set}: impact {index}: {source}").into(),
        RunError::Sink(f) => f,
    })?;
    progress.finish();
    Ok(run)
}

/// The same `impacts` at the same `sensors` on the model of `set` with half its modes:
/// what each number owes to the modal truncation (the difference overstates the error at N
/// if the AUC converges in N).
pub fn half_modes(
    scene: &Scene,
    (study, impacts): (&Study, Impacts<'_>),
    set: &SupportSet,
    sensors: &[(f64, f64)],
    progress: &dyn Progress,
) -> Result<ConditionRun, Failure> {
    let settings = super::sensors::reduced_settings(scene, set)?;
    let half = ReducedSettings { modes: (settings.modes / 2).max(1), ..settings };
    let model = ReducedModel::new(&scene.plate, set, half)?;
    let instrument = Instrument::new(&model, &scene.plate, &spec(scene, sensors.to_vec()), scene)?;
    let what = format!("{} modes", half.modes);
    run_on(study, (Held::NONE, impacts), &instrument, (&set.name, &what), progress, |_| Ok(()))
}

/// Impacts of a range of the ensemble, with the channels that recorded them.
#[derive(Debug, Clone)]
pub struct Shard {
    /// The channels, in the order of each record's features.
    pub channels: Vec<ChannelInfo>,
    /// Each impact's family name and record, in impact order.
    pub records: Vec<(String, ImpactRecord)>,
}

/// Impacts `range` of the scene's ensemble on `model` (the reduced model of one support set),
/// recorded at `sensors` with the scene's signals (window, rate, every quantity, the corners).
/// Impact `i` depends only on the scene and `i`, so shards of any split concatenate to the
/// rows of one run.
pub fn shard(
    scene: &Scene,
    model: &ReducedModel,
    sensors: &[(f64, f64)],
    range: std::ops::Range<usize>,
) -> Result<Shard, Failure> {
    let e = &scene.ensemble.as_ref().ok_or("the scene has no [ensemble]")?.ensemble;
    let instrument = Instrument::new(model, &scene.plate, &spec(scene, sensors.to_vec()), scene)?;
    let records = range
        .map(|i| {
            let draw = e.draw(i, Held::NONE).ok_or_else(|| format!("impact {i} is beyond the ensemble"))?;
            let name = e.families[draw.family].name.clone();
            instrument.impact(draw, &name).map(|r| (name, r)).map_err(|x| format!("impact {i}: {x}").into())
        })
        .collect::<Result<Vec<_>, Failure>>()?;
    Ok(Shard { channels: channel_infos(&instrument, sensors, &scene.plate), records })
}

/// The validity criteria one impact fails, as [`coupled::identification::EnsembleValidity`]
/// counts them: the rock yields (δ_max > δ_my, eq. 51), the contact is faster than the
/// quasi-static limit of t_c/T₁, the sphere strikes again, the first contact is still on at
/// the window's end.
pub fn validity_flags(r: &ImpactRecord) -> Vec<&'static str> {
    let mut f = Vec::new();
    if r.compression_ratio > 1.0 {
        f.push("beyond elastic range");
    }
    if r.hertz_time_ratio < QUASI_STATIC_MIN_RATIO {
        f.push("not quasi-static");
    }
    if r.contacts > 1 {
        f.push("re-contact");
    }
    if r.contact_time.is_none() {
        f.push("contact unfinished in the window");
    }
    f
}
