//! A window detector a user can take away: the logistic model fitted on a stream's windows
//! with everything needed to apply it to a new recording, saved as plain JSON.
//!
//! **What it holds.** The window length W and hop H, the sample rate the features assume,
//! the channels in order (name and unit), the features read on each channel (keys of
//! [`crate::features::FEATURES`]; every channel's features in that order, channel-major, as
//! [`window_features`] makes them), the model ([`Logistic`]: intercept, weights and each
//! column's standardisation), the alarm probability, and its provenance (the scene, its
//! hash, the support set, the measurement chain, the windows it was fitted on).
//!
//! **Applying it.** [`Detector::score`] cuts a recording into the same windows (from its
//! first sample, every H, each wholly inside it), computes the same features and returns
//! P(gangue-rich) per window. The recording must have the detector's channels and rate: a
//! feature such as the dominant frequency depends on both, and a model fitted at one rate
//! says nothing at another.
//!
//! **The file.** [`Detector::to_json`] writes it with every number in the shortest form that
//! reads back to the same bits, and [`Detector::from_json`] reads it (refusing another
//! format's file, an unknown feature, or a model whose columns do not match): the same
//! file gives the same scores bit for bit in Rust and in Python, which calls this code.

use crate::classify::{FitError, Logistic, RIDGE};
use crate::detect::{windows, Window};
use crate::features::{Extractor, FEATURES};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// The file format this code writes and reads.
pub const FORMAT: &str = "impact-detector/1";

/// Most samples in a window (a window's features hold its spectrum: 10⁷ samples is 80 MB).
pub const MAX_WINDOW_SAMPLES: usize = 10_000_000;

/// A recorded channel as the detector reads it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChannelSpec {
    /// Its name, e.g. "sensor 1 acceleration".
    pub name: String,
    /// The unit of its samples, e.g. "m/s²".
    pub unit: String,
}

/// Where a detector comes from: the fields every file `impact` writes opens with (program,
/// version, scene, its hash, units), then the support set, the chain and the windows.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Provenance {
    /// The program that fitted it, "impact".
    pub program: String,
    /// Its version.
    pub version: String,
    /// The scene it was trained on.
    pub scene: String,
    /// The scene's provenance hash (SHA-256 of its canonical form), where the file was written
    /// by the command line (null from a library call).
    pub scene_sha256: Option<String>,
    /// The unit system, "SI".
    pub units: String,
    /// The support set.
    pub support_set: String,
    /// The measurement chain the recordings went through, as the scene states it (null: the
    /// model's signals as they are).
    pub chain: Option<serde_json::Value>,
    /// Windows it was fitted on, and how many of them were gangue-rich.
    pub windows: usize,
    /// See `windows`.
    pub gangue_rich: usize,
}

/// A trained window detector (module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Detector {
    /// Where it comes from.
    pub provenance: Provenance,
    /// [`FORMAT`].
    pub format: String,
    /// Window length W, s.
    pub window_s: f64,
    /// Hop H between window starts, s.
    pub hop_s: f64,
    /// The sample rate the features assume, Hz.
    pub rate_hz: f64,
    /// The channels, in the order of the model's columns.
    pub channels: Vec<ChannelSpec>,
    /// The features read on every channel, by key.
    pub features: Vec<String>,
    /// The probability at which a window raises an alarm.
    pub alarm_probability: f64,
    /// The model: one column per channel and feature, channel-major.
    pub model: Logistic,
}

/// One window of a recording and its score.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WindowScore {
    /// Start, s from the recording's first sample.
    pub start_s: f64,
    /// End, s.
    pub end_s: f64,
    /// P(gangue-rich); None where a channel the model reads as a logarithm (peak, RMS,
    /// energy) is silent in the window (every sample zero: nothing struck, or a dead
    /// sensor), where the model says nothing.
    pub probability: Option<f64>,
    /// Whether it reaches the alarm probability.
    pub alarm: bool,
}

/// Why a detector cannot be made, read or applied.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DetectorError {
    /// The file is not a detector of this format, or is inconsistent.
    #[error("detector file: {0}")]
    File(String),
    /// The recording does not match the detector.
    #[error("recording: {0}")]
    Recording(String),
    /// The model could not be fitted.
    #[error(transparent)]
    Fit(#[from] FitError),
}

/// Every channel's [`FEATURES`] over each of `wins` of `channels` sampled at `rate_hz`,
/// channel-major: window w covers samples round(start·f_s) onwards, round(W·f_s) of them
/// (`window_s` = W), times on the channels' own axis less `offset` of the window's stream.
pub fn window_features(
    channels: &[&[f64]],
    rate_hz: f64,
    wins: &[Window],
    window_s: f64,
    offset: impl Fn(&Window) -> f64 + Sync,
) -> Vec<Vec<f64>> {
    let n = (window_s * rate_hz).round() as usize;
    let extractor = Extractor::new(n, rate_hz);
    wins.par_iter()
        .map(|w| {
            let i0 = ((w.start - offset(w)) * rate_hz).round() as usize;
            let mut row = Vec::with_capacity(channels.len() * FEATURES.len());
            for channel in channels {
                let end = (i0 + n).min(channel.len());
                extractor.push_features(FEATURES, &channel[i0.min(end)..end], &mut row);
            }
            row
        })
        .collect()
}

