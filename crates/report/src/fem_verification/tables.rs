//! The verification's tables, from [`studies::fem_verification`]'s data.

use crate::present::table::{Cell, Table};
use studies::fem_verification::mindlin::MindlinVerification;
use studies::fem_verification::{
    Convergence, CornerUpdate, ExtremeCase, ExtremeReference, ExtremeRow, LevyRow, NarrowRow, PaperPlate,
    SkfemComparison,
};

/// A mesh as the tables write it.
pub(super) fn mesh((nx, nz): (usize, usize)) -> String {
    format!("{nx} x {nz}")
}

/// A yes/no shown as "true"/"false".
fn truth(yes: bool) -> Cell {
    Cell::Flag { yes, shown: if yes { "true" } else { "false" } }
}

/// A convergence table against an exact value.
pub(super) fn convergence_table(c: &Convergence) -> Table {
    let mut t =
        Table::new("", &["mesh", "C (m/N)", "rel. error", "observed rate", "Richardson value", "its rel. error"]);
    for r in &c.rows {
        t.push(vec![
            mesh((r.nx, r.nz)).into(),
            r.compliance.into(),
            Cell::Sig(r.rel_error, 3),
            r.observed_rate.map_or(Cell::Empty, |r| Cell::Sig(r, 4)),
            r.richardson.map_or(Cell::Empty, Cell::Num),
            r.richardson_error.map_or(Cell::Empty, |e| Cell::Sig(e, 2)),
        ]);
    }
    t
}

/// The Lévy plate at its load points.
pub(super) fn levy_table(rows: &[LevyRow]) -> Table {
    let mut t = Table::new(
        "",
        &[
            "load point",
            "series C (m/N)",
            "FE 24 x 16",
            "rel. error",
            "FE 96 x 64",
            "rel. error",
            "observed rate",
            "Richardson rel. error",
        ],
    );
    for r in rows {
        t.push(vec![
            format!("({}, {})", r.point.0, r.point.1).into(),
            r.exact.into(),
            r.coarse.into(),
            r.coarse_error.into(),
            r.fine.into(),
            r.fine_error.into(),
            r.observed_rate.map_or(Cell::Empty, Cell::Num),
            r.richardson_error.into(),
        ]);
    }
    t
}

/// Narrow plates against the beam.
pub(super) fn narrow_table(rows: &[NarrowRow]) -> Table {
    let mut t = Table::new(
        "",
        &["B/L", "C_plate / C_beam, centre", "quarter span", "load on the free edge", "(centre ratio - 1)/(B/L)²"],
    );
    for r in rows {
        t.push(vec![r.width_ratio.into(), r.centre.into(), r.quarter.into(), r.edge.into(), r.coefficient.into()]);
    }
    t
}

/// The ladders on the scene's plate.
pub(super) fn paper_table(p: &PaperPlate) -> Table {
    let mut t = Table::new(
        "",
        &[
            "condition",
            "point",
            "C on 80 x 64 (m/N)",
            "Richardson (m/N)",
            "error 40 x 32 vs Richardson",
            "estimated error 80 x 64",
            "observed rate",
            "asymptotic",
        ],
    );
    for r in &p.rows {
        t.push(vec![
            r.condition.clone().into(),
            r.point.clone().into(),
            r.finest.into(),
            r.extrapolated.into(),
            r.second_error.map_or(Cell::Empty, Cell::Num),
            Cell::Num(r.estimate),
            r.observed_rate.map_or(Cell::Empty, Cell::Num),
            (if r.asymptotic { "yes" } else { "no: estimate is the last difference" }).into(),
        ]);
    }
    t.csv_name("asymptotic", &["asymptotic_verdict"])
}

/// The corner update against fresh factorizations.
pub(super) fn update_table(u: &CornerUpdate) -> Table {
    let mut t = Table::new(
        "",
        &[
            "k_T (N/m)",
            "condition",
            "point",
            "C, one factorization: update or condensation (m/N)",
            "C, fresh factorization (m/N)",
            "rel. difference",
            "fresh residual",
            "exact (Con 2 centre)",
            "update error",
            "fresh error",
        ],
    );
    for r in &u.rows {
        let err = |c: f64| r.exact.map_or(Cell::Empty, |exact| Cell::Num((c - exact).abs() / exact));
        // No relative difference to a zero compliance: the absolute one, as a note.
        let diff = r.difference.map_or_else(
            || Cell::Noted { value: f64::NAN, digits: 2, note: format!("abs {:.1e}", r.update.abs()) },
            Cell::Num,
        );
        t.push(vec![
            r.k_t.into(),
            format!("Con {}", r.con).into(),
            Cell::Pair { x: r.point.0, z: r.point.1, scale: 1.0, decimals: 4 },
            r.update.into(),
            r.fresh.into(),
            diff,
            r.fresh_residual.into(),
            r.exact.map_or(Cell::Empty, Cell::Num),
            err(r.update),
            err(r.fresh),
        ]);
    }
    t.csv_name("point", &["x_m", "z_m"])
}

