//! `impact identify`: the scene's random-impact ensemble on every support set, the features'
//! separability of coal from gangue, sensor-placement maps, which variability hides the
//! difference, and the validity of the ensemble, written up as a report.
//!
//! The physics is in `coupled::identification` and the statistics in crate `identify`;
//! this module streams the feature rows to the output directory, draws the maps and
//! histograms, and fills the templates.

use crate::present::plot::{line_plot, Axis, ColourMap, Scale, Series};
use crate::present::table::{sig, unit_key, Cell, Table};
use crate::provenance::Provenance;
use crate::template::render;
use crate::Failure;
use coupled::identification::{
    run_condition, ConditionRun, EnsembleValidity, ImpactRecord, Instrument, RunError, CHUNK,
};
use coupled::reduced::{ChannelKind, Quantity, ReducedModel, ReducedSettings, SignalSettings, SignalSpec};
use coupled::{Scene, SupportSet};
use identify::classify::{CrossValidated, FOLDS, RIDGE};
use identify::distribution::Distribution;
use identify::features::FEATURES;
use identify::placement::{best, classifier, map, separabilities, Separability};
use identify::roc::{auc_with_error, bootstrap_interval, Auc, BOOTSTRAP_RESAMPLES};
use identify::{Class, Feature, Held, Speed, Study};
use output::{Artifacts, OutputDir, StreamedFile};
use serde::Serialize;
use std::io::Write as _;
use std::time::Instant;
pub use studies::channel::ChannelInfo;

const HEAD: &str = include_str!("templates/identify/head.md");
const FINDING: &str = include_str!("templates/identify/finding.md");
const FINDING_HELD: &str = include_str!("templates/identify/finding-held.md");
const FINDING_RESOLUTION: &str = include_str!("templates/identify/finding-resolution.md");
const CONDITION: &str = include_str!("templates/identify/condition.md");
const METHOD: &str = include_str!("templates/identify/method.md");
const LAW_ELASTIC: &str = include_str!("templates/identify/law-elastic.md");
const LAW_PLASTIC: &str = include_str!("templates/identify/law-plastic.md");

/// Entries of the ranking that get a bootstrap interval (the rest carry DeLong's error).
const TOP: usize = 10;
/// Histogram bins.
const BINS: usize = 30;
/// The confidence level of every interval.
const LEVEL: f64 = 0.95;

/// Channels an identification records per impact on `set`: three quantities at every named
/// and candidate sensor (once where they coincide), and the held or sprung corners.
pub fn channels_per_impact(scene: &Scene, study: &Study, set: &SupportSet) -> usize {
    let sensors = run_sensors(&scene.signals.sensors, study, &scene.plate).0.len();
    let corners = set.supports.corners.iter().filter(|c| !matches!(c, plate_fem::CornerSupport::Free)).count();
    3 * sensors + corners
}

/// The sensors of an identification run: the named sensors, then the candidate grid's points
/// that are not at a named sensor; and, for each grid point in [`Study::candidates`] order,
/// the index of the sensor that records it. A grid point at a named sensor is that sensor (the
/// same signals), so its channels are recorded, ranked and written once, under the named
/// sensor. Positions coincide within 1e-9 of the plate's larger side, far below the
/// millimetre digits a scene gives them in.
pub fn run_sensors(named: &[(f64, f64)], study: &Study, plate: &analytic::Plate) -> (Vec<(f64, f64)>, Vec<usize>) {
    let tol = 1e-9 * plate.length().max(plate.width());
    let mut sensors = named.to_vec();
    let grid = study
        .candidates()
        .into_iter()
        .map(|(x, z)| {
            named.iter().position(|&(nx, nz)| (nx - x).abs() <= tol && (nz - z).abs() <= tol).unwrap_or_else(|| {
                sensors.push((x, z));
                sensors.len() - 1
            })
        })
        .collect();
    (sensors, grid)
}

/// Bytes of features one run holds: [`FEATURES`] of 8 bytes each per impact and channel.
pub fn feature_bytes(impacts: usize, channels: usize) -> usize {
    impacts.saturating_mul(channels).saturating_mul(FEATURES.len() * 8)
}

// ---------------------------------------------------------------- results

/// One ranked feature of one channel with its intervals.
#[derive(Debug, Clone, Serialize)]
pub struct Ranked {
    /// The channel, e.g. "acceleration at (229.2, 180) mm".
    pub channel: String,
    /// The feature.
    pub feature: &'static dyn Feature,
    /// AUC (P(gangue > coal)) with DeLong's standard error.
    pub auc: Auc,
    /// The 95 % percentile bootstrap interval.
    pub interval: (f64, f64),
    /// AUC on the model with N modes minus AUC with N/2 (the same impacts): how much the
    /// number owes to the modal truncation.
    pub resolution: Option<f64>,
}

/// A change in AUC below which no conclusion here changes (the AUCs are quoted to 3 digits
/// and separabilities compared in steps of a few hundredths).
const AUC_RESOLUTION: f64 = 0.01;

/// Whether a change `delta` of an AUC with standard error `se` between N/2 and N modes is
/// within the sampling error or below [`AUC_RESOLUTION`].
fn resolved(delta: f64, se: f64) -> bool {
    delta.abs() <= se.max(AUC_RESOLUTION)
}

impl Ranked {
    /// Whether the modal truncation moves the AUC by less than its sampling error or
    /// the AUC resolution (0.01).
    pub fn converged(&self) -> bool {
        self.resolution.is_some_and(|r| resolved(r, self.auc.standard_error))
    }
}

/// One classifier's cross-validated accuracy.
#[derive(Debug, Clone, Serialize)]
pub struct Accuracy {
    /// Which features it sees.
    pub features: String,
    /// Its accuracy.
    pub result: CrossValidated,
    /// Accuracy with N modes minus accuracy with N/2 (the same impacts and folds).
    pub resolution: f64,
}

/// One run of the variability study.
#[derive(Debug, Clone, Serialize)]
pub struct Held1 {
    /// What was held.
    pub which: Held,
    /// It in words ("size", "position, size and speed", ...).
    pub held: String,
    /// The reference feature's AUC.
    pub reference: Auc,
    /// The best feature of the run.
    pub best: Ranked,
    /// P_max's AUC.
    pub force_max: Auc,
    /// The classifier on every channel of the run.
    pub accuracy: CrossValidated,
}

