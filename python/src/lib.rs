//! `impact._impact`: the Python extension module of `impact`, built by maturin from the same
//! library crates as the command line. Scenes are read and validated by the `scene` crate,
//! scenes are run by `studies::run` (the command line's own entry point), transient cases by
//! `coupled::plan`; this crate only converts: Python values in, columns of numpy arrays out.
//! Every long computation runs with the Python interpreter released (`Python::detach`), so
//! other Python threads (a Dask worker's heartbeat, a GUI) go on meanwhile.
//!
//! The public API, its docstrings and its types are in `python/impact/__init__.py` and
//! `python/impact/_impact.pyi`; the tests are `python/tests` (pytest).

#![warn(missing_docs)]

mod columns;
mod detector;
mod dict;
mod drops;
mod errors;
mod identify;
mod scene;
mod stream;
mod tail_beam;

use ::scene::{limits, Analysis};
use analytic::params::{check, Range};
use columns::Table;
use coupled::plan::{scene_striker, transient_response, transient_values, ModelKind, ResponseRow, RowOutcome};
use coupled::transient::{Discretisation, Ladder, Sample, TransientCase, DEFAULT_TOLERANCE};
use errors::{argument_error, argument_message, model_error};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use scene::Scene;

/// Runs `scene` with the models named by `model` ("beam", "plate", "transient" or "all"),
/// exactly as `impact solve` does (`studies::run::results`): on the scene's points, or on
/// `sweep` evenly spaced centreline points (`impact sweep --count`), and only the yield
/// velocities when `yield_only` (`impact yield`); the transient model chooses each case's mesh
/// and step for the relative `tolerance` (`--tolerance`, default 1e-4) and counts as main
/// contacts those carrying `main_contact_share` of m·v₀ (`--main-contact-share`, default 0.05).
/// Returns the columns of [`columns::results`].
#[pyfunction]
#[pyo3(signature = (scene, model = "beam", sweep = None, yield_only = false, tolerance = None, main_contact_share = None))]
fn run<'py>(
    py: Python<'py>,
    scene: &Scene,
    model: &str,
    sweep: Option<f64>,
    yield_only: bool,
    tolerance: Option<f64>,
    main_contact_share: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let models = studies::run::model_kinds(model).ok_or_else(|| {
        argument_message(
            "model",
            format!("'{model}' is not a model; allowed: \"beam\", \"plate\", \"transient\", \"all\""),
        )
    })?;
    let mut s = match sweep {
        None => scene.scene.clone(),
        Some(n) => {
            let n = check("count", n, limits::POINT_COUNT, "").map_err(|e| argument_error(&e))?;
            if n.fract() != 0.0 {
                return Err(argument_message(
                    "count",
                    format!("{n} is not a whole number; the allowed range is {}", limits::POINT_COUNT),
                ));
            }
            scene.scene.with_sweep(n as usize)
        }
    };
    if yield_only {
        s.analyses = vec![Analysis::YieldVelocity];
    }
    if let Some(t) = tolerance {
        s.transient_discretisation = Discretisation::tolerance(transient_tolerance(t)?);
    }
    if let Some(share) = main_contact_share {
        s.main_contact_share =
            check("main_contact_share", share, limits::MAIN_CONTACT_SHARE, "").map_err(|e| argument_error(&e))?;
    }
    let results = py
        .detach(|| studies::run::results(&s, &models, &studies::progress::Silent).map_err(|e| e.to_string()))
        .map_err(model_error)?;
    columns::results(py, &results)
}

/// The history samples as columns (SI, unit in the name); `first_contact` marks the samples
/// up to the first separation.
fn history<'py>(py: Python<'py>, first: &[Sample], later: &[Sample]) -> PyResult<Bound<'py, PyDict>> {
    let all: Vec<&Sample> = first.iter().chain(later).collect();
    let d = PyDict::new(py);
    let col = |f: fn(&Sample) -> f64| PyArray1::from_vec(py, all.iter().map(|s| f(s)).collect());
    d.set_item("t_s", col(|s| s.t))?;
    d.set_item("force_N", col(|s| s.force))?;
    d.set_item("compression_m", col(|s| s.compression))?;
    d.set_item("sphere_velocity_m_per_s", col(|s| s.sphere_velocity))?;
    d.set_item("plate_displacement_m", col(|s| s.plate_displacement))?;
    d.set_item("sphere_kinetic_J", col(|s| s.sphere_kinetic))?;
    d.set_item("contact_J", col(|s| s.contact))?;
    d.set_item("plate_kinetic_J", col(|s| s.plate_kinetic))?;
    d.set_item("plate_strain_J", col(|s| s.plate_strain))?;
    d.set_item("springs_J", col(|s| s.springs))?;
    d.set_item("dissipated_J", col(|s| s.dissipated))?;
    let first_flags: Vec<bool> = (0..all.len()).map(|i| i < first.len()).collect();
    d.set_item("first_contact", PyArray1::from_vec(py, first_flags))?;
    Ok(d)
}

/// Finds a name among `names`, or says which names there are.
fn by_name(field: &str, name: &str, names: Vec<&str>) -> PyResult<usize> {
    names
        .iter()
        .position(|n| *n == name)
        .ok_or_else(|| argument_message(field, format!("'{name}' is not in the scene; it has {names:?}")))
}

// Python gets the range as a (low, high) pair, documented as including both ends.
const _: () = assert!(limits::TRANSIENT_TOLERANCE.lo_closed && limits::TRANSIENT_TOLERANCE.hi_closed);

