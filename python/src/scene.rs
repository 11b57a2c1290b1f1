//! Scenes from Python: a TOML file, TOML text or a dict. A dict is written out as TOML text
//! and read by the same parser and validation as a scene file (the `scene` crate), so every
//! rule and every error message is the command line's.

use crate::dict::{dict_error, Dict};
use crate::errors::{overflow_error, scene_error};
use ::scene::{Scene as Validated, SceneError as Invalid, SceneSource, DEFAULT_ORIGIN, DEFAULT_SCENE};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// A validated scene (SI units inside): the plate, the bodies, the support sets, the impact
/// points, the velocities and the analyses. Build one with `Scene.from_toml(path)`,
/// `Scene.from_str(text)`, `Scene.from_dict(d)` or `Scene.default()`.
#[pyclass(frozen, module = "impact._impact", name = "Scene")]
pub struct Scene {
    /// The validated scene.
    pub scene: Validated,
    /// The TOML text it was read from (a dict's generated text), kept so that a scene can be
    /// pickled to another process (a Dask worker) and read there by the same validation.
    text: String,
    /// Where it came from, for messages.
    origin: String,
    /// The folder of the file it was read from (absolute), against which the files it names
    /// are read again when it is unpickled elsewhere; None for text and dicts.
    folder: Option<PathBuf>,
}

impl Scene {
    /// The TOML text the scene was read from.
    pub fn text(&self) -> &str {
        &self.text
    }

    fn parse(text: String, origin: String) -> PyResult<Self> {
        let scene = Validated::parse(&text, &origin).map_err(|e| scene_error(&e))?;
        Ok(Self { scene, text, origin, folder: None })
    }
}

/// TOML text of a scene dict, and where in it each key and value the user wrote lies: one
/// line per top-level key, tables and arrays inline, so that every key and value has its own
/// byte range to map a parser error's position back to the dict's path.
#[derive(Default)]
struct Emitted {
    text: String,
    /// (byte range, path, whether a value rather than a key) of every key and value written.
    spans: Vec<(std::ops::Range<usize>, String, bool)>,
}

impl Emitted {
    fn key(&mut self, key: &str, path: &str) {
        let bare = !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        let start = self.text.len();
        if bare {
            self.text.push_str(key);
        } else {
            self.text.push_str(&toml::Value::String(key.to_string()).to_string());
        }
        self.spans.push((start..self.text.len(), path.to_string(), false));
    }

    fn value(&mut self, v: &toml::Value, path: &str) {
        let start = self.text.len();
        match v {
            toml::Value::Table(t) => {
                self.text.push('{');
                for (i, (k, item)) in t.iter().enumerate() {
                    self.text.push_str(if i == 0 { " " } else { ", " });
                    let child = format!("{path}.{k}");
                    self.key(k, &child);
                    self.text.push_str(" = ");
                    self.value(item, &child);
                }
                self.text.push_str(if t.is_empty() { "}" } else { " }" });
            }
            toml::Value::Array(a) => {
                self.text.push('[');
                for (i, item) in a.iter().enumerate() {
                    if i > 0 {
                        self.text.push_str(", ");
                    }
                    self.value(item, &format!("{path}[{i}]"));
                }
                self.text.push(']');
            }
            scalar => self.text.push_str(&scalar.to_string()),
        }
        self.spans.push((start..self.text.len(), path.to_string(), true));
    }

    fn document(table: &toml::Table) -> Self {
        let mut e = Emitted::default();
        for (k, v) in table {
            e.key(k, k);
            e.text.push_str(" = ");
            e.value(v, k);
            e.text.push('\n');
        }
        e
    }

    /// The path of the smallest key or value (only values with `values_only`) holding `span`.
    fn path_at(&self, span: &std::ops::Range<usize>, values_only: bool) -> Option<&str> {
        self.spans
            .iter()
            .filter(|(r, _, is_value)| {
                (*is_value || !values_only) && r.start <= span.start && span.end <= r.end.max(r.start + 1)
            })
            .min_by_key(|(r, _, _)| r.len())
            .map(|(_, p, _)| p.as_str())
    }
}

/// A parser error on a dict's text as an error naming the dict's field: the key or value the
/// parser points at, or for a missing key the table that lacks it (a value; the top level,
/// which is no value, where none holds the position) and the key.
fn dict_syntax_error(e: &Emitted, reason: &str, span: Option<&std::ops::Range<usize>>) -> PyErr {
    let quoted = |prefix: &str| reason.strip_prefix(prefix).and_then(|r| r.split('`').next()).map(str::to_string);
    let missing = quoted("missing field `");
    let at = span.and_then(|s| e.path_at(s, missing.is_some())).unwrap_or("");
    let path = match missing {
        Some(name) if at.is_empty() => name,
        Some(name) => format!("{at}.{name}"),
        None if at.is_empty() => "the scene".to_string(),
        None => at.to_string(),
    };
    // serde names the expected Rust type; say it in the user's terms.
    let allowed = reason.split_once(", expected ").map(|(_, a)| match a {
        "f64" | "f32" => "a number".to_string(),
        "u8" | "u16" | "u32" | "u64" | "usize" | "i32" | "i64" => "a whole number".to_string(),
        other => other.to_string(),
    });
    dict_error(&path, format!("{path}: {reason}"), allowed)
}

