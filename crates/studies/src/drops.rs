//! Measured drops against the model (`impact drops`): every drop of a drop-test recording
//! (a lump of stated size and rock, dropped from a stated height onto a stated point) thrown
//! on the scene's reduced model of the same support set, through the scene's measurement
//! chain, and each channel's peak and spectral centroid, and the impact force's peak and
//! duration where the recording states them, set against the model's with its error bar.
//!
//! **The prediction and its bar.** A measured feature is one realisation of the chain's
//! noise, and noise moves a feature's mean as well as its spread (a peak of signal plus noise
//! is larger than the signal's). So the model's prediction is the mean over K =
//! [`REALISATIONS`] realisations of the scene's background on the model's signal, and the bar
//! is
//!
//!   bar = |ȳ_N − ȳ_{N/2}| + |ȳ_Δt − ȳ_{2Δt}| + ε_chain·|ȳ| + t·s·√(1 + 1/K),
//!
//! the modal truncation (the same realisations on the model with half the modes: the
//! difference overstates the error at N where the feature converges in N), the contact's
//! time step (the same on the model with half the steps per contact: for a second-order
//! rule the difference is three times the error at Δt), the realised digital chain's largest
//! gain deviation from the analog one over the ADC's band taken as a relative error of the
//! feature (an estimate of how far a real, analog chain may be from the modelled one, not a
//! bound), and the noise: s is one realisation's standard deviation about the mean of K, and
//! t = [`T_QUANTILE`] is Student's with K − 1 degrees of freedom, so that a row of a drop the
//! model describes leaves its bar with 0.27 % odds under normal noise (a drop of r rows with
//! about r times that). P_max and t_c, where the recording states them, carry the two model
//! terms and three of the standard deviations the recording states for them (none where it
//! states none, and the row says so). What the bar leaves out: the mesh's discretisation
//! error (the same mesh carries both models; the compliance's convergence study bounds it)
//! and any difference between the scene's background and the rig's.
//!
//! **The touch between samples.** The recording's window starts at the ADC sample at or
//! before the touch, and the model's signal is delayed by the touch's fraction of a sample
//! in model samples (the model runs at a whole multiple of the ADC's rate), so that both are
//! sampled at the same instants after the touch to 1/(2m) of an ADC interval.

use crate::identify::sensors::{channel_infos, reduced_settings, spec};
use crate::progress::Progress;
use crate::Failure;
use coupled::identification::Instrument;
use coupled::reduced::{ReducedModel, ReducedSettings};
use identify::features::{Peak, SpectralCentroid, FEATURES};
use identify::recording::Recording;
use identify::Feature;
use scene::drops::Drop;
use scene::Scene;
use serde::Serialize;

/// Realisations of the chain's background per prediction: the bar's s is then known to
/// about 1/√(2(K − 1)) = 18 % of itself.
pub const REALISATIONS: usize = 16;
/// Student's t with [`REALISATIONS`] − 1 = 15 degrees of freedom at 0.99865 (scipy.stats.t.ppf
/// (0.99865, 15) = 3.5864): the two-sided 0.27 % of three standard deviations of a normal
/// law, with s estimated from the realisations.
pub const T_QUANTILE: f64 = 3.5864;
/// The background streams of predictions start here, apart from every ensemble impact's.
const PREDICTION_KEY: usize = 1 << 40;
/// Standard deviations of a stated measurement error in the bar: 0.27 % odds per row for a
/// normal error.
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
    /// What could not be compared, and why.
    pub notes: Vec<String>,
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
    /// s, one realisation's standard deviation (0 without noise), or the standard deviation
    /// the recording states for its P_max or t_c.
    pub noise_sd: f64,
    /// The whole bar.
    pub bar: f64,
    /// |measured − predicted| > bar.
    pub disagrees: bool,
    /// What the bar leaves out for this row, if anything beyond the module's list.
    pub note: String,
}

/// A recording checked against a scene, before any model is built: its support set, its
/// drops in SI and each drop's window.
#[derive(Debug, Clone)]
pub struct Checked {
    /// The support set's position in the scene.
    pub set: usize,
    /// The drops.
    pub drops: Vec<Drop>,
    /// Each drop's window.
    pub windows: Vec<Window>,
}

/// Where a drop's window sits in the recording.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window {
    /// Its first sample: the one at or before the touch.
    pub start: usize,
    /// Model samples from that sample to the touch (0 to m − 1, m model samples a recorded one).
    pub delay: usize,
}

