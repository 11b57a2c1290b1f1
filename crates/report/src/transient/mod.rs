//! `impact dynamic` and the transient section of the main report, rendered: the transient
//! study's data ([`studies::transient`]) as the page, its tables and CSV files, its figures
//! and `findings.json`.

mod figures;
mod law_section;
mod prose;
mod tables;
mod verification;

pub use coupled::plan::scene_striker as striker;
pub use studies::settings::{DYNAMIC_MESH, STEPS_PER_CONTACT};
pub use studies::transient::{
    contact_count, end_state, first_contact as transient, laws, median, peak_over_contacts, LawCase, TransientCase,
    TransientData, LAW_RATIOS,
};
pub use tables::{
    comparison_table, contact_rows, contacts_table, discretisation_table, laws_table, regimes_table, size_map_table,
};

use crate::template::{and_list, count_words, render};
use crate::Failure;
use output::Artifacts;
use scene::Scene;
use studies::progress::Progress;
use studies::settings::Settings;
use studies::study::{Study, Transient};

// The page's prose, one template per section (verification and the size map are written
// only when the scene asks for them; the summary repeats a line per body).
const HEAD: &str = include_str!("../templates/transient/head.md");
const NOT_VERIFIED: &str = include_str!("../templates/transient/not-verified.md");
const COMPARISON: &str = include_str!("../templates/transient/comparison.md");
const HISTORY: &str = include_str!("../templates/transient/history.md");
const SUMMARY: &str = include_str!("../templates/transient/summary.md");
const SIZE_MAP: &str = include_str!("../templates/transient/size-map.md");
const LAWS_NOT_ASKED: &str = include_str!("../templates/transient/laws-not-asked.md");

/// Transient against quasi-static at the given points, for every condition, body and
/// velocity of the scene ([`studies::transient::comparison`] with the default settings).
pub fn comparison(
    scene: &Scene,
    points: &[(f64, f64)],
    progress: &dyn Progress,
) -> Result<Vec<TransientCase>, Failure> {
    studies::transient::comparison(scene, &Settings::default(), points, progress)
}

/// What the study found, each finding a Markdown bullet line rendered from the templates: the
/// study's page opens with them, and the main report's transient section repeats them.
#[derive(Debug, Clone, PartialEq)]
pub struct TransientSummary {
    /// Per body: t_c/T₁, the quasi-static error and the plate's share of E₀.
    pub bodies: String,
    /// The whole impact: re-contact, and impacts the window cut.
    pub contacts: String,
    /// Cases beyond the elastic range under an elastic law (empty where there are none).
    pub elastic: String,
    /// The discretisation errors against the tolerance, and the cost of a case.
    pub errors: String,
    /// The regime criteria on the scene's cases.
    pub regimes: String,
    /// The counts behind the lines, for `findings.json` and the main report's finding.
    pub numbers: studies::transient::findings::Numbers,
}

impl TransientSummary {
    /// Every finding, in the order the pages list them.
    pub fn lines(&self) -> String {
        [&self.bodies, &self.contacts, &self.elastic, &self.errors, &self.regimes].iter().map(|s| s.as_str()).collect()
    }
}

/// Everything `impact dynamic` writes for `scene` at its transient points.
pub fn report(scene: &Scene, progress: &dyn Progress) -> Result<Artifacts, Failure> {
    Ok(study(scene, progress)?.0)
}

/// [`report`], and its findings for the main report.
pub fn study(scene: &Scene, progress: &dyn Progress) -> Result<(Artifacts, TransientSummary), Failure> {
    let data = Transient::compute(scene, &Settings::default(), progress)?;
    render_study(scene, &data)
}

/// The study's files for `data` of `scene`: the page opens with the findings, then the
/// figures, the tables, the laws, and the verification last; each section is rendered into
/// its own string and assembled at the end.
pub fn render_study(scene: &Scene, data: &TransientData) -> Result<(Artifacts, TransientSummary), Failure> {
    let mut a = Artifacts::new();
    let head = render(
        "transient/head.md",
        HEAD,
        &[("scene", scene.name.clone()), ("discretisation", prose::discretisation_prose(scene)?)],
    )?;
    let verification_md = match &data.verification {
        Some(v) => verification::section(scene, v)?,
        None => render("transient/not-verified.md", NOT_VERIFIED, &[])?,
    };
    let t = comparison_table(&data.cases);
    a.add("transient-vs-quasistatic.csv", t.to_csv());
    let mut md = render("transient/comparison.md", COMPARISON, &[("table", t.to_markdown())])?;
    md.push_str(&prose::contacts_section(scene, data, &mut a)?);
    md.push_str(&prose::discretisation_section(data, &mut a)?);
    md.push_str(&prose::regimes_section(data, &mut a)?);
    let figures = history_section(data, &mut a)?;
    md.push_str(&match &data.laws {
        Some(lc) => law_section::laws_section(scene, lc, &mut a)?,
        None => {
            let laws: Vec<&str> = coupled::transient::LawKind::ALL.iter().map(|l| l.name()).collect();
            let runs = count_words(coupled::transient::LawKind::ALL.len() * studies::transient::LAW_RATIOS.len());
            render("transient/laws-not-asked.md", LAWS_NOT_ASKED, &[("laws", and_list(&laws)), ("runs", runs)])?
        }
    });
    let found = prose::findings(scene, data)?;
    let mut summary_md = render("transient/summary.md", SUMMARY, &[("findings", found.lines())])?;
    let mut size_md = String::new();
    if let Some(rows) = &data.size_map {
        let st = size_map_table(rows);
        a.add("size-map.csv", st.to_csv());
        a.add("size-map.svg", figures::ratio_figure(&figures::size_series(rows), &data.cases).svg());
        let findings = prose::size_map_findings(&studies::transient::size_map::findings(rows));
        let said = findings.trim_start_matches("Measured in this run:").trim();
        summary_md = format!("{}\n", summary_md.trim_end());
        summary_md.push_str(&format!("- Over plate size and thickness (Con 1, centre): {said}\n"));
        size_md = render("transient/size-map.md", SIZE_MAP, &[("findings", findings), ("table", st.to_markdown())])?;
    }
    a.add("findings.json", findings_json(&summary_md, &found)?);
    a.add("index.md", [head, summary_md, figures, size_md, md, verification_md].concat());
    Ok((a, found))
}

/// The first case in time: its force history beside the quasi-static P_max and the rigid
/// target, its energy split, and every step as CSV (nothing without cases).
fn history_section(data: &TransientData, a: &mut Artifacts) -> Result<String, Failure> {
    let Some(c) = data.cases.first() else { return Ok(String::new()) };
    a.add("history-force.svg", figures::history_figure(&data.cases, &data.rigid_hertz).svg());
    a.add("history-energy.svg", figures::energy_figure(c));
    a.add("history.csv", tables::history_table(c).to_csv());
    Ok(render("transient/history.md", HISTORY, &[])?)
}

/// `findings.json`: every finding line of the page's summary, plain, and the counts.
fn findings_json(summary_md: &str, found: &TransientSummary) -> Result<String, Failure> {
    let all: Vec<String> = summary_md
        .lines()
        .filter(|l| l.starts_with("- "))
        .map(|l| l.trim_start_matches("- ").replace("**", ""))
        .collect();
    Ok(serde_json::to_string_pretty(&serde_json::json!({
        "report": "transient against quasi-static",
        "findings": all,
        "numbers": found.numbers,
    }))?)
}
