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
use serde::Serialize;
use std::sync::Arc;

/// One feature of a signal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Feature {
    /// Largest absolute value.
    Peak,
    /// Root mean square over the window.
    Rms,
    /// ∫x² dt over the window.
    Energy,
    /// The -20 dB span, s.
    Duration,
    /// The frequency of the largest spectral power, Hz.
    DominantFrequency,
    /// The power-weighted mean frequency, Hz.
    SpectralCentroid,
}

/// Every feature, in the order of [`Features::values`].
pub const FEATURES: [Feature; 6] = [
    Feature::Peak,
    Feature::Rms,
    Feature::Energy,
    Feature::Duration,
    Feature::DominantFrequency,
    Feature::SpectralCentroid,
];

impl Feature {
    /// Its name in tables and file headers.
    pub fn key(self) -> &'static str {
        match self {
            Feature::Peak => "peak",
            Feature::Rms => "rms",
            Feature::Energy => "energy",
            Feature::Duration => "duration",
            Feature::DominantFrequency => "dominant_frequency",
            Feature::SpectralCentroid => "spectral_centroid",
        }
    }

    /// Its unit for a signal in `unit` ("m/s^2", "N", ...).
    pub fn unit(self, unit: &str) -> String {
        match self {
            Feature::Peak | Feature::Rms => unit.to_string(),
            Feature::Energy => format!("({unit})^2*s"),
            Feature::Duration => "s".into(),
            Feature::DominantFrequency | Feature::SpectralCentroid => "Hz".into(),
        }
    }

    /// Whether the feature measures a size that spreads over decades (peak, RMS, energy),
    /// so that a linear classifier should see its logarithm.
    pub fn is_scale(self) -> bool {
        matches!(self, Feature::Peak | Feature::Rms | Feature::Energy)
    }

    /// Its position in [`FEATURES`].
    pub fn index(self) -> usize {
        FEATURES.iter().position(|f| *f == self).expect("every feature is listed")
    }
}

/// The features of one signal.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Features {
    /// max abs(x).
    pub peak: f64,
    /// √(mean x²).
    pub rms: f64,
    /// Σ x² Δt.
    pub energy: f64,
    /// The -20 dB span, s.
    pub duration: f64,
    /// Hz.
    pub dominant_frequency: f64,
    /// Hz.
    pub spectral_centroid: f64,
}

impl Features {
    /// The values in the order of [`FEATURES`].
    pub fn values(&self) -> [f64; 6] {
        [self.peak, self.rms, self.energy, self.duration, self.dominant_frequency, self.spectral_centroid]
    }

    /// The value of `feature`.
    pub fn get(&self, feature: Feature) -> f64 {
        self.values()[feature.index()]
    }
}

/// Fraction of the peak that defines the duration (-20 dB).
pub const DURATION_THRESHOLD: f64 = 0.1;
/// Fraction of the window at its end over which the Tukey taper falls from 1 to 0.
pub const TAPER_FRACTION: f64 = 0.1;

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

    /// The features of `x` (of [`Extractor::samples`] values; a shorter signal is read as
    /// followed by zeros, a longer one is cut).
    pub fn features(&self, x: &[f64]) -> Features {
        let x = &x[..x.len().min(self.samples)];
        let dt = 1.0 / self.rate_hz;
        let peak = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if !peak.is_finite() || peak <= 0.0 {
            return Features::default();
        }
        let sum_sq: f64 = x.iter().map(|v| v * v).sum();
        let threshold = DURATION_THRESHOLD * peak;
        let first = x.iter().position(|v| v.abs() >= threshold).unwrap_or(0);
        let last = x.iter().rposition(|v| v.abs() >= threshold).unwrap_or(0);
        let (dominant_frequency, spectral_centroid) = self.spectrum(x);
        Features {
            peak,
            rms: (sum_sq / self.samples as f64).sqrt(),
            energy: sum_sq * dt,
            duration: (last - first) as f64 * dt,
            dominant_frequency,
            spectral_centroid,
        }
    }

    /// (dominant frequency, spectral centroid) of `x`.
    fn spectrum(&self, x: &[f64]) -> (f64, f64) {
        let n = self.fft.len();
        let mut buf: Vec<Complex<f64>> = vec![Complex::new(0.0, 0.0); n];
        for (b, (v, w)) in buf.iter_mut().zip(x.iter().zip(&self.window)) {
            b.re = v * w;
        }
        self.fft.process(&mut buf);
        let half = n / 2;
        let power: Vec<f64> = buf[..=half].iter().map(|c| c.norm_sqr()).collect();
        let bin = self.bin_hz();
        let (mut num, mut den) = (0.0, 0.0);
        let mut best = 1;
        for (j, &p) in power.iter().enumerate().skip(1) {
            num += j as f64 * p;
            den += p;
            if p > power[best] {
                best = j;
            }
        }
        if den.is_nan() || den <= 0.0 {
            return (0.0, 0.0);
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
        ((best as f64 + offset) * bin, num / den * bin)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    const RATE: f64 = 50_000.0;

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
        let ft = e.features(&x);
        assert!((ft.rms / (a / 2f64.sqrt()) - 1.0).abs() < 1e-12, "{}", ft.rms);
        assert!((ft.energy / (a * a * 0.02 / 2.0) - 1.0).abs() < 1e-12, "{}", ft.energy);
        assert!(ft.peak <= a && ft.peak > a * (1.0 - 1.8e-4));
    }

    #[test]
    fn dominant_frequency_of_a_tone_off_the_bins() {
        // Bins are 50000/1024 = 48.8 Hz; tones between bins must come out within a tenth of a
        // bin (the parabola through the log powers of the tapered tone).
        let e = Extractor::new(1000, RATE);
        for f in [300.0, 1234.5, 4321.0, 9876.0] {
            let ft = e.features(&sine(1.0, f, 1000));
            assert!((ft.dominant_frequency - f).abs() < 0.1 * e.bin_hz(), "{f}: {}", ft.dominant_frequency);
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
        let ft = Extractor::new(n, RATE).features(&x);
        let expected = (f1 + 4.0 * f2) / 5.0;
        assert!((ft.spectral_centroid / expected - 1.0).abs() < 0.01, "{} vs {expected}", ft.spectral_centroid);
        assert!((ft.dominant_frequency - f2).abs() < 0.01 * bin);
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
        let ft = Extractor::new(n, RATE).features(&x);
        let expected = tau * 10f64.ln();
        assert!((ft.duration - expected).abs() < 1.0 / f, "{} vs {expected}", ft.duration);
    }

    #[test]
    fn zero_signal_has_zero_features() {
        let ft = Extractor::new(100, RATE).features(&[0.0; 100]);
        assert_eq!(ft, Features::default());
        assert!(ft.values().iter().all(|v| v.is_finite()));
    }
}