/// Whether `recording` (read from `origin`) can be compared with `scene`, before any model
/// is built: the scene describes a rig (\"drops\" among its analyses), the recording lists
/// drops, names one of the scene's support sets (or the scene has one), is sampled at the
/// rate the scene's features read, every drop is in range and its window lies inside the
/// recording. (The channel count needs the model's channels, and is checked once it is built,
/// still before anything is written.)
pub fn check(scene: &Scene, recording: &Recording, origin: &str) -> Result<Checked, Failure> {
    if !scene.analyses.contains(&scene::Analysis::Drops) {
        return Err(format!(
            "scene {}: comparing recorded drops needs a scene that describes the rig; add \"drops\" to its analyses",
            scene.name
        )
        .into());
    }
    if recording.drops.is_empty() {
        return Err(format!("{origin}: lists no drops (the sidecar's \"drops\", docs/guide.md)").into());
    }
    let set = scene::drops::condition(scene, recording.condition.as_deref(), origin)?;
    let drops = scene::drops::drops(scene, &recording.drops, origin)?;
    let signal_spec = spec(scene, scene.signals.sensors.clone());
    let (rate, per_sample, n) = match &scene.measurement {
        None => (signal_spec.rate_hz, 1, signal_spec.samples()),
        Some(c) => {
            let chain = identify::measurement::Chain::new(c.clone(), signal_spec.rate_hz)?;
            (c.rate_hz, chain.decimation(), chain.samples(signal_spec.samples()))
        }
    };
    if recording.rate_hz != rate {
        return Err(format!(
            "{origin}: rate_hz = {}, but the scene's features read {rate} Hz (its [measurement] rate_hz)",
            recording.rate_hz
        )
        .into());
    }
    let len = recording.channels.first().map_or(0, Vec::len);
    if len < n {
        return Err(format!(
            "{origin}: the recording's {len} samples are fewer than one drop's window of {n} ([signals] window_ms at {rate} Hz)"
        )
        .into());
    }
    let windows = drops
        .iter()
        .map(|d| {
            let at = d.touch * rate;
            let (mut start, mut delay) = (at.floor(), ((at - at.floor()) * per_sample as f64).round() as usize);
            if delay == per_sample {
                (start, delay) = (start + 1.0, 0);
            }
            if start + n as f64 > len as f64 {
                let latest = (len - n) as f64 / rate;
                return Err(format!(
                    "{origin}: drops[{}].touch_s = {}: its window of {n} samples ends after the recording's {len}; allowed [0, {latest}] s",
                    d.draw.index, d.touch
                )
                .into());
            }
            Ok(Window { start: start as usize, delay })
        })
        .collect::<Result<Vec<_>, Failure>>()?;
    Ok(Checked { set, drops, windows })
}

/// The comparison of `recording` (read from `origin`) with `scene`'s model.
pub fn compute(
    scene: &Scene,
    recording: &Recording,
    origin: &str,
    progress: &dyn Progress,
) -> Result<DropsData, Failure> {
    let Checked { set, drops, windows } = check(scene, recording, origin)?;
    let set = &scene.conditions[set];
    let settings = reduced_settings(scene, set)?;
    let half = ReducedSettings { modes: (settings.modes / 2).max(1), ..settings };
    let coarse = ReducedSettings { steps_per_contact: 0.5 * settings.steps_per_contact, ..settings };
    progress.start(3 + drops.len(), &format!("{}: drops", set.name));
    let signal_spec = spec(scene, scene.signals.sensors.clone());
    let model = ReducedModel::new(&scene.plate, set, settings)?;
    let full = Instrument::new(&model, &scene.plate, &signal_spec, scene)?;
    let channels: Vec<String> =
        channel_infos(&full, &scene.signals.sensors, &scene.plate).iter().map(crate::stream::channel_name).collect();
    if recording.channels.len() != channels.len() {
        return Err(format!(
            "{origin}: columns names {} channels; the scene's sensors and measurement record {}, in this order: {}",
            recording.channels.len(),
            channels.len(),
            channels.join("; ")
        )
        .into());
    }
    progress.advance(1);
    let half_model = ReducedModel::new(&scene.plate, set, half)?;
    let halved = Instrument::new(&half_model, &scene.plate, &signal_spec, scene)?;
    progress.advance(1);
    let coarse_model = ReducedModel::new(&scene.plate, set, coarse)?;
    let coarser = Instrument::new(&coarse_model, &scene.plate, &signal_spec, scene)?;
    progress.advance(1);
    let realisations = if full.chain().is_some() { REALISATIONS } else { 1 };
    let mut compared = Vec::with_capacity(drops.len());
    for (d, &window) in drops.iter().zip(&windows) {
        let (rows, notes) = drop_rows(d, [&full, &halved, &coarser], (recording, window), &channels, realisations)?;
        compared.push(DropComparison {
            index: d.draw.index,
            touch: d.touch,
            class: d.class_stated.then_some(d.draw.class),
            point: (d.draw.x, d.draw.z),
            velocity: d.draw.velocity,
            disagreeing: rows.iter().filter(|r| r.disagrees).count(),
            rows,
            notes,
        });
        progress.advance(1);
    }
    progress.finish();
    let rate = full.chain().map_or(full.model_rate_hz(), |c| c.spec().rate_hz);
    Ok(DropsData {
        scene: scene.name.clone(),
        condition: set.name.clone(),
        channels,
        recorded_as: recording.names.clone(),
        rate_hz: recording.rate_hz,
        window: full.extractor().samples() as f64 / rate,
        modes: (settings.modes, half.modes),
        steps_per_contact: (settings.steps_per_contact, coarse.steps_per_contact),
        realisations,
        drops: compared,
    })
}

