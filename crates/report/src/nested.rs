//! The studies the scene report nests beside the beam-against-plate comparison, as a
//! registry: each one says when the scene asks for it, computes and renders itself, and
//! hands back its files, the scene they come from, and what the comparison's page says of it.
//!
//! A new study of the scene report is a compute module in `studies`, a render module and
//! templates here, one [`NestedStudy`] impl and one line in [`NESTED`].

use crate::paper::Paper;
use crate::present::table::percent;
use crate::template::render;
use crate::{paper_studies, regimes, transient, yield_models, Failure};
use coupled::{Analysis, Scene};
use output::Artifacts;
use studies::progress::Progress;

/// What a nested study adds to the scene report.
#[derive(Debug)]
pub struct Nested {
    /// Its files, nested in [`NestedStudy::folder`].
    pub files: Artifacts,
    /// The scene its files come from (their provenance): the paper's own scene for the
    /// paper's studies, whatever scene is given.
    pub of: Scene,
    /// Bullet lines among the comparison's findings.
    pub findings: Vec<String>,
    /// Markdown after the comparison's figures, in registry order.
    pub section: String,
}

/// A study the scene report nests beside the comparison when the scene asks for it.
///
/// ```
/// use report::nested::{Nested, NestedStudy};
/// use report::{Failure, Progress, Silent};
/// use coupled::Scene;
/// use output::Artifacts;
/// use scene::SceneSource;
///
/// /// A page that counts the scene's impact points.
/// struct PointCount;
/// impl NestedStudy for PointCount {
///     fn folder(&self) -> &'static str {
///         "points"
///     }
///     fn wanted(&self, _: &Scene) -> bool {
///         true
///     }
///     fn run(&self, scene: &Scene, _: &dyn Progress) -> Result<Nested, Failure> {
///         let mut files = Artifacts::new();
///         let n = scene.point_pairs().len();
///         files.add("index.md", format!("{n} points\n"));
///         let findings = vec![format!("- **Points**: {n}.\n")];
///         Ok(Nested { files, of: scene.clone(), findings, section: String::new() })
///     }
/// }
/// let nested = PointCount.run(&Scene::default_scene(), &Silent).unwrap();
/// assert!(nested.files.get("index.md").is_some());
/// ```
pub trait NestedStudy: Sync {
    /// The folder its files go to, relative to the scene report.
    fn folder(&self) -> &'static str;
    /// Whether `scene` asks for it.
    fn wanted(&self, scene: &Scene) -> bool;
    /// Computes it for `scene` and renders it.
    fn run(&self, scene: &Scene, progress: &dyn Progress) -> Result<Nested, Failure>;
}

/// Every nested study, in the order the scene report runs them and its page shows them.
pub const NESTED: [&dyn NestedStudy; 6] =
    [&PaperStudiesPage, &ThreeModelYield, &TransientPage, &RegimePage, &TailBeamPage, &ShellMeshPage];

/// The paper's conclusions, tables and figures under both models, on the paper's scene.
struct PaperStudiesPage;

impl NestedStudy for PaperStudiesPage {
    fn folder(&self) -> &'static str {
        "paper-studies"
    }
    fn wanted(&self, scene: &Scene) -> bool {
        scene.wants(Analysis::PaperStudies)
    }
    fn run(&self, _scene: &Scene, progress: &dyn Progress) -> Result<Nested, Failure> {
        let of = Paper::new().scene;
        let files = paper_studies::study(&of, progress)?;
        let section = render("comparison/paper-studies.md", PAPER_STUDIES, &[])?;
        Ok(Nested { files, of, findings: Vec::new(), section })
    }
}

/// The three-model yield study: on the paper's scene against its printed tables when the
/// scene asks for the paper's studies, otherwise on the scene's own transient cases when it
/// asks for yield velocities and the transient study.
struct ThreeModelYield;

impl NestedStudy for ThreeModelYield {
    fn folder(&self) -> &'static str {
        yield_models::FOLDER
    }
    fn wanted(&self, scene: &Scene) -> bool {
        scene.wants(Analysis::PaperStudies)
            || (scene.wants(Analysis::YieldVelocity) && scene.wants(Analysis::Transient))
    }
    fn run(&self, scene: &Scene, progress: &dyn Progress) -> Result<Nested, Failure> {
        let ((files, summary), of) = if scene.wants(Analysis::PaperStudies) {
            let of = Paper::new().scene;
            (yield_models::study(&of, progress)?, of)
        } else {
            (yield_models::scene_study(scene, progress)?, scene.clone())
        };
        Ok(Nested { files, of, findings: vec![summary.finding], section: summary.section })
    }
}

