//! One function per command, each in the shape plan → compute → render → commit: the scene
//! is read and every flag checked before any work, the output target is prepared (so a run
//! that cannot write fails before it spends time), the study computes, and its files are
//! committed whole.

use crate::cli::{Command, Common, FemBenchArgs, StudyArgs};
use crate::commit::{commit, commit_reporting, emit, prepare, print_json};
use crate::progress::Terminal;
use crate::written::in_range;
use crate::{cli_doc, out};
use clap::CommandFactory;
use coupled::plan::{ModelKind, Results};
use impact::output::OutputDir;
use impact::present::rows::slug;
use impact::provenance::Provenance;
use impact::report::identify::RowFiles;
use impact::report::Failure;
use impact::scene::{limits, Analysis, Scene, SceneSource, DEFAULT_SCENE};
use std::path::{Path, PathBuf};

/// Runs one command.
pub fn run(command: Command) -> Result<(), Failure> {
    match command {
        Command::Solve(c) => rows(&c, "solve", Ok),
        Command::Sweep { common, count } => rows(&common, "sweep", |s| Ok(s.with_sweep(count as usize))),
        Command::Yield(c) => rows(&c, "yield", |mut s| {
            s.analyses = vec![Analysis::YieldVelocity];
            Ok(s)
        }),
        Command::Paper { out, json } => paper(&out, json),
        Command::Dynamic(StudyArgs { scene, out, transient, json }) => {
            let scene = transient.apply(load_bodies(&scene, "dynamic")?)?;
            let target = OutputDir::prepare(out.unwrap_or_else(|| default_out(&scene, "dynamic")))?;
            let mut a = impact::report::transient::report(&scene, &Terminal::new())?;
            Provenance::of(&scene).stamp(&mut a);
            commit_reporting(target, &a, &scene, json)
        }
        Command::Signals { scene, out, json } => signals(&load(&scene)?, out, json),
        Command::Compare(StudyArgs { scene, out, transient, json }) => {
            let scene = transient.apply(load_bodies(&scene, "compare")?)?;
            let target = OutputDir::prepare(out.unwrap_or_else(|| default_out(&scene, "compare")))?;
            commit_reporting(target, &impact::report::scene_report(&scene, &Terminal::new())?, &scene, json)
        }
        Command::Identify { scene, out, json, no_features_csv } => identify(&scene, out, json, no_features_csv),
        Command::Stream { scene, out, json } => stream(&scene, out, json),
        Command::Detect { detector, signal, out, json } => detect(&detector, &signal, out, json),
        Command::Drops { scene, signal, out, json } => drops(&scene, &signal, out, json),
        Command::Report { out, json } => {
            let mut target = OutputDir::prepare(&out)?;
            let scene = Scene::default_scene();
            let artifacts = impact::report::full_report(&scene, &mut target, &Terminal::new())?;
            // The provenance printed is that of the scene the report ran, as in its files.
            commit_reporting(target, &artifacts, &impact::report::main_scene(&scene), json)
        }
        Command::FemBench(args) => fem_bench(&args),
        Command::Mesh { scene, out, json } => mesh(&scene, out, json),
        Command::Field(args) => crate::field::run(&args),
        Command::DefaultScene => out(DEFAULT_SCENE),
        Command::Reference { what } => out(&cli_doc::reference(what, crate::cli::Cli::command())),
        Command::Completions { shell } => {
            // Into a buffer first: clap_complete panics on a write error, and a closed pipe
            // (`impact completions bash | head`) should end quietly like every other command.
            let mut script = Vec::new();
            clap_complete::generate(shell, &mut crate::cli::Cli::command(), "impact", &mut script);
            out(&String::from_utf8(script)?)
        }
    }
}

/// `solve`, `sweep` and `yield`: the scene's rows by the chosen models, `shape` turning the
/// scene into the command's cases.
fn rows(c: &Common, command: &str, shape: impl FnOnce(Scene) -> Result<Scene, Failure>) -> Result<(), Failure> {
    let scene = shape(c.transient.apply(load_bodies(&c.scene, command)?)?)?;
    let target = prepare(c.out.as_deref())?;
    let r = results(&scene, &c.model.kinds())?;
    emit(c, target, &scene, r)
}

/// `impact paper`: the paper's tables and figures reproduced on its own scene.
fn paper(dir: &Path, json: bool) -> Result<(), Failure> {
    let target = OutputDir::prepare(dir)?;
    let scene = impact::report::paper::Paper::new().scene;
    let mut a = impact::report::paper::reproduce()?;
    Provenance::of(&scene).stamp(&mut a);
    commit_reporting(target, &a, &scene, json)
}

