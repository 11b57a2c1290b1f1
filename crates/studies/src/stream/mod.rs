//! Gangue detection on a continuous caving stream (`impact stream`): the scene's ensemble
//! arriving as Poisson streams whose gangue share changes, simulated as one continuous
//! signal per support set ([`coupled::reduced::stream`]), recorded through the scene's
//! measurement chain, cut into sliding windows and scored by a logistic detector
//! cross-validated by time blocks ([`identify::detect`]).
//!
//! Per support set: the main run (the scene's rate, the chain as stated) scored on every
//! channel together, on each sensor's channels, and on the supports' channels, beside the
//! baselines of the lumps' own truth per window (mean contact time, mean P_max, total mass,
//! count); then the same streams with the chain's background scaled (what survives the
//! noise) and streams at other arrival rates (what survives crowding), each scored on every
//! channel together. Then the detector on the sensors' channels carried, without refitting,
//! from each support set's main run to the other support sets and to its own sweeps
//! ([`transfer`]), and the every-channel detector fitted on every window, to take away
//! ([`identify::detector`]).

mod alone;
pub mod design;
mod on_box;
pub mod plates;
mod recorder;
mod run;
mod score;
pub mod segments;
pub mod transfer;

use crate::channel::ChannelInfo;
use crate::progress::Progress;
use crate::Failure;
use identify::stream::StreamStudy;
use scene::Scene;
use serde::Serialize;

pub use alone::one_stream;
pub use design::{FeatureWeight, WindowDesign, WindowDesignStep};
pub use on_box::truncation_shift;
pub use run::RECORDING_KEY;
pub use score::Score;
pub use transfer::TransferPoint;

/// The study's results.
#[derive(Debug, Clone, Serialize)]
pub struct StreamData {
    /// The scene's name.
    pub scene: String,
    /// The study as the scene states it.
    pub study: StreamStudy,
    /// Whether the signals ran through a measurement chain.
    pub measured: bool,
    /// Per support set.
    pub conditions: Vec<ConditionStream>,
    /// Detectors applied where they were not trained ([`transfer`]).
    pub transfer: Vec<TransferPoint>,
    /// The struck structure's model, where the stream strikes a tail beam (None: the plate).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub structure: Option<StructureFacts>,
    /// On the plate: every plate struck (the scene's and each swept one) on every support
    /// set, its kept modes against the chain's band ([`plates`]).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub bands: Vec<plates::Band>,
}

/// The model of a struck structure (a tail beam) and how far the chain's band is resolved.
#[derive(Debug, Clone, Serialize)]
pub struct StructureFacts {
    /// Unknowns of its mesh.
    pub unknowns: usize,
    /// Modes kept.
    pub modes: usize,
    /// The lowest and highest kept mode's frequency, Hz.
    pub frequencies_hz: (f64, f64),
    /// Load points the lumps strike (the mesh's top-plate nodes in the region).
    pub load_points: usize,
    /// Their largest spacing, m.
    pub spacing: f64,
    /// The chain's largest gain above the highest kept mode (None without a chain): what the
    /// modes left out could pass into the recording.
    pub gain_above_highest: Option<f64>,
    /// Whether that gain is within the chain's band tolerance (None without a chain).
    pub resolved: Option<bool>,
    /// The truncation's check: the main run's streams on the lowest half of the modes (the
    /// others joining the static correction), and the every-channel detector's score there.
    pub truncation: Option<(usize, Score)>,
}

