//! Result rows as tables: one table per support set, every model in it (a `model`
//! column), with only the columns that apply (no spring force where the set has no springs,
//! no sphere kinetic energy where no row is transient), and a `validity` column that names
//! every criterion a row is beyond.

use crate::present::table::{Cell, Table};
use coupled::plan::{Evidence, ResponseRow, Results, RowOutcome, YieldRow};
use coupled::Validity;

fn in_order<'a>(names: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut out: Vec<&str> = Vec::new();
    for n in names {
        if !out.contains(&n) {
            out.push(n);
        }
    }
    out
}

/// "valid", or the criteria a result is beyond, with their values.
pub fn validity_text(v: &Validity) -> String {
    let beyond: Vec<String> = v
        .criteria()
        .into_iter()
        .filter(|(_, c)| !c.valid)
        .map(|(name, c)| {
            format!(
                "{name}: {} = {} (limit {})",
                c.measure,
                crate::present::table::sig(c.value, 3),
                crate::present::table::sig(c.limit, 3)
            )
        })
        .collect();
    if beyond.is_empty() {
        "valid".into()
    } else {
        format!("beyond {}", beyond.join("; "))
    }
}

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

fn opt(v: Option<f64>) -> Cell {
    v.map_or(Cell::Empty, Cell::Num)
}

/// Response tables, one per support set.
pub fn response_tables(results: &Results) -> Vec<Table> {
    in_order(results.responses.iter().map(|r| r.condition.as_str()))
        .into_iter()
        .map(|cond| {
            let rows: Vec<&ResponseRow> = results.responses.iter().filter(|r| r.condition == cond).collect();
            let springs: Vec<String> = rows
                .iter()
                .find_map(|r| r.values().filter(|v| !v.spring_forces.is_empty()))
                .map(|v| v.spring_forces.iter().map(|s| s.name.clone()).collect())
                .unwrap_or_default();
            let transient =
                rows.iter().any(|r| matches!(r.values().map(|v| v.evidence), Some(Evidence::Transient { .. })));
            let mut headers: Vec<String> = [
                "model",
                "body",
                "x (mm)",
                "z (mm)",
                "v (m/s)",
                "C (m/N)",
                "C error (m/N)",
                "P_max (N)",
                "P_max error (N)",
                "delta_max (m)",
                "deflection (m)",
            ]
            .iter()
            .map(|s| s.to_string())
            .collect();
            headers.extend(springs.iter().map(|s| format!("{s} force (N)")));
            headers.extend(["rock total", "rock stored", "plate"].iter().map(|s| s.to_string()));
            if !springs.is_empty() {
                headers.push("springs".into());
            }
            if transient {
                headers.push("sphere kinetic".into());
                headers.push("deflection error (m)".into());
                headers.push("largest energy-share error".into());
                headers.push("discretisation".into());
            }
            headers.extend(
                ["iterations or steps", "residual or peak force (N)", "validity"].iter().map(|s| s.to_string()),
            );
            let headers_len = headers.len();
            let mut t = Table {
                title: format!("{cond}: responses at maximum compression"),
                headers,
                rows: vec![],
                csv_names: vec![],
            };
            if transient {
                t = t.csv_name("discretisation", &["discretisation_note"]);
            }
            for r in rows {
                let mut row: Vec<Cell> = vec![
                    r.model.key().into(),
                    r.body.clone().into(),
                    (r.x * 1e3).into(),
                    (r.z * 1e3).into(),
                    r.velocity.into(),
                ];
                match &r.outcome {
                    RowOutcome::NotApplicable { reason } => {
                        // Every value column empty, the reason where the validity goes.
                        let values = headers_len - row.len() - 1;
                        row.extend(std::iter::repeat_n(Cell::Empty, values));
                        row.push(Cell::Text(format!("not applicable: {reason}")));
                    }
                    RowOutcome::Computed(v) => {
                        row.extend([
                            opt(v.compliance),
                            opt(v.compliance_error),
                            Cell::Num(v.contact_force),
                            opt(v.contact_force_error),
                            Cell::Num(v.compression),
                            Cell::Num(v.deflection),
                        ]);
                        for name in &springs {
                            row.push(
                                v.spring_forces
                                    .iter()
                                    .find(|s| &s.name == name)
                                    .map_or(Cell::Empty, |s| Cell::Num(s.force)),
                            );
                        }
                        row.extend([v.rock_total_ratio, v.rock_stored_ratio, v.plate_ratio].map(Cell::Num));
                        if !springs.is_empty() {
                            row.push(v.spring_ratio.into());
                        }
                        if transient {
                            row.push(v.sphere_kinetic_ratio.into());
                            let e = v.state_errors.as_ref();
                            row.push(opt(e.map(|e| e.deflection)));
                            row.push(opt(e.map(|e| {
                                [
                                    e.rock_total_ratio,
                                    e.rock_stored_ratio,
                                    e.plate_ratio,
                                    e.spring_ratio,
                                    e.sphere_kinetic_ratio,
                                ]
                                .into_iter()
                                .fold(0.0, f64::max)
                            })));
                            row.push(discretisation_text(&v.evidence).into());
                        }
                        match v.evidence {
                            Evidence::Balance { iterations, residual } => {
                                row.push(iterations.into());
                                row.push(residual.into());
                            }
                            Evidence::Transient { steps, peak_force, .. } => {
                                row.push(steps.into());
                                row.push(peak_force.into());
                            }
                        }
                        row.push(validity_text(&v.validity).into());
                    }
                }
                t.push(row);
            }
            t
        })
        .collect()
}

/// Yield-velocity tables, one per support set.
pub fn yield_tables(results: &Results) -> Vec<Table> {
    in_order(results.yields.iter().map(|r| r.condition.as_str()))
        .into_iter()
        .map(|cond| {
            let rows: Vec<&YieldRow> = results.yields.iter().filter(|r| r.condition == cond).collect();
            let mut t = Table::new(
                format!("{cond}: yield velocities (eqs. 51-54)"),
                &[
                    "model",
                    "body",
                    "x (mm)",
                    "z (mm)",
                    "C (m/N)",
                    "C error (m/N)",
                    "delta_my (m)",
                    "v_y (m/s)",
                    "v_y error (m/s)",
                    "validity at v_y",
                ],
            )
            .csv_name("validity at v_y", &["v_y_validity"]);
            for r in rows {
                let mut row: Vec<Cell> =
                    vec![r.model.key().into(), r.body.clone().into(), (r.x * 1e3).into(), (r.z * 1e3).into()];
                match &r.outcome {
                    RowOutcome::NotApplicable { reason } => {
                        row.extend(std::iter::repeat_n(Cell::Empty, 5));
                        row.push(Cell::Text(format!("not applicable: {reason}")));
                    }
                    RowOutcome::Computed(v) => {
                        row.extend([
                            opt(v.compliance),
                            opt(v.compliance_error),
                            Cell::Num(v.yield_compression),
                            Cell::Num(v.yield_velocity),
                            opt(v.yield_velocity_error),
                        ]);
                        row.push(validity_text(&v.validity).into());
                    }
                }
                t.push(row);
            }
            t
        })
        .collect()
}

pub use scene::slug;
