//! `impact identify` written up: the scene's random-impact ensemble on every support set, the
//! features' separability of coal from gangue, sensor-placement maps, which variability hides
//! the difference, and the validity of the ensemble.
//!
//! The study computes in [`studies::identify`] (the physics in `coupled::identification`, the
//! statistics in crate `identify`); here its main runs' impacts are streamed to the output
//! directory as they arrive ([`RowFiles`]), and its data becomes the maps, the histograms and
//! the page.

mod check;
pub(crate) mod design;
mod figures;
mod head;
mod measurement;
mod rows;
mod section;

pub use rows::RowFiles;
pub use studies::channel::ChannelInfo;
pub use studies::identify::{
    channels_per_impact, checked_study, feature_bytes, no_channels, run_sensors, ConditionResult, IdentifyData, Ranked,
    Summary,
};

use crate::present::table::{sig, Cell, Table};
use crate::provenance::Provenance;
use crate::Failure;
use coupled::Scene;
use output::{Artifacts, OutputDir};
use rows::Rows;
use section::{ci, percent};
use studies::progress::Progress;

/// `impact identify`, also run by `impact report` for its identification scenes: the
/// identification of `scene` (which must carry an ensemble), its row files streamed into
/// `out` under `dir` ("" for the top), and the report's files, under `dir` and carrying the
/// scene's provenance like the streamed ones, with the summary.
pub fn write(
    scene: &Scene,
    out: &mut OutputDir,
    dir: &str,
    files: RowFiles,
    progress: &dyn Progress,
) -> Result<(Artifacts, Summary), Failure> {
    checked_study(scene)?;
    let provenance = Provenance::of(scene);
    let mut rows = Rows::open(out, dir, &provenance, files)?;
    let data = studies::identify::compute_with(scene, progress, &mut |m| rows.write(m))?;
    rows.finish(out)?;
    let mut artifacts = report(scene, &data, files)?;
    provenance.stamp(&mut artifacts);
    if dir.is_empty() {
        return Ok((artifacts, data.summary));
    }
    let mut nested = Artifacts::new();
    nested.nest(dir, artifacts);
    Ok((nested, data.summary))
}

/// The report's files of the identification `data` of `scene`, whose run streamed the row
/// files `files`: the maps and histograms of each support set, `index.md` and `summary.json`.
pub fn report(scene: &Scene, data: &IdentifyData, files: RowFiles) -> Result<Artifacts, Failure> {
    let study = checked_study(scene)?;
    let summary = &data.summary;
    let mut artifacts = Artifacts::new();
    let mut sections = String::new();
    for (i, (c, d)) in summary.conditions.iter().zip(&data.details).enumerate() {
        let (maps, hists) = figures::figures(&c.condition, &format!("c{}", i + 1), d, &mut artifacts);
        let modes = c.modes(&summary.signals);
        sections.push_str(&section::section(c, modes, scene.contact_law, (&maps, &hists), d.reference.as_deref())?);
    }
    let head = head::head(scene, study, summary)?;
    let method = head::method(summary, files)?;
    artifacts.add("index.md", format!("{head}{sections}{method}"));
    artifacts.add("summary.json", serde_json::to_string_pretty(summary)? + "\n");
    Ok(artifacts)
}

/// The baselines' separations max(AUC, 1 - AUC), "0.998 / 0.771 / 0.512".
fn baselines_cell(h: &studies::identify::baselines::Headline) -> String {
    h.baselines.iter().map(|b| sig(b.separation().0, 3)).collect::<Vec<_>>().join(" / ")
}

/// The summary as tables for the terminal.
pub fn summary_tables(s: &Summary) -> Vec<Table> {
    let mut t = Table::new(
        format!(
            "{}: coal against gangue over {} impacts per support set ({} coal, {} gangue); AUC with 95 % CI, and its change from N/2 to N modes",
            s.scene, s.impacts, s.classes.0, s.classes.1
        ),
        &[
            "support set",
            "signals",
            "best feature",
            "AUC",
            "N/2 to N",
            "best feature resolved in N",
            "AUC",
            "separation by t_c / P_max / m",
            "resolved best feature against the best baseline",
            "best accuracy",
            "beyond elastic",
            "impacts/s",
        ],
    );
    let auc = |r: &Ranked| Cell::Text(format!("{} ({})", sig(r.auc.auc, 3), ci(r)));
    let name = |r: &Ranked| Cell::Text(format!("{} {}", r.feature.name(), r.channel));
    for c in &s.conditions {
        let top = c.ranking.first();
        let acc = c.classifiers.iter().map(|a| a.result.accuracy).fold(f64::NAN, f64::max);
        t.push(vec![
            c.condition.clone().into(),
            Cell::Text(measurement::signals_cell(c)),
            top.map_or(Cell::Empty, name),
            top.map_or(Cell::Empty, auc),
            top.and_then(|r| r.resolution).map_or(Cell::Empty, |d| Cell::Text(sig(d, 2))),
            c.best_converged.as_ref().map_or(Cell::Empty, name),
            c.best_converged.as_ref().map_or(Cell::Empty, auc),
            Cell::Text(baselines_cell(&c.headline)),
            Cell::Text(section::verdict_words(&c.headline)),
            if acc.is_finite() { Cell::Text(sig(acc, 3)) } else { Cell::Empty },
            percent(c.validity.beyond_elastic, c.validity.impacts).into(),
            Cell::Text(sig(c.impacts_per_second, 3)),
        ]);
    }
    vec![t]
}
