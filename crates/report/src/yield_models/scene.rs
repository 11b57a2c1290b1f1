//! The three-model yield study on a scene of one's own, rendered: its page, its CSV file, the
//! main report's section and a finding per body.

use super::{YieldSummary, FOLDER};
use crate::present::rows::validity_text;
use crate::present::table::{sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use output::Artifacts;
use scene::Scene;
use studies::yield_models::scene::SceneYieldData;

/// The study's page, the main report's section and a finding per body.
const SCENE_PAGE: &str = include_str!("../templates/yield/scene.md");
const SCENE_SECTION: &str = include_str!("../templates/yield/scene-section.md");
const SCENE_FINDING: &str = include_str!("../templates/yield/scene-finding.md");

/// Every cell under the three models.
fn table(d: &SceneYieldData) -> Table {
    let mut t = Table::new(
        "",
        &[
            "body",
            "condition",
            "x (mm)",
            "z (mm)",
            "beam (m/s)",
            "plate (m/s)",
            "plate ± (m/s)",
            "transient (m/s)",
            "transient ± (m/s)",
            "plate/beam - 1",
            "transient/plate - 1",
            "transient below plate",
            "plate validity",
        ],
    );
    for r in &d.rows {
        t.push(vec![
            r.body.clone().into(),
            r.condition.clone().into(),
            (r.x * 1e3).into(),
            (r.z * 1e3).into(),
            r.beam.map_or(Cell::Empty, Cell::from),
            r.plate.into(),
            r.plate_error.into(),
            r.transient.into(),
            r.transient_error.into(),
            r.plate_over_beam().map_or(Cell::Empty, Cell::from),
            r.transient_over_plate().into(),
            r.below_plate.word().into(),
            validity_text(&r.plate_validity).into(),
        ]);
    }
    t
}

/// One finding line per body with cells.
fn findings(d: &SceneYieldData) -> Result<String, Failure> {
    let mut out = String::new();
    for b in &d.bodies {
        out.push_str(&render(
            "yield/scene-finding.md",
            SCENE_FINDING,
            &[
                ("body", b.body.clone()),
                ("v_lo", sig(b.transient.0, 3)),
                ("v_hi", sig(b.transient.1, 3)),
                ("rel_lo", sig(100.0 * b.transient_over_plate.0, 3)),
                ("rel_hi", sig(100.0 * b.transient_over_plate.1, 3)),
                ("below", b.below.to_string()),
                ("open", b.open.to_string()),
                ("cells", b.cells.to_string()),
                ("folder", FOLDER.to_string()),
            ],
        )?);
    }
    Ok(out)
}

/// The study's files and what the main report shows of it.
pub(super) fn files(scene: &Scene, d: &SceneYieldData) -> Result<(Artifacts, YieldSummary), Failure> {
    let t = table(d);
    let findings = findings(d)?;
    let values = [
        ("scene", scene.name.clone()),
        ("plate_base", d.plate_base_mesh.to_string()),
        ("plate_finest", d.plate_finest_mesh.to_string()),
        ("root_tolerance", format!("{:e}", d.root_tolerance)),
        ("table", t.to_markdown()),
    ];
    let mut a = Artifacts::new();
    a.add(
        "index.md",
        render("yield/scene.md", SCENE_PAGE, &[values.to_vec(), vec![("findings", findings.clone())]].concat())?,
    );
    a.add(
        "yield-three-models.csv",
        t.clone().csv_name("transient below plate", &["transient_below_plate_verdict"]).to_csv(),
    );
    let section = render(
        "yield/scene-section.md",
        SCENE_SECTION,
        &[("findings", findings.clone()), ("table", t.to_markdown()), ("folder", FOLDER.to_string())],
    )?;
    Ok((a, YieldSummary { section, finding: findings }))
}
