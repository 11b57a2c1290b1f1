//! The stationary background a channel records beside the impact: Gaussian noise of a given
//! one-sided power spectral density S(f) (unit²/Hz) plus tonal machinery lines, and Welch's
//! estimate of a PSD from samples (the inverse, to check the first).
//!
//! Synthesis (the spectral method; Shinozuka & Deodatis, Appl. Mech. Rev. 44 (1991) 191): on
//! N = 2^⌈log₂ 2n⌉ points at rate f_s, bin k stands for the band of width Δf = f_s/N about
//! f_k = kΔf, of power P_k = ∫S over it (the first band from 0, the last to f_s/2). The bins
//! X_k, 0 < k < N/2, are independent complex Gaussians with E abs(X_k)² = N²P_k/2, DC and the
//! Nyquist bin real Gaussians with E X² = N²P_k, the rest their conjugates; x = IDFT(X)/N
//! then has E x² = Σ_k P_k = ∫₀^{f_s/2} S df exactly, and its periodogram is S on average
//! where S varies little over a bin. The power below Δf/2 becomes a random offset of the
//! window, which is what a background's slow part is within a short window. The first n of
//! the N samples are kept: the synthesised process is periodic in N, so taking at most half
//! of it keeps correlations shorter than n/2 samples exact.

use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use serde::Serialize;
use std::f64::consts::PI;
use std::sync::Arc;

/// A one-sided power spectral density.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "shape", rename_all = "kebab-case")]
pub enum Psd {
    /// White: S(f) = level for all f.
    White {
        /// unit²/Hz.
        level: f64,
    },
    /// Pink: S(f) = level · (f_ref/max(f, f_low)) with f_ref = 1 Hz, flat below `f_low`.
    Pink {
        /// unit²/Hz at 1 Hz.
        level: f64,
        /// Hz, positive.
        f_low: f64,
    },
    /// A measured PSD: linear between its (frequency, S) points, increasing in frequency;
    /// zero outside them (nothing is assumed where nothing was measured).
    Table {
        /// (Hz, unit²/Hz).
        points: Vec<(f64, f64)>,
    },
}

impl Psd {
    /// White noise of `rms` over 0..`band_hz`.
    pub fn white(rms: f64, band_hz: f64) -> Self {
        Psd::White { level: rms * rms / band_hz }
    }

    /// Pink noise of `rms` over 0..`band_hz`, flat below `f_low`:
    /// ∫₀^B S = level (1 + ln(B/f_low)) (for f_low < B).
    pub fn pink(rms: f64, f_low: f64, band_hz: f64) -> Self {
        let shape = 1.0 + (band_hz / f_low).ln().max(0.0);
        Psd::Pink { level: rms * rms / shape, f_low }
    }

    /// S(f), unit²/Hz.
    pub fn density(&self, f: f64) -> f64 {
        match self {
            Psd::White { level } => *level,
            Psd::Pink { level, f_low } => level / f.max(*f_low),
            Psd::Table { points } => {
                let i = points.partition_point(|p| p.0 <= f);
                if i == 0 || i == points.len() {
                    // Beyond the table, except exactly at its last point.
                    return points.last().filter(|p| p.0 == f).map_or(0.0, |p| p.1);
                }
                let ((f0, s0), (f1, s1)) = (points[i - 1], points[i]);
                s0 + (s1 - s0) * (f - f0) / (f1 - f0)
            }
        }
    }

    /// ∫₀^`band_hz` S df, unit².
    pub fn power(&self, band_hz: f64) -> f64 {
        self.band_power(0.0, band_hz)
    }

    /// ∫_{f₀}^{f₁} S df (f₀ ≤ f₁), in closed form: white level·(f₁ - f₀); pink level/f_low
    /// below f_low and level·ln(f₁/f₀) above; a table exactly, piece by linear piece.
    pub fn band_power(&self, f0: f64, f1: f64) -> f64 {
        if f1 <= f0 {
            return 0.0;
        }
        match self {
            Psd::White { level } => level * (f1 - f0),
            Psd::Pink { level, f_low } => {
                let flat = (f1.min(*f_low) - f0).max(0.0) * level / f_low;
                let falling = if f1 > *f_low { level * (f1 / f0.max(*f_low)).ln() } else { 0.0 };
                flat + falling
            }
            Psd::Table { points } => points
                .windows(2)
                .map(|w| {
                    let ((a, sa), (b, sb)) = (w[0], w[1]);
                    let (lo, hi) = (f0.max(a), f1.min(b));
                    if hi <= lo {
                        return 0.0;
                    }
                    let at = |f: f64| sa + (sb - sa) * (f - a) / (b - a);
                    0.5 * (hi - lo) * (at(lo) + at(hi))
                })
                .sum(),
        }
    }
}

/// A tonal machinery line: √2 · rms · sin(2πft + φ), the phase φ uniform and drawn anew for
/// every window.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Tone {
    /// Hz.
    pub frequency_hz: f64,
    /// RMS amplitude, in the channel's unit.
    pub rms: f64,
}

