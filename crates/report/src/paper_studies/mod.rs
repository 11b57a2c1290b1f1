//! The paper's own studies redone with both models: its conclusions (section V) item by item,
//! Tables 6-8 and 11 at the midpoint, and its figures along the centreline.
//!
//! The studies compute in [`studies::paper_studies`]; here they become the page, the
//! conclusions' table and matrix, the tables' CSV and the figures with their curves' CSV.

pub mod conclusions;

use crate::present::plot::{line_plot, series_csv, Matrix, Scale, Series};
use crate::present::table::Table;
use crate::template::render;
use crate::Failure;
use output::Artifacts;
use scene::Scene;
use studies::paper_studies::{MidpointRow, PaperStudiesData, StudyFigure};
use studies::progress::{Progress, Silent};
use studies::settings::Settings;
use studies::study::{PaperStudies, Study};

/// The report's prose, every number in it a placeholder.
const TEMPLATE: &str = include_str!("../templates/paper_studies.md");
/// One figure's line on the page.
const FIGURE: &str = include_str!("../templates/paper_studies/figure.md");

/// The title and y label of each figure, by its file stem.
const FIGURES: [(&str, &str, &str); 12] = [
    ("study-fig08-yield-coal", "Fig. 8 redone: coal yield velocity along the centreline", "v_y (m/s)"),
    ("study-fig10-contact-force", "Fig. 10(1) redone: coal P_max at 0.008 m/s, centreline", "P_max (N)"),
    ("study-fig10-deflection", "Fig. 10(3) redone: impact-point deflection, centreline", "deflection (µm)"),
    ("study-fig11-yield-stiffness", "Fig. 11 redone: coal yield velocity, Con 2, three k_T", "v_y (m/s)"),
    ("study-fig12-yield-stiffness-con3", "Fig. 12 redone: coal yield velocity, Con 3, three k_T", "v_y (m/s)"),
    (
        "study-fig13-spring-energy",
        "Fig. 13(8) redone: spring energy ratio, coal 0.008 m/s, three k_T",
        "spring energy / E0",
    ),
    ("study-fig18-spring-force", "Fig. 18 redone: right-end spring force, Con 2, 0.0025 m/s", "spring force (N)"),
    ("study-fig19-spring-energy", "Fig. 19 redone: spring energy ratio, Con 2, 0.0025 m/s", "spring energy / E0"),
    ("study-fig17-contact-force-bodies", "Fig. 17(2) redone: P_max of three spheres at 0.0025 m/s, Con 1", "P_max (N)"),
    (
        "study-fig15-spring-force-length",
        "Fig. 15 redone: left-end spring force, Con 2, k_T = 5e6 N/m, coal 0.008 m/s, four lengths",
        "spring force (N)",
    ),
    (
        "study-fig16-spring-energy-length",
        "Fig. 16 redone: spring energy ratio, Con 2, k_T = 5e6 N/m, four lengths",
        "spring energy / E0",
    ),
    (
        "study-fig14-contact-force-length",
        "Fig. 14(1) redone: coal P_max at 0.008 m/s, Con 1, four lengths",
        "P_max (N)",
    ),
];

/// Tables 6-8 and 11 under both models.
fn midpoint_table(rows: &[MidpointRow]) -> Table {
    let mut t = Table::new(
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
    for r in rows {
        let (b, p) = (&r.beam, &r.plate);
        t.push(vec![
            r.condition.clone().into(),
            r.body.clone().into(),
            b.contact_force.into(),
            p.contact_force.into(),
            (b.compression * 1e7).into(),
            (p.compression * 1e7).into(),
            (b.deflection * 1e7).into(),
            (p.deflection * 1e7).into(),
            b.rock_total_ratio.into(),
            p.rock_total_ratio.into(),
            b.plate_ratio.into(),
            p.plate_ratio.into(),
            b.spring_ratio.into(),
            p.spring_ratio.into(),
        ]);
    }
    t
}

/// A figure's curves, named "beam ..." and "plate ...".
fn series(f: &StudyFigure) -> Vec<Series> {
    f.curves
        .iter()
        .map(|c| Series::new(format!("{} {}", if c.plate { "plate" } else { "beam" }, c.label), c.points.clone()))
        .collect()
}

/// The figures' files, and their lines on the page.
fn figures(d: &PaperStudiesData, a: &mut Artifacts) -> Result<String, Failure> {
    let mut lines = Vec::new();
    for f in &d.figures {
        let (_, title, y_label) =
            FIGURES.iter().find(|(stem, ..)| *stem == f.stem).ok_or_else(|| format!("no caption for {}", f.stem))?;
        let series = series(f);
        a.add(format!("{}.svg", f.stem), line_plot(title, "x (mm)", y_label, &series, Scale::Linear));
        a.add(format!("{}.csv", f.stem), series_csv(&series, "x (mm)", y_label));
        lines.push(render(
            "paper_studies/figure.md",
            FIGURE,
            &[("title", title.to_string()), ("stem", f.stem.clone())],
        )?);
    }
    Ok(lines.join("\n"))
}

/// The studies' files from their data.
pub fn files(d: &PaperStudiesData) -> Result<Artifacts, Failure> {
    let mut a = Artifacts::new();
    let checks = &d.checks;
    let t = conclusions::table(checks)?;
    a.add("conclusions.csv", t.to_csv());
    let matrix = Matrix {
        title: "Section V's conclusions: do they hold?".into(),
        columns: vec!["beam".into(), "plate FE".into()],
        rows: checks
            .iter()
            .map(|c| Ok(format!("{}: {}", c.item, conclusions::statement(c)?)))
            .collect::<Result<_, Failure>>()?,
        cells: checks.iter().map(|c| vec![c.beam_holds.into(), c.plate_holds.into()]).collect(),
    };
    a.add("conclusions.svg", matrix.svg());
    let held = |p: bool| checks.iter().filter(|c| if p { c.plate_holds } else { c.beam_holds }).count();
    let items = checks.iter().map(|c| c.item).max().ok_or("no numbered item")?;
    let t68 = midpoint_table(&d.midpoint);
    a.add("tables-6-8-11-both-models.csv", t68.to_csv());
    let figures = figures(d, &mut a)?;
    let md = render(
        "paper_studies.md",
        TEMPLATE,
        &[
            ("items", items.to_string()),
            ("beam_held", held(false).to_string()),
            ("statements", checks.len().to_string()),
            ("plate_held", held(true).to_string()),
            ("conclusions_table", t.to_markdown()),
            ("velocity", d.velocity.to_string()),
            ("tables_6_8_11", t68.to_markdown()),
            ("figures", figures),
        ],
    )?;
    a.add("index.md", md);
    Ok(a)
}

/// The paper's conclusions item by item, Tables 6-8 and 11 and the paper's figures, each
/// under both models (the paper's own scene, whatever `scene` is).
pub fn report(scene: &Scene) -> Result<Artifacts, Failure> {
    study(scene, &Silent)
}

/// [`report`], reporting its progress.
pub fn study(scene: &Scene, progress: &dyn Progress) -> Result<Artifacts, Failure> {
    files(&PaperStudies::compute(scene, &Settings::default(), progress)?)
}
