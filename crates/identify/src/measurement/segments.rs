//! A long recording made in segments, each alone, so that segments recorded apart (one task
//! each) put together to the recording bit for bit.
//!
//! **The filters.** Segment b hands the chain the model's samples from its warm-up's start
//! (where the plate is at rest, so the filters start from rest consistently), and keeps the
//! ADC's samples from the segment's first. What the filters held of the input before the
//! warm-up has decayed by e^{-r_f W}, r_f the slowest decay of their poles
//! ([`super::Chain::slowest_decay`]).
//!
//! **The background.** One synthesis over the whole recording ([`super::noise`]) cannot be
//! cut; independent blocks can. Block b is drawn over the ADC samples [bS, (b+1)S + L) from
//! its own place in the channel's stream of random numbers; sample j of segment b is block
//! b's, except over the first L samples of every segment after the first, where the blocks
//! b-1 and b overlap and are joined by a constant-power cross-fade,
//! cos θ · x_{b-1} + sin θ · x_b with θ = (π/2)(j + 1/2)/L. The blocks are independent
//! Gaussian processes of one PSD, so the variance is exactly the PSD's integral everywhere
//! (cos²θ + sin²θ = 1); within the cross-fade the autocovariance at lag τ is the process's
//! times cos(θ(t+τ) - θ(t)) = cos(πτ/2L), so correlations much shorter than L are kept,
//! and the signal runs on continuously through both ends of the fade (block b-1 goes on
//! past the join, block b goes on after the fade). A process correlated over longer than L
//! is decorrelated across a join, as it is across the synthesis's own period.
//!
//! **The tones** are functions of the recording's sample number with a phase drawn once per
//! channel and recording, so they run on through the joins.

use super::noise::{self, Synthesizer, Tone};
use super::{quantise, Chain, Measurand, Measured};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::FRAC_PI_2;

/// Segment `index` of a recording cut into segments of `length` ADC samples whose
/// backgrounds cross-fade over `overlap` samples (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Segment {
    /// b, from 0.
    pub index: usize,
    /// S, ADC samples of every segment (the last may record fewer).
    pub length: usize,
    /// L, at most S.
    pub overlap: usize,
}

impl Segment {
    /// The recording's ADC sample number of the segment's first.
    pub fn first(&self) -> usize {
        self.index * self.length
    }
}

/// The words of a channel's random stream a block may use (2^36): its n-point synthesis
/// draws about 4n words.
const BLOCK_WORDS: u32 = 36;

/// Most blocks a recording holds: a block's 36 bits of words, 21 of block number, 10 of
/// channel and one of half fill the stream's 2^68 words.
pub const MAX_SEGMENTS: usize = 1 << 21;

/// Channel `channel`'s random numbers for its block `block`: the recording's stream, from a
/// word of its upper half ([`MAX_SEGMENTS`] blocks; 2^10 channels, where a scene has at most
/// 4 × 64 sensors' and 4 corners').
fn block_stream(mut rng: ChaCha8Rng, channel: usize, block: usize) -> ChaCha8Rng {
    debug_assert!(block < MAX_SEGMENTS && channel < 1 << 10, "block {block}, channel {channel}");
    let word = (1u128 << 67) | ((channel as u128) << (BLOCK_WORDS + 21)) | ((block as u128) << BLOCK_WORDS);
    rng.set_word_pos(word);
    rng
}

/// Channel `channel`'s tone phases, 2π·u each: from the recording's stream at its own word
/// in the lower half (a few words per tone).
fn tone_phases(mut rng: ChaCha8Rng, channel: usize, tones: usize) -> Vec<f64> {
    rng.set_word_pos((channel as u128) << 20);
    (0..tones).map(|_| 2.0 * std::f64::consts::PI * crate::ensemble::open_uniform(&mut rng)).collect()
}

impl Chain {
    /// The slowest decay rate of the chain's filters, 1/s (module docs).
    pub fn slowest_decay(&self) -> f64 {
        self.cascade.slowest_decay()
    }

