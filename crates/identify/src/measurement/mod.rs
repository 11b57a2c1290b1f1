//! The measurement chain between the plate and a feature: what a data acquisition on a
//! support records of the model's exact response.
//!
//! A channel's model signal y(t), sampled at the model's rate f_m, goes through
//! 1. the sensor's band: its mounted resonance ω_r²/(s² + 2ζω_r s + ω_r²) and its AC coupling
//!    s/(s + ω_h), each optional;
//! 2. the anti-aliasing filter: a Butterworth low-pass of order n and corner f_c;
//! 3. the sampler: every m-th sample, so the ADC's rate is f_m/m;
//! 4. the background the channel records beside the impact, added at the ADC's input:
//!    stationary Gaussian noise of a PSD (white, pink or measured) plus tonal machinery lines,
//!    each window drawn from its own seeded stream ([`noise`]);
//! 5. the ADC: range ±R and b bits, so a step q = 2R/2^b; values beyond the range clip, and
//!    every window counts its clipped samples.
//!
//! The analog filters run on the model's samples as their bilinear images ([`filter`]). The
//! model's samples are exact samples of its response, so what lies above f_m/2 in the model
//! (its highest modes) has already folded when the chain sees it: [`Chain::gain`] at f_m/2
//! says how much of that the chain would have passed. The background is what a recording of
//! the quiet machine shows at the ADC's input, so its PSD is given as measured, not as it
//! would be before the filters.
//!
//! A channel's signal-to-noise ratio is quoted as 20 log₁₀(median coal peak / σ), where the
//! peak is that of the measured signal without the background and
//! σ² = ∫₀^{f_s/2} S df + Σ rms_tone² + q²/12 is the background's and the quantisation's
//! variance.

pub mod filter;
pub mod noise;
pub mod segments;

use crate::ensemble::impact_stream;
use filter::{Analog, Cascade};
use noise::{Psd, Synthesizer, Tone};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// What a channel measures, as the chain sees it (its unit and its recording).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Measurand {
    /// Plate acceleration at a sensor point, m/s².
    Acceleration,
    /// Plate velocity at a sensor point, m/s.
    Velocity,
    /// Plate deflection at a sensor point, m.
    Displacement,
    /// A prop's or jack's force (a spring corner) or a fixed corner's reaction, N.
    SupportForce,
    /// The bending strain along x on the unstruck face at a sensor point (a strain gauge),
    /// dimensionless.
    Strain,
}

impl Measurand {
    /// Its key in scene files and columns.
    pub fn key(self) -> &'static str {
        match self {
            Measurand::Acceleration => "acceleration",
            Measurand::Velocity => "velocity",
            Measurand::Displacement => "displacement",
            Measurand::SupportForce => "support_force",
            Measurand::Strain => "strain",
        }
    }

    /// Its SI unit.
    pub fn unit(self) -> &'static str {
        match self {
            Measurand::Acceleration => "m/s²",
            Measurand::Velocity => "m/s",
            Measurand::Displacement => "m",
            Measurand::SupportForce => "N",
            Measurand::Strain => "1",
        }
    }
}

/// The sensor's own band.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SensorBand {
    /// The mounted resonance (Hz) and its damping ratio, if modelled.
    pub resonance: Option<(f64, f64)>,
    /// The AC coupling's -3 dB corner, Hz, if any.
    pub high_pass_hz: Option<f64>,
}

/// The anti-aliasing filter: a Butterworth low-pass.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AntiAlias {
    /// Its order n, 1 to [`MAX_FILTER_ORDER`].
    pub order: usize,
    /// Its -3 dB corner, Hz.
    pub corner_hz: f64,
}

/// Mixed into the chain's seed for its background streams ("noise" in ASCII).
pub const BACKGROUND_KEY: u64 = 0x6e_6f_69_73_65;

/// The highest anti-aliasing order accepted (a DAQ's filters are rarely above 8; beyond 16 the
/// cascade's sections are numerically fragile at low corner-to-rate ratios).
pub const MAX_FILTER_ORDER: usize = 16;

