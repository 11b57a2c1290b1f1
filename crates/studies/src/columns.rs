//! One column schema for the result rows (responses at maximum compression and yield
//! velocities): every quantity has one key, with its SI unit in the key style of
//! `docs/output-format.md` (`contact_force_N`, `x_m`, `velocity_m_per_s`), one display
//! header for the terminal, a kind and a getter. The terminal table, the CSV files, the JSON
//! rows and the Python columns are all made from these lists, so a quantity is named the same
//! everywhere and a new column is one entry here.
//!
//! A getter returns `None` where the quantity does not apply to a row (a row the model does
//! not describe, an error a model does not estimate, a transient number of a quasi-static
//! row); a column that applies to no row of a table is left out of it.

use coupled::plan::{Evidence, ResponseRow, ResponseValues, RowOutcome, YieldRow, YieldValues};
use coupled::Validity;

/// What a column holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A name, a label, a verdict.
    Text,
    /// A finite number in the unit of the key.
    Num,
    /// Yes or no.
    Flag,
    /// A whole number (steps, contacts, iterations).
    Count,
}

/// One cell's value.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// Text.
    Text(String),
    /// A number, SI.
    Num(f64),
    /// Yes or no.
    Flag(bool),
    /// A whole number.
    Count(u64),
}

/// One quantity of a row type `R`.
pub struct Column<R> {
    /// The key: quantity then SI unit (`contact_force_N`); CSV header, JSON key and Python
    /// column name.
    pub key: &'static str,
    /// The terminal's header, with the unit it is shown in (`P_max (N)`, `x (mm)`).
    pub header: &'static str,
    /// What it holds.
    pub kind: Kind,
    /// The value of a row, `None` where the quantity does not apply.
    pub get: fn(&R) -> Option<Value>,
}

impl<R> Column<R> {
    const fn new(key: &'static str, header: &'static str, kind: Kind, get: fn(&R) -> Option<Value>) -> Self {
        Self { key, header, kind, get }
    }
}

fn num(v: f64) -> Option<Value> {
    Some(Value::Num(v))
}

fn opt(v: Option<f64>) -> Option<Value> {
    v.map(Value::Num)
}

fn text(s: &str) -> Option<Value> {
    Some(Value::Text(s.to_string()))
}

fn on<T>(o: &RowOutcome<T>) -> Option<&T> {
    match o {
        RowOutcome::Computed(v) => Some(v),
        RowOutcome::NotApplicable { .. } => None,
    }
}

fn values(r: &ResponseRow) -> Option<&ResponseValues> {
    on(&r.outcome)
}

fn yields(r: &YieldRow) -> Option<&YieldValues> {
    on(&r.outcome)
}

/// A transient row's evidence, or `None` for the balance.
macro_rules! transient {
    ($r:expr, $field:ident) => {
        match values($r).map(|v| v.evidence) {
            Some(Evidence::Transient { $field, .. }) => Some($field),
            _ => None,
        }
    };
}

/// The largest of the estimated errors of the five energy shares (transient rows).
fn largest_share_error(v: &ResponseValues) -> Option<f64> {
    let e = v.state_errors.as_ref()?;
    Some(
        [e.rock_total_ratio, e.rock_stored_ratio, e.plate_ratio, e.spring_ratio, e.sphere_kinetic_ratio]
            .into_iter()
            .fold(0.0, f64::max),
    )
}

/// "valid", or the criteria a result is beyond, with their values and limits.
pub fn validity_text(v: &Validity) -> String {
    let beyond: Vec<String> = v
        .criteria()
        .into_iter()
        .filter(|(_, c)| !c.valid)
        .map(|(name, c)| format!("{name}: {} = {} (limit {})", c.measure, sig(c.value, 3), sig(c.limit, 3)))
        .collect();
    if beyond.is_empty() {
        "valid".into()
    } else {
        format!("beyond {}", beyond.join("; "))
    }
}