/// Whether each column of `channels` channels' [`FEATURES`] is a scale feature.
pub fn scale_flags(channels: usize) -> Vec<bool> {
    (0..channels).flat_map(|_| FEATURES.iter().map(|f| f.is_scale())).collect()
}

impl Detector {
    /// Fits the detector on `rows` ([`window_features`] of `channels`) labelled `labels`
    /// (true: gangue-rich), with the ridge [`RIDGE`] as the cross-validated detectors.
    pub fn fit(
        rows: &[Vec<f64>],
        labels: &[bool],
        (window_s, hop_s, rate_hz): (f64, f64, f64),
        channels: Vec<ChannelSpec>,
        alarm_probability: f64,
        provenance: Provenance,
    ) -> Result<Self, DetectorError> {
        let model = Logistic::fit(rows, labels, &scale_flags(channels.len()), RIDGE)?;
        let provenance =
            Provenance { windows: labels.len(), gangue_rich: labels.iter().filter(|&&g| g).count(), ..provenance };
        let d = Self {
            format: FORMAT.into(),
            window_s,
            hop_s,
            rate_hz,
            channels,
            features: FEATURES.iter().map(|f| f.key().to_string()).collect(),
            alarm_probability,
            model,
            provenance,
        };
        d.check().map_err(DetectorError::File)?;
        Ok(d)
    }

    /// The detector as JSON text (module docs).
    pub fn to_json(&self) -> String {
        // Serialising plain numbers and strings cannot fail.
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Reads a detector from JSON text, checked (module docs).
    pub fn from_json(text: &str) -> Result<Self, DetectorError> {
        let format = serde_json::from_str::<serde_json::Value>(text)
            .map_err(|e| DetectorError::File(format!("not JSON: {e}")))?
            .get("format")
            .and_then(|f| f.as_str().map(str::to_string));
        if format.as_deref() != Some(FORMAT) {
            return Err(DetectorError::File(format!(
                "format is {}, this program reads \"{FORMAT}\"",
                format.map_or("missing".into(), |f| format!("\"{f}\""))
            )));
        }
        let d: Self = serde_json::from_str(text).map_err(|e| DetectorError::File(e.to_string()))?;
        d.check().map_err(DetectorError::File)?;
        Ok(d)
    }

    /// Whether the file's parts agree: known features in [`FEATURES`]' order, one column per
    /// channel and feature, a positive finite rate, a window of 2 to [`MAX_WINDOW_SAMPLES`]
    /// samples and a hop of at least one, a probability in (0, 1), finite coefficients and no
    /// negative spread.
    fn check(&self) -> Result<(), String> {
        let known: Vec<&str> = FEATURES.iter().map(|f| f.key()).collect();
        if self.features != known {
            return Err(format!("features are {:?}; this program computes {known:?}", self.features));
        }
        let columns = self.channels.len() * known.len();
        if self.channels.is_empty() || self.model.weights.len() != columns || self.model.columns.len() != columns {
            return Err(format!(
                "{} channels × {} features need {columns} model columns; the model has {} weights and {} columns",
                self.channels.len(),
                known.len(),
                self.model.weights.len(),
                self.model.columns.len()
            ));
        }
        let positive = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(format!("{name} = {v}, allowed (0, ∞)"))
            }
        };
        positive("rate_hz", self.rate_hz)?;
        positive("window_s", self.window_s)?;
        positive("hop_s", self.hop_s)?;
        let n = (self.window_s * self.rate_hz).round();
        if !(2.0..=MAX_WINDOW_SAMPLES as f64).contains(&n) {
            return Err(format!(
                "window_s = {} is {n} samples at {} Hz, allowed 2 to {MAX_WINDOW_SAMPLES}",
                self.window_s, self.rate_hz
            ));
        }
        if self.hop_s * self.rate_hz < 1.0 {
            return Err(format!("hop_s = {} is less than one sample at {} Hz", self.hop_s, self.rate_hz));
        }
        if !(self.alarm_probability > 0.0 && self.alarm_probability < 1.0) {
            return Err(format!("alarm_probability = {}, allowed (0, 1)", self.alarm_probability));
        }
        let numbers = std::iter::once(self.model.intercept)
            .chain(self.model.weights.iter().copied())
            .chain(self.model.columns.iter().flat_map(|c| [c.mean, c.sd]));
        if numbers.into_iter().any(|v| !v.is_finite()) {
            return Err("the model holds a number that is not finite".into());
        }
        if let Some(j) = self.model.columns.iter().position(|c| c.sd < 0.0) {
            return Err(format!("model column {j} has sd = {}, allowed [0, ∞)", self.model.columns[j].sd));
        }
        Ok(())
    }

    /// P(gangue-rich) of every window of the recording `channels` (the detector's channels in
    /// order, each sampled at `rate_hz` from the same instant): windows of W every H from
    /// the first sample, each wholly inside the recording.
    pub fn score(&self, channels: &[&[f64]], rate_hz: f64) -> Result<Vec<WindowScore>, DetectorError> {
        let bad = |m: String| Err(DetectorError::Recording(m));
        if channels.len() != self.channels.len() {
            let names: Vec<&str> = self.channels.iter().map(|c| c.name.as_str()).collect();
            return bad(format!("{} channels given; the detector reads {} ({names:?})", channels.len(), names.len()));
        }
        if !(rate_hz.is_finite() && (rate_hz / self.rate_hz - 1.0).abs() <= 1e-9) {
            return bad(format!("rate_hz = {rate_hz}; the detector's features assume {} Hz", self.rate_hz));
        }
        let len = channels.first().map_or(0, |c| c.len());
        if let Some(c) = channels.iter().position(|c| c.len() != len) {
            return bad(format!("channel {c} has {} samples, channel 0 has {len}", channels[c].len()));
        }
        let n = (self.window_s * self.rate_hz).round() as usize;
        if len < n {
            return bad(format!(
                "{len} samples, fewer than one window of {n} ({} s at {} Hz)",
                self.window_s, self.rate_hz
            ));
        }
        for (c, ch) in channels.iter().enumerate() {
            if let Some(i) = ch.iter().position(|v| !v.is_finite()) {
                return bad(format!("channel {c} ({}) sample {i} is {}", self.channels[c].name, ch[i]));
            }
        }
        let duration = len as f64 / self.rate_hz;
        let wins = windows(0, 0.0, duration, self.window_s, self.hop_s);
        let rows = window_features(channels, self.rate_hz, &wins, self.window_s, |_| 0.0);
        Ok(wins
            .iter()
            .zip(&rows)
            .map(|(w, row)| {
                let probability = self.speaks(row).then(|| self.model.probability(row)).filter(|p| p.is_finite());
                let alarm = probability.is_some_and(|p| p >= self.alarm_probability);
                WindowScore { start_s: w.start, end_s: w.end, probability, alarm }
            })
            .collect())
    }

    /// Whether every column the model reads as a logarithm is positive in `row` (a silent
    /// channel's features are all zero).
    fn speaks(&self, row: &[f64]) -> bool {
        self.model.columns.iter().zip(row).all(|(c, &x)| !(c.log && c.sd > 0.0) || x > 0.0)
    }
}

