//! The page's head (the findings, then the ensemble, the signals and the sensors as the scene
//! gave them) and its method section (the statistics' settings, the timings, the files).

use super::rows::RowFiles;
use super::section::finding;
use crate::present::table::{sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use coupled::identification::CHUNK;
use identify::classify::{FOLDS, RIDGE};
use identify::distribution::Distribution;
use identify::roc::BOOTSTRAP_RESAMPLES;
use identify::{Speed, Study};
use scene::Scene;
use studies::channel::mm;
use studies::identify::{Summary, TOP};

const HEAD: &str = include_str!("../templates/identify/head.md");
const METHOD: &str = include_str!("../templates/identify/method.md");

/// A distribution in words, its values in `unit` (SI times `scale`).
fn describe(d: &Distribution, unit: &str, scale: f64) -> String {
    // Values as the scene wrote them (to rounding of the unit conversion).
    let v = |x: f64| analytic::params::compact(format!("{:.6e}", x * scale).parse::<f64>().unwrap_or(x * scale));
    match d {
        Distribution::Fixed { value } => format!("{} {unit}", v(*value)),
        Distribution::Uniform { min, max } => format!("uniform on [{}, {}] {unit}", v(*min), v(*max)),
        Distribution::Normal { mean, sd, min, max } => {
            format!("normal, mean {} sd {}, in [{}, {}] {unit}", v(*mean), v(*sd), v(*min), v(*max))
        }
        Distribution::LogNormal { median, sigma_log, min, max } => format!(
            "lognormal, median {} σ_ln {}, in [{}, {}] {unit}",
            v(*median),
            analytic::params::compact(*sigma_log),
            v(*min),
            v(*max)
        ),
        Distribution::RosinRammler { scale: s, shape, min, max } => {
            format!("Rosin-Rammler, x₆₃ {} n {}, in [{}, {}] {unit}", v(*s), sig(*shape, 3), v(*min), v(*max))
        }
        Distribution::Choice { values } => {
            format!("one of {} {unit}", values.iter().map(|x| v(*x)).collect::<Vec<_>>().join(", "))
        }
    }
}

fn families_table(study: &Study) -> Table {
    let mut families = Table::new(
        "",
        &[
            "family",
            "class",
            "count",
            "radius",
            "density",
            "Young's modulus",
            "Poisson ratio",
            "cohesion",
            "friction angle",
        ],
    );
    for f in &study.ensemble.families {
        families.push(vec![
            f.name.clone().into(),
            f.class.key().into(),
            f.count.into(),
            describe(&f.radius, "mm", 1e3).into(),
            describe(&f.density, "kg/m³", 1.0).into(),
            describe(&f.youngs_modulus, "GPa", 1e-9).into(),
            describe(&f.poisson_ratio, "", 1.0).into(),
            describe(&f.cohesion, "MPa", 1e-6).into(),
            describe(&f.friction_angle_deg, "°", 1.0).into(),
        ]);
    }
    families
}

/// The modes kept: the scene's count, or per support set those the chain chose.
fn modes_text(summary: &Summary) -> String {
    if summary.conditions.iter().all(|c| c.chain_modes.is_none()) {
        return summary.signals.modes.to_string();
    }
    let each: Vec<String> =
        summary.conditions.iter().map(|c| format!("{} on {}", c.modes(&summary.signals), c.condition)).collect();
    format!("{} (the fewest the measurement chain needs, `[signals] modes = \"chain\"`)", each.join(", "))
}

/// The head of the page of `summary`, the identification of `scene`'s ensemble `study`.
pub(super) fn head(scene: &Scene, study: &Study, summary: &Summary) -> Result<String, Failure> {
    let (e, settings) = (&study.ensemble, &summary.signals);
    let most_modes = summary.conditions.iter().map(|c| c.modes(settings)).max().unwrap_or(settings.modes);
    let mut findings = String::new();
    for c in &summary.conditions {
        findings.push_str(&finding(c, c.modes(settings))?);
    }
    let speed = match &e.speed {
        Speed::FallHeight(h) => format!("free fall from rest, v = √(2gh), fall height h {}", describe(h, "m", 1.0)),
        Speed::Velocity(v) => format!("velocity {}", describe(v, "m/s", 1.0)),
    };
    let sensors = if settings.sensors.is_empty() {
        "none named".to_string()
    } else {
        settings.sensors.iter().map(|(x, z)| format!("({}, {}) mm", mm(*x), mm(*z))).collect::<Vec<_>>().join(", ")
    };
    let candidates = if study.candidates_x.is_empty() {
        "none".to_string()
    } else {
        format!("{} x {} points from (0, 0) to (L, B)", study.candidates_x.len(), study.candidates_z.len())
    };
    let (x, z) = (e.region.x, e.region.z);
    Ok(render(
        "identify/head.md",
        HEAD,
        &[
            ("scene", scene.name.clone()),
            ("findings", findings),
            ("impacts", e.len().to_string()),
            ("coal", summary.classes.0.to_string()),
            ("gangue", summary.classes.1.to_string()),
            ("seed", e.seed.to_string()),
            ("region", format!("x in [{}, {}] mm, z in [{}, {}] mm", mm(x.0), mm(x.1), mm(z.0), mm(z.1))),
            ("speed", speed),
            ("families", families_table(study).to_markdown()),
            ("window_ms", sig(settings.window * 1e3, 3)),
            ("rate_hz", sig(settings.rate_hz, 3)),
            ("modes", modes_text(summary)),
            ("damping", sig(settings.damping_ratio * 100.0, 3)),
            ("contact_law", scene.contact_law.key().to_string()),
            ("restitution", sig(scene.restitution, 3)),
            ("sensors", sensors),
            ("candidates", candidates),
            ("recorded", super::measurement::recorded(scene)),
            ("arithmetic", crate::arithmetic::paragraph(settings.arithmetic, most_modes)?),
            ("measurement", super::measurement::section(scene, summary)?),
        ],
    )?)
}

/// What each support set cost, and the full model's check of the reduced one.
fn timing_table(summary: &Summary) -> Table {
    let mut timing = Table::new(
        "",
        &[
            "support set",
            "model set-up (s)",
            "ensemble run (s)",
            "impacts/s",
            "one full Newmark impact (s)",
            "speed-up per impact",
            "reduced/full P_max - 1",
            "reduced/full t_c - 1",
            "features held (MB)",
        ],
    );
    for c in &summary.conditions {
        let per_impact = c.run_seconds / summary.impacts.max(1) as f64;
        timing.push(vec![
            c.condition.clone().into(),
            Cell::Text(sig(c.setup_seconds, 3)),
            Cell::Text(sig(c.run_seconds, 3)),
            Cell::Text(sig(c.impacts_per_second, 3)),
            Cell::Text(sig(c.full_model.seconds, 3)),
            Cell::Text(sig(c.full_model.seconds / per_impact.max(1e-12), 3)),
            Cell::Text(sig(c.full_model.force_difference, 2)),
            Cell::Text(sig(c.full_model.contact_time_difference, 2)),
            Cell::Text(sig(c.feature_bytes as f64 / 1e6, 3)),
        ]);
    }
    timing
}

/// The method section of the page of `summary`, whose run wrote the row files `files`.
pub(super) fn method(summary: &Summary, files: RowFiles) -> Result<String, Failure> {
    let features_file = match files {
        RowFiles::All => "Both are here.",
        RowFiles::Impacts => {
            "This run wrote `impacts.csv` only; `impact identify --scene FILE` writes `features.csv` too."
        }
    };
    Ok(render(
        "identify/method.md",
        METHOD,
        &[
            ("resamples", BOOTSTRAP_RESAMPLES.to_string()),
            ("folds", FOLDS.to_string()),
            ("ridge", sig(RIDGE, 3)),
            ("top", TOP.to_string()),
            ("timing", timing_table(summary).to_markdown()),
            ("threshold", sig(identify::features::DURATION_THRESHOLD * 100.0, 3)),
            ("taper", sig(identify::features::TAPER_FRACTION * 100.0, 3)),
            ("chunk", CHUNK.to_string()),
            ("features_file", features_file.to_string()),
        ],
    )?)
}
