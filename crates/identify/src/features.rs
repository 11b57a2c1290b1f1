//! Features of one sampled signal x_k = x(kΔt), k = 0..n-1, Δt = 1/rate, over the window
//! after the impact: the numbers a sensor's data acquisition would keep.
//!
//! | feature | definition |
//! |---|---|
//! | peak | max_k abs(x_k) (for a spring-force channel: the peak spring force) |
//! | RMS | √(Σ x_k² / n), over the whole window |
//! | energy | ∫x² dt ≈ Σ x_k² Δt (the rectangle rule, exact for a sampled sine over whole periods) |
//! | duration | from the first to the last sample with abs(x_k) ≥ peak/10 (the -20 dB span), s |
//! | dominant frequency | the peak of the power spectrum, excluding DC, refined by a parabola through the log powers of its bin and its two neighbours, Hz |
//! | spectral centroid | Σ f_j P_j / Σ P_j over the one-sided bins j = 1..N/2 (DC excluded), Hz |
//!
//! The threshold of the duration is relative to the channel's own peak, so that the
//! duration measures how long the response rings (its decay), independent of its size; for
//! x = A e^{-t/τ} sin ωt it is τ ln 10 to within a period.
//!
//! Spectra: the signal is multiplied by a one-sided Tukey window (1 up to 90 % of the
//! window, then a half cosine to 0 at its end), zero-padded to the next power of two and
//! transformed (rustfft); P_j = abs(X_j)². The window starts the signal at the impact, when the
//! plate is at rest, so the start needs no taper; the end cuts the plate's ringing, and the
//! taper there keeps that cut from spreading power over the whole spectrum. A signal
//! identically zero (a sensor on a fixed corner) has every feature 0.

use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use serde::{Serialize, Serializer};
use std::cell::OnceCell;
use std::sync::Arc;

/// One feature of a sampled signal: the extension point of the identification. A new
/// feature is one implementation and one line in [`FEATURES`]; the feature table, the AUC
/// ranking, the classifiers, the report's `features.csv` and the Python columns all iterate
/// that registry.
///
/// ```
/// use identify::features::{Extractor, Feature, Signal, FEATURES};
///
/// /// The crest factor: peak over RMS.
/// struct CrestFactor;
///
/// impl Feature for CrestFactor {
///     fn key(&self) -> &'static str {
///         "crest_factor"
///     }
///     fn name(&self) -> &'static str {
///         "crest factor"
///     }
///     fn unit(&self, _signal_unit: &str) -> String {
///         "1".into()
///     }
///     fn compute(&self, s: &Signal<'_>) -> f64 {
///         let sum_sq: f64 = s.values().iter().map(|v| v * v).sum();
///         s.peak() / (sum_sq / s.window_samples() as f64).sqrt()
///     }
/// }
///
/// // 50 ms of a 500 Hz sine at 20 kHz: 25 whole periods, a crest on a sample (k = 10), so
/// // the crest factor is √2 to rounding.
/// let rate = 20_000.0;
/// let x: Vec<f64> = (0..1000).map(|k| (std::f64::consts::TAU * 500.0 * k as f64 / rate).sin()).collect();
/// let extractor = Extractor::new(x.len(), rate);
/// let mut values = Vec::new();
/// extractor.push_features(&[&CrestFactor, FEATURES[0]], &x, &mut values);
/// assert!((values[0] - 2f64.sqrt()).abs() < 1e-12, "{}", values[0]);
/// assert_eq!(values[1], extractor.features(&x)[0]); // the peak, as the registry computes it
/// ```
pub trait Feature: Send + Sync {
    /// Its name in tables, file headers and column names ("dominant_frequency"): unique in
    /// [`FEATURES`], which identifies features by it.
    fn key(&self) -> &'static str;

    /// Its name in the report's words ("dominant frequency"); the key unless given.
    fn name(&self) -> &'static str {
        self.key()
    }

    /// Its unit for a signal in `signal_unit` ("m/s^2", "N", ...).
    fn unit(&self, signal_unit: &str) -> String;

    /// Whether the feature measures a size that spreads over decades (peak, RMS, energy),
    /// so that a linear classifier should see its logarithm (its values must then be
    /// positive). No unless given.
    fn is_scale(&self) -> bool {
        false
    }

    /// Its value for `signal` (never identically zero: a zero signal has every feature 0
    /// without asking them).
    fn compute(&self, signal: &Signal<'_>) -> f64;
}

/// Every feature the identification computes, in the order of [`Extractor::features`] and
/// of the feature table's columns.
pub const FEATURES: &[&dyn Feature] = &[&Peak, &Rms, &Energy, &Duration, &DominantFrequency, &SpectralCentroid];