/// How one measurand is recorded: its ADC and its background.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Recording {
    /// What is recorded.
    pub measurand: Measurand,
    /// The ADC's full scale ±R, in the measurand's unit.
    pub range: f64,
    /// The ADC's bits, 1 to 32.
    pub bits: u32,
    /// The stationary background, if any.
    pub background: Option<Psd>,
    /// Tonal machinery lines.
    pub tones: Vec<Tone>,
}

impl Recording {
    /// The ADC's step q = 2R/2^b.
    pub fn step(&self) -> f64 {
        2.0 * self.range / 2f64.powi(self.bits as i32)
    }

    /// σ: the standard deviation of the background, its tones and the quantisation at an
    /// ADC rate `rate_hz` (module docs).
    pub fn noise_rms(&self, rate_hz: f64) -> f64 {
        let background = self.background.as_ref().map_or(0.0, |p| p.power(rate_hz / 2.0));
        let tones: f64 = self.tones.iter().map(|t| t.rms * t.rms).sum();
        (background + tones + self.step().powi(2) / 12.0).sqrt()
    }
}

/// A measurement chain as a scene states it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChainSpec {
    /// The sensor's band.
    pub sensor: SensorBand,
    /// The anti-aliasing filter, if any.
    pub anti_alias: Option<AntiAlias>,
    /// The ADC's sample rate, Hz: the model's rate over a whole number.
    pub rate_hz: f64,
    /// The recorded measurands; a channel whose measurand has none is not recorded.
    pub recordings: Vec<Recording>,
    /// The seed of the backgrounds.
    pub seed: u64,
    /// The chain's gain below which a frequency counts as outside its band.
    pub band_tolerance: f64,
}

/// One window as the chain recorded it.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// The ADC's samples, in the measurand's unit.
    pub samples: Vec<f64>,
    /// max abs of the filtered, sampled signal before the background and the ADC.
    pub clean_peak: f64,
    /// How many samples clipped at ±R.
    pub clipped: usize,
}

/// Why a chain cannot run on a model's samples.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ChainError {
    /// The ADC's rate is not the model's over a whole number.
    #[error("measurement.rate_hz = {adc} Hz is not the model's {model} Hz (signals.rate_hz) divided by a whole number; choose {model} Hz / m for a whole m")]
    Rate {
        /// The ADC's rate, Hz.
        adc: f64,
        /// The model's, Hz.
        model: f64,
    },
    /// A filter frequency at or above 0.45 of the model's rate, where its bilinear image
    /// warps by more than it models.
    #[error("{field} = {value} Hz is above 0.45 × the model's rate {model} Hz, where the chain's filters cannot be realised on its samples; raise signals.rate_hz or lower {field}")]
    Frequency {
        /// The scene key.
        field: &'static str,
        /// Its value, Hz.
        value: f64,
        /// The model's rate, Hz.
        model: f64,
    },
}

/// A chain ready to run on one model rate.
#[derive(Debug, Clone)]
pub struct Chain {
    spec: ChainSpec,
    cascade: Cascade,
    decimation: usize,
    /// Each recording's background synthesizer for the window length first measured (its
    /// FFT plan and bin deviations; a window of another length draws through a new one).
    synthesizers: OnceLock<(usize, Vec<Option<Synthesizer>>)>,
}

/// The model's samples per ADC sample: the ADC's rate `adc_hz` must divide the model's
/// `model_hz` (within 1e-9 of the ratio), so that the ADC keeps every k-th model sample.
pub fn decimation(adc_hz: f64, model_hz: f64) -> Result<usize, ChainError> {
    let ratio = model_hz / adc_hz;
    let k = ratio.round();
    if !(k >= 1.0 && (ratio - k).abs() <= 1e-9 * ratio) {
        return Err(ChainError::Rate { adc: adc_hz, model: model_hz });
    }
    Ok(k as usize)
}

