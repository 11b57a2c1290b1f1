//! The studies a scene can ask for, each written up as a set of files ([`Artifacts`]).
//!
//! Every report has the same signature, `fn(&Scene) -> Result<Artifacts, Failure>`, and
//! writes only its own files; a report that includes another nests the other's files
//! under a subdirectory.

pub mod present;
pub mod provenance;

pub mod comparison;
pub mod fem_bench;
pub mod fem_verification;
pub mod field;
pub mod field_series;
pub mod identify;
pub mod paper;
pub mod paper_studies;
pub mod plate_field;
pub mod regimes;
pub mod signals;
pub mod skfem;
pub mod template;
pub mod transient;
pub mod yield_models;

use crate::identify::RowFiles;
use crate::present::rows::slug;
use crate::present::table::percent;
use crate::provenance::Provenance;
use crate::template::render;
use coupled::{Analysis, Scene};
use output::{Artifacts, OutputDir};
use scene::SceneSource;

pub use studies::progress::{Progress, Silent};
pub use studies::Failure;

/// The signature every report has.
pub type Report = fn(&Scene) -> Result<Artifacts, Failure>;

/// Everything a scene asks `impact compare` for: the beam-against-plate comparison, and
/// beside it, each in its own folder, the studies the scene names; the comparison's page
/// shows what each found (the three-model yield table and figures, the transient cases'
/// contacts, errors and regimes, the regime maps) and links it. Every CSV and JSON carries
/// its scene's provenance.
///
/// The paper's studies run on the paper's own scene, whatever `scene` is (their files carry
/// that scene's provenance). A scene that asks for yield velocities and the transient study
/// but not for the paper's studies gets the three-model yield study on its own cases.
pub fn scene_report(scene: &Scene, progress: &dyn Progress) -> Result<Artifacts, Failure> {
    let paper_scene = paper::Paper::new().scene;
    let mut nested: Vec<(&str, Artifacts, &Scene)> = Vec::new();
    let mut extra = comparison::StudySections::default();
    if scene.wants(Analysis::PaperStudies) {
        nested.push(("paper-studies", paper_studies::report(&paper_scene)?, &paper_scene));
        extra.sections.push_str(&render("comparison/paper-studies.md", PAPER_STUDIES, &[])?);
    }
    let yields = if scene.wants(Analysis::PaperStudies) {
        Some((yield_models::study(&paper_scene)?, &paper_scene))
    } else if scene.wants(Analysis::YieldVelocity) && scene.wants(Analysis::Transient) {
        Some((yield_models::scene_study(scene, progress)?, scene))
    } else {
        None
    };
    if let Some(((part, summary), of)) = yields {
        nested.push((yield_models::FOLDER, part, of));
        extra.findings.push(summary.finding);
        extra.sections.push_str(&summary.section);
    }
    let dynamic = if scene.wants(Analysis::Transient) {
        let (part, summary) = transient::study(scene, progress)?;
        nested.push(("dynamic", part, scene));
        Some(summary)
    } else {
        None
    };
    let regime_maps = if scene.wants(Analysis::RegimeMaps) {
        let (part, finding) = regimes::study(scene)?;
        nested.push(("regimes", part, scene));
        Some(finding)
    } else {
        None
    };
    if let Some(t) = &dynamic {
        extra.findings.push(render(
            "comparison/finding-transient.md",
            FINDING_TRANSIENT,
            &[
                ("cases", t.numbers["cases"].to_string()),
                ("repeated", t.numbers["struck_more_than_once"].to_string()),
                ("unfinished", t.numbers["unfinished_in_window"].to_string()),
                ("beyond", t.numbers["beyond_elastic_with_elastic_law"].to_string()),
                ("above", t.numbers["above_tolerance"].to_string()),
                ("error_lo", percent(t.numbers["quasi_static_force_error"][0].as_f64().unwrap_or(f64::NAN))),
                ("error_hi", percent(t.numbers["quasi_static_force_error"][1].as_f64().unwrap_or(f64::NAN))),
            ],
        )?);
        extra.sections.push_str(&render(
            "comparison/transient.md",
            TRANSIENT,
            &[
                ("points", scene.transient_points.len().to_string()),
                ("cases", t.numbers["cases"].to_string()),
                ("findings", t.lines()),
                ("regimes", regime_maps.clone().unwrap_or_default()),
            ],
        )?);
    } else if let Some(finding) = &regime_maps {
        extra.sections.push_str(&render("comparison/regimes.md", REGIMES, &[("finding", finding.clone())])?);
    }
    let mut a = comparison::report_with(scene, &extra, progress)?;
    for (dir, mut part, of) in nested {
        Provenance::of(of).stamp(&mut part);
        a.nest(dir, part);
    }
    Provenance::of(scene).stamp(&mut a);
    Ok(a)
}

