//! The transient study's prose: the findings (each a Markdown bullet line from the templates)
//! and the sections on the whole impact, the discretisation and the regimes, each with its
//! table and CSV file.

use super::tables::{contact_rows, contacts_table, discretisation_table, regimes_table};
use super::TransientSummary;
use crate::present::table::sig;
use crate::template::render;
use crate::Failure;
use coupled::transient::{Discretisation, TransientSettings};
use output::Artifacts;
use scene::Scene;
use studies::transient::findings::{BodyRanges, Findings};
use studies::transient::size_map::SizeMapFindings;
use studies::transient::{TransientCase, TransientData};

const CONTACTS: &str = include_str!("../templates/transient/contacts.md");
const DISCRETISATION: &str = include_str!("../templates/transient/discretisation.md");
const DISC_FIXED: &str = include_str!("../templates/transient/discretisation-fixed.md");
const DISC_TOLERANCE: &str = include_str!("../templates/transient/discretisation-tolerance.md");
const REGIMES: &str = include_str!("../templates/transient/regimes.md");
const SUMMARY_BODY: &str = include_str!("../templates/transient/summary-body.md");
const FINDING_CONTACTS: &str = include_str!("../templates/transient/finding-contacts.md");
const FINDING_SINGLE: &str = include_str!("../templates/transient/finding-single.md");
const FINDING_UNFINISHED: &str = include_str!("../templates/transient/finding-unfinished.md");
const FINDING_ELASTIC: &str = include_str!("../templates/transient/finding-elastic.md");
const FINDING_ERRORS: &str = include_str!("../templates/transient/finding-errors.md");
const FINDING_ERRORS_UNMET: &str = include_str!("../templates/transient/finding-errors-unmet.md");
const FINDING_REGIMES: &str = include_str!("../templates/transient/finding-regimes.md");

/// The discretisation of the comparison in words (from the templates).
pub(super) fn discretisation_prose(scene: &Scene) -> Result<String, Failure> {
    Ok(match scene.transient_discretisation {
        Discretisation::Fixed { settings } => render(
            "transient/discretisation-fixed.md",
            DISC_FIXED,
            &[("elements", settings.elements.to_string()), ("steps", settings.steps_per_contact.to_string())],
        )?,
        Discretisation::Tolerance { tolerance, budget } => {
            let start = TransientSettings::default();
            render(
                "transient/discretisation-tolerance.md",
                DISC_TOLERANCE,
                &[
                    ("tolerance", sig(tolerance, 2)),
                    ("elements", start.elements.to_string()),
                    ("steps", start.steps_per_contact.to_string()),
                    ("max_elements", budget.max_elements.to_string()),
                    ("max_steps", budget.max_steps_per_contact.to_string()),
                ],
            )?
        }
    })
}

/// The window of the scene's runs, in Hertz times, as the prose quotes it.
fn window(scene: &Scene) -> String {
    sig(scene.transient_discretisation.start().window_contacts, 3)
}

/// The whole impact: every contact of every case ([contacts.csv](contacts.csv) added to `a`).
pub(super) fn contacts_section(scene: &Scene, data: &TransientData, a: &mut Artifacts) -> Result<String, Failure> {
    let (cases, n) = (&data.cases, &data.findings.numbers);
    a.add("contacts.csv", contact_rows(cases).to_csv());
    Ok(render(
        "transient/contacts.md",
        CONTACTS,
        &[
            ("cases", cases.len().to_string()),
            ("repeated", n.struck_more_than_once.to_string()),
            ("unproven", n.unfinished_in_window.to_string()),
            ("window", window(scene)),
            ("table", contacts_table(cases).to_markdown()),
        ],
    )?)
}