/// One support set's detection results.
#[derive(Debug, Clone, Serialize)]
pub struct ConditionStream {
    /// The support set's name.
    pub name: String,
    /// The channels recorded.
    pub channels: Vec<String>,
    /// The main run's simulation: lumps, overlaps, cost.
    pub simulation: Simulation,
    /// The detector on channel groups (every channel first), at the scene's rate and noise.
    pub groups: Vec<Score>,
    /// The baselines: a window's lumps' own truth as the feature.
    pub baselines: Vec<Baseline>,
    /// Every channel together with the chain's background scaled.
    pub noise_sweep: Vec<NoisePoint>,
    /// Every channel together at other arrival rates.
    pub rate_sweep: Vec<RatePoint>,
    /// The main run's windows (every stream), with the every-channel score.
    #[serde(skip)]
    pub windows: Vec<WindowRow>,
    /// The main run's lumps (every stream).
    #[serde(skip)]
    pub lumps: Vec<LumpRow>,
    /// The first stream's recorded signals, when the scene asks for them: (channel, samples).
    #[serde(skip)]
    pub signal: Option<RecordedSignal>,
    /// The every-channel detector fitted on every window of the main run, to be taken away.
    #[serde(skip)]
    pub detector: identify::detector::Detector,
    /// The window-level sensor design, where the scene asks for one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub design: Option<WindowDesign>,
}

/// What the stream simulation did and cost.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Simulation {
    /// Lumps over all streams of the main run.
    pub lumps: usize,
    /// Share of them in contact at the same time as another.
    pub overlapped_share: f64,
    /// Contact steps per lump (the stream's whole contact stepping over its lumps).
    pub steps_per_lump: f64,
    /// Contact steps with two or more lumps in contact.
    pub joint_steps: usize,
    /// Joint steps whose solve did not converge.
    pub unconverged_steps: usize,
    /// Lumps let go while still in contact, after four windows resting on the plate.
    pub released_in_contact: usize,
    /// The left-out cross static correction's bound over the static compliance.
    pub cross_residual_bound: f64,
    /// Stream seconds simulated per second of computing (the model alone, no chain).
    pub real_time_factor: f64,
    /// The same for the plate ringing free over the same length (no lumps), measured in
    /// the same run: the floor of the sampling, modes × channels × samples.
    pub free_real_time_factor: f64,
    /// Modes kept and model samples per second.
    pub modes: usize,
    /// Model rate, Hz.
    pub model_rate_hz: f64,
    /// How each stream was cut in time (None: in one piece).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub segments: Option<SegmentFacts>,
}

/// How each stream was cut in time: segments run and recorded alone from rest after a
/// warm-up.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct SegmentFacts {
    /// A segment's length, s (to a whole ADC sample).
    pub length_s: f64,
    /// Its warm-up, s: ln(1/ε) over the slowest decay rate.
    pub warm_up_s: f64,
    /// ε.
    pub tolerance: f64,
    /// The slowest decay rate of the plate's modes and the chain's filters, 1/s.
    pub slowest_decay_per_s: f64,
    /// Segments of a stream.
    pub segments: usize,
    /// The share the warm-ups add to the samples a stream runs (a warm-up reaching back
    /// past the stream's start runs from there).
    pub added_share: f64,
}

/// A baseline: a window's truth as its score.
#[derive(Debug, Clone, Serialize)]
pub struct Baseline {
    /// What it is.
    pub quantity: &'static str,
    /// Its window AUC, oriented (≥ ½), with the block-bootstrap interval.
    pub auc: f64,
    /// 95 % interval.
    pub interval: (f64, f64),
}

/// The detector at one scale of the chain's background.
#[derive(Debug, Clone, Serialize)]
pub struct NoisePoint {
    /// The scale of the stated background.
    pub scale: f64,
    /// The SNR of the best channel over the streams, dB (signal and noise power).
    pub snr_db: Option<f64>,
    /// The detector on every channel.
    pub score: Score,
}

/// The detector at one arrival rate.
#[derive(Debug, Clone, Serialize)]
pub struct RatePoint {
    /// Lumps per second.
    pub rate_per_s: f64,
    /// Share of lumps in contact with another at the same time.
    pub overlapped_share: f64,
    /// The detector on every channel.
    pub score: Score,
}

