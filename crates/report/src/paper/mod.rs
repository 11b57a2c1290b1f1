//! The paper's section IV reproduced: Tables 2-12 beside the printed values and the curves
//! of Figures 8-19, rendered from the reproduction computed in [`studies::paper`].

use crate::present::table::{Cell, Table};
use crate::template::render;
use crate::Failure;
use analytic::Method;
use output::Artifacts;
use scene::Scene;
pub use studies::paper::*;
use studies::progress::{Progress, Silent};
use studies::settings::Settings;
use studies::study::{Reproduction, Study};

mod figures;

/// The report's prose; every number in it is a placeholder filled from the run.
const PAPER_TEMPLATE: &str = include_str!("../templates/paper.md");
/// One printed table's comparison on the page.
const COMPARISON_TABLE: &str = include_str!("../templates/paper/comparison-table.md");

/// A verdict as the tables write it.
fn verdict_text(v: &Verdict) -> String {
    match v {
        Verdict::WithinPrint => "within print rounding".to_string(),
        Verdict::Close => format!("≤ {EXPLAIN_ABOVE:e}"),
        Verdict::Explained(s) => s.clone(),
        Verdict::Unexplained => "UNEXPLAINED".to_string(),
    }
}

/// The comparison tables, one per printed table, as Markdown, and all of them as one table.
fn comparison_tables(rows: &[ComparedRow]) -> Result<(String, Table), Failure> {
    let headers = [
        "case",
        "quantity",
        "printed",
        "equations (converged)",
        "rel. dev. (converged)",
        "recursion ğ=1e-6",
        "rel. dev. (recursion)",
        "verdict",
    ];
    let mut all = Table::new("", &[&["table"], &headers[..]].concat());
    let mut md = String::new();
    let mut tables: Vec<&str> = rows.iter().map(|r| r.comparison.table.as_str()).collect();
    tables.dedup();
    for t in tables {
        let mut tab = Table::new("", &headers);
        for ComparedRow { comparison: r, verdict } in rows.iter().filter(|r| r.comparison.table == t) {
            let row = vec![
                Cell::from(r.case.clone()),
                r.quantity.clone().into(),
                r.printed_text.clone().into(),
                Cell::Num(r.equations),
                Cell::Num(r.deviation(r.equations)),
                r.recursion.map_or(Cell::Empty, Cell::Num),
                r.recursion.map_or(Cell::Empty, |x| Cell::Num(r.deviation(x))),
                verdict_text(verdict).into(),
            ];
            let mut full = vec![Cell::from(t)];
            full.extend(row.iter().cloned());
            all.push(full);
            tab.push(row);
        }
        md.push_str(&render(
            "paper/comparison-table.md",
            COMPARISON_TABLE,
            &[("table", t.to_string()), ("rows", tab.to_markdown())],
        )?);
    }
    Ok((md, all))
}

/// How well each ğ reproduces print.
fn evidence_table(rows: &[ToleranceRow]) -> Table {
    let mut t = Table::new(
        "",
        &[
            "ğ of eq. 18",
            "max |reproduced - printed| in half units of the last printed digit",
            "cells within print rounding",
            "cells",
        ],
    );
    for r in rows {
        let label = r.tolerance.map_or_else(|| format!("converged ({CONVERGED_TOLERANCE:e})"), |t| format!("{t:e}"));
        t.push(vec![label.into(), r.worst.into(), r.within.into(), r.cells.into()]);
    }
    t
}

/// Table 5.
fn table5_table(minima: &[Minimum]) -> Table {
    let mut t = Table::new("", &["body", "condition", "min v_y (m/s)", "at x (mm)"]);
    for m in minima {
        t.push(vec![m.body.clone().into(), format!("Con {}", m.condition).into(), m.v.into(), (m.x * 1e3).into()]);
    }
    t
}

/// The solver study.
fn solver_table(rows: &[SolverRow]) -> Table {
    let mut t = Table::new(
        "",
        &[
            "C / C_paper",
            "v (m/s)",
            "E_sphere / E_plate",
            "recursion iterations",
            "recursion residual",
            "bracketed iterations",
            "bracketed residual",
            "rel. diff. in δ",
            "both converged",
        ],
    );
    for s in rows {
        let (r, b) = (&s.recursion, &s.bracketed);
        let yes = r.converged && b.converged;
        t.push(vec![
            s.compliance_factor.into(),
            s.velocity.into(),
            s.modulus_ratio.into(),
            r.iterations.into(),
            r.residual.into(),
            b.iterations.into(),
            b.residual.into(),
            ((r.delta - b.delta).abs() / b.delta).into(),
            Cell::Flag { yes, shown: if yes { "yes" } else { "NO" } },
        ]);
    }
    t
}

