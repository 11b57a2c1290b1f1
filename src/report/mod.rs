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

use crate::output::Artifacts;
use crate::provenance::Provenance;
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