/// Transient against quasi-static at the scene's transient points.
struct TransientPage;

impl NestedStudy for TransientPage {
    fn folder(&self) -> &'static str {
        "dynamic"
    }
    fn wanted(&self, scene: &Scene) -> bool {
        scene.wants(Analysis::Transient)
    }
    fn run(&self, scene: &Scene, progress: &dyn Progress) -> Result<Nested, Failure> {
        let (files, t) = transient::study(scene, progress)?;
        let n = &t.numbers;
        let finding = render(
            "comparison/finding-transient.md",
            FINDING_TRANSIENT,
            &[
                ("cases", n.cases.to_string()),
                ("repeated", n.struck_more_than_once.to_string()),
                ("unfinished", n.unfinished_in_window.to_string()),
                ("beyond", n.beyond_elastic_with_elastic_law.to_string()),
                ("above", n.above_tolerance.to_string()),
                ("error_lo", percent(n.quasi_static_force_error.0)),
                ("error_hi", percent(n.quasi_static_force_error.1)),
            ],
        )?;
        let section = render(
            "comparison/transient.md",
            TRANSIENT,
            &[
                ("points", scene.transient_points.len().to_string()),
                ("cases", n.cases.to_string()),
                ("findings", t.lines()),
            ],
        )?;
        Ok(Nested { files, of: scene.clone(), findings: vec![finding], section })
    }
}

/// The regime maps. Their finding closes the transient section ("contacts, errors and
/// regimes"), which comes just before in [`NESTED`], and has a heading of its own when the
/// scene does not ask for the transient study.
struct RegimePage;

impl NestedStudy for RegimePage {
    fn folder(&self) -> &'static str {
        "regimes"
    }
    fn wanted(&self, scene: &Scene) -> bool {
        scene.wants(Analysis::RegimeMaps)
    }
    fn run(&self, scene: &Scene, progress: &dyn Progress) -> Result<Nested, Failure> {
        let (files, finding) = regimes::study(scene, progress)?;
        let section = if scene.wants(Analysis::Transient) {
            finding
        } else {
            render("comparison/regimes.md", REGIMES, &[("finding", finding)])?
        };
        Ok(Nested { files, of: scene.clone(), findings: Vec::new(), section })
    }
}

/// The scene's impacts on its box-section tail beam, beside the paper's beam and plate.
struct TailBeamPage;

impl NestedStudy for TailBeamPage {
    fn folder(&self) -> &'static str {
        "tail-beam"
    }
    fn wanted(&self, scene: &Scene) -> bool {
        scene.wants(Analysis::TailBeam)
    }
    fn run(&self, scene: &Scene, _progress: &dyn Progress) -> Result<Nested, Failure> {
        let data = studies::tail_beam::compute(scene)?;
        let (files, finding) = crate::tail_beam::report(scene, &data)?;
        let section = render("comparison/tail-beam.md", TAIL_BEAM, &[])?;
        Ok(Nested { files, of: scene.clone(), findings: vec![finding], section })
    }
}

/// The scene's impacts on a shell structure read from its mesh file.
struct ShellMeshPage;

impl NestedStudy for ShellMeshPage {
    fn folder(&self) -> &'static str {
        "shell-mesh"
    }
    fn wanted(&self, scene: &Scene) -> bool {
        scene.wants(Analysis::ShellMesh)
    }
    fn run(&self, scene: &Scene, _progress: &dyn Progress) -> Result<Nested, Failure> {
        let data = studies::shell_mesh::compute(scene)?;
        let (files, finding) = crate::shell_mesh::report(scene, &data)?;
        let section = render("comparison/shell-mesh.md", SHELL_MESH, &[])?;
        Ok(Nested { files, of: scene.clone(), findings: vec![finding], section })
    }
}

// The main report's sections on the studies nested beside the comparison.
const PAPER_STUDIES: &str = include_str!("templates/comparison/paper-studies.md");
const TRANSIENT: &str = include_str!("templates/comparison/transient.md");
const REGIMES: &str = include_str!("templates/comparison/regimes.md");
const TAIL_BEAM: &str = include_str!("templates/comparison/tail-beam.md");
const SHELL_MESH: &str = include_str!("templates/comparison/shell-mesh.md");
const FINDING_TRANSIENT: &str = include_str!("templates/comparison/finding-transient.md");
