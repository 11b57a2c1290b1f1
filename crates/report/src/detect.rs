//! `impact detect` rendered: a trained window detector ([`identify::detector`]) applied to a
//! recording ([`identify::recording`]): every window's probability as `scores.csv`, and
//! `detect.json` with the detector's provenance, the recording, the alarms and, where the
//! recording states its onset, the operating answer.

use crate::present::table::{sig, Cell, Table};
use crate::provenance::Provenance;
use crate::Failure;
use identify::detector::{assess, Assessment, Detector, WindowScore};
use identify::recording::Recording;
use output::Artifacts;
use serde::Serialize;

/// A detector's answer on one recording.
#[derive(Debug, Clone, Serialize)]
pub struct DetectData {
    /// The detector's scene, support set and chain, and its file.
    pub detector: identify::detector::Provenance,
    /// Where the detector was read from.
    pub detector_file: String,
    /// Where the recording was read from.
    pub recording_file: String,
    /// The recording's channels, in the detector's channel order, beside the detector's.
    pub channels: Vec<(String, String)>,
    /// Samples per channel and the rate, Hz.
    pub samples: usize,
    /// See `samples`.
    pub rate_hz: f64,
    /// Whether the recording's channel names are the detector's (a recording from another
    /// rig names its channels its own way: the order is what counts, and it is the user's).
    pub names_match: bool,
    /// Windows, and how many reached the alarm probability.
    pub windows: usize,
    /// Windows left unscored: a channel read as a logarithm silent in them.
    pub silent_windows: usize,
    /// See `windows`.
    pub alarms: usize,
    /// The alarm probability.
    pub alarm_probability: f64,
    /// The operating answer, where the recording states its onset.
    pub assessment: Option<Assessment>,
    /// Every window's score.
    #[serde(skip)]
    pub scores: Vec<WindowScore>,
}

/// Applies `detector` to `recording` (read from the files named) and returns its files.
pub fn detect(
    detector: &Detector,
    recording: &Recording,
    (detector_file, recording_file): (&str, &str),
) -> Result<(Artifacts, DetectData), Failure> {
    let channels: Vec<&[f64]> = recording.channels.iter().map(Vec::as_slice).collect();
    let scores = detector.score(&channels, recording.rate_hz).map_err(|e| format!("{recording_file}: {e}"))?;
    let data = DetectData {
        detector: detector.provenance.clone(),
        detector_file: detector_file.to_string(),
        recording_file: recording_file.to_string(),
        channels: detector.channels.iter().map(|c| c.name.clone()).zip(recording.names.iter().cloned()).collect(),
        samples: channels.first().map_or(0, |c| c.len()),
        rate_hz: recording.rate_hz,
        names_match: detector
            .channels
            .iter()
            .map(|c| format!("{} ({})", c.name, c.unit))
            .eq(recording.names.iter().cloned())
            || detector.channels.iter().map(|c| c.name.clone()).eq(recording.names.iter().cloned()),
        windows: scores.len(),
        silent_windows: scores.iter().filter(|s| s.probability.is_none()).count(),
        alarms: scores.iter().filter(|s| s.alarm).count(),
        alarm_probability: detector.alarm_probability,
        assessment: recording.onset_s.map(|t| assess(&scores, detector.alarm_probability, t)),
        scores,
    };
    let stamp = provenance(detector);
    let mut a = Artifacts::new();
    a.add(
        "scores.csv",
        String::from_utf8_lossy(&stamp.stamp_csv(scores_table(&data).to_csv().as_bytes())).into_owned(),
    );
    let json = serde_json::to_string_pretty(&data)?;
    a.add("detect.json", String::from_utf8_lossy(&stamp.stamp_json(json.as_bytes())).into_owned());
    Ok((a, data))
}

/// The files' provenance: the detector's scene and its hash.
fn provenance(d: &Detector) -> Provenance {
    Provenance {
        program: "impact",
        version: env!("CARGO_PKG_VERSION"),
        scene: d.provenance.scene.clone(),
        scene_sha256: d.provenance.scene_sha256.clone().unwrap_or_else(|| "unknown".into()),
        units: "SI",
    }
}

/// One row per window.
fn scores_table(d: &DetectData) -> Table {
    let mut t = Table::new("", &["start (s)", "end (s)", "probability gangue-rich", "alarm"]);
    for s in &d.scores {
        // A silent window's probability is left empty, as an unscored window's in windows.csv.
        let p = s.probability.map_or(Cell::Text(String::new()), Cell::Num);
        t.push(vec![Cell::Num(s.start_s), Cell::Num(s.end_s), p, s.alarm.into()]);
    }
    t
}

/// The terminal's summary.
pub fn summary_table(d: &DetectData) -> Table {
    let mut t = Table::new(
        format!(
            "the detector of {} ({}) on {}: {} windows ({} silent, unscored), {} alarms at probability {}{}",
            d.detector.scene,
            d.detector.support_set,
            d.recording_file,
            d.windows,
            d.silent_windows,
            d.alarms,
            sig(d.alarm_probability, 3),
            if d.names_match {
                ""
            } else {
                "; the recording's channel names are not the detector's (detect.json lists both): check their order"
            }
        ),
        &["onset", "windows before/after", "AUC after against before", "delay", "false alarms/h (count)"],
    );
    let Some(a) = &d.assessment else {
        t.push(vec!["not stated".into(), "".into(), "".into(), "".into(), "".into()]);
        return t;
    };
    t.push(vec![
        format!("{} s", sig(a.onset_s, 4)).into(),
        format!("{}/{}", a.windows_before, a.windows_after).into(),
        a.auc.map_or("".into(), |v| format!("{} (no interval: one recording)", sig(v, 3)).into()),
        a.delay_s.map_or("no alarm".into(), |v| format!("{} s", sig(v, 3)).into()),
        a.false_alarms_per_hour.map_or("".into(), |v| format!("{} ({})", sig(v, 3), a.false_alarms).into()),
    ]);
    t
}