/// The identification on one support set.
#[derive(Debug, Clone, Serialize)]
pub struct ConditionResult {
    /// Support set name.
    pub condition: String,
    /// The supported plate's fundamental frequency, Hz.
    pub fundamental_hz: f64,
    /// Validity counts.
    pub validity: EnsembleValidity,
    /// The most separating features, best first.
    pub ranking: Vec<Ranked>,
    /// The best sensor point (x, z), mm, and its best feature.
    pub best_sensor: Option<((f64, f64), Ranked)>,
    /// The most separating feature whose AUC the modal truncation moves by less than its
    /// sampling error.
    pub best_converged: Option<Ranked>,
    /// P_max and the first contact's duration: the paper's quantities.
    pub force_max: Ranked,
    /// The contact time.
    pub contact_time: Ranked,
    /// Classifiers.
    pub classifiers: Vec<Accuracy>,
    /// The reference feature of the variability study (the most separating one the modal
    /// truncation does not move, else the best sensor's best).
    pub reference: Option<Ranked>,
    /// The variability study.
    pub held: Vec<Held1>,
    /// Seconds for the reduced model's set-up (modes, residual flexibility).
    pub setup_seconds: f64,
    /// Seconds for the main ensemble run (impacts, features, rows to disk).
    pub run_seconds: f64,
    /// Impacts per second of that run.
    pub impacts_per_second: f64,
    /// Bytes of features held in memory for the run.
    pub feature_bytes: usize,
    /// The reference impact (every variable at its median, the first family) on the full
    /// Newmark model of the same mesh and step rule: seconds, and the reduced model's P_max
    /// relative to it.
    pub full_model: FullModelCheck,
}

/// One impact on the full transient model beside the reduced one, in the same run.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct FullModelCheck {
    /// Seconds for the full model's run (set-up and factorization included, no signals).
    pub seconds: f64,
    /// Its P_max, N.
    pub force_max: f64,
    /// The reduced model's P_max over it, minus 1.
    pub force_difference: f64,
    /// The reduced model's first-contact time over the full model's, minus 1 (0 if either
    /// contact did not end).
    pub contact_time_difference: f64,
}

/// What `impact identify` found, for the terminal and the JSON.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Scene name.
    pub scene: String,
    /// Impacts per support set.
    pub impacts: usize,
    /// Coal and gangue impacts.
    pub classes: (usize, usize),
    /// The contact law.
    pub contact_law: &'static str,
    /// The signals.
    pub signals: SignalSettings,
    /// Per support set.
    pub conditions: Vec<ConditionResult>,
}

// ---------------------------------------------------------------- labels

use studies::channel::mm;

fn quantity_name(q: Quantity) -> &'static str {
    match q {
        Quantity::Displacement => "displacement",
        Quantity::Velocity => "velocity",
        Quantity::Acceleration => "acceleration",
    }
}

fn describe(d: &Distribution, unit: &str, scale: f64) -> String {
    // Values as the scene wrote them (to rounding of the unit conversion).
    let v = |x: f64| analytic::params::compact(format!("{:.6e}", x * scale).parse::<f64>().unwrap_or(x * scale));
    match d {
        Distribution::Fixed { value } => format!("{} {unit}", v(*value)),
        Distribution::Uniform { min, max } => format!("uniform on [{}, {}] {unit}", v(*min), v(*max)),
        Distribution::Normal { mean, sd, min, max } => {
            format!("normal, mean {} sd {}, in [{}, {}] {unit}", v(*mean), v(*sd), v(*min), v(*max))
        }
        Distribution::LogNormal { median, sigma_log, min, max } => format!(
            "lognormal, median {} σ_ln {}, in [{}, {}] {unit}",
            v(*median),
            analytic::params::compact(*sigma_log),
            v(*min),
            v(*max)
        ),
        Distribution::RosinRammler { scale: s, shape, min, max } => {
            format!("Rosin-Rammler, x₆₃ {} n {}, in [{}, {}] {unit}", v(*s), sig(*shape, 3), v(*min), v(*max))
        }
        Distribution::Choice { values } => {
            format!("one of {} {unit}", values.iter().map(|x| v(*x)).collect::<Vec<_>>().join(", "))
        }
    }
}

fn held_label(h: Held) -> String {
    let mut parts = Vec::new();
    for (on, name) in [(h.position, "position"), (h.size, "size"), (h.speed, "speed"), (h.material, "material")] {
        if on {
            parts.push(name);
        }
    }
    match parts.len() {
        0 => "nothing".into(),
        1 => parts[0].into(),
        n => format!("{} and {}", parts[..n - 1].join(", "), parts[n - 1]),
    }
}

// ---------------------------------------------------------------- rows on disk

/// Which row files an identification streams: `impacts.csv` always, `features.csv` (one row
/// per impact and channel, about 19 kB per impact with the default candidate grid: 112 MB for
/// `scenes/caving-stream.toml`) unless left out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RowFiles {
    /// `impacts.csv` and `features.csv`.
    All,
    /// `impacts.csv` only.
    Impacts,
}

/// The streamed files: one row per impact, one row per impact and channel.
struct Rows {
    impacts: csv::Writer<StreamedFile>,
    features: Option<csv::Writer<StreamedFile>>,
}

/// The columns of `impacts.csv`, in SI (docs/output-format.md).
const IMPACT_HEADERS: [&str; 19] = [
    "condition",
    "impact",
    "family",
    "class",
    "x_m",
    "z_m",
    "radius_m",
    "velocity_m_per_s",
    "density_kg_per_m3",
    "youngs_modulus_Pa",
    "poisson_ratio",
    "cohesion_Pa",
    "friction_angle_rad",
    "force_max_N",
    "contact_time_s",
    "contacts",
    "delta_max_per_delta_my",
    "t_H_per_T1",
    "mass_kg",
];

/// The columns of `features.csv` before the features.
const FEATURE_ROW_HEADERS: [&str; 7] = ["condition", "impact", "class", "quantity", "x_m", "z_m", "unit"];

/// The columns of `features.csv`: [`FEATURE_ROW_HEADERS`], then one per feature of
/// [`FEATURES`], its key and its unit. A channel's features are in its own SI unit, named
/// in the row's `unit` column (`m`, `m_per_s`, `m_per_s2`, `N`); `_unit` in a column name
/// stands for it: "peak_unit", "energy_unit2_s", "duration_s", "dominant_frequency_Hz".
fn feature_headers() -> Vec<String> {
    let unit_key = |u: String| u.replace(['(', ')', '^'], "").replace('*', "_").replace('/', "_per_");
    FEATURE_ROW_HEADERS
        .iter()
        .map(|h| h.to_string())
        .chain(FEATURES.iter().map(|f| format!("{}_{}", f.key(), unit_key(f.unit("unit")))))
        .collect()
}

