//! `impact compare`: the paper's beam model and the plate FE model through the same energy
//! balance and yield model, and where and by how much they differ.

use crate::paper::Paper;
use crate::present::plot::{line_plot, Axis, ColourMap, Plot, Scale, Series};
use crate::present::rows::slug;
use crate::present::table::{percent, sig, Cell, Table};
use analytic::Condition;
use coupled::plan::ResponseValues;
use coupled::plan::{fundamental_periods, run, ModelKind, Results};
use coupled::PlateModel;
use coupled::{BeamModel, ComplianceModel};
use indicatif::{ProgressBar, ProgressStyle};
use output::Artifacts;
use scene::{even_points, Analysis, Scene, SupportSet};
use std::fmt::Write as _;
use std::time::Instant;

use crate::template::render;
use crate::Failure;

/// Mesh ladder of the comparison: 20 x 16 and 40 x 32 elements for the paper's plate
/// (Richardson from the two; reports/fem shows the estimate is conservative there).
pub const BASE_MESH: usize = 20;
pub const LEVELS: u32 = 2;
/// The map grid: L in 100 parts as in the paper, B in 20.
pub const MAP_X: usize = 101;
pub const MAP_Z: usize = 21;
/// The paper's Areas 1-7 (Table 2), as fractions of L.
pub const AREAS: [f64; 7] = [0.03, 0.25, 0.46, 0.5, 0.54, 0.75, 0.98];
/// The part of the length the maps and their statistics cover, as fractions of L: towards
/// the ends the beam's compliance falls to zero and the ratio to it diverges.
pub const INNER: (f64, f64) = (0.1, 0.9);
/// The spring stiffnesses (N/m), velocities (m/s) and thicknesses (m) of the extreme cases.
pub const EXTREME_SPRINGS: [f64; 4] = [1.0, 5e4, 5.11545e8, 1e15];
pub const EXTREME_VELOCITIES: [f64; 4] = [1e-6, 1e-3, 1.0, 10.0];
pub const EXTREME_THICKNESSES: [f64; 2] = [0.5e-3, 80e-3];

// The report's prose, one template per section (sections are written only when the scene
// asks for them; the map section repeats per support set).
const HEAD: &str = include_str!("templates/comparison/head.md");
const ACROSS: &str = include_str!("templates/comparison/across.md");
const NO_MAP: &str = include_str!("templates/comparison/no-map.md");
const MAP: &str = include_str!("templates/comparison/map.md");
const WIDTH: &str = include_str!("templates/comparison/width.md");
const EXTREME: &str = include_str!("templates/comparison/extreme.md");
const ERROR_PAGE: &str = include_str!("templates/comparison/error-vs-time-page.md");
const ERROR_LINK: &str = include_str!("templates/comparison/error-vs-time.md");
const FIELD: &str = include_str!("templates/comparison/field.md");
const METHOD_TEXT: &str = include_str!("templates/comparison/method.md");
const SUMMARY: &str = include_str!("templates/comparison/summary.md");
const FINDING_COMPLIANCE: &str = include_str!("templates/comparison/finding-compliance.md");
const FINDING_ENDS: &str = include_str!("templates/comparison/finding-ends.md");
const FINDING_FORCE: &str = include_str!("templates/comparison/finding-force.md");
const FINDING_FORCE_YIELD: &str = include_str!("templates/comparison/finding-force-yield.md");
const FINDING_MAP: &str = include_str!("templates/comparison/finding-map.md");
const FINDING_FIELD: &str = include_str!("templates/comparison/finding-field.md");
const FINDING_WIDTH: &str = include_str!("templates/comparison/finding-width.md");

