//! The paper's section IV reproduced: Tables 2-12 beside the printed values and the curves
//! of Figures 8-19, rendered from the comparisons of `studies::paper`.

use crate::present::plot::{line_plot, Scale, Series};
use crate::present::table::{Cell, Table};
use analytic::{beam_compliance, evaluate, Condition, Method, Plate, Response, Sphere};
use coupled::plan::both_solvers;
use output::Artifacts;
use scene::{even_points, Scene};
use std::fmt::Write as _;
pub use studies::paper::*;

use crate::Failure;

mod figures;
use figures::figures;

/// The comparison tables, one per printed table, with a summary.
/// How many comparisons got each verdict: within print, close, explained, unexplained.
type Counts = [usize; 4];

fn comparison_markdown(
    paper: &Paper,
    printed: &PrintedTables,
    rows: &[Comparison],
    inversion: &[(String, Vec<f64>)],
) -> (String, Table, Counts) {
    let explain = explain(paper, printed, inversion);
    let mut md = String::new();
    let mut all = Table::new(
        "",
        &[
            "table",
            "case",
            "quantity",
            "printed",
            "equations (converged)",
            "rel. dev. (converged)",
            "recursion ğ=1e-6",
            "rel. dev. (recursion)",
            "verdict",
        ],
    );
    let mut tables: Vec<&str> = rows.iter().map(|r| r.table.as_str()).collect();
    tables.dedup();
    let mut counts = [0usize; 4];
    for t in tables {
        let mut tab = Table::new(
            "",
            &[
                "case",
                "quantity",
                "printed",
                "equations (converged)",
                "rel. dev. (converged)",
                "recursion ğ=1e-6",
                "rel. dev. (recursion)",
                "verdict",
            ],
        );
        for r in rows.iter().filter(|r| r.table == t) {
            let verdict = r.verdict(&explain);
            let v = match &verdict {
                Verdict::WithinPrint => {
                    counts[0] += 1;
                    "within print rounding".to_string()
                }
                Verdict::Close => {
                    counts[1] += 1;
                    format!("≤ {EXPLAIN_ABOVE:e}")
                }
                Verdict::Explained(s) => {
                    counts[2] += 1;
                    s.clone()
                }
                Verdict::Unexplained => {
                    counts[3] += 1;
                    "UNEXPLAINED".to_string()
                }
            };
            let rec = r.recursion.map_or(Cell::Empty, Cell::Num);
            let rec_dev = r.recursion.map_or(Cell::Empty, |x| Cell::Num(r.deviation(x)));
            let row = vec![
                Cell::from(r.case.clone()),
                r.quantity.clone().into(),
                r.printed_text.clone().into(),
                Cell::Num(r.equations),
                Cell::Num(r.deviation(r.equations)),
                rec,
                rec_dev,
                v.into(),
            ];
            let mut full = vec![Cell::from(t)];
            full.extend(row.iter().cloned());
            all.push(full);
            tab.push(row);
        }
        let _ = writeln!(md, "\n### {t}\n\n{}", tab.to_markdown());
    }
    (md, all, counts)
}

/// How well each ğ reproduces the printed responses (Tables 3, 4, 6-12): evidence for the
/// paper's stopping residual.
fn tolerance_evidence(paper: &Paper, printed: &PrintedTables) -> Result<(Table, f64), PrintedError> {
    let mut t = Table::new(
        "",
        &[
            "ğ of eq. 18",
            "max |reproduced - printed| in half units of the last printed digit",
            "cells within print rounding",
            "cells",
        ],
    );
    let plate = paper.scene.plate;
    let mid = plate.length() / 2.0;
    // Largest relative deviation of the converged root from print over the cells printed
    // to 7 or more significant digits.
    let mut converged_worst: f64 = 0.0;
    for tol in [f64::NAN, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8] {
        // Tables 6-8 and 11 print 8 decimals, finer than Tables 3-4, so they identify ğ best.
        let mut worst: f64 = 0.0;
        let mut worst_relative: f64 = 0.0;
        let (mut ok, mut n) = (0usize, 0usize);
        let mut check = |ours: f64, cell: &PrintedText, scale: f64| {
            let p = cell.printed;
            let v = ours / scale;
            worst = worst.max((v - p.value).abs() / p.half_ulp);
            // A relative deviation means something only where print resolves it.
            if Printed::significant_digits(&cell.text) >= 7 {
                worst_relative = worst_relative.max(((v - p.value) / p.value).abs());
            }
            ok += usize::from((v - p.value).abs() <= p.half_ulp * (1.0 + 1e-9) + 1e-12 * p.value.abs());
            n += 1;
        };
        let solve = |body: &Sphere, cond: usize| {
            let c = beam_compliance(&plate, Paper::condition(cond, paper.k_t), mid).unwrap();
            let imp = paper.impact(&plate, body, V_TABLE6);
            let m = if tol.is_nan() { CONVERGED } else { Method::Recursion { tolerance: tol, max_iterations: 200 } };
            evaluate(&imp, &c, imp.balance(c.total()).attempt(m))
        };
        for tab in &printed.tables6_8 {
            for row in &tab.rows {
                let r = solve(body(paper, &row.body)?, tab.condition);
                for (c, cell) in tab.columns.iter().zip(&row.values) {
                    check(c.quantity.of(&r), cell, c.scale);
                }
            }
        }
        for row in &printed.table11.rows {
            let b = body(paper, &row.body)?;
            for (c, cell) in printed.table11.columns.iter().zip(&row.values) {
                check(c.quantity.of(&solve(b, c.condition)), cell, 1.0);
            }
        }
        let label = if tol.is_nan() {
            converged_worst = worst_relative;
            format!("converged ({CONVERGED_TOLERANCE:e})")
        } else {
            format!("{tol:e}")
        };
        t.push(vec![label.into(), worst.into(), ok.into(), n.into()]);
    }
    Ok((t, converged_worst))
}

