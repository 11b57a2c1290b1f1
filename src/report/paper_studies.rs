//! The paper's own studies redone with both models: its conclusions (section V) item by item,
//! Tables 6-8 and 11 at the midpoint, and its figures along the centreline.

use crate::output::Artifacts;
use crate::present::plot::{line_plot, Scale};
use crate::present::table::Table;
use crate::report::studies::{BASE_MESH, LEVELS};
use crate::report::Failure;
use crate::scene::Scene;
use coupled::{BeamModel, ComplianceModel, PlateModel};
use std::fmt::Write as _;

/// The paper's conclusions item by item, Tables 6-8 and 11 and the paper's figures, each
/// under both models (the paper's own scene, whatever `scene` is).
pub fn report(_scene: &Scene) -> Result<Artifacts, Failure> {
    let mut a = Artifacts::new();
    let checks = crate::report::conclusions::checks()?;
    let t = crate::report::conclusions::table(&checks);
    a.add("conclusions.csv", t.to_csv());
    let held = |p: bool| checks.iter().filter(|c| if p { c.plate_holds } else { c.beam_holds }).count();
    let mut md = String::from("# The paper's own studies under both models\n\nThe paper's scene (Table 1), whatever scene asked for these studies: its conclusions, its Tables 6-8 and 11 and its figures, each with the beam and with the plate FE compliance through the same balance.\n");
    let _ = writeln!(
        md,
        "\n## Do the paper's conclusions hold under the plate model?\n\nSection V's items 1-5, each tested on the paper's scene with the beam and with the plate FE model, on the centreline (where the beam should be closest) and on a free edge z = 0. {} of {} statements hold under the beam, {} under the plate. Values are from the same energy balance; only C differs.\n\n{}",
        held(false),
        checks.len(),
        held(true),
        t.to_markdown()
    );
    // Tables 6-8 and 11 of the paper (midpoint, 0.0025 m/s, three spheres) under both models.
    let paper = crate::report::paper::Paper::new();
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
            let imp = coupled::plan::impact_of(sc, body, 0.0025);
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
    let _ = writeln!(md, "\n### Tables 6-8 and 11 under both models\n\nThe paper's midpoint responses of the three spheres at 0.0025 m/s (Tables 6-8; spring energy of Table 11), with the beam (the paper's equations, converged) and with the plate FE compliance at the centre of the plate.\n\n{}", t68.to_markdown());

    let _ = writeln!(md, "\n### The paper's figures redone with both models (centreline)\n\nBeam curves are the paper's equations; plate curves the same balance with the plate FE compliance on the centreline z = B/2. CSV of every curve beside each SVG.\n");
    for crate::report::conclusions::Figure { stem, title, y_label: ylabel, series } in
        crate::report::conclusions::study_figures()?
    {
        a.add(format!("{stem}.svg"), line_plot(&title, "x (mm)", &ylabel, &series, Scale::Linear));
        a.add(format!("{stem}.csv"), crate::present::plot::series_csv(&series));
        let _ = writeln!(md, "![{title}]({stem}.svg)\n");
    }
    a.add("index.md", md);
    Ok(a)
}
