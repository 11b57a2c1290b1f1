//! Measured drops against the model (`impact drops`): every drop of a drop-test recording
//! (a lump of stated size and rock, dropped from a stated height onto a stated point) thrown
//! on the scene's reduced model of the same support set, through the scene's measurement
//! chain, and each channel's peak and spectral centroid, and the impact force's peak and
//! duration where the recording states them, set against the model's with its error bar.
//!
//! **The prediction and its bar.** A measured feature is one realisation of the chain's
//! noise, and noise moves a feature's mean as well as its spread (a peak of signal plus noise
//! is larger than the signal's). So the model's prediction is the mean over
//! [`REALISATIONS`] realisations of the scene's background on the model's signal, and the bar
//! is
//!
//!   bar = |ȳ_N − ȳ_{N/2}| + |ȳ_Δt − ȳ_{2Δt}| + ε_chain·|ȳ| + 3·s·√(1 + 1/K),
//!
//! the modal truncation (the same realisations on the model with half the modes: the
//! difference overstates the error at N where the feature converges in N), the contact's
//! time step (the same on the model with half the steps per contact: for a second-order
//! rule the difference is three times the error at Δt), the realised digital chain's largest
//! gain deviation from the analog one over the ADC's band taken as a relative error of the
//! feature (an estimate of a real chain's difference from the modelled one, not a bound; it
//! is zero where the recording went through the same digital chain), and three standard
//! deviations s of one realisation about a mean of K. P_max and t_c carry the two model
//! terms only: the recording's own error of them is not known here. What the bar
//! leaves out: the mesh's discretisation error (the same mesh carries both models; the
//! compliance's convergence study bounds it) and any difference between the scene's noise
//! and the rig's. A drop disagrees where |measured − predicted| exceeds its bar on any row.

use crate::identify::sensors::{channel_infos, reduced_settings, spec};
use crate::progress::Progress;
use crate::Failure;
use coupled::identification::{ImpactRecord, Instrument};
use coupled::reduced::{ReducedModel, ReducedSettings};
use identify::features::{Peak, SpectralCentroid, FEATURES};
use identify::recording::Recording;
use identify::{Draw, Feature};
use scene::drops::Drop;
use scene::Scene;
use serde::Serialize;

/// Realisations of the chain's background per prediction: the bar's s is then known to
/// about 1/√(2(K − 1)) = 18 % of itself.
pub const REALISATIONS: usize = 16;
/// The background streams of predictions start here, apart from every ensemble impact's.
const PREDICTION_KEY: usize = 1 << 40;
/// Three standard deviations: a drop the model describes falls outside with 0.3 % odds per
/// row under normal noise.
const SIGMAS: f64 = 3.0;

/// What `impact drops` computed.
#[derive(Debug, Clone, Serialize)]
pub struct DropsData {
    /// The scene's name.
    pub scene: String,
    /// The support set the drops were recorded on.
    pub condition: String,
    /// The model's channels, in the recording's column order.
    pub channels: Vec<String>,
    /// The recording's names of the same channels.
    pub recorded_as: Vec<String>,
    /// Samples per second of the recording and of the features, Hz.
    pub rate_hz: f64,
    /// Window of each drop's features, s from the touch.
    pub window: f64,
    /// Modes of the model and of its truncation check.
    pub modes: (usize, usize),
    /// Steps per Hertz contact time of the model and of its time-step check.
    pub steps_per_contact: (f64, f64),
    /// Realisations of the background per prediction (1 without a chain: no noise).
    pub realisations: usize,
    /// Every drop.
    pub drops: Vec<DropComparison>,
}

/// One drop and its rows.
#[derive(Debug, Clone, Serialize)]
pub struct DropComparison {
    /// Its position in the recording's list.
    pub index: usize,
    /// When the lump touched the plate, s from the first sample.
    pub touch: f64,
    /// The class the recording states, if any.
    pub class: Option<identify::Class>,
    /// Impact point (x, z), m.
    pub point: (f64, f64),
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// Every quantity compared.
    pub rows: Vec<Compared>,
    /// Rows outside their bar.
    pub disagreeing: usize,
}

/// One quantity of one drop: measured, predicted, and the bar.
#[derive(Debug, Clone, Serialize)]
pub struct Compared {
    /// What ("peak of acceleration at (229.2, 180) mm", "P_max").
    pub quantity: String,
    /// Its unit.
    pub unit: String,
    /// The recording's value.
    pub measured: f64,
    /// The model's (module docs).
    pub predicted: f64,
    /// |ȳ_N − ȳ_{N/2}|.
    pub truncation: f64,
    /// |ȳ_Δt − ȳ_{2Δt}|.
    pub step: f64,
    /// ε_chain·|ȳ_N|.
    pub chain: f64,
    /// s, one realisation's standard deviation (0 without noise).
    pub noise_sd: f64,
    /// The whole bar.
    pub bar: f64,
    /// |measured − predicted| > bar.
    pub disagrees: bool,
}