fn num(v: f64) -> String {
    if v.is_finite() {
        format!("{v:e}")
    } else {
        String::new()
    }
}

/// Opens `name` under `dir` in `out` with the provenance line first.
fn open_stream(
    out: &mut OutputDir,
    dir: &str,
    name: &str,
    provenance: &Provenance,
    headers: &[impl AsRef<[u8]>],
) -> Result<csv::Writer<StreamedFile>, Failure> {
    let path = if dir.is_empty() { name.to_string() } else { format!("{dir}/{name}") };
    let mut file = out.stream(&path)?;
    file.write_all(provenance.csv_line().as_bytes())?;
    let mut w = csv::Writer::from_writer(file);
    w.write_record(headers)?;
    Ok(w)
}

impl Rows {
    fn open(out: &mut OutputDir, dir: &str, provenance: &Provenance, files: RowFiles) -> Result<Self, Failure> {
        let impacts = open_stream(out, dir, "impacts.csv", provenance, &IMPACT_HEADERS)?;
        let features = match files {
            RowFiles::All => Some(open_stream(out, dir, "features.csv", provenance, &feature_headers())?),
            RowFiles::Impacts => None,
        };
        Ok(Self { impacts, features })
    }

    fn write(
        &mut self,
        condition: &str,
        r: &ImpactRecord,
        family: &str,
        channels: &[ChannelInfo],
    ) -> Result<(), Failure> {
        let d = &r.draw;
        let mass = d.density * 4.0 / 3.0 * std::f64::consts::PI * d.radius.powi(3);
        self.impacts.write_record([
            condition.to_string(),
            d.index.to_string(),
            family.to_string(),
            d.class.key().to_string(),
            num(d.x),
            num(d.z),
            num(d.radius),
            num(d.velocity),
            num(d.density),
            num(d.youngs_modulus),
            num(d.poisson_ratio),
            num(d.cohesion),
            num(d.friction_angle_deg.to_radians()),
            num(r.force_max),
            r.contact_time.map_or(String::new(), num),
            r.contacts.to_string(),
            num(r.compression_ratio),
            num(r.hertz_time_ratio),
            num(mass),
        ])?;
        let Some(features) = self.features.as_mut() else { return Ok(()) };
        for (c, f) in channels.iter().zip(r.channel_features()) {
            let row = [
                condition.to_string(),
                d.index.to_string(),
                d.class.key().to_string(),
                c.quantity.to_string(),
                num(c.at.0),
                num(c.at.1),
                unit_key(c.unit),
            ];
            features.write_record(row.into_iter().chain(f.iter().map(|v| num(*v))))?;
        }
        Ok(())
    }

    fn finish(self, out: &mut OutputDir) -> Result<(), Failure> {
        for w in std::iter::once(self.impacts).chain(self.features) {
            let file = w.into_inner().map_err(|e| e.into_error())?;
            out.finish_stream(file)?;
        }
        Ok(())
    }
}

// ---------------------------------------------------------------- the runs

fn progress(len: usize, message: String) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(len as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg:30} [{bar:30}] {pos}/{len} impacts, {per_sec}, eta {eta}")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    bar.set_message(message);
    bar
}

fn spec(settings: &SignalSettings, sensors: Vec<(f64, f64)>) -> SignalSpec {
    SignalSpec {
        window: settings.window,
        rate_hz: settings.rate_hz,
        sensors,
        quantities: Quantity::ALL.to_vec(),
        corners: true,
    }
}

fn ranked(
    channel: String,
    feature: &'static dyn Feature,
    (coal, gangue): (&[f64], &[f64]),
    half_auc: Option<f64>,
    seed: u64,
) -> Ranked {
    let auc = auc_with_error(coal, gangue);
    Ranked {
        channel,
        feature,
        auc,
        interval: bootstrap_interval(coal, gangue, BOOTSTRAP_RESAMPLES, LEVEL, seed),
        resolution: half_auc.map(|h| auc.auc - h),
    }
}

fn split(values: &[f64], classes: &[Class]) -> (Vec<f64>, Vec<f64>) {
    let mut c = Vec::new();
    let mut g = Vec::new();
    for (v, k) in values.iter().zip(classes) {
        match k {
            Class::Coal => c.push(*v),
            Class::Gangue => g.push(*v),
        }
    }
    (c, g)
}

/// The histogram of coal and gangue values of one column as two curves of the fraction of
/// each class per bin; scale features on log10 axes when all values are positive.
fn histogram(title: &str, label: &str, coal: &[f64], gangue: &[f64], log: bool) -> String {
    let log = log && coal.iter().chain(gangue).all(|v| *v > 0.0);
    let t = |v: f64| if log { v.log10() } else { v };
    let (lo, hi) =
        coal.iter().chain(gangue).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(t(v)), b.max(t(v))));
    let (lo, hi) = if lo.is_finite() && hi > lo { (lo, hi) } else { (lo.min(0.0), lo.max(0.0) + 1.0) };
    let width = (hi - lo) / BINS as f64;
    let curve = |vals: &[f64]| -> Vec<(f64, f64)> {
        let mut counts = vec![0.0; BINS];
        for &v in vals {
            let k = (((t(v) - lo) / width) as usize).min(BINS - 1);
            counts[k] += 1.0;
        }
        let n = vals.len().max(1) as f64;
        counts.iter().enumerate().map(|(k, c)| (lo + (k as f64 + 0.5) * width, c / n)).collect()
    };
    let x_label = if log { format!("log10 {label}") } else { label.to_string() };
    line_plot(
        title,
        &x_label,
        "fraction of the class per bin",
        &[Series::new("coal", curve(coal)), Series::new("gangue", curve(gangue))],
        Scale::Linear,
    )
}

/// The error of a support set on which nothing is recorded.
pub fn no_channels(set: &str) -> Failure {
    format!(
        "support set '{set}' records no channel (no named sensor, no candidate grid, no spring or fixed corner): give [signals] sensors_mm or [ensemble.placement]"
    )
    .into()
}

fn run_failure(set: &str, err: RunError<Failure>) -> Failure {
    match err {
        RunError::Model { index, source } => format!("{set}: impact {index}: {source}").into(),
        RunError::Sink(f) => f,
    }
}

/// What one support set gives besides its files: its results and its report section.
struct ConditionOutput {
    result: ConditionResult,
    markdown: String,
}

