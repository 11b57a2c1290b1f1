//! The window-level sensor design of a stream study ([`studies::stream::WindowDesign`]): per
//! support set a table of steps and the first step's map over the candidate grid.

use crate::present::table::{sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use studies::stream::{StreamData, WindowDesign, WindowDesignStep};

const DESIGN: &str = include_str!("templates/stream/design.md");

/// Features listed per design, of the chosen sensors' every feature.
const SHOWN_FEATURES: usize = 6;

/// The design section of the stream page; empty where the scene asks for no design.
pub(crate) fn section(d: &StreamData) -> Result<String, Failure> {
    let designs: Vec<(&str, &WindowDesign)> =
        d.conditions.iter().filter_map(|c| c.design.as_ref().map(|g| (c.name.as_str(), g))).collect();
    let Some((_, first)) = designs.first() else { return Ok(String::new()) };
    let noise = if d.measured {
        "recorded through the scene's measurement chain at its stated background"
    } else {
        "noise-free: the scene has no measurement chain, so the design says where the signals differ most, not what survives a mine's noise"
    };
    let tables: Vec<String> = designs
        .iter()
        .map(|(name, g)| {
            format!(
                "### {name}\n\n{}\nWindow AUC with one more sensor at each candidate point, at the first step (● the point chosen):\n\n{}\nThe features the chosen sensors' detector weighs most, fitted on every window:\n\n{}",
                steps(g).to_markdown(),
                first_map(g).to_markdown(),
                features(g).to_markdown()
            )
        })
        .collect();
    Ok(render(
        "stream/design.md",
        DESIGN,
        &[
            ("count", first.steps.len().to_string()),
            ("quantity", first.quantity.to_string()),
            ("candidates", (first.x_mm.len() * first.z_mm.len()).to_string()),
            ("noise", noise.to_string()),
            ("designs", tables.join("\n")),
        ],
    )?)
}

/// The design in a sentence for the findings' index, as a paragraph of its own (a blank line
/// before it): per support set the first sensor's point and window AUC and the last step's
/// (empty where the scene asks for no design).
pub(crate) fn headline(d: &StreamData) -> String {
    let sets: Vec<String> = d
        .conditions
        .iter()
        .filter_map(|c| {
            let g = c.design.as_ref()?;
            let (first, last) = (g.steps.first()?, g.steps.last()?);
            let auc = |s: &WindowDesignStep| {
                format!("{} ({}-{})", sig(s.score.auc, 3), sig(s.score.interval.0, 3), sig(s.score.interval.1, 3))
            };
            Some(format!(
                "{}: the first at ({}, {}) mm, window AUC {}; {} of them {}",
                c.name,
                sig(first.at_mm.0, 4),
                sig(first.at_mm.1, 4),
                auc(first),
                g.steps.len(),
                auc(last)
            ))
        })
        .collect();
    let Some(g) = d.conditions.iter().find_map(|c| c.design.as_ref()) else { return String::new() };
    format!(
        "\nWhere to put {} {} sensors for the window detector (the page's design, chosen greedily among {} candidate points, each step's AUC the best of many on the same blocks): {}.",
        g.steps.len(),
        g.quantity,
        g.x_mm.len() * g.z_mm.len(),
        sets.join("; ")
    ) + "\n"
}

/// One row per step: where, the window AUC so far with its interval, the gain with its paired
/// interval, the delay and the false alarms.
fn steps(g: &WindowDesign) -> Table {
    let mut t = Table::new(
        "",
        &[
            "sensors",
            "added at (x, z) (mm)",
            "window AUC (95 % interval)",
            "gain (95 % interval; paired from the second sensor on)",
            "median delay",
            "false alarms per hour (count)",
        ],
    );
    for (k, s) in g.steps.iter().enumerate() {
        let score = &s.score;
        t.push(vec![
            Cell::Int(k as u64 + 1),
            format!("({}, {})", sig(s.at_mm.0, 4), sig(s.at_mm.1, 4)).into(),
            format!("{} ({}-{})", sig(score.auc, 3), sig(score.interval.0, 3), sig(score.interval.1, 3)).into(),
            format!("{:+.3} ({:+.3} to {:+.3})", s.gain, s.gain_interval.0, s.gain_interval.1).into(),
            score.median_delay_s.map_or_else(|| "none".into(), |d| format!("{} s", sig(d, 3)).into()),
            score
                .false_alarms_per_hour
                .map_or_else(|| "n/a".into(), |f| format!("{} ({})", sig(f, 3), score.false_alarms).into()),
        ]);
    }
    t
}

/// Features that the chosen sensors' detector weighs most: the largest [`SHOWN_FEATURES`]
/// weights.
fn features(g: &WindowDesign) -> Table {
    let mut t = Table::new("", &["sensor at (x, z) (mm)", "feature", "weight (standardised)"]);
    for f in g.features.iter().take(SHOWN_FEATURES) {
        t.push(vec![
            format!("({}, {})", sig(f.at_mm.0, 4), sig(f.at_mm.1, 4)).into(),
            f.feature.to_string().into(),
            format!("{:+.3}", f.weight).into(),
        ]);
    }
    t
}

/// The first step's map: a row per z, a column per x, the chosen point marked.
fn first_map(g: &WindowDesign) -> Table {
    let first = g.steps.first().map(|s| (s.at_mm, s.map.as_slice()));
    crate::identify::design::chosen_map((&g.x_mm, &g.z_mm), first)
}
