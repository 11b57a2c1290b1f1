//! A scene dict's Python values as TOML values, bounded: nesting at most [`MAX_DEPTH`] deep
//! (lists, tuples, dicts and `tolist()` results alike), no container inside itself, every
//! numpy scalar taken as its Python number or refused with a `TypeError`. Without the bounds a
//! self-referential list, a list nested 100,000 deep or an object whose `tolist()` returns
//! itself recursed until the interpreter's stack overflowed (SIGSEGV).

use crate::errors::{field_error, field_type_error};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// Deepest nesting of a scene dict. The deepest scene key,
/// `ensemble.families[i].radius_mm.values[j]`, is five levels down; 32 leaves room for any
/// layout to come and keeps this conversion, the TOML text made from it and its parser's
/// recursion far from the end of any stack.
pub const MAX_DEPTH: usize = 32;

/// The conversion's state: integers beyond a float, and the containers being converted.
#[derive(Default)]
pub struct Dict<'py> {
    /// Integers (and long doubles) beyond a float's range, written into the TOML as ±inf so
    /// that the range check of their field names it: (path, the value in short form, the
    /// Python object).
    pub overflowed: Vec<(String, String, Py<PyAny>)>,
    /// The containers from the root to the value being converted: one met again is a cycle.
    open: Vec<Bound<'py, PyAny>>,
}

/// A scene dict's problem, naming the field as the user wrote it (`plate.length_mm`,
/// `bodies[1].radius_mm`).
pub fn dict_error(path: &str, message: String, allowed: Option<String>) -> PyErr {
    field_error("<dict>", path, message, allowed)
}

/// The path as the message shows it: the root has none.
fn shown(path: &str) -> &str {
    if path.is_empty() {
        "the scene"
    } else {
        path
    }
}

/// `n` (a Python int) in short scientific form: "1e400", "-1.2345e400".
fn short_int(n: &Bound<'_, PyAny>) -> String {
    let text = n.str().map_or_else(|_| "?".into(), |t| t.to_string());
    let (sign, digits) = text.strip_prefix('-').map_or(("", text.as_str()), |d| ("-", d));
    let tail = digits.get(1..6).unwrap_or("").trim_end_matches('0');
    let dot = if tail.is_empty() { String::new() } else { format!(".{tail}") };
    format!("{sign}{}{dot}e{}", &digits[..1.min(digits.len())], digits.len().saturating_sub(1))
}

fn type_name(v: &Bound<'_, PyAny>) -> String {
    v.get_type().fully_qualified_name().map_or_else(|_| "?".into(), |n| n.to_string())
}

/// A value of a type a scene cannot hold, as a `TypeError` (also a `SceneError`).
fn refused(path: &str, v: &Bound<'_, PyAny>, what: &str) -> PyErr {
    let p = shown(path);
    field_type_error(
        "<dict>",
        p,
        format!("{p} is {what} of type {}; a scene holds numbers, strings, booleans, lists and dicts", type_name(v)),
        "a number, string, boolean, list or dict",
    )
}

impl<'py> Dict<'py> {
    /// `v` as TOML; `path` names it in errors.
    pub fn convert(&mut self, v: &Bound<'py, PyAny>, path: &str) -> PyResult<toml::Value> {
        if v.is_none() {
            return Err(dict_error(path, format!("{path} is None; leave the key out to take its default"), None));
        }
        if v.is_instance_of::<PyBool>() {
            return Ok(toml::Value::Boolean(v.extract()?));
        }
        if v.is_instance_of::<PyInt>() {
            return Ok(self.int(v, path));
        }
        if v.is_instance_of::<PyFloat>() {
            return Ok(toml::Value::Float(v.extract()?));
        }
        if v.is_instance_of::<PyString>() {
            return Ok(toml::Value::String(v.extract()?));
        }
        self.enter(v, path)?;
        let out = self.container(v, path);
        self.open.pop();
        out
    }

    /// A Python int: beyond 64 bits as a float, so that the range check names it; beyond a
    /// float as ±inf, and the value as written goes back into the message.
    fn int(&mut self, v: &Bound<'py, PyAny>, path: &str) -> toml::Value {
        if let Ok(i) = v.extract::<i64>() {
            return toml::Value::Integer(i);
        }
        if let Ok(f) = v.extract::<f64>() {
            return toml::Value::Float(f);
        }
        let negative = v.lt(0).unwrap_or(false);
        self.overflowed.push((path.to_string(), short_int(v), v.clone().unbind()));
        toml::Value::Float(if negative { f64::NEG_INFINITY } else { f64::INFINITY })
    }