/// What a detector said of one recording with a known onset of the change.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Assessment {
    /// When the stream turned gangue-rich, s from the first sample.
    pub onset_s: f64,
    /// Scored windows wholly before the onset, and wholly after it (a window across it is
    /// neither).
    pub windows_before: usize,
    /// See `windows_before`.
    pub windows_after: usize,
    /// The AUC of the windows after the onset against those before (None without both).
    /// It has no interval here: overlapping windows of one recording are not independent,
    /// and one recording has no blocks to resample.
    pub auc: Option<f64>,
    /// From the onset to the end of the first alarmed window ending after it, s.
    pub delay_s: Option<f64>,
    /// Alarm episodes starting in windows that end before the onset.
    pub false_alarms: usize,
    /// Per hour of windows before the onset.
    pub false_alarms_per_hour: Option<f64>,
}

/// The operating answer ([`crate::detect::operate`]) and the before/after AUC of `scores`
/// (one recording's, from [`Detector::score`]) at its `threshold`, the change at `onset_s`.
pub fn assess(scores: &[WindowScore], threshold: f64, onset_s: f64) -> Assessment {
    let wins: Vec<Window> = scores.iter().map(|s| Window { stream: 0, start: s.start_s, end: s.end_s }).collect();
    let p: Vec<Option<f64>> = scores.iter().map(|s| s.probability).collect();
    let op = crate::detect::operate(&wins, &p, threshold, onset_s, &[0.0]);
    let before: Vec<f64> = scores.iter().filter(|s| s.end_s <= onset_s).filter_map(|s| s.probability).collect();
    let after: Vec<f64> = scores.iter().filter(|s| s.start_s >= onset_s).filter_map(|s| s.probability).collect();
    Assessment {
        onset_s,
        windows_before: before.len(),
        windows_after: after.len(),
        auc: (!before.is_empty() && !after.is_empty()).then(|| crate::roc::auc(&before, &after)),
        delay_s: op.delays.first().copied().flatten(),
        false_alarms: op.false_alarms,
        false_alarms_per_hour: op.false_alarms_per_hour(),
    }
}
