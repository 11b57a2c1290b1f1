//! Section V's conclusions as the report writes them: each statement (from the templates),
//! the numbers behind its verdict under each model, and the verdicts as a table.

use crate::present::table::{sig, Cell, Table};
use crate::template::{render, TemplateError};
use studies::paper_studies::{Along, Check, Evidence, Statement};

/// The statements of section V, by name and template.
fn template(s: Statement) -> (&'static str, &'static str) {
    match s {
        Statement::YieldShape => ("yield-shape.md", include_str!("../templates/paper_studies/yield-shape.md")),
        Statement::ForceShape => ("force-shape.md", include_str!("../templates/paper_studies/force-shape.md")),
        Statement::DeflectionShape => {
            ("deflection-shape.md", include_str!("../templates/paper_studies/deflection-shape.md"))
        }
        Statement::YieldOrder => ("yield-order.md", include_str!("../templates/paper_studies/yield-order.md")),
        Statement::SpringShare => ("spring-share.md", include_str!("../templates/paper_studies/spring-share.md")),
        Statement::ForceOrder => ("force-order.md", include_str!("../templates/paper_studies/force-order.md")),
        Statement::StiffnessSweep => {
            ("stiffness-sweep.md", include_str!("../templates/paper_studies/stiffness-sweep.md"))
        }
        Statement::Length => ("length.md", include_str!("../templates/paper_studies/length.md")),
        Statement::GangueHarder => ("gangue-harder.md", include_str!("../templates/paper_studies/gangue-harder.md")),
        Statement::GangueDifference => {
            ("gangue-difference.md", include_str!("../templates/paper_studies/gangue-difference.md"))
        }
    }
}

/// The statement of a check, on its line.
pub fn statement(c: &Check) -> Result<String, TemplateError> {
    let (name, text) = template(c.statement);
    let line = |a: Along| match a {
        Along::Centreline => "centreline",
        Along::FreeEdge => "free edge z = 0",
    };
    let values: Vec<(&str, String)> = c.along.map(|a| ("line", line(a).to_string())).into_iter().collect();
    render(&format!("paper_studies/{name}"), text, &values)
}

/// Values joined by `sep`, each to `digits` significant digits.
fn joined(v: &[f64], digits: usize, sep: &str) -> String {
    v.iter().map(|x| sig(*x, digits)).collect::<Vec<_>>().join(sep)
}

/// The numbers behind a verdict, as the table shows them.
pub fn evidence(s: Statement, e: &Evidence) -> String {
    match e {
        Evidence::Extremes { min_at, min, max_at, max } => {
            format!("min {} at x = {min_at:.2} L, max {} at x = {max_at:.2} L", sig(*min, 5), sig(*max, 5))
        }
        Evidence::Order { held, areas, worst } => {
            format!("{held}/{areas} areas; v_y(Con 2)/v_y(Con 1) - 1 ≥ {}", sig(*worst, 3))
        }
        Evidence::Values { values } => match s {
            Statement::SpringShare => joined(values, 4, " vs "),
            Statement::ForceOrder => joined(values, 7, " ≥ "),
            _ => joined(values, 7, ", "),
        },
        Evidence::Sweep { yield_velocity, contact_force, spring_ratio } => format!(
            "v_y {}; P {}; springs {}",
            joined(yield_velocity, 6, " → "),
            joined(contact_force, 6, " → "),
            joined(spring_ratio, 6, " → ")
        ),
        Evidence::Differences { values } => values
            .iter()
            .map(|(c, d)| format!("{c}: ΔP(coal - gangue 1) = {}", sig(*d, 6)))
            .collect::<Vec<_>>()
            .join("; "),
        Evidence::Lengths { values } => {
            values.iter().map(|(p, d)| format!("{}/{}", sig(*p, 5), sig(*d, 4))).collect::<Vec<_>>().join(" → ")
        }
    }
}

/// The verdicts as a table.
pub fn table(checks: &[Check]) -> Result<Table, TemplateError> {
    let mut t =
        Table::new("", &["item", "statement of section V", "beam", "holds (beam)", "plate FE", "holds (plate)"]);
    for c in checks {
        let yn = |yes: bool| Cell::Flag { yes, shown: if yes { "yes" } else { "**no**" } };
        t.push(vec![
            c.item.to_string().into(),
            statement(c)?.into(),
            evidence(c.statement, &c.beam).into(),
            yn(c.beam_holds),
            evidence(c.statement, &c.plate).into(),
            yn(c.plate_holds),
        ]);
    }
    Ok(t.csv_name("statement of section V", &["statement"])
        .csv_name("beam", &["beam_evidence"])
        .csv_name("plate FE", &["plate_FE_evidence"]))
}