impl Chain {
    /// `spec` on samples at the model's rate `model_rate_hz`.
    pub fn new(spec: ChainSpec, model_rate_hz: f64) -> Result<Self, ChainError> {
        let decimation = decimation(spec.rate_hz, model_rate_hz)?;
        let mut sections = Vec::new();
        let frequency = |field: &'static str, value: f64| {
            if value >= 0.45 * model_rate_hz {
                return Err(ChainError::Frequency { field, value, model: model_rate_hz });
            }
            Ok(2.0 * PI * value)
        };
        if let Some((f, zeta)) = spec.sensor.resonance {
            sections.push(Analog::resonance(frequency("measurement.sensor.resonance_hz", f)?, zeta));
        }
        if let Some(f) = spec.sensor.high_pass_hz {
            sections.push(Analog::high_pass(frequency("measurement.sensor.high_pass_hz", f)?));
        }
        if let Some(a) = spec.anti_alias {
            sections.extend(Analog::butterworth(a.order, frequency("measurement.anti_alias.corner_hz", a.corner_hz)?));
        }
        Ok(Self { cascade: Cascade::new(sections, model_rate_hz), decimation, spec, synthesizers: OnceLock::new() })
    }

    /// The chain as stated.
    pub fn spec(&self) -> &ChainSpec {
        &self.spec
    }

    /// The model's samples per ADC sample, m.
    pub fn decimation(&self) -> usize {
        self.decimation
    }

    /// The ADC's samples of a window of `model_samples` model samples: every m-th from the
    /// first.
    pub fn samples(&self, model_samples: usize) -> usize {
        model_samples.div_ceil(self.decimation)
    }

    /// The recording of `measurand`, if the chain records it.
    pub fn recording(&self, measurand: Measurand) -> Option<&Recording> {
        self.spec.recordings.iter().find(|r| r.measurand == measurand)
    }

    /// abs(H(j2πf)) of the analog chain (sensor band and anti-aliasing filter).
    pub fn gain(&self, f_hz: f64) -> f64 {
        self.cascade.analog_response(f_hz).norm()
    }

    /// The chain's largest gain at or above `f_hz` (sampled on a log grid to 1000 × f): what
    /// a part of the response above `f_hz` (modes left out, or folded) could pass.
    pub fn gain_above(&self, f_hz: f64) -> f64 {
        (0..=600).map(|k| self.gain(f_hz * 10f64.powf(k as f64 / 200.0))).fold(0.0, f64::max)
    }

    /// The fewest of the modes of natural frequencies `frequencies_hz` (rising) to keep so
    /// that the chain's gain above the highest kept one is at most `band_tolerance`: what the
    /// truncation leaves out then reaches the recording at most that much. None if even all
    /// of them leave more.
    pub fn modes_needed(&self, frequencies_hz: &[f64]) -> Option<usize> {
        frequencies_hz.iter().position(|&f| self.gain_above(f) <= self.spec.band_tolerance).map(|i| i + 1)
    }

    /// The generator of the backgrounds of window `index`: ChaCha8 keyed by the chain's seed
    /// mixed with [`BACKGROUND_KEY`], on stream `index`, so that a chain seeded as its ensemble
    /// never draws an impact's own random numbers.
    pub fn stream(&self, index: usize) -> ChaCha8Rng {
        impact_stream(self.spec.seed ^ BACKGROUND_KEY, index)
    }

    /// The largest deviation of the realised chain from the analog one over the ADC's band
    /// (module docs of [`filter`]).
    pub fn realisation_error(&self) -> f64 {
        self.cascade.largest_deviation(0.5 * self.spec.rate_hz)
    }

    /// `y` (model samples of `measurand`) as the chain records it, the background drawn from
    /// `rng` with its level scaled by `noise_scale` (1: as stated); None if the chain does not
    /// record `measurand`.
    pub fn measure(&self, measurand: Measurand, y: &[f64], noise_scale: f64, rng: &mut ChaCha8Rng) -> Option<Measured> {
        let rec = self.recording(measurand)?;
        let mut x = y.to_vec();
        self.cascade.run(&mut x);
        let mut samples: Vec<f64> = x.iter().step_by(self.decimation).copied().collect();
        let clean_peak = samples.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let rate = self.spec.rate_hz;
        if let Some(psd) = &rec.background {
            let n = samples.len();
            let (len, all) = self.synthesizers.get_or_init(|| {
                let built =
                    self.spec.recordings.iter().map(|r| r.background.as_ref().map(|p| Synthesizer::new(p, n, rate)));
                (n, built.collect())
            });
            let index = self.spec.recordings.iter().position(|r| r.measurand == measurand);
            let noise = match index.and_then(|i| all.get(i)) {
                Some(Some(s)) if *len == n => s.draw(rng),
                _ => noise::synthesize(psd, n, rate, rng),
            };
            samples.iter_mut().zip(noise).for_each(|(s, n)| *s += noise_scale * n);
        }
        let tones: Vec<Tone> = rec.tones.iter().map(|t| Tone { rms: noise_scale * t.rms, ..*t }).collect();
        noise::add_tones(&mut samples, &tones, rate, rng);
        let clipped = quantise(&mut samples, rec.range, rec.bits);
        Some(Measured { samples, clean_peak, clipped })
    }
}

