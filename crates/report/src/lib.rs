//! The studies a scene can ask for, each written up as a set of files ([`Artifacts`]).
//!
//! Every report has the same signature, `fn(&Scene) -> Result<Artifacts, Failure>`, and
//! writes only its own files; a report that includes another nests the other's files
//! under a subdirectory.

pub mod present;
pub mod provenance;

mod arithmetic;
pub mod comparison;
pub mod detect;
pub mod drops;
pub mod fem_bench;
pub mod fem_verification;
pub mod field;
pub mod field_series;
pub mod identify;
pub mod in_time;
pub mod nested;
pub mod paper;
pub mod paper_studies;
pub mod plate_field;
pub mod regimes;
pub mod shell_mesh;
pub mod signals;
pub mod skfem;
pub mod stream;
mod stream_band;
mod stream_design;
pub mod tail_beam;
pub mod template;
pub mod transient;
pub mod yield_models;

use crate::identify::RowFiles;
use crate::present::rows::slug;
use crate::provenance::Provenance;
use crate::template::render;
use coupled::Scene;
use output::{Artifacts, OutputDir};
use scene::SceneSource;

pub use studies::progress::{Progress, Silent};
pub use studies::Failure;

/// The signature every report has.
pub type Report = fn(&Scene) -> Result<Artifacts, Failure>;

/// Everything a scene asks `impact compare` for: the beam-against-plate comparison, and
/// beside it, each in its own folder, the studies of [`nested::NESTED`] the scene names; the
/// comparison's page shows what each found (the three-model yield table and figures, the
/// transient cases' contacts, errors and regimes, the regime maps) and links it. Every CSV and
/// JSON carries its scene's provenance.
///
/// The paper's studies run on the paper's own scene, whatever `scene` is (their files carry
/// that scene's provenance). A scene that asks for yield velocities and the transient study
/// but not for the paper's studies gets the three-model yield study on its own cases.
pub fn scene_report(scene: &Scene, progress: &dyn Progress) -> Result<Artifacts, Failure> {
    let mut extra = comparison::StudySections::default();
    let mut parts = Vec::new();
    for study in nested::NESTED.iter().filter(|s| s.wanted(scene)) {
        let n = study.run(scene, progress)?;
        extra.findings.extend(n.findings);
        extra.sections.push_str(&n.section);
        parts.push((study.folder(), n.files, n.of));
    }
    // A blank line closes the nested studies' sections (the regime maps' finding may close
    // the transient section's list, so the sections themselves end without one).
    if !extra.sections.is_empty() {
        extra.sections.push('\n');
    }
    let mut a = comparison::report_with(scene, &extra, progress)?;
    for (dir, mut part, of) in parts {
        Provenance::of(&of).stamp(&mut part);
        a.nest(dir, part);
    }
    Provenance::of(scene).stamp(&mut a);
    Ok(a)
}

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
pub const IDENTIFY_SCENES: [(&str, &str); 3] = [
    ("caving-stream.toml", include_str!("../../../scenes/caving-stream.toml")),
    ("caving-stream-measured.toml", include_str!("../../../scenes/caving-stream-measured.toml")),
    ("paper-velocities-ensemble.toml", include_str!("../../../scenes/paper-velocities-ensemble.toml")),
];

/// The caving-stream detection scenes `impact report` runs (`impact stream`), shipped in
/// `scenes/` and embedded: file name and text.
pub const STREAM_SCENES: [(&str, &str); 2] = [
    ("caving-stream-detect.toml", include_str!("../../../scenes/caving-stream-detect.toml")),
    ("tail-beam-stream.toml", include_str!("../../../scenes/tail-beam-stream.toml")),
];

/// The tail-beam scenes `impact report` runs (the "tail-beam" study), shipped in `scenes/` and
/// embedded: file name and text.
pub const TAIL_BEAM_SCENES: [(&str, &str); 1] = [("tail-beam.toml", include_str!("../../../scenes/tail-beam.toml"))];