// ------------------------------------------------------------------ Table 5 and solvers

/// Minimum yield velocity over the 101 points for every body and condition (Table 5,
/// whose values the text does not carry; section IV-D quotes the overall minimum).
fn table5(paper: &Paper) -> (Table, Vec<Minimum>) {
    let mut t = Table::new("", &["body", "condition", "min v_y (m/s)", "at x (mm)"]);
    let mut minima = Vec::new();
    for b in paper.bodies() {
        for n in 1..=3 {
            let (x, v) = even_points(paper.scene.plate.length(), SWEEP)
                .into_iter()
                .map(|x| (x, paper.yield_velocity(b, Paper::condition(n, paper.k_t), x)))
                .fold((0.0, f64::INFINITY), |a, p| if p.1 < a.1 { p } else { a });
            minima.push(Minimum { v, body: b.name.clone(), condition: n, x });
            t.push(vec![b.name.clone().into(), format!("Con {n}").into(), v.into(), (x * 1e3).into()]);
        }
    }
    (t, minima)
}

/// A minimum yield velocity of Table 5 and where it occurs.
struct Minimum {
    v: f64,
    body: String,
    condition: usize,
    x: f64,
}

/// Compliance factors, velocities (m/s) and sphere-to-plate modulus ratios of the solver
/// study: from no plate compliance to far beyond the paper's, and from slow to fast.
const SOLVER_COMPLIANCE_FACTORS: [f64; 5] = [0.0, 1e-3, 1.0, 1e3, 1e6];
const SOLVER_VELOCITIES: [f64; 4] = [1e-6, 1e-3, 1e-1, 10.0];
const SOLVER_MODULUS_RATIOS: [f64; 4] = [1e-3, 1e-2, 1.0, 1e3];

/// The paper's recursion against the bracketed solver on stiff and extreme cases.
pub fn solver_study(paper: &Paper) -> Table {
    let plate = paper.scene.plate;
    let c_paper = beam_compliance(&plate, Condition::BothFixed, plate.length() / 2.0).unwrap().total();
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
    let e_plate = plate.material().youngs_modulus();
    for factor in SOLVER_COMPLIANCE_FACTORS {
        for v in SOLVER_VELOCITIES {
            for ratio in SOLVER_MODULUS_RATIOS {
                let m = analytic::Elastic::new(ratio * e_plate, 0.28).unwrap();
                let body =
                    Sphere::new("s", paper.coal.density(), paper.coal.radius(), m, paper.coal.strength()).unwrap();
                let imp = paper.impact(&plate, &body, v);
                let (r, b) = both_solvers(&imp, factor * c_paper);
                t.push(vec![
                    factor.into(),
                    v.into(),
                    ratio.into(),
                    r.iterations.into(),
                    r.residual.into(),
                    b.iterations.into(),
                    b.residual.into(),
                    ((r.delta - b.delta).abs() / b.delta).into(),
                    {
                        let yes = r.converged && b.converged;
                        Cell::Flag { yes, shown: if yes { "yes" } else { "NO" } }
                    },
                ]);
            }
        }
    }
    t
}

// ------------------------------------------------------------------ the report

/// The report's prose; every number in it is a placeholder filled from the run.
const PAPER_TEMPLATE: &str = include_str!("../templates/paper.md");

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

