//! Result rows as columns: one numpy array per quantity, every array one entry per row, so
//! a dict of them goes straight into `pandas.DataFrame`.
//!
//! Conventions (the Python docstrings repeat them): SI units, the unit in the column name
//! (`contact_force_n`, `x_m`); NaN only where a quantity does not apply to a row (a row the
//! model does not describe, an error estimate a model does not give, a spring a support set
//! does not have), never as a computed value; a column that applies to no row is left out.
//! Counts (`steps`, `contacts`, `elements`, `solver_iterations`) are int64; in a table that
//! mixes rows where a count does not apply (`model="all"`, a row the model does not describe)
//! the column is float64 with NaN in those rows, as pandas itself does for an integer column
//! with missing values.

use coupled::plan::{Evidence, ResponseRow, ResponseValues, Results, RowOutcome, YieldRow};
use coupled::Validity;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// The kind of one column.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// float64, NaN where the quantity does not apply.
    Num,
    /// bool, false where it does not apply.
    Flag,
    /// str, empty where it does not apply.
    Text,
    /// int64 (counts and indices that every row has).
    Int,
    /// A count that some rows may lack: int64 where every row has it, else float64 with NaN.
    Count,
}

enum Data {
    Num(Vec<f64>),
    Flag(Vec<bool>),
    Text(Vec<String>),
    Int(Vec<i64>),
    Count(Vec<Option<i64>>),
}

struct Column {
    name: String,
    data: Data,
    /// Whether any row set a value.
    used: bool,
}

/// A table of `n` rows filled cell by cell; columns keep the order they were declared in.
pub struct Table {
    n: usize,
    columns: Vec<Column>,
}

impl Table {
    /// `n` rows and the declared columns, every cell empty.
    pub fn new(n: usize, declared: &[(&str, Kind)]) -> Self {
        let mut t = Self { n, columns: Vec::new() };
        for &(name, kind) in declared {
            t.declare(name, kind);
        }
        t
    }

    fn declare(&mut self, name: &str, kind: Kind) -> usize {
        if let Some(i) = self.columns.iter().position(|c| c.name == name) {
            return i;
        }
        let data = match kind {
            Kind::Num => Data::Num(vec![f64::NAN; self.n]),
            Kind::Flag => Data::Flag(vec![false; self.n]),
            Kind::Text => Data::Text(vec![String::new(); self.n]),
            Kind::Int => Data::Int(vec![0; self.n]),
            Kind::Count => Data::Count(vec![None; self.n]),
        };
        self.columns.push(Column { name: name.to_string(), data, used: false });
        self.columns.len() - 1
    }

    /// Sets a number (declaring the column if it is new).
    pub fn num(&mut self, name: &str, row: usize, v: f64) {
        let i = self.declare(name, Kind::Num);
        let c = &mut self.columns[i];
        if let Data::Num(d) = &mut c.data {
            d[row] = v;
            c.used = true;
        }
    }

    /// Sets a number if there is one.
    pub fn opt(&mut self, name: &str, row: usize, v: Option<f64>) {
        if let Some(v) = v {
            self.num(name, row, v);
        }
    }

    /// Sets a flag.
    pub fn flag(&mut self, name: &str, row: usize, v: bool) {
        let i = self.declare(name, Kind::Flag);
        let c = &mut self.columns[i];
        if let Data::Flag(d) = &mut c.data {
            d[row] = v;
            c.used = true;
        }
    }

    /// Sets a text.
    pub fn text(&mut self, name: &str, row: usize, v: &str) {
        let i = self.declare(name, Kind::Text);
        let c = &mut self.columns[i];
        if let Data::Text(d) = &mut c.data {
            d[row] = v.to_string();
            c.used = true;
        }
    }

    /// Sets an integer.
    pub fn int(&mut self, name: &str, row: usize, v: i64) {
        let i = self.declare(name, Kind::Int);
        let c = &mut self.columns[i];
        if let Data::Int(d) = &mut c.data {
            d[row] = v;
            c.used = true;
        }
    }

