//! A recorded support signal as `impact` reads it: a JSON sidecar of metadata beside a CSV
//! of samples, the form `impact stream` writes its signals in and pandas reads as it is.
//!
//! **Why CSV and JSON.** Every acquisition system exports CSV, pandas and xarray read it
//! without conversion, and numbers written in their shortest round-trip form read back to
//! the same bits. WAV holds no units, positions or labels, and a Parquet reader needs the
//! arrow crates, which this build does not have.
//!
//! **The sidecar** (`signal.json`):
//! ```json
//! { "format": "impact-signal/1", "data": "signal.csv", "rate_hz": 10000.0,
//!   "columns": ["sensor_1_acceleration_m_per_s2", "sensor_2_acceleration_m_per_s2"],
//!   "channels": ["sensor 1 acceleration (m/s²)", "sensor 2 acceleration (m/s²)"],
//!   "onset_s": 45.0 }
//! ```
//! `columns` names the CSV's columns to read, in the detector's channel order; `channels`
//! (optional) their names in words; `onset_s` (optional) when the stream turned
//! gangue-rich, s from the first sample, for the operating answer. Other keys (sensor
//! positions, units, the run's truth) are kept for the reader and not needed here.
//!
//! **The CSV**: lines starting with `#` are comments, the first other line is the header
//! (column keys), and every later line holds one sample of every column.

use serde::Deserialize;

/// The sidecar format this code reads and `impact stream` writes.
pub const FORMAT: &str = "impact-signal/1";

/// The sidecar's keys this code reads (module docs).
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Sidecar {
    /// [`FORMAT`].
    pub format: String,
    /// The CSV file, relative to the sidecar's folder.
    pub data: String,
    /// Samples per second, Hz.
    pub rate_hz: f64,
    /// The CSV columns to read, in order.
    pub columns: Vec<String>,
    /// Their names in words.
    #[serde(default)]
    pub channels: Vec<String>,
    /// When the stream turned gangue-rich, s from the first sample.
    #[serde(default)]
    pub onset_s: Option<f64>,
}

/// A recording: channels of samples at one rate.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    /// Samples per second, Hz.
    pub rate_hz: f64,
    /// The channels' names (the column keys where the sidecar gives none).
    pub names: Vec<String>,
    /// One vector of samples per channel.
    pub channels: Vec<Vec<f64>>,
    /// When the stream turned gangue-rich, s from the first sample.
    pub onset_s: Option<f64>,
}

/// A sidecar or CSV that cannot be read, with where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{origin}: {message}")]
pub struct RecordingError {
    /// The file.
    pub origin: String,
    /// What is wrong, naming the key or line.
    pub message: String,
}

fn error(origin: &str, message: String) -> RecordingError {
    RecordingError { origin: origin.to_string(), message }
}

impl Sidecar {
    /// Reads the sidecar's text (from the file `origin`), checked.
    pub fn parse(text: &str, origin: &str) -> Result<Self, RecordingError> {
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| error(origin, format!("not JSON: {e}")))?;
        match value.get("format").and_then(|f| f.as_str()) {
            Some(FORMAT) => {}
            other => {
                let found = other.map_or("missing".into(), |f| format!("\"{f}\""));
                return Err(error(origin, format!("format is {found}, this program reads \"{FORMAT}\"")));
            }
        }
        let s: Sidecar = serde_json::from_value(value).map_err(|e| error(origin, e.to_string()))?;
        if !(s.rate_hz.is_finite() && s.rate_hz > 0.0) {
            return Err(error(origin, format!("rate_hz = {}, allowed (0, ∞) Hz", s.rate_hz)));
        }
        if s.columns.is_empty() {
            return Err(error(origin, "columns is empty: name at least one CSV column to read".into()));
        }
        if !s.channels.is_empty() && s.channels.len() != s.columns.len() {
            return Err(error(
                origin,
                format!("channels names {} channels, columns {}", s.channels.len(), s.columns.len()),
            ));
        }
        if let Some(t) = s.onset_s.filter(|t| !(t.is_finite() && *t >= 0.0)) {
            return Err(error(origin, format!("onset_s = {t}, allowed [0, ∞) s")));
        }
        Ok(s)
    }

    /// The CSV's path: `data`, relative to the folder of the sidecar at `sidecar`.
    pub fn data_path(&self, sidecar: &std::path::Path) -> std::path::PathBuf {
        sidecar.parent().unwrap_or(std::path::Path::new(".")).join(&self.data)
    }

    /// The recording: the sidecar's columns of the CSV text `csv` (from the file `origin`).
    pub fn read(&self, csv_text: &str, origin: &str) -> Result<Recording, RecordingError> {
        let mut reader =
            csv::ReaderBuilder::new().comment(Some(b'#')).trim(csv::Trim::All).from_reader(csv_text.as_bytes());
        let header = reader.headers().map_err(|e| error(origin, format!("header: {e}")))?.clone();
        let index: Vec<usize> = self
            .columns
            .iter()
            .map(|c| {
                header.iter().position(|h| h == c).ok_or_else(|| {
                    error(origin, format!("no column \"{c}\"; the header has {:?}", header.iter().collect::<Vec<_>>()))
                })
            })
            .collect::<Result<_, _>>()?;
        let mut channels = vec![Vec::new(); index.len()];
        for (row, record) in reader.records().enumerate() {
            let line = match &record {
                Ok(r) => r.position().map_or(row + 2, |p| p.line() as usize),
                Err(e) => e.position().map_or(row + 2, |p| p.line() as usize),
            };
            let record = record.map_err(|e| error(origin, format!("line {line}: {e}")))?;
            for (k, (channel, &i)) in channels.iter_mut().zip(&index).enumerate() {
                let text = record.get(i).unwrap_or("");
                let v: f64 = text.parse().ok().filter(|v: &f64| v.is_finite()).ok_or_else(|| {
                    error(
                        origin,
                        format!("line {line}, column \"{}\": \"{text}\" is not a finite number", self.columns[k]),
                    )
                })?;
                channel.push(v);
            }
        }
        if channels[0].is_empty() {
            return Err(error(origin, "no samples after the header".into()));
        }
        let names = if self.channels.is_empty() { self.columns.clone() } else { self.channels.clone() };
        Ok(Recording { rate_hz: self.rate_hz, names, channels, onset_s: self.onset_s })
    }
}