impl dyn Feature + '_ {
    /// Its position in [`FEATURES`] (by key); panics for a feature not registered there.
    pub fn index(&self) -> usize {
        FEATURES
            .iter()
            .position(|f| f.key() == self.key())
            .unwrap_or_else(|| panic!("{} is not in FEATURES", self.key()))
    }
}

/// Features are the same when their keys are.
impl<'a, 'b> PartialEq<dyn Feature + 'b> for dyn Feature + 'a {
    fn eq(&self, other: &(dyn Feature + 'b)) -> bool {
        self.key() == other.key()
    }
}

impl std::fmt::Debug for dyn Feature + '_ {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.key())
    }
}

/// In JSON a feature is its key in kebab case ("dominant-frequency").
impl Serialize for dyn Feature + '_ {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(&self.key().replace('_', "-"))
    }
}

/// Largest absolute value.
#[derive(Debug, Clone, Copy)]
pub struct Peak;

impl Feature for Peak {
    fn key(&self) -> &'static str {
        "peak"
    }
    fn unit(&self, signal_unit: &str) -> String {
        signal_unit.to_string()
    }
    fn is_scale(&self) -> bool {
        true
    }
    fn compute(&self, s: &Signal<'_>) -> f64 {
        s.peak()
    }
}

/// Σ x_k² over the window's samples.
fn sum_of_squares(s: &Signal<'_>) -> f64 {
    s.values().iter().map(|v| v * v).sum()
}

/// Root mean square over the window.
#[derive(Debug, Clone, Copy)]
pub struct Rms;

impl Feature for Rms {
    fn key(&self) -> &'static str {
        "rms"
    }
    fn name(&self) -> &'static str {
        "RMS"
    }
    fn unit(&self, signal_unit: &str) -> String {
        signal_unit.to_string()
    }
    fn is_scale(&self) -> bool {
        true
    }
    fn compute(&self, s: &Signal<'_>) -> f64 {
        (sum_of_squares(s) / s.window_samples() as f64).sqrt()
    }
}

/// ∫x² dt over the window.
#[derive(Debug, Clone, Copy)]
pub struct Energy;

impl Feature for Energy {
    fn key(&self) -> &'static str {
        "energy"
    }
    fn unit(&self, signal_unit: &str) -> String {
        format!("({signal_unit})^2*s")
    }
    fn is_scale(&self) -> bool {
        true
    }
    fn compute(&self, s: &Signal<'_>) -> f64 {
        sum_of_squares(s) * s.dt()
    }
}

/// The -20 dB span, s.
#[derive(Debug, Clone, Copy)]
pub struct Duration;

impl Feature for Duration {
    fn key(&self) -> &'static str {
        "duration"
    }
    fn unit(&self, _signal_unit: &str) -> String {
        "s".into()
    }
    fn compute(&self, s: &Signal<'_>) -> f64 {
        let x = s.values();
        let threshold = DURATION_THRESHOLD * s.peak();
        let first = x.iter().position(|v| v.abs() >= threshold).unwrap_or(0);
        let last = x.iter().rposition(|v| v.abs() >= threshold).unwrap_or(0);
        (last - first) as f64 * s.dt()
    }
}

/// The frequency of the largest spectral power, Hz.
#[derive(Debug, Clone, Copy)]
pub struct DominantFrequency;

impl Feature for DominantFrequency {
    fn key(&self) -> &'static str {
        "dominant_frequency"
    }
    fn name(&self) -> &'static str {
        "dominant frequency"
    }
    fn unit(&self, _signal_unit: &str) -> String {
        "Hz".into()
    }
    fn compute(&self, s: &Signal<'_>) -> f64 {
        let power = s.power();
        let half = power.len() - 1;
        let mut den = 0.0;
        let mut best = 1;
        for (j, &p) in power.iter().enumerate().skip(1) {
            den += p;
            if p > power[best] {
                best = j;
            }
        }
        if den.is_nan() || den <= 0.0 {
            return 0.0;
        }
        // A parabola through the log powers of the peak bin and its neighbours (exact for a
        // Gaussian peak, and within a small fraction of a bin for the tapered tone).
        let offset = if best > 1 && best < half && power[best - 1] > 0.0 && power[best + 1] > 0.0 {
            let (a, b, c) = (power[best - 1].ln(), power[best].ln(), power[best + 1].ln());
            let d = a - 2.0 * b + c;
            if d < 0.0 {
                (0.5 * (a - c) / d).clamp(-0.5, 0.5)
            } else {
                0.0
            }
        } else {
            0.0
        };
        (best as f64 + offset) * s.bin_hz()
    }
}

/// The power-weighted mean frequency, Hz.
#[derive(Debug, Clone, Copy)]
pub struct SpectralCentroid;

