//! The comparison's maps: C_plate/C_beam over the plate per support set the beam describes,
//! the compliance along the plate and the ratio across it at the paper's Areas, and `maps.csv`.

use super::Numbers;
use crate::present::plot::{line_plot, Axis, ColourMap, Scale, Series};
use crate::present::rows::slug;
use crate::present::table::{percent, Table};
use crate::template::render;
use crate::Failure;
use output::Artifacts;
use scene::Scene;
use studies::comparison::maps::nearest;
use studies::comparison::{MapFinding, Maps, INNER};
use studies::settings::{AREAS, MAP_X, MAP_Z};

const ACROSS: &str = include_str!("../templates/comparison/across.md");
const NO_MAP: &str = include_str!("../templates/comparison/no-map.md");
const MAP: &str = include_str!("../templates/comparison/map.md");
const FINDING_MAP: &str = include_str!("../templates/comparison/finding-map.md");

/// Every map value as a table (`maps.csv`).
fn map_table(scene: &Scene, mp: &Maps, findings: &[MapFinding]) -> Table {
    let mut t = Table::new(
        "",
        &["condition", "x (mm)", "z (mm)", "C beam (m/N)", "C plate (m/N)", "FE ± (m/N)", "C plate/beam - 1"],
    );
    for f in findings {
        let ci = f.index;
        for (i, &x) in mp.xs.iter().enumerate() {
            for (j, &z) in mp.zs.iter().enumerate() {
                t.push(vec![
                    scene.conditions[ci].name.clone().into(),
                    (x * 1e3).into(),
                    (z * 1e3).into(),
                    mp.beam[ci][i].into(),
                    mp.plate[ci][i][j].into(),
                    mp.error[ci][i][j].into(),
                    mp.ratio(ci, i, j).into(),
                ]);
            }
        }
    }
    t
}

/// The colour map of C_plate/C_beam of one support set, within [`INNER`].
fn colour_map(scene: &Scene, mp: &Maps, f: &MapFinding) -> ColourMap {
    let (ci, l) = (f.index, scene.plate.length());
    ColourMap {
        title: format!("{}: C_plate / C_beam over the plate", f.condition),
        x: Axis::linear("x (mm)"),
        y: Axis::linear("z (mm)"),
        xs: mp.xs.iter().map(|x| x * 1e3).collect(),
        ys: mp.zs.iter().map(|z| z * 1e3).collect(),
        edges: false,
        values: (0..mp.xs.len())
            .map(|i| {
                (0..mp.zs.len()).map(|j| if mp.inner(i, l) { mp.ratio(ci, i, j) + 1.0 } else { f64::NAN }).collect()
            })
            .collect(),
        bar: Axis::log("C_plate / C_beam"),
        missing: Some(format!(
            "x < {} L and x > {} L, where the beam's C falls to 0 and the ratio diverges",
            INNER.0, INNER.1
        )),
        marks: vec![],
        notes: vec!["Supports at the four corners; the beam has the same C across the width.".into()],
    }
}

/// The compliance along the plate (beam, plate on the centreline and the free edge), and
/// C_plate/C_beam across the width at the paper's Areas.
fn line_plots(scene: &Scene, mp: &Maps, f: &MapFinding) -> (String, String) {
    let (ci, (_, zc, ze)) = (f.index, f.grid);
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
    let along =
        line_plot(&format!("{}: compliance along the plate", f.condition), "x (mm)", "C (m/N)", &series, Scale::Linear);
    let across: Vec<Series> = AREAS
        .iter()
        .enumerate()
        .map(|(k, a)| {
            let i = nearest(&mp.xs, a * scene.plate.length());
            Series::new(
                format!("Area {} (x = {:.0} mm)", k + 1, mp.xs[i] * 1e3),
                mp.zs.iter().enumerate().map(|(j, z)| (z * 1e3, mp.ratio(ci, i, j) + 1.0)).collect(),
            )
        })
        .collect();
    let across = line_plot(
        &format!("{}: C_plate/C_beam across the width", f.condition),
        "z (mm)",
        "C_plate / C_beam (log)",
        &across,
        Scale::Log,
    );
    (along, across)
}

/// The maps' section: per support set its figures (or why there are none), its finding and
/// numbers; `maps.csv` and the figures into `a`.
pub(super) fn section(
    scene: &Scene,
    mp: &Maps,
    map_findings: &[MapFinding],
    a: &mut Artifacts,
    findings: &mut Vec<String>,
    numbers: &mut Numbers,
) -> Result<String, Failure> {
    let mut figures = render(
        "comparison/across.md",
        ACROSS,
        &[
            ("inner_from", INNER.0.to_string()),
            ("inner_to", INNER.1.to_string()),
            ("map_x", MAP_X.to_string()),
            ("map_z", MAP_Z.to_string()),
            ("areas", AREAS.len().to_string()),
        ],
    )?;
    for (ci, c) in scene.conditions.iter().enumerate() {
        let Some(f) = map_findings.iter().find(|f| f.index == ci) else {
            figures.push_str(&render("comparison/no-map.md", NO_MAP, &[("condition", c.name.clone())])?);
            continue;
        };
        let stem = format!("map-{}", slug(&c.name));
        a.add(format!("{stem}.svg"), colour_map(scene, mp, f).svg());
        numbers.insert(
            format!("{}: map C_plate/C_beam - 1", c.name),
            serde_json::json!({ "lowest": f.lowest, "highest": f.highest, "centre": f.centre, "free_edge": f.free_edge }),
        );
        let map_values = [
            ("condition", c.name.clone()),
            ("inner_from", INNER.0.to_string()),
            ("inner_to", INNER.1.to_string()),
            ("lowest", percent(f.lowest)),
            ("highest", percent(f.highest)),
            ("centre", percent(f.centre)),
            ("edge", percent(f.free_edge)),
        ];
        findings.push(render("comparison/finding-map.md", FINDING_MAP, &map_values)?);
        let (along, across) = line_plots(scene, mp, f);
        a.add(format!("{stem}-along.svg"), along);
        a.add(format!("{stem}-across.svg"), across);
        let mut with_stem = map_values.to_vec();
        with_stem.push(("stem", stem.clone()));
        figures.push_str(&render("comparison/map.md", MAP, &with_stem)?);
    }
    a.add("maps.csv", map_table(scene, mp, map_findings).to_csv());
    Ok(figures)
}