#[allow(clippy::too_many_arguments)]
fn run_set(
    scene: &Scene,
    study: &Study,
    settings: &SignalSettings,
    set: &SupportSet,
    index: usize,
    rows: &mut Rows,
    artifacts: &mut Artifacts,
) -> Result<ConditionOutput, Failure> {
    let plate = &scene.plate;
    let e = &study.ensemble;
    let started = Instant::now();
    let model = ReducedModel::new(plate, set, settings.reduced())?;
    let setup_seconds = started.elapsed().as_secs_f64();

    // The main run: named sensors, then the candidate grid (less its points at named
    // sensors), every quantity, the corners.
    let named = settings.sensors.len();
    let (sensors, grid) = run_sensors(&settings.sensors, study, plate);
    let instrument =
        Instrument::new(&model, plate, &spec(settings, sensors.clone()), scene.restitution, scene.contact_law)?;
    let infos: Vec<ChannelInfo> =
        instrument.channels().into_iter().map(|k| ChannelInfo::new(k, &sensors, plate)).collect();
    if infos.is_empty() {
        return Err(no_channels(&set.name));
    }
    let bar = progress(e.len(), format!("{}: ensemble", set.name));
    let t0 = Instant::now();
    let run: ConditionRun = run_condition(study, Held::NONE, &instrument, |r: &ImpactRecord| -> Result<(), Failure> {
        rows.write(&set.name, r, &e.families[r.draw.family].name, &infos)?;
        bar.inc(1);
        Ok(())
    })
    .map_err(|err| run_failure(&set.name, err))?;
    let run_seconds = t0.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let full_model = full_model_check(scene, study, settings, set, &instrument)?;
    let held_bytes = 2 * run.table.bytes() + CHUNK * infos.len() * FEATURES.len() * 8;

    // The same impacts on the model with half the modes: what each AUC owes to the modal
    // truncation (the difference overstates the error at N if the AUC converges in N).
    let half_settings = ReducedSettings { modes: (settings.modes / 2).max(1), ..settings.reduced() };
    let half_model = ReducedModel::new(plate, set, half_settings)?;
    let half_instrument =
        Instrument::new(&half_model, plate, &spec(settings, sensors.clone()), scene.restitution, scene.contact_law)?;
    let bar = progress(e.len(), format!("{}: {} modes", set.name, half_settings.modes));
    let half = run_condition(study, Held::NONE, &half_instrument, |_: &ImpactRecord| -> Result<(), Failure> {
        bar.inc(1);
        Ok(())
    })
    .map_err(|err| run_failure(&set.name, err))?;
    bar.finish_and_clear();
    let half_all = separabilities(&half.table);
    let half_classes = half.table.classes().to_vec();
    let half_of = |values: &[f64]| {
        let (c, g) = split(values, &half_classes);
        auc_with_error(&c, &g).auc
    };

    let seed = e.seed ^ (index as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    let all = separabilities(&run.table);
    let mut order: Vec<&Separability> = all.iter().collect();
    order.sort_by(|a, b| b.auc.separability().total_cmp(&a.auc.separability()).then(a.channel.cmp(&b.channel)));
    let classes = run.table.classes().to_vec();
    let rank_of = |s: &Separability, k: usize| {
        let (c, g) = run.table.split(s.channel, s.feature);
        let h = half_all[s.channel * FEATURES.len() + s.feature.index()].auc.auc;
        ranked(infos[s.channel].label(), s.feature, (&c, &g), Some(h), seed.wrapping_add(k as u64))
    };
    let ranking: Vec<Ranked> = order.iter().take(TOP).enumerate().map(|(k, s)| rank_of(s, k)).collect();
    let best_converged = order
        .iter()
        .find(|s| {
            resolved(s.auc.auc - half_all[s.channel * FEATURES.len() + s.feature.index()].auc.auc, s.auc.standard_error)
        })
        .map(|s| rank_of(s, TOP + 2));
    let (fc, fg) = split(&run.force_max, &classes);
    let force_max = ranked(
        "contact force P_max".into(),
        &identify::features::Peak,
        (&fc, &fg),
        Some(half_of(&half.force_max)),
        seed ^ 1,
    );
    let (tc, tg) = split(&run.contact_time, &classes);
    let contact_time = ranked(
        "contact time t_c".into(),
        &identify::features::Duration,
        (&tc, &tg),
        Some(half_of(&half.contact_time)),
        seed ^ 2,
    );

    // The best sensor: the sensor channel with the most separating feature.
    let sensor_channels: Vec<usize> = (0..infos.len()).filter(|&c| infos[c].sensor.is_some()).collect();
    let best_sensor_entry = if sensor_channels.is_empty() { None } else { best(&all, &sensor_channels) };
    let best_sensor =
        best_sensor_entry.map(|s| ((infos[s.channel].at.0 * 1e3, infos[s.channel].at.1 * 1e3), rank_of(&s, TOP + 1)));

    let stem = format!("c{}", index + 1);

    // Placement maps: per quantity, the feature whose best grid value is highest.
    let mut maps_md = String::new();
    if !grid.is_empty() {
        for q in Quantity::ALL {
            // One channel per grid point, in grid order: a point at a named sensor is its channel.
            let Some(chans) = grid
                .iter()
                .map(|&s| infos.iter().position(|i| i.sensor == Some(s) && i.quantity == quantity_name(q)))
                .collect::<Option<Vec<usize>>>()
            else {
                continue;
            };
            let Some(top) = best(&all, &chans) else { continue };
            let values = map(&all, &chans, top.feature);
            let nz = study.candidates_z.len();
            let svg = ColourMap {
                title: format!("{}: separability of {} {}", set.name, quantity_name(q), top.feature.name()),
                x: Axis::linear("x (mm)"),
                y: Axis::linear("z (mm)"),
                xs: study.candidates_x.iter().map(|x| x * 1e3).collect(),
                ys: study.candidates_z.iter().map(|z| z * 1e3).collect(),
                edges: false,
                values: (0..study.candidates_x.len())
                    .map(|i| (0..nz).map(|j| values[i * nz + j].separability()).collect())
                    .collect(),
                bar: Axis::linear("max(AUC, 1 - AUC)"),
                missing: None,
                marks: vec![],
                notes: vec![],
            }
            .svg();
            let file = format!("{stem}-map-{}.svg", quantity_name(q));
            maps_md.push_str(&format!("![{} map]({file})\n\n", quantity_name(q)));
            artifacts.add(file, svg);
        }
    }

    // Histograms: the best feature overall and P_max.
    let mut hist_md = String::new();
    if let Some(top) = order.first() {
        let (c, g) = run.table.split(top.channel, top.feature);
        let label = format!(
            "{} {} ({})",
            infos[top.channel].label(),
            top.feature.name(),
            top.feature.unit(infos[top.channel].unit)
        );
        let file = format!("{stem}-hist-best.svg");
        artifacts.add(&file, histogram(&format!("{}: best feature", set.name), &label, &c, &g, top.feature.is_scale()));
        hist_md.push_str(&format!("![best feature]({file})\n\n"));
    }
    let file = format!("{stem}-hist-force.svg");
    artifacts.add(&file, histogram(&format!("{}: contact force", set.name), "P_max (N)", &fc, &fg, true));
    hist_md.push_str(&format!("![contact force]({file})\n\n"));

    // The reference feature of the variability study: the most separating one the modal
    // truncation does not move, else the best sensor's.
    let converged_entry = order
        .iter()
        .find(|s| {
            resolved(s.auc.auc - half_all[s.channel * FEATURES.len() + s.feature.index()].auc.auc, s.auc.standard_error)
        })
        .map(|s| **s);
    let reference_entry = converged_entry.or(best_sensor_entry);

    // Classifiers, each also fitted on the half-mode run.
    let sensor_group = |s: &Separability, what: &str| -> (String, Vec<usize>) {
        let sensor = infos[s.channel].sensor;
        let chans = (0..infos.len()).filter(|&c| infos[c].sensor == sensor).collect();
        (
            format!(
                "{what} 3 quantities × {} features, at ({}, {}) mm",
                FEATURES.len(),
                mm(infos[s.channel].at.0),
                mm(infos[s.channel].at.1)
            ),
            chans,
        )
    };
    let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
    if let Some(s) = best_sensor_entry {
        groups.push(sensor_group(&s, "the best sensor's"));
    }
    if let Some(s) = converged_entry.filter(|c| infos[c.channel].sensor.is_some()) {
        if best_sensor_entry.is_none_or(|b| infos[b.channel].sensor != infos[s.channel].sensor) {
            groups.push(sensor_group(&s, "the reference feature's sensor:"));
        }
    }
    let corner_channels: Vec<usize> = (0..infos.len()).filter(|&c| infos[c].sensor.is_none()).collect();
    if !corner_channels.is_empty() {
        groups.push((
            format!(
                "the {} corner channels (spring forces, reactions) × {} features",
                corner_channels.len(),
                FEATURES.len()
            ),
            corner_channels.clone(),
        ));
    }
    if named > 0 {
        groups.push((
            format!(
                "every named sensor and corner channel ({} channels) × {} features",
                named * 3 + corner_channels.len(),
                FEATURES.len()
            ),
            (0..infos.len()).filter(|&c| infos[c].sensor.is_none_or(|s| s < named)).collect(),
        ));
    }
    let mut classifiers = Vec::new();
    for (k, (features, chans)) in groups.into_iter().enumerate() {
        let result = classifier(&run.table, &chans, seed ^ (3 + k as u64))?;
        let coarse = classifier(&half.table, &chans, seed ^ (3 + k as u64))?;
        classifiers.push(Accuracy { features, result, resolution: result.accuracy - coarse.accuracy });
    }

    // The variability study, on the reference instrument: the named sensors, the reference
    // feature's sensor, the corners.
    let mut reference_sensors = settings.sensors.clone();
    let mut reference = reference_entry.map(|s| (infos[s.channel].kind, s.feature));
    if let Some((kind, feature)) = reference {
        if let Some(s) = infos.iter().find(|i| i.kind == kind).and_then(|i| i.sensor) {
            if s >= named {
                reference_sensors.push(sensors[s]);
                let moved = match kind {
                    ChannelKind::Displacement { .. } => ChannelKind::Displacement { sensor: named },
                    ChannelKind::Velocity { .. } => ChannelKind::Velocity { sensor: named },
                    ChannelKind::Acceleration { .. } => ChannelKind::Acceleration { sensor: named },
                    other => other,
                };
                reference = Some((moved, feature));
            }
        }
    }
    let reference_instrument = Instrument::new(
        &model,
        plate,
        &spec(settings, reference_sensors.clone()),
        scene.restitution,
        scene.contact_law,
    )?;
    let ref_infos: Vec<ChannelInfo> =
        reference_instrument.channels().into_iter().map(|k| ChannelInfo::new(k, &reference_sensors, plate)).collect();
    let mut variants: Vec<Held> = study.hold.iter().map(|v| Held::only(*v)).collect();
    if !study.hold.is_empty() {
        variants.push(Held { position: true, size: true, speed: true, material: false });
    }
    let all_channels: Vec<usize> = (0..ref_infos.len()).collect();
    let mut held = Vec::new();
    for (k, h) in variants.into_iter().enumerate() {
        let bar = progress(e.len(), format!("{}: {} held", set.name, held_label(h)));
        let r = run_condition(study, h, &reference_instrument, |_: &ImpactRecord| -> Result<(), Failure> {
            bar.inc(1);
            Ok(())
        })
        .map_err(|err| run_failure(&set.name, err))?;
        bar.finish_and_clear();
        let seps = separabilities(&r.table);
        let reference_auc = reference
            .and_then(|(kind, f)| ref_infos.iter().position(|i| i.kind == kind).map(|c| (c, f)))
            .map_or(Auc { auc: 0.5, standard_error: 0.0 }, |(c, f)| {
                let (a, b) = r.table.split(c, f);
                auc_with_error(&a, &b)
            });
        let Some(top) = best(&seps, &[]) else { continue };
        let (a, b) = r.table.split(top.channel, top.feature);
        let (pc, pg) = split(&r.force_max, r.table.classes());
        held.push(Held1 {
            which: h,
            held: held_label(h),
            reference: reference_auc,
            best: ranked(ref_infos[top.channel].label(), top.feature, (&a, &b), None, seed ^ (100 + k as u64)),
            force_max: auc_with_error(&pc, &pg),
            accuracy: classifier(&r.table, &all_channels, seed ^ (200 + k as u64))?,
        });
    }
    let reference_ranked = reference_entry.map(|s| rank_of(&s, TOP + 3));

    let result = ConditionResult {
        condition: set.name.clone(),
        fundamental_hz: run.fundamental_hz,
        validity: run.validity,
        ranking,
        best_sensor,
        best_converged,
        force_max,
        contact_time,
        classifiers,
        reference: reference_ranked,
        held,
        setup_seconds,
        run_seconds,
        impacts_per_second: e.len() as f64 / run_seconds.max(1e-9),
        feature_bytes: held_bytes,
        full_model,
    };
    let markdown = condition_markdown(
        &result,
        settings.modes,
        scene.contact_law,
        &maps_md,
        &hist_md,
        reference.map(|(k, f)| {
            let i = ref_infos.iter().find(|i| i.kind == k).map_or_else(|| "-".to_string(), |i| i.label());
            format!("{i}, {}", f.name())
        }),
    )?;
    Ok(ConditionOutput { result, markdown })
}

/// The median impact of the first family on the full Newmark model and on `instrument`.
fn full_model_check(
    scene: &Scene,
    study: &Study,
    settings: &SignalSettings,
    set: &SupportSet,
    instrument: &Instrument<'_>,
) -> Result<FullModelCheck, Failure> {
    let e = &study.ensemble;
    let all = Held { position: true, size: true, speed: true, material: true };
    let draw = e.draw(0, all).ok_or("the ensemble is empty")?;
    let name = &e.families[draw.family].name;
    let sphere = draw.sphere(name)?;
    let striker = coupled::transient::Striker {
        k: analytic::contact_stiffness(&sphere, scene.plate.material()),
        restitution: scene.restitution,
        mass: sphere.mass(),
        velocity: draw.velocity,
        law: scene.contact_law.law_for(&sphere),
    };
    let reduced = instrument.impact(draw.clone(), name)?;
    let t = Instant::now();
    let props = coupled::discretisation::plate_properties(&scene.plate);
    let fe = plate_fem::Model::new(props, coupled::discretisation::mesh_for(&props, settings.reduced().elements)?)?;
    let full =
        crate::transient::transient(&fe, set.supports, &striker, draw.x, draw.z, settings.reduced().steps_per_contact)?;
    let seconds = t.elapsed().as_secs_f64();
    let full_force = full.force_max_interpolated.max(full.force_max);
    let contact_time_difference = match (reduced.contact_time, full.contact_time) {
        (Some(a), Some(b)) if b > 0.0 => a / b - 1.0,
        _ => 0.0,
    };
    Ok(FullModelCheck {
        seconds,
        force_max: full_force,
        force_difference: reduced.force_max / full_force - 1.0,
        contact_time_difference,
    })
}

// ---------------------------------------------------------------- the report

fn ci(r: &Ranked) -> String {
    format!("{}-{}", sig(r.interval.0, 3), sig(r.interval.1, 3))
}

fn direction(a: &Auc) -> &'static str {
    if a.gangue_higher() {
        "gangue higher"
    } else {
        "coal higher"
    }
}