/// The δ_my inversion per body.
fn inversion_table(rows: &[InversionRow]) -> Table {
    let mut t = Table::new("", &["body", "cells", "mean δ_my ratio", "min", "max"]);
    for r in rows {
        t.push(vec![r.body.clone().into(), r.cells.into(), r.mean.into(), r.min.into(), r.max.into()]);
    }
    t
}

/// A number as the prose writes a round value: `0`, small integers as they are, the rest
/// in exponent form (`1e-6`, `1e3`).
fn short(v: f64) -> String {
    if v == 0.0 || (v.fract() == 0.0 && v.abs() < 100.0) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// The stopping tolerance of a solver method.
fn tolerance_of(m: Method) -> f64 {
    match m {
        Method::Recursion { tolerance, .. } | Method::Bracketed { tolerance, .. } => tolerance,
    }
}

/// The placeholders on the comparisons, the unit slip, Table 2's inversion and Table 5.
fn finding_values(d: &ReproductionData) -> Vec<(&'static str, String)> {
    let (slip, close, inv, t5) = (&d.slip, &d.close, &d.inversion_findings, &d.table5_findings);
    let counts = d.counts;
    let (q_min, q_coal, q_ratio) = (&t5.quoted_min, &t5.quoted_coal_min, &t5.quoted_ratio);
    vec![
        ("converged_tolerance", format!("{CONVERGED_TOLERANCE:e}")),
        ("paper_tolerance", format!("{PAPER_RECURSION_TOLERANCE:e}")),
        ("converged_max_deviation", format!("{:.0e}", d.converged_worst)),
        ("evidence", evidence_table(&d.evidence).to_markdown()),
        ("explain_above", format!("{EXPLAIN_ABOVE:e}")),
        ("compared", d.rows.len().to_string()),
        ("within_print", counts[0].to_string()),
        ("close", counts[1].to_string()),
        ("explained", counts[2].to_string()),
        ("unexplained", counts[3].to_string()),
        ("slip_printed", slip.printed.clone()),
        ("slip_column_unit", format!("1e{}", slip.column_exponent)),
        ("slip_deflection", format!("{:.6e}", slip.deflection)),
        ("slip_unit", format!("1e{}", slip.column_exponent - slip.slip_exponent)),
        ("slip_factor", slip.factor().to_string()),
        ("zero_printed", slip.zero_printed.clone()),
        ("zero_store", format!("{:.3e}", slip.plate_ratio)),
        ("t34_digits", close.digits.clone()),
        ("t34_close_count", close.count.to_string()),
        ("t34_close_converged", close.converged.to_string()),
        ("t34_close_min", format!("{:.0e}", close.min)),
        ("t34_close_max", format!("{:.0e}", close.max)),
        ("c3_stores", format!("{:.6e}", d.c3.0)),
        ("c3_deflection", format!("{:.6e}", d.c3.1)),
        ("c3_ratio", format!("{:.6}", d.c3.0 / d.c3.1)),
        ("t2_deviation_coal", format!("{:.1e}", inv.t2_deviation_coal)),
        ("t2_deviation_gangue", format!("{:.1e}", inv.t2_deviation_gangue)),
        ("inversion", inversion_table(&d.inversion).to_markdown()),
        ("inversion_cells", inv.cells.to_string()),
        ("inversion_spread", format!("{:.0e}", inv.spread)),
        ("d_my_coal", format!("{:+.3}", (inv.d_my_coal - 1.0) * 100.0)),
        ("d_my_gangue", format!("{:+.3}", (inv.d_my_gangue - 1.0) * 100.0)),
        ("quoted_min", q_min.0.clone()),
        ("quoted_coal_min", q_coal.0.clone()),
        ("quoted_ratio", q_ratio.0.clone()),
        ("table5", table5_table(&d.table5).to_markdown()),
        ("overall_min", format!("{:.7}", t5.overall_min)),
        ("overall_deviation", format!("{:+.2e}", (t5.overall_min - q_min.1) / q_min.1)),
        ("overall_min_body", t5.overall_body.clone()),
        ("overall_d_my_part", format!("{:+.1e}", t5.overall_rescaled)),
        ("quoted_min_digits", Printed::significant_digits(&q_min.0).to_string()),
        ("quoted_min_resolution", format!("{:.1e}", q_min.2 / q_min.1)),
        ("coal_min", format!("{:.7}", t5.coal_min)),
        ("coal_ok", (t5.coal_min > q_coal.1).to_string()),
        ("coal_ratio", format!("{:.3}", t5.coal_min / t5.gangue_min)),
        ("coal_ratio_ok", (t5.coal_min / t5.gangue_min > q_ratio.1).to_string()),
    ]
}

/// The placeholders on the figures and the solver study.
fn study_values(d: &ReproductionData) -> Vec<(&'static str, String)> {
    let first = |v: &[f64]| short(v[0]);
    let last = |v: &[f64]| short(v[v.len() - 1]);
    vec![
        ("sweep_points", SWEEP.to_string()),
        ("sweep_parts", (SWEEP - 1).to_string()),
        ("k_length", format!("{K_LENGTH_STUDY:e}")),
        ("length_factors", format!("{LENGTH_FACTORS:?}")),
        ("k_study", format!("{K_STUDY:?}")),
        ("solver_recursion_tolerance", format!("{:e}", tolerance_of(Method::paper()))),
        ("solver_bracketed_tolerance", format!("{:e}", tolerance_of(Method::default()))),
        ("solver_c_min", first(&SOLVER_COMPLIANCE_FACTORS)),
        ("solver_c_max", last(&SOLVER_COMPLIANCE_FACTORS)),
        ("solver_v_min", first(&SOLVER_VELOCITIES)),
        ("solver_v_max", last(&SOLVER_VELOCITIES)),
        ("solver_e_min", first(&SOLVER_MODULUS_RATIOS)),
        ("solver_e_max", last(&SOLVER_MODULUS_RATIOS)),
        ("c_paper", format!("{:e}", d.c_paper)),
        ("solvers", solver_table(&d.solvers).to_markdown()),
    ]
}

/// The reproduction's files from its data.
pub fn files(d: &ReproductionData) -> Result<Artifacts, Failure> {
    let mut a = Artifacts::new();
    let (cmp_md, cmp_all) = comparison_tables(&d.rows)?;
    a.add("comparison.csv", cmp_all.to_csv());
    a.add("table5.csv", table5_table(&d.table5).to_csv());
    a.add("solvers.csv", solver_table(&d.solvers).to_csv());
    let fig_md = figures::figures(&d.panels, &mut a)?;
    let mut values = finding_values(d);
    values.extend(study_values(d));
    values.extend([("comparisons", cmp_md), ("figures", fig_md)]);
    a.add("index.md", render("paper.md", PAPER_TEMPLATE, &values)?);
    // The findings the page opens with, as numbers.
    let counts = d.counts;
    a.add(
        "findings.json",
        serde_json::to_string_pretty(&serde_json::json!({
            "report": "the paper reproduced",
            "printed_numbers_compared": d.rows.len(),
            "within_print_rounding": counts[0],
            "within_explain_threshold": counts[1],
            "explained": counts[2],
            "unexplained": counts[3],
            "table3_con3_deflection_unit_factor": d.slip.factor(),
            "table2_delta_my_ratio": {
                "coal": d.inversion_findings.d_my_coal,
                "gangue 1": d.inversion_findings.d_my_gangue,
            },
            "table5_overall_min_yield_velocity_m_per_s": d.table5_findings.overall_min,
        }))?,
    );
    Ok(a)
}

/// The reproduction as a report: the paper's own scene, whatever scene is given.
pub fn report(scene: &Scene) -> Result<Artifacts, Failure> {
    study(scene, &Silent)
}

/// [`report`], reporting its progress.
pub fn study(scene: &Scene, progress: &dyn Progress) -> Result<Artifacts, Failure> {
    files(&Reproduction::compute(scene, &Settings::default(), progress)?)
}

/// Everything `impact paper` writes: Tables 2-12 and Figs. 8-19 beside the printed values.
pub fn reproduce() -> Result<Artifacts, Failure> {
    report(&Paper::new().scene)
}
