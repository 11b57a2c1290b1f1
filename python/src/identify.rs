//! The scene's coal-gangue ensemble (`[ensemble]`, `[signals]`; what `impact identify` runs)
//! on one support set, impacts `start..stop`, as feature columns.
//!
//! Impact `i` is drawn by `identify` from its own stream (ChaCha8 keyed by the ensemble's
//! seed, stream `i`) and thrown on the reduced-order model (`coupled::identification`), so a
//! row depends only on the scene and `i`: any split of the ensemble into index ranges gives,
//! concatenated, the rows of one run of the whole ensemble, bit for bit. That is what
//! `impact.shards` distributes. The reduced model (the plate's modes) is built once per process
//! and support set and kept for the next shards ([`reduced_model`]); the impacts themselves are
//! computed by `studies::identify::ensemble::shard`, as `impact identify` computes them.

use crate::columns::{Kind, Table};
use crate::errors::{argument_error, argument_message, model_error};
use ::identify::features::FEATURES;
use ::identify::Ensemble;
use analytic::params::{check, Range};
use coupled::reduced::ReducedModel;
use coupled::SupportSet;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::{Arc, Mutex};
use studies::identify::ensemble::{shard, validity_flags, Shard};

/// Reduced models built in this process, most recent last, by (scene text, support set): a
/// Dask worker runs many shards of one scene and support set, and their model (the plate's
/// modes and residual flexibility, about a second to build) is the same for all of them, so it
/// is built once per process instead of once per shard. A model is a pure function of the
/// scene text and the support set, so a kept one gives the same numbers as a new one.
static MODELS: Mutex<Vec<(String, String, Arc<ReducedModel>)>> = Mutex::new(Vec::new());
/// Models kept: a few scenes or support sets at a time (each a few MB).
const MODELS_KEPT: usize = 4;

/// The reduced model of `set` for the scene read from `text`, kept or built.
fn reduced_model(text: &str, s: &coupled::Scene, set: &coupled::SupportSet) -> Result<Arc<ReducedModel>, String> {
    // A poisoned lock only means another thread panicked while building; the list is intact.
    let mut kept = MODELS.lock().unwrap_or_else(|p| p.into_inner());
    if let Some(i) = kept.iter().position(|(t, c, _)| t == text && *c == set.name) {
        let entry = kept.remove(i);
        let model = entry.2.clone();
        kept.push(entry);
        return Ok(model);
    }
    let settings = studies::identify::sensors::reduced_settings(s, set).map_err(|x| x.to_string())?;
    let model = Arc::new(ReducedModel::new(&s.plate, set, settings).map_err(|x| x.to_string())?);
    if kept.len() == MODELS_KEPT {
        kept.remove(0);
    }
    kept.push((text.to_string(), set.name.clone(), model.clone()));
    Ok(model)
}

/// Most impacts one shard may hold: a shard is a unit of work of seconds to minutes.
const MAX_SHARD: f64 = 1_000_000.0;

/// The columns every shard has before the features, in order.
const SCHEMA: [(&str, Kind); 20] = [
    ("index", Kind::Int),
    ("family", Kind::Text),
    ("class", Kind::Text),
    ("x_m", Kind::Num),
    ("z_m", Kind::Num),
    ("velocity_m_per_s", Kind::Num),
    ("radius_m", Kind::Num),
    ("density_kg_m3", Kind::Num),
    ("youngs_modulus_pa", Kind::Num),
    ("poisson_ratio", Kind::Num),
    ("cohesion_pa", Kind::Num),
    ("friction_angle_deg", Kind::Num),
    ("force_max_N", Kind::Num),
    ("contact_time_s", Kind::Num),
    ("contacts", Kind::Int),
    ("valid", Kind::Flag),
    ("validity_flags", Kind::Text),
    ("elastic_ratio", Kind::Num),
    ("quasi_static_ratio", Kind::Num),
    ("unfinished", Kind::Flag),
];

/// The scene's ensemble and its support set `condition`, or why the arguments do not name them.
fn ensemble_and_set<'s>(s: &'s coupled::Scene, condition: &str) -> PyResult<(&'s Ensemble, &'s SupportSet)> {
    let study = s.ensemble.as_ref().ok_or_else(|| {
        argument_message(
            "scene",
            "has no [ensemble] table; impact identify's scenes (scenes/caving-stream.toml) have one".into(),
        )
    })?;
    if s.identifies_on_tail_beam() {
        return Err(argument_message(
            "scene",
            format!("{}: its identification strikes its tail beam as a caving stream (impact.stream); single impacts strike the plate's support sets only", s.name),
        ));
    }
    let set = s.conditions.iter().find(|c| c.name == condition).ok_or_else(|| {
        let names: Vec<&str> = s.conditions.iter().map(|c| c.name.as_str()).collect();
        argument_message("condition", format!("'{condition}' is not in the scene; it has {names:?}"))
    })?;
    Ok((&study.ensemble, set))
}

/// `start..stop` as impact indices of an ensemble of `n`: whole numbers, in order, at most
/// [`MAX_SHARD`] apart.
fn shard_range(n: usize, start: f64, stop: f64) -> PyResult<std::ops::Range<usize>> {
    let n = n as f64;
    let arg = |name: &str, v: f64, r: Range| check(name, v, r, "").map_err(|err| argument_error(&err));
    let start = arg("start", start, Range::closed(0.0, n))?;
    let stop = arg("stop", stop, Range::closed(start, n.min(start + MAX_SHARD)))?;
    if start.fract() != 0.0 || stop.fract() != 0.0 {
        return Err(argument_message("start, stop", format!("{start}, {stop} are not whole numbers")));
    }
    Ok(start as usize..stop as usize)
}

