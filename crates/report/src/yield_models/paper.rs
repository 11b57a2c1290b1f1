//! The paper's three-model yield study rendered: its page (Table 2, the discretisation
//! check, Table 5, Figs. 8-9, the statements), the main report's section and finding, the
//! CSV files and the run times.

use super::{YieldSummary, FOLDER};
use crate::paper::PrintedTables;
use crate::present::plot::{line_plot, series_csv, Matrix, Scale, Series, Verdict};
use crate::present::rows::slug;
use crate::present::table::{sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use output::Artifacts;
use studies::yield_models::paper::{Minimum, PaperYieldData};
use studies::yield_models::statements::Evidence;

/// The report's prose: every number in it is a placeholder filled from the run.
const TEMPLATE: &str = include_str!("../templates/yield_models.md");
/// The main report's section and finding of the paper's study.
const PAPER_SECTION: &str = include_str!("../templates/yield/paper-section.md");
const PAPER_FINDING: &str = include_str!("../templates/yield/paper-finding.md");

/// The models' names in tables, in the data's order.
const MODELS: [&str; 3] = ["beam", "plate", "transient"];

fn verdict(v: Verdict) -> Cell {
    v.word().into()
}

/// A fraction of a length, 2 decimals.
fn frac(fraction: f64) -> String {
    format!("{fraction:.2}")
}

/// The numbers a verdict rests on, in words.
fn evidence(e: &Evidence) -> String {
    match e {
        Evidence::Extremes(parts) => parts
            .iter()
            .map(|p| format!("{}: min at x = {} L, max at x = {} L", p.body, frac(p.min_at), frac(p.max_at)))
            .collect::<Vec<_>>()
            .join("; "),
        Evidence::Rise { smallest, resolution } => {
            format!("smallest rise {}; resolution {}", sig(*smallest, 3), sig(*resolution, 2))
        }
        Evidence::Count { holds, cells, open } => format!("holds in {holds} of {cells} cells, not resolved in {open}"),
        Evidence::GangueOverCoal { largest } => format!("largest v_y(gangue 1)/v_y(coal) {}", sig(*largest, 3)),
        Evidence::Ranges(ranges) => ranges
            .iter()
            .map(|r| format!("{} {} to {}", r.body, sig(r.lo, 3), sig(r.hi, 3)))
            .collect::<Vec<_>>()
            .join("; "),
        Evidence::Located { body, condition, x, z } => {
            format!("{body}, {condition}, at (x/L, z/B) = ({}, {})", frac(*x), frac(*z))
        }
        Evidence::Minimum { coal, over_gangues } => {
            format!("coal's minimum {}; over the gangues' {}", sig(*coal, 4), sig(*over_gangues, 4))
        }
    }
}

/// Table 2 under the three models.
fn table2(d: &PaperYieldData) -> Table {
    let mut t = Table::new(
        "",
        &[
            "body",
            "condition",
            "area",
            "x (mm)",
            "printed (m/s)",
            "beam (m/s)",
            "plate (m/s)",
            "plate ± (m/s)",
            "transient (m/s)",
            "transient ± disc. (m/s)",
            "transient bracket (m/s)",
            "plate/beam - 1",
            "transient/beam - 1",
            "beam/printed - 1",
        ],
    );
    for r in &d.table2 {
        let tr = &r.transient;
        t.push(vec![
            r.body.clone().into(),
            format!("Con {}", r.condition).into(),
            r.area.into(),
            (r.x * 1e3).into(),
            r.printed.into(),
            r.beam.into(),
            r.plate.into(),
            r.plate_error.into(),
            tr.velocity.into(),
            (d.discretisation_error * tr.velocity).into(),
            tr.width.into(),
            (r.plate / r.beam - 1.0).into(),
            (tr.velocity / r.beam - 1.0).into(),
            (r.beam / r.printed - 1.0).into(),
        ]);
    }
    t
}

/// The discretisation check: three cells at the default and the finer discretisation.
fn discretisation(d: &PaperYieldData) -> Table {
    let (s, f) = (&d.transient, &d.fine);
    let mut t = Table::new(
        "",
        &[
            "body",
            "condition",
            "x (mm)",
            &format!("v_y, {} el., {} steps (m/s)", s.elements, s.steps_per_contact),
            &format!("v_y, {} el., {} steps (m/s)", f.elements, f.steps_per_contact),
            "relative change",
            "runs (fine)",
        ],
    );
    for r in &d.discretisation {
        t.push(vec![
            r.body.clone().into(),
            r.condition.clone().into(),
            (r.x * 1e3).into(),
            r.coarse.velocity.into(),
            r.fine.velocity.into(),
            r.relative.into(),
            r.fine.runs.into(),
        ]);
    }
    t
}

/// Table 5 under the three models, and the lowest of all per model against the quoted value.
fn table5(d: &PaperYieldData, quoted_min: f64) -> (Table, Table) {
    let (l, b) = (d.length, d.width);
    let mut t5 = Table::new(
        "",
        &[
            "body",
            "condition",
            "beam min (m/s)",
            "beam at x/L",
            "plate min (m/s)",
            "plate at (x/L, z/B)",
            "transient min (m/s)",
            "transient at (x/L, z/B)",
        ],
    );
    let pair = |m: &Minimum| Cell::Pair { x: m.x / l, z: m.z / b, scale: 1.0, decimals: 2 };
    for r in &d.table5 {
        let [beam, plate, transient] = &r.minima;
        t5.push(vec![
            r.body.clone().into(),
            r.condition.clone().into(),
            beam.velocity.into(),
            frac(beam.x / l).into(),
            plate.velocity.into(),
            pair(plate),
            transient.velocity.into(),
            pair(transient),
        ]);
    }
    let mut t5o = Table::new("", &["model", "lowest v_y (m/s)", "body", "condition", "at (x/L, z/B)", "/ quoted - 1"]);
    for (name, o) in MODELS.iter().zip(&d.overall) {
        let v = o.at.velocity;
        t5o.push(vec![
            (*name).into(),
            v.into(),
            o.body.clone().into(),
            o.condition.clone().into(),
            format!("({}, {})", frac(o.at.x / l), frac(o.at.z / b)).into(),
            (v / quoted_min - 1.0).into(),
        ]);
    }
    (t5, t5o)
}

/// Figs. 8-9 redone: the plots and their CSV files into `a`, and their Markdown for the
/// study's page and (linked into [`FOLDER`]) for the main report.
fn figures(d: &PaperYieldData, a: &mut Artifacts) -> (String, String) {
    let (mut figures, mut links) = (String::new(), String::new());
    let mm = |c: &[(f64, f64)]| c.iter().map(|&(x, v)| (x * 1e3, v)).collect::<Vec<_>>();
    for fig in &d.figures {
        let mut series = Vec::new();
        for c in &fig.curves {
            for (m, name) in MODELS.iter().enumerate() {
                series.push(Series::new(format!("{name}, {}", c.condition), mm(c.of(m))));
            }
        }
        let number = fig.number;
        let stem = format!("fig{number:02}-yield-{}-three-models", slug(&fig.body));
        let title = format!("Fig. {number} redone: {} yield velocity on the centreline, three models", fig.body);
        a.add(format!("{stem}.svg"), line_plot(&title, "x (mm)", "v_y (m/s)", &series, Scale::Linear));
        a.add(format!("{stem}.csv"), series_csv(&series, "x (mm)", "v_y (m/s)"));
        figures.push_str(&format!("![{title}]({stem}.svg)\n\n"));
        links.push_str(&format!("![{title}]({FOLDER}/{stem}.svg)\n\n"));
    }
    (figures, links)
}

/// The statements with each model's verdict and the numbers it rests on.
fn statements(d: &PaperYieldData) -> Table {
    let mut st =
        Table::new("", &["statement", "beam", "plate", "transient", "beam: data", "plate: data", "transient: data"]);
    for s in &d.statements {
        let mut row: Vec<Cell> = vec![s.text.clone().into()];
        row.extend(s.holds.iter().map(|&h| verdict(h)));
        row.extend(s.evidence.iter().map(|e| evidence(e).into()));
        st.push(row);
    }
    st
}

/// The numbers the page's prose quotes.
fn numbers(d: &PaperYieldData, printed: &PrintedTables) -> Vec<(&'static str, String)> {
    let s = &d.summary;
    let (cm, gm) = (&s.coal_mid, &s.gangue_mid);
    let dy = &d.cross_check;
    let pct = |v: f64| sig(100.0 * v, 3);
    let resolved = s.condition_spread <= s.pair_resolution;
    let above = s.above_beam_areas.iter().map(|a| a.to_string()).collect::<Vec<_>>().join(", ");
    vec![
        ("points_beam", d.sweep.to_string()),
        ("points_transient", d.transient_sweep.to_string()),
        ("plate_base", d.plate_base_mesh.to_string()),
        ("plate_finest", d.plate_finest_mesh.to_string()),
        ("transient_elements", d.transient.elements.to_string()),
        ("transient_steps", d.transient.steps_per_contact.to_string()),
        ("fine_elements", d.fine.elements.to_string()),
        ("fine_steps", d.fine.steps_per_contact.to_string()),
        ("root_tolerance", format!("{:e}", d.root_tolerance)),
        ("coal_mid_beam", sig(cm.beam, 6)),
        ("coal_mid_plate", sig(cm.plate, 6)),
        ("coal_mid_transient", sig(cm.transient.velocity, 6)),
        ("coal_mid_printed", sig(cm.printed, 7)),
        ("coal_mid_pb", pct(cm.plate / cm.beam - 1.0)),
        ("coal_mid_tb", pct(cm.transient.velocity / cm.beam - 1.0)),
        ("gangue_mid_beam", sig(gm.beam, 6)),
        ("gangue_mid_plate", sig(gm.plate, 6)),
        ("gangue_mid_transient", sig(gm.transient.velocity, 6)),
        ("gangue_mid_pb", pct(gm.plate / gm.beam - 1.0)),
        ("gangue_mid_tb", pct(gm.transient.velocity / gm.beam - 1.0)),
        ("pb_lo", pct(s.plate_over_beam.0)),
        ("pb_hi", pct(s.plate_over_beam.1)),
        ("tb_lo", pct(s.transient_over_beam.0)),
        ("tb_hi", pct(s.transient_over_beam.1)),
        ("tp_lo", pct(s.transient_over_plate.0)),
        ("tp_hi", pct(s.transient_over_plate.1)),
        ("width_lo", sig(s.bracket_width.0, 2)),
        ("width_hi", sig(s.bracket_width.1, 2)),
        ("plate_err_lo", sig(s.plate_error.0, 2)),
        ("plate_err_hi", sig(s.plate_error.1, 2)),
        ("disc_rel", sig(d.discretisation_error, 2)),
        ("cells_t2", d.table2.len().to_string()),
        ("runs_t2", s.table2_runs.to_string()),
        ("between", s.between.to_string()),
        ("above_beam_cells", s.above_beam_cells.to_string()),
        ("above_beam_areas", if above.is_empty() { "none".into() } else { above }),
        ("cond_spread", sig(s.condition_spread, 2)),
        ("pair_resolution", sig(s.pair_resolution, 2)),
        ("spread_vs_disc", (if resolved { "within" } else { "beyond" }).to_string()),
        ("resolves", (if resolved { "does not resolve" } else { "resolves" }).to_string()),
        ("runs_per_cell", format!("{:.1}", s.table2_runs as f64 / d.table2.len() as f64)),
        ("dy_ours", sig(dy.ours.velocity, 8)),
        ("dy_theirs", sig(dy.dynamic_yield.yield_velocity, 8)),
        ("dy_diff", sig(dy.dynamic_yield.yield_velocity / dy.ours.velocity - 1.0, 2)),
        (
            "dy_width",
            sig(dy.dynamic_yield.yield_velocity_error.unwrap_or(f64::NAN) / dy.dynamic_yield.yield_velocity, 2),
        ),
        ("dy_runs", dy.ours.runs.to_string()),
        ("grid_x", d.grid.0.to_string()),
        ("grid_z", d.grid.1.to_string()),
        ("candidates", d.candidates.to_string()),
        ("quoted_min", printed.section4d.min_yield_velocity.text.clone()),
        ("rigid_gangue", sig(s.rigid_gangue1, 6)),
        ("rigid_gangue2", sig(s.rigid_gangue2, 6)),
        ("statements_count", d.statements.len().to_string()),
        ("held_beam", s.held[0].to_string()),
        ("held_plate", s.held[1].to_string()),
        ("held_transient", s.held[2].to_string()),
        ("unresolved_beam", s.unresolved[0].to_string()),
        ("unresolved_plate", s.unresolved[1].to_string()),
        ("unresolved_transient", s.unresolved[2].to_string()),
        ("transient_cells", d.transient_cells.to_string()),
        ("transient_runs", d.transient_runs.to_string()),
    ]
}

/// The main report's section and finding: the statements' verdicts without their data.
fn summary(d: &PaperYieldData, values: &[(&str, String)], figure_links: String) -> Result<YieldSummary, Failure> {
    let mut verdicts = Table::new("", &["statement", "beam", "plate", "transient"]);
    for s in &d.statements {
        let mut row: Vec<Cell> = vec![s.text.clone().into()];
        row.extend(s.holds.iter().map(|&h| verdict(h)));
        verdicts.push(row);
    }
    let pick = |names: &[&str]| -> Vec<(&str, String)> {
        values.iter().filter(|(n, _)| names.contains(n)).map(|(n, v)| (*n, v.clone())).collect()
    };
    let mut section_values = pick(&[
        "coal_mid_beam",
        "coal_mid_plate",
        "coal_mid_transient",
        "coal_mid_pb",
        "coal_mid_tb",
        "tp_lo",
        "tp_hi",
        "table5",
        "held_beam",
        "held_plate",
        "held_transient",
        "unresolved_plate",
        "unresolved_transient",
        "statements_count",
    ]);
    section_values.push(("verdicts", verdicts.to_markdown()));
    section_values.push(("figures", figure_links));
    section_values.push(("folder", FOLDER.to_string()));
    let mut finding_values = pick(&[
        "coal_mid_beam",
        "coal_mid_plate",
        "coal_mid_transient",
        "coal_mid_pb",
        "coal_mid_tb",
        "tp_lo",
        "tp_hi",
        "held_transient",
        "unresolved_transient",
        "statements_count",
    ]);
    finding_values.push(("folder", FOLDER.to_string()));
    Ok(YieldSummary {
        section: render("yield/paper-section.md", PAPER_SECTION, &section_values)?,
        finding: render("yield/paper-finding.md", PAPER_FINDING, &finding_values)?,
    })
}

/// The run times, kept apart from the deterministic pages.
fn timing(d: &PaperYieldData) -> String {
    let t = &d.timing;
    format!(
        "# Run time of the three-model yield study\n\nWall-clock on this machine, the transient roots of each part on {} threads; the only page of the study that changes between runs.\n\n| part | s |\n|---|---|\n| quasi-static beam and plate (every point) | {:.1} |\n| Table 2, transient roots | {:.1} |\n| discretisation check ({} cells at {} elements, {} steps) | {:.1} |\n| `dynamic_yield` cross-check (one cell) | {:.1} |\n| Table 5, transient candidates | {:.1} |\n| Figs. 8-9, transient curves | {:.1} |\n| **total** | **{:.1}** |\n\n{} transient roots, {} transient runs at the default discretisation; {} runs of the reduced model placed their brackets (its modal models, one per support set, are built by the first roots, in Table 2's time).\n",
        t.threads,
        t.quasi_static,
        t.table2,
        d.discretisation.len(),
        d.fine.elements,
        d.fine.steps_per_contact,
        t.discretisation,
        t.cross_check,
        t.table5,
        t.figures,
        t.total,
        d.transient_cells,
        d.transient_runs,
        d.reduced_runs
    )
}

/// The study's files and what the main report shows of it.
pub(super) fn files(d: &PaperYieldData, printed: &PrintedTables) -> Result<(Artifacts, YieldSummary), Failure> {
    let mut a = Artifacts::new();
    let (figures, figure_links) = figures(d, &mut a);
    let st = statements(d);
    let matrix = Matrix {
        title: "The paper's yield statements under three models".into(),
        columns: MODELS.iter().map(|m| m.to_string()).collect(),
        rows: d.statements.iter().map(|s| s.text.clone()).collect(),
        cells: d.statements.iter().map(|s| s.holds.to_vec()).collect(),
    };
    a.add("statements.svg", matrix.svg());
    let (t2t, disc) = (table2(d), discretisation(d));
    let (t5, t5o) = table5(d, printed.section4d.min_yield_velocity.printed.value);
    let mut values = numbers(d, printed);
    values.extend([
        ("table2", t2t.to_markdown()),
        ("discretisation", disc.to_markdown()),
        ("table5", t5.to_markdown()),
        ("table5_overall", t5o.to_markdown()),
        ("figures", figures),
        ("statements", st.to_markdown()),
    ]);
    let summary = summary(d, &values, figure_links)?;
    a.add("index.md", render("yield_models.md", TEMPLATE, &values)?);
    a.add("table2-three-models.csv", t2t.to_csv());
    let t5 = t5
        .csv_name("plate at (x/L, z/B)", &["plate_at_x_per_L", "plate_at_z_per_B"])
        .csv_name("transient at (x/L, z/B)", &["transient_at_x_per_L", "transient_at_z_per_B"]);
    a.add("table5-three-models.csv", t5.to_csv());
    let st = st
        .csv_name("beam", &["beam_verdict"])
        .csv_name("plate", &["plate_verdict"])
        .csv_name("transient", &["transient_verdict"])
        .csv_name("beam: data", &["beam_evidence"])
        .csv_name("plate: data", &["plate_evidence"])
        .csv_name("transient: data", &["transient_evidence"]);
    a.add("statements.csv", st.to_csv());
    a.add("transient-discretisation.csv", disc.to_csv());
    a.add("timing.md", timing(d));
    Ok((a, summary))
}