/// Whether `recording` (read from `origin`) can be compared with `scene`, before any model
/// is built: it lists drops, names one of the scene's support sets (or the scene has one),
/// and every drop is in range.
pub fn check(scene: &Scene, recording: &Recording, origin: &str) -> Result<(), Failure> {
    if recording.drops.is_empty() {
        return Err(format!("{origin}: lists no drops (the sidecar's \"drops\", docs/guide.md)").into());
    }
    scene::drops::condition(scene, recording.condition.as_deref(), origin)?;
    scene::drops::drops(scene, &recording.drops, origin)?;
    Ok(())
}

/// The comparison of `recording` (read from `origin`) with `scene`'s model.
pub fn compute(
    scene: &Scene,
    recording: &Recording,
    origin: &str,
    progress: &dyn Progress,
) -> Result<DropsData, Failure> {
    check(scene, recording, origin)?;
    let set_index = scene::drops::condition(scene, recording.condition.as_deref(), origin)?;
    let drops = scene::drops::drops(scene, &recording.drops, origin)?;
    let set = &scene.conditions[set_index];
    let settings = reduced_settings(scene, set)?;
    let half = ReducedSettings { modes: (settings.modes / 2).max(1), ..settings };
    let coarse = ReducedSettings { steps_per_contact: 0.5 * settings.steps_per_contact, ..settings };
    progress.start(3 + drops.len(), &format!("{}: drops", set.name));
    let model = ReducedModel::new(&scene.plate, set, settings)?;
    let full = Instrument::new(&model, &scene.plate, &spec(scene, scene.signals.sensors.clone()), scene)?;
    let windows = windows(&full, recording, &drops, origin)?;
    progress.advance(1);
    let half_model = ReducedModel::new(&scene.plate, set, half)?;
    let halved = Instrument::new(&half_model, &scene.plate, &spec(scene, scene.signals.sensors.clone()), scene)?;
    progress.advance(1);
    let coarse_model = ReducedModel::new(&scene.plate, set, coarse)?;
    let coarser = Instrument::new(&coarse_model, &scene.plate, &spec(scene, scene.signals.sensors.clone()), scene)?;
    progress.advance(1);
    let channels: Vec<String> =
        channel_infos(&full, &scene.signals.sensors, &scene.plate).iter().map(crate::stream::channel_name).collect();
    let realisations = if full.chain().is_some() { REALISATIONS } else { 1 };
    let mut compared = Vec::with_capacity(drops.len());
    for (d, &start) in drops.iter().zip(&windows) {
        let rows = drop_rows(d, [&full, &halved, &coarser], (recording, start), &channels, realisations)?;
        let disagreeing = rows.iter().filter(|r| r.disagrees).count();
        compared.push(DropComparison {
            index: d.draw.index,
            touch: d.touch,
            class: d.class_stated.then_some(d.draw.class),
            point: (d.draw.x, d.draw.z),
            velocity: d.draw.velocity,
            rows,
            disagreeing,
        });
        progress.advance(1);
    }
    progress.finish();
    let e = full.extractor();
    Ok(DropsData {
        scene: scene.name.clone(),
        condition: set.name.clone(),
        channels,
        recorded_as: recording.names.clone(),
        rate_hz: recording.rate_hz,
        window: e.samples() as f64 / feature_rate(&full),
        modes: (settings.modes, half.modes),
        steps_per_contact: (settings.steps_per_contact, coarse.steps_per_contact),
        realisations,
        drops: compared,
    })
}

/// The rate the instrument's features read, Hz: the chain's ADC, else the model's.
fn feature_rate(instrument: &Instrument<'_>) -> f64 {
    instrument.chain().map_or(instrument.model_rate_hz(), |c| c.spec().rate_hz)
}

/// The first sample of every drop's window, after checking that the recording is one the
/// instrument reads (its rate and channels) and that every window lies inside it.
fn windows(
    instrument: &Instrument<'_>,
    recording: &Recording,
    drops: &[Drop],
    origin: &str,
) -> Result<Vec<usize>, Failure> {
    let rate = feature_rate(instrument);
    if recording.rate_hz != rate {
        return Err(format!(
            "{origin}: rate_hz = {}, but the scene's features read {rate} Hz (its [measurement] rate_hz, else [signals] rate_hz)",
            recording.rate_hz
        )
        .into());
    }
    let expected = instrument.channels().len();
    if recording.channels.len() != expected {
        return Err(format!(
            "{origin}: columns names {} channels, the scene's sensors and measurement record {expected}, in the order docs/guide.md gives",
            recording.channels.len()
        )
        .into());
    }
    let n = instrument.extractor().samples();
    let len = recording.channels[0].len();
    drops
        .iter()
        .map(|d| {
            let start = (d.touch * rate).round();
            if start + n as f64 > len as f64 {
                let latest = len.saturating_sub(n) as f64 / rate;
                return Err(format!(
                    "{origin}: drops[{}].touch_s = {}: its window of {n} samples ends after the recording's {len}; allowed [0, {latest}] s",
                    d.draw.index, d.touch
                )
                .into());
            }
            Ok(start as usize)
        })
        .collect()
}

