//! Scenes from Python: a TOML file, TOML text or a dict. A dict is written out as TOML text
//! and read by the same parser and validation as a scene file (`impact::scene`), so every
//! rule and every error message is the command line's.

use crate::errors::scene_error;
use impact::scene::{Scene as Validated, SceneSource, DEFAULT_ORIGIN, DEFAULT_SCENE};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
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
}

impl Scene {
    /// The TOML text the scene was read from.
    pub fn text(&self) -> &str {
        &self.text
    }

    fn parse(text: String, origin: String) -> PyResult<Self> {
        let scene = Validated::parse(&text, &origin).map_err(|e| scene_error(&e))?;
        Ok(Self { scene, text, origin })
    }
}

/// A Python value as TOML; `path` names it in errors.
fn to_toml(v: &Bound<'_, PyAny>, path: &str) -> PyResult<toml::Value> {
    if v.is_none() {
        return Err(PyValueError::new_err(format!(
            "scene dict: {path} is None; leave the key out to take its default"
        )));
    }
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return match v.extract::<i64>() {
            Ok(i) => Ok(toml::Value::Integer(i)),
            // Beyond 64 bits: as a float, so that the range check names it.
            Err(_) => Ok(toml::Value::Float(v.extract()?)),
        };
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(v.extract()?));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, item) in d.iter() {
            let key: String = k.extract().map_err(|_| {
                PyTypeError::new_err(format!(
                    "scene dict: {path} has a key {} that is not a str",
                    k.repr().map_or_else(|_| "?".into(), |r| r.to_string())
                ))
            })?;
            let child = if path.is_empty() { key.clone() } else { format!("{path}.{key}") };
            table.insert(key, to_toml(&item, &child)?);
        }
        return Ok(toml::Value::Table(table));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items: Vec<Bound<'_, PyAny>> = v.try_iter()?.collect::<PyResult<_>>()?;
        return items
            .iter()
            .enumerate()
            .map(|(i, item)| to_toml(item, &format!("{path}[{i}]")))
            .collect::<PyResult<Vec<_>>>()
            .map(toml::Value::Array);
    }
    // numpy scalars and arrays: their Python equivalents.
    if v.hasattr("tolist")? {
        return to_toml(&v.call_method0("tolist")?, path);
    }
    if let Ok(i) = v.call_method0("__index__") {
        return to_toml(&i, path);
    }
    if let Ok(f) = v.call_method0("__float__") {
        return to_toml(&f, path);
    }
    Err(PyTypeError::new_err(format!(
        "scene dict: {path} is a {}; a scene holds numbers, strings, booleans, lists and dicts",
        v.get_type().name().map_or_else(|_| "?".into(), |n| n.to_string())
    )))
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
        Ok(Self { scene, text, origin: shown })
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
        let toml::Value::Table(table) = to_toml(d.as_any(), "")? else {
            return Err(PyTypeError::new_err("scene dict: not a dict"));
        };
        let text = toml::to_string(&table)
            .map_err(|e| PyValueError::new_err(format!("scene dict: cannot be written as TOML: {e}")))?;
        Self::parse(text, origin)
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

    /// Pickles as its TOML text, read again (and validated) on unpickling.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String, String))> {
        let s = slf.get();
        Ok((slf.get_type().getattr("from_str")?, (s.text.clone(), s.origin.clone())))
    }
}
