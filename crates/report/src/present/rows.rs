//! Result rows as tables: one table per support set, every model in it (a `model`
//! column), with only the columns that apply (no spring force where the set has no springs,
//! no sphere kinetic energy where no row is transient), and a `validity` column that names
//! every criterion a row is beyond.

use crate::present::table::{csv_key, Cell, Table};
use coupled::plan::{Evidence, ResponseRow, Results, YieldRow};
use studies::columns::{response_columns, spring_columns, yield_columns, Value};

fn in_order<'a>(names: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut out: Vec<&str> = Vec::new();
    for n in names {
        if !out.contains(&n) {
            out.push(n);
        }
    }
    out
}

pub use studies::columns::validity_text;

/// One word for a row's validity, for a narrow terminal: `valid`, or the first criterion it
/// is beyond with the count of further ones (`elastic+2`); [`validity_text`] has the values.
pub fn validity_word(text: &str) -> String {
    if text == "valid" {
        return text.into();
    }
    if text.starts_with("not applicable") {
        return "n/a".into();
    }
    let beyond: Vec<&str> = text.trim_start_matches("beyond ").split("; ").collect();
    let first = beyond[0].split(':').next().unwrap_or("flagged").replace(' ', "-");
    match beyond.len() {
        1 => first,
        n => format!("{first}+{}", n - 1),
    }
}

/// The columns a narrow terminal shows by default: the case, P_max or v_y with its error, and
/// one validity word. Where every row is of one model the model column is left out.
pub const NARROW: [&str; 11] = [
    "model",
    "body",
    "x (mm)",
    "z (mm)",
    "v (m/s)",
    "P_max (N)",
    "P_max error (N)",
    "v_y (m/s)",
    "v_y error (m/s)",
    "validity",
    "validity at v_y",
];

/// `t` with only the columns named in `keep` (display headers, in the table's order); the
/// validity columns become one word each unless `keep` names the validity in full. A header
/// in `keep` that the table lacks is skipped (tables differ in their columns).
pub fn narrow(t: &Table, keep: &[&str], validity_words: bool) -> Table {
    let one_model = t.rows.iter().all(|r| r.first() == t.rows[0].first());
    let cols: Vec<usize> = (0..t.headers.len())
        .filter(|&i| keep.contains(&t.headers[i].as_str()))
        .filter(|&i| !(i == 0 && t.headers[0] == "model" && one_model && keep == NARROW))
        .collect();
    let words = |i: usize| validity_words && t.headers[i].starts_with("validity");
    Table {
        title: t.title.clone(),
        headers: cols.iter().map(|&i| t.headers[i].clone()).collect(),
        rows: t
            .rows
            .iter()
            .map(|r| {
                cols.iter()
                    .map(|&i| if words(i) { Cell::Text(validity_word(&r[i].show())) } else { r[i].clone() })
                    .collect()
            })
            .collect(),
        csv_names: vec![],
    }
}

/// The transient discretisation of a row: elements, steps per Hertz time, the largest
/// relative error estimate and the tolerance it was chosen for (empty for other models).
pub fn discretisation_text(e: &Evidence) -> String {
    match *e {
        Evidence::Transient { elements, steps_per_contact, relative_error, tolerance, met_tolerance, .. } => {
            let est =
                relative_error.map_or(String::new(), |r| format!(", estimate {}", crate::present::table::sig(r, 2)));
            let tol = match tolerance {
                Some(t) if met_tolerance => format!(" <= {}", crate::present::table::sig(t, 2)),
                Some(t) => format!(" > {} (budget reached)", crate::present::table::sig(t, 2)),
                None => String::new(),
            };
            format!("{elements} elements, {steps_per_contact} steps/t_H{est}{tol}")
        }
        Evidence::Balance { .. } => String::new(),
    }
}

/// A schema value as a table cell, a number in the unit of `header` (SI over the header's
/// factor: metres shown in mm under "x (mm)"); yes/no as 1/0.
fn cell(v: Option<Value>, header: &str) -> Cell {
    let to_display = csv_key(header).1;
    match v {
        None => Cell::Empty,
        Some(Value::Num(x)) => Cell::Num(x / to_display),
        Some(Value::Count(n)) => Cell::Int(n),
        Some(Value::Flag(b)) => Cell::Int(u64::from(b)),
        Some(Value::Text(t)) => Cell::Text(t),
    }
}

/// A column as the table builder takes it: key, header, getter.
type Getter<'a, R> = (String, String, Box<dyn Fn(&R) -> Option<Value> + 'a>);

/// A table of `rows` by the schema's `columns` (and any further ones), each column that
/// applies to at least one row, under its header, its CSV name the schema's key.
fn schema_table<R>(title: String, rows: &[&R], columns: &[Getter<'_, R>]) -> Table {
    let used: Vec<&Getter<'_, R>> =
        columns.iter().filter(|(_, _, get)| rows.iter().any(|r| get(r).is_some())).collect();
    let headers: Vec<&str> = used.iter().map(|(_, h, _)| h.as_str()).collect();
    let mut t = Table::new(title, &headers);
    t.csv_names = used.iter().enumerate().map(|(i, (k, _, _))| (i, vec![k.clone()])).collect();
    for r in rows {
        t.push(used.iter().map(|(_, h, get)| cell(get(r), h)).collect());
    }
    t
}

/// Response tables, one per support set, every column of the schema
/// ([`studies::columns::response_columns`]) that applies to one of its rows, the spring forces
/// after the deflection.
pub fn response_tables(results: &Results) -> Vec<Table> {
    let schema = response_columns();
    in_order(results.responses.iter().map(|r| r.condition.as_str()))
        .into_iter()
        .map(|cond| {
            let rows: Vec<&ResponseRow> = results.responses.iter().filter(|r| r.condition == cond).collect();
            let springs = spring_columns(&rows);
            let mut columns: Vec<Getter<'_, ResponseRow>> = Vec::new();
            for c in &schema {
                columns.push((c.key.to_string(), c.header.to_string(), Box::new(c.get)));
                if c.key == "deflection_error_m" {
                    for s in &springs {
                        columns.push((s.key.clone(), s.header.clone(), Box::new(move |r: &ResponseRow| s.get(r))));
                    }
                }
            }
            schema_table(format!("{cond}: responses at maximum compression"), &rows, &columns)
        })
        .collect()
}

/// Yield-velocity tables, one per support set, by the schema
/// ([`studies::columns::yield_columns`]).
pub fn yield_tables(results: &Results) -> Vec<Table> {
    let schema = yield_columns();
    in_order(results.yields.iter().map(|r| r.condition.as_str()))
        .into_iter()
        .map(|cond| {
            let rows: Vec<&YieldRow> = results.yields.iter().filter(|r| r.condition == cond).collect();
            let columns: Vec<Getter<'_, YieldRow>> = schema
                .iter()
                .map(|c| (c.key.to_string(), c.header.to_string(), Box::new(c.get) as Box<dyn Fn(&YieldRow) -> _>))
                .collect();
            schema_table(format!("{cond}: yield velocities (eqs. 51-54)"), &rows, &columns)
        })
        .collect()
}

pub use scene::slug;