/// The discretisation each case got, its error estimate and its cost (with its CSV file).
pub(super) fn discretisation_section(data: &TransientData, a: &mut Artifacts) -> Result<String, Failure> {
    let (cases, f) = (&data.cases, &data.findings);
    let dt = discretisation_table(cases);
    a.add("discretisation.csv", dt.to_csv());
    Ok(render(
        "transient/discretisation.md",
        DISCRETISATION,
        &[
            ("cases", cases.len().to_string()),
            ("seconds", sig(data.comparison_seconds, 3)),
            ("threads", data.threads.to_string()),
            ("median", sig(f.numbers.median_seconds_per_case.unwrap_or(0.0), 3)),
            ("slowest", sig(f.slowest_seconds, 3)),
            ("worst_estimate", sig(f.numbers.largest_relative_error_estimate, 2)),
            ("unmet", f.not_met.to_string()),
            ("finest", f.finest_elements.to_string()),
            ("table", dt.to_markdown()),
        ],
    )?)
}

/// Each case's regime against its measured quasi-static error (with its CSV file).
pub(super) fn regimes_section(data: &TransientData, a: &mut Artifacts) -> Result<String, Failure> {
    let (cases, f) = (&data.cases, &data.findings);
    let rt = regimes_table(cases);
    a.add("regimes.csv", rt.to_csv());
    Ok(render(
        "transient/regimes.md",
        REGIMES,
        &[
            ("cases", cases.len().to_string()),
            ("trusted", f.numbers.rule_trusts.to_string()),
            ("wrong", f.numbers.rule_trusts_wrongly.to_string()),
            ("conservative", f.numbers.rule_flags_needlessly.to_string()),
            ("wave", f.numbers.olsson_wave_controlled.to_string()),
            ("repeated", f.numbers.struck_more_than_once.to_string()),
            ("beyond", f.beyond_yield.to_string()),
            ("table", rt.to_markdown()),
        ],
    )?)
}

/// A case as the findings name it.
fn case_label(c: &TransientCase) -> String {
    format!("{}, {} at ({:.1}, {:.1}) mm, {} m/s", c.body, c.condition, c.x * 1e3, c.z * 1e3, sig(c.velocity, 3))
}

/// What the study found, every line rendered from the templates.
pub(super) fn findings(scene: &Scene, data: &TransientData) -> Result<TransientSummary, Failure> {
    let f = &data.findings;
    Ok(TransientSummary {
        bodies: f.bodies.iter().map(body_line).collect::<Result<String, _>>()?,
        contacts: contacts_finding(scene, data)?,
        elastic: elastic_finding(scene, f)?,
        errors: errors_finding(f)?,
        regimes: regimes_finding(f)?,
        numbers: f.numbers.clone(),
    })
}

/// One body's line: t_c/T₁, the quasi-static error and the plate's share of E₀.
fn body_line(b: &BodyRanges) -> Result<String, Failure> {
    let (tc, e, pe, pq) = (b.contact_ratio, b.force_error, b.plate_energy, b.quasi_static_plate_energy);
    Ok(render(
        "transient/summary-body.md",
        SUMMARY_BODY,
        &[
            ("body", b.body.clone()),
            ("ratio_from", format!("{:.3}", tc.0)),
            ("ratio_to", format!("{:.3}", tc.1)),
            ("error_from", format!("{:+.0}", 100.0 * e.0)),
            ("error_to", format!("{:+.0}", 100.0 * e.1)),
            ("plate_from", format!("{:.0}", 100.0 * pe.0)),
            ("plate_to", format!("{:.0}", 100.0 * pe.1)),
            ("qs_from", format!("{:.0}", 100.0 * pq.0)),
            ("qs_to", format!("{:.0}", 100.0 * pq.1)),
        ],
    )?)
}