fn percent(n: usize, of: usize) -> String {
    format!("{} %", sig(100.0 * n as f64 / of.max(1) as f64, 3))
}

fn condition_markdown(
    r: &ConditionResult,
    modes: usize,
    law: coupled::transient::LawKind,
    maps: &str,
    hists: &str,
    reference: Option<String>,
) -> Result<String, Failure> {
    let law_note = if law.is_elastic() {
        render("identify/law-elastic.md", LAW_ELASTIC, &[("law", law.key().to_string())])?
    } else {
        render("identify/law-plastic.md", LAW_PLASTIC, &[("law", law.key().to_string())])?
    };
    let law_note = law_note.trim_end();
    let mut ranking = Table::new(
        "",
        &["channel", "feature", "AUC", "DeLong SE", "95 % bootstrap CI", "AUC(N) - AUC(N/2)", "direction"],
    );
    let extra = r
        .best_converged
        .as_ref()
        .filter(|b| !r.ranking.iter().any(|x| x.channel == b.channel && x.feature == b.feature));
    for x in std::iter::once(&r.force_max).chain([&r.contact_time]).chain(&r.ranking).chain(extra) {
        ranking.push(vec![
            x.channel.clone().into(),
            x.feature.name().into(),
            Cell::Text(sig(x.auc.auc, 3)),
            Cell::Text(sig(x.auc.standard_error, 2)),
            ci(x).into(),
            x.resolution
                .map_or(Cell::Empty, |d| Cell::Text(format!("{}{}", sig(d, 2), if x.converged() { "" } else { " *" }))),
            direction(&x.auc).into(),
        ]);
    }
    let mut acc = Table::new("", &["features", "accuracy", "SE", "accuracy(N) - accuracy(N/2)"]);
    for a in &r.classifiers {
        acc.push(vec![
            a.features.clone().into(),
            Cell::Text(sig(a.result.accuracy, 3)),
            Cell::Text(sig(a.result.standard_error, 2)),
            Cell::Text(sig(a.resolution, 2)),
        ]);
    }
    let mut held = Table::new(
        "",
        &[
            "held at the median",
            "reference AUC",
            "best feature of the run",
            "its AUC (95 % CI)",
            "P_max AUC",
            "classifier accuracy",
        ],
    );
    for h in &r.held {
        held.push(vec![
            h.held.clone().into(),
            Cell::Text(format!("{} ± {}", sig(h.reference.auc, 3), sig(h.reference.standard_error, 2))),
            format!("{} {}", h.best.channel, h.best.feature.name()).into(),
            Cell::Text(format!("{} ({})", sig(h.best.auc.auc, 3), ci(&h.best))),
            Cell::Text(sig(h.force_max.auc, 3)),
            Cell::Text(format!("{} ± {}", sig(h.accuracy.accuracy, 3), sig(h.accuracy.standard_error, 2))),
        ]);
    }
    let v = &r.validity;
    let held_md = if r.held.is_empty() {
        "No variable held (the scene's `hold = []`).".to_string()
    } else {
        format!(
            "Reference: {}. Each row reruns the same impacts (the same random numbers) with one variable at its median.\n\n{}",
            reference.unwrap_or_else(|| "-".into()),
            held.to_markdown()
        )
    };
    Ok(render(
        "identify/condition.md",
        CONDITION,
        &[
            ("condition", r.condition.clone()),
            ("fundamental_hz", sig(r.fundamental_hz, 4)),
            ("ranking", ranking.to_markdown()),
            ("modes", modes.to_string()),
            ("half_modes", (modes / 2).max(1).to_string()),
            ("resolution", sig(AUC_RESOLUTION, 2)),
            ("classifiers", acc.to_markdown()),
            (
                "maps",
                if maps.is_empty() {
                    "No candidate grid in the scene ([ensemble.placement]).\n".into()
                } else {
                    maps.to_string()
                },
            ),
            ("histograms", hists.to_string()),
            ("held", held_md),
            ("impacts", v.impacts.to_string()),
            ("beyond_elastic", percent(v.beyond_elastic, v.impacts)),
            ("not_quasi_static", percent(v.not_quasi_static, v.impacts)),
            ("recontact", percent(v.recontact, v.impacts)),
            ("unfinished", percent(v.unfinished, v.impacts)),
            ("law", law_note.to_string()),
        ],
    )?)
}

