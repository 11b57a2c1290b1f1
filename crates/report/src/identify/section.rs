//! A support set's section of the page (its ranking, classifiers, maps, histograms,
//! variability study and validity) and its finding at the top of the page.

use crate::present::table::{sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use coupled::transient::LawKind;
use identify::roc::Auc;
use studies::identify::baselines::{oriented, Headline, Verdict, SEPARATES};
use studies::identify::{ConditionResult, Held1, Ranked, AUC_RESOLUTION};

const FINDING: &str = include_str!("../templates/identify/finding.md");
const FINDING_HELD: &str = include_str!("../templates/identify/finding-held.md");
const FINDING_RESOLUTION: &str = include_str!("../templates/identify/finding-resolution.md");
const VERDICT_SEPARATES: &str = include_str!("../templates/identify/verdict-baseline-separates.md");
const VERDICT_ADDS: &str = include_str!("../templates/identify/verdict-feature-adds.md");
const VERDICT_NO_GAIN: &str = include_str!("../templates/identify/verdict-no-resolved-gain.md");
const VERDICT_BETTER: &str = include_str!("../templates/identify/verdict-baseline-better.md");
const CONDITION: &str = include_str!("../templates/identify/condition.md");
const LAW_ELASTIC: &str = include_str!("../templates/identify/law-elastic.md");
const LAW_PLASTIC: &str = include_str!("../templates/identify/law-plastic.md");

/// What the best feature adds over the best baseline, in a few words for a table cell.
pub(super) fn verdict_words(h: &Headline) -> String {
    let Some(b) = h.baselines.get(h.best_baseline) else { return String::new() };
    let name = b.quantity;
    match h.verdict {
        Verdict::BaselineSeparates => format!("{name} alone separates ({})", sig(b.separation().0, 3)),
        Verdict::FeatureAdds => format!("{:+.3} over {name}{}", h.gain, unresolved(h)),
        Verdict::NoResolvedGain => format!("no resolved gain over {name} ({:+.3}){}", h.gain, unresolved(h)),
        Verdict::BaselineBetter => format!("{name} is better ({:+.3}){}", h.gain, unresolved(h)),
    }
}

/// A mark for a compared feature the model does not resolve (no resolved one exists).
fn unresolved(h: &Headline) -> &'static str {
    if h.resolved {
        ""
    } else {
        " (feature not resolved)"
    }
}