/// One window of the main run.
#[derive(Debug, Clone, Serialize)]
pub struct WindowRow {
    /// Stream number.
    pub stream: usize,
    /// Start and end within its stream, s.
    pub start: f64,
    /// End, s.
    pub end: f64,
    /// Lumps touching in it.
    pub lumps: usize,
    /// Gangue lumps among them.
    pub gangue: usize,
    /// The profile's mean gangue share over it.
    pub expected_share: f64,
    /// Its label.
    pub gangue_rich: bool,
    /// The every-channel out-of-fold probability (None: left out by the blocks).
    pub score: Option<f64>,
}

/// One lump of the main run.
#[derive(Debug, Clone, Serialize)]
pub struct LumpRow {
    /// Stream number.
    pub stream: usize,
    /// First touch, s in its stream.
    pub time: f64,
    /// Family name.
    pub family: String,
    /// Whether it is gangue.
    pub gangue: bool,
    /// Mass, kg.
    pub mass: f64,
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// Struck point, m.
    pub x: f64,
    /// See `x`.
    pub z: f64,
    /// Contacts it made.
    pub contacts: usize,
    /// First contact's duration, s.
    pub contact_time: f64,
    /// Largest force, N.
    pub force_max: f64,
    /// Whether another lump was in contact at the same time.
    pub overlapped: bool,
}

/// The first stream's signals as recorded.
#[derive(Debug, Clone)]
pub struct RecordedSignal {
    /// Samples per second.
    pub rate_hz: f64,
    /// Channel names and units, e.g. "acceleration at (229.2, 180) mm (m/s^2)".
    pub names: Vec<String>,
    /// One column per channel.
    pub columns: Vec<Vec<f64>>,
}

/// Runs the stream study of `scene` (its `[stream]` table) on every support set.
pub fn compute(scene: &Scene, progress: &dyn Progress) -> Result<StreamData, Failure> {
    check(scene)?;
    let (Some(study), Some(ensemble)) = (&scene.stream, &scene.ensemble) else {
        return Err("the scene has no [stream] and [ensemble]".into());
    };
    let mut conditions = Vec::with_capacity(scene.conditions.len());
    let mut shifted = Vec::with_capacity(scene.conditions.len());
    let mut structure = None;
    let mut bands = Vec::new();
    match &scene.tail_beam {
        Some(tb) if scene.identifies_on_tail_beam() => {
            let (data, rows, facts) = on_box::condition(scene, (study, ensemble), tb, progress)?;
            conditions.push(data);
            shifted.push(rows);
            structure = Some(facts);
        }
        _ => {
            let built = plates::every_set(scene, study, progress)?;
            for (index, (set, (models, set_bands))) in scene.conditions.iter().zip(built).enumerate() {
                let (data, rows) = run::condition(scene, (study, ensemble), (set, index, &models), progress)?;
                conditions.push(data);
                shifted.push(rows);
                bands.extend(set_bands);
            }
        }
    }
    Ok(StreamData {
        scene: scene.name.clone(),
        study: study.clone(),
        measured: scene.measurement.is_some(),
        conditions,
        transfer: transfer::transfers(&shifted)?,
        structure,
        bands,
    })
}

/// Whether the scene's stream study can run and be scored, before anything runs: it has one,
/// and its cross-validation scores (the folds depend only on the study, not on the streams).
pub fn check(scene: &Scene) -> Result<(), Failure> {
    let (Some(study), Some(_)) = (&scene.stream, &scene.ensemble) else {
        return Err(format!(
            "scene {}: impact stream runs the scene's [stream] table (with [ensemble]), and it has none (see docs/scenes.md)",
            scene.name
        )
        .into());
    };
    run::window_set(study, study.spec.seed).check()
}

/// "acceleration at (229.2, 180) mm (m/s^2)".
pub(crate) fn channel_name(info: &ChannelInfo) -> String {
    format!("{} ({})", info.label(), info.unit)
}