/// `v` with `sig` significant digits: plain for moderate magnitudes, else scientific.
pub fn sig(v: f64, sig: usize) -> String {
    if v == 0.0 {
        return "0".into();
    }
    if !v.is_finite() {
        return format!("{v}");
    }
    let mag = v.abs().log10().floor() as i32;
    if (-3..6).contains(&mag) {
        let decimals = (sig as i32 - 1 - mag).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{:.*e}", sig - 1, v)
    }
}

/// The validity columns of a row type whose values carry a [`Validity`].
macro_rules! validity_columns {
    ($row:ty, $values:ident, $text_header:expr) => {
        [
            Column::<$row>::new("valid", "valid", Kind::Flag, |r| {
                $values(r).map(|v| Value::Flag(v.validity.all_valid()))
            }),
            Column::new("validity_flags", "validity flags", Kind::Text, |r| {
                $values(r).map(|v| Value::Text(v.validity.flags().join("; ")))
            }),
            Column::new("elastic_ratio", "delta_max/delta_my", Kind::Num, |r| {
                opt($values(r).and_then(|v| v.validity.elastic.map(|c| c.value)))
            }),
            Column::new("quasi_static_ratio", "t_c/T1", Kind::Num, |r| {
                opt($values(r).and_then(|v| v.validity.quasi_static.map(|c| c.value)))
            }),
            Column::new("thin_plate_ratio", "h/min(L, B)", Kind::Num, |r| {
                $values(r).map(|v| Value::Num(v.validity.thin_plate.value))
            }),
            Column::new("regime_force_error", "regime rule force error bound", Kind::Num, |r| {
                opt($values(r).and_then(|v| v.validity.regime.map(|c| c.value)))
            }),
            Column::new("validity", $text_header, Kind::Text, |r| match &r.outcome {
                RowOutcome::NotApplicable { reason } => Some(Value::Text(format!("not applicable: {reason}"))),
                RowOutcome::Computed(v) => Some(Value::Text(validity_text(&v.validity))),
            }),
        ]
    };
}

/// The columns of a response row, in table order. The spring forces, one column per spring,
/// follow from [`spring_columns`].
pub fn response_columns() -> Vec<Column<ResponseRow>> {
    let mut c = vec![
        Column::new("model", "model", Kind::Text, |r: &ResponseRow| text(r.model.key())),
        Column::new("body", "body", Kind::Text, |r| text(&r.body)),
        Column::new("condition", "condition", Kind::Text, |r| text(&r.condition)),
        Column::new("x_m", "x (mm)", Kind::Num, |r| num(r.x)),
        Column::new("z_m", "z (mm)", Kind::Num, |r| num(r.z)),
        Column::new("velocity_m_per_s", "v (m/s)", Kind::Num, |r| num(r.velocity)),
        Column::new("applicable", "applicable", Kind::Flag, |r| Some(Value::Flag(on(&r.outcome).is_some()))),
        Column::new("reason", "not applicable because", Kind::Text, |r| match &r.outcome {
            RowOutcome::NotApplicable { reason } => text(reason),
            RowOutcome::Computed(_) => None,
        }),
        Column::new("compliance_m_per_N", "C (m/N)", Kind::Num, |r| opt(values(r)?.compliance)),
        Column::new("compliance_error_m_per_N", "C error (m/N)", Kind::Num, |r| opt(values(r)?.compliance_error)),
        Column::new("contact_force_N", "P_max (N)", Kind::Num, |r| num(values(r)?.contact_force)),
        Column::new("contact_force_error_N", "P_max error (N)", Kind::Num, |r| opt(values(r)?.contact_force_error)),
        Column::new("compression_m", "delta_max (m)", Kind::Num, |r| num(values(r)?.compression)),
        Column::new("compression_error_m", "delta_max error (m)", Kind::Num, |r| opt(values(r)?.compression_error)),
        Column::new("deflection_m", "deflection (m)", Kind::Num, |r| num(values(r)?.deflection)),
        Column::new("deflection_error_m", "deflection error (m)", Kind::Num, |r| {
            opt(values(r)?.state_errors.as_ref().map(|e| e.deflection))
        }),
        Column::new("rock_total_ratio", "rock total", Kind::Num, |r| num(values(r)?.rock_total_ratio)),
        Column::new("rock_stored_ratio", "rock stored", Kind::Num, |r| num(values(r)?.rock_stored_ratio)),
        Column::new("plate_ratio", "plate", Kind::Num, |r| num(values(r)?.plate_ratio)),
        Column::new("spring_ratio", "springs", Kind::Num, |r| {
            values(r).filter(|v| !v.spring_forces.is_empty()).map(|v| Value::Num(v.spring_ratio))
        }),
        Column::new("sphere_kinetic_ratio", "sphere kinetic", Kind::Num, |r| {
            values(r).filter(|v| v.state_errors.is_some()).map(|v| Value::Num(v.sphere_kinetic_ratio))
        }),
        Column::new("energy_share_error_max", "largest energy-share error", Kind::Num, |r| {
            opt(largest_share_error(values(r)?))
        }),
        Column::new("solver_iterations", "iterations", Kind::Count, |r| match values(r)?.evidence {
            Evidence::Balance { iterations, .. } => Some(Value::Count(u64::from(iterations))),
            Evidence::Transient { .. } => None,
        }),
        Column::new("solver_residual", "residual", Kind::Num, |r| match values(r)?.evidence {
            Evidence::Balance { residual, .. } => num(residual),
            Evidence::Transient { .. } => None,
        }),
    ];
    c.extend(transient_columns());
    c.extend(validity_columns!(ResponseRow, values, "validity"));
    c
}