/// The baselines with their intervals, as separations: "contact time t_c 0.998 (0.996-1),
/// ...".
fn baselines_sentence(h: &Headline) -> String {
    h.baselines
        .iter()
        .map(|b| {
            let (s, (lo, hi)) = b.separation();
            format!("{} {} ({}-{})", b.quantity, sig(s, 3), sig(lo, 3), sig(hi, 3))
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The bootstrap interval, "0.612-0.701".
pub(super) fn ci(r: &Ranked) -> String {
    format!("{}-{}", sig(r.interval.0, 3), sig(r.interval.1, 3))
}

fn direction(a: &Auc) -> &'static str {
    if a.gangue_higher() {
        "gangue higher"
    } else {
        "coal higher"
    }
}

/// `n` of `of` as a percentage.
pub(super) fn percent(n: usize, of: usize) -> String {
    format!("{} %", sig(100.0 * n as f64 / of.max(1) as f64, 3))
}

/// The paper's quantities, then the ranking, then the best converged entry if not in it.
fn ranking_table(r: &ConditionResult) -> Table {
    let mut ranking = Table::new(
        "",
        &["channel", "feature", "AUC", "DeLong SE", "95 % bootstrap CI", "AUC(N) - AUC(N/2)", "direction"],
    );
    let extra = r
        .best_converged
        .as_ref()
        .filter(|b| !r.ranking.iter().any(|x| x.channel == b.channel && x.feature == b.feature));
    for x in std::iter::once(&r.force_max).chain([&r.contact_time]).chain(&r.ranking).chain(extra) {
        ranking.push(vec![
            x.channel.clone().into(),
            x.feature.name().into(),
            Cell::Text(sig(x.auc.auc, 3)),
            Cell::Text(sig(x.auc.standard_error, 2)),
            ci(x).into(),
            x.resolution.map_or(Cell::Empty, |d| {
                let error = x.resolution_error.map_or(String::new(), |e| format!(" ± {}", sig(e, 2)));
                Cell::Text(format!("{}{error}{}", sig(d, 2), if x.converged() { "" } else { " *" }))
            }),
            direction(&x.auc).into(),
        ]);
    }
    ranking
}

fn classifier_table(r: &ConditionResult) -> Table {
    let mut acc = Table::new("", &["features", "accuracy", "SE", "accuracy(N) - accuracy(N/2)"]);
    for a in &r.classifiers {
        acc.push(vec![
            a.features.clone().into(),
            Cell::Text(sig(a.result.accuracy, 3)),
            Cell::Text(sig(a.result.standard_error, 2)),
            Cell::Text(sig(a.resolution, 2)),
        ]);
    }
    acc
}

/// The variability study: its table under the reference feature, or why there is none.
fn held_markdown(r: &ConditionResult, reference: Option<&str>) -> String {
    if r.held.is_empty() {
        return "No variable held (the scene's `hold = []`).".to_string();
    }
    let mut held = Table::new(
        "",
        &[
            "held at the median",
            "reference AUC",
            "best feature of the run",
            "its AUC (95 % CI)",
            "P_max AUC",
            "classifier accuracy",
        ],
    );
    for h in &r.held {
        held.push(vec![
            h.held.clone().into(),
            Cell::Text(format!("{} ± {}", sig(h.reference.auc, 3), sig(h.reference.standard_error, 2))),
            format!("{} {}", h.best.channel, h.best.feature.name()).into(),
            Cell::Text(format!("{} ({})", sig(h.best.auc.auc, 3), ci(&h.best))),
            Cell::Text(sig(h.force_max.auc, 3)),
            Cell::Text(format!("{} ± {}", sig(h.accuracy.accuracy, 3), sig(h.accuracy.standard_error, 2))),
        ]);
    }
    format!(
        "Reference: {}. Each row reruns the same impacts (the same random numbers) with one variable at its median.\n\n{}",
        reference.unwrap_or("-"),
        held.to_markdown()
    )
}

/// The section of support set `r` on a model of `modes` modes under the contact law `law`,
/// with its figures' Markdown and the variability study's reference feature in words.
pub(super) fn section(
    r: &ConditionResult,
    modes: usize,
    law: LawKind,
    (maps, hists): (&str, &str),
    reference: Option<&str>,
) -> Result<String, Failure> {
    let law_note = if law.is_elastic() {
        render("identify/law-elastic.md", LAW_ELASTIC, &[("law", law.key().to_string())])?
    } else {
        render("identify/law-plastic.md", LAW_PLASTIC, &[("law", law.key().to_string())])?
    };
    let v = &r.validity;
    let mut maps = if maps.is_empty() {
        "No candidate grid in the scene ([ensemble.placement]).\n".into()
    } else {
        maps.to_string()
    };
    if let Some(d) = &r.design {
        maps.push_str(&super::design::markdown(d, r.measurement.is_some())?);
        maps.push_str(&super::design::at_backgrounds(&r.design_backgrounds)?);
    }
    Ok(render(
        "identify/condition.md",
        CONDITION,
        &[
            ("condition", r.condition.clone()),
            ("fundamental_hz", sig(r.fundamental_hz, 4)),
            ("ranking", ranking_table(r).to_markdown()),
            ("modes", modes.to_string()),
            ("half_modes", (modes / 2).max(1).to_string()),
            ("resolution", sig(AUC_RESOLUTION, 2)),
            ("check", super::check::markdown(r, modes)?.trim_end().to_string()),
            ("classifiers", classifier_table(r).to_markdown()),
            ("maps", maps),
            ("histograms", hists.to_string()),
            ("held", held_markdown(r, reference)),
            ("impacts", v.impacts.to_string()),
            ("beyond_elastic", percent(v.beyond_elastic, v.impacts)),
            ("not_quasi_static", percent(v.not_quasi_static, v.impacts)),
            ("recontact", percent(v.recontact, v.impacts)),
            ("unfinished", percent(v.unfinished, v.impacts)),
            ("law", law_note.trim_end().to_string()),
        ],
    )?)
}

/// The variability finding: the single variable whose holding separates best, against the
/// paper's comparison (position, size and speed held); empty without both runs.
fn held_finding(r: &ConditionResult) -> Result<String, Failure> {
    let single = |h: &&Held1| {
        [h.which.position, h.which.size, h.which.speed, h.which.material].iter().filter(|x| **x).count() == 1
    };
    let most =
        r.held.iter().filter(single).max_by(|a, b| a.reference.separability().total_cmp(&b.reference.separability()));
    let paper = r.held.iter().find(|h| h.which.position && h.which.size && h.which.speed && !h.which.material);
    let (Some(m), Some(p), Some(reference)) = (most, paper, &r.reference) else { return Ok(String::new()) };
    Ok(render(
        "identify/finding-held.md",
        FINDING_HELD,
        &[
            ("reference", format!("the {} of the {}", reference.feature.name(), reference.channel)),
            ("variable", m.held.clone()),
            ("free", sig(reference.auc.auc, 3)),
            ("auc", sig(m.reference.auc, 3)),
            ("se", sig(m.reference.standard_error, 2)),
            ("paper_auc", sig(p.reference.auc, 3)),
            ("paper_se", sig(p.reference.standard_error, 2)),
        ],
    )?)
}

/// The finding of support set `r` on `modes` modes.
pub(super) fn finding(r: &ConditionResult, modes: usize) -> Result<String, Failure> {
    let dash = || "-".to_string();
    let top = r.ranking.first();
    let best_classifier = r.classifiers.iter().max_by(|a, b| a.result.accuracy.total_cmp(&b.result.accuracy));
    let resolution = match (top, &r.best_converged) {
        (Some(t), Some(b)) if !t.converged() => render(
            "identify/finding-resolution.md",
            FINDING_RESOLUTION,
            &[
                ("delta", t.resolution.map_or_else(dash, |d| sig(d, 2))),
                ("half_modes", (modes / 2).max(1).to_string()),
                ("modes", modes.to_string()),
                ("feature", b.feature.name().to_string()),
                ("channel", b.channel.clone()),
                ("auc", sig(b.auc.auc, 3)),
                ("ci", ci(b)),
            ],
        )?,
        _ => String::new(),
    };
    Ok(render(
        "identify/finding.md",
        FINDING,
        &[
            ("condition", r.condition.clone()),
            ("feature", top.map_or_else(dash, |t| t.feature.name().to_string())),
            ("channel", top.map_or_else(dash, |t| t.channel.clone())),
            ("best_auc", top.map_or_else(dash, |t| sig(t.auc.auc, 3))),
            ("best_ci", top.map_or_else(dash, ci)),
            ("resolution", resolution.trim_end().to_string()),
            ("best_separation", top.map_or_else(dash, |t| sig(oriented(t.auc.auc, t.interval).0, 3))),
            ("baselines", baselines_sentence(&r.headline)),
            ("verdict", verdict_sentence(&r.headline)?),
            ("noise", super::measurement::finding_noise(r)),
            ("classifier", best_classifier.map_or_else(dash, |a| a.features.clone())),
            ("accuracy", best_classifier.map_or_else(dash, |a| sig(a.result.accuracy, 3))),
            ("accuracy_se", best_classifier.map_or_else(dash, |a| sig(a.result.standard_error, 2))),
            ("held", held_finding(r)?.trim_end().to_string()),
        ],
    )?)
}

/// The headline's verdict as a sentence of the finding.
fn verdict_sentence(h: &Headline) -> Result<String, Failure> {
    let Some(b) = h.baselines.get(h.best_baseline) else { return Ok(String::new()) };
    let (name, template) = match h.verdict {
        Verdict::BaselineSeparates => ("identify/verdict-baseline-separates.md", VERDICT_SEPARATES),
        Verdict::FeatureAdds => ("identify/verdict-feature-adds.md", VERDICT_ADDS),
        Verdict::NoResolvedGain => ("identify/verdict-no-resolved-gain.md", VERDICT_NO_GAIN),
        Verdict::BaselineBetter => ("identify/verdict-baseline-better.md", VERDICT_BETTER),
    };
    let mut values = vec![("baseline", b.quantity.to_string()), ("gain", format!("{:+.3}", h.gain))];
    if h.verdict != Verdict::BaselineSeparates {
        let which = if h.resolved {
            format!("best resolved feature ({})", h.feature)
        } else {
            format!("best feature ({}, which the model does not resolve)", h.feature)
        };
        values.push(("feature", which));
    }
    if h.verdict == Verdict::BaselineSeparates {
        values.extend([("separation", sig(b.separation().0, 3)), ("separates", sig(SEPARATES, 2))]);
    }
    let text = render(name, template, &values)?;
    Ok(text.trim_end().to_string())
}
