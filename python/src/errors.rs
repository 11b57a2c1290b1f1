//! The package's exceptions. `SceneError` (a `ValueError`) carries what the command line's
//! message says, as attributes a program can read: the scene field, the value as written,
//! the allowed range and its unit. A bad argument of a function (not of the scene) is a plain
//! `ValueError` with the same attributes; a scene file that does not exist a
//! `FileNotFoundError`. `ModelError` (a `RuntimeError`) is a model that could not
//! answer (a solver that did not converge, a request beyond the budgets).

use ::scene::SceneError as Invalid;
use analytic::params::InvalidParameter;
use pyo3::prelude::*;

pyo3::create_exception!(
    impact,
    SceneError,
    pyo3::exceptions::PyValueError,
    "An invalid scene or argument. Attributes: `field` (the scene field or argument, or None \
     for a file that cannot be read or parsed), `value` (the number refused, or None), \
     `allowed` (the allowed range as text, e.g. \"[1, 100000]\", or None), `low`/`high` (its \
     ends), `unit` (of value and range, \"\" when dimensionless) and `origin` (where the scene \
     came from)."
);
pyo3::create_exception!(
    impact,
    ModelError,
    pyo3::exceptions::PyRuntimeError,
    "A model that could not answer: a request beyond the memory or transient-run budget, or \
     a solver that did not converge. The message says which."
);

/// `SceneTypeError`: a scene dict's value of a type no scene holds (a complex number, a
/// numpy datetime, an arbitrary object). Both a `SceneError`, as every other problem of a
/// scene dict, and a `TypeError`, as Python reports a value of the wrong type; made once
/// with `type()` because an exception class of two bases cannot be declared here.
pub fn scene_type_error(py: Python<'_>) -> PyResult<Bound<'_, pyo3::types::PyType>> {
    static TYPE: pyo3::sync::PyOnceLock<Py<pyo3::types::PyType>> = pyo3::sync::PyOnceLock::new();
    TYPE.get_or_try_init(py, || {
        let bases = (py.get_type::<SceneError>(), py.get_type::<pyo3::exceptions::PyTypeError>());
        let namespace = pyo3::types::PyDict::new(py);
        namespace.set_item("__module__", "impact")?;
        namespace
            .set_item("__doc__", "A scene dict's value of a type no scene holds: a SceneError and a TypeError.")?;
        let made = py.get_type::<pyo3::types::PyType>().call1(("SceneTypeError", bases, namespace))?;
        Ok::<_, PyErr>(made.cast_into::<pyo3::types::PyType>()?.unbind())
    })
    .map(|t| t.bind(py).clone())
}

/// A scene dict's value at `field` of a type no scene holds, as a `SceneTypeError` with
/// `field` and `allowed` set.
pub fn field_type_error(origin: &str, field: &str, message: String, allowed: &str) -> PyErr {
    Python::attach(|py| {
        let err = match scene_type_error(py) {
            Ok(t) => PyErr::from_type(t, format!("scene {origin}: {message}")),
            Err(e) => return e,
        };
        let d = Details {
            origin: Some(origin.to_string()),
            field: Some(field.to_string()),
            allowed: Some(allowed.to_string()),
            ..Details::default()
        };
        with_details(err, d)
    })
}

/// Fields of a `SceneError`, each None where the error has no such thing.
#[derive(Default)]
struct Details {
    origin: Option<String>,
    field: Option<String>,
    value: Option<f64>,
    allowed: Option<String>,
    low: Option<f64>,
    high: Option<f64>,
    unit: Option<String>,
}

fn raise(message: String, d: Details) -> PyErr {
    with_details(SceneError::new_err(message), d)
}

/// `err` with the attributes of `d` set on its instance.
fn with_details(err: PyErr, d: Details) -> PyErr {
    Python::attach(|py| {
        let v = err.value(py);
        // Attributes of a fresh exception instance: setting them cannot fail.
        let _ = v.setattr("origin", d.origin);
        let _ = v.setattr("field", d.field);
        let _ = v.setattr("value", d.value);
        let _ = v.setattr("allowed", d.allowed);
        let _ = v.setattr("low", d.low);
        let _ = v.setattr("high", d.high);
        let _ = v.setattr("unit", d.unit);
        err
    })
}

fn range_details(origin: Option<String>, p: &InvalidParameter) -> Details {
    Details {
        origin,
        field: Some(p.name.clone()),
        value: Some(p.value),
        allowed: Some(p.allowed.to_string()),
        low: Some(p.allowed.lo),
        high: Some(p.allowed.hi),
        unit: Some(p.unit.to_string()),
    }
}

/// A problem of a scene given as a dict, at the field `field` as the user wrote it (which
/// `message` names): a `SceneError` with `field` and, where known, `allowed` set.
pub fn field_error(origin: &str, field: &str, message: String, allowed: Option<String>) -> PyErr {
    raise(
        format!("scene {origin}: {message}"),
        Details { origin: Some(origin.to_string()), field: Some(field.to_string()), allowed, ..Details::default() },
    )
}

/// A range error of a value too large for a float (a Python int), with `message` naming it
/// as written and `value` the int itself.
pub fn overflow_error(message: String, p: &InvalidParameter, origin: &str, value: &Py<PyAny>) -> PyErr {
    let err = raise(message, range_details(Some(origin.to_string()), p));
    Python::attach(|py| {
        let _ = err.value(py).setattr("value", value.clone_ref(py));
    });
    err
}

/// A scene error as a Python `SceneError`, with the command line's message; a scene file
/// that does not exist is a `FileNotFoundError` (errno, message, file name), as `open` raises.
pub fn scene_error(e: &Invalid) -> PyErr {
    if let Invalid::Read { path, source } = e {
        if source.kind() == std::io::ErrorKind::NotFound {
            return pyo3::exceptions::PyFileNotFoundError::new_err((
                source.raw_os_error().unwrap_or(2),
                e.to_string(),
                path.clone(),
            ));
        }
    }
    let details = match e {
        Invalid::Read { path, .. } | Invalid::NotAFile { path, .. } => {
            Details { origin: Some(path.clone()), ..Details::default() }
        }
        Invalid::Syntax { origin, .. } => Details { origin: Some(origin.clone()), ..Details::default() },
        Invalid::OutOfRange { origin, source } => range_details(Some(origin.clone()), source),
        Invalid::Inconsistent { origin, field, .. } => {
            Details { origin: Some(origin.clone()), field: Some(field.clone()), ..Details::default() }
        }
    };
    raise(e.to_string(), details)
}

/// An argument outside its range, as a `ValueError` naming the argument (the scene is not
/// at fault, so not a `SceneError`), with the same attributes.
pub fn argument_error(p: &InvalidParameter) -> PyErr {
    with_details(pyo3::exceptions::PyValueError::new_err(p.to_string()), range_details(None, p))
}

/// Any other refusal of an argument (an unknown name), as a `ValueError` naming it.
pub fn argument_message(field: &str, message: String) -> PyErr {
    with_details(
        pyo3::exceptions::PyValueError::new_err(format!("{field}: {message}")),
        Details { field: Some(field.to_string()), ..Details::default() },
    )
}

/// A model error as a Python `ModelError`.
pub fn model_error(message: impl std::fmt::Display) -> PyErr {
    ModelError::new_err(message.to_string())
}