/// The whole impact: re-contact, and impacts the window cut.
fn contacts_finding(scene: &Scene, data: &TransientData) -> Result<String, Failure> {
    let n = &data.findings.numbers;
    let cases = n.cases.to_string();
    let mut out = match data.findings.hardest_recontact {
        Some(r) => render(
            "transient/finding-contacts.md",
            FINDING_CONTACTS,
            &[
                ("repeated", n.struck_more_than_once.to_string()),
                ("cases", cases.clone()),
                ("most", n.most_contacts.to_string()),
                ("later_peak", sig(r.later_peak, 3)),
                ("first_peak", sig(r.first_peak, 3)),
                ("later_ratio", sig(r.later_peak / r.first_peak, 3)),
                ("later_case", case_label(&data.cases[r.case])),
            ],
        )?,
        None => render("transient/finding-single.md", FINDING_SINGLE, &[("cases", cases.clone())])?,
    };
    if n.unfinished_in_window > 0 {
        out.push_str(&render(
            "transient/finding-unfinished.md",
            FINDING_UNFINISHED,
            &[("unfinished", n.unfinished_in_window.to_string()), ("cases", cases), ("window", window(scene))],
        )?);
    }
    Ok(out)
}

/// Cases beyond the elastic range under an elastic law (empty where there are none).
fn elastic_finding(scene: &Scene, f: &Findings) -> Result<String, Failure> {
    let n = &f.numbers;
    if n.beyond_elastic_with_elastic_law == 0 {
        return Ok(String::new());
    }
    Ok(render(
        "transient/finding-elastic.md",
        FINDING_ELASTIC,
        &[
            ("beyond", n.beyond_elastic_with_elastic_law.to_string()),
            ("cases", n.cases.to_string()),
            ("worst", sig(f.worst_beyond_elastic, 3)),
            ("law", scene.contact_law.key().to_string()),
        ],
    )?)
}

/// The discretisation errors against the tolerance, and the cost of a case.
fn errors_finding(f: &Findings) -> Result<String, Failure> {
    let n = &f.numbers;
    let worst = n.largest_relative_error_estimate;
    let median = sig(n.median_seconds_per_case.unwrap_or(0.0), 3);
    let slowest = sig(f.slowest_seconds, 3);
    Ok(if n.above_tolerance > 0 {
        render(
            "transient/finding-errors-unmet.md",
            FINDING_ERRORS_UNMET,
            &[
                ("above", n.above_tolerance.to_string()),
                ("cases", n.cases.to_string()),
                ("tolerance", sig(n.tolerance.unwrap_or(f64::NAN), 2)),
                ("worst", sig(worst, 2)),
                ("median", median),
                ("slowest", slowest),
            ],
        )?
    } else {
        let within = n.tolerance.map_or_else(|| format!("{} (fixed discretisation)", sig(worst, 2)), |t| sig(t, 2));
        render(
            "transient/finding-errors.md",
            FINDING_ERRORS,
            &[("within", within), ("worst", sig(worst, 2)), ("median", median), ("slowest", slowest)],
        )?
    })
}

/// The regime criteria on the scene's cases.
fn regimes_finding(f: &Findings) -> Result<String, Failure> {
    let n = &f.numbers;
    Ok(render(
        "transient/finding-regimes.md",
        FINDING_REGIMES,
        &[
            ("cases", n.cases.to_string()),
            ("trusted", n.rule_trusts.to_string()),
            ("wrong", n.rule_trusts_wrongly.to_string()),
            ("conservative", n.rule_flags_needlessly.to_string()),
            ("wave", n.olsson_wave_controlled.to_string()),
        ],
    )?)
}

/// The size map's findings in numbers from this run: the largest error where the contact is
/// slow against the plate (t_c/T₁ ≥ 0.2) and the error at the fastest contact.
pub(super) fn size_map_findings(f: &SizeMapFindings) -> String {
    let limit = coupled::validity::QUASI_STATIC_MIN_RATIO;
    let mut out = String::from("Measured in this run:");
    match f.slow_error {
        Some(e) => {
            out.push_str(&format!(" where t_c/T₁ ≥ {limit} the quasi-static force is within {:.1} %;", 100.0 * e))
        }
        None => out.push_str(&format!(" no plate of the map reaches t_c/T₁ ≥ {limit};")),
    }
    if let Some((r, ratio)) = f.fastest {
        out.push_str(&format!(
            " at the fastest contact, t_c/T₁ = {r:.3}, it is off by {:.0} %.",
            100.0 * (ratio - 1.0).abs()
        ));
    }
    out
}