/// `impact signals`: the reduced model's time series into files, its first-contact numbers
/// on the terminal.
fn signals(scene: &Scene, dir: Option<PathBuf>, json: bool) -> Result<(), Failure> {
    let target = OutputDir::prepare(dir.unwrap_or_else(|| default_out(scene, "signals")))?;
    let (run, tables, mut artifacts) = impact::report::signals::signals(scene)?;
    Provenance::of(scene).stamp(&mut artifacts);
    commit(target, &artifacts)?;
    if json {
        return print_json(scene, &run);
    }
    let text: Vec<String> = tables.iter().map(|t| t.to_text()).collect();
    out(&format!("scene: {} ({})\n\n{}", scene.name, scene.description, text.join("\n")))
}

/// `impact mesh`: the scene's tail beam as a Gmsh mesh file with named groups.
fn mesh(path: &Path, dir: Option<PathBuf>, json: bool) -> Result<(), Failure> {
    let scene = Scene::load(path)?;
    let tb = scene.tail_beam.as_ref().ok_or("the scene has no [tail_beam] table to write as a mesh")?;
    let target = OutputDir::prepare(dir.unwrap_or_else(|| default_out(&scene, "mesh")))?;
    let text = tb.beam.mesh_file(tb.element, 0)?.to_msh41(1e-3);
    let mut artifacts = impact::output::Artifacts::new();
    artifacts.add(format!("{}.msh", slug(&scene.name)), text);
    commit_reporting(target, &artifacts, &scene, json)
}

/// `impact identify`: the scene's ensemble, checked against every budget before it runs.
fn identify(path: &Path, dir: Option<PathBuf>, json: bool, no_features_csv: bool) -> Result<(), Failure> {
    let scene = Scene::load(path)?;
    impact::report::identify::checked_study(&scene)?;
    let mut target = OutputDir::prepare(dir.unwrap_or_else(|| default_out(&scene, "identify")))?;
    let files = if no_features_csv { RowFiles::Impacts } else { RowFiles::All };
    let (artifacts, summary) = impact::report::identify::write(&scene, &mut target, "", files, &Terminal::new())?;
    commit(target, &artifacts)?;
    if json {
        return print_json(&scene, &summary);
    }
    for t in impact::report::identify::summary_tables(&summary) {
        out(&format!("{}\n", t.to_text()))?;
    }
    Ok(())
}

/// `impact stream`: the scene's caving-stream detection study, its table on the terminal.
fn stream(path: &Path, dir: Option<PathBuf>, json: bool) -> Result<(), Failure> {
    let scene = Scene::load(path)?;
    impact::report::stream::check(&scene)?;
    let target = OutputDir::prepare(dir.unwrap_or_else(|| default_out(&scene, "stream")))?;
    let (mut artifacts, data) = impact::report::stream::report(&scene, &Terminal::new())?;
    Provenance::of(&scene).stamp(&mut artifacts);
    commit(target, &artifacts)?;
    if json {
        return print_json(&scene, &data);
    }
    out(&format!("{}\n", impact::report::stream::summary_table(&data).to_text()))
}

/// Largest recording or detector file read, bytes: its text and parsed samples stay in
/// memory together (a 4 GB CSV holds about 200 million samples).
const MAX_READ_BYTES: u64 = 4_000_000_000;

/// The text of `path`, refused before reading beyond [`MAX_READ_BYTES`].
fn read_text(path: &Path, what: &str) -> Result<String, Failure> {
    let bytes = read_bytes(path, what)?;
    Ok(String::from_utf8(bytes).map_err(|e| format!("{what} {}: not UTF-8 text: {e}", path.display()))?)
}

/// The bytes of `path`, refused before reading beyond [`MAX_READ_BYTES`].
fn read_bytes(path: &Path, what: &str) -> Result<Vec<u8>, Failure> {
    let size = std::fs::metadata(path).map_err(|e| format!("{what} {}: {e}", path.display()))?.len();
    if size > MAX_READ_BYTES {
        return Err(format!("{what} {}: {size} bytes, allowed at most {MAX_READ_BYTES}", path.display()).into());
    }
    Ok(std::fs::read(path).map_err(|e| format!("{what} {}: {e}", path.display()))?)
}