/// The transient model's own columns (its discretisation and the whole impact).
fn transient_columns() -> Vec<Column<ResponseRow>> {
    vec![
        Column::new("steps", "steps", Kind::Count, |r| transient!(r, steps).map(|s| Value::Count(s as u64))),
        Column::new("time_step_s", "time step (s)", Kind::Num, |r| opt(transient!(r, time_step))),
        Column::new("peak_force_N", "peak force (N)", Kind::Num, |r| opt(transient!(r, peak_force))),
        Column::new("peak_force_error_N", "peak force error (N)", Kind::Num, |r| opt(transient!(r, peak_force_error)?)),
        Column::new("contact_time_s", "t_c (s)", Kind::Num, |r| opt(transient!(r, contact_time)?)),
        Column::new("contact_time_error_s", "t_c error (s)", Kind::Num, |r| opt(transient!(r, contact_time_error)?)),
        Column::new("apparent_restitution", "e apparent", Kind::Num, |r| opt(transient!(r, apparent_restitution)?)),
        Column::new("restitution_error", "e error", Kind::Num, |r| opt(transient!(r, restitution_error)?)),
        Column::new("elements", "elements", Kind::Count, |r| {
            transient!(r, elements).filter(|&n| n > 0).map(|n| Value::Count(n as u64))
        }),
        Column::new("steps_per_contact", "steps/t_H", Kind::Num, |r| opt(transient!(r, steps_per_contact))),
        Column::new("relative_error", "relative error estimate", Kind::Num, |r| opt(transient!(r, relative_error)?)),
        Column::new("tolerance", "tolerance", Kind::Num, |r| opt(transient!(r, tolerance)?)),
        Column::new("met_tolerance", "met tolerance", Kind::Flag, |r| match values(r).map(|v| v.evidence) {
            Some(Evidence::Transient { tolerance: Some(_), met_tolerance, .. }) => Some(Value::Flag(met_tolerance)),
            _ => None,
        }),
        Column::new("contacts", "contacts", Kind::Count, |r| transient!(r, contacts).map(|n| Value::Count(n as u64))),
        Column::new("main_contacts", "main contacts", Kind::Count, |r| {
            transient!(r, main_contacts).map(|n| Value::Count(n as u64))
        }),
        Column::new("micro_contacts", "micro-contacts", Kind::Count, |r| {
            transient!(r, micro_contacts).map(|n| Value::Count(n as u64))
        }),
        Column::new("micro_impulse_N_s", "micro impulse (N s)", Kind::Num, |r| opt(transient!(r, micro_impulse))),
        Column::new("contact_count_changes", "count changes", Kind::Flag, |r| {
            transient!(r, contact_count_changes)?.map(Value::Flag)
        }),
        Column::new("total_impulse_N_s", "total impulse (N s)", Kind::Num, |r| opt(transient!(r, total_impulse))),
        Column::new("total_impulse_error_N_s", "total impulse error (N s)", Kind::Num, |r| {
            opt(transient!(r, total_impulse_error)?)
        }),
        Column::new("final_velocity_m_per_s", "final v (m/s)", Kind::Num, |r| opt(transient!(r, final_velocity))),
        Column::new("final_velocity_error_m_per_s", "final v error (m/s)", Kind::Num, |r| {
            opt(transient!(r, final_velocity_error)?)
        }),
        Column::new("left_for_good", "left for good", Kind::Flag, |r| transient!(r, left_for_good).map(Value::Flag)),
        Column::new("returns_at_s", "falls back at (s)", Kind::Num, |r| opt(transient!(r, returns_at)?)),
    ]
}

