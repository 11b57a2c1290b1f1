//! The transverse-shear section: Mindlin's plate beside Kirchhoff's at the scene's points.

use crate::present::table::{percent, sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use output::Artifacts;
use scene::Scene;
use studies::comparison::{Shear, ShearRow};

const SECTION: &str = include_str!("../templates/comparison/shear.md");
const FINDING: &str = include_str!("../templates/comparison/finding-shear.md");

/// Mindlin/Kirchhoff - 1 of a row's compliance.
fn excess(r: &ShearRow) -> f64 {
    r.mindlin / r.kirchhoff - 1.0
}

/// The table of both plates at every support set and point.
pub fn table(d: &Shear) -> Table {
    let mut t = Table::new(
        "",
        &[
            "condition",
            "x (mm)",
            "z (mm)",
            "C Kirchhoff (m/N)",
            "C Mindlin (m/N)",
            "Mindlin/Kirchhoff - 1",
            "estimates (rel.)",
            "C Kirchhoff same patch (m/N)",
            "shear alone",
            "shear share",
            "P_max Kirchhoff (N)",
            "P_max Mindlin (N)",
            "P rel. diff.",
        ],
    );
    for r in &d.rows {
        let (pk, pm) = r.p_max.map_or((Cell::Empty, Cell::Empty), |(k, m)| (Cell::Num(k), Cell::Num(m)));
        let rel = r.p_max.map_or(Cell::Empty, |(k, m)| Cell::Rel(m / k - 1.0));
        t.push(vec![
            Cell::Text(r.condition.clone()),
            Cell::Given(r.x * 1e3),
            Cell::Given(r.z * 1e3),
            Cell::Measured { value: r.kirchhoff, error: r.kirchhoff_error },
            Cell::Measured { value: r.mindlin, error: r.mindlin_error },
            Cell::Rel(excess(r)),
            Cell::Sig(r.kirchhoff_error / r.kirchhoff + r.mindlin_error / r.mindlin, 2),
            Cell::Num(r.kirchhoff_patch),
            Cell::Rel(r.mindlin / r.kirchhoff_patch - 1.0),
            Cell::Rel(r.shear / r.mindlin),
            pk,
            pm,
            rel,
        ]);
    }
    t
}

/// The section and its finding; the table's CSV into `a`.
pub fn section(scene: &Scene, d: &Shear, a: &mut Artifacts, findings: &mut Vec<String>) -> Result<String, Failure> {
    let t = table(d);
    a.add("transverse-shear.csv", t.to_csv());
    let levels: Vec<String> = d.levels.iter().map(|c| format!("{} x {}", c.nx, c.nz)).collect();
    let ratio = sig(d.thickness_ratio, 3);
    let section = render(
        "comparison/shear.md",
        SECTION,
        &[
            ("thickness_mm", sig(scene.plate.thickness() * 1e3, 4)),
            ("levels", levels.join(", ")),
            ("ratio", ratio.clone()),
            ("thin", if d.thickness_ratio <= 0.05 { "inside" } else { "beyond" }.into()),
            (
                "first",
                match (scene.bodies.first(), scene.velocities.first()) {
                    (Some(b), Some(v)) => format!("{} at {v} m/s", b.name),
                    _ => "not computed (no responses)".into(),
                },
            ),
            ("seconds", format!("{:.1}", d.seconds)),
            ("table", t.to_markdown()),
        ],
    )?;
    let range = |v: Vec<f64>| v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)));
    let (low, high) = range(d.rows.iter().map(excess).collect());
    let (share_low, share_high) = range(d.rows.iter().map(|r| r.shear / r.mindlin).collect());
    let (alone_low, alone_high) = range(d.rows.iter().map(|r| r.mindlin / r.kirchhoff_patch - 1.0).collect());
    let (p_low, p_high) = range(d.rows.iter().filter_map(|r| r.p_max.map(|(k, m)| m / k - 1.0)).collect());
    let (cx, cz) = (scene.plate.length() / 2.0, scene.plate.width() / 2.0);
    let centre = d.rows.iter().min_by(|a, b| (a.x - cx).hypot(a.z - cz).total_cmp(&(b.x - cx).hypot(b.z - cz)));
    let resolved = d.rows.iter().all(|r| (r.mindlin - r.kirchhoff).abs() > r.mindlin_error + r.kirchhoff_error);
    if d.rows.is_empty() {
        return Ok(section);
    }
    findings.push(render(
        "comparison/finding-shear.md",
        FINDING,
        &[
            ("ratio", ratio),
            ("low", percent(low)),
            ("high", percent(high)),
            ("centre", centre.map_or_else(String::new, |r| percent(excess(r)))),
            ("resolved", if resolved { "beyond" } else { "not everywhere beyond" }.into()),
            ("alone_low", percent(alone_low)),
            ("alone_high", percent(alone_high)),
            ("share_low", percent(share_low)),
            ("share_high", percent(share_high)),
            ("p_low", if p_low.is_finite() { percent(p_low) } else { "-".into() }),
            ("p_high", if p_high.is_finite() { percent(p_high) } else { "-".into() }),
        ],
    )?);
    Ok(section)
}
