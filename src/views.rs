//! Results as tables: one table per condition, with only the columns that apply
//! (no spring force under Con 1, no z for a model that does not resolve the width).

use crate::run::{ResponseRow, Results, YieldRow};
use crate::table::{Cell, Table};

fn conditions_in_order<'a>(names: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut out: Vec<&str> = Vec::new();
    for n in names {
        if !out.contains(&n) {
            out.push(n);
        }
    }
    out
}

/// Response tables, one per condition.
pub fn response_tables(results: &Results) -> Vec<Table> {
    let conds = conditions_in_order(results.responses.iter().map(|r| r.condition.as_str()));
    conds
        .into_iter()
        .map(|cond| {
            let rows: Vec<&ResponseRow> = results.responses.iter().filter(|r| r.condition == cond).collect();
            let with_z = rows.iter().any(|r| r.z.is_some());
            let springs: Vec<String> = rows
                .first()
                .map(|r| r.response.spring_forces.iter().map(|s| format!("{} force (N)", s.name)).collect())
                .unwrap_or_default();
            let has_springs = !springs.is_empty();
            let mut headers: Vec<String> = vec!["body".into(), "x (mm)".into()];
            if with_z {
                headers.push("z (mm)".into());
            }
            headers.extend(
                ["v (m/s)", "C (m/N)", "P_max (N)", "delta_max (m)", "deflection (m)"].iter().map(|s| s.to_string()),
            );
            headers.extend(springs);
            headers.extend(["rock total", "rock stored", "plate"].iter().map(|s| s.to_string()));
            if has_springs {
                headers.push("springs".into());
            }
            headers.extend(["iterations", "residual"].iter().map(|s| s.to_string()));
            let mut t = Table {
                title: format!("{} ({} model): responses at maximum compression", cond, results.model),
                headers,
                rows: vec![],
            };
            for r in rows {
                let s = &r.response;
                let mut row: Vec<Cell> = vec![r.body.clone().into(), (r.x * 1e3).into()];
                if with_z {
                    row.push(r.z.map_or(Cell::Empty, |z| Cell::Num(z * 1e3)));
                }
                row.extend([r.velocity, r.compliance, s.contact_force, s.compression, s.deflection].map(Cell::Num));
                row.extend(s.spring_forces.iter().map(|f| Cell::Num(f.force)));
                row.extend([s.rock_total_ratio, s.rock_stored_ratio, s.plate_ratio].map(Cell::Num));
                if has_springs {
                    row.push(s.spring_ratio.into());
                }
                row.push(s.solution.iterations.into());
                row.push(s.solution.residual.into());
                t.push(row);
            }
            t
        })
        .collect()
}

/// Yield-velocity tables, one per condition.
pub fn yield_tables(results: &Results) -> Vec<Table> {
    let conds = conditions_in_order(results.yields.iter().map(|r| r.condition.as_str()));
    conds
        .into_iter()
        .map(|cond| {
            let rows: Vec<&YieldRow> = results.yields.iter().filter(|r| r.condition == cond).collect();
            let with_z = rows.iter().any(|r| r.z.is_some());
            let mut headers = vec!["body", "x (mm)"];
            if with_z {
                headers.push("z (mm)");
            }
            headers.extend(["C (m/N)", "delta_my (m)", "v_y (m/s)"]);
            let mut t =
                Table::new(format!("{} ({} model): yield velocities (eqs. 51-54)", cond, results.model), &headers);
            for r in rows {
                let mut row: Vec<Cell> = vec![r.body.clone().into(), (r.x * 1e3).into()];
                if with_z {
                    row.push(r.z.map_or(Cell::Empty, |z| Cell::Num(z * 1e3)));
                }
                row.extend([r.compliance, r.yield_compression, r.yield_velocity].map(Cell::Num));
                t.push(row);
            }
            t
        })
        .collect()
}

/// A file-name-safe form of a name ("Con 2" -> "con-2").
pub fn slug(name: &str) -> String {
    let mut s = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            s.push(c.to_ascii_lowercase());
        } else if !s.ends_with('-') {
            s.push('-');
        }
    }
    s.trim_matches('-').to_string()
}