/// The sensors of a shard: the scene's named ones, or `sensors_mm` ((x, z) in mm) checked to
/// lie on the plate and to carry distinct channel labels (as the scene reader checks
/// `[signals] sensors_mm`), in m.
fn sensors(s: &coupled::Scene, sensors_mm: Option<Vec<(f64, f64)>>) -> PyResult<Vec<(f64, f64)>> {
    let Some(list) = sensors_mm else { return Ok(s.signals.sensors.clone()) };
    let (l_mm, b_mm) = (s.plate.length() * 1e3, s.plate.width() * 1e3);
    let sensors = list
        .iter()
        .enumerate()
        .map(|(j, &(x, z))| {
            let x = check(&format!("sensors_mm[{j}][0] (x)"), x, Range::closed(0.0, l_mm), "mm");
            let z = check(&format!("sensors_mm[{j}][1] (z)"), z, Range::closed(0.0, b_mm), "mm");
            match (x, z) {
                (Ok(x), Ok(z)) => Ok((x * 1e-3, z * 1e-3)),
                (Err(err), _) | (_, Err(err)) => Err(argument_error(&err)),
            }
        })
        .collect::<PyResult<Vec<_>>>()?;
    if let Some((field, message)) = ::scene::sensor_label_refusal("sensors_mm", &sensors) {
        return Err(argument_message(&field, message));
    }
    Ok(sensors)
}

/// The shard as columns: [`SCHEMA`], then every channel's features named as the identify
/// report names the channel ("acceleration at (229.2, 180) mm: peak (m/s^2)").
fn table(shard: &Shard) -> Table {
    let mut t = Table::new(shard.records.len(), &SCHEMA);
    for (row, (family, r)) in shard.records.iter().enumerate() {
        let d = &r.draw;
        t.int("index", row, d.index as i64);
        t.text("family", row, family);
        t.text("class", row, d.class.key());
        for (k, v) in [
            ("x_m", d.x),
            ("z_m", d.z),
            ("velocity_m_per_s", d.velocity),
            ("radius_m", d.radius),
            ("density_kg_m3", d.density),
            ("youngs_modulus_pa", d.youngs_modulus),
            ("poisson_ratio", d.poisson_ratio),
            ("cohesion_pa", d.cohesion),
            ("friction_angle_deg", d.friction_angle_deg),
            ("force_max_N", r.force_max),
            ("elastic_ratio", r.compression_ratio),
            ("quasi_static_ratio", r.hertz_time_ratio),
        ] {
            t.num(k, row, v);
        }
        // A first contact still open at the window's end has no duration: NaN, flagged.
        t.num("contact_time_s", row, r.contact_time.unwrap_or(f64::NAN));
        t.flag("unfinished", row, r.contact_time.is_none());
        t.int("contacts", row, r.contacts as i64);
        let f = validity_flags(r);
        // The quasi-static criterion is a regime label here (the reduced model is
        // transient), so it does not make an impact invalid.
        t.flag("valid", row, f.iter().all(|x| *x == "not quasi-static"));
        t.text("validity_flags", row, &f.join("; "));
        for (c, features) in shard.channels.iter().zip(r.channel_features()) {
            let label = c.label();
            for (feature, value) in FEATURES.iter().zip(features) {
                t.num(&format!("{label}: {} ({})", feature.key(), feature.unit(c.unit)), row, *value);
            }
        }
        // Under a measurement chain: each channel's peak before the background (the SNR's
        // signal) and the samples the ADC clipped.
        if !r.clean_peaks.is_empty() {
            t.int("clipped_samples", row, r.clipped as i64);
            for (c, peak) in shard.channels.iter().zip(&r.clean_peaks) {
                t.num(&format!("{}: clean peak ({})", c.label(), c.unit), row, *peak);
            }
        }
    }
    t
}

/// Impacts `start..stop` of the scene's ensemble on the support set `condition`, with the
/// scene's signals (window, rate, modes, damping, every quantity, the corners) at the scene's
/// named sensors or at `sensors_mm` ((x, z) in mm): draws, contact quantities, validity and
/// every channel's features.
#[pyfunction]
#[pyo3(signature = (scene, condition, start, stop, sensors_mm = None))]
pub fn identify<'py>(
    py: Python<'py>,
    scene: &crate::scene::Scene,
    condition: &str,
    start: f64,
    stop: f64,
    sensors_mm: Option<Vec<(f64, f64)>>,
) -> PyResult<Bound<'py, PyDict>> {
    let s = &scene.scene;
    let (e, set) = ensemble_and_set(s, condition)?;
    let range = shard_range(e.len(), start, stop)?;
    let sensors = sensors(s, sensors_mm)?;
    let computed = py.detach(|| -> Result<Shard, String> {
        if range.is_empty() {
            return Ok(Shard { channels: vec![], records: vec![] });
        }
        let model = reduced_model(scene.text(), s, set)?;
        shard(s, &model, &sensors, range).map_err(|x| x.to_string())
    });
    // An empty shard has no feature columns (they follow from the channels the reduced
    // model records); `impact.shards.merge` leaves empty shards out.
    table(&computed.map_err(model_error)?).into_py_all(py)
}