/// The key form of a spring's name: its letters and digits, every other run one `_`
/// ("spring at corner (L, 0)" -> "spring_at_corner_L_0").
pub fn spring_key(name: &str) -> String {
    let mut s = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            s.push(c);
        } else if !s.ends_with('_') {
            s.push('_');
        }
    }
    s.trim_matches('_').to_string()
}

/// The spring-force columns of `rows`: for each spring (by name, in order of appearance) its
/// force and, where a row estimates it, the force's error; keys `<spring>_force_N` and
/// `<spring>_force_error_N`, headers `<spring> force (N)`.
pub fn spring_columns(rows: &[&ResponseRow]) -> Vec<SpringColumn> {
    let mut names: Vec<&str> = Vec::new();
    for v in rows.iter().filter_map(|r| values(r)) {
        for s in &v.spring_forces {
            if !names.contains(&s.name.as_str()) {
                names.push(&s.name);
            }
        }
    }
    names
        .into_iter()
        .flat_map(|n| {
            [false, true].map(|error| SpringColumn {
                key: format!("{}_force{}_N", spring_key(n), if error { "_error" } else { "" }),
                header: format!("{n} force{} (N)", if error { " error" } else { "" }),
                spring: n.to_string(),
                error,
            })
        })
        .collect()
}

/// One spring's force (or its error) as a column.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringColumn {
    /// `<spring>_force_N` or `<spring>_force_error_N`.
    pub key: String,
    /// `<spring> force (N)` or `<spring> force error (N)`.
    pub header: String,
    /// The spring's name as the model gives it.
    pub spring: String,
    /// Whether this is the force's estimated error.
    pub error: bool,
}

impl SpringColumn {
    /// The value of `r`, `None` where its support set lacks the spring or no error is estimated.
    pub fn get(&self, r: &ResponseRow) -> Option<Value> {
        let v = values(r)?;
        let k = v.spring_forces.iter().position(|s| s.name == self.spring)?;
        if self.error {
            opt(v.state_errors.as_ref()?.spring_forces.get(k).copied())
        } else {
            num(v.spring_forces[k].force)
        }
    }
}

/// The columns of a yield-velocity row, in table order.
pub fn yield_columns() -> Vec<Column<YieldRow>> {
    let mut c = vec![
        Column::new("model", "model", Kind::Text, |r: &YieldRow| text(r.model.key())),
        Column::new("body", "body", Kind::Text, |r| text(&r.body)),
        Column::new("condition", "condition", Kind::Text, |r| text(&r.condition)),
        Column::new("x_m", "x (mm)", Kind::Num, |r| num(r.x)),
        Column::new("z_m", "z (mm)", Kind::Num, |r| num(r.z)),
        Column::new("applicable", "applicable", Kind::Flag, |r| Some(Value::Flag(on(&r.outcome).is_some()))),
        Column::new("reason", "not applicable because", Kind::Text, |r| match &r.outcome {
            RowOutcome::NotApplicable { reason } => text(reason),
            RowOutcome::Computed(_) => None,
        }),
        Column::new("compliance_m_per_N", "C (m/N)", Kind::Num, |r| opt(yields(r)?.compliance)),
        Column::new("compliance_error_m_per_N", "C error (m/N)", Kind::Num, |r| opt(yields(r)?.compliance_error)),
        Column::new("yield_compression_m", "delta_my (m)", Kind::Num, |r| num(yields(r)?.yield_compression)),
        Column::new("yield_velocity_m_per_s", "v_y (m/s)", Kind::Num, |r| num(yields(r)?.yield_velocity)),
        Column::new("yield_velocity_error_m_per_s", "v_y error (m/s)", Kind::Num, |r| {
            opt(yields(r)?.yield_velocity_error)
        }),
    ];
    c.extend(validity_columns!(YieldRow, yields, "validity at v_y"));
    c
}