fn finding(r: &ConditionResult, modes: usize) -> Result<String, Failure> {
    let dash = || "-".to_string();
    let top = r.ranking.first();
    let best_classifier = r.classifiers.iter().max_by(|a, b| a.result.accuracy.total_cmp(&b.result.accuracy));
    let single = |h: &&Held1| {
        [h.which.position, h.which.size, h.which.speed, h.which.material].iter().filter(|x| **x).count() == 1
    };
    let most =
        r.held.iter().filter(single).max_by(|a, b| a.reference.separability().total_cmp(&b.reference.separability()));
    let paper = r.held.iter().find(|h| h.which.position && h.which.size && h.which.speed && !h.which.material);
    let held = match (most, paper, &r.reference) {
        (Some(m), Some(p), Some(reference)) => render(
            "identify/finding-held.md",
            FINDING_HELD,
            &[
                ("reference", format!("the {} of the {}", reference.feature.name(), reference.channel)),
                ("variable", m.held.clone()),
                ("free", sig(reference.auc.auc, 3)),
                ("auc", sig(m.reference.auc, 3)),
                ("se", sig(m.reference.standard_error, 2)),
                ("paper_auc", sig(p.reference.auc, 3)),
                ("paper_se", sig(p.reference.standard_error, 2)),
            ],
        )?,
        _ => String::new(),
    };
    let resolution = match (top, &r.best_converged) {
        (Some(t), Some(b)) if !t.converged() => render(
            "identify/finding-resolution.md",
            FINDING_RESOLUTION,
            &[
                ("delta", t.resolution.map_or_else(dash, |d| sig(d, 2))),
                ("half_modes", (modes / 2).max(1).to_string()),
                ("modes", modes.to_string()),
                ("feature", b.feature.name().to_string()),
                ("channel", b.channel.clone()),
                ("auc", sig(b.auc.auc, 3)),
                ("ci", ci(b)),
            ],
        )?,
        _ => String::new(),
    };
    Ok(render(
        "identify/finding.md",
        FINDING,
        &[
            ("condition", r.condition.clone()),
            ("feature", top.map_or_else(dash, |t| t.feature.name().to_string())),
            ("channel", top.map_or_else(dash, |t| t.channel.clone())),
            ("best_auc", top.map_or_else(dash, |t| sig(t.auc.auc, 3))),
            ("best_ci", top.map_or_else(dash, ci)),
            ("resolution", resolution.trim_end().to_string()),
            ("force_auc", sig(r.force_max.auc.auc, 3)),
            ("force_ci", ci(&r.force_max)),
            ("classifier", best_classifier.map_or_else(dash, |a| a.features.clone())),
            ("accuracy", best_classifier.map_or_else(dash, |a| sig(a.result.accuracy, 3))),
            ("accuracy_se", best_classifier.map_or_else(dash, |a| sig(a.result.standard_error, 2))),
            ("held", held.trim_end().to_string()),
        ],
    )?)
}