impl Feature for SpectralCentroid {
    fn key(&self) -> &'static str {
        "spectral_centroid"
    }
    fn name(&self) -> &'static str {
        "spectral centroid"
    }
    fn unit(&self, _signal_unit: &str) -> String {
        "Hz".into()
    }
    fn compute(&self, s: &Signal<'_>) -> f64 {
        let (mut num, mut den) = (0.0, 0.0);
        for (j, &p) in s.power().iter().enumerate().skip(1) {
            num += j as f64 * p;
            den += p;
        }
        if den.is_nan() || den <= 0.0 {
            return 0.0;
        }
        num / den * s.bin_hz()
    }
}

/// Fraction of the peak that defines the duration (-20 dB).
pub const DURATION_THRESHOLD: f64 = 0.1;
/// Fraction of the window at its end over which the Tukey taper falls from 1 to 0.
pub const TAPER_FRACTION: f64 = 0.1;

/// One signal as its features read it: the window's samples, their peak, and the power
/// spectrum, computed on the first feature that asks for it and shared by the rest.
pub struct Signal<'a> {
    x: &'a [f64],
    peak: f64,
    extractor: &'a Extractor,
    power: OnceCell<Vec<f64>>,
}

impl Signal<'_> {
    /// The samples x_k within the window (a longer signal is cut to it).
    pub fn values(&self) -> &[f64] {
        self.x
    }

    /// The samples of the window, n: a signal shorter than that is read as followed by zeros.
    pub fn window_samples(&self) -> usize {
        self.extractor.samples
    }

    /// The sampling interval Δt, s.
    pub fn dt(&self) -> f64 {
        1.0 / self.extractor.rate_hz
    }

    /// max_k abs(x_k), positive and finite.
    pub fn peak(&self) -> f64 {
        self.peak
    }

    /// The one-sided power spectrum P_j = abs(X_j)², j = 0..=N/2 (module docs: the taper and
    /// the padding).
    pub fn power(&self) -> &[f64] {
        self.power.get_or_init(|| self.extractor.power(self.x))
    }

    /// The spacing of the spectrum's bins, Hz.
    pub fn bin_hz(&self) -> f64 {
        self.extractor.bin_hz()
    }
}

/// Computes the features of signals of one length and rate; holds the FFT plan and the
/// window, and may be shared between threads.
pub struct Extractor {
    rate_hz: f64,
    samples: usize,
    fft: Arc<dyn Fft<f64>>,
    window: Vec<f64>,
}

impl std::fmt::Debug for Extractor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Extractor")
            .field("rate_hz", &self.rate_hz)
            .field("samples", &self.samples)
            .field("fft_len", &self.fft.len())
            .finish()
    }
}

impl Extractor {
    /// For signals of `samples` values at `rate_hz` (both positive).
    pub fn new(samples: usize, rate_hz: f64) -> Self {
        let samples = samples.max(1);
        let n = samples.next_power_of_two();
        let fft = FftPlanner::new().plan_fft_forward(n);
        let start = ((1.0 - TAPER_FRACTION) * samples as f64).floor() as usize;
        let window = (0..samples)
            .map(|k| {
                if k < start || samples - start < 2 {
                    1.0
                } else {
                    // 1 at k = start, 0 at the last sample.
                    let t = (k - start) as f64 / (samples - 1 - start) as f64;
                    0.5 * (1.0 + (std::f64::consts::PI * t).cos())
                }
            })
            .collect();
        Self { rate_hz, samples, fft, window }
    }

    /// The number of samples per signal.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// The spacing of the spectrum's bins, Hz.
    pub fn bin_hz(&self) -> f64 {
        self.rate_hz / self.fft.len() as f64
    }

    /// The features of [`FEATURES`] of `x`, in that order (of [`Extractor::samples`] values;
    /// a shorter signal is read as followed by zeros, a longer one is cut).
    pub fn features(&self, x: &[f64]) -> Vec<f64> {
        let mut values = Vec::with_capacity(FEATURES.len());
        self.push_features(FEATURES, x, &mut values);
        values
    }

    /// Appends to `values` the value of each of `features` for `x` (as [`Extractor::features`]).
    pub fn push_features(&self, features: &[&dyn Feature], x: &[f64], values: &mut Vec<f64>) {
        let x = &x[..x.len().min(self.samples)];
        let peak = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if !peak.is_finite() || peak <= 0.0 {
            values.extend(features.iter().map(|_| 0.0));
            return;
        }
        let signal = Signal { x, peak, extractor: self, power: OnceCell::new() };
        values.extend(features.iter().map(|f| f.compute(&signal)));
    }