/// The transient model's relative tolerance, checked as `impact solve --tolerance` checks it.
fn transient_tolerance(t: f64) -> PyResult<f64> {
    check("tolerance", t, limits::TRANSIENT_TOLERANCE, "").map_err(|e| argument_error(&e))
}

/// One transient impact: `body` on the support set `condition` at (`x_mm`, `z_mm`) with
/// `velocity_m_per_s`, with the scene's contact law and restitution. Returns
/// `{"response": one-row response columns, "history": time series, "contacts": one row per
/// contact, "left_for_good": bool, "returns_at_s": under gravity the earliest instant the
/// sphere can be back after the window, else None}`. With `error_estimate` the case's mesh and step are
/// chosen for the relative `tolerance` and every response carries its error, exactly as
/// `impact solve --model transient` computes a row; without, one run on the starting mesh
/// (20 elements, 200 steps per Hertz time).
#[pyfunction]
#[pyo3(signature = (scene, body, condition, x_mm, z_mm, velocity_m_per_s, error_estimate = true, tolerance = None))]
#[allow(clippy::too_many_arguments)]
fn transient<'py>(
    py: Python<'py>,
    scene: &Scene,
    body: &str,
    condition: &str,
    x_mm: f64,
    z_mm: f64,
    velocity_m_per_s: f64,
    error_estimate: bool,
    tolerance: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let s = &scene.scene;
    let b = &s.bodies[by_name("body", body, s.bodies.iter().map(|b| b.name.as_str()).collect())?];
    let set = &s.conditions[by_name("condition", condition, s.conditions.iter().map(|c| c.name.as_str()).collect())?];
    let (l_mm, b_mm) = (s.plate.length() * 1e3, s.plate.width() * 1e3);
    let arg =
        |name: &str, v: f64, r: Range, unit: &'static str| check(name, v, r, unit).map_err(|e| argument_error(&e));
    let x = arg("x_mm", x_mm, Range::closed(0.0, l_mm), "mm")? * 1e-3;
    let z = arg("z_mm", z_mm, Range::closed(0.0, b_mm), "mm")? * 1e-3;
    let v = arg("velocity_m_per_s", velocity_m_per_s, limits::VELOCITY_M_PER_S, "m/s")?;
    let disc = match tolerance {
        Some(t) => Discretisation::tolerance(transient_tolerance(t)?),
        None => s.transient_discretisation,
    };
    let computed = py
        .detach(|| -> Result<_, coupled::ModelError> {
            if error_estimate {
                let ladder = Ladder::new(&s.plate, disc.start())?;
                let (values, e) = transient_response(s, disc, &ladder, set, b, (x, z), v)?;
                Ok((values, e.outcome))
            } else {
                let start = disc.start();
                let st = scene_striker(s, b, v);
                let o = TransientCase::new(&s.plate, start)?.run(set, &st, x, z)?;
                let dt = st.hertz_time() / start.steps_per_contact;
                Ok((transient_values(s, set, b, &o, &st, dt, (x, z), None), o))
            }
        })
        .map_err(model_error)?;
    let (values, outcome) = computed;
    let row = columns::responses(&[ResponseRow {
        model: ModelKind::Transient,
        body: b.name.clone(),
        condition: set.name.clone(),
        x,
        z,
        velocity: v,
        outcome: RowOutcome::Computed(values),
    }]);
    let mut contacts = Table::new(outcome.contacts.len(), &[]);
    for (i, c) in outcome.contacts.iter().enumerate() {
        contacts.num("start_s", i, c.start);
        contacts.num("duration_s", i, c.duration);
        contacts.num("peak_force_N", i, c.peak_force);
        contacts.num("impulse_N_s", i, c.impulse);
        contacts.num("rebound_velocity_m_per_s", i, c.rebound_velocity);
        contacts.count("steps", i, c.steps as u64);
    }
    let d = PyDict::new(py);
    d.set_item("response", row.into_py(py)?)?;
    d.set_item("history", history(py, &outcome.history, &outcome.later_history)?)?;
    d.set_item("contacts", contacts.into_py(py)?)?;
    d.set_item("left_for_good", outcome.left_at.is_some() && outcome.returns_at.is_none())?;
    d.set_item("returns_at_s", outcome.returns_at)?;
    Ok(d)
}

/// The extension module.
#[pymodule]
fn _impact(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<Scene>()?;
    m.add_class::<detector::Detector>()?;
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add("ModelError", py.get_type::<errors::ModelError>())?;
    m.add("SceneTypeError", errors::scene_type_error(py)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(transient, m)?)?;
    m.add_function(wrap_pyfunction!(identify::identify, m)?)?;
    m.add_function(wrap_pyfunction!(stream::stream, m)?)?;
    m.add_function(wrap_pyfunction!(stream::stream_recording, m)?)?;
    m.add_function(wrap_pyfunction!(stream::stream_segments, m)?)?;
    m.add_function(wrap_pyfunction!(detector::read_signal, m)?)?;
    m.add_function(wrap_pyfunction!(drops::drops, m)?)?;
    m.add_function(wrap_pyfunction!(tail_beam::tail_beam, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    // The Python layer documents these from here rather than repeat the numbers.
    let t = limits::TRANSIENT_TOLERANCE;
    m.add("TRANSIENT_TOLERANCE", (t.lo, t.hi))?;
    m.add("DEFAULT_TOLERANCE", DEFAULT_TOLERANCE)?;
    Ok(())
}