/// The scene's ensemble, after checking before anything runs that every support set records
/// a channel and that the features held for one support set fit the memory budget.
pub fn checked_study(scene: &Scene) -> Result<&Study, Failure> {
    let study = scene.ensemble.as_ref().ok_or_else(|| {
        format!("scene {}: impact identify needs an [ensemble] table and \"identify\" in analyses", scene.name)
    })?;
    for set in &scene.conditions {
        let channels = channels_per_impact(scene, study, set);
        if channels == 0 {
            return Err(no_channels(&set.name));
        }
        let bytes = feature_bytes(study.ensemble.len(), channels);
        if bytes as f64 > studies::run::MEMORY_BUDGET_BYTES {
            return Err(format!(
                "the ensemble's features are {} impacts x {channels} channels x {} features, about {:.1} GB for support set '{}'; the budget is {:.0} GB: use fewer impacts or candidate points",
                study.ensemble.len(),
                FEATURES.len(),
                bytes as f64 / 1e9,
                set.name,
                studies::run::MEMORY_BUDGET_BYTES / 1e9
            )
            .into());
        }
    }
    Ok(study)
}

/// `impact identify`, also run by `impact report` for its identification scenes: the
/// identification of `scene` (which must carry an ensemble), its row files streamed into
/// `out` under `dir` ("" for the top), and the report's files, under `dir` and carrying the
/// scene's provenance like the streamed ones, with the summary.
pub fn write(scene: &Scene, out: &mut OutputDir, dir: &str, files: RowFiles) -> Result<(Artifacts, Summary), Failure> {
    checked_study(scene)?;
    let provenance = Provenance::of(scene);
    let (mut artifacts, summary) = report(scene, out, dir, &provenance, files)?;
    provenance.stamp(&mut artifacts);
    if dir.is_empty() {
        return Ok((artifacts, summary));
    }
    let mut nested = Artifacts::new();
    nested.nest(dir, artifacts);
    Ok((nested, summary))
}