/// The rows of drop `d` and what could not be compared: its measured window against the
/// model's prediction on `models[0]`, with `models[1]` (half the modes) for the truncation and
/// `models[2]` (twice the contact step) for the time step.
fn drop_rows(
    d: &Drop,
    models: [&Instrument<'_>; 3],
    (recording, window): (&Recording, Window),
    channels: &[String],
    realisations: usize,
) -> Result<(Vec<Compared>, Vec<String>), Failure> {
    let full = models[0];
    let n = full.extractor().samples();
    let [on_full, on_half, on_coarse] = models.map(|m| predictions(m, d, window.delay, realisations));
    let (on_full, on_half, on_coarse) = (on_full?, on_half?, on_coarse?);
    let eps = full.chain().map_or(0.0, |c| c.realisation_error());
    let noise_factor = if realisations > 1 { T_QUANTILE * (1.0 + 1.0 / realisations as f64).sqrt() } else { 0.0 };
    let mut rows = Vec::new();
    let kinds = full.channels();
    for (c, (channel, samples)) in channels.iter().zip(&recording.channels).enumerate() {
        let measured = full.extractor().features(&samples[window.start..window.start + n]);
        for (feature, unit) in [(&Peak as &dyn Feature, kinds[c].unit()), (&SpectralCentroid, "Hz")] {
            let k = c * FEATURES.len() + feature.index();
            let (mean, sd) = mean_sd(on_full.features.iter().map(|f| f[k]));
            let model = [
                mean,
                mean_sd(on_half.features.iter().map(|f| f[k])).0,
                mean_sd(on_coarse.features.iter().map(|f| f[k])).0,
            ];
            let quantity = format!("{} of {channel}", feature.name());
            let noise = (sd, noise_factor * sd);
            rows.push(row((quantity, unit), measured[feature.index()], model, eps * mean.abs(), noise, String::new()));
        }
    }
    let mut notes = Vec::new();
    let force = [&on_full, &on_half, &on_coarse].map(|p| Some(p.force_max));
    let time = [&on_full, &on_half, &on_coarse].map(|p| p.contact_time);
    for (quantity, unit, measured, sd, model) in
        [("P_max", "N", d.force_max, d.force_max_sd, force), ("t_c", "s", d.contact_time, d.contact_time_sd, time)]
    {
        let Some(m) = measured else { continue };
        let [Some(p), Some(h), Some(c)] = model else {
            notes.push(format!("{quantity}: the model's first contact does not end within the window; not compared"));
            continue;
        };
        let note = if sd.is_some() {
            String::new()
        } else {
            "the recording states no standard deviation for it: the bar is the model's alone".to_string()
        };
        let sd = sd.unwrap_or(0.0);
        rows.push(row((quantity.into(), unit), m, [p, h, c], 0.0, (sd, SIGMAS * sd), note));
    }
    Ok((rows, notes))
}

/// One row: `measured` against the prediction `[ȳ_N, ȳ_{N/2}, ȳ_{2Δt}]` (module docs).
fn row(
    (quantity, unit): (String, &str),
    measured: f64,
    model: [f64; 3],
    chain: f64,
    (noise_sd, noise): (f64, f64),
    note: String,
) -> Compared {
    let [mean, half_mean, coarse_mean] = model;
    let truncation = (mean - half_mean).abs();
    let step = (mean - coarse_mean).abs();
    let bar = truncation + step + chain + noise;
    Compared {
        quantity,
        unit: unit.to_string(),
        measured,
        predicted: mean,
        truncation,
        step,
        chain,
        noise_sd,
        bar,
        disagrees: (measured - mean).abs() > bar,
        note,
    }
}

/// A drop thrown once on one model and read several times.
struct Prediction {
    /// Each reading's features.
    features: Vec<Vec<f64>>,
    /// The first contact's P_max, N, and t_c, s (which do not depend on the reading).
    force_max: f64,
    contact_time: Option<f64>,
}

/// `realisations` readings of drop `d` thrown once on `instrument`, each with its own
/// background and the touch `delay` model samples into the window.
fn predictions(
    instrument: &Instrument<'_>,
    d: &Drop,
    delay: usize,
    realisations: usize,
) -> Result<Prediction, Failure> {
    let (_, _, hit) = instrument.simulate(&d.draw, d.draw.class.key())?;
    let features = (0..realisations)
        .map(|r| {
            Ok(instrument.measure(&hit.signals, PREDICTION_KEY + d.draw.index * REALISATIONS + r, delay)?.features)
        })
        .collect::<Result<Vec<_>, Failure>>()?;
    let o = &hit.outcome;
    Ok(Prediction { features, force_max: o.force_max_interpolated.max(o.force_max), contact_time: o.contact_time })
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