// The main report's sections on the studies nested beside the comparison.
const PAPER_STUDIES: &str = include_str!("templates/comparison/paper-studies.md");
const TRANSIENT: &str = include_str!("templates/comparison/transient.md");
const REGIMES: &str = include_str!("templates/comparison/regimes.md");
const FINDING_TRANSIENT: &str = include_str!("templates/comparison/finding-transient.md");

/// The scene the main report runs: `scene` with its transient cases to
/// [`studies::settings::REPORT_TOLERANCE`] (its files carry this scene's provenance).
pub fn main_scene(scene: &Scene) -> Scene {
    Scene {
        transient_discretisation: coupled::transient::Discretisation::tolerance(studies::settings::REPORT_TOLERANCE),
        ..scene.clone()
    }
}

/// The main job: the paper's reproduction, the plate FE verification, and the scene report
/// of the default scene, its transient cases to [`studies::settings::REPORT_TOLERANCE`].
pub fn main_report(scene: &Scene, progress: &dyn Progress) -> Result<Artifacts, Failure> {
    let scene = &main_scene(scene);
    let paper_scene = paper::Paper::new().scene;
    let reports: [(&str, Report, &Scene); 2] =
        [("paper", paper::report, &paper_scene), ("fem", fem_verification::report, scene)];
    let mut all = Artifacts::new();
    for (dir, report, of) in reports {
        let mut part = report(scene)?;
        Provenance::of(of).stamp(&mut part);
        all.nest(dir, part);
    }
    all.nest(&crate::present::rows::slug(&scene.name), scene_report(scene, progress)?);
    Ok(all)
}

/// The identification scenes `impact report` runs beside the default scene's reports (shipped
/// in `scenes/`, embedded like the default scene): file name and text.
pub const IDENTIFY_SCENES: [(&str, &str); 2] = [
    ("caving-stream.toml", include_str!("../../../scenes/caving-stream.toml")),
    ("paper-velocities-ensemble.toml", include_str!("../../../scenes/paper-velocities-ensemble.toml")),
];

const INDEX: &str = include_str!("templates/index/index.md");
const INDEX_IDENTIFY: &str = include_str!("templates/index/identify.md");
const INDEX_IDENTIFY_ROW: &str = include_str!("templates/index/identify-row.md");

/// `impact report`: [`main_report`], then each of [`IDENTIFY_SCENES`] into
/// `identify/<scene name>/` by `impact identify`'s own code path ([`identify::write`]; its
/// rows streamed into `out`, `features.csv` left out: one row per impact and channel, 112 MB
/// for the caving stream), and the index page that opens with the identification's answer.
pub fn full_report(scene: &Scene, out: &mut OutputDir, progress: &dyn Progress) -> Result<Artifacts, Failure> {
    let mut all = main_report(scene, progress)?;
    let mut identified = Vec::new();
    for (file, text) in IDENTIFY_SCENES {
        let s = Scene::parse(text, &format!("scenes/{file} (embedded)"))?;
        let (files, summary) =
            identify::write(&s, out, &format!("identify/{}", slug(&s.name)), RowFiles::Impacts, progress)?;
        all.extend(files);
        identified.push((file, s, summary));
    }
    all.add("index.md", index_page(&identified)?);
    Ok(all)
}

/// The report's index page: the identifications' answers (each scene's file name in
/// `scenes/`, the scene, its summary), then what is where.
pub fn index_page(identified: &[(&str, Scene, identify::Summary)]) -> Result<String, Failure> {
    let (mut sections, mut rows) = (String::new(), String::new());
    for (file, s, summary) in identified {
        let dir = slug(&s.name);
        // The terminal's summary without its timing, which would make the page change with
        // every run.
        let table = identify::summary_tables(summary)
            .into_iter()
            .map(|mut t| {
                if let Some(k) = t.headers.iter().position(|h| h == "impacts/s") {
                    t.headers.remove(k);
                    t.rows.iter_mut().for_each(|r| {
                        r.remove(k);
                    });
                }
                t.to_markdown()
            })
            .collect::<Vec<_>>()
            .join("\n");
        let description = s.description.trim().trim_end_matches('.');
        sections.push_str(&render(
            "index/identify.md",
            INDEX_IDENTIFY,
            &[
                ("scene", s.name.clone()),
                ("dir", dir.clone()),
                ("description", if description.is_empty() { String::new() } else { format!("{description}. ") }),
                ("impacts", summary.impacts.to_string()),
                ("coal", summary.classes.0.to_string()),
                ("gangue", summary.classes.1.to_string()),
                ("law", summary.contact_law.to_string()),
                ("table", table),
            ],
        )?);
        rows.push_str(&render(
            "index/identify-row.md",
            INDEX_IDENTIFY_ROW,
            &[("dir", dir), ("file", file.to_string())],
        )?);
    }
    Ok(render("index/index.md", INDEX, &[("identify", sections), ("identify_rows", rows)])?)
}
