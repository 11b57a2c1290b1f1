//! What the measurement chain does to an identification run: the signal-to-noise ratio of
//! every recorded quantity, the ADC's clipping, whether the reduced model's truncation lies
//! outside the chain's band, how much folds at the ADC, and a sweep of the background's
//! level (none, as stated, and scaled to SNRs of 40 to 0 dB) that shows at which SNR the
//! separation survives.
//!
//! The SNR of a channel is 20 log₁₀(median coal peak / σ) (`identify::measurement`): coal is
//! the weaker class, so this is the ratio a detector of the weaker impacts works at.

use super::ensemble::run;
use super::sensors::{channel_infos, spec};
use super::separability::ranked;
use super::variability::MainRun;
use super::Ranked;
use crate::progress::Progress;
use crate::Failure;
use coupled::identification::{measurand, ConditionRun, Instrument};
use identify::measurement::{Chain, ChainSpec};
use identify::placement::{best, separabilities};
use identify::{Class, Feature, Held, Study};
use scene::{Scene, SupportSet};
use serde::Serialize;

/// The SNRs of the tracked channel the background sweep scales the background to, dB: from a
/// quiet mine to one where the median coal impact is as strong as the background.
pub const SWEEP_SNR_DB: [f64; 5] = [40.0, 30.0, 20.0, 10.0, 0.0];

/// The SNR of one recorded quantity over its channels.
#[derive(Debug, Clone, Serialize)]
pub struct QuantitySnr {
    /// The measurand's key.
    pub quantity: &'static str,
    /// Its SI unit.
    pub unit: &'static str,
    /// σ of the background, its tones and the ADC's step, in the unit.
    pub noise_rms: f64,
    /// The lowest, median and highest channel SNR, dB (None if every channel is silent).
    pub snr_db: Option<(f64, f64, f64)>,
    /// The channels with a signal.
    pub channels: usize,
    /// The channels without one (a median coal peak of 0: on a held edge or corner).
    pub silent: usize,
}

/// One level of the background sweep, on the named sensors' channels.
#[derive(Debug, Clone, Serialize)]
pub struct SweepPoint {
    /// The background's level over the stated one (0: none, the ADC's step alone).
    pub scale: f64,
    /// The SNR of the tracked channel, dB (None without coal impacts).
    pub snr_db: Option<f64>,
    /// The tracked feature (the main run's best among the named sensors' channels) at this level.
    pub tracked: Ranked,
    /// The best feature of the named sensors' channels at this level.
    pub best: Ranked,
}

/// The chain's part of a support set's result.
#[derive(Debug, Clone, Serialize)]
pub struct ChainSummary {
    /// The chain as the scene stated it.
    pub spec: ChainSpec,
    /// Model samples per ADC sample.
    pub decimation: usize,
    /// The reduced model's highest mode, Hz.
    pub highest_mode_hz: f64,
    /// The chain's largest gain at or above it: what the truncated modes could pass.
    pub gain_above_highest_mode: f64,
    /// The chain's largest gain at or above the model's Nyquist frequency: what of the
    /// model's response above it could fold into its samples.
    pub gain_above_model_nyquist: f64,
    /// The chain's largest gain at or above the ADC's Nyquist frequency: what folds into the
    /// ADC's band when every m-th sample is kept.
    pub gain_above_adc_nyquist: f64,
    /// The largest deviation of the realised (bilinear) chain's gain from the analog one over
    /// the ADC's band, as a share of the analog chain's largest gain there.
    pub realisation_error: f64,
    /// Whether the truncation lies outside the chain's band (the gain above the highest
    /// mode is at most the band tolerance).
    pub truncation_outside_band: bool,
    /// Samples clipped by the ADC over all samples of the main run.
    pub clipped_share: f64,
    /// Per recorded quantity.
    pub snr: Vec<QuantitySnr>,
    /// The SNR of the best feature's channel, dB.
    pub best_channel_snr_db: Option<f64>,
    /// The background sweep (empty if the chain states no background).
    pub sweep: Vec<SweepPoint>,
}

