//! The contact laws side by side: their section of the transient page, with its table,
//! figure and CSV file.

use super::figures::laws_figure;
use super::tables::laws_table;
use crate::present::table::sig;
use crate::template::render;
use crate::Failure;
use coupled::transient::LawKind;
use output::Artifacts;
use scene::Scene;
use studies::transient::{contact_count, end_state, peak_over_contacts, LawCase, LAW_RATIOS};

const LAWS: &str = include_str!("../templates/transient/laws.md");
const LAWS_END_LEFT: &str = include_str!("../templates/transient/laws-end-left.md");
const LAWS_END_OPEN: &str = include_str!("../templates/transient/laws-end-open.md");

/// The contact-laws section: Hertz, Flores and Thornton side by side at [`LAW_RATIOS`] times
/// the yield velocity (the runs `lc`), its table, figure and CSV added to `a`.
pub(super) fn laws_section(scene: &Scene, lc: &[LawCase], a: &mut Artifacts) -> Result<String, Failure> {
    let lt = laws_table(lc);
    a.add("contact-laws.csv", lt.clone().csv_name("the end", &["run_end_label"]).to_csv());
    let top = LAW_RATIOS.iter().copied().fold(0.0, f64::max);
    let at = |law: LawKind, ratio: f64| lc.iter().find(|c| c.law == law && c.ratio == ratio);
    let (hertz, flores, thornton) = (
        at(LawKind::Hertz, top).ok_or("no Hertz run")?,
        at(LawKind::Flores, top).ok_or("no Flores run")?,
        at(LawKind::Thornton, top).ok_or("no Thornton run")?,
    );
    a.add("contact-laws.svg", laws_figure(&[hertz, flores, thornton], top));
    let end_dissipated = |c: &LawCase| {
        let o = &c.estimate.outcome;
        o.later_history.last().or(o.history.last()).map_or(f64::NAN, |s| s.dissipated / c.energy)
    };
    let below = at(LawKind::Thornton, LAW_RATIOS[0]).ok_or("no run below yield")?;
    let below_hertz = at(LawKind::Hertz, LAW_RATIOS[0]).ok_or("no run below yield")?;
    // "After the impact" only where every run at the top velocity has provably ended.
    let top_runs = [hertz, flores, thornton];
    let open: Vec<String> = top_runs
        .iter()
        .filter(|c| c.estimate.outcome.left_at.is_none())
        .map(|c| format!("{}: {}", c.law.key(), end_state(&c.estimate.outcome)))
        .collect();
    let end = if open.is_empty() {
        render("transient/laws-end-left.md", LAWS_END_LEFT, &[])?
    } else {
        render(
            "transient/laws-end-open.md",
            LAWS_END_OPEN,
            &[("open", open.len().to_string()), ("states", open.join("; "))],
        )?
    };
    let peaks = |f: &dyn Fn(&LawCase) -> f64| top_runs.iter().map(|c| sig(f(c), 3)).collect::<Vec<_>>().join(" / ");
    render(
        "transient/laws.md",
        LAWS,
        &[
            ("end", end.trim().to_string()),
            ("first_peaks", peaks(&|c| c.estimate.values.peak_force)),
            ("all_peaks", peaks(&|c| peak_over_contacts(&c.estimate.outcome))),
            (
                "contacts",
                top_runs.iter().map(|c| contact_count(&c.estimate.outcome).to_string()).collect::<Vec<_>>().join(" / "),
            ),
            ("body", scene.bodies[0].name.clone()),
            ("condition", scene.conditions[0].name.clone()),
            ("v_y", sig(hertz.velocity / hertz.ratio, 4)),
            ("ratios", LAW_RATIOS.iter().map(|r| r.to_string()).collect::<Vec<_>>().join(", ")),
            ("top", top.to_string()),
            ("v_top", sig(hertz.velocity, 3)),
            (
                "thornton_hertz",
                format!("{:.3}", thornton.estimate.values.peak_force / hertz.estimate.values.peak_force),
            ),
            ("flores_hertz", format!("{:.3}", flores.estimate.values.peak_force / hertz.estimate.values.peak_force)),
            ("thornton_e", format!("{:.3}", thornton.estimate.values.restitution)),
            ("flores_e", format!("{:.3}", flores.estimate.values.restitution)),
            ("thornton_dissipated", format!("{:.0}", 100.0 * end_dissipated(thornton))),
            ("flores_dissipated", format!("{:.0}", 100.0 * end_dissipated(flores))),
            ("below_ratio", LAW_RATIOS[0].to_string()),
            (
                "below_same",
                sig((below.estimate.values.peak_force / below_hertz.estimate.values.peak_force - 1.0).abs(), 2),
            ),
            ("table", lt.to_markdown()),
        ],
    )
    .map_err(Into::into)
}