/// `impact detect`: a detector file applied to a recording, every file read and checked and
/// the recording scored before the output folder is prepared.
fn detect(detector: &Path, signal: &Path, dir: Option<PathBuf>, json: bool) -> Result<(), Failure> {
    let d = identify::detector::Detector::from_json(&read_text(detector, "--detector")?)
        .map_err(|e| format!("--detector {}: {e}", detector.display()))?;
    let origin = signal.display().to_string();
    let sidecar = identify::recording::Sidecar::parse(&read_text(signal, "--signal")?, &origin)?;
    let data = sidecar.data_path(signal);
    let recording = sidecar.read_data(read_bytes(&data, "the recording's data")?, &data.display().to_string())?;
    let (artifacts, data) = impact::report::detect::detect(&d, &recording, (&detector.display().to_string(), &origin))?;
    let target = OutputDir::prepare(
        dir.unwrap_or_else(|| PathBuf::from("impact-out").join(format!("{}-detect", slug(&d.provenance.scene)))),
    )?;
    commit(target, &artifacts)?;
    if json {
        return out(&format!("{}\n", serde_json::to_string_pretty(&data)?));
    }
    out(&format!("{}\n", impact::report::detect::summary_table(&data).to_text()))
}

/// `impact drops`: a drop-test recording against the scene's model, the scene and every
/// file read and checked before the output folder is prepared (the channel count once the
/// model is built, before anything is written).
fn drops(path: &Path, signal: &Path, dir: Option<PathBuf>, json: bool) -> Result<(), Failure> {
    let scene = Scene::load(path)?;
    let origin = signal.display().to_string();
    let sidecar = identify::recording::Sidecar::parse(&read_text(signal, "--signal")?, &origin)?;
    let data = sidecar.data_path(signal);
    let recording = sidecar.read_data(read_bytes(&data, "the recording's data")?, &data.display().to_string())?;
    studies::drops::check(&scene, &recording, &origin)?;
    let target = OutputDir::prepare(dir.unwrap_or_else(|| default_out(&scene, "drops")))?;
    let (mut artifacts, data) = impact::report::drops::drops(&scene, &recording, &origin, &Terminal::new())?;
    Provenance::of(&scene).stamp(&mut artifacts);
    commit(target, &artifacts)?;
    if json {
        return print_json(&scene, &data);
    }
    out(&format!("{}\n", impact::report::drops::summary_table(&data).to_text()))
}

/// `impact fem-bench`: the plate FE compliance map timed on the mesh that reaches the
/// tolerance.
fn fem_bench(args: &FemBenchArgs) -> Result<(), Failure> {
    let scene = load(&args.scene)?;
    let tolerance = args.tolerance.within("--tolerance", limits::FEM_BENCH_TOLERANCE, "")?;
    for (flag, n) in [("--nx", args.nx), ("--nz", args.nz)] {
        in_range(flag, &n.to_string(), n as f64, limits::FEM_BENCH_POINTS, "")?;
    }
    let r = impact::report::fem_bench::bench(&scene, tolerance, args.nx, args.nz)?;
    if args.json {
        return print_json(&scene, &r);
    }
    for t in impact::report::fem_bench::bench_tables(&r) {
        out(&format!("\n{}", t.to_text()))?;
    }
    Ok(())
}

/// The scene at `path`, or the embedded default.
pub fn load(path: &Option<PathBuf>) -> Result<Scene, Failure> {
    Ok(match path {
        Some(p) => Scene::load(p)?,
        None => Scene::default_scene(),
    })
}

/// A scene for the commands that strike its bodies at its points: a scene written only for
/// `impact identify` has neither (its ensemble draws its own).
fn load_bodies(path: &Option<PathBuf>, command: &str) -> Result<Scene, Failure> {
    let scene = load(path)?;
    // A structure from a mesh file brings its own struck points.
    if scene.bodies.is_empty() || (scene.points.is_empty() && scene.shell_mesh.is_none()) {
        return Err(format!(
            "scene {}: impact {command} strikes the scene's [[bodies]] at its [points], and it has none (a scene of only \"identify\" or \"drops\" is for impact identify, stream or drops)",
            scene.name
        )
        .into());
    }
    Ok(scene)
}

/// The one rule for default output folders: `impact-out/<scene name as a file name>-<command>`.
fn default_out(scene: &Scene, command: &str) -> PathBuf {
    PathBuf::from("impact-out").join(format!("{}-{command}", slug(&scene.name)))
}

/// The scene's rows by each requested model (the library's [`impact::run::results`]).
fn results(scene: &Scene, models: &[ModelKind]) -> Result<Results, Failure> {
    impact::run::results(scene, models, &Terminal::new())
}