/// The rows of drop `d`: its measured window (from sample `start` of the recording) against
/// the model's prediction on `models[0]`, with `models[1]` (half the modes) for the truncation
/// and `models[2]` (twice the contact step) for the time step.
fn drop_rows(
    d: &Drop,
    models: [&Instrument<'_>; 3],
    (recording, start): (&Recording, usize),
    channels: &[String],
    realisations: usize,
) -> Result<Vec<Compared>, Failure> {
    let full = models[0];
    let name = d.draw.class.key();
    let n = full.extractor().samples();
    let runs = models.map(|m| predictions(m, &d.draw, name, realisations));
    let [on_full, on_half, on_coarse] = runs;
    let ((on_full, record), (on_half, half_record), (on_coarse, coarse_record)) = (on_full?, on_half?, on_coarse?);
    let eps = full.chain().map_or(0.0, |c| c.realisation_error());
    let mut rows = Vec::new();
    for (c, (channel, samples)) in channels.iter().zip(&recording.channels).enumerate() {
        let measured = full.extractor().features(&samples[start..start + n]);
        let unit = full.channels()[c].unit();
        for (feature, unit) in [(&Peak as &dyn Feature, unit.to_string()), (&SpectralCentroid, "Hz".to_string())] {
            let k = c * FEATURES.len() + feature.index();
            let (mean, sd) = mean_sd(on_full.iter().map(|f| f[k]));
            let half_mean = mean_sd(on_half.iter().map(|f| f[k])).0;
            let coarse_mean = mean_sd(on_coarse.iter().map(|f| f[k])).0;
            let noise = SIGMAS * sd * (1.0 + 1.0 / realisations as f64).sqrt();
            let quantity = format!("{} of {channel}", feature.name());
            let model = [mean, half_mean, coarse_mean];
            rows.push(row(quantity, unit, measured[feature.index()], model, eps * mean.abs(), (sd, noise)));
        }
    }
    let stated = [
        (
            "P_max",
            "N",
            d.force_max,
            [Some(record.force_max), Some(half_record.force_max), Some(coarse_record.force_max)],
        ),
        ("t_c", "s", d.contact_time, [record.contact_time, half_record.contact_time, coarse_record.contact_time]),
    ];
    for (quantity, unit, measured, model) in stated {
        if let (Some(m), [Some(p), Some(h), Some(c)]) = (measured, model) {
            rows.push(row(quantity.into(), unit.into(), m, [p, h, c], 0.0, (0.0, 0.0)));
        }
    }
    Ok(rows)
}

/// One row: `measured` against the prediction `[ȳ_N, ȳ_{N/2}, ȳ_{2Δt}]` (module docs).
fn row(
    quantity: String,
    unit: String,
    measured: f64,
    model: [f64; 3],
    chain: f64,
    (noise_sd, noise): (f64, f64),
) -> Compared {
    let [mean, half_mean, coarse_mean] = model;
    let truncation = (mean - half_mean).abs();
    let step = (mean - coarse_mean).abs();
    let bar = truncation + step + chain + noise;
    Compared {
        quantity,
        unit,
        measured,
        predicted: mean,
        truncation,
        step,
        chain,
        noise_sd,
        bar,
        disagrees: (measured - mean).abs() > bar,
    }
}

/// The features of `realisations` throws of `draw` on `instrument`, each with its own
/// background, and the first throw's record (force and contact time do not depend on it).
fn predictions(
    instrument: &Instrument<'_>,
    draw: &Draw,
    family: &str,
    realisations: usize,
) -> Result<(Vec<Vec<f64>>, ImpactRecord), Failure> {
    let mut features = Vec::with_capacity(realisations);
    let mut first = None;
    for r in 0..realisations {
        let index = PREDICTION_KEY + draw.index * REALISATIONS + r;
        let record = instrument.impact(Draw { index, ..draw.clone() }, family)?;
        features.push(record.features.clone());
        first.get_or_insert(record);
    }
    let first = first.ok_or("no realisations")?;
    Ok((features, first))
}

/// The mean and the sample standard deviation (0 for one value).
fn mean_sd(values: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
    let n = values.clone().count() as f64;
    let mean = values.clone().sum::<f64>() / n;
    if n < 2.0 {
        return (mean, 0.0);
    }
    let var = values.map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}
