//! `impact compare`: the paper's beam model and the plate FE model through the same energy
//! balance and yield model, and where and by how much they differ.
//!
//! The comparison computes in [`studies::comparison`]; here it becomes the page (findings,
//! figures, detail tables, the studies the scene names, the method), its CSV files,
//! `findings.json` and `results.json`.

mod map_figures;
mod shear;
mod tables;

pub use studies::comparison::{
    error_vs_time, extreme_cases, map_points, maps, maps_from, pair, pair_on, scene_points, width_dependence,
    ComparisonData, ErrorVsTime, Maps, Pair, PointFinding, WidthRow, EXTREME_SPRINGS, EXTREME_THICKNESSES,
    EXTREME_VELOCITIES, INNER, WIDTH_RATIOS,
};
pub use studies::settings::{AREAS, BASE_MESH, LEVELS, MAP_X, MAP_Z};
pub use tables::{error_table, extreme_table, pair_tables, width_table};

use crate::present::plot::{Axis, Plot, Series};
use crate::present::rows::slug;
use crate::present::table::{percent, sig};
use crate::template::render;
use crate::Failure;
use output::Artifacts;
use scene::Scene;
use studies::comparison::PeakCase;
use studies::progress::{Progress, Silent};
use studies::settings::Settings;
use studies::study::{Comparison, Study};

// The report's prose, one template per section (sections are written only when the scene
// asks for them; the map section repeats per support set).
const HEAD: &str = include_str!("../templates/comparison/head.md");
const WIDTH: &str = include_str!("../templates/comparison/width.md");
const EXTREME: &str = include_str!("../templates/comparison/extreme.md");
const ERROR_PAGE: &str = include_str!("../templates/comparison/error-vs-time-page.md");
const ERROR_LINK: &str = include_str!("../templates/comparison/error-vs-time.md");
const RECOMMENDED: &str = include_str!("../templates/comparison/recommended.md");
const RECOMMENDED_MESH: &str = include_str!("../templates/comparison/recommended-mesh.md");
const RECOMMENDED_FINER: &str = include_str!("../templates/comparison/recommended-finer.md");
const FIELD: &str = include_str!("../templates/comparison/field.md");
const METHOD_TEXT: &str = include_str!("../templates/comparison/method.md");
const SUMMARY: &str = include_str!("../templates/comparison/summary.md");
const DETAIL_TABLES: &str = include_str!("../templates/comparison/detail-tables.md");
const DETAIL_TABLE: &str = include_str!("../templates/comparison/detail-table.md");
const FINDING_COMPLIANCE: &str = include_str!("../templates/comparison/finding-compliance.md");
const FINDING_ENDS: &str = include_str!("../templates/comparison/finding-ends.md");
const FINDING_FORCE: &str = include_str!("../templates/comparison/finding-force.md");
const FINDING_FORCE_YIELD: &str = include_str!("../templates/comparison/finding-force-yield.md");
const FINDING_FIELD: &str = include_str!("../templates/comparison/finding-field.md");
const FINDING_WIDTH: &str = include_str!("../templates/comparison/finding-width.md");

/// The findings and numbers of `findings.json`, as the page's sections add them.
type Numbers = serde_json::Map<String, serde_json::Value>;

