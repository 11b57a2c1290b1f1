//! A recorded support signal as `impact` reads it: a JSON sidecar of metadata beside a CSV
//! or Parquet file of samples, the forms `impact stream` writes its signals in and pandas
//! reads as they are.
//!
//! **Why CSV, Parquet and JSON.** Every acquisition system exports CSV, pandas and xarray
//! read it without conversion, and numbers written in their shortest round-trip form read
//! back to the same bits. Parquet ([`parquet`]) holds long signals at 8 bytes a sample and
//! reads at the speed of a copy, also to the same bits. WAV holds no units, positions or
//! labels. The sidecar's `data` names the file; a name ending in `.parquet` is read as
//! Parquet, any other as CSV.
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
//! **Drops** (optional): a drop-test recording names the support set it was made on
//! (`"condition"`, a condition of the scene it is compared with) and lists its drops, each
//! with the instant its lump touched the plate and what was dropped where:
//! ```json
//! "condition": "Con 1",
//! "drops": [ { "touch_s": 0.105, "point_mm": [229.2, 180.0], "radius_mm": 25.0,
//!              "density_kg_m3": 2400.0, "youngs_modulus_gpa": 16.0, "poisson_ratio": 0.28,
//!              "cohesion_mpa": 37.68, "friction_angle_deg": 37.0, "fall_height_m": 0.45,
//!              "class": "gangue", "force_max_kn": 12.3, "contact_time_ms": 0.61 } ]
//! ```
//! The speed is `fall_height_m` (free fall from rest) or `velocity_m_per_s`, exactly one;
//! `class`, and the impact force's peak and duration where an instrumented lump or a load
//! cell measured them (`force_max_kn`, `contact_time_ms`, each with its standard deviation
//! `force_max_sd_kn`, `contact_time_sd_ms` where known), are optional. The scene crate
//! checks every value against its range; this module reads them as written.
//!
//! **The CSV**: lines starting with `#` are comments, the first other line is the header
//! (column keys), and every later line holds one sample of every column.

pub mod parquet;

use serde::Deserialize;

/// The sidecar format this code reads and `impact stream` writes.
pub const FORMAT: &str = "impact-signal/1";

/// The sidecar's keys this code reads (module docs).
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Sidecar {
    /// [`FORMAT`].
    pub format: String,
    /// The data file (CSV, or Parquet where its name ends in `.parquet`), relative to the
    /// sidecar's folder.
    pub data: String,
    /// Samples per second, Hz.
    pub rate_hz: f64,
    /// The data file's columns to read, in order.
    pub columns: Vec<String>,
    /// Their names in words.
    #[serde(default)]
    pub channels: Vec<String>,
    /// When the stream turned gangue-rich, s from the first sample.
    #[serde(default)]
    pub onset_s: Option<f64>,
    /// The support set a drop test was recorded on: a condition of the scene.
    #[serde(default)]
    pub condition: Option<String>,
    /// The drops, in the sidecar's order (module docs).
    #[serde(skip)]
    pub drops: Vec<DropRecord>,
}

/// One drop as the sidecar states it, in the units its keys name (module docs).
#[derive(Debug, Clone, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct DropRecord {
    /// When the lump touched the plate, s from the first sample.
    pub touch_s: f64,
    /// Impact point (x, z), mm.
    pub point_mm: [f64; 2],
    /// Lump radius, mm.
    pub radius_mm: f64,
    /// Lump density, kg/m³.
    pub density_kg_m3: f64,
    /// Lump Young's modulus, GPa.
    pub youngs_modulus_gpa: f64,
    /// Lump Poisson ratio.
    pub poisson_ratio: f64,
    /// Lump cohesion, MPa.
    pub cohesion_mpa: f64,
    /// Lump friction angle, degrees.
    pub friction_angle_deg: f64,
    /// Fall height from rest, m.
    #[serde(default)]
    pub fall_height_m: Option<f64>,
    /// Impact velocity, m/s.
    #[serde(default)]
    pub velocity_m_per_s: Option<f64>,
    /// "coal" or "gangue".
    #[serde(default)]
    pub class: Option<String>,
    /// Measured peak impact force, kN.
    #[serde(default)]
    pub force_max_kn: Option<f64>,
    /// Measured duration of the first contact, ms.
    #[serde(default)]
    pub contact_time_ms: Option<f64>,
    /// Standard deviation of the measured peak force, kN.
    #[serde(default)]
    pub force_max_sd_kn: Option<f64>,
    /// Standard deviation of the measured contact time, ms.
    #[serde(default)]
    pub contact_time_sd_ms: Option<f64>,
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
    /// The support set a drop test was recorded on.
    pub condition: Option<String>,
    /// The drops it holds, as written.
    pub drops: Vec<DropRecord>,
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
        let mut s: Sidecar = serde_json::from_value(value.clone()).map_err(|e| error(origin, e.to_string()))?;
        s.drops = drops(&value, origin)?;
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

    /// Whether `data` names a Parquet file (its name ends in `.parquet`, in any case).
    pub fn is_parquet(&self) -> bool {
        self.data.to_ascii_lowercase().ends_with(".parquet")
    }

    /// The recording: the sidecar's columns of the data file's `bytes` (from the file
    /// `origin`), read as Parquet or CSV as [`Self::is_parquet`] says.
    pub fn read_data(&self, bytes: Vec<u8>, origin: &str) -> Result<Recording, RecordingError> {
        if self.is_parquet() {
            let (channels, _) = parquet::read(bytes, &self.columns, origin)?;
            return self.recording(channels, origin);
        }
        let text = String::from_utf8(bytes).map_err(|e| {
            error(origin, format!("not UTF-8 text at byte {}: a CSV is text", e.utf8_error().valid_up_to()))
        })?;
        self.read(&text, origin)
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
        self.recording(channels, origin)
    }

    /// The recording of the sidecar's `channels`, read from `origin`.
    fn recording(&self, channels: Vec<Vec<f64>>, origin: &str) -> Result<Recording, RecordingError> {
        if channels[0].is_empty() {
            return Err(error(origin, "no samples: the file holds the columns but no rows".into()));
        }
        let names = if self.channels.is_empty() { self.columns.clone() } else { self.channels.clone() };
        Ok(Recording {
            rate_hz: self.rate_hz,
            names,
            channels,
            onset_s: self.onset_s,
            condition: self.condition.clone(),
            drops: self.drops.clone(),
        })
    }
}

/// The sidecar's `drops`, each read on its own so that an error names the drop.
fn drops(value: &serde_json::Value, origin: &str) -> Result<Vec<DropRecord>, RecordingError> {
    match value.get("drops") {
        None | Some(serde_json::Value::Null) => Ok(Vec::new()),
        Some(serde_json::Value::Array(list)) => list
            .iter()
            .enumerate()
            .map(|(i, d)| serde_json::from_value(d.clone()).map_err(|e| error(origin, format!("drops[{i}]: {e}"))))
            .collect(),
        Some(_) => {
            Err(error(origin, "drops is not a list: give a list of drops, [ { \"touch_s\": ..., ... } ]".into()))
        }
    }
}
