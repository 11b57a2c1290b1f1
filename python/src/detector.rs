//! A trained window detector (`identify::detector`, what `impact stream` writes as
//! `detector.json` and `impact detect` applies) and a recording (`identify::recording`, a
//! `signal.json` sidecar beside its CSV), for the Python layer: the same code as the command
//! line, so the same file gives the same scores bit for bit.

use crate::columns::Table;
use crate::errors::{argument_message, model_error};
use identify::detector::{assess, Detector as Trained, WindowScore};
use identify::recording::{Recording, Sidecar};
use numpy::{AllowTypeChange, PyArray1, PyArrayLike1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::Path;

/// A trained window detector.
#[pyclass(frozen, module = "impact._impact", name = "Detector")]
pub struct Detector {
    pub(crate) detector: Trained,
}

/// The text of `path`, a missing file as Python's `FileNotFoundError`.
fn read(path: &Path, field: &str) -> PyResult<String> {
    std::fs::read_to_string(path).map_err(|e| io_error(field, path, e))
}

/// A file that cannot be read: FileNotFoundError where it is missing, else ValueError.
fn io_error(field: &str, path: &Path, e: std::io::Error) -> PyErr {
    match e.kind() {
        std::io::ErrorKind::NotFound => {
            pyo3::exceptions::PyFileNotFoundError::new_err(format!("{field}: {}: {e}", path.display()))
        }
        _ => argument_message(field, format!("{}: {e}", path.display())),
    }
}

/// Every window's score as columns.
fn score_columns(scores: &[WindowScore]) -> Table {
    let mut t = Table::new(scores.len(), &[]);
    for (row, s) in scores.iter().enumerate() {
        t.num("start_s", row, s.start_s);
        t.num("end_s", row, s.end_s);
        // NaN where the model says nothing (a silent channel), as for an unscored window.
        t.num("probability_gangue_rich", row, s.probability.unwrap_or(f64::NAN));
        t.flag("alarm", row, s.alarm);
    }
    t
}

#[pymethods]
impl Detector {
    /// Reads a detector from JSON text (format impact-detector/1).
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        Trained::from_json(text)
            .map(|detector| Self { detector })
            .map_err(|e| argument_message("detector", e.to_string()))
    }

    /// Reads a detector file.
    #[staticmethod]
    fn load(path: std::path::PathBuf) -> PyResult<Self> {
        Trained::from_json(&read(&path, "path")?)
            .map(|detector| Self { detector })
            .map_err(|e| argument_message("path", format!("{}: {e}", path.display())))
    }

    /// The detector as JSON text, as `impact stream` writes it.
    fn to_json(&self) -> String {
        self.detector.to_json()
    }

    /// The channels in the model's order: (name, unit).
    #[getter]
    fn channels(&self) -> Vec<(String, String)> {
        self.detector.channels.iter().map(|c| (c.name.clone(), c.unit.clone())).collect()
    }

    /// The features read on every channel, by key.
    #[getter]
    fn features(&self) -> Vec<String> {
        self.detector.features.clone()
    }

    /// (window length, hop), s.
    #[getter]
    fn window_s(&self) -> (f64, f64) {
        (self.detector.window_s, self.detector.hop_s)
    }

    /// The sample rate the features assume, Hz.
    #[getter]
    fn rate_hz(&self) -> f64 {
        self.detector.rate_hz
    }

    /// The probability at which a window raises an alarm.
    #[getter]
    fn alarm_probability(&self) -> f64 {
        self.detector.alarm_probability
    }

    /// Where it comes from, as JSON text.
    #[getter]
    fn provenance(&self) -> PyResult<String> {
        serde_json::to_string(&self.detector.provenance).map_err(model_error)
    }

    /// P(gangue-rich) of every window of `channels` (one array or sequence of numbers per
    /// channel, the detector's channels in order, each sampled at `rate_hz`), as columns.
    fn score<'py>(
        &self,
        py: Python<'py>,
        channels: Vec<PyArrayLike1<'py, f64, AllowTypeChange>>,
        rate_hz: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let owned: Vec<Vec<f64>> = channels.iter().map(|c| c.as_array().to_vec()).collect();
        let views: Vec<&[f64]> = owned.iter().map(Vec::as_slice).collect();
        let d = &self.detector;
        let scores = py.detach(|| d.score(&views, rate_hz)).map_err(|e| argument_message("channels", e.to_string()))?;
        score_columns(&scores).into_py(py)
    }

    /// Applies the detector to the recording whose sidecar is `signal` (its CSV beside it):
    /// the windows' scores as columns, and the operating answer as JSON text (null where the
    /// sidecar states no onset), as `impact detect` writes them.
    fn detect<'py>(&self, py: Python<'py>, signal: std::path::PathBuf) -> PyResult<Bound<'py, PyDict>> {
        let origin = signal.display().to_string();
        let recording = recording(&signal)?;
        let views: Vec<&[f64]> = recording.channels.iter().map(Vec::as_slice).collect();
        let d = &self.detector;
        let scores = py
            .detach(|| d.score(&views, recording.rate_hz))
            .map_err(|e| argument_message("signal", format!("{origin}: {e}")))?;
        let assessment = recording.onset_s.map(|t| assess(&scores, d.alarm_probability, t));
        let out = PyDict::new(py);
        out.set_item("scores", score_columns(&scores).into_py(py)?)?;
        out.set_item("assessment", serde_json::to_string(&assessment).map_err(model_error)?)?;
        out.set_item("names", recording.names.clone())?;
        out.set_item("rate_hz", recording.rate_hz)?;
        Ok(out)
    }
}

/// The recording whose sidecar is `signal`, its CSV read from the sidecar's folder.
pub(crate) fn recording(signal: &Path) -> PyResult<Recording> {
    let origin = signal.display().to_string();
    let sidecar =
        Sidecar::parse(&read(signal, "signal")?, &origin).map_err(|e| argument_message("signal", e.to_string()))?;
    let data = sidecar.data_path(signal);
    let bytes = std::fs::read(&data).map_err(|e| io_error("signal", &data, e))?;
    sidecar.read_data(bytes, &data.display().to_string()).map_err(|e| argument_message("signal", e.to_string()))
}

/// A recording: its sidecar read and its CSV columns as float64 arrays.
#[pyfunction]
pub fn read_signal<'py>(py: Python<'py>, signal: std::path::PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let r = recording(&signal)?;
    let out = PyDict::new(py);
    let channels: Vec<Bound<'py, PyArray1<f64>>> = r.channels.iter().map(|c| PyArray1::from_slice(py, c)).collect();
    out.set_item("channels", channels)?;
    out.set_item("names", r.names)?;
    out.set_item("rate_hz", r.rate_hz)?;
    out.set_item("onset_s", r.onset_s)?;
    Ok(out)
}