/// A round number as the prose writes it: small integers as they are, the rest in
/// exponent form (`1e15`).
fn short(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < 100.0 {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

fn progress(len: u64, what: &str) -> ProgressBar {
    let pb = ProgressBar::new(len);
    pb.set_style(
        ProgressStyle::with_template("{msg:30} [{bar:30}] {pos}/{len} {elapsed}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    pb.set_message(what.to_string());
    pb
}

/// Beam and plate results for the same scene.
pub struct Pair {
    pub beam: Results,
    pub plate: Results,
    pub model: PlateModel,
}

/// All (x, z) pairs of the scene's points.
pub fn scene_points(scene: &Scene) -> Vec<(f64, f64)> {
    scene.point_pairs()
}

/// Runs both models on the scene's own points.
pub fn pair(scene: &Scene) -> Result<Pair, Failure> {
    pair_on(scene, PlateModel::compute(&scene.plate, &scene.conditions, &scene_points(scene), BASE_MESH, LEVELS)?)
}

/// Runs both models on the scene's points with a plate model already computed there.
pub fn pair_on(scene: &Scene, model: PlateModel) -> Result<Pair, Failure> {
    let periods = fundamental_periods(scene)?;
    let beam = run(scene, &BeamModel { plate: &scene.plate }, ModelKind::Beam, &periods)?;
    let plate = run(scene, &model, ModelKind::Plate, &periods)?;
    Ok(Pair { beam, plate, model })
}

/// plate/beam - 1; none (an empty cell) where the beam's value is 0 and the ratio has no
/// value, so a numeric column holds numbers only.
fn rel(p: f64, b: f64) -> Cell {
    if b != 0.0 && b.is_finite() && p.is_finite() {
        Cell::Rel(p / b - 1.0)
    } else if p == b {
        Cell::Rel(0.0)
    } else {
        Cell::Empty
    }
}

/// The row of `other` for the same case (support set, body, point and velocity) as `row`.
fn same_case<'a>(other: &'a Results, row: &coupled::ResponseRow) -> Option<&'a coupled::ResponseRow> {
    other.responses.iter().find(|b| {
        b.condition == row.condition && b.body == row.body && b.x == row.x && b.z == row.z && b.velocity == row.velocity
    })
}

/// Per condition: both models' responses and yield velocities at the scene's points.
pub fn pair_tables(scene: &Scene, pair: &Pair) -> Vec<Table> {
    let mut out = Vec::new();
    for cond in &scene.conditions {
        if scene.wants(Analysis::Responses) {
            let springs = cond.has_springs();
            let mut h = vec![
                "body",
                "x (mm)",
                "z (mm)",
                "v (m/s)",
                "C beam (m/N)",
                "C plate (m/N)",
                "FE ± (m/N)",
                "C plate/beam - 1",
                "P_max beam (N)",
                "P_max plate (N)",
                "P rel. diff.",
                "δ_max beam (m)",
                "δ_max plate (m)",
                "deflection beam (m)",
                "deflection plate (m)",
                "plate energy beam",
                "plate energy plate",
            ];
            if springs {
                h.extend(["spring energy beam", "spring energy plate"]);
            }
            let mut t = Table::new(format!("{}: responses, beam against plate FE", cond.name), &h);
            for pr in pair.plate.responses.iter().filter(|r| r.condition == cond.name) {
                let Some(br) = same_case(&pair.beam, pr) else { continue };
                let z = pr.z;
                let Some(p) = pr.values() else { continue };
                let b = br.values();
                // Beam values are closed forms (4 significant digits shown); plate C and P_max to
                // the digit their FE error supports; the rest of the plate's to 4 digits, which its
                // relative FE error (below 1e-4) supports.
                let bv = |f: &dyn Fn(&ResponseValues) -> f64| b.map_or(Cell::Empty, |b| Cell::Sig(f(b), 4));
                let brel = |f: &dyn Fn(&ResponseValues) -> f64| b.map_or(Cell::Empty, |b| rel(f(p), f(b)));
                let c = |v: &ResponseValues| v.compliance.unwrap_or(0.0);
                let mut row: Vec<Cell> = vec![
                    pr.body.clone().into(),
                    Cell::Given(pr.x * 1e3),
                    Cell::Given(z * 1e3),
                    Cell::Given(pr.velocity),
                    bv(&c),
                    Cell::Measured { value: c(p), error: p.compliance_error.unwrap_or(0.0) },
                    p.compliance_error.map_or(Cell::Empty, |e| Cell::Sig(e, 2)),
                    brel(&c),
                    bv(&|v| v.contact_force),
                    Cell::Measured { value: p.contact_force, error: p.contact_force_error.unwrap_or(0.0) },
                    brel(&|v| v.contact_force),
                    bv(&|v| v.compression),
                    Cell::Sig(p.compression, 4),
                    bv(&|v| v.deflection),
                    Cell::Sig(p.deflection, 4),
                    bv(&|v| v.plate_ratio),
                    Cell::Sig(p.plate_ratio, 4),
                ];
                if springs {
                    row.extend([bv(&|v| v.spring_ratio), Cell::Sig(p.spring_ratio, 4)]);
                }
                t.push(row);
            }
            out.push(t);
            if springs {
                let mut t = Table::new(
                    format!(
                        "{}: spring forces (N), beam (each spring of an end) against plate FE (each corner)",
                        cond.name
                    ),
                    &[
                        "body",
                        "x (mm)",
                        "z (mm)",
                        "v (m/s)",
                        "beam left (N)",
                        "plate (0, 0) (N)",
                        "plate (0, B) (N)",
                        "beam right (N)",
                        "plate (L, 0) (N)",
                        "plate (L, B) (N)",
                    ],
                );
                for pr in pair.plate.responses.iter().filter(|r| r.condition == cond.name) {
                    let Some(br) = same_case(&pair.beam, pr) else { continue };
                    let Some(p) = pr.values() else { continue };
                    let bf = |n: &str| match br.values() {
                        None => Cell::Empty,
                        Some(b) => b
                            .spring_forces
                            .iter()
                            .find(|s| s.name.starts_with(n))
                            .map_or(Cell::Empty, |s| Cell::Num(s.force)),
                    };
                    let pf = |n: &str| {
                        p.spring_forces.iter().find(|s| s.name.ends_with(n)).map_or(Cell::Empty, |s| Cell::Num(s.force))
                    };
                    t.push(vec![
                        pr.body.clone().into(),
                        Cell::Given(pr.x * 1e3),
                        Cell::Given(pr.z * 1e3),
                        Cell::Given(pr.velocity),
                        bf("left"),
                        pf("(0, 0)"),
                        pf("(0, B)"),
                        bf("right"),
                        pf("(L, 0)"),
                        pf("(L, B)"),
                    ]);
                }
                out.push(t);
            }
        }
        if scene.wants(Analysis::YieldVelocity) {
            let mut t = Table::new(
                format!("{}: yield velocities, beam against plate FE", cond.name),
                &["body", "x (mm)", "z (mm)", "v_y beam (m/s)", "v_y plate (m/s)", "rel. diff."],
            );
            for py in pair.plate.yields.iter().filter(|r| r.condition == cond.name) {
                if let Some(by) = pair
                    .beam
                    .yields
                    .iter()
                    .find(|b| b.condition == cond.name && b.body == py.body && b.x == py.x && b.z == py.z)
                {
                    let Some(p) = py.values() else { continue };
                    let b = by.values();
                    t.push(vec![
                        py.body.clone().into(),
                        Cell::Given(py.x * 1e3),
                        Cell::Given(py.z * 1e3),
                        b.map_or(Cell::Empty, |b| Cell::Sig(b.yield_velocity, 4)),
                        Cell::Measured { value: p.yield_velocity, error: p.yield_velocity_error.unwrap_or(0.0) },
                        b.map_or(Cell::Empty, |b| rel(p.yield_velocity, b.yield_velocity)),
                    ]);
                }
            }
            out.push(t);
        }
    }
    out
}

/// Compliance maps of both models over the plate for the scene's conditions.
pub struct Maps {
    pub xs: Vec<f64>,
    pub zs: Vec<f64>,
    /// condition -> `[ix][iz]` plate compliance, and beam compliance per ix.
    pub plate: Vec<Vec<Vec<f64>>>,
    pub error: Vec<Vec<Vec<f64>>>,
    pub beam: Vec<Vec<f64>>,
}

/// The map grid: L in `MAP_X - 1` parts, B in `MAP_Z - 1`.
pub fn map_points(scene: &Scene) -> Vec<(f64, f64)> {
    let zs = even_points(scene.plate.width(), MAP_Z);
    even_points(scene.plate.length(), MAP_X).into_iter().flat_map(|x| zs.iter().map(move |&z| (x, z))).collect()
}

/// The maps, with their own plate model.
pub fn maps(scene: &Scene) -> Result<Maps, Failure> {
    maps_from(scene, &PlateModel::compute(&scene.plate, &scene.conditions, &map_points(scene), BASE_MESH, LEVELS)?)
}

/// The maps from a plate model that holds the map grid.
pub fn maps_from(scene: &Scene, model: &PlateModel) -> Result<Maps, Failure> {
    let xs = even_points(scene.plate.length(), MAP_X);
    let zs = even_points(scene.plate.width(), MAP_Z);
    let beam = BeamModel { plate: &scene.plate };
    let mut plate = Vec::new();
    let mut error = Vec::new();
    let mut beam_c = Vec::new();
    for c in &scene.conditions {
        let mut grid = Vec::new();
        let mut egrid = Vec::new();
        let mut brow = Vec::new();
        for &x in &xs {
            // The beam describes only Con 1-3; the map's beam row is unused for other sets.
            brow.push(match beam.compliance(c, x, 0.0) {
                Ok(e) => e.compliance.total(),
                Err(coupled::ModelError::NotApplicable { .. }) => 0.0,
                Err(e) => return Err(e.into()),
            });
            let (mut col, mut ecol) = (Vec::new(), Vec::new());
            for &z in &zs {
                let v = model.get(&c.name, x, z).ok_or("map point missing")?;
                col.push(v.compliance.total());
                ecol.push(v.error_estimate);
            }
            grid.push(col);
            egrid.push(ecol);
        }
        plate.push(grid);
        error.push(egrid);
        beam_c.push(brow);
    }
    Ok(Maps { xs, zs, plate, error, beam: beam_c })
}

fn nearest(v: &[f64], x: f64) -> usize {
    v.iter().enumerate().min_by(|a, b| (a.1 - x).abs().total_cmp(&(b.1 - x).abs())).map_or(0, |(i, _)| i)
}

/// The widths of the width study, as B/L.
pub const WIDTH_RATIOS: [f64; 7] = [0.1, 0.25, 0.5, 0.785, 1.0, 1.5, 2.0];

/// One width of the width study: C_plate/C_beam (Con 1) at three points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WidthRow {
    /// B/L.
    pub width_ratio: f64,
    /// At x = L/2 on the centreline.
    pub centre: f64,
    /// At x = L/2 on the free edge z = 0.
    pub free_edge: f64,
    /// At Area 2 (x = L/4) on the centreline.
    pub quarter_span: f64,
    /// The FE error estimate of the centre compliance, relative to it.
    pub fe_error: f64,
}

/// Ratio C_plate/C_beam at x = L/2 on the centreline and the free edge, Con 1, for a range
/// of widths (the beam is the same B-proportional stiffness at every width).
pub fn width_dependence(scene: &Scene) -> Result<Vec<WidthRow>, Failure> {
    let l = scene.plate.length();
    let mut rows = Vec::new();
    for bl in WIDTH_RATIOS {
        let plate = scene.plate.with_width(bl * l)?;
        let s = Scene { plate, ..scene.clone() };
        let cond = SupportSet::preset("Con 1", Condition::BothFixed);
        let b = plate.width();
        let pts = [(l / 2.0, b / 2.0), (l / 2.0, 0.0), (l / 4.0, b / 2.0)];
        // Near-square elements, 20 (then 40) along the longer side.
        let model = PlateModel::compute(&s.plate, std::slice::from_ref(&cond), &pts, BASE_MESH, LEVELS)?;
        let beam = BeamModel { plate: &s.plate };
        let r = |p: (f64, f64)| -> Result<(f64, f64), Failure> {
            let fe = model.get("Con 1", p.0, p.1).ok_or("missing")?;
            Ok((
                fe.compliance.total() / beam.compliance(&cond, p.0, 0.0)?.compliance.total(),
                fe.error_estimate / fe.compliance.total(),
            ))
        };
        let (centre, fe_error) = r(pts[0])?;
        rows.push(WidthRow { width_ratio: bl, centre, free_edge: r(pts[1])?.0, quarter_span: r(pts[2])?.0, fe_error });
    }
    Ok(rows)
}

/// The width study as the report prints it.
pub fn width_table(rows: &[WidthRow]) -> Table {
    let mut t = Table::new(
        "",
        &[
            "B/L",
            "C_plate/C_beam centre (x = L/2)",
            "at the free edge (z = 0)",
            "at Area 2 (x = L/4), centre",
            "FE ± (rel.)",
        ],
    );
    for r in rows {
        t.push(vec![
            r.width_ratio.into(),
            r.centre.into(),
            r.free_edge.into(),
            r.quarter_span.into(),
            r.fe_error.into(),
        ]);
    }
    t
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
    report_with(scene, &StudySections::default())
}

/// [`report`] with the findings and sections of the studies nested beside it.
pub fn report_with(scene: &Scene, extra: &StudySections) -> Result<Artifacts, Failure> {
    let t0 = Instant::now();
    let pb = progress(5, "plate FE at all points");
    // One plate model (one factorization per mesh) for the scene's points and the map grid.
    let mut points = scene_points(scene);
    let want_maps = scene.wants(Analysis::WidthMaps);
    if want_maps {
        points.extend(map_points(scene));
    }
    let pr = pair_on(scene, PlateModel::compute(&scene.plate, &scene.conditions, &points, BASE_MESH, LEVELS)?)?;
    pb.inc(1);
    pb.set_message("compliance maps");
    let mp = if want_maps { Some(maps_from(scene, &pr.model)?) } else { None };
    pb.inc(1);
    let mut a = Artifacts::new();
    let mut findings: Vec<String> = Vec::new();
    let mut numbers = serde_json::Map::new();
    let levels: Vec<String> =
        pr.model.levels.iter().map(|c| format!("{} x {} ({} DOFs)", c.nx, c.nz, c.dofs)).collect();
    let head = render(
        "comparison/head.md",
        HEAD,
        &[("scene", scene.name.clone()), ("description", scene.description.clone())],
    )?;
    let method = render("comparison/method.md", METHOD_TEXT, &[("mesh_levels", levels.join(" and "))])?;

    // Findings at the scene's points, per support set the beam describes.
    findings.extend(point_findings(scene, &pr, &mut numbers)?);

    let mut figures = String::new();
    if scene.wants(Analysis::Responses) {
        if let Some((md_field, w_svg, s_svg, finding)) = peak_field_section(scene, &pr)? {
            a.add("field-w.svg", w_svg);
            a.add("field-stress.svg", s_svg);
            figures.push_str(&md_field);
            findings.push(finding);
        }
    }

    let mut tables = String::from("\n## Detail tables\n");
    for t in pair_tables(scene, &pr) {
        let stem = format!("table-{}", slug(&t.title));
        a.add(format!("{stem}.csv"), t.to_csv());
        let _ = writeln!(tables, "\n### {}\n\n{}", t.title, t.to_markdown());
    }

    if let Some(mp) = &mp {
        // Maps and lines.
        figures.push_str(&render(
            "comparison/across.md",
            ACROSS,
            &[
                ("inner_from", INNER.0.to_string()),
                ("inner_to", INNER.1.to_string()),
                ("map_x", MAP_X.to_string()),
                ("map_z", MAP_Z.to_string()),
                ("areas", AREAS.len().to_string()),
            ],
        )?);
        let mut map_csv = Table::new(
            "",
            &["condition", "x (mm)", "z (mm)", "C beam (m/N)", "C plate (m/N)", "FE ± (m/N)", "C plate/beam - 1"],
        );
        for (ci, c) in scene.conditions.iter().enumerate() {
            if c.beam_condition().is_none() {
                figures.push_str(&render("comparison/no-map.md", NO_MAP, &[("condition", c.name.clone())])?);
                continue;
            }
            let ratio = |i: usize, j: usize| {
                if mp.beam[ci][i] > 0.0 {
                    mp.plate[ci][i][j] / mp.beam[ci][i] - 1.0
                } else {
                    f64::NAN
                }
            };
            for (i, &x) in mp.xs.iter().enumerate() {
                for (j, &z) in mp.zs.iter().enumerate() {
                    map_csv.push(vec![
                        c.name.clone().into(),
                        (x * 1e3).into(),
                        (z * 1e3).into(),
                        mp.beam[ci][i].into(),
                        mp.plate[ci][i][j].into(),
                        mp.error[ci][i][j].into(),
                        ratio(i, j).into(),
                    ]);
                }
            }
            let stem = format!("map-{}", slug(&c.name));
            let inner_x = |i: usize| (INNER.0..=INNER.1).contains(&(mp.xs[i] / scene.plate.length()));
            let colour_map = ColourMap {
                title: format!("{}: C_plate / C_beam over the plate", c.name),
                x: Axis::linear("x (mm)"),
                y: Axis::linear("z (mm)"),
                xs: mp.xs.iter().map(|x| x * 1e3).collect(),
                ys: mp.zs.iter().map(|z| z * 1e3).collect(),
                edges: false,
                values: (0..mp.xs.len())
                    .map(|i| (0..mp.zs.len()).map(|j| if inner_x(i) { ratio(i, j) + 1.0 } else { f64::NAN }).collect())
                    .collect(),
                bar: Axis::log("C_plate / C_beam"),
                missing: Some(format!(
                    "x < {} L and x > {} L, where the beam's C falls to 0 and the ratio diverges",
                    INNER.0, INNER.1
                )),
                marks: vec![],
                notes: vec!["Supports at the four corners; the beam has the same C across the width.".into()],
            };
            a.add(format!("{stem}.svg"), colour_map.svg());
            // Interior statistics (away from the ends, where the beam ratio is singular).
            let inner: Vec<f64> = (0..mp.xs.len())
                .filter(|&i| inner_x(i))
                .flat_map(|i| (0..mp.zs.len()).map(move |j| (i, j)))
                .map(|(i, j)| ratio(i, j))
                .filter(|v| v.is_finite())
                .collect();
            let (lo, hi) = inner.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
            let mid = nearest(&mp.xs, scene.plate.length() / 2.0);
            let (zc, ze) = (nearest(&mp.zs, scene.plate.width() / 2.0), 0);
            numbers.insert(
                format!("{}: map C_plate/C_beam - 1", c.name),
                serde_json::json!({ "lowest": lo, "highest": hi, "centre": ratio(mid, zc), "free_edge": ratio(mid, ze) }),
            );
            let map_values = [
                ("condition", c.name.clone()),
                ("inner_from", INNER.0.to_string()),
                ("inner_to", INNER.1.to_string()),
                ("lowest", percent(lo)),
                ("highest", percent(hi)),
                ("centre", percent(ratio(mid, zc))),
                ("edge", percent(ratio(mid, ze))),
            ];
            findings.push(render("comparison/finding-map.md", FINDING_MAP, &map_values)?);
            let line = |j: usize| {
                Series::new(
                    format!("plate, z = {:.0} mm", mp.zs[j] * 1e3),
                    mp.xs.iter().enumerate().map(|(i, x)| (x * 1e3, mp.plate[ci][i][j])).collect(),
                )
            };
            let series = vec![
                Series::new("beam", mp.xs.iter().enumerate().map(|(i, x)| (x * 1e3, mp.beam[ci][i])).collect()),
                line(zc),
                line(ze),
            ];
            a.add(
                format!("{stem}-along.svg"),
                line_plot(
                    &format!("{}: compliance along the plate", c.name),
                    "x (mm)",
                    "C (m/N)",
                    &series,
                    Scale::Linear,
                ),
            );
            let across: Vec<Series> = AREAS
                .iter()
                .enumerate()
                .map(|(k, f)| {
                    let i = nearest(&mp.xs, f * scene.plate.length());
                    Series::new(
                        format!("Area {} (x = {:.0} mm)", k + 1, mp.xs[i] * 1e3),
                        mp.zs.iter().enumerate().map(|(j, z)| (z * 1e3, ratio(i, j) + 1.0)).collect(),
                    )
                })
                .collect();
            a.add(
                format!("{stem}-across.svg"),
                line_plot(
                    &format!("{}: C_plate/C_beam across the width", c.name),
                    "z (mm)",
                    "C_plate / C_beam (log)",
                    &across,
                    Scale::Log,
                ),
            );
            let mut with_stem = map_values.to_vec();
            with_stem.push(("stem", stem.clone()));
            figures.push_str(&render("comparison/map.md", MAP, &with_stem)?);
        }
        a.add("maps.csv", map_csv.to_csv());
    }
    pb.inc(1);

    let mut studies = String::new();
    pb.set_message("width dependence");
    if scene.wants(Analysis::AspectRatio) {
        let rows = width_dependence(scene)?;
        let wd = width_table(&rows);
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
    pb.inc(1);

    pb.set_message("extreme cases");
    if scene.wants(Analysis::ExtremeCases) {
        let xt = extreme_cases(scene)?;
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

    pb.set_message("error against run time");
    if scene.wants(Analysis::ErrorVsTime) {
        let ev = error_vs_time(scene)?;
        a.add("error-vs-time.csv", ev.table.to_csv());
        a.add("error-vs-time.svg", ev.svg);
        let timing = render(
            "comparison/error-vs-time-page.md",
            ERROR_PAGE,
            &[
                ("scene", scene.name.clone()),
                ("reference_meshes", ev.reference_meshes.join(" and ")),
                ("table", ev.table.to_markdown()),
                ("recommended", ev.recommended),
                ("seconds", format!("{:.1}", t0.elapsed().as_secs_f64())),
            ],
        )?;
        a.add("error-vs-time.md", timing);
        studies.push_str(&render("comparison/error-vs-time.md", ERROR_LINK, &[])?);
    }
    pb.inc(1);
    pb.finish_and_clear();

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
        pr.model.levels.iter().map(|c| serde_json::json!({ "nx": c.nx, "nz": c.nz, "dofs": c.dofs })).collect();
    let json = serde_json::json!({ "scene": scene.name, "beam": pr.beam, "plate": pr.plate, "mesh_levels": levels });
    a.add("results.json", serde_json::to_string_pretty(&json)?);
    Ok(a)
}

/// The findings at the scene's own points, one line per support set the beam describes:
/// the range of C_plate/C_beam - 1 (and the supported-end points where the beam's C is 0),
/// of P_max and of v_y, plate against beam. The numbers go into `numbers` too.
fn point_findings(
    scene: &Scene,
    pr: &Pair,
    numbers: &mut serde_json::Map<String, serde_json::Value>,
) -> Result<Vec<String>, Failure> {
    let range = |v: &[f64]| v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    let mut out = Vec::new();
    for cond in scene.conditions.iter().filter(|c| c.beam_condition().is_some()) {
        let (mut ratios, mut fe, mut ends, mut ends_c, mut forces) = (vec![], 0.0f64, 0usize, 0.0f64, vec![]);
        let mut seen: Vec<(f64, f64)> = Vec::new();
        for pr_row in pr.plate.responses.iter().filter(|r| r.condition == cond.name) {
            let (Some(p), Some(b)) = (pr_row.values(), same_case(&pr.beam, pr_row).and_then(|b| b.values())) else {
                continue;
            };
            let (cp, cb) = (p.compliance.unwrap_or(f64::NAN), b.compliance.unwrap_or(f64::NAN));
            if !seen.contains(&(pr_row.x, pr_row.z)) {
                seen.push((pr_row.x, pr_row.z));
                if cb > 0.0 {
                    ratios.push(cp / cb - 1.0);
                    fe = fe.max(p.compliance_error.unwrap_or(0.0) / cp);
                } else {
                    ends += 1;
                    ends_c = ends_c.max(cp);
                }
            }
            if b.contact_force > 0.0 {
                forces.push(p.contact_force / b.contact_force - 1.0);
            }
        }
        let yields: Vec<f64> = pr
            .plate
            .yields
            .iter()
            .filter(|r| r.condition == cond.name)
            .filter_map(|py| {
                let by = pr
                    .beam
                    .yields
                    .iter()
                    .find(|b| b.condition == py.condition && b.body == py.body && b.x == py.x && b.z == py.z)?;
                Some(py.values()?.yield_velocity / by.values()?.yield_velocity - 1.0)
            })
            .collect();
        if ratios.is_empty() && forces.is_empty() {
            continue;
        }
        let (lo, hi) = range(&ratios);
        let ends_text = if ends > 0 {
            let count =
                if ends == 1 { "1 supported-end point".to_string() } else { format!("{ends} supported-end points") };
            render("comparison/finding-ends.md", FINDING_ENDS, &[("count", count), ("plate_c", sig(ends_c, 3))])?
                .trim_end()
                .to_string()
        } else {
            String::new()
        };
        if !ratios.is_empty() {
            out.push(render(
                "comparison/finding-compliance.md",
                FINDING_COMPLIANCE,
                &[
                    ("condition", cond.name.clone()),
                    ("points", ratios.len().to_string()),
                    ("lowest", percent(lo)),
                    ("highest", percent(hi)),
                    ("fe_error", percent(fe).trim_start_matches('+').to_string()),
                    ("ends", ends_text),
                ],
            )?);
        }
        let (flo, fhi) = range(&forces);
        let (ylo, yhi) = range(&yields);
        if !forces.is_empty() {
            // The yield clause only where the scene asked for yield velocities.
            let yield_text = if yields.is_empty() {
                String::new()
            } else {
                render(
                    "comparison/finding-force-yield.md",
                    FINDING_FORCE_YIELD,
                    &[("lowest", percent(ylo)), ("highest", percent(yhi))],
                )?
            };
            out.push(render(
                "comparison/finding-force.md",
                FINDING_FORCE,
                &[
                    ("condition", cond.name.clone()),
                    ("lowest", percent(flo)),
                    ("highest", percent(fhi)),
                    ("cases", forces.len().to_string()),
                    ("yield", yield_text),
                ],
            )?);
        }
        // A range over no cases is null, not a pair of infinities.
        let span = |v: &[f64], (a, b): (f64, f64)| {
            if v.is_empty() {
                serde_json::Value::Null
            } else {
                serde_json::json!([a, b])
            }
        };
        numbers.insert(
            format!("{}: plate/beam - 1 at the scene's points", cond.name),
            serde_json::json!({
                "compliance": span(&ratios, (lo, hi)), "contact_force": span(&forces, (flo, fhi)),
                "yield_velocity": span(&yields, (ylo, yhi)),
                "fe_error_relative": fe, "ends_with_beam_c_zero": ends, "plate_c_at_those_ends_max": ends_c,
            }),
        );
    }
    Ok(out)
}

/// The plate at the maximum force of one impact: the first support set, body and velocity
/// of the scene at its point nearest the plate's centre (the typical impact), as the plate
/// FE model answers it. `None` when the scene has no such plate row.
fn peak_field_section(scene: &Scene, pr: &Pair) -> Result<Option<(String, String, String, String)>, Failure> {
    let (Some(cond), Some(body), Some(&v)) = (scene.conditions.first(), scene.bodies.first(), scene.velocities.first())
    else {
        return Ok(None);
    };
    let (cx, cz) = (scene.plate.length() / 2.0, scene.plate.width() / 2.0);
    let row = pr
        .plate
        .responses
        .iter()
        .filter(|r| r.condition == cond.name && r.body == body.name && r.velocity == v && r.values().is_some())
        .min_by(|a, b| (a.x - cx).hypot(a.z - cz).total_cmp(&(b.x - cx).hypot(b.z - cz)));
    let Some(row) = row else { return Ok(None) };
    let Some(values) = row.values() else { return Ok(None) };
    let p_max = values.contact_force;
    let what = format!("{} at {} m/s on {} at ({:.1}, {:.1}) mm", body.name, v, cond.name, row.x * 1e3, row.z * 1e3);
    let validity = crate::present::rows::validity_text(&values.validity);
    let caveat = crate::field::quasi_static_caveat(&values.validity)?;
    let f = crate::plate_field::peak_field(scene, cond, row.x, row.z, p_max, &[what.clone(), validity.clone()])?;
    let finding = render(
        "comparison/finding-field.md",
        FINDING_FIELD,
        &[
            ("what", what.clone()),
            ("validity", validity.clone()),
            ("w_max", sig(f.w_max * 1e6, 3)),
            ("stress_max", sig(f.stress_max / 1e3, 3)),
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
            ("p_max", sig(p_max, 3)),
            ("mesh", crate::plate_field::FIELD_ELEMENTS.to_string()),
            ("w_max", sig(f.w_max * 1e6, 3)),
            ("w_x", format!("{:.1}", f.w_max_at.0 * 1e3)),
            ("w_z", format!("{:.1}", f.w_max_at.1 * 1e3)),
            ("left_out", f.left_out.to_string()),
            ("stress_max", sig(f.stress_max / 1e3, 3)),
            ("s_x", format!("{:.1}", f.stress_max_at.0 * 1e3)),
            ("s_z", format!("{:.1}", f.stress_max_at.1 * 1e3)),
        ],
    )?;
    Ok(Some((md, f.deflection_svg, f.stress_svg, finding)))
}

/// The error-against-run-time study.
pub struct ErrorVsTime {
    pub table: Table,
    /// The coarsest mesh for each tolerance, as a Markdown list.
    pub recommended: String,
    pub svg: String,
    /// The two finest meshes, whose Richardson value is the reference.
    pub reference_meshes: [String; 2],
}

/// Error of the plate compliances at the scene's points against run time, for a ladder of
/// meshes; the text recommends the coarsest mesh for each tolerance.
pub fn error_vs_time(scene: &Scene) -> Result<ErrorVsTime, Failure> {
    let pts = scene_points(scene);
    let mut runs: Vec<(usize, usize, usize, f64, Vec<f64>)> = Vec::new();
    for mesh in coupled::discretisation::ladder_meshes(&coupled::discretisation::plate_properties(&scene.plate), 10, 5)?
    {
        let t = Instant::now();
        let m = PlateModel::on_meshes(&scene.plate, &scene.conditions, &pts, vec![mesh])?;
        let secs = t.elapsed().as_secs_f64();
        let lv = m.levels.last().ok_or("no level")?.clone();
        let mut vals = Vec::new();
        for c in &scene.conditions {
            for &(x, z) in &pts {
                vals.push(m.get(&c.name, x, z).ok_or("missing")?.compliance.total());
            }
        }
        runs.push((lv.nx, lv.nz, lv.dofs, secs, vals));
    }
    let n = runs.len();
    let reference: Vec<f64> = runs[n - 1].4.iter().zip(&runs[n - 2].4).map(|(f, c)| f + (f - c) / 3.0).collect();
    let mut t = Table::new("", &["mesh", "DOFs", "time (s)", "max rel. error", "median rel. error"]);
    let mut pts_plot = Vec::new();
    let mut rec = String::from(
        "Recommended meshes (coarsest whose maximum error over the scene's points is within the tolerance):\n\n",
    );
    let mut errs_by_mesh = Vec::new();
    for (nx, nz, dofs, secs, vals) in &runs[..n - 1] {
        let mut e: Vec<f64> =
            vals.iter().zip(&reference).filter(|(_, r)| r.abs() > 0.0).map(|(v, r)| (v - r).abs() / r.abs()).collect();
        e.sort_by(f64::total_cmp);
        let max = *e.last().unwrap_or(&0.0);
        let med = e.get(e.len() / 2).copied().unwrap_or(0.0);
        t.push(vec![format!("{nx} x {nz}").into(), (*dofs).into(), (*secs).into(), max.into(), med.into()]);
        pts_plot.push((*secs, max.max(1e-16)));
        errs_by_mesh.push((format!("{nx} x {nz}"), max, *secs));
    }
    for tol in [1e-2, 1e-3, 1e-4, 1e-5] {
        match errs_by_mesh.iter().find(|(_, e, _)| *e <= tol) {
            Some((m, e, s)) => {
                let _ = writeln!(rec, "- {tol:e}: {m} (max error {e:.1e}, {s:.3} s)");
            }
            None => {
                let _ = writeln!(
                    rec,
                    "- {tol:e}: finer than the ladder (use Richardson extrapolation, as this report does)"
                );
            }
        }
    }
    // Both axes span decades: log-log, each mesh a marked point.
    let svg = Plot::new("Plate FE: max error against run time", Axis::log("time (s)"), Axis::log("max relative error"))
        .with(Series::new("BFS mesh ladder (each point a mesh)", pts_plot))
        .svg();
    let mesh = |r: &(usize, usize, usize, f64, Vec<f64>)| format!("{} x {}", r.0, r.1);
    Ok(ErrorVsTime { table: t, recommended: rec, svg, reference_meshes: [mesh(&runs[n - 2]), mesh(&runs[n - 1])] })
}

/// The paper as seen through both models: a checker of section V's conclusions.
pub fn paper_scene() -> Scene {
    Paper::new().scene
}

/// Both models on extreme inputs: do they stay finite, converged and stable?
pub fn extreme_cases(scene: &Scene) -> Result<Table, Failure> {
    let body = scene.bodies.first().ok_or("the scene has no body")?;
    let mut t = Table::new(
        "",
        &[
            "case",
            "point",
            "P_max beam (N)",
            "P_max plate (N)",
            "plate/beam - 1",
            "balance residual beam",
            "balance residual plate",
            "FE ± rel.",
            "stable",
        ],
    );
    let (l, b) = (scene.plate.length(), scene.plate.width());
    let points = [("centre", (l / 2.0, b / 2.0)), ("end (0, B/2)", (0.0, b / 2.0)), ("edge (L/2, 0)", (l / 2.0, 0.0))];
    let mut cases: Vec<(String, Scene, SupportSet, f64)> = Vec::new();
    for k in EXTREME_SPRINGS {
        cases.push((
            format!("Con 2, k_T = {k:e} N/m, v = 0.008"),
            scene.clone(),
            SupportSet::preset("Con 2", Condition::BothSprings { k_t: k }),
            0.008,
        ));
    }
    let con1 = SupportSet::preset("Con 1", Condition::BothFixed);
    for v in EXTREME_VELOCITIES {
        cases.push((format!("Con 1, v = {v:e} m/s"), scene.clone(), con1.clone(), v));
    }
    for h in EXTREME_THICKNESSES {
        let plate = analytic::Plate::new(l, b, h, scene.plate.density(), scene.plate.material())?;
        cases.push((
            format!("Con 1, h = {} mm, v = 0.008", h * 1e3),
            Scene { plate, ..scene.clone() },
            con1.clone(),
            0.008,
        ));
    }
    for (name, s, cond, v) in cases {
        let pts: Vec<(f64, f64)> = points.iter().map(|p| p.1).collect();
        let model = PlateModel::compute(&s.plate, std::slice::from_ref(&cond), &pts, BASE_MESH, LEVELS)?;
        let beam = BeamModel { plate: &s.plate };
        let imp = coupled::plan::impact_of(&s, body, v);
        for (pname, (x, z)) in points {
            let cb = beam.compliance(&cond, x, z)?.compliance;
            let fe = model.get(&cond.name, x, z).ok_or("missing")?;
            let rb = analytic::respond(&imp, &cb, s.solver);
            let rp = analytic::respond(&imp, &fe.compliance, s.solver);
            let (pb, pp) =
                (rb.as_ref().map_or(f64::NAN, |r| r.contact_force), rp.as_ref().map_or(f64::NAN, |r| r.contact_force));
            let res = |r: &Result<analytic::Response, analytic::NotConverged>| {
                r.as_ref().map_or(f64::NAN, |r| r.solution.residual)
            };
            let fe_rel = fe.error_estimate / fe.compliance.total();
            let stable =
                rb.is_ok() && rp.is_ok() && pb.is_finite() && pp.is_finite() && fe.compliance.total().is_finite();
            t.push(vec![
                name.clone().into(),
                pname.into(),
                pb.into(),
                pp.into(),
                rel(pp, pb),
                Cell::Sig(res(&rb), 2),
                Cell::Sig(res(&rp), 2),
                Cell::Sig(fe_rel, 2),
                Cell::Flag { yes: stable, shown: if stable { "yes" } else { "NO" } },
            ]);
        }
    }
    Ok(t)
}
