//! The studies a scene can ask for, each written up as a set of files ([`Artifacts`]).
//!
//! Every report has the same signature, `fn(&Scene) -> Result<Artifacts, Failure>`, and
//! writes only its own files; a report that includes another nests the other's files
//! under a subdirectory.

pub mod comparison;
pub mod conclusions;
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
pub mod studies;
pub mod template;
pub mod transient;
pub mod yield_models;

use crate::output::{Artifacts, OutputDir};
use crate::present::rows::slug;
use crate::provenance::Provenance;
use crate::report::identify::RowFiles;
use crate::report::template::render;
use crate::scene::SceneSource;
use coupled::{Analysis, Scene};

/// Any failure of a study, with its source.
pub type Failure = Box<dyn std::error::Error>;

/// The signature every report has.
pub type Report = fn(&Scene) -> Result<Artifacts, Failure>;

/// Everything a scene asks `impact compare` for: the beam-against-plate comparison, and
/// beside it, each in its own folder, the paper's studies and the transient study when
/// the scene names them. Every CSV and JSON carries its scene's provenance.
pub fn scene_report(scene: &Scene) -> Result<Artifacts, Failure> {
    // The paper's studies run on the paper's own scene, whatever `scene` is: their files
    // carry that scene's provenance.
    let paper_scene = paper::Paper::new().scene;
    let studies: [(Analysis, &str, Report, &Scene); 4] = [
        (Analysis::PaperStudies, "paper-studies", paper_studies::report, &paper_scene),
        (Analysis::PaperStudies, "yield-three-models", yield_models::report, &paper_scene),
        (Analysis::Transient, "dynamic", transient::report, scene),
        (Analysis::RegimeMaps, "regimes", regimes::report, scene),
    ];
    let mut a = comparison::report(scene)?;
    for (analysis, dir, report, of) in studies {
        if scene.wants(analysis) {
            let mut part = report(scene)?;
            Provenance::of(of).stamp(&mut part);
            a.nest(dir, part);
        }
    }
    Provenance::of(scene).stamp(&mut a);
    Ok(a)
}

/// The scene the main report runs: `scene` with its transient cases to
/// [`studies::REPORT_TOLERANCE`] (its files carry this scene's provenance).
pub fn main_scene(scene: &Scene) -> Scene {
    Scene {
        transient_discretisation: coupled::transient::Discretisation::tolerance(studies::REPORT_TOLERANCE),
        ..scene.clone()
    }
}

/// The main job: the paper's reproduction, the plate FE verification, and the scene report
/// of the default scene, its transient cases to [`studies::REPORT_TOLERANCE`].
pub fn main_report(scene: &Scene) -> Result<Artifacts, Failure> {
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
    all.nest(&crate::present::rows::slug(&scene.name), scene_report(scene)?);
    Ok(all)
}

/// The identification scenes `impact report` runs beside the default scene's reports (shipped
/// in `scenes/`, embedded like the default scene): file name and text.
pub const IDENTIFY_SCENES: [(&str, &str); 2] = [
    ("caving-stream.toml", include_str!("../../scenes/caving-stream.toml")),
    ("paper-velocities-ensemble.toml", include_str!("../../scenes/paper-velocities-ensemble.toml")),
];

const INDEX: &str = include_str!("templates/index/index.md");
const INDEX_IDENTIFY: &str = include_str!("templates/index/identify.md");
const INDEX_IDENTIFY_ROW: &str = include_str!("templates/index/identify-row.md");

/// `impact report`: [`main_report`], then each of [`IDENTIFY_SCENES`] into
/// `identify/<scene name>/` by `impact identify`'s own code path ([`identify::write`]; its
/// rows streamed into `out`, `features.csv` left out: one row per impact and channel, 112 MB
/// for the caving stream), and the index page that opens with the identification's answer.
pub fn full_report(scene: &Scene, out: &mut OutputDir) -> Result<Artifacts, Failure> {
    let mut all = main_report(scene)?;
    let mut identified = Vec::new();
    for (file, text) in IDENTIFY_SCENES {
        let s = Scene::parse(text, &format!("scenes/{file} (embedded)"))?;
        let (files, summary) = identify::write(&s, out, &format!("identify/{}", slug(&s.name)), RowFiles::Impacts)?;
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