    /// Segment `segment` of channel `channel` of recording number `recording` (its random
    /// numbers [`Chain::stream`]`(recording)`): `y` the model's samples of `measurand` from the segment's
    /// warm-up start, `warm_up` of them (a whole number of the chain's decimation) before
    /// its first; the background scaled by `noise_scale`. None if the chain does not record
    /// `measurand`.
    pub fn measure_segment(
        &self,
        (measurand, channel): (Measurand, usize),
        (y, warm_up): (&[f64], usize),
        segment: Segment,
        noise_scale: f64,
        recording: usize,
    ) -> Option<Measured> {
        let rec = self.recording(measurand)?;
        let rng = self.stream(recording);
        let mut x = y.to_vec();
        self.cascade.run(&mut x);
        let mut samples: Vec<f64> = x[warm_up.min(x.len())..].iter().step_by(self.decimation).copied().collect();
        let clean_peak = samples.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let rate = self.spec.rate_hz;
        if let Some(psd) = &rec.background {
            let synth = Synthesizer::new(psd, segment.length + segment.overlap, rate);
            let block = |b: usize| synth.draw(&mut block_stream(rng.clone(), channel, b));
            let here = block(segment.index);
            let before = (segment.index > 0 && segment.overlap > 0).then(|| block(segment.index - 1));
            for (j, s) in samples.iter_mut().enumerate() {
                let n = match &before {
                    Some(prev) if j < segment.overlap => {
                        let theta = FRAC_PI_2 * (j as f64 + 0.5) / segment.overlap as f64;
                        theta.cos() * prev[segment.length + j] + theta.sin() * here[j]
                    }
                    _ => here[j],
                };
                *s += noise_scale * n;
            }
        }
        let tones: Vec<Tone> = rec.tones.iter().map(|t| Tone { rms: noise_scale * t.rms, ..*t }).collect();
        let phases = tone_phases(rng.clone(), channel, tones.len());
        noise::add_tones_at(&mut samples, &tones, rate, &phases, segment.first());
        let clipped = quantise(&mut samples, rec.range, rec.bits);
        Some(Measured { samples, clean_peak, clipped })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measurement::noise::{welch, Psd};
    use crate::measurement::{AntiAlias, ChainSpec, Recording, SensorBand};

    fn chain(background: Psd, tones: Vec<Tone>) -> Chain {
        let spec = ChainSpec {
            sensor: SensorBand { resonance: Some((12_000.0, 0.05)), high_pass_hz: Some(1.0) },
            anti_alias: Some(AntiAlias { order: 8, corner_hz: 4_000.0 }),
            rate_hz: 10_000.0,
            recordings: vec![Recording {
                measurand: Measurand::Acceleration,
                range: 4.0,
                bits: 32,
                background: Some(background),
                tones,
            }],
            seed: 9,
            band_tolerance: 1e-3,
        };
        Chain::new(spec, 40_000.0).unwrap()
    }

    /// Segment `b` of a silent channel: its background and tones alone.
    fn quiet(chain: &Chain, b: usize, (length, overlap): (usize, usize), scale: f64) -> Vec<f64> {
        let segment = Segment { index: b, length, overlap };
        let y = vec![0.0; 4 * length];
        let m = chain.measure_segment((Measurand::Acceleration, 0), (&y, 0), segment, scale, 5);
        m.unwrap().samples
    }

    /// The background of a recording made in segments keeps its PSD across the joins: Welch's
    /// estimate over 32 segments of 4,096 samples joined by cross-fades of 1,024 (a quarter of
    /// the record cross-faded) lies within its confidence of the pink PSD in 90-99 % of the
    /// bins, as one synthesis does (`noise` tests); and its variance is the PSD's integral
    /// within 3 % (the pink part flat below 100 Hz holds a few thousand degrees of freedom in
    /// the 13 s record, so a variance's standard error of about 1 %).
    #[test]
    fn the_background_keeps_its_psd_across_the_joins() {
        let psd = Psd::pink(0.5, 100.0, 5_000.0);
        let chain = chain(psd.clone(), Vec::new());
        let x: Vec<f64> = (0..32).flat_map(|b| quiet(&chain, b, (4096, 1024), 1.0)).collect();
        let var = x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64;
        assert!((var / 0.25 - 1.0).abs() < 0.03, "variance {var} against 0.25");
        let (f, p, k) = welch(&x, 10_000.0, 512);
        let sd = (2.0 / (2.0 * k as f64 / (1.0 + 2.0 / 36.0))).sqrt();
        let (mut inside, mut total) = (0, 0);
        for i in 4..p.len() - 1 {
            let z = (p[i] / psd.density(f[i]) - 1.0) / sd;
            assert!(z.abs() < 5.0, "{} Hz: {z} sd", f[i]);
            inside += usize::from(z.abs() < 1.96);
            total += 1;
        }
        let share = inside as f64 / total as f64;
        assert!((0.90..=0.99).contains(&share), "{share} of the bins within 1.96 sd");
    }

    /// The background runs on through the joins: for a slowly varying background (white
    /// below 20 Hz at 10 kHz), the mean square step between neighbouring samples anywhere
    /// outside a fade is 2σ²(1 - ρ₁); a step that turns the fade's angle by Δθ multiplies
    /// the lag-1 correlation by cos Δθ (module docs), which adds about σ²Δθ² to it. The
    /// steps into a fade (where segments join) and out of it each turn it by half a step of
    /// the fade, Δθ = π/4L. There, over 400 joins, the step is that prediction within a
    /// factor 1.5; a join that jumped to an independent block would step by 2σ², some 10⁴
    /// times more.
    #[test]
    fn the_background_runs_on_through_the_joins() {
        let slow = Psd::Table { points: vec![(0.0, 1.0), (20.0, 1.0), (20.5, 0.0)] };
        let chain = chain(slow, Vec::new());
        let (length, overlap) = (512, 128);
        let x: Vec<f64> = (0..400).flat_map(|b| quiet(&chain, b, (length, overlap), 1.0)).collect();
        let var = x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64;
        let step = |k: usize| (x[k] - x[k - 1]).powi(2);
        let mean = |at: &dyn Fn(usize) -> usize| (1..400).map(|b| step(at(b))).sum::<f64>() / 399.0;
        let elsewhere = mean(&|b| b * length + length / 2);
        let faded = elsewhere + var * (std::f64::consts::PI / (4.0 * overlap as f64)).powi(2);
        let joins = mean(&|b| b * length);
        let fades_end = mean(&|b| b * length + overlap);
        for (at, v) in [("joins", joins), ("ends of the fades", fades_end)] {
            assert!(v / faded < 1.5 && faded / v < 1.5, "{at}: {v:e} against {faded:e} ({elsewhere:e} outside)");
        }
    }

    /// The tones run on through the joins: segments put together are one sine of each
    /// line (to rounding), with the phase of the recording.
    #[test]
    fn the_tones_run_on_through_the_joins() {
        let tone = Tone { frequency_hz: 24.7, rms: 0.5 };
        let chain = chain(Psd::White { level: 0.0 }, vec![tone]);
        let x: Vec<f64> = (0..3).flat_map(|b| quiet(&chain, b, (1000, 100), 1.0)).collect();
        let phase = tone_phases(chain.stream(5), 0, 1)[0];
        for (k, v) in x.iter().enumerate() {
            let exact = 2f64.sqrt() * 0.5 * (2.0 * std::f64::consts::PI * 24.7 * k as f64 / 10_000.0 + phase).sin();
            // The ADC's step is 2 × 4/2^32.
            assert!((v - exact).abs() <= 1e-9, "{k}: {v} against {exact}");
        }
    }

    /// A segment's filters, started from rest at its warm-up's start, give the whole
    /// recording's filtered samples within what the filters' slowest decay leaves of their
    /// past: a signal whose history before the warm-up is left out differs by at most
    /// e^{-r_f W} times its largest value (a 1 Hz high-pass: r_f = 2π).
    #[test]
    fn the_filters_warm_up_by_their_slowest_decay() {
        let chain = chain(Psd::White { level: 0.0 }, Vec::new());
        assert!((chain.slowest_decay() / (2.0 * std::f64::consts::PI) - 1.0).abs() < 1e-12);
        let y: Vec<f64> = (0..200_000).map(|k| (k as f64 * 0.003).sin() * (k as f64 * 1e-5).cos() + 0.3).collect();
        let whole = chain.measure(Measurand::Acceleration, &y, 0.0, &mut chain.stream(0)).unwrap().samples;
        let (start, from, length) = (40_000, 120_000, 20_000);
        let segment = Segment { index: from / length, length: length / 4, overlap: 0 };
        let seg = chain.measure_segment(
            (Measurand::Acceleration, 0),
            (&y[start..from + length], from - start),
            segment,
            0.0,
            0,
        );
        // The signal's largest value is 1.3; the ADC's step 2e-9.
        let bound = (-chain.slowest_decay() * (from - start) as f64 / 40_000.0).exp() * 1.3 + 2e-9;
        let diff = seg.unwrap().samples.iter().zip(&whole[from / 4..]).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(diff <= bound && diff > 0.0, "{diff:e} against {bound:e}");
    }
}
