//! The identification study (`impact identify`): the scene's random-impact ensemble struck on
//! every support set, and how well the response tells coal from gangue.
//!
//! Per support set the reduced model is built once and the whole ensemble thrown on it
//! ([`ensemble`]); every feature of every channel is then scored by its ROC AUC (Mann-Whitney,
//! DeLong's standard error, a percentile bootstrap interval: [`separability`]), mapped over the
//! candidate grid ([`placement`]), and whole sensors are scored by the cross-validated accuracy
//! of a logistic classifier ([`classifiers`]). The same impacts on half the modes measure what
//! each number owes to the modal truncation, and reruns with one variable at its median measure
//! which variability hides the difference ([`variability`]). One impact on the full Newmark
//! model checks the reduced one ([`full_model`]).
//!
//! The physics is in `coupled::identification` and the statistics in crate `identify`; here
//! they are composed into plain serde data ([`IdentifyData`]). Nothing is written: the main
//! run's impacts reach a caller's sink in impact order ([`compute_with`]), so the rows can be
//! streamed to disk while no more than one chunk of records is held.

pub mod baselines;
pub mod check;
pub mod classifiers;
pub mod ensemble;
pub mod full_model;
pub mod measured;
pub mod placement;
pub mod sensors;
pub mod separability;
mod set;
pub mod variability;

pub use sensors::{channels_per_impact, feature_bytes, no_channels, run_sensors};

use crate::channel::ChannelInfo;
use crate::progress::Progress;
use crate::Failure;
use coupled::identification::{EnsembleValidity, ImpactRecord};
use coupled::reduced::SignalSettings;
use identify::classify::CrossValidated;
use identify::features::FEATURES;
use identify::roc::Auc;
use identify::{Feature, Held, Study};
use scene::Scene;
use serde::Serialize;

/// Entries of the ranking that get a bootstrap interval (the rest carry DeLong's error).
pub const TOP: usize = 10;
/// The confidence level of every interval.
pub const LEVEL: f64 = 0.95;
/// A change in AUC below which no conclusion here changes (the AUCs are quoted to 3 digits
/// and separabilities compared in steps of a few hundredths).
pub const AUC_RESOLUTION: f64 = 0.01;

/// Whether a change `delta` of an AUC with standard error `se` between N/2 and N modes is
/// within the sampling error or below [`AUC_RESOLUTION`]: the modal truncation then moves the
/// AUC by less than the ensemble can resolve.
pub fn resolved(delta: f64, se: f64) -> bool {
    delta.abs() <= se.max(AUC_RESOLUTION)
}

/// The check of the modal truncation on one support set.
#[derive(Debug, Clone, Serialize)]
pub struct TruncationCheck {
    /// Impacts struck again on N/2 modes.
    pub impacts: usize,
    /// Impacts of the main run.
    pub of: usize,
    /// The scene's `signals.truncation_check_fraction`.
    pub fraction: f64,
    /// Whether only some impacts were struck again (a share below 1 may keep them all).
    pub sampled: bool,
    /// With every impact struck again, how well subsamples of each of
    /// [`check::COVERAGE_FRACTIONS`] would have stood for the check (empty otherwise).
    pub coverage: Vec<check::SubsampleCheck>,
}

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
    /// The standard error of `resolution` as the whole ensemble's change, when the check
    /// struck a subsample again (`signals.truncation_check_fraction` below 1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub resolution_error: Option<f64>,
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
    /// The best feature against the trivial baselines (contact time, P_max, mass).
    pub headline: baselines::Headline,
    /// Classifiers.
    pub classifiers: Vec<Accuracy>,
    /// The reference feature of the variability study (the most separating one the modal
    /// truncation does not move, else the best sensor's best).
    pub reference: Option<Ranked>,
    /// The variability study.
    pub held: Vec<Held1>,
    /// Seconds for the reduced model's set-up (modes, residual flexibility).
    pub setup_seconds: f64,
    /// Seconds for the main ensemble run (impacts, features, the caller's sink).
    pub run_seconds: f64,
    /// Impacts per second of that run.
    pub impacts_per_second: f64,
    /// Bytes of features held in memory for the run.
    pub feature_bytes: usize,
    /// The reference impact (every variable at its median, the first family) on the full
    /// Newmark model of the same mesh and step rule: seconds, and the reduced model's P_max
    /// relative to it.
    pub full_model: FullModelCheck,
    /// What the measurement chain did, if the scene has one.
    pub measurement: Option<measured::ChainSummary>,
    /// The modes kept on this support set where the chain chose them (`[signals] modes =
    /// "chain"`); left out otherwise, when the scene's count holds.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub chain_modes: Option<usize>,
    /// The sensor design, where the scene asks for one (`[ensemble.placement]
    /// design_sensors`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub design: Option<SensorDesign>,
    /// The design chosen again at each of the scene's other backgrounds
    /// (`[ensemble.placement] design_backgrounds`); empty without them.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub design_backgrounds: Vec<BackgroundDesign>,
    /// The check of the modal truncation: which impacts it struck again and, when it struck
    /// them all, how well subsamples would have stood for it.
    pub truncation_check: TruncationCheck,
}