/// Draws windows of `n` samples of Gaussian noise of one PSD at one rate (module docs): the
/// bins' standard deviations and the inverse FFT's plan, computed once.
#[derive(Clone)]
pub struct Synthesizer {
    n: usize,
    /// Per bin k = 0..=N/2, the standard deviation of each of X_k's parts, N√(P_k/4) (so
    /// E abs(X_k)² = N²P_k/2), with P_k the band power of bin k; N√P_k for the real DC and
    /// Nyquist bins.
    deviation: Vec<f64>,
    fft: Arc<dyn Fft<f64>>,
}

impl std::fmt::Debug for Synthesizer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Synthesizer").field("n", &self.n).field("size", &self.fft.len()).finish()
    }
}

impl Synthesizer {
    /// For `n` samples of `psd` at `rate_hz`.
    pub fn new(psd: &Psd, n: usize, rate_hz: f64) -> Self {
        let size = (2 * n.max(1)).next_power_of_two();
        let df = rate_hz / size as f64;
        let big_n = size as f64;
        let deviation = (0..=size / 2)
            .map(|k| {
                // Bin k stands for the band [f_k - Δf/2, f_k + Δf/2] cut to [0, f_s/2]: the
                // power below Δf/2 becomes a random offset of the window (what a slow part
                // of the background is within it), so the variance is ∫S exactly.
                let f = k as f64 * df;
                let p = psd.band_power((f - 0.5 * df).max(0.0), (f + 0.5 * df).min(0.5 * rate_hz));
                if k == 0 || k == size / 2 {
                    big_n * p.sqrt()
                } else {
                    big_n * (0.25 * p).sqrt()
                }
            })
            .collect();
        Self { n, deviation, fft: FftPlanner::new().plan_fft_inverse(size) }
    }

    /// The next window, drawn from `rng`.
    pub fn draw(&self, rng: &mut ChaCha8Rng) -> Vec<f64> {
        let size = self.fft.len();
        let mut bins = vec![Complex::new(0.0, 0.0); size];
        for (k, d) in self.deviation.iter().enumerate() {
            let (a, b): (f64, f64) = (StandardNormal.sample(rng), StandardNormal.sample(rng));
            if k == 0 || k == size / 2 {
                bins[k] = Complex::new(d * a, 0.0);
            } else {
                bins[k] = Complex::new(d * a, d * b);
                bins[size - k] = bins[k].conj();
            }
        }
        self.fft.process(&mut bins);
        bins[..self.n].iter().map(|c| c.re / size as f64).collect()
    }

    /// The samples of a window.
    pub fn samples(&self) -> usize {
        self.n
    }
}

/// The next `n` samples at `rate_hz` of Gaussian noise of PSD `psd` (module docs), drawn from
/// `rng` ([`Synthesizer`] once).
pub fn synthesize(psd: &Psd, n: usize, rate_hz: f64, rng: &mut ChaCha8Rng) -> Vec<f64> {
    Synthesizer::new(psd, n, rate_hz).draw(rng)
}

/// Adds `tones` to `x` (sampled at `rate_hz`), each with a phase drawn from `rng`.
pub fn add_tones(x: &mut [f64], tones: &[Tone], rate_hz: f64, rng: &mut ChaCha8Rng) {
    let phases: Vec<f64> = tones.iter().map(|_| 2.0 * PI * crate::ensemble::open_uniform(rng)).collect();
    add_tones_at(x, tones, rate_hz, &phases, 0);
}

/// Adds `tones` of phases `phases` to `x`, whose first sample is the recording's sample
/// number `first`: √2 · rms · sin(2πf(first + k)/f_s + φ).
pub fn add_tones_at(x: &mut [f64], tones: &[Tone], rate_hz: f64, phases: &[f64], first: usize) {
    for (t, &phase) in tones.iter().zip(phases) {
        let (amplitude, w) = (2f64.sqrt() * t.rms, 2.0 * PI * t.frequency_hz / rate_hz);
        for (k, v) in x.iter_mut().enumerate() {
            *v += amplitude * (w * (first + k) as f64 + phase).sin();
        }
    }
}