/// The mesh-file scenes `impact report` runs (the "shell-mesh" study), shipped in `scenes/`
/// with their meshes and embedded: file name, text, and the mesh file (its name as the scene
/// writes it, its contents).
pub const SHELL_MESH_SCENES: [(&str, &str, (&str, &str)); 1] = [(
    "tail-beam-mesh.toml",
    include_str!("../../../scenes/tail-beam-mesh.toml"),
    ("meshes/tail-beam.msh", include_str!("../../../scenes/meshes/tail-beam.msh")),
)];

const INDEX: &str = include_str!("templates/index/index.md");
const INDEX_STREAM: &str = include_str!("templates/index/stream.md");
const INDEX_STREAM_ROW: &str = include_str!("templates/index/stream-row.md");
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
    let mut streamed = Vec::new();
    for (file, text) in STREAM_SCENES {
        let s = Scene::parse(text, &format!("scenes/{file} (embedded)"))?;
        let (mut files, data) = stream::report(&s, progress)?;
        Provenance::of(&s).stamp(&mut files);
        all.nest(&format!("stream/{}", slug(&s.name)), files);
        streamed.push((file, s, data));
    }
    let mut tail_beam = String::new();
    for (file, text) in TAIL_BEAM_SCENES {
        let s = Scene::parse(text, &format!("scenes/{file} (embedded)"))?;
        let data = studies::tail_beam::compute(&s)?;
        let (mut files, finding) = tail_beam::report(&s, &data)?;
        Provenance::of(&s).stamp(&mut files);
        let dir = format!("tail-beam/{}", slug(&s.name));
        all.nest(&dir, files);
        tail_beam.push_str(&format!("{finding}  ([{dir}/]({dir}/index.md), `scenes/{file}`)\n"));
    }
    for (file, text, mesh) in SHELL_MESH_SCENES {
        let s = scene::parse_with_files(text, &format!("scenes/{file} (embedded)"), &[mesh])?;
        let data = studies::shell_mesh::compute(&s)?;
        let (mut files, finding) = shell_mesh::report(&s, &data)?;
        Provenance::of(&s).stamp(&mut files);
        let dir = format!("shell-mesh/{}", slug(&s.name));
        all.nest(&dir, files);
        tail_beam.push_str(&format!("{finding}  ([{dir}/]({dir}/index.md), `scenes/{file}`)\n"));
    }
    all.add("index.md", index_page(&identified, &streamed, &tail_beam)?);
    Ok(all)
}

/// The report's index page: the identifications' answers (each scene's file name in
/// `scenes/`, the scene, its summary), the stream detections' answers, then what is where.
pub fn index_page(
    identified: &[(&str, Scene, identify::Summary)],
    streamed: &[(&str, Scene, studies::stream::StreamData)],
    tail_beam: &str,
) -> Result<String, Failure> {
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
    let (mut stream_sections, mut stream_rows) = (String::new(), String::new());
    for (file, s, data) in streamed {
        let dir = slug(&s.name);
        let st = &data.study;
        stream_sections.push_str(&render(
            "index/stream.md",
            INDEX_STREAM,
            &[
                ("scene", s.name.clone()),
                ("dir", dir.clone()),
                ("description", s.description.trim().trim_end_matches('.').to_string()),
                ("streams", st.streams.to_string()),
                ("duration", analytic::params::compact(st.spec.duration)),
                ("table", stream::summary_table(data).to_markdown()),
                ("transfer", stream::worst_transfer(data)),
                ("design", stream_design::headline(data)),
            ],
        )?);
        stream_rows.push_str(&render(
            "index/stream-row.md",
            INDEX_STREAM_ROW,
            &[("dir", dir), ("file", file.to_string())],
        )?);
    }
    Ok(render(
        "index/index.md",
        INDEX,
        &[
            ("identify", sections),
            ("identify_rows", rows),
            ("stream", stream_sections),
            ("stream_rows", stream_rows),
            ("tail_beam", tail_beam.to_string()),
        ],
    )?)
}