    /// Sets a count.
    pub fn count(&mut self, name: &str, row: usize, v: u64) {
        let i = self.declare(name, Kind::Count);
        let c = &mut self.columns[i];
        if let Data::Count(d) = &mut c.data {
            d[row] = Some(i64::try_from(v).unwrap_or(i64::MAX));
            c.used = true;
        }
    }

    /// The used columns as a dict of numpy arrays (numbers, flags, integers) and lists
    /// (texts; the Python layer turns them into numpy str arrays).
    pub fn into_py(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        self.into_py_with(py, false)
    }

    /// Every declared column, used or not: a fixed schema, for shards that are merged.
    pub fn into_py_all(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        self.into_py_with(py, true)
    }

    fn into_py_with(self, py: Python<'_>, all: bool) -> PyResult<Bound<'_, PyDict>> {
        let d = PyDict::new(py);
        for c in self.columns.into_iter().filter(|c| all || c.used) {
            match c.data {
                Data::Num(v) => d.set_item(c.name, PyArray1::from_vec(py, v))?,
                Data::Flag(v) => d.set_item(c.name, PyArray1::from_vec(py, v))?,
                Data::Int(v) => d.set_item(c.name, PyArray1::from_vec(py, v))?,
                Data::Count(v) => match v.iter().copied().collect::<Option<Vec<i64>>>() {
                    Some(all) => d.set_item(c.name, PyArray1::from_vec(py, all))?,
                    None => d.set_item(
                        c.name,
                        PyArray1::from_vec(py, v.iter().map(|x| x.map_or(f64::NAN, |n| n as f64)).collect()),
                    )?,
                },
                Data::Text(v) => d.set_item(c.name, PyList::new(py, v)?)?,
            }
        }
        Ok(d)
    }
}

use Kind::{Count, Flag, Num, Text};

/// The row identity and outcome columns every result table starts with.
const KEYS: [(&str, Kind); 7] = [
    ("model", Text),
    ("body", Text),
    ("condition", Text),
    ("x_m", Num),
    ("z_m", Num),
    ("applicable", Flag),
    ("reason", Text),
];

/// The validity columns: whether every criterion holds, the failing ones by name, and each
/// criterion's measured value (its limit: 1, 0.2, 0.05, 3 % for the regime rule's bound on
/// the quasi-static force error, 1 contact). The transient criteria "impact finished" and
/// "discretisation" have their values among the transient columns (`left_for_good`,
/// `relative_error` against `tolerance`).
const VALIDITY: [(&str, Kind); 7] = [
    ("valid", Flag),
    ("validity_flags", Text),
    ("elastic_ratio", Num),
    ("quasi_static_ratio", Num),
    ("thin_plate_ratio", Num),
    ("regime_force_error", Num),
    ("contacts", Count),
];

fn validity(t: &mut Table, row: usize, v: &Validity) {
    t.flag("valid", row, v.all_valid());
    t.text("validity_flags", row, &v.flags().join("; "));
    t.opt("elastic_ratio", row, v.elastic.map(|c| c.value));
    t.opt("quasi_static_ratio", row, v.quasi_static.map(|c| c.value));
    t.num("thin_plate_ratio", row, v.thin_plate.value);
    t.opt("regime_force_error", row, v.regime.map(|c| c.value));
    // The criterion holds the count as its measured value (a whole number).
    if let Some(c) = v.recontact {
        t.count("contacts", row, c.value as u64);
    }
}

fn keys(t: &mut Table, row: usize, model: &str, body: &str, condition: &str, (x, z): (f64, f64)) {
    t.text("model", row, model);
    t.text("body", row, body);
    t.text("condition", row, condition);
    t.num("x_m", row, x);
    t.num("z_m", row, z);
}

/// Columns of the responses at maximum compression.
const RESPONSES: [(&str, Kind); 39] = [
    ("velocity_m_per_s", Num),
    ("compliance_m_per_n", Num),
    ("compliance_error_m_per_n", Num),
    ("contact_force_n", Num),
    ("contact_force_error_n", Num),
    ("compression_m", Num),
    ("compression_error_m", Num),
    ("deflection_m", Num),
    ("deflection_error_m", Num),
    ("rock_total_ratio", Num),
    ("rock_total_ratio_error", Num),
    ("rock_stored_ratio", Num),
    ("rock_stored_ratio_error", Num),
    ("plate_ratio", Num),
    ("plate_ratio_error", Num),
    ("spring_ratio", Num),
    ("spring_ratio_error", Num),
    ("sphere_kinetic_ratio", Num),
    ("sphere_kinetic_ratio_error", Num),
    ("solver_iterations", Count),
    ("solver_residual", Num),
    ("steps", Count),
    ("time_step_s", Num),
    ("peak_force_n", Num),
    ("peak_force_error_n", Num),
    ("contact_time_s", Num),
    ("contact_time_error_s", Num),
    ("apparent_restitution", Num),
    ("restitution_error", Num),
    ("elements", Count),
    ("steps_per_contact", Num),
    ("relative_error", Num),
    ("tolerance", Num),
    ("met_tolerance", Flag),
    ("total_impulse_n_s", Num),
    ("total_impulse_error_n_s", Num),
    ("final_velocity_m_per_s", Num),
    ("final_velocity_error_m_per_s", Num),
    ("left_for_good", Flag),
];

/// One response row's values into row `row` of `t`.
pub fn response_values(t: &mut Table, row: usize, v: &ResponseValues) {
    t.opt("compliance_m_per_n", row, v.compliance);
    t.opt("compliance_error_m_per_n", row, v.compliance_error);
    t.num("contact_force_n", row, v.contact_force);
    t.opt("contact_force_error_n", row, v.contact_force_error);
    t.num("compression_m", row, v.compression);
    t.opt("compression_error_m", row, v.compression_error);
    t.num("deflection_m", row, v.deflection);
    t.num("rock_total_ratio", row, v.rock_total_ratio);
    t.num("rock_stored_ratio", row, v.rock_stored_ratio);
    t.num("plate_ratio", row, v.plate_ratio);
    t.num("sphere_kinetic_ratio", row, v.sphere_kinetic_ratio);
    if !v.spring_forces.is_empty() {
        t.num("spring_ratio", row, v.spring_ratio);
    }
    if let Some(e) = &v.state_errors {
        t.num("deflection_error_m", row, e.deflection);
        t.num("rock_total_ratio_error", row, e.rock_total_ratio);
        t.num("rock_stored_ratio_error", row, e.rock_stored_ratio);
        t.num("plate_ratio_error", row, e.plate_ratio);
        t.num("sphere_kinetic_ratio_error", row, e.sphere_kinetic_ratio);
        if !v.spring_forces.is_empty() {
            t.num("spring_ratio_error", row, e.spring_ratio);
        }
    }
    match v.evidence {
        Evidence::Balance { iterations, residual } => {
            t.count("solver_iterations", row, u64::from(iterations));
            t.num("solver_residual", row, residual);
        }
        Evidence::Transient {
            steps,
            time_step,
            peak_force,
            peak_force_error,
            contact_time,
            contact_time_error,
            apparent_restitution,
            restitution_error,
            elements,
            steps_per_contact,
            relative_error,
            tolerance,
            met_tolerance,
            contacts: _,
            total_impulse,
            total_impulse_error,
            final_velocity,
            final_velocity_error,
            left_for_good,
        } => {
            t.count("steps", row, steps as u64);
            t.num("time_step_s", row, time_step);
            t.num("peak_force_n", row, peak_force);
            t.opt("peak_force_error_n", row, peak_force_error);
            t.opt("contact_time_s", row, contact_time);
            t.opt("contact_time_error_s", row, contact_time_error);
            t.opt("apparent_restitution", row, apparent_restitution);
            t.opt("restitution_error", row, restitution_error);
            if elements > 0 {
                t.count("elements", row, elements as u64);
            }
            t.num("steps_per_contact", row, steps_per_contact);
            t.opt("relative_error", row, relative_error);
            t.opt("tolerance", row, tolerance);
            if tolerance.is_some() {
                t.flag("met_tolerance", row, met_tolerance);
            }
            t.num("total_impulse_n_s", row, total_impulse);
            t.opt("total_impulse_error_n_s", row, total_impulse_error);
            t.num("final_velocity_m_per_s", row, final_velocity);
            t.opt("final_velocity_error_m_per_s", row, final_velocity_error);
            t.flag("left_for_good", row, left_for_good);
        }
    }
    // One column per spring, named as the model names it ("right spring", "spring at
    // corner (L, 0)"); NaN in rows whose support set lacks that spring.
    for s in &v.spring_forces {
        t.num(&format!("spring_force_n: {}", s.name), row, s.force);
    }
    if let Some(e) = &v.state_errors {
        for (s, err) in v.spring_forces.iter().zip(&e.spring_forces) {
            t.num(&format!("spring_force_error_n: {}", s.name), row, *err);
        }
    }
    validity(t, row, &v.validity);
}

/// The responses as columns.
pub fn responses(rows: &[ResponseRow]) -> Table {
    let declared: Vec<(&str, Kind)> = KEYS.iter().chain(&RESPONSES).chain(&VALIDITY).copied().collect();
    let mut t = Table::new(rows.len(), &declared);
    for (i, r) in rows.iter().enumerate() {
        keys(&mut t, i, r.model.key(), &r.body, &r.condition, (r.x, r.z));
        t.num("velocity_m_per_s", i, r.velocity);
        match &r.outcome {
            RowOutcome::NotApplicable { reason } => {
                t.flag("applicable", i, false);
                t.text("reason", i, reason);
            }
            RowOutcome::Computed(v) => {
                t.flag("applicable", i, true);
                response_values(&mut t, i, v);
            }
        }
    }
    t
}

/// Columns of the yield velocities.
const YIELDS: [(&str, Kind); 5] = [
    ("compliance_m_per_n", Num),
    ("compliance_error_m_per_n", Num),
    ("yield_compression_m", Num),
    ("yield_velocity_m_per_s", Num),
    ("yield_velocity_error_m_per_s", Num),
];

/// The yield velocities as columns.
pub fn yields(rows: &[YieldRow]) -> Table {
    let declared: Vec<(&str, Kind)> = KEYS.iter().chain(&YIELDS).chain(&VALIDITY).copied().collect();
    let mut t = Table::new(rows.len(), &declared);
    for (i, r) in rows.iter().enumerate() {
        keys(&mut t, i, r.model.key(), &r.body, &r.condition, (r.x, r.z));
        match &r.outcome {
            RowOutcome::NotApplicable { reason } => {
                t.flag("applicable", i, false);
                t.text("reason", i, reason);
            }
            RowOutcome::Computed(v) => {
                t.flag("applicable", i, true);
                t.opt("compliance_m_per_n", i, v.compliance);
                t.opt("compliance_error_m_per_n", i, v.compliance_error);
                t.num("yield_compression_m", i, v.yield_compression);
                t.num("yield_velocity_m_per_s", i, v.yield_velocity);
                t.opt("yield_velocity_error_m_per_s", i, v.yield_velocity_error);
                validity(&mut t, i, &v.validity);
            }
        }
    }
    t
}

/// A run's results: `{"responses": {...}, "yields": {...}, "status": str, "summary": {...}}`.
pub fn results<'py>(py: Python<'py>, r: &Results) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("scene", &r.scene)?;
    d.set_item("responses", responses(&r.responses).into_py(py)?)?;
    d.set_item("yields", yields(&r.yields).into_py(py)?)?;
    d.set_item("status", studies::run::status_line(r))?;
    let s = r.summary();
    let summary = PyDict::new(py);
    for (k, v) in [
        ("computed", s.computed),
        ("valid", s.valid),
        ("beyond_elastic", s.beyond_elastic),
        ("not_quasi_static", s.not_quasi_static),
        ("beyond_thin_plate", s.beyond_thin_plate),
        ("outside_regime_rule", s.outside_regime_rule),
        ("recontact", s.recontact),
        ("unfinished", s.unfinished),
        ("above_tolerance", s.above_tolerance),
        ("not_applicable", s.not_applicable),
    ] {
        summary.set_item(k, v)?;
    }
    d.set_item("summary", summary)?;
    Ok(d)
}