/// 20 log₁₀(median coal `peaks` / σ), dB; None without coal or for a silent channel (a
/// median peak of 0: a sensor on a held edge).
pub fn snr_db(peaks: &[f64], classes: &[Class], sigma: f64) -> Option<f64> {
    let mut coal: Vec<f64> = peaks.iter().zip(classes).filter(|(_, c)| **c == Class::Coal).map(|(p, _)| *p).collect();
    if coal.is_empty() || sigma <= 0.0 {
        return None;
    }
    coal.sort_by(f64::total_cmp);
    let n = coal.len();
    let median = if n % 2 == 1 { coal[n / 2] } else { 0.5 * (coal[n / 2 - 1] + coal[n / 2]) };
    (median > 0.0).then(|| 20.0 * (median / sigma).log10())
}

/// The SNR of channel `c` of `run` under `chain` with its background scaled by `scale` as
/// the chain scales it (noise and tones, not the quantisation): σ² = (scale σ_b)² + q²/12,
/// σ_b the background's RMS as stated (noise and tones) and q the ADC's step.
pub fn scaled_snr(run: &ConditionRun, c: usize, chain: &Chain, scale: f64) -> Option<f64> {
    let rec = chain.recording(measurand(run.channels[c]))?;
    let (background, q2) = background_and_quantisation(rec, chain.spec().rate_hz);
    snr_db(&run.clean_peaks(c), run.table.classes(), ((scale * background).powi(2) + q2).sqrt())
}

/// A recording's background RMS as stated (noise and tones: its RMS at `rate` less the
/// quantisation's) and the quantisation's variance q²/12, what a background scale leaves alone.
fn background_and_quantisation(rec: &identify::measurement::Recording, rate: f64) -> (f64, f64) {
    let (q2, total) = (rec.step().powi(2) / 12.0, rec.noise_rms(rate).powi(2));
    ((total - q2).max(0.0).sqrt(), q2)
}

/// The SNR of channel `c` of `run` under `chain`.
fn channel_snr(run: &ConditionRun, c: usize, chain: &Chain) -> Option<f64> {
    let rec = chain.recording(measurand(run.channels[c]))?;
    snr_db(&run.clean_peaks(c), run.table.classes(), rec.noise_rms(chain.spec().rate_hz))
}

/// The chain's summary of `main` (recorded by `instrument` through `chain`), the best
/// feature's channel `best_channel`.
pub fn summarise(
    instrument: &Instrument<'_>,
    main: &ConditionRun,
    best_channel: Option<usize>,
) -> Option<ChainSummary> {
    let chain = instrument.chain()?;
    let spec = chain.spec();
    let highest = instrument.highest_mode_hz();
    let gain_above = chain.gain_above(highest);
    let snr = spec
        .recordings
        .iter()
        .map(|rec| {
            let of_quantity: Vec<usize> =
                (0..main.channels.len()).filter(|&c| measurand(main.channels[c]) == rec.measurand).collect();
            let mut values: Vec<f64> = of_quantity.iter().filter_map(|&c| channel_snr(main, c, chain)).collect();
            values.sort_by(f64::total_cmp);
            let range = values.first().zip(values.last()).map(|(a, b)| (*a, values[values.len() / 2], *b));
            QuantitySnr {
                quantity: rec.measurand.key(),
                unit: rec.measurand.unit(),
                noise_rms: rec.noise_rms(spec.rate_hz),
                snr_db: range,
                channels: values.len(),
                silent: of_quantity.len() - values.len(),
            }
        })
        .collect();
    let samples = main.validity.impacts * main.channels.len() * chain.samples(instrument.model_samples());
    Some(ChainSummary {
        spec: spec.clone(),
        decimation: chain.decimation(),
        highest_mode_hz: highest,
        gain_above_highest_mode: gain_above,
        gain_above_model_nyquist: chain.gain_above(0.5 * spec.rate_hz * chain.decimation() as f64),
        gain_above_adc_nyquist: chain.gain_above(0.5 * spec.rate_hz),
        realisation_error: chain.realisation_error(),
        truncation_outside_band: gain_above <= spec.band_tolerance,
        clipped_share: main.clipped as f64 / samples.max(1) as f64,
        snr,
        best_channel_snr_db: best_channel.and_then(|c| channel_snr(main, c, chain)),
        sweep: Vec::new(),
    })
}