impl ConditionResult {
    /// The modes the reduced model kept on this support set, given the scene's `signals`.
    pub fn modes(&self, signals: &coupled::reduced::SignalSettings) -> usize {
        self.chain_modes.unwrap_or(signals.modes)
    }
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

/// What the identification found, for the terminal and the JSON (`summary.json`).
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

/// The separability of one feature over the candidate grid: a placement map.
#[derive(Debug, Clone, Serialize)]
pub struct PlacementMap {
    /// The quantity ("displacement", "velocity", "acceleration", "strain").
    pub quantity: &'static str,
    /// The feature whose best grid value is highest for that quantity.
    pub feature: &'static dyn Feature,
    /// The grid's x, mm.
    pub x_mm: Vec<f64>,
    /// The grid's z, mm.
    pub z_mm: Vec<f64>,
    /// max(AUC, 1 - AUC) at each grid point, `[x][z]`.
    pub separability: Vec<Vec<f64>>,
}

/// The sensor design of one support set: sensors of one quantity chosen one at a time among
/// the candidate grid by the cross-validated AUC of the logistic classifier on every feature
/// of the sensors chosen ([`identify::design`]).
#[derive(Debug, Clone, Serialize)]
pub struct SensorDesign {
    /// The quantity ("acceleration", ...): that of the placement map peaking highest.
    pub quantity: &'static str,
    /// The grid's x, mm.
    pub x_mm: Vec<f64>,
    /// The grid's z, mm.
    pub z_mm: Vec<f64>,
    /// Every step, in the order the sensors were added.
    pub steps: Vec<DesignStep>,
}

/// The sensor design at one background level.
#[derive(Debug, Clone, Serialize)]
pub struct BackgroundDesign {
    /// The scale of the chain's background (1: as stated, 0: quantisation alone).
    pub scale: f64,
    /// The SNR the first sensor chosen ran at, dB: its median coal peak before the
    /// background over the RMS of the background (its noise and tones) at this scale and the
    /// quantisation (None without coal or for a silent channel). Nominal where the ADC clips.
    pub snr_db: Option<f64>,
    /// The design (None where no placement map could be drawn).
    pub design: Option<SensorDesign>,
}

/// One sensor added.
#[derive(Debug, Clone, Serialize)]
pub struct DesignStep {
    /// Where, (x, z) mm.
    pub at_mm: (f64, f64),
    /// The cross-validated AUC of the sensors so far, with DeLong's standard error.
    pub auc: identify::Auc,
    /// Its gain over the step before (the first's over chance, 0.5).
    pub gain: f64,
    /// DeLong's paired standard error of the gain.
    pub gain_standard_error: f64,
    /// The AUC had each grid point been added instead, `[x][z]` (None: already chosen).
    pub map: Vec<Vec<Option<f64>>>,
}

/// The values of one column split by class, for a histogram.
#[derive(Debug, Clone, Serialize)]
pub struct ClassValues {
    /// What the values are, with their unit.
    pub label: String,
    /// Coal impacts' values.
    pub coal: Vec<f64>,
    /// Gangue impacts' values.
    pub gangue: Vec<f64>,
    /// Whether the feature is a scale (drawn on a log axis when every value is positive).
    pub scale: bool,
}

/// What a support set's section shows besides its results: maps, histograms, the reference.
#[derive(Debug, Clone, Serialize)]
pub struct ConditionDetail {
    /// One map per quantity recorded over the whole grid (none without a grid).
    pub maps: Vec<PlacementMap>,
    /// The most separating feature's values.
    pub best: Option<ClassValues>,
    /// P_max's values.
    pub force_max: ClassValues,
    /// The variability study's reference feature: its channel on the reference instrument
    /// and its name.
    pub reference: Option<String>,
}

/// The identification of a scene.
#[derive(Debug, Clone, Serialize)]
pub struct IdentifyData {
    /// What was found (`summary.json`).
    pub summary: Summary,
    /// Per support set, in the summary's order: what its section shows besides.
    pub details: Vec<ConditionDetail>,
}

/// One impact of a support set's main run, as the caller's sink receives it.
pub struct MainImpact<'a> {
    /// The support set's name.
    pub condition: &'a str,
    /// The impact.
    pub record: &'a ImpactRecord,
    /// Its family's name.
    pub family: &'a str,
    /// The run's channels, in the order of the record's features.
    pub channels: &'a [ChannelInfo],
}