/// Runs the identification, streaming the rows into `out` under `dir`; returns the report's
/// files (relative to `dir`) and the summary.
fn report(
    scene: &Scene,
    out: &mut OutputDir,
    dir: &str,
    provenance: &Provenance,
    files: RowFiles,
) -> Result<(Artifacts, Summary), Failure> {
    let study = checked_study(scene)?;
    let settings = &scene.signals;
    let mut rows = Rows::open(out, dir, provenance, files)?;
    let mut artifacts = Artifacts::new();
    let mut conditions = Vec::new();
    let mut sections = String::new();
    for (i, set) in scene.conditions.iter().enumerate() {
        let c = run_set(scene, study, settings, set, i, &mut rows, &mut artifacts)?;
        sections.push_str(&c.markdown);
        conditions.push(c.result);
    }
    rows.finish(out)?;
    let e = &study.ensemble;
    let summary = Summary {
        scene: scene.name.clone(),
        impacts: e.len(),
        classes: e.class_counts(),
        contact_law: scene.contact_law.key(),
        signals: settings.clone(),
        conditions,
    };
    let mut findings = String::new();
    for c in &summary.conditions {
        findings.push_str(&finding(c, settings.modes)?);
    }
    let mut families = Table::new(
        "",
        &[
            "family",
            "class",
            "count",
            "radius",
            "density",
            "Young's modulus",
            "Poisson ratio",
            "cohesion",
            "friction angle",
        ],
    );
    for f in &e.families {
        families.push(vec![
            f.name.clone().into(),
            f.class.key().into(),
            f.count.into(),
            describe(&f.radius, "mm", 1e3).into(),
            describe(&f.density, "kg/m³", 1.0).into(),
            describe(&f.youngs_modulus, "GPa", 1e-9).into(),
            describe(&f.poisson_ratio, "", 1.0).into(),
            describe(&f.cohesion, "MPa", 1e-6).into(),
            describe(&f.friction_angle_deg, "°", 1.0).into(),
        ]);
    }
    let speed = match &e.speed {
        Speed::FallHeight(h) => format!("free fall from rest, v = √(2gh), fall height h {}", describe(h, "m", 1.0)),
        Speed::Velocity(v) => format!("velocity {}", describe(v, "m/s", 1.0)),
    };
    let sensors = if settings.sensors.is_empty() {
        "none named".to_string()
    } else {
        settings.sensors.iter().map(|(x, z)| format!("({}, {}) mm", mm(*x), mm(*z))).collect::<Vec<_>>().join(", ")
    };
    let candidates = if study.candidates_x.is_empty() {
        "none".to_string()
    } else {
        format!("{} x {} points from (0, 0) to (L, B)", study.candidates_x.len(), study.candidates_z.len())
    };
    let mut timing = Table::new(
        "",
        &[
            "support set",
            "model set-up (s)",
            "ensemble run (s)",
            "impacts/s",
            "one full Newmark impact (s)",
            "speed-up per impact",
            "reduced/full P_max - 1",
            "reduced/full t_c - 1",
            "features held (MB)",
        ],
    );
    for c in &summary.conditions {
        let per_impact = c.run_seconds / summary.impacts.max(1) as f64;
        timing.push(vec![
            c.condition.clone().into(),
            Cell::Text(sig(c.setup_seconds, 3)),
            Cell::Text(sig(c.run_seconds, 3)),
            Cell::Text(sig(c.impacts_per_second, 3)),
            Cell::Text(sig(c.full_model.seconds, 3)),
            Cell::Text(sig(c.full_model.seconds / per_impact.max(1e-12), 3)),
            Cell::Text(sig(c.full_model.force_difference, 2)),
            Cell::Text(sig(c.full_model.contact_time_difference, 2)),
            Cell::Text(sig(c.feature_bytes as f64 / 1e6, 3)),
        ]);
    }
    let head = render(
        "identify/head.md",
        HEAD,
        &[
            ("scene", scene.name.clone()),
            ("findings", findings),
            ("impacts", e.len().to_string()),
            ("coal", summary.classes.0.to_string()),
            ("gangue", summary.classes.1.to_string()),
            ("seed", e.seed.to_string()),
            (
                "region",
                format!(
                    "x in [{}, {}] mm, z in [{}, {}] mm",
                    mm(e.region.x.0),
                    mm(e.region.x.1),
                    mm(e.region.z.0),
                    mm(e.region.z.1)
                ),
            ),
            ("speed", speed),
            ("families", families.to_markdown()),
            ("window_ms", sig(settings.window * 1e3, 3)),
            ("rate_hz", sig(settings.rate_hz, 3)),
            ("modes", settings.modes.to_string()),
            ("damping", sig(settings.damping_ratio * 100.0, 3)),
            ("contact_law", scene.contact_law.key().to_string()),
            ("restitution", sig(scene.restitution, 3)),
            ("sensors", sensors),
            ("candidates", candidates),
        ],
    )?;
    let method = render(
        "identify/method.md",
        METHOD,
        &[
            ("resamples", BOOTSTRAP_RESAMPLES.to_string()),
            ("folds", FOLDS.to_string()),
            ("ridge", sig(RIDGE, 3)),
            ("top", TOP.to_string()),
            ("timing", timing.to_markdown()),
            ("threshold", sig(identify::features::DURATION_THRESHOLD * 100.0, 3)),
            ("taper", sig(identify::features::TAPER_FRACTION * 100.0, 3)),
            ("chunk", CHUNK.to_string()),
            (
                "features_file",
                match files {
                    RowFiles::All => "Both are here.",
                    RowFiles::Impacts => {
                        "This run wrote `impacts.csv` only; `impact identify --scene FILE` writes `features.csv` too."
                    }
                }
                .to_string(),
            ),
        ],
    )?;
    artifacts.add("index.md", format!("{head}{sections}{method}"));
    artifacts.add("summary.json", serde_json::to_string_pretty(&summary)? + "\n");
    Ok((artifacts, summary))
}

/// The summary as tables for the terminal.
pub fn summary_tables(s: &Summary) -> Vec<Table> {
    let mut t = Table::new(
        format!(
            "{}: coal against gangue over {} impacts per support set ({} coal, {} gangue); AUC with 95 % CI, and its change from N/2 to N modes",
            s.scene, s.impacts, s.classes.0, s.classes.1
        ),
        &[
            "support set",
            "best feature",
            "AUC",
            "N/2 to N",
            "best feature resolved in N",
            "AUC",
            "P_max AUC",
            "best accuracy",
            "beyond elastic",
            "impacts/s",
        ],
    );
    let auc = |r: &Ranked| Cell::Text(format!("{} ({})", sig(r.auc.auc, 3), ci(r)));
    let name = |r: &Ranked| Cell::Text(format!("{} {}", r.feature.name(), r.channel));
    for c in &s.conditions {
        let top = c.ranking.first();
        let acc = c.classifiers.iter().map(|a| a.result.accuracy).fold(f64::NAN, f64::max);
        t.push(vec![
            c.condition.clone().into(),
            top.map_or(Cell::Empty, name),
            top.map_or(Cell::Empty, auc),
            top.and_then(|r| r.resolution).map_or(Cell::Empty, |d| Cell::Text(sig(d, 2))),
            c.best_converged.as_ref().map_or(Cell::Empty, name),
            c.best_converged.as_ref().map_or(Cell::Empty, auc),
            auc(&c.force_max),
            if acc.is_finite() { Cell::Text(sig(acc, 3)) } else { Cell::Empty },
            percent(c.validity.beyond_elastic, c.validity.impacts).into(),
            Cell::Text(sig(c.impacts_per_second, 3)),
        ]);
    }
    vec![t]
}