/// Welch's estimate of the one-sided PSD of `x` at `rate_hz` (Welch, IEEE Trans. Audio
/// Electroacoust. 15 (1967) 70): Hann-windowed segments of `segment` samples overlapping by
/// half, P_k = c · mean abs(X_k)²/(f_s Σw²) with c = 2 except at DC and Nyquist (c = 1).
/// Returns (frequencies, densities) of bins 0..=segment/2 and the number of segments
/// averaged (none for a segment of fewer than 2 samples). At DC and Nyquist, where c = 1, a
/// smooth S is estimated as S/2 (half the Hann window's main lobe lies outside the band).
pub fn welch(x: &[f64], rate_hz: f64, segment: usize) -> (Vec<f64>, Vec<f64>, usize) {
    if segment < 2 {
        return (Vec::new(), Vec::new(), 0);
    }
    let w: Vec<f64> = (0..segment).map(|k| 0.5 - 0.5 * (2.0 * PI * k as f64 / segment as f64).cos()).collect();
    let norm = rate_hz * w.iter().map(|v| v * v).sum::<f64>();
    let fft = FftPlanner::new().plan_fft_forward(segment);
    let mut sum = vec![0.0; segment / 2 + 1];
    let mut count = 0;
    let mut start = 0;
    while start + segment <= x.len() {
        let mut buf: Vec<Complex<f64>> =
            x[start..start + segment].iter().zip(&w).map(|(v, w)| Complex::new(v * w, 0.0)).collect();
        fft.process(&mut buf);
        for (s, b) in sum.iter_mut().zip(&buf) {
            *s += b.norm_sqr();
        }
        count += 1;
        start += segment / 2;
    }
    let freqs = (0..sum.len()).map(|k| k as f64 * rate_hz / segment as f64).collect();
    let last = sum.len() - 1;
    let psd = sum
        .iter()
        .enumerate()
        .map(|(k, s)| if k == 0 || k == last { 1.0 } else { 2.0 } * s / (count.max(1) as f64 * norm))
        .collect();
    (freqs, psd, count)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ensemble::impact_stream;

    /// Welch's estimate of synthesised noise recovers its PSD within the estimate's own
    /// confidence: with K Hann segments overlapping by half the estimate of each bin is
    /// S χ²_ν/ν with ν ≈ 2K/(1 + 2 ρ²), ρ = 1/6 the overlap correlation of the Hann window
    /// (Welch 1967, eq. 20), so its relative standard deviation is √(2/ν). Every bin away
    /// from DC lies within 5 of them and 90-99 % within 1.96 of them (95 % expected; the
    /// neighbours of a Hann bin are correlated, so the count is wider than a binomial's).
    #[test]
    fn welch_recovers_the_psd_within_its_confidence() {
        let rate = 10_000.0;
        let table = Psd::Table { points: vec![(0.0, 1e-4), (2_000.0, 4e-4), (3_000.0, 1e-4), (5_000.0, 1e-4)] };
        for psd in [Psd::white(0.3, rate / 2.0), Psd::pink(0.3, 10.0, rate / 2.0), table] {
            let x = synthesize(&psd, 1 << 19, rate, &mut impact_stream(7, 0));
            let segment = 512;
            let (f, p, k) = welch(&x, rate, segment);
            let nu = 2.0 * k as f64 / (1.0 + 2.0 / 36.0);
            let sd = (2.0 / nu).sqrt();
            let (mut inside, mut total) = (0, 0);
            // Skip the lowest bins, where the Hann window's leakage of pink noise's steep
            // 1/f part biases any estimate, and the Nyquist bin.
            for i in 4..p.len() - 1 {
                let s = psd.density(f[i]);
                let z = (p[i] / s - 1.0) / sd;
                assert!(z.abs() < 5.0, "{psd:?}: {} Hz: {} against {s} ({z} sd)", f[i], p[i]);
                inside += usize::from(z.abs() < 1.96);
                total += 1;
            }
            let share = inside as f64 / total as f64;
            assert!((0.90..=0.99).contains(&share), "{psd:?}: {share} of the bins within 1.96 sd");
        }
    }

    /// The variance of the synthesised noise is ∫S df (to the sampling error of a variance
    /// of 2^18 correlated samples: a band B holds about 2 B T independent degrees of freedom
    /// in a record of T = 13 s, so a pink PSD flat below 200 Hz puts a fifth of its power in
    /// some 5,000 of them and the variance's standard error stays below 1 %; a pink PSD flat
    /// only below 5 Hz would leave a quarter of its power to a few hundred), and the rms a
    /// white or pink PSD was made for.
    #[test]
    fn synthesised_variance_is_the_integral() {
        let rate = 20_000.0;
        for psd in [Psd::white(2.0, rate / 2.0), Psd::pink(2.0, 200.0, rate / 2.0)] {
            let x = synthesize(&psd, 1 << 18, rate, &mut impact_stream(3, 1));
            let var = x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64;
            assert!((var / 4.0 - 1.0).abs() < 0.02, "{psd:?}: {var}");
            assert!((psd.power(rate / 2.0) / 4.0 - 1.0).abs() < 0.01, "{psd:?}");
        }
    }

    /// A tone adds its mean square: rms² over whole periods.
    #[test]
    fn a_tone_has_its_rms() {
        let mut x = vec![0.0; 20_000];
        add_tones(&mut x, &[Tone { frequency_hz: 50.0, rms: 0.7 }], 20_000.0, &mut impact_stream(1, 2));
        let ms = x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64;
        assert!((ms - 0.49).abs() < 1e-9, "{ms}");
    }
}