/// Where the main run's impacts go as they are computed.
pub type Sink<'s> = dyn FnMut(&MainImpact<'_>) -> Result<(), Failure> + 's;

/// The scene's ensemble, after checking before anything runs that every support set records
/// a channel and that the features held for one support set fit the memory budget.
pub fn checked_study(scene: &Scene) -> Result<&Study, Failure> {
    let study = scene.ensemble.as_ref().ok_or_else(|| {
        format!("scene {}: impact identify needs an [ensemble] table and \"identify\" in analyses", scene.name)
    })?;
    if scene.identifies_on_tail_beam() {
        return Err(format!(
            "scene {}: its identification strikes its tail beam, as a caving stream (impact stream); the ensemble of single impacts (impact identify) strikes the plate's support sets only",
            scene.name
        )
        .into());
    }
    for set in &scene.conditions {
        let channels = channels_per_impact(scene, study, set);
        if channels == 0 {
            return Err(no_channels(&set.name));
        }
        // Under a chain each impact and channel also keeps its clean peak.
        let peaks = if scene.measurement.is_some() { 8 * study.ensemble.len() * channels } else { 0 };
        let bytes = feature_bytes(study.ensemble.len(), channels) + peaks;
        if bytes as f64 > crate::run::MEMORY_BUDGET_BYTES {
            return Err(format!(
                "the ensemble's features are {} impacts x {channels} channels x {} features, about {:.1} GB for support set '{}'; the budget is {:.0} GB: use fewer impacts or candidate points",
                study.ensemble.len(),
                FEATURES.len(),
                bytes as f64 / 1e9,
                set.name,
                crate::run::MEMORY_BUDGET_BYTES / 1e9
            )
            .into());
        }
    }
    Ok(study)
}

/// The identification of `scene` (which must carry an ensemble), every support set in turn,
/// each main-run impact handed to `sink` in impact order.
pub fn compute_with(scene: &Scene, progress: &dyn Progress, sink: &mut Sink<'_>) -> Result<IdentifyData, Failure> {
    let study = checked_study(scene)?;
    let mut conditions = Vec::new();
    let mut details = Vec::new();
    for (i, set) in scene.conditions.iter().enumerate() {
        let (result, detail) = set::run_set(scene, study, set, i, progress, sink)?;
        conditions.push(result);
        details.push(detail);
    }
    let e = &study.ensemble;
    let summary = Summary {
        scene: scene.name.clone(),
        impacts: e.len(),
        classes: e.class_counts(),
        contact_law: scene.contact_law.key(),
        signals: scene.signals.clone(),
        conditions,
    };
    Ok(IdentifyData { summary, details })
}

/// The identification of `scene`, its impacts computed and dropped.
pub fn compute(scene: &Scene, progress: &dyn Progress) -> Result<IdentifyData, Failure> {
    compute_with(scene, progress, &mut |_| Ok(()))
}

/// `h` in words: "nothing", "size", "position, size and speed".
pub fn held_label(h: Held) -> String {
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
