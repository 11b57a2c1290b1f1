//! Result rows as columns: one numpy array per quantity, every array one entry per row, so
//! a dict of them goes straight into `pandas.DataFrame`.
//!
//! Conventions (the Python docstrings repeat them): the columns and their names are the result
//! rows' one schema (`studies::columns`), shared with the command line's tables, CSV and JSON:
//! SI units, the unit in the column name (`contact_force_N`, `x_m`); NaN only where a quantity does not apply to a row (a row the
//! model does not describe, an error estimate a model does not give, a spring a support set
//! does not have), never as a computed value; a column that applies to no row is left out.
//! Counts (`steps`, `contacts`, `elements`, `solver_iterations`) are int64; in a table that
//! mixes rows where a count does not apply (`model="all"`, a row the model does not describe)
//! the column is float64 with NaN in those rows, as pandas itself does for an integer column
//! with missing values.

use coupled::plan::{ResponseRow, Results, YieldRow};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use studies::columns::{
    response_columns, spring_columns, yield_columns, Column as SchemaColumn, Kind as SchemaKind, Value,
};

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

/// The Python kind of a schema column.
fn kind_of(k: SchemaKind) -> Kind {
    match k {
        SchemaKind::Text => Kind::Text,
        SchemaKind::Num => Kind::Num,
        SchemaKind::Flag => Kind::Flag,
        SchemaKind::Count => Kind::Count,
    }
}

/// Sets cell (`key`, `row`) of `t` to `v`.
fn put(t: &mut Table, key: &str, row: usize, v: Value) {
    match v {
        Value::Text(s) => t.text(key, row, &s),
        Value::Num(x) => t.num(key, row, x),
        Value::Flag(b) => t.flag(key, row, b),
        Value::Count(n) => t.count(key, row, n),
    }
}

/// Rows as columns by the schema: every schema column declared (in the schema's order), each
/// cell set where the quantity applies.
fn by_schema<R>(rows: &[R], schema: &[SchemaColumn<R>]) -> Table {
    let declared: Vec<(&str, Kind)> = schema.iter().map(|c| (c.key, kind_of(c.kind))).collect();
    let mut t = Table::new(rows.len(), &declared);
    for (i, r) in rows.iter().enumerate() {
        for c in schema {
            if let Some(v) = (c.get)(r) {
                put(&mut t, c.key, i, v);
            }
        }
    }
    t
}

/// The responses as columns ([`studies::columns::response_columns`]), then one column per
/// spring (`<spring>_force_N`, and `<spring>_force_error_N` where estimated), NaN in rows
/// whose support set lacks that spring.
pub fn responses(rows: &[ResponseRow]) -> Table {
    let mut t = by_schema(rows, &response_columns());
    let refs: Vec<&ResponseRow> = rows.iter().collect();
    for s in spring_columns(&refs) {
        for (i, r) in rows.iter().enumerate() {
            if let Some(v) = s.get(r) {
                put(&mut t, &s.key, i, v);
            }
        }
    }
    t
}

/// The yield velocities as columns ([`studies::columns::yield_columns`]).
pub fn yields(rows: &[YieldRow]) -> Table {
    by_schema(rows, &yield_columns())
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
