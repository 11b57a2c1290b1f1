//! The comparison's tables: both models' responses, spring forces and yield velocities per
//! support set, the width study, the extreme cases and the error against run time.

use crate::present::table::{Cell, Table};
use coupled::plan::{ResponseValues, Results};
use scene::{Analysis, Scene, SupportSet};
use studies::comparison::{same_case, same_cell, ErrorVsTime, ExtremeCase, ExtremeRow, WidthRow};

/// plate/beam - 1; none (an empty cell) where the beam's value is 0 and the ratio has no
/// value, so a numeric column holds numbers only.
pub(super) fn rel(p: f64, b: f64) -> Cell {
    if b != 0.0 && b.is_finite() && p.is_finite() {
        Cell::Rel(p / b - 1.0)
    } else if p == b {
        Cell::Rel(0.0)
    } else {
        Cell::Empty
    }
}

/// The responses of both models under `cond`.
fn responses_table(cond: &SupportSet, beam: &Results, plate: &Results) -> Table {
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
    for pr in plate.responses.iter().filter(|r| r.condition == cond.name) {
        let Some(br) = same_case(beam, pr) else { continue };
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
            Cell::Given(pr.z * 1e3),
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
    t
}

/// The spring forces of both models under `cond`: each spring of a beam end against each
/// corner of the plate.
fn springs_table(cond: &SupportSet, beam: &Results, plate: &Results) -> Table {
    let mut t = Table::new(
        format!("{}: spring forces (N), beam (each spring of an end) against plate FE (each corner)", cond.name),
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
    for pr in plate.responses.iter().filter(|r| r.condition == cond.name) {
        let Some(br) = same_case(beam, pr) else { continue };
        let Some(p) = pr.values() else { continue };
        let bf = |n: &str| match br.values() {
            None => Cell::Empty,
            Some(b) => {
                b.spring_forces.iter().find(|s| s.name.starts_with(n)).map_or(Cell::Empty, |s| Cell::Num(s.force))
            }
        };
        let pf =
            |n: &str| p.spring_forces.iter().find(|s| s.name.ends_with(n)).map_or(Cell::Empty, |s| Cell::Num(s.force));
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
    t
}

/// The yield velocities of both models under `cond`.
fn yields_table(cond: &SupportSet, beam: &Results, plate: &Results) -> Table {
    let mut t = Table::new(
        format!("{}: yield velocities, beam against plate FE", cond.name),
        &["body", "x (mm)", "z (mm)", "v_y beam (m/s)", "v_y plate (m/s)", "rel. diff."],
    );
    for py in plate.yields.iter().filter(|r| r.condition == cond.name) {
        let Some(by) = same_cell(beam, py) else { continue };
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
    t
}

/// Per support set: both models' responses (and spring forces) and yield velocities at the
/// scene's points, as the scene asks for them.
pub fn pair_tables(scene: &Scene, beam: &Results, plate: &Results) -> Vec<Table> {
    let mut out = Vec::new();
    for cond in &scene.conditions {
        if scene.wants(Analysis::Responses) {
            out.push(responses_table(cond, beam, plate));
            if cond.has_springs() {
                out.push(springs_table(cond, beam, plate));
            }
        }
        if scene.wants(Analysis::YieldVelocity) {
            out.push(yields_table(cond, beam, plate));
        }
    }
    out
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

/// An extreme input as the table names it.
fn case_name(c: ExtremeCase) -> String {
    match c {
        ExtremeCase::Spring { k_t, velocity } => format!("Con 2, k_T = {k_t:e} N/m, v = {velocity}"),
        ExtremeCase::Velocity { velocity } => format!("Con 1, v = {velocity:e} m/s"),
        ExtremeCase::Thickness { thickness, velocity } => format!("Con 1, h = {} mm, v = {velocity}", thickness * 1e3),
    }
}

/// Both models on extreme inputs.
pub fn extreme_table(rows: &[ExtremeRow]) -> Table {
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
    for r in rows {
        t.push(vec![
            case_name(r.case).into(),
            r.point.clone().into(),
            r.beam_force.into(),
            r.plate_force.into(),
            rel(r.plate_force, r.beam_force),
            Cell::Sig(r.beam_residual, 2),
            Cell::Sig(r.plate_residual, 2),
            Cell::Sig(r.fe_error, 2),
            Cell::Flag { yes: r.stable, shown: if r.stable { "yes" } else { "NO" } },
        ]);
    }
    t
}

/// The error against run time, mesh by mesh.
pub fn error_table(ev: &ErrorVsTime) -> Table {
    let mut t = Table::new("", &["mesh", "DOFs", "time (s)", "max rel. error", "median rel. error"]);
    for r in &ev.runs {
        t.push(vec![
            format!("{} x {}", r.nx, r.nz).into(),
            r.dofs.into(),
            r.seconds.into(),
            r.max_error.into(),
            r.median_error.into(),
        ]);
    }
    t
}