/// An extreme case as the table names it.
fn case_name(c: &ExtremeCase) -> String {
    match c {
        ExtremeCase::Thickness { ratio } => format!("h/L = {ratio}, Con 1 centre"),
        ExtremeCase::Aspect { ratio } => format!("B/L = {ratio}, simply supported ends, centre"),
        ExtremeCase::Support { condition, point } => format!("{condition}, {point}"),
    }
}

/// What an extreme case is checked against, as the table says it.
fn reference_text(r: ExtremeReference) -> String {
    match r {
        ExtremeReference::ThicknessScaling => "C·h³ of h = 8 mm".into(),
        ExtremeReference::LevySeries => "Lévy series".into(),
        ExtremeReference::FixedCorner => "0 (fixed corner)".into(),
        ExtremeReference::SpringCorner { k_t } => {
            format!("just below 1/k_T = {:.4e} (the plate relieves the spring)", 1.0 / k_t)
        }
        ExtremeReference::FinitePositive => "finite, positive".into(),
    }
}

/// The extreme cases.
pub(super) fn extreme_table(rows: &[ExtremeRow]) -> Table {
    let mut t = Table::new("", &["case", "mesh", "C (m/N)", "reference", "rel. error", "max residual", "finite"]);
    for r in rows {
        t.push(vec![
            case_name(&r.case).into(),
            mesh(r.mesh).into(),
            r.compliance.into(),
            reference_text(r.reference).into(),
            r.error.map_or(Cell::Empty, Cell::Num),
            r.residual.into(),
            truth(r.finite),
        ]);
    }
    t
}

/// BFS against scikit-fem.
pub(super) fn skfem_table(s: &SkfemComparison) -> Table {
    let mut t = Table::new(
        "",
        &[
            "case",
            "x (mm)",
            "z (mm)",
            "BFS extrapolated (m/N)",
            "± estimate",
            "Argyris extrapolated (m/N)",
            "± estimate",
            "rel. difference",
            "Morley 160 x 128",
            "bracketed",
        ],
    );
    for r in &s.rows {
        t.push(vec![
            r.case.clone().into(),
            Cell::Given(r.point.0 * 1e3),
            Cell::Given(r.point.1 * 1e3),
            r.bfs.0.into(),
            r.bfs.1.into(),
            r.argyris.0.into(),
            r.argyris.1.into(),
            // Both 0 on a supported edge: no relative difference exists.
            r.difference.map_or(Cell::Empty, Cell::Num),
            r.morley.into(),
            Cell::Flag { yes: r.bracketed, shown: if r.bracketed { "yes" } else { "NO" } },
        ]);
    }
    t
}

/// The reference's timings as committed.
pub(super) fn timing_table(s: &SkfemComparison) -> Table {
    let mut t = Table::new("", &["code", "element", "mesh", "DOFs", "time (s)", "rel. error"]);
    let num = |t: &str| {
        t.parse::<u64>().map(Cell::Int).or_else(|_| t.parse::<f64>().map(Cell::Num)).unwrap_or(Cell::Text(t.into()))
    };
    for c in &s.timing {
        t.push(vec![c[0].clone().into(), c[1].clone().into(), c[2].clone().into(), num(&c[3]), num(&c[4]), num(&c[5])]);
    }
    t
}

/// The thick ladders of the Mindlin plate against Navier's series with shear.
pub fn mindlin_thick_table(d: &MindlinVerification) -> Table {
    let mut t = Table::new(
        "",
        &["h/L", "elements a side", "C FE (m/N)", "C series (m/N)", "FE/series - 1", "shear share (series)"],
    );
    for l in &d.thick {
        for &(n, c) in &l.values {
            t.push(vec![
                Cell::Given(l.ratio),
                Cell::Int(n as u64),
                Cell::Num(c),
                Cell::Num(l.series.0),
                Cell::Rel(c / l.series.0 - 1.0),
                Cell::Rel(l.shear_share),
            ]);
        }
    }
    t
}

/// The node supports' compliance per mesh, each increment against the predicted growth.
pub fn mindlin_growth_table(d: &MindlinVerification) -> Table {
    let mut t = Table::new("", &["elements a side", "C FE (m/N)", "increment (m/N)", "increment / predicted"]);
    let mut previous: Option<f64> = None;
    for &(n, c) in &d.growth.values {
        let (inc, ratio) = match previous {
            Some(p) => (Cell::Num(c - p), Cell::Sig((c - p) / d.growth.predicted, 4)),
            None => (Cell::Empty, Cell::Empty),
        };
        t.push(vec![Cell::Int(n as u64), Cell::Num(c), inc, ratio]);
        previous = Some(c);
    }
    t
}