/// A round number as the prose writes it: small integers as they are, the rest in
/// exponent form (`1e15`).
fn short(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < 100.0 {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// What the studies nested beside the comparison add to its page: lines among its findings
/// and sections after its figures (links relative to the page).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StudySections {
    /// Markdown bullet lines, each ending in a newline.
    pub findings: Vec<String>,
    /// Markdown sections.
    pub sections: String,
}

/// Everything `impact compare` writes for `scene`: the findings first (computed here), the
/// figures, the detail tables, the studies the scene names, the method last.
pub fn report(scene: &Scene) -> Result<Artifacts, Failure> {
    report_with(scene, &StudySections::default(), &Silent)
}

/// [`report`] with the findings and sections of the studies nested beside it.
pub fn report_with(scene: &Scene, extra: &StudySections, progress: &dyn Progress) -> Result<Artifacts, Failure> {
    files(scene, &Comparison::compute(scene, &Settings::default(), progress)?, extra)
}

/// The comparison's files from its data.
pub fn files(scene: &Scene, d: &ComparisonData, extra: &StudySections) -> Result<Artifacts, Failure> {
    let mut a = Artifacts::new();
    let mut numbers = Numbers::new();
    let levels: Vec<String> = d.mesh_levels.iter().map(|c| format!("{} x {} ({} DOFs)", c.nx, c.nz, c.dofs)).collect();
    let head = render(
        "comparison/head.md",
        HEAD,
        &[("scene", scene.name.clone()), ("description", scene.description.clone())],
    )?;
    let method = render("comparison/method.md", METHOD_TEXT, &[("mesh_levels", levels.join(" and "))])?;
    let mut findings = Vec::new();
    for f in &d.points {
        findings.extend(point_finding(f, &mut numbers)?);
    }
    let mut figures = String::new();
    if let Some(peak) = &d.peak {
        let (md_field, w_svg, s_svg, finding) = peak_field_section(scene, peak)?;
        a.add("field-w.svg", w_svg);
        a.add("field-stress.svg", s_svg);
        figures.push_str(&md_field);
        findings.push(finding);
    }
    let mut tables = String::new();
    for t in pair_tables(scene, &d.beam, &d.plate) {
        a.add(format!("table-{}.csv", slug(&t.title)), t.to_csv());
        tables.push_str(&render(
            "comparison/detail-table.md",
            DETAIL_TABLE,
            &[("title", t.title.clone()), ("table", t.to_markdown())],
        )?);
    }
    // No detail table without a table; and a scene whose every study is nested beside the
    // comparison (the tail beam, say) compares nothing of beam against plate, so it has no
    // method of that comparison to state.
    let tables = if tables.is_empty() {
        String::new()
    } else {
        render("comparison/detail-tables.md", DETAIL_TABLES, &[("tables", tables)])?
    };
    let compared = !tables.is_empty()
        || !d.points.is_empty()
        || d.peak.is_some()
        || d.maps.is_some()
        || d.width.is_some()
        || d.extremes.is_some()
        || d.error_vs_time.is_some()
        || d.shear.is_some();
    let method = if compared { method } else { String::new() };
    if let Some(mp) = &d.maps {
        figures.push_str(&map_figures::section(scene, mp, &d.map_findings, &mut a, &mut findings, &mut numbers)?);
    }
    let studies = study_sections(scene, d, &mut a, &mut findings)?;
    findings.extend(extra.findings.iter().cloned());
    let summary = render("comparison/summary.md", SUMMARY, &[("findings", findings.join(""))])?;
    a.add("index.md", [head, summary, figures, extra.sections.clone(), tables, studies, method].concat());
    a.add(
        "findings.json",
        serde_json::to_string_pretty(&serde_json::json!({
            "report": "beam against plate",
            "findings": findings.iter().map(|f| f.trim().trim_start_matches("- ").replace("**", "")).collect::<Vec<_>>(),
            "numbers": numbers,
        }))?,
    );
    let levels: Vec<serde_json::Value> =
        d.mesh_levels.iter().map(|c| serde_json::json!({ "nx": c.nx, "nz": c.nz, "dofs": c.dofs })).collect();
    let json = serde_json::json!({ "scene": scene.name, "beam": d.beam, "plate": d.plate, "mesh_levels": levels });
    a.add("results.json", serde_json::to_string_pretty(&json)?);
    Ok(a)
}

/// The findings of one support set at the scene's points (C_plate/C_beam - 1 with the
/// supported-end points where the beam's C is 0; P_max and v_y, plate against beam), and
/// their numbers into `numbers`.
fn point_finding(f: &PointFinding, numbers: &mut Numbers) -> Result<Vec<String>, Failure> {
    let mut out = Vec::new();
    if let Some((lo, hi)) = f.compliance {
        let ends = if f.ends > 0 {
            let count = if f.ends == 1 {
                "1 supported-end point".to_string()
            } else {
                format!("{} supported-end points", f.ends)
            };
            let values = [("count", count), ("plate_c", sig(f.ends_compliance, 3))];
            render("comparison/finding-ends.md", FINDING_ENDS, &values)?.trim_end().to_string()
        } else {
            String::new()
        };
        out.push(render(
            "comparison/finding-compliance.md",
            FINDING_COMPLIANCE,
            &[
                ("condition", f.condition.clone()),
                ("points", f.points.to_string()),
                ("lowest", percent(lo)),
                ("highest", percent(hi)),
                ("fe_error", percent(f.fe_error).trim_start_matches('+').to_string()),
                ("ends", ends),
            ],
        )?);
    }
    if let Some((flo, fhi)) = f.contact_force {
        // The yield clause only where the scene asked for yield velocities.
        let yield_text = match f.yield_velocity {
            None => String::new(),
            Some((ylo, yhi)) => render(
                "comparison/finding-force-yield.md",
                FINDING_FORCE_YIELD,
                &[("lowest", percent(ylo)), ("highest", percent(yhi))],
            )?,
        };
        out.push(render(
            "comparison/finding-force.md",
            FINDING_FORCE,
            &[
                ("condition", f.condition.clone()),
                ("lowest", percent(flo)),
                ("highest", percent(fhi)),
                ("cases", f.force_cases.to_string()),
                ("yield", yield_text),
            ],
        )?);
    }
    // A range over no cases is null, not a pair of infinities.
    let span = |r: Option<(f64, f64)>| r.map_or(serde_json::Value::Null, |(a, b)| serde_json::json!([a, b]));
    numbers.insert(
        format!("{}: plate/beam - 1 at the scene's points", f.condition),
        serde_json::json!({
            "compliance": span(f.compliance), "contact_force": span(f.contact_force),
            "yield_velocity": span(f.yield_velocity),
            "fe_error_relative": f.fe_error, "ends_with_beam_c_zero": f.ends,
            "plate_c_at_those_ends_max": f.ends_compliance,
        }),
    );
    Ok(out)
}

/// The plate at the maximum force of the impact of [`PeakCase`], as the plate FE model answers
/// it: the section, the two figures and the finding.
fn peak_field_section(scene: &Scene, peak: &PeakCase) -> Result<(String, String, String, String), Failure> {
    let cond = scene.conditions.iter().find(|c| c.name == peak.condition).ok_or("the peak case's support set")?;
    let (x, z) = peak.point;
    let what =
        format!("{} at {} m/s on {} at ({:.1}, {:.1}) mm", peak.body, peak.velocity, cond.name, x * 1e3, z * 1e3);
    let validity = crate::present::rows::validity_text(&peak.validity);
    let caveat = crate::field::quasi_static_caveat(&peak.validity)?;
    let f = crate::plate_field::peak_field(scene, cond, x, z, peak.p_max, &[what.clone(), validity.clone()])?;
    let finding = render(
        "comparison/finding-field.md",
        FINDING_FIELD,
        &[
            ("what", what.clone()),
            ("validity", validity.clone()),
            ("w_max", sig(f.data.w_max * 1e6, 3)),
            ("stress_max", sig(f.data.stress_max / 1e3, 3)),
            ("caveat", caveat.clone()),
        ],
    )?;
    let md = render(
        "comparison/field.md",
        FIELD,
        &[
            ("what", what),
            ("validity", validity),
            ("caveat", caveat),
            ("p_max", sig(peak.p_max, 3)),
            ("mesh", crate::plate_field::FIELD_ELEMENTS.to_string()),
            ("w_max", sig(f.data.w_max * 1e6, 3)),
            ("w_x", format!("{:.1}", f.data.w_max_at.0 * 1e3)),
            ("w_z", format!("{:.1}", f.data.w_max_at.1 * 1e3)),
            ("left_out", f.data.left_out.to_string()),
            ("stress_max", sig(f.data.stress_max / 1e3, 3)),
            ("s_x", format!("{:.1}", f.data.stress_max_at.0 * 1e3)),
            ("s_z", format!("{:.1}", f.data.stress_max_at.1 * 1e3)),
        ],
    )?;
    Ok((md, f.deflection_svg, f.stress_svg, finding))
}

/// The sections of the studies the scene names (width, extreme cases, error against time),
/// their files and the width finding.
fn study_sections(
    scene: &Scene,
    d: &ComparisonData,
    a: &mut Artifacts,
    findings: &mut Vec<String>,
) -> Result<String, Failure> {
    let mut studies = String::new();
    if let Some(rows) = &d.width {
        let wd = width_table(rows);
        a.add("width-dependence.csv", wd.to_csv());
        if let (Some(n), Some(w)) = (rows.first(), rows.last()) {
            findings.push(render(
                "comparison/finding-width.md",
                FINDING_WIDTH,
                &[
                    ("narrow", sig(n.centre, 3)),
                    ("narrow_bl", n.width_ratio.to_string()),
                    ("wide", sig(w.centre, 3)),
                    ("wide_bl", w.width_ratio.to_string()),
                ],
            )?);
        }
        studies.push_str(&render("comparison/width.md", WIDTH, &[("table", wd.to_markdown())])?);
    }
    if let Some(rows) = &d.extremes {
        let xt = extreme_table(rows);
        a.add("extreme-cases.csv", xt.to_csv());
        let decades = (EXTREME_VELOCITIES[EXTREME_VELOCITIES.len() - 1] / EXTREME_VELOCITIES[0]).log10();
        studies.push_str(&render(
            "comparison/extreme.md",
            EXTREME,
            &[
                ("k_min", short(EXTREME_SPRINGS[0])),
                ("k_max", short(EXTREME_SPRINGS[EXTREME_SPRINGS.len() - 1])),
                ("decades", format!("{decades:.0}")),
                ("h_min", (EXTREME_THICKNESSES[0] * 1e3).to_string()),
                ("h_max", (EXTREME_THICKNESSES[EXTREME_THICKNESSES.len() - 1] * 1e3).to_string()),
                ("table", xt.to_markdown()),
            ],
        )?);
    }
    if let Some(sh) = &d.shear {
        studies.push_str(&shear::section(scene, sh, a, findings)?);
    }
    if let Some(ev) = &d.error_vs_time {
        error_vs_time_page(scene, ev, d.seconds, a)?;
        studies.push_str(&render("comparison/error-vs-time.md", ERROR_LINK, &[])?);
    }
    Ok(studies)
}

/// The error-against-run-time page, its table and figure.
fn error_vs_time_page(scene: &Scene, ev: &ErrorVsTime, seconds: f64, a: &mut Artifacts) -> Result<(), Failure> {
    let table = error_table(ev);
    a.add("error-vs-time.csv", table.to_csv());
    // Both axes span decades: log-log, each mesh a marked point.
    let pts = ev.runs.iter().map(|r| (r.seconds, r.max_error.max(1e-16))).collect();
    let svg = Plot::new("Plate FE: max error against run time", Axis::log("time (s)"), Axis::log("max relative error"))
        .with(Series::new("BFS mesh ladder (each point a mesh)", pts))
        .svg();
    a.add("error-vs-time.svg", svg);
    let mut lines = String::new();
    for r in &ev.recommended {
        let tolerance = format!("{:e}", r.tolerance);
        lines.push_str(&match r.run.map(|i| &ev.runs[i]) {
            Some(m) => render(
                "comparison/recommended-mesh.md",
                RECOMMENDED_MESH,
                &[
                    ("tolerance", tolerance),
                    ("mesh", format!("{} x {}", m.nx, m.nz)),
                    ("error", format!("{:.1e}", m.max_error)),
                    ("seconds", format!("{:.3}", m.seconds)),
                ],
            )?,
            None => render("comparison/recommended-finer.md", RECOMMENDED_FINER, &[("tolerance", tolerance)])?,
        });
    }
    let mesh = |(nx, nz): (usize, usize)| format!("{nx} x {nz}");
    let page = render(
        "comparison/error-vs-time-page.md",
        ERROR_PAGE,
        &[
            ("scene", scene.name.clone()),
            ("reference_meshes", ev.reference_meshes.map(mesh).join(" and ")),
            ("table", table.to_markdown()),
            ("recommended", render("comparison/recommended.md", RECOMMENDED, &[("lines", lines)])?),
            ("seconds", format!("{seconds:.1}")),
        ],
    )?;
    a.add("error-vs-time.md", page);
    Ok(())
}
