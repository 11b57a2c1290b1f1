//! Figures 8-19 of the paper drawn from their panels ([`studies::paper::Panel`]): each panel's
//! title and axis label, its SVG and the CSV of its curves.

use crate::present::plot::{line_plot, series_csv, Scale, Series};
use crate::template::render;
use crate::Failure;
use output::Artifacts;
use studies::paper::{Drawn, Panel};

/// A figure's heading on the page.
const HEADING: &str = include_str!("../templates/paper/figure-heading.md");
/// A panel's line on the page.
const PANEL: &str = include_str!("../templates/paper/panel.md");

/// The y labels of [`studies::paper::RESPONSE_PANELS`], in its order.
const RESPONSE_LABELS: [&str; 8] = [
    "Maximum contact force (N)",
    "Maximum rock compression (µm)",
    "Impact-point deflection (µm)",
    "Spring force (N)",
    "Rock total energy ratio",
    "Rock absorbed energy ratio",
    "Plate energy ratio",
    "Spring energy ratio",
];

/// The titles of the yield-velocity panels, by stem.
const YIELD_TITLES: [(&str, &str); 4] = [
    ("fig08-yield-coal", "Fig. 8 Yield velocity of the coal sphere"),
    ("fig09-yield-gangue1", "Fig. 9 Yield velocity of gangue sphere 1"),
    ("fig11-yield-con2-stiffness", "Fig. 11 Yield velocity, Con 2, three k_T"),
    ("fig12-yield-con3-stiffness", "Fig. 12 Yield velocity, Con 3, three k_T"),
];

/// What each response figure shows, by figure number.
const RESPONSE_CASES: [(&str, &str); 7] = [
    ("10", "coal, v = 0.008 m/s"),
    ("13", "coal, v = 0.008 m/s, three k_T"),
    ("14", "coal, v = 0.008 m/s, k_T = 5e6 N/m, four lengths"),
    ("15", "coal, v = 0.008 m/s, k_T = 5e6 N/m, four lengths"),
    ("16", "coal, v = 0.008 m/s, k_T = 5e6 N/m, four lengths"),
    ("17", "three spheres, v = 0.0025 m/s"),
    ("18", "three spheres, v = 0.0025 m/s"),
];

/// The title and y label of a panel.
fn caption(p: &Panel) -> Result<(String, &'static str), Failure> {
    let missing = || format!("no caption for panel {}", p.stem);
    Ok(match p.drawn {
        Drawn::Yield => {
            let title = YIELD_TITLES.iter().find(|(s, _)| *s == p.stem).ok_or_else(missing)?.1;
            (title.to_string(), "Yield velocity (m/s)")
        }
        Drawn::Response { quantity, panel } => {
            // Fig. 19 shows the cases of Fig. 18.
            let fig = if p.figure == "19" { "18" } else { p.figure.as_str() };
            let what = RESPONSE_CASES.iter().find(|(f, _)| *f == fig).ok_or_else(missing)?.1;
            let label = RESPONSE_LABELS.get(quantity).ok_or_else(missing)?;
            (format!("Fig. {}({panel}) {what}", p.figure), label)
        }
    })
}

/// The panels' SVG and CSV files, and their Markdown: a heading per figure, a line per panel.
pub(super) fn figures(panels: &[Panel], a: &mut Artifacts) -> Result<String, Failure> {
    let mut fig_md = String::new();
    let mut last_fig = String::new();
    for p in panels {
        let (title, y_label) = caption(p)?;
        let series: Vec<Series> = p.curves.iter().map(|c| Series::new(c.name.clone(), c.points.clone())).collect();
        let scale = if p.log { Scale::Log } else { Scale::Linear };
        a.add(format!("{}.svg", p.stem), line_plot(&title, "Impact position x (mm)", y_label, &series, scale));
        a.add(format!("{}.csv", p.stem), series_csv(&series, "x (mm)", y_label));
        let fig = p.stem[..5].to_string();
        if fig != last_fig {
            let number = fig[3..].trim_start_matches('0').to_string();
            fig_md.push_str(&render("paper/figure-heading.md", HEADING, &[("figure", number)])?);
            last_fig = fig;
        }
        fig_md.push_str(&render("paper/panel.md", PANEL, &[("title", title), ("stem", p.stem.clone())])?);
    }
    Ok(fig_md)
}