#[pymethods]
impl Scene {
    /// Reads and validates a scene file (TOML, units in the key names; at most 1 MiB).
    #[staticmethod]
    fn from_toml(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let shown = path.display().to_string();
        // The file checks (regular file, size) are the command line's.
        let scene = py.detach(|| Validated::load(&path)).map_err(|e| scene_error(&e))?;
        let text = std::fs::read_to_string(&path).map_err(|e| PyValueError::new_err(format!("{shown}: {e}")))?;
        let folder = std::path::absolute(&path).ok().and_then(|p| p.parent().map(PathBuf::from));
        Ok(Self { scene, text, origin: shown, folder })
    }

    /// Parses and validates scene text; `origin` names it in error messages.
    #[staticmethod]
    #[pyo3(signature = (text, origin = "<string>".to_string()))]
    fn from_str(text: String, origin: String) -> PyResult<Self> {
        Self::parse(text, origin)
    }

    /// Validates a scene given as a dict with the layout and keys of a scene file.
    #[staticmethod]
    #[pyo3(signature = (d, origin = "<dict>".to_string()))]
    fn from_dict(d: &Bound<'_, PyDict>, origin: String) -> PyResult<Self> {
        let mut dict = Dict::default();
        let toml::Value::Table(table) = dict.convert(d.as_any(), "")? else {
            return Err(PyTypeError::new_err("scene dict: not a dict"));
        };
        let emitted = Emitted::document(&table);
        match Validated::parse(&emitted.text, &origin) {
            Ok(scene) => match dict.overflowed.first() {
                // Every float a scene holds is range-checked, so an overflowed integer cannot
                // pass; should one, it is refused here rather than kept as inf.
                Some((path, written, _)) => Err(dict_error(
                    path,
                    format!("{path} = {written} is beyond the range of a float"),
                    Some("a finite number".into()),
                )),
                None => Ok(Self { scene, text: emitted.text, origin, folder: None }),
            },
            Err(Invalid::Syntax { reason, span, .. }) => Err(dict_syntax_error(&emitted, &reason, span.as_ref())),
            Err(Invalid::OutOfRange { source, .. })
                if dict.overflowed.iter().any(|(path, _, _)| *path == source.name) =>
            {
                let (path, written, value) =
                    dict.overflowed.iter().find(|(path, _, _)| *path == source.name).expect("found above");
                let message = format!(
                    "scene {origin}: {path} = {written} is outside the allowed range {}{}",
                    source.allowed,
                    if source.unit.is_empty() { String::new() } else { format!(" {}", source.unit) }
                );
                Err(overflow_error(message, &source, &origin, value))
            }
            Err(e) => Err(scene_error(&e)),
        }
    }

    /// The embedded default scene: the paper's Table 1.
    #[staticmethod]
    fn default() -> PyResult<Self> {
        Self::parse(DEFAULT_SCENE.to_string(), DEFAULT_ORIGIN.to_string())
    }

    /// The TOML text the scene was read from (a dict's generated text).
    fn to_toml_str(&self) -> &str {
        &self.text
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> &str {
        &self.scene.name
    }

    /// Where the scene came from (file path, "<dict>", ...).
    #[getter]
    fn origin(&self) -> &str {
        &self.origin
    }

    /// The bodies' names, in scene order.
    #[getter]
    fn bodies(&self) -> Vec<String> {
        self.scene.bodies.iter().map(|b| b.name.clone()).collect()
    }

    /// The support sets' names, in scene order.
    #[getter]
    fn conditions(&self) -> Vec<String> {
        self.scene.conditions.iter().map(|c| c.name.clone()).collect()
    }

    /// The impact points as (x, z) pairs, m.
    #[getter]
    fn points_m(&self) -> Vec<(f64, f64)> {
        self.scene.point_pairs()
    }

    /// The velocities, m/s.
    #[getter]
    fn velocities_m_per_s(&self) -> Vec<f64> {
        self.scene.velocities.clone()
    }

    /// The analyses the scene asks for, by their scene-file names.
    #[getter]
    fn analyses(&self) -> Vec<&'static str> {
        self.scene.analyses.iter().map(|a| a.key()).collect()
    }

    /// The number of impacts of the `[ensemble]` table (0 without one).
    #[getter]
    fn ensemble_size(&self) -> usize {
        self.scene.ensemble.as_ref().map_or(0, |s| s.ensemble.len())
    }

    /// Plate length, width and thickness, m.
    #[getter]
    fn plate_m(&self) -> (f64, f64, f64) {
        let p = &self.scene.plate;
        (p.length(), p.width(), p.thickness())
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene({:?}: {} bodies, {} support sets, {} points, {} velocities, from {})",
            self.scene.name,
            self.scene.bodies.len(),
            self.scene.conditions.len(),
            self.scene.points.len(),
            self.scene.velocities.len(),
            self.origin
        )
    }

    /// Reads scene text from a file in `folder` (what unpickling a scene read from a file
    /// calls): the files it names are read relative to that folder.
    #[staticmethod]
    fn _from_str_in(text: String, origin: String, folder: PathBuf) -> PyResult<Self> {
        let scene = ::scene::parse_in_folder(&text, &origin, &folder).map_err(|e| scene_error(&e))?;
        Ok(Self { scene, text, origin, folder: Some(folder) })
    }

    /// Pickles as its TOML text, read again (and validated) on unpickling; a scene read from
    /// a file keeps its folder, so that the files it names (a measured PSD) are found again
    /// from any working folder.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        let s = slf.get();
        let py = slf.py();
        match &s.folder {
            Some(folder) => Ok((
                slf.get_type().getattr("_from_str_in")?,
                (s.text.clone(), s.origin.clone(), folder.clone()).into_pyobject(py)?,
            )),
            None => Ok((slf.get_type().getattr("from_str")?, (s.text.clone(), s.origin.clone()).into_pyobject(py)?)),
        }
    }
}