/// The ADC: each value to the nearest of the codes k q, k = -2^(b-1) .. 2^(b-1) - 1, with
/// q = 2R/2^b; returns how many clipped (lay beyond the codes' span by more than q/2).
pub fn quantise(x: &mut [f64], range: f64, bits: u32) -> usize {
    let q = 2.0 * range / 2f64.powi(bits as i32);
    let (lo, hi) = (-(2f64.powi(bits as i32 - 1)), 2f64.powi(bits as i32 - 1) - 1.0);
    let mut clipped = 0;
    for v in x.iter_mut() {
        let code = (*v / q).round();
        clipped += usize::from(code < lo || code > hi);
        *v = code.clamp(lo, hi) * q;
    }
    clipped
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The modes to keep against the closed form: behind an 8th-order Butterworth at 4 kHz
    /// alone, abs(H) = 1/√(1 + (f/f_c)¹⁶) falls monotonically, so the gain above f is abs(H(f))
    /// and it reaches 1e-3 at f_c (10⁶ - 1)^(1/16) = 9,484 Hz: of modes at 1, 5, 9, 9.6 and
    /// 12 kHz the first four are needed; of modes up to 9 kHz, none suffices.
    #[test]
    fn the_modes_needed_end_where_the_chain_is_deaf() {
        let spec = ChainSpec { sensor: SensorBand { resonance: None, high_pass_hz: None }, ..spec(40_000.0) };
        let chain = Chain::new(spec, 40_000.0).unwrap();
        let edge = 4_000.0 * (1e6f64 - 1.0).powf(1.0 / 16.0);
        assert!((chain.gain(edge) - 1e-3).abs() < 1e-9, "{}", chain.gain(edge));
        assert_eq!(chain.modes_needed(&[1e3, 5e3, 9e3, 9.6e3, 12e3]), Some(4));
        assert_eq!(chain.modes_needed(&[1e3, 5e3, 9e3]), None);
    }

    fn spec(rate_hz: f64) -> ChainSpec {
        ChainSpec {
            sensor: SensorBand { resonance: Some((12_000.0, 0.05)), high_pass_hz: Some(1.0) },
            anti_alias: Some(AntiAlias { order: 8, corner_hz: 4_000.0 }),
            rate_hz,
            recordings: vec![Recording {
                measurand: Measurand::Acceleration,
                range: 100.0,
                bits: 16,
                background: Some(Psd::white(0.5, rate_hz / 2.0)),
                tones: vec![Tone { frequency_hz: 50.0, rms: 0.2 }],
            }],
            seed: 9,
            band_tolerance: 1e-3,
        }
    }

    /// The chain's gain is the product of its sections' analog gains, and the largest gain
    /// above a frequency past the resonance is the gain there (both fall monotonically):
    /// abs(H) = 1/abs(1 - (f/f_r)² + 2jζf/f_r) · (f/f_h)/√(1 + (f/f_h)²) · 1/√(1 + (f/f_c)^16).
    #[test]
    fn the_gain_is_the_closed_form() {
        let chain = Chain::new(spec(10_000.0), 40_000.0).unwrap();
        let exact = |f: f64| {
            let r = f / 12_000.0;
            let resonance = 1.0 / ((1.0 - r * r).powi(2) + (2.0 * 0.05 * r).powi(2)).sqrt();
            let high_pass = (f / 1.0) / (1.0 + (f / 1.0).powi(2)).sqrt();
            resonance * high_pass / (1.0 + (f / 4_000.0).powi(16)).sqrt()
        };
        for f in [0.5, 1.0, 100.0, 4_000.0, 12_000.0, 30_000.0] {
            assert!((chain.gain(f) / exact(f) - 1.0).abs() < 1e-12, "{f} Hz");
        }
        assert!((chain.gain_above(15_000.0) / exact(15_000.0) - 1.0).abs() < 1e-12);
    }

    /// σ, the background's stated standard deviation (what every SNR divides by), is what a
    /// silent channel records: over 2,000 windows of 200 ADC samples of a zero signal, the
    /// measured samples' standard deviation is `noise_rms` within 1 % (the estimate of a
    /// variance: each window's mean square scatters by about 0.4 of itself, the pink part's
    /// slow offset included, so the mean of 2,000 windows by 0.9 %, and σ by 0.45 %; 1 % is
    /// 2.2 standard errors, and a background missing a tenth of its power would fail by 5 %).
    #[test]
    fn a_silent_channel_records_sigma() {
        let mut s = spec(10_000.0);
        s.recordings[0].background = Some(Psd::pink(0.5, 10.0, 5_000.0));
        let chain = Chain::new(s, 40_000.0).unwrap();
        let sigma = chain.recording(Measurand::Acceleration).unwrap().noise_rms(10_000.0);
        let (mut sum, mut n) = (0.0, 0);
        for w in 0..2_000 {
            let m = chain.measure(Measurand::Acceleration, &[0.0; 800], 1.0, &mut chain.stream(w)).unwrap();
            sum += m.samples.iter().map(|v| v * v).sum::<f64>();
            n += m.samples.len();
            assert_eq!(m.clean_peak, 0.0);
        }
        let measured = (sum / n as f64).sqrt();
        assert!((measured / sigma - 1.0).abs() < 0.01, "{measured} against {sigma}");
    }

    /// The ADC rounds to its step and clips at its codes' span.
    #[test]
    fn quantisation_rounds_and_clips() {
        let mut x = vec![0.26, -0.26, 0.74, 5.0, -5.0];
        // R = 1, 3 bits: q = 0.25, codes -4..3, so the span is -1..0.75.
        let clipped = quantise(&mut x, 1.0, 3);
        assert_eq!(x, vec![0.25, -0.25, 0.75, 0.75, -1.0]);
        assert_eq!(clipped, 2);
    }

    /// The ADC's rate must divide the model's; filters must lie below 0.45 of it.
    #[test]
    fn rates_and_frequencies_are_checked() {
        assert!(matches!(Chain::new(spec(15_000.0), 40_000.0), Err(ChainError::Rate { .. })));
        assert_eq!(Chain::new(spec(10_000.0), 40_000.0).unwrap().decimation(), 4);
        assert!(matches!(Chain::new(spec(10_000.0), 20_000.0), Err(ChainError::Frequency { .. })));
    }

    /// A window with the background scaled to zero is the filtered, sampled, quantised
    /// signal (within half a step of the clean one); the background's windows differ by
    /// index and repeat for the same index.
    #[test]
    fn measure_is_filter_sample_noise_and_adc() {
        let chain = Chain::new(spec(10_000.0), 40_000.0).unwrap();
        let y: Vec<f64> = (0..800).map(|k| (2.0 * PI * 300.0 * k as f64 / 40_000.0).sin() * 30.0).collect();
        let quiet = chain.measure(Measurand::Acceleration, &y, 0.0, &mut chain.stream(0)).unwrap();
        let mut reference = y.clone();
        chain.cascade.run(&mut reference);
        let q = chain.recording(Measurand::Acceleration).unwrap().step();
        for (k, v) in quiet.samples.iter().enumerate() {
            assert!((v - reference[4 * k]).abs() <= 0.5 * q + 1e-12);
        }
        assert_eq!(quiet.samples.len(), 200);
        let a = chain.measure(Measurand::Acceleration, &y, 1.0, &mut chain.stream(3)).unwrap();
        let b = chain.measure(Measurand::Acceleration, &y, 1.0, &mut chain.stream(3)).unwrap();
        let c = chain.measure(Measurand::Acceleration, &y, 1.0, &mut chain.stream(4)).unwrap();
        assert_eq!(a, b);
        assert_ne!(a.samples, c.samples);
        assert!(chain.measure(Measurand::SupportForce, &y, 1.0, &mut chain.stream(0)).is_none());
    }
}
