//! Recorded drop tests against the scene's model (`impact drops`, `studies::drops::compute`):
//! one row per drop and quantity as columns, with the run's settings and every row as JSON
//! text for the Python layer to parse.

use crate::columns::Table;
use crate::errors::{argument_message, model_error};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use studies::drops::DropsData;
use studies::progress::Silent;

/// The drops of the recording whose sidecar is `signal` against `scene`'s model.
#[pyfunction]
pub fn drops<'py>(
    py: Python<'py>,
    scene: &crate::scene::Scene,
    signal: std::path::PathBuf,
) -> PyResult<Bound<'py, PyDict>> {
    let s = &scene.scene;
    let origin = signal.display().to_string();
    let recording = crate::detector::recording(&signal)?;
    studies::drops::check(s, &recording, &origin).map_err(|e| argument_message("signal", e.to_string()))?;
    let data = py
        .detach(|| studies::drops::compute(s, &recording, &origin, &Silent).map_err(|e| e.to_string()))
        .map_err(model_error)?;
    let out = PyDict::new(py);
    out.set_item("results", serde_json::to_string(&data).map_err(model_error)?)?;
    out.set_item("rows", rows(&data).into_py(py)?)?;
    Ok(out)
}

/// One row per drop and quantity, as `drops.csv` has them.
fn rows(d: &DropsData) -> Table {
    let n = d.drops.iter().map(|x| x.rows.len()).sum();
    let mut t = Table::new(n, &[]);
    let mut row = 0;
    for drop in &d.drops {
        for r in &drop.rows {
            t.int("drop", row, drop.index as i64);
            t.num("touch_s", row, drop.touch);
            t.text("class", row, drop.class.map_or("not stated", |c| c.key()));
            t.text("quantity", row, &r.quantity);
            t.text("unit", row, &r.unit);
            t.num("measured", row, r.measured);
            t.num("predicted", row, r.predicted);
            t.num("bar", row, r.bar);
            t.num("truncation", row, r.truncation);
            t.num("time_step", row, r.step);
            t.num("chain", row, r.chain);
            t.num("noise_sd", row, r.noise_sd);
            t.flag("disagrees", row, r.disagrees);
            t.text("note", row, &r.note);
            row += 1;
        }
    }
    t
}