/// Everything `impact paper` writes.
/// The reproduction as a report: the paper's own scene, whatever scene is given.
pub fn report(_scene: &Scene) -> Result<Artifacts, Failure> {
    reproduce()
}

/// Reproduces Tables 2-12 and Figs. 8-19 beside the printed values.
pub fn reproduce() -> Result<Artifacts, Failure> {
    let paper = Paper::new();
    let printed = PrintedTables::embedded()?;
    let mut a = Artifacts::new();
    let rows = comparisons(&paper, &printed)?;
    let inversion = yield_inversion(&paper, &printed)?;
    let (cmp_md, cmp_all, counts) = comparison_markdown(&paper, &printed, &rows, &inversion);
    a.add("comparison.csv", cmp_all.to_csv());

    let mut inv = Table::new("", &["body", "cells", "mean δ_my ratio", "min", "max"]);
    for (name, r) in &inversion {
        let (lo, hi) = r.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
        inv.push(vec![name.clone().into(), r.len().into(), mean(r).into(), lo.into(), hi.into()]);
    }
    let (evidence, converged_worst) = tolerance_evidence(&paper, &printed)?;
    let (t5, minima) = table5(&paper);
    a.add("table5.csv", t5.to_csv());
    let solvers = solver_study(&paper);
    a.add("solvers.csv", solvers.to_csv());

    let panels = figures(&paper);
    let mut fig_md = String::new();
    let mut last_fig = String::new();
    for p in &panels {
        let svg = line_plot(&p.title, "Impact position x (mm)", &p.y_label, &p.series, p.scale);
        a.add(format!("{}.svg", p.stem), svg);
        a.add(format!("{}.csv", p.stem), crate::present::plot::series_csv(&p.series, "x (mm)", &p.y_label));
        let fig = p.stem[..5].to_string();
        if fig != last_fig {
            let _ = writeln!(fig_md, "\n### Fig. {}\n", fig[3..].trim_start_matches('0'));
            last_fig = fig;
        }
        let _ = writeln!(fig_md, "![{}]({}.svg)", p.title, p.stem);
    }

    let plate = paper.scene.plate;
    let l = plate.length();
    let slip = unit_slip(&paper, &printed)?;
    let c3 = beam_compliance(&plate, Paper::condition(3, paper.k_t), l)?;
    let close = close_cells(&rows, &explain(&paper, &printed, &inversion));
    let inv_found = inversion_findings(&rows, &inversion)?;
    let inversion_mean = |name: &str| inversion.iter().find(|(n, _)| n == name).map(|(_, r)| mean(r));
    let no_inversion =
        |name: &str| PrintedError::Shape { table: "Table 2".into(), what: format!("no rows for {name}") };

    // Table 5 against the values section IV-D quotes.
    let quoted = &printed.section4d;
    let (q_min, q_coal, q_ratio) =
        (quoted.min_yield_velocity.printed, quoted.coal_min_exceeds.printed, quoted.coal_over_gangue_exceeds.printed);
    let coal_min = t5.rows.iter().filter(|r| r[0] == Cell::from("coal")).filter_map(|r| match r[2] {
        Cell::Num(v) => Some(v),
        _ => None,
    });
    let coal_min = coal_min.fold(f64::INFINITY, f64::min);
    let gangue_min = t5
        .rows
        .iter()
        .filter(|r| r[0] != Cell::from("coal"))
        .filter_map(|r| if let Cell::Num(v) = r[2] { Some(v) } else { None })
        .fold(f64::INFINITY, f64::min);
    let overall_min = minima.iter().map(|m| m.v).fold(f64::INFINITY, f64::min);
    // The δ_my factor is known only for the bodies of Table 2; the gangue minima agree to
    // rounding, so the smallest minimum among those bodies stands for the overall one.
    let known = minima.iter().filter(|m| inversion_mean(&m.body).is_some());
    let overall = known.min_by(|a, b| a.v.total_cmp(&b.v)).ok_or_else(|| no_inversion("any body of Table 5"))?;
    let overall_factor = inversion_mean(&overall.body).ok_or_else(|| no_inversion(&overall.body))?;
    let overall_rescaled = paper.yield_velocity_scaled(
        &plate,
        body(&paper, &overall.body)?,
        Paper::condition(overall.condition, paper.k_t),
        overall.x,
        overall_factor,
    );

    let c_paper = beam_compliance(&plate, Condition::BothFixed, l / 2.0)?.total();
    let values: Vec<(&str, String)> = vec![
        ("converged_tolerance", format!("{CONVERGED_TOLERANCE:e}")),
        ("paper_tolerance", format!("{PAPER_RECURSION_TOLERANCE:e}")),
        ("converged_max_deviation", format!("{converged_worst:.0e}")),
        ("evidence", evidence.to_markdown()),
        ("explain_above", format!("{EXPLAIN_ABOVE:e}")),
        ("compared", rows.len().to_string()),
        ("within_print", counts[0].to_string()),
        ("close", counts[1].to_string()),
        ("explained", counts[2].to_string()),
        ("unexplained", counts[3].to_string()),
        ("comparisons", cmp_md),
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
        ("c3_stores", format!("{:.6e}", c3.total())),
        ("c3_deflection", format!("{:.6e}", c3.deflection_per_unit_load())),
        ("c3_ratio", format!("{:.6}", c3.total() / c3.deflection_per_unit_load())),
        ("t2_deviation_coal", format!("{:.1e}", inv_found.t2_deviation_coal)),
        ("t2_deviation_gangue", format!("{:.1e}", inv_found.t2_deviation_gangue)),
        ("inversion", inv.to_markdown()),
        ("inversion_cells", inv_found.cells.to_string()),
        ("inversion_spread", format!("{:.0e}", inv_found.spread)),
        ("d_my_coal", format!("{:+.3}", (inv_found.d_my_coal - 1.0) * 100.0)),
        ("d_my_gangue", format!("{:+.3}", (inv_found.d_my_gangue - 1.0) * 100.0)),
        ("quoted_min", quoted.min_yield_velocity.text.clone()),
        ("quoted_coal_min", quoted.coal_min_exceeds.text.clone()),
        ("quoted_ratio", quoted.coal_over_gangue_exceeds.text.clone()),
        ("table5", t5.to_markdown()),
        ("overall_min", format!("{overall_min:.7}")),
        ("overall_deviation", format!("{:+.2e}", (overall_min - q_min.value) / q_min.value)),
        ("overall_min_body", overall.body.clone()),
        ("overall_d_my_part", format!("{:+.1e}", overall_rescaled / overall.v - 1.0)),
        ("quoted_min_digits", Printed::significant_digits(&quoted.min_yield_velocity.text).to_string()),
        ("quoted_min_resolution", format!("{:.1e}", q_min.half_ulp / q_min.value)),
        ("coal_min", format!("{coal_min:.7}")),
        ("coal_ok", (coal_min > q_coal.value).to_string()),
        ("coal_ratio", format!("{:.3}", coal_min / gangue_min)),
        ("coal_ratio_ok", (coal_min / gangue_min > q_ratio.value).to_string()),
        ("sweep_points", SWEEP.to_string()),
        ("sweep_parts", (SWEEP - 1).to_string()),
        ("k_length", format!("{K_LENGTH_STUDY:e}")),
        ("length_factors", format!("{LENGTH_FACTORS:?}")),
        ("k_study", format!("{K_STUDY:?}")),
        ("figures", fig_md),
        ("solver_recursion_tolerance", format!("{:e}", tolerance_of(Method::paper()))),
        ("solver_bracketed_tolerance", format!("{:e}", tolerance_of(Method::default()))),
        ("solver_c_min", short(SOLVER_COMPLIANCE_FACTORS[0])),
        ("solver_c_max", short(SOLVER_COMPLIANCE_FACTORS[SOLVER_COMPLIANCE_FACTORS.len() - 1])),
        ("solver_v_min", short(SOLVER_VELOCITIES[0])),
        ("solver_v_max", short(SOLVER_VELOCITIES[SOLVER_VELOCITIES.len() - 1])),
        ("solver_e_min", short(SOLVER_MODULUS_RATIOS[0])),
        ("solver_e_max", short(SOLVER_MODULUS_RATIOS[SOLVER_MODULUS_RATIOS.len() - 1])),
        ("c_paper", format!("{c_paper:e}")),
        ("solvers", solvers.to_markdown()),
    ];
    a.add("index.md", crate::template::render("paper.md", PAPER_TEMPLATE, &values)?);
    // The findings the page opens with, as numbers.
    a.add(
        "findings.json",
        serde_json::to_string_pretty(&serde_json::json!({
            "report": "the paper reproduced",
            "printed_numbers_compared": rows.len(),
            "within_print_rounding": counts[0],
            "within_explain_threshold": counts[1],
            "explained": counts[2],
            "unexplained": counts[3],
            "table3_con3_deflection_unit_factor": slip.factor(),
            "table2_delta_my_ratio": { "coal": inv_found.d_my_coal, "gangue 1": inv_found.d_my_gangue },
            "table5_overall_min_yield_velocity_m_per_s": overall_min,
        }))?,
    );
    Ok(a)
}
