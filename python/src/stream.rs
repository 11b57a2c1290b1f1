//! The scene's caving-stream detection study (`[stream]`; what `impact stream` runs,
//! `studies::stream::compute`): per support set the windows' and lumps' truth as columns and,
//! where the scene asks for it, the first stream's recorded signals as numpy arrays, with the
//! study's results as JSON text for the Python layer to parse.

use crate::columns::Table;
use crate::errors::{argument_message, model_error};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use studies::progress::Silent;
use studies::stream::ConditionStream;

/// Runs the `[stream]` study of `scene`.
#[pyfunction]
pub fn stream<'py>(py: Python<'py>, scene: &crate::scene::Scene) -> PyResult<Bound<'py, PyDict>> {
    let s = &scene.scene;
    if s.stream.is_none() {
        return Err(argument_message(
            "scene",
            format!("{} has no [stream] table (see docs/scenes.md); impact.stream runs it", s.name),
        ));
    }
    let data = py.detach(|| studies::stream::compute(s, &Silent).map_err(|e| e.to_string())).map_err(model_error)?;
    let out = PyDict::new(py);
    out.set_item("results", serde_json::to_string(&data).map_err(model_error)?)?;
    let conditions = PyDict::new(py);
    for c in &data.conditions {
        let d = PyDict::new(py);
        d.set_item("windows", windows(c).into_py(py)?)?;
        d.set_item("lumps", lumps(c).into_py(py)?)?;
        d.set_item("detector", crate::detector::Detector { detector: c.detector.clone() })?;
        if let Some(sig) = &c.signal {
            let columns = PyDict::new(py);
            for (name, samples) in sig.names.iter().zip(&sig.columns) {
                columns.set_item(name, PyArray1::from_slice(py, samples))?;
            }
            d.set_item("signal_rate_hz", sig.rate_hz)?;
            d.set_item("signal", columns)?;
        }
        conditions.set_item(&c.name, d)?;
    }
    out.set_item("conditions", conditions)?;
    Ok(out)
}

/// Largest stream number one call takes (streams are numbered from the study's seed).
const MAX_STREAM: f64 = 1e9;

/// Stream `stream` of the scene's `[stream]` study on the support set `condition`, alone:
/// its recorded channels and its lumps, bit for bit the study's stream of that number, so
/// that streams are computed apart (a task each) and put together; with `segment`, only that
/// segment of a stream the scene cuts (`segment_s`), bit for bit the study's.
#[pyfunction]
#[pyo3(signature = (scene, condition, stream, segment=None))]
pub fn stream_recording<'py>(
    py: Python<'py>,
    scene: &crate::scene::Scene,
    condition: &str,
    stream: f64,
    segment: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let s = &scene.scene;
    let (Some(study), Some(ensemble)) = (&s.stream, &s.ensemble) else {
        return Err(argument_message(
            "scene",
            format!(
                "{} has no [stream] table (see docs/scenes.md); impact.stream_recording runs one of its streams",
                s.name
            ),
        ));
    };
    if s.identifies_on_tail_beam() {
        return Err(argument_message(
            "scene",
            format!("{}: its stream strikes its tail beam, whose streams impact.stream runs together; one stream apart is built for the plate's support sets only", s.name),
        ));
    }
    let set = s.conditions.iter().find(|c| c.name == condition).ok_or_else(|| {
        let names: Vec<&str> = s.conditions.iter().map(|c| c.name.as_str()).collect();
        argument_message("condition", format!("'{condition}' is not in the scene; it has {names:?}"))
    })?;
    if !(stream.is_finite() && stream >= 0.0 && stream.fract() == 0.0 && stream <= MAX_STREAM) {
        return Err(argument_message(
            "stream",
            format!("{stream} is not a stream number; allowed whole numbers in [0, {MAX_STREAM}]"),
        ));
    }
    let r = stream as usize;
    let segment = match segment {
        None => None,
        Some(b) if b.is_finite() && b >= 0.0 && b.fract() == 0.0 && b <= MAX_STREAM => Some(b as usize),
        Some(b) => {
            return Err(argument_message(
                "segment",
                format!("{b} is not a segment number; allowed whole numbers in [0, {MAX_STREAM}]"),
            ))
        }
    };
    if let Some(why) = segment.and_then(|b| studies::stream::segments::refusal(s, study, b)) {
        return Err(argument_message("segment", why));
    }
    let (signal, rows) = py
        .detach(|| studies::stream::one_stream(s, (study, ensemble), set, (r, segment)).map_err(|e| e.to_string()))
        .map_err(model_error)?;
    let out = PyDict::new(py);
    let columns = PyDict::new(py);
    for (name, samples) in signal.names.iter().zip(&signal.columns) {
        columns.set_item(name, PyArray1::from_slice(py, samples))?;
    }
    out.set_item("signal", columns)?;
    out.set_item("rate_hz", signal.rate_hz)?;
    out.set_item("lumps", lump_table(&rows).into_py(py)?)?;
    Ok(out)
}

/// How the scene's `[stream]` cuts every stream: (segments, a segment's length in s), or None
/// where it runs each in one piece.
#[pyfunction]
pub fn stream_segments(scene: &crate::scene::Scene) -> PyResult<Option<(usize, f64)>> {
    let s = &scene.scene;
    let Some(study) = &s.stream else {
        return Err(argument_message("scene", format!("{} has no [stream] table (see docs/scenes.md)", s.name)));
    };
    if s.identifies_on_tail_beam() {
        return Err(argument_message(
            "scene",
            format!("{}: its stream strikes its tail beam, whose streams impact.stream runs together; a segment alone is built for the plate's support sets only", s.name),
        ));
    }
    Ok(studies::stream::segments::count(s, study))
}

/// Every window of the main run: its stream, span, truth and every-channel score.
fn windows(c: &ConditionStream) -> Table {
    let mut t = Table::new(c.windows.len(), &[]);
    for (row, w) in c.windows.iter().enumerate() {
        t.int("stream", row, w.stream as i64);
        t.num("start_s", row, w.start);
        t.num("end_s", row, w.end);
        t.int("lumps", row, w.lumps as i64);
        t.int("gangue_lumps", row, w.gangue as i64);
        t.num("expected_gangue_share", row, w.expected_share);
        t.flag("gangue_rich", row, w.gangue_rich);
        // A window straddling a block edge is not scored: NaN.
        t.num("probability_gangue_rich", row, w.score.unwrap_or(f64::NAN));
    }
    t
}

/// Every lump of the main run.
fn lumps(c: &ConditionStream) -> Table {
    lump_table(&c.lumps)
}

/// The lumps `rows` as columns.
fn lump_table(rows: &[studies::stream::LumpRow]) -> Table {
    let mut t = Table::new(rows.len(), &[]);
    for (row, l) in rows.iter().enumerate() {
        t.int("stream", row, l.stream as i64);
        t.num("time_s", row, l.time);
        t.text("family", row, &l.family);
        t.flag("gangue", row, l.gangue);
        t.num("mass_kg", row, l.mass);
        t.num("velocity_m_per_s", row, l.velocity);
        t.num("x_m", row, l.x);
        t.num("z_m", row, l.z);
        t.int("contacts", row, l.contacts as i64);
        t.num("contact_time_s", row, l.contact_time);
        t.num("force_max_N", row, l.force_max);
        t.flag("overlapped", row, l.overlapped);
    }
    t
}