    /// Steps into `v`: refused if it is one of the containers it is inside, or too deep.
    fn enter(&mut self, v: &Bound<'py, PyAny>, path: &str) -> PyResult<()> {
        let p = shown(path);
        if self.open.iter().any(|o| o.is(v)) {
            return Err(dict_error(
                p,
                format!("{p} contains itself (a list, dict or tolist() result inside itself); a scene is a tree"),
                Some("a tree of lists and dicts, no cycles".into()),
            ));
        }
        if self.open.len() >= MAX_DEPTH {
            return Err(dict_error(
                p,
                format!("{p} is nested more than {MAX_DEPTH} lists or dicts deep; a scene nests at most five"),
                Some(format!("at most {MAX_DEPTH} levels of nesting")),
            ));
        }
        self.open.push(v.clone());
        Ok(())
    }

    /// Dicts, lists and tuples (their own items, never a subclass's `__iter__`, which could
    /// run for ever), numpy scalars and arrays, and numbers by `__index__` or `__float__`.
    fn container(&mut self, v: &Bound<'py, PyAny>, path: &str) -> PyResult<toml::Value> {
        if let Ok(d) = v.cast::<PyDict>() {
            let mut table = toml::Table::new();
            for (k, item) in d.iter() {
                let key: String = k.extract().map_err(|_| {
                    let key = k.repr().map_or_else(|_| "?".into(), |r| r.to_string());
                    let at = shown(path);
                    dict_error(at, format!("{at} has a key {key} that is not a str"), Some("str keys".into()))
                })?;
                let child = if path.is_empty() { key.clone() } else { format!("{path}.{key}") };
                let value = self.convert(&item, &child)?;
                table.insert(key, value);
            }
            return Ok(toml::Value::Table(table));
        }
        let items: Option<Vec<Bound<'py, PyAny>>> = match (v.cast::<PyList>(), v.cast::<PyTuple>()) {
            (Ok(l), _) => Some(l.iter().collect()),
            (_, Ok(t)) => Some(t.iter().collect()),
            _ => None,
        };
        if let Some(items) = items {
            let mut out = Vec::with_capacity(items.len());
            for (i, item) in items.iter().enumerate() {
                out.push(self.convert(item, &format!("{path}[{i}]"))?);
            }
            return Ok(toml::Value::Array(out));
        }
        if let Some(kind) = numpy_scalar_kind(v) {
            return self.numpy_scalar(v, &kind, path);
        }
        // numpy arrays (and any array-like): their Python lists, checked as everything else.
        if v.hasattr("tolist")? {
            return self.convert(&v.call_method0("tolist")?, path);
        }
        if let Ok(i) = v.call_method0("__index__") {
            return self.convert(&i, path);
        }
        if v.is_instance_of::<pyo3::types::PyComplex>() {
            return Err(refused(path, v, "a complex number"));
        }
        if let Ok(f) = v.call_method0("__float__") {
            return self.convert(&f, path);
        }
        Err(refused(path, v, "a value"))
    }

    /// A numpy scalar (or 0-d array) of dtype kind `kind`: booleans, integers and reals as
    /// their Python values (a long double through `float`, recorded if beyond a float's
    /// range); complex numbers, bytes, dates, times and objects refused.
    fn numpy_scalar(&mut self, v: &Bound<'py, PyAny>, kind: &str, path: &str) -> PyResult<toml::Value> {
        match kind {
            "b" => Ok(toml::Value::Boolean(v.is_truthy()?)),
            "i" | "u" => self.convert(&v.call_method0("__index__")?, path),
            "f" => {
                let f: f64 = v.call_method0("__float__")?.extract()?;
                let finite_before = v.call_method0("__abs__")?.lt(f64::INFINITY)?;
                if f.is_infinite() && finite_before {
                    let written = v.str().map_or_else(|_| "?".into(), |t| t.to_string());
                    self.overflowed.push((path.to_string(), written, v.clone().unbind()));
                }
                Ok(toml::Value::Float(f))
            }
            "U" => self.convert(&v.str()?.into_any(), path),
            "c" => Err(refused(path, v, "a complex number")),
            _ => Err(refused(path, v, "a numpy value")),
        }
    }
}

/// The dtype kind ("b", "i", "u", "f", "c", "U", "S", "M", "m", "O", "V") of a numpy scalar
/// or 0-d array, None for anything else.
fn numpy_scalar_kind(v: &Bound<'_, PyAny>) -> Option<String> {
    let ndim: usize = v.getattr("ndim").ok()?.extract().ok()?;
    if ndim != 0 {
        return None;
    }
    v.getattr("dtype").ok()?.getattr("kind").ok()?.extract().ok()
}