/// The background sweep on the named sensors of `main_run`'s model (nothing without a
/// named sensor or a stated background). The stated level runs first; its best feature of the
/// named sensors' channels is tracked, and the background is then scaled so that the tracked
/// channel's SNR is each of [`SWEEP_SNR_DB`] (levels the ADC's step alone already exceeds are
/// left out), and to zero. Every level reruns the same impacts with the same background draws,
/// scaled, so the levels differ by the background's level alone. The k-th level's bootstrap
/// stream derives from `seed ^ (400 + k)`.
pub fn sweep(
    scene: &Scene,
    study: &Study,
    set: &SupportSet,
    main_run: &MainRun<'_>,
    seed: u64,
    progress: &dyn Progress,
) -> Result<Vec<SweepPoint>, Failure> {
    let named = scene.signals.sensors.clone();
    let stated_background = scene
        .measurement
        .as_ref()
        .is_some_and(|m| m.recordings.iter().any(|r| r.background.is_some() || !r.tones.is_empty()));
    if named.is_empty() || !stated_background {
        return Ok(Vec::new());
    }
    // One instrument (its probes and the model's factorization once), its background rescaled
    // between the levels.
    let mut instrument = Instrument::new(main_run.model, &scene.plate, &spec(scene, named.clone()), scene)?;
    let infos = channel_infos(&instrument, &named, &scene.plate);
    let stated = run(study, Held::NONE, &instrument, &set.name, "background as stated", progress, |_| Ok(()))?;
    let Some(tracked) = best(&separabilities(&stated.table), &[]) else { return Ok(Vec::new()) };
    let chain = instrument.chain().ok_or("the sweep needs a measurement chain")?;
    let Some(rec) = chain.recording(measurand(stated.channels[tracked.channel])) else { return Ok(Vec::new()) };
    let peaks = stated.clean_peaks(tracked.channel);
    let classes = stated.table.classes();
    let rate = chain.spec().rate_hz;
    let (background, q2) = background_and_quantisation(rec, rate);
    // The scale that puts the tracked channel at `db`: σ² = (s σ_b)² + q²/12.
    let median_coal = snr_db(&peaks, classes, 1.0).map(|v| 10f64.powf(v / 20.0));
    let mut scales = vec![0.0, 1.0];
    for &db in &SWEEP_SNR_DB {
        let Some(m) = median_coal else { break };
        let sigma = m / 10f64.powf(db / 20.0);
        if sigma * sigma > q2 && background > 0.0 {
            scales.push(((sigma * sigma - q2).sqrt() / background).max(0.0));
        }
    }
    scales.sort_by(f64::total_cmp);
    let mut out = Vec::with_capacity(scales.len());
    for (k, &scale) in scales.iter().enumerate() {
        let rescaled;
        let r = if scale == 1.0 {
            &stated
        } else {
            instrument.set_noise_scale(scale);
            let label = format!("background × {}", sig3(scale));
            rescaled = run(study, Held::NONE, &instrument, &set.name, &label, progress, |_| Ok(()))?;
            &rescaled
        };
        let s = seed ^ (400 + k as u64);
        let score = |c: usize, f: &'static dyn Feature| {
            let (a, b) = r.table.split(c, f);
            ranked(infos[c].label(), f, (&a, &b), None, s)
        };
        let Some(top) = best(&separabilities(&r.table), &[]) else { continue };
        let sigma = (scale * scale * background * background + q2).sqrt();
        out.push(SweepPoint {
            scale,
            snr_db: snr_db(&peaks, classes, sigma),
            tracked: score(tracked.channel, tracked.feature),
            best: score(top.channel, top.feature),
        });
    }
    Ok(out)
}

/// The chain's part of a support set's result (None without a chain): the summary of the
/// `main` run of `instrument`, whose best feature is on channel `best_channel`, with the
/// background sweep on `main_run`'s model.
#[allow(clippy::too_many_arguments)]
pub fn of_set(
    scene: &Scene,
    study: &Study,
    set: &SupportSet,
    instrument: &Instrument<'_>,
    main: &ConditionRun,
    main_run: &MainRun<'_>,
    best_channel: Option<usize>,
    seed: u64,
    progress: &dyn Progress,
) -> Result<Option<ChainSummary>, Failure> {
    let Some(summary) = summarise(instrument, main, best_channel) else { return Ok(None) };
    Ok(Some(ChainSummary { sweep: sweep(scene, study, set, main_run, seed, progress)?, ..summary }))
}

/// `v` to three significant digits, for a progress label.
fn sig3(v: f64) -> String {
    analytic::params::compact(format!("{v:.3e}").parse::<f64>().unwrap_or(v))
}
