//! The paper's own studies redone with both models: its conclusions (section V) item by item,
//! Tables 6-8 and 11 at the midpoint, and its figures along the centreline.

use crate::present::plot::{line_plot, Matrix, Scale};
use crate::present::table::Table;
use crate::Failure;
use coupled::{BeamModel, ComplianceModel, PlateModel};
use output::Artifacts;
use scene::Scene;
use studies::settings::{BASE_MESH, LEVELS};

/// The report's prose, every number in it a placeholder.
const TEMPLATE: &str = include_str!("templates/paper_studies.md");
/// The impact velocity of the paper's Tables 6-8 and 11, m/s.
const TABLES_VELOCITY: f64 = 0.0025;

/// The paper's conclusions item by item, Tables 6-8 and 11 and the paper's figures, each
/// under both models (the paper's own scene, whatever `scene` is).
pub fn report(_scene: &Scene) -> Result<Artifacts, Failure> {
    let mut a = Artifacts::new();
    let checks = crate::conclusions::checks()?;
    let t = crate::conclusions::table(&checks);
    a.add("conclusions.csv", t.to_csv());
    let matrix = Matrix {
        title: "Section V's conclusions: do they hold?".into(),
        columns: vec!["beam".into(), "plate FE".into()],
        rows: checks.iter().map(|c| format!("{}: {}", c.item, c.statement)).collect(),
        cells: checks.iter().map(|c| vec![c.beam_holds.into(), c.plate_holds.into()]).collect(),
    };
    a.add("conclusions.svg", matrix.svg());
    let held = |p: bool| checks.iter().filter(|c| if p { c.plate_holds } else { c.beam_holds }).count();
    let items = checks.iter().filter_map(|c| c.item.parse::<u32>().ok()).max().ok_or("no numbered item")?;
    // Tables 6-8 and 11 of the paper (midpoint, 0.0025 m/s, three spheres) under both models.
    let paper = crate::paper::Paper::new();
    let sc = &paper.scene;
    let mid = (sc.plate.length() / 2.0, sc.plate.width() / 2.0);
    let model = PlateModel::compute(&sc.plate, &sc.conditions, &[mid], BASE_MESH, LEVELS)?;
    let beam = BeamModel { plate: &sc.plate };
    let mut t68 = Table::new(
        "",
        &[
            "condition",
            "body",
            "P_max beam (N)",
            "P_max plate (N)",
            "δ_max beam (1e-7 m)",
            "δ_max plate (1e-7 m)",
            "deflection beam (1e-7 m)",
            "deflection plate (1e-7 m)",
            "rock total beam",
            "rock total plate",
            "plate energy beam",
            "plate energy plate",
            "spring energy beam",
            "spring energy plate",
        ],
    );
    for cond in &sc.conditions {
        for body in paper.bodies() {
            let imp = coupled::plan::impact_of(sc, body, TABLES_VELOCITY);
            let m = analytic::Method::Bracketed { tolerance: 1e-13, max_iterations: 200 };
            let rb = analytic::respond(&imp, &beam.compliance(cond, mid.0, mid.1)?.compliance, m)?;
            let rp = analytic::respond(&imp, &model.compliance(cond, mid.0, mid.1)?.compliance, m)?;
            t68.push(vec![
                cond.name.clone().into(),
                body.name.clone().into(),
                rb.contact_force.into(),
                rp.contact_force.into(),
                (rb.compression * 1e7).into(),
                (rp.compression * 1e7).into(),
                (rb.deflection * 1e7).into(),
                (rp.deflection * 1e7).into(),
                rb.rock_total_ratio.into(),
                rp.rock_total_ratio.into(),
                rb.plate_ratio.into(),
                rp.plate_ratio.into(),
                rb.spring_ratio.into(),
                rp.spring_ratio.into(),
            ]);
        }
    }
    a.add("tables-6-8-11-both-models.csv", t68.to_csv());
    let mut figures = String::new();
    for crate::conclusions::Figure { stem, title, y_label: ylabel, series } in crate::conclusions::study_figures()? {
        a.add(format!("{stem}.svg"), line_plot(&title, "x (mm)", &ylabel, &series, Scale::Linear));
        a.add(format!("{stem}.csv"), crate::present::plot::series_csv(&series, "x (mm)", &ylabel));
        figures.push_str(&format!("![{title}]({stem}.svg)\n\n"));
    }
    // The template ends the last figure's line itself.
    figures.pop();
    let md = crate::template::render(
        "paper_studies.md",
        TEMPLATE,
        &[
            ("items", items.to_string()),
            ("beam_held", held(false).to_string()),
            ("statements", checks.len().to_string()),
            ("plate_held", held(true).to_string()),
            ("conclusions_table", t.to_markdown()),
            ("velocity", TABLES_VELOCITY.to_string()),
            ("tables_6_8_11", t68.to_markdown()),
            ("figures", figures),
        ],
    )?;
    a.add("index.md", md);
    Ok(a)
}