/// The result rows in the schema's keys, for JSON: `{"responses": [{key: value, ...}],
/// "yields": [...]}`, each row holding the columns that apply to it (the spring forces among
/// them); serialized straight from the rows, with no intermediate tree.
pub struct Rows<'a>(pub &'a coupled::plan::Results);

impl serde::Serialize for Value {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Value::Text(t) => s.serialize_str(t),
            Value::Num(x) => s.serialize_f64(*x),
            Value::Flag(b) => s.serialize_bool(*b),
            Value::Count(n) => s.serialize_u64(*n),
        }
    }
}

/// One row as a JSON object: the schema's columns that apply, then its springs.
struct Row<'a, R> {
    row: &'a R,
    columns: &'a [Column<R>],
    springs: &'a [SpringColumn],
    spring: fn(&SpringColumn, &R) -> Option<Value>,
}

impl<R> serde::Serialize for Row<'_, R> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut m = s.serialize_map(None)?;
        for c in self.columns {
            if let Some(v) = (c.get)(self.row) {
                m.serialize_entry(c.key, &v)?;
            }
        }
        for c in self.springs {
            if let Some(v) = (self.spring)(c, self.row) {
                m.serialize_entry(&c.key, &v)?;
            }
        }
        m.end()
    }
}

impl serde::Serialize for Rows<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::{SerializeMap, SerializeSeq};
        struct Seq<'b, R>(&'b [R], &'b [Column<R>], Vec<SpringColumn>, fn(&SpringColumn, &R) -> Option<Value>);
        impl<R> serde::Serialize for Seq<'_, R> {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                let mut q = s.serialize_seq(Some(self.0.len()))?;
                for r in self.0 {
                    q.serialize_element(&Row { row: r, columns: self.1, springs: &self.2, spring: self.3 })?;
                }
                q.end()
            }
        }
        let (rc, yc) = (response_columns(), yield_columns());
        let refs: Vec<&ResponseRow> = self.0.responses.iter().collect();
        let mut m = s.serialize_map(Some(2))?;
        m.serialize_entry("responses", &Seq(&self.0.responses, &rc, spring_columns(&refs), |c, r| c.get(r)))?;
        m.serialize_entry("yields", &Seq(&self.0.yields, &yc, vec![], |_, _| None))?;
        m.end()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_is_unique_and_in_the_key_form() {
        let keys: Vec<&str> =
            response_columns().iter().map(|c| c.key).chain(yield_columns().iter().map(|c| c.key)).collect();
        for k in &keys {
            assert!(k.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_') && !k.contains("__"), "{k}");
            // Newtons are `N`, hertz `Hz`: a lower-case unit word marks a column not converted.
            assert!(!k.ends_with("_n") && !k.contains("_n_") && !k.ends_with("_hz"), "{k}");
        }
        let r: Vec<&str> = response_columns().iter().map(|c| c.key).collect();
        let mut sorted = r.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), r.len(), "a response key twice");
    }

    #[test]
    fn spring_keys_are_key_words() {
        assert_eq!(spring_key("spring at corner (L, 0)"), "spring_at_corner_L_0");
        assert_eq!(spring_key("right spring"), "right_spring");
    }
}
