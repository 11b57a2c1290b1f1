//! The identification on one support set: the main run, the same impacts on half the modes,
//! and every score of [`super`] composed into the set's result and section data.

use super::check::Truncation;
use super::ensemble::run;
use super::sensors::{channel_infos, no_channels, run_sensors, spec, stated_channels};
use super::separability::{contact_quantities, split, Separation};
use super::{
    baselines, classifiers, full_model, measured, placement, variability, ClassValues, ConditionDetail,
    ConditionResult, MainImpact, SensorDesign, Sink,
};
use crate::channel::ChannelInfo;
use crate::progress::Progress;
use crate::Failure;
use coupled::identification::ConditionRun;
use coupled::identification::{Instrument, CHUNK};
use coupled::reduced::ReducedModel;
use identify::features::FEATURES;
use identify::placement::best;
use identify::{Held, Study};
use scene::{Scene, SupportSet};
use std::time::Instant;

/// The sensor design's folds, apart from every other stream of the set's seed.
const DESIGN_KEY: u64 = 400;

/// The identification on `set`, the `index`-th support set of `scene`: the main run's
/// impacts handed to `sink`, the result and what its section shows.
pub(super) fn run_set(
    scene: &Scene,
    study: &Study,
    set: &SupportSet,
    index: usize,
    progress: &dyn Progress,
    sink: &mut Sink<'_>,
) -> Result<(ConditionResult, ConditionDetail), Failure> {
    let (plate, settings, e) = (&scene.plate, &scene.signals, &study.ensemble);
    let started = Instant::now();
    let model = ReducedModel::new(plate, set, super::sensors::reduced_settings(scene, set)?)?;
    let setup_seconds = started.elapsed().as_secs_f64();

    // The main run: named sensors, then the candidate grid (less its points at named
    // sensors), every quantity, the corners.
    let (sensors, grid) = run_sensors(&settings.sensors, study, plate);
    let mut instrument = Instrument::new(&model, plate, &spec(scene, sensors.clone()), scene)?;
    let infos = channel_infos(&instrument, &sensors, plate);
    if infos.is_empty() {
        return Err(no_channels(&set.name));
    }
    let t0 = Instant::now();
    let main = run(study, Held::NONE, &instrument, &set.name, "ensemble", progress, |record| {
        let family = &e.families[record.draw.family].name;
        sink(&MainImpact { condition: &set.name, record, family, channels: &infos })
    })?;
    let run_seconds = t0.elapsed().as_secs_f64();
    let full_model = full_model::check(scene, study, set, &instrument)?;

    let seed = super::check::set_seed(e.seed, index);
    let check = Truncation::run(scene, (study, &main), (set, &sensors), seed, progress)?;
    let sep = Separation::new(&main, &check, &infos, seed);
    let (force_max, contact_time) = contact_quantities(&main, &check, seed);
    let groups = classifiers::groups(&infos, sep.best_sensor, sep.converged, settings.sensors.len());
    let classifiers = classifiers::accuracies(&main, &check, groups, seed)?;
    let truncation_check = check.summary((&main, &stated_channels(&infos, settings.sensors.len())), &sep, seed);
    let main_run = variability::MainRun { model: &model, sensors: &sensors, infos: &infos };
    let (held, reference) = variability::held_runs(scene, study, set, &main_run, sep.reference(), seed, progress)?;
    let top = best(&sep.all, &[]).map(|s| s.channel);
    let measurement = measured::of_set(scene, study, set, &instrument, &main, &main_run, top, seed, progress)?;
    let (detail, design) = detail(study, (&grid, &infos), &main, &sep, reference, seed)?;
    // The main run's instrument records the design's reruns, its background rescaled: the
    // last use of it.
    let design_run = (&mut instrument, &main, design.as_ref());
    let design_backgrounds =
        placement::at_backgrounds(study, set, design_run, (&infos, &grid), seed ^ DESIGN_KEY, progress)?;
    let ranking = sep.ranking();
    let baselines = vec![
        baselines::of_ranked("contact time t_c", &contact_time),
        baselines::of_ranked("contact force P_max", &force_max),
        baselines::mass(&main, seed ^ 300),
    ];
    let converged = sep.converged_ranked();
    let headline = baselines::headline(baselines, ranking.first(), converged.as_ref());
    let result = ConditionResult {
        condition: set.name.clone(),
        fundamental_hz: main.fundamental_hz,
        validity: main.validity,
        ranking,
        best_sensor: sep.best_sensor_ranked(),
        best_converged: converged,
        force_max,
        contact_time,
        headline,
        classifiers,
        reference: sep.reference_ranked(),
        held,
        setup_seconds,
        run_seconds,
        impacts_per_second: e.len() as f64 / run_seconds.max(1e-9),
        feature_bytes: held_bytes(&main, &check, infos.len()),
        full_model,
        measurement,
        chain_modes: settings.modes_from_chain.then(|| model.settings().modes),
        design,
        design_backgrounds,
        truncation_check,
    };
    Ok((result, detail))
}

/// The bytes a set's run holds: the main run's, the half-mode run's and (on a subsample) the
/// checked impacts' features and clean peaks (under a chain), and one chunk of records of
/// `channels` channels.
fn held_bytes(main: &ConditionRun, check: &Truncation, channels: usize) -> usize {
    let run = |r: &ConditionRun| r.table.bytes() + 8 * r.clean_peaks.len();
    let checked = if check.sampled() { run(check.main(main)) } else { 0 };
    run(main) + run(&check.half) + checked + CHUNK * channels * FEATURES.len() * 8
}

/// What the set's section shows (the placement maps, the histograms' values, the variability
/// study's reference) and the sensor design, from the main run `main` and its separations.
fn detail(
    study: &Study,
    (grid, infos): (&[usize], &[ChannelInfo]),
    main: &ConditionRun,
    sep: &Separation,
    reference: Option<String>,
    seed: u64,
) -> Result<(ConditionDetail, Option<SensorDesign>), Failure> {
    let (fc, fg) = split(&main.force_max, main.table.classes());
    let maps = placement::maps(study, grid, infos, &sep.all);
    let design = placement::design(study, grid, infos, &maps, &main.table, seed ^ DESIGN_KEY)?;
    let detail = ConditionDetail {
        maps,
        best: sep.best_values(),
        force_max: ClassValues { label: "P_max (N)".into(), coal: fc, gangue: fg, scale: true },
        reference,
    };
    Ok((detail, design))
}