    /// The one-sided power spectrum of `x` (at most [`Extractor::samples`] values), tapered
    /// and zero-padded.
    fn power(&self, x: &[f64]) -> Vec<f64> {
        let n = self.fft.len();
        let mut buf: Vec<Complex<f64>> = vec![Complex::new(0.0, 0.0); n];
        for (b, (v, w)) in buf.iter_mut().zip(x.iter().zip(&self.window)) {
            b.re = v * w;
        }
        self.fft.process(&mut buf);
        buf[..=n / 2].iter().map(|c| c.norm_sqr()).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    const RATE: f64 = 50_000.0;

    /// The value of `feature` for `x`, computed on the registry with the others.
    fn get(e: &Extractor, feature: &dyn Feature, x: &[f64]) -> f64 {
        e.features(x)[feature.index()]
    }

    fn sine(a: f64, f: f64, n: usize) -> Vec<f64> {
        (0..n).map(|k| a * (2.0 * PI * f * k as f64 / RATE).sin()).collect()
    }

    #[test]
    fn sine_rms_energy_and_peak_are_the_closed_forms() {
        // 20 ms at 50 kHz, 300 Hz: six whole periods. RMS = A/√2, ∫x² dt = A²T/2 (the
        // rectangle sum of sin² over whole periods is exact), peak = A to the sampling
        // (the crest falls on a sample here: 50 kHz / 300 Hz / 4 is not whole, so allow the
        // cosine of half a sample's phase, 1 - cos(π·300/50000) = 1.8e-4).
        let (a, f, n) = (3.0, 300.0, 1000);
        let x = sine(a, f, n);
        let e = Extractor::new(n, RATE);
        let (rms, energy, peak) = (get(&e, &Rms, &x), get(&e, &Energy, &x), get(&e, &Peak, &x));
        assert!((rms / (a / 2f64.sqrt()) - 1.0).abs() < 1e-12, "{rms}");
        assert!((energy / (a * a * 0.02 / 2.0) - 1.0).abs() < 1e-12, "{energy}");
        assert!(peak <= a && peak > a * (1.0 - 1.8e-4));
    }

    #[test]
    fn dominant_frequency_of_a_tone_off_the_bins() {
        // Bins are 50000/1024 = 48.8 Hz; tones between bins must come out within a tenth of a
        // bin (the parabola through the log powers of the tapered tone).
        let e = Extractor::new(1000, RATE);
        for f in [300.0, 1234.5, 4321.0, 9876.0] {
            let dominant = get(&e, &DominantFrequency, &sine(1.0, f, 1000));
            assert!((dominant - f).abs() < 0.1 * e.bin_hz(), "{f}: {dominant}");
        }
    }

    #[test]
    fn centroid_of_two_tones_is_their_power_weighted_mean() {
        // Tones on bin centres (n a power of two, no padding) with amplitudes 1 and 2: the
        // centroid is (f₁·1 + f₂·4)/5. The taper leaks a little power into neighbouring
        // bins on both sides, almost symmetrically: 1 % is that leakage's bound here.
        let n = 1024;
        let bin = RATE / n as f64;
        let (f1, f2) = (20.0 * bin, 100.0 * bin);
        let x: Vec<f64> = sine(1.0, f1, n).iter().zip(sine(2.0, f2, n)).map(|(a, b)| a + b).collect();
        let e = Extractor::new(n, RATE);
        let (centroid, dominant) = (get(&e, &SpectralCentroid, &x), get(&e, &DominantFrequency, &x));
        let expected = (f1 + 4.0 * f2) / 5.0;
        assert!((centroid / expected - 1.0).abs() < 0.01, "{centroid} vs {expected}");
        assert!((dominant - f2).abs() < 0.01 * bin);
    }

    #[test]
    fn duration_of_a_decaying_tone_is_tau_ln_10() {
        // x = e^{-t/τ} sin(2πft): the envelope falls to a tenth at τ ln 10; the last sample
        // above the threshold lies within one period before that, the first within one
        // period of the start.
        let (tau, f, n) = (0.004, 2000.0, 1000);
        let x: Vec<f64> = (0..n)
            .map(|k| {
                let t = k as f64 / RATE;
                (-t / tau).exp() * (2.0 * PI * f * t).sin()
            })
            .collect();
        let duration = get(&Extractor::new(n, RATE), &Duration, &x);
        let expected = tau * 10f64.ln();
        assert!((duration - expected).abs() < 1.0 / f, "{duration} vs {expected}");
    }

    #[test]
    fn zero_signal_has_zero_features() {
        let ft = Extractor::new(100, RATE).features(&[0.0; 100]);
        assert_eq!(ft, vec![0.0; FEATURES.len()]);
    }

    #[test]
    fn registry_keys_are_unique_and_serialise_in_kebab_case() {
        let mut keys: Vec<&str> = FEATURES.iter().map(|f| f.key()).collect();
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(keys.len(), FEATURES.len());
        for (k, f) in FEATURES.iter().enumerate() {
            assert_eq!(f.index(), k);
        }
        let json = serde_json::to_string(FEATURES).unwrap();
        assert_eq!(json, r#"["peak","rms","energy","duration","dominant-frequency","spectral-centroid"]"#);
    }
}
