//! The `impact` command line.

use clap::{Args, CommandFactory, Parser, Subcommand, ValueEnum};
use coupled::plan::{ModelKind, Results};
use coupled::transient::{Discretisation, DEFAULT_TOLERANCE};
use impact::output::{Artifacts, OutputDir, OutputFile};
use impact::present::rows::{narrow, response_tables, slug, yield_tables, NARROW};
use impact::present::table::Table;
use impact::provenance::Provenance;
use impact::report::identify::RowFiles;
use impact::report::Failure;
use impact::scene::{limits, Analysis, Scene, SceneSource, DEFAULT_SCENE};
use progress::Terminal;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use written::{in_range, Written};

mod cli_doc;
mod progress;
mod written;

#[derive(Parser)]
#[command(
    name = "impact",
    version,
    about = "Rock-sphere impact on supported steel plates: the paper's beam model and its checks"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Args, Clone)]
struct Common {
    /// Scene file (TOML); the embedded default is the paper's Table 1.
    #[arg(long, value_name = "FILE")]
    scene: Option<PathBuf>,
    /// Print JSON instead of tables.
    #[arg(long)]
    json: bool,
    /// Also write CSV and JSON files into DIR.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Which model answers: the paper's beam, the plate finite elements (quasi-static), the
    /// transient plate, or all three.
    #[arg(long, value_enum, default_value_t = ModelChoice::Beam)]
    model: ModelChoice,
    #[command(flatten)]
    transient: TransientArgs,
    /// Show every column on the terminal (the compliance and its error, δ_max, deflection,
    /// spring forces, energy shares, solver evidence, each validity criterion with its value
    /// and limit); the default shows the case, P_max or v_y with its error and one validity
    /// word. Files (--out, --json) always hold every column.
    #[arg(long, conflicts_with = "columns")]
    wide: bool,
    /// Show these columns on the terminal, comma-separated, by header or CSV key (e.g.
    /// `body,velocity_m_per_s,contact_force_N,deflection_m,validity`); `--wide` lists them all.
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    columns: Vec<String>,
}

impl Common {
    /// The terminal's view of `tables`: every column (`--wide`), the chosen ones (`--columns`,
    /// each in the tables that have it; one that no table has is an error), or the narrow
    /// default ([`NARROW`]).
    fn view(&self, tables: &[Table]) -> Result<Vec<Table>, Failure> {
        if self.wide {
            return Ok(tables.to_vec());
        }
        if self.columns.is_empty() {
            return Ok(tables.iter().map(|t| narrow(t, &NARROW, true)).collect());
        }
        // Each column by its header or its key (the CSV name), the key case-insensitive.
        let named = |t: &Table, c: &str| -> Vec<usize> {
            let keys = t.csv_headers();
            (0..t.headers.len())
                .filter(|&i| t.headers[i] == c || keys.get(i).is_some_and(|k| k.eq_ignore_ascii_case(c)))
                .collect()
        };
        let mut known: Vec<String> = Vec::new();
        for k in tables.iter().flat_map(|t| t.csv_headers()) {
            if !known.contains(&k) {
                known.push(k);
            }
        }
        if let Some(c) = self.columns.iter().find(|c| tables.iter().all(|t| named(t, c.trim()).is_empty())) {
            return Err(format!("--columns {c}: no such column; the columns are {}", known.join(", ")).into());
        }
        Ok(tables
            .iter()
            .map(|t| {
                let mut cols: Vec<usize> = self.columns.iter().flat_map(|c| named(t, c.trim())).collect();
                cols.sort_unstable();
                cols.dedup();
                let keep: Vec<&str> = cols.iter().map(|&i| t.headers[i].as_str()).collect();
                narrow(t, &keep, false)
            })
            .collect())
    }
}

/// How the transient model is discretised.
#[derive(Args, Clone)]
struct TransientArgs {
    // The help states the range from its one definition, hence no doc comment.
    #[arg(long, default_value_t = Written::from(DEFAULT_TOLERANCE), value_name = "REL", help = format!(
        "Relative error allowed on the transient model's P_max (the force at maximum compression) and contact time: each case's mesh and time step are chosen so that its error estimate is within it (in {})",
        limits::TRANSIENT_TOLERANCE
    ))]
    tolerance: Written,
}

impl TransientArgs {
    /// The scene with this discretisation, or an error naming the flag.
    fn apply(&self, mut scene: Scene) -> Result<Scene, Failure> {
        let tolerance = self.tolerance.within("--tolerance", limits::TRANSIENT_TOLERANCE, "")?;
        scene.transient_discretisation = Discretisation::tolerance(tolerance);
        Ok(scene)
    }
}

/// The `impact field --format` choice.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum FieldFormat {
    /// `impact-plate-field/1` JSON, per unit load (reference/README.md).
    Json,
    /// VTK XML UnstructuredGrid, with stresses and the near-load flag.
    Vtu,
    /// The transient model's deflection during contact: a ParaView time series (`.pvd`
    /// with one `.vtu` per frame, and the run's history.csv) into a directory.
    Pvd,
}

/// The `--model` choice.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum ModelChoice {
    Beam,
    Plate,
    Transient,
    All,
}

impl ModelChoice {
    fn kinds(self) -> Vec<ModelKind> {
        match self {
            ModelChoice::Beam => vec![ModelKind::Beam],
            ModelChoice::Plate => vec![ModelKind::Plate],
            ModelChoice::Transient => vec![ModelKind::Transient],
            ModelChoice::All => ModelKind::ALL.to_vec(),
        }
    }
}

#[derive(Subcommand)]
enum Command {
    /// Responses (and yield velocities, if the scene asks) at the scene's points.
    Solve(Common),
    /// Responses and yield velocities along the plate, evenly spaced.
    Sweep {
        #[command(flatten)]
        common: Common,
        #[arg(
            long,
            default_value_t = 101,
            value_parser = clap::value_parser!(u32).range(limits::POINT_COUNT.lo as i64..=limits::POINT_COUNT.hi as i64),
            help = format!("Number of points on the centreline from 0 to L (the paper uses 101), in {}", limits::POINT_COUNT)
        )]
        count: u32,
    },
    /// Yield velocities at the scene's points (eqs. 51-54).
    Yield(Common),
    /// Beam against plate FE for a scene: the studies the scene names, into DIR (default
    /// impact-out/<scene name>-compare).
    Compare {
        /// Scene file; default: the paper's Table 1.
        #[arg(long, value_name = "FILE")]
        scene: Option<PathBuf>,
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        #[command(flatten)]
        transient: TransientArgs,
        /// Print a JSON summary of the run (provenance, findings, files written) to stdout.
        #[arg(long)]
        json: bool,
    },
    /// Transient impact against the quasi-static models for a scene (default out:
    /// impact-out/<scene name>-dynamic).
    Dynamic {
        /// Scene file; default: the paper's Table 1.
        #[arg(long, value_name = "FILE")]
        scene: Option<PathBuf>,
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        #[command(flatten)]
        transient: TransientArgs,
        /// Print a JSON summary of the run (provenance, findings, files written) to stdout.
        #[arg(long)]
        json: bool,
    },
    /// Sensor signals of the scene's impacts by the reduced-order model (its `[signals]`
    /// table): every support set, body, transient point and velocity; the time series as CSV
    /// (default out: impact-out/<scene name>-signals), the first-contact numbers with their
    /// truncation errors on the terminal.
    Signals {
        /// Scene file; default: the paper's Table 1.
        #[arg(long, value_name = "FILE")]
        scene: Option<PathBuf>,
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Print the summary as JSON instead of tables.
        #[arg(long)]
        json: bool,
    },
    /// Coal-gangue identification over the scene's random-impact ensemble ([ensemble]): the
    /// separability of every sensor feature, placement maps, which variability hides the
    /// difference, into DIR (default impact-out/<scene name>-identify).
    Identify {
        /// Scene file with an [ensemble] table and "identify" among its analyses.
        #[arg(long, value_name = "FILE")]
        scene: PathBuf,
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Print the summary as JSON instead of a table.
        #[arg(long)]
        json: bool,
        /// Leave out features.csv (one row per impact and channel; 112 MB for
        /// scenes/caving-stream.toml); impacts.csv and the report are written as always.
        #[arg(long)]
        no_features_csv: bool,
    },
    /// Reproduce the paper's Tables 2-12 and Figures 8-19 into DIR.
    Paper {
        #[arg(long, value_name = "DIR", default_value = "impact-out/paper")]
        out: PathBuf,
        /// Print a JSON summary of the run (provenance, findings, files written) to stdout.
        #[arg(long)]
        json: bool,
    },
    /// The main job on the default scene: every report into DIR, and the coal-gangue
    /// identification of the shipped scenes (scenes/caving-stream.toml,
    /// scenes/paper-velocities-ensemble.toml) into DIR/identify/<scene name>/.
    Report {
        #[arg(long, value_name = "DIR", default_value = "reports")]
        out: PathBuf,
        /// Print a JSON summary of the run (provenance, findings, files written) to stdout.
        #[arg(long)]
        json: bool,
    },
    /// Time the plate FE compliance map (101 x 21 points, Con 1-3) on the mesh that
    /// reaches the tolerance at the centre.
    FemBench {
        /// Scene file; default: the paper's Table 1.
        #[arg(long, value_name = "FILE")]
        scene: Option<PathBuf>,
        /// Print JSON instead of tables.
        #[arg(long)]
        json: bool,
        #[arg(long, default_value_t = Written::from(1e-4), help = format!(
            "Relative error allowed at the plate centre, from the mesh convergence study (in {})",
            limits::FEM_BENCH_TOLERANCE
        ))]
        tolerance: Written,
        #[arg(long, default_value_t = 101, help = format!("Impact points along the length (in {})", limits::FEM_BENCH_POINTS))]
        nx: usize,
        #[arg(long, default_value_t = 21, help = format!("Impact points across the width (in {})", limits::FEM_BENCH_POINTS))]
        nz: usize,
    },
    /// Write the plate FE deflection field under a point load: JSON for meshio (see
    /// reference/README.md) or a .vtu that ParaView opens directly.
    ///
    /// The .vtu has point data `displacement` (0, 0, w) for "Warp By Vector" and w, w_x, w_z;
    /// cell data the element-centre moments M_x, M_z, M_xz, the surface bending stresses
    /// sigma = 6M/h², and `near_load` = 1 on the elements touching the load point. There the
    /// Kirchhoff moment of a point load is singular and the values grow with refinement: read
    /// stress maxima from the other elements.
    Field {
        /// Scene file; default: the paper's Table 1.
        #[arg(long, value_name = "FILE")]
        scene: Option<PathBuf>,
        /// Condition name from the scene.
        #[arg(long, default_value = "Con 1")]
        condition: String,
        /// Load position along the length, mm.
        #[arg(long, allow_negative_numbers = true)]
        x_mm: f64,
        /// Load position across the width, mm.
        #[arg(long, allow_negative_numbers = true)]
        z_mm: f64,
        #[arg(long, default_value_t = 40, help = format!("Elements along the longer side (in {})", limits::FIELD_ELEMENTS))]
        elements: usize,
        /// Output file (a regular file or a new one; `-` for standard output); default
        /// field.json or field.vtu by --format.
        #[arg(long, value_name = "FILE")]
        out: Option<PathBuf>,
        /// File format.
        #[arg(long, value_enum, default_value_t = FieldFormat::Json)]
        format: FieldFormat,
        #[arg(long, value_name = "F", allow_negative_numbers = true, help = format!(
            "Load, N, that scales every value in the .vtu (fields are linear in it), in {} N (default 1 N); the JSON is always per unit load",
            limits::FORCE_N
        ))]
        force_n: Option<Written>,
        /// Scale the .vtu by the impact's maximum force instead: P_max of --body at
        /// --velocity-m-per-s at the load point by the quasi-static plate model (the paper's
        /// energy balance on the plate FE compliance, as `impact solve --model plate`). The
        /// terminal and the file say so, with P_max's error and the case's validity.
        #[arg(long, conflicts_with = "force_n")]
        force_of_impact: bool,
        /// --format pvd or --force-of-impact: the striking body (a name from the scene;
        /// default its first).
        #[arg(long)]
        body: Option<String>,
        /// --format pvd or --force-of-impact: impact velocity, m/s (default the scene's first).
        #[arg(long, value_name = "V", allow_negative_numbers = true)]
        velocity_m_per_s: Option<Written>,
        /// Print a JSON summary of what was written (provenance, every file with its size and
        /// SHA-256) to stdout; not with `--out -`, which prints the field itself.
        #[arg(long)]
        json: bool,
    },
    /// Print a shell completion script to standard output (e.g. `impact completions bash >
    /// ~/.local/share/bash-completion/completions/impact`).
    Completions {
        #[arg(value_enum)]
        shell: clap_complete::Shell,
    },
    /// Print the embedded default scene (a template for your own).
    DefaultScene,
    /// Print a generated reference: docs/cli.md or docs/scenes.md (a test keeps them equal).
    #[command(hide = true)]
    Reference {
        #[arg(value_enum)]
        what: cli_doc::Reference,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match execute(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // A closed pipe (`impact solve | head -1`) is the reader's normal end, not ours.
            if e.downcast_ref::<std::io::Error>().is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe) {
                return ExitCode::SUCCESS;
            }
            note(&format!("error: {e}"));
            ExitCode::FAILURE
        }
    }
}

/// The impact `impact field` strikes: `--body` (default the scene's first) at
/// `--velocity-m-per-s` (default the scene's first), checked against the scene's ranges.
fn impact_of<'a>(
    scene: &'a Scene,
    body: &Option<String>,
    velocity: &Option<Written>,
) -> Result<(&'a analytic::Sphere, f64), Failure> {
    let sphere = match body {
        None => scene.bodies.first().ok_or("the scene has no body; give one in [[bodies]]")?,
        Some(b) => scene.bodies.iter().find(|s| &s.name == b).ok_or_else(|| {
            let names: Vec<&str> = scene.bodies.iter().map(|s| s.name.as_str()).collect();
            format!("--body '{b}' is not in the scene; it has {names:?}")
        })?,
    };
    let v = match velocity {
        Some(v) => v.within("--velocity-m-per-s", limits::VELOCITY_M_PER_S, "m/s")?,
        None => *scene.velocities.first().ok_or("the scene has no velocity; give --velocity-m-per-s")?,
    };
    Ok((sphere, v))
}

/// The field data of a .vtu scaled to a case's quasi-static P_max: the force's error, the
/// velocity, and every validity criterion's value and limit with `valid` (1 or 0).
fn case_numbers(case: &coupled::plan::ResponseValues, v: f64) -> Vec<(String, f64)> {
    let mut n = vec![("contact_force_N".to_string(), case.contact_force), ("velocity_m_per_s".into(), v)];
    if let Some(e) = case.contact_force_error {
        n.push(("contact_force_error_N".into(), e));
    }
    for (name, c) in case.validity.criteria() {
        let key = name.replace([' ', '-'], "_");
        n.push((format!("{key}_value"), c.value));
        n.push((format!("{key}_limit"), c.limit));
    }
    n.push(("valid".into(), f64::from(u8::from(case.validity.all_valid()))));
    n
}

fn load(path: &Option<PathBuf>) -> Result<Scene, Failure> {
    Ok(match path {
        Some(p) => Scene::load(p)?,
        None => Scene::default_scene(),
    })
}

/// A scene for the commands that strike its bodies at its points: a scene written only for
/// `impact identify` has neither (its ensemble draws its own).
fn load_bodies(path: &Option<PathBuf>, command: &str) -> Result<Scene, Failure> {
    let scene = load(path)?;
    if scene.bodies.is_empty() || scene.points.is_empty() {
        return Err(format!(
            "scene {}: impact {command} strikes the scene's [[bodies]] at its [points], and it has none (a scene whose only analysis is \"identify\" is for impact identify)",
            scene.name
        )
        .into());
    }
    Ok(scene)
}

/// Writes a line to standard error, ignoring a failed write: a message nobody can receive (a
/// closed pipe, `2>&1 | head`) must neither panic, as `eprintln!` does, nor turn the run's own
/// outcome into another one; the exit code still says how the run ended.
fn note(text: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{text}");
}

/// `text` broken at spaces into lines of at most `width` characters (a longer word stays whole).
fn wrap(text: &str, width: usize) -> String {
    let mut lines: Vec<String> = vec![String::new()];
    for word in text.split_whitespace() {
        let last = lines.last_mut().expect("one line at least");
        if !last.is_empty() && last.chars().count() + 1 + word.chars().count() > width {
            lines.push(word.to_string());
        } else {
            if !last.is_empty() {
                last.push(' ');
            }
            last.push_str(word);
        }
    }
    lines.join("\n")
}

/// The one rule for default output folders: `impact-out/<scene name as a file name>-<command>`.
fn default_out(scene: &Scene, command: &str) -> PathBuf {
    PathBuf::from("impact-out").join(format!("{}-{command}", slug(&scene.name)))
}

/// Writes to standard output; a closed pipe ends the program quietly (see `main`).
fn out(text: &str) -> Result<(), Failure> {
    let mut o = std::io::stdout().lock();
    o.write_all(text.as_bytes())?;
    o.flush()?;
    Ok(())
}

/// The scene's rows by each requested model (the library's [`impact::run::results`]).
fn results(scene: &Scene, models: &[ModelKind]) -> Result<Results, Failure> {
    impact::run::results(scene, models, &Terminal::new())
}

fn execute(command: Command) -> Result<(), Failure> {
    match command {
        Command::Solve(c) => {
            let scene = c.transient.apply(load_bodies(&c.scene, "solve")?)?;
            let target = prepare(c.out.as_deref())?;
            let r = results(&scene, &c.model.kinds())?;
            emit(&c, target, &scene, r)
        }
        Command::Sweep { common, count } => {
            let scene = common.transient.apply(load_bodies(&common.scene, "sweep")?)?.with_sweep(count as usize);
            let target = prepare(common.out.as_deref())?;
            let r = results(&scene, &common.model.kinds())?;
            emit(&common, target, &scene, r)
        }
        Command::Yield(c) => {
            let mut scene = c.transient.apply(load_bodies(&c.scene, "yield")?)?;
            scene.analyses = vec![Analysis::YieldVelocity];
            let target = prepare(c.out.as_deref())?;
            let r = results(&scene, &c.model.kinds())?;
            emit(&c, target, &scene, r)
        }
        Command::Paper { out, json } => {
            let target = OutputDir::prepare(&out)?;
            let scene = impact::report::paper::Paper::new().scene;
            let mut a = impact::report::paper::reproduce()?;
            Provenance::of(&scene).stamp(&mut a);
            commit_reporting(target, &a, &scene, json)
        }
        Command::Dynamic { scene, out, transient, json } => {
            let scene = transient.apply(load_bodies(&scene, "dynamic")?)?;
            let dir = out.unwrap_or_else(|| default_out(&scene, "dynamic"));
            let target = OutputDir::prepare(&dir)?;
            let mut a = impact::report::transient::report(&scene, &Terminal::new())?;
            Provenance::of(&scene).stamp(&mut a);
            commit_reporting(target, &a, &scene, json)
        }
        Command::Signals { scene, out: dir, json } => {
            let scene = load(&scene)?;
            let dir = dir.unwrap_or_else(|| default_out(&scene, "signals"));
            let target = OutputDir::prepare(&dir)?;
            let (run, tables, mut artifacts) = impact::report::signals::signals(&scene)?;
            Provenance::of(&scene).stamp(&mut artifacts);
            commit(target, &artifacts)?;
            if json {
                print_json(&scene, &run)
            } else {
                let text: Vec<String> = tables.iter().map(|t| t.to_text()).collect();
                out(&format!("scene: {} ({})\n\n{}", scene.name, scene.description, text.join("\n")))
            }
        }
        Command::Compare { scene, out, transient, json } => {
            let scene = transient.apply(load_bodies(&scene, "compare")?)?;
            let dir = out.unwrap_or_else(|| default_out(&scene, "compare"));
            let target = OutputDir::prepare(&dir)?;
            commit_reporting(target, &impact::report::scene_report(&scene, &Terminal::new())?, &scene, json)
        }
        Command::Identify { scene, out: dir, json, no_features_csv } => {
            let scene = Scene::load(&scene)?;
            impact::report::identify::checked_study(&scene)?;
            let dir = dir.unwrap_or_else(|| default_out(&scene, "identify"));
            let mut target = OutputDir::prepare(&dir)?;
            let files = if no_features_csv { RowFiles::Impacts } else { RowFiles::All };
            let (artifacts, summary) =
                impact::report::identify::write(&scene, &mut target, "", files, &Terminal::new())?;
            commit(target, &artifacts)?;
            if json {
                print_json(&scene, &summary)?;
            } else {
                for t in impact::report::identify::summary_tables(&summary) {
                    out(&format!("{}\n", t.to_text()))?;
                }
            }
            Ok(())
        }
        Command::Report { out, json } => {
            let mut target = OutputDir::prepare(&out)?;
            let scene = Scene::default_scene();
            let artifacts = impact::report::full_report(&scene, &mut target, &Terminal::new())?;
            // The provenance printed is that of the scene the report ran, as in its files.
            commit_reporting(target, &artifacts, &impact::report::main_scene(&scene), json)
        }
        Command::FemBench { scene, json, tolerance, nx, nz } => {
            let scene = load(&scene)?;
            let tolerance = tolerance.within("--tolerance", limits::FEM_BENCH_TOLERANCE, "")?;
            for (flag, n) in [("--nx", nx), ("--nz", nz)] {
                in_range(flag, &n.to_string(), n as f64, limits::FEM_BENCH_POINTS, "")?;
            }
            let r = impact::report::fem_bench::bench(&scene, tolerance, nx, nz)?;
            if json {
                print_json(&scene, &r)?;
            } else {
                for t in impact::report::fem_bench::bench_tables(&r) {
                    out(&format!("\n{}", t.to_text()))?;
                }
            }
            Ok(())
        }
        Command::Field {
            scene,
            condition,
            x_mm,
            z_mm,
            elements,
            out: dest,
            format,
            force_n,
            force_of_impact,
            body,
            velocity_m_per_s,
            json,
        } => {
            let scene = load(&scene)?;
            if json && dest.as_deref() == Some(Path::new("-")) {
                return Err("--json prints a summary of the files written; with --out - the field itself goes to standard output, so give one or the other".into());
            }
            let cond = scene.conditions.iter().find(|c| c.name == condition).ok_or_else(|| {
                let names: Vec<&str> = scene.conditions.iter().map(|c| c.name.as_str()).collect();
                format!("--condition '{condition}' is not in the scene; it has {names:?}")
            })?;
            in_range("--elements", &elements.to_string(), elements as f64, limits::FIELD_ELEMENTS, "")?;
            let (l, b) = (scene.plate.length() * 1e3, scene.plate.width() * 1e3);
            if !(0.0..=l).contains(&x_mm) {
                return Err(format!("--x-mm {x_mm} is outside the plate: the allowed range is [0, {l}] mm").into());
            }
            if !(0.0..=b).contains(&z_mm) {
                return Err(format!("--z-mm {z_mm} is outside the plate: the allowed range is [0, {b}] mm").into());
            }
            let force_n = force_n.map(|f| f.within("--force-n", limits::FORCE_N, "N")).transpose()?;
            // The JSON format is defined per unit load; a scaled JSON would read as one.
            if format != FieldFormat::Vtu && (force_n.is_some() || force_of_impact) {
                return Err("--force-n and --force-of-impact scale the .vtu only; add --format vtu (the JSON is per unit load, the .pvd at the impact's own force)".into());
            }
            if !(format == FieldFormat::Pvd || force_of_impact) && (body.is_some() || velocity_m_per_s.is_some()) {
                return Err(
                    "--body and --velocity-m-per-s choose the impact of --format pvd or --force-of-impact only".into(),
                );
            }
            let (x, z) = (x_mm * 1e-3, z_mm * 1e-3);
            if format == FieldFormat::Pvd {
                let (sphere, v) = impact_of(&scene, &body, &velocity_m_per_s)?;
                let dir = dest.unwrap_or_else(|| PathBuf::from("field-series"));
                let target = OutputDir::prepare(&dir)?;
                let mut a = impact::report::field_series::contact_series(&scene, cond, sphere, v, (x, z), elements)?;
                Provenance::of(&scene).stamp(&mut a);
                return commit_reporting(target, &a, &scene, json);
            }
            let path = dest.unwrap_or_else(|| {
                PathBuf::from(match format {
                    FieldFormat::Json => "field.json",
                    FieldFormat::Vtu | FieldFormat::Pvd => "field.vtu",
                })
            });
            let target = OutputFile::prepare(&path)?;
            let f = impact::report::field::field(&scene, cond, x, z, elements)?;
            let mut said = None;
            let bytes = match format {
                FieldFormat::Json => {
                    Provenance::of(&scene).stamp_json(format!("{}\n", serde_json::to_string(&f)?).as_bytes())
                }
                FieldFormat::Vtu | FieldFormat::Pvd => {
                    let mut meta = impact::present::vtk::Metadata {
                        provenance: Provenance::of(&scene),
                        lines: vec![format!(
                            "impact field: the plate FE deflection, moments and stresses of '{}' under a point load at ({x_mm}, {z_mm}) mm on {elements} elements along the longer side",
                            cond.name
                        )],
                        numbers: vec![("load_x_m".into(), x), ("load_z_m".into(), z)],
                    };
                    let force = if force_of_impact {
                        let (sphere, v) = impact_of(&scene, &body, &velocity_m_per_s)?;
                        let case = impact::report::field::quasi_static_impact(&scene, cond, sphere, v, x, z)?;
                        let what = format!("{} at {v} m/s on {} at ({x_mm}, {z_mm}) mm", sphere.name, cond.name);
                        let text = impact::report::field::p_max_text(&case, &what)?;
                        meta.lines.push(text.clone());
                        let numbers = case_numbers(&case, v);
                        meta.numbers.extend(numbers.iter().cloned());
                        said = Some((text, numbers));
                        case.contact_force
                    } else {
                        meta.lines.push(format!("scaled by the load given, {} N", force_n.unwrap_or(1.0)));
                        force_n.unwrap_or(1.0)
                    };
                    impact::present::vtk::to_vtu(&f, force, &meta)?
                }
            };
            if target.is_stdout() {
                out(std::str::from_utf8(&bytes)?)?;
            } else if let Some(p) = target.commit(&bytes)? {
                note(&format!("wrote {}", p.display()));
                if json {
                    let mut doc = serde_json::json!({
                        "files": [{
                            "path": p.to_string_lossy(),
                            "bytes": bytes.len(),
                            "sha256": impact::output::sha256_hex(&bytes),
                        }],
                    });
                    // With --force-of-impact: what the load is, as the file's field data says.
                    if let Some((text, numbers)) = &said {
                        let map: serde_json::Map<String, serde_json::Value> =
                            numbers.iter().map(|(k, v)| (k.clone(), serde_json::json!(v))).collect();
                        doc["quasi_static_p_max"] = serde_json::json!({ "text": text, "numbers": map });
                    }
                    // The provenance as the first key, as in every JSON document of ours.
                    let doc = Provenance::of(&scene).stamp_json(serde_json::to_string_pretty(&doc)?.as_bytes());
                    out(&format!("{}\n", String::from_utf8(doc)?))?;
                }
            }
            if let Some((text, _)) = said {
                note(&text);
            }
            Ok(())
        }
        Command::DefaultScene => out(DEFAULT_SCENE),
        Command::Reference { what } => out(&cli_doc::reference(what, Cli::command())),
        Command::Completions { shell } => {
            // Into a buffer first: clap_complete panics on a write error, and a closed pipe
            // (`impact completions bash | head`) should end quietly like every other command.
            let mut script = Vec::new();
            clap_complete::generate(shell, &mut Cli::command(), "impact", &mut script);
            out(&String::from_utf8(script)?)
        }
    }
}

/// Checks an output directory before any computation: a run that cannot write fails
/// before it spends time, and a run that fails leaves earlier output as it was.
fn prepare(dir: Option<&Path>) -> Result<Option<OutputDir>, Failure> {
    Ok(match dir {
        Some(d) => Some(OutputDir::prepare(d)?),
        None => None,
    })
}

fn commit(target: OutputDir, artifacts: &Artifacts) -> Result<(), Failure> {
    let dir = target.path().to_path_buf();
    let written = target.commit(artifacts)?;
    note(&format!("wrote {} files under {}", written.len(), dir.display()));
    Ok(())
}

/// Commits a report's files and, with `json`, prints what a program needs to use them: the
/// provenance, the directory, every file with its size and SHA-256, and the findings the
/// report opens with (`findings.json`, when it has one).
fn commit_reporting(target: OutputDir, artifacts: &Artifacts, scene: &Scene, json: bool) -> Result<(), Failure> {
    let dir = target.path().to_path_buf();
    commit(target, artifacts)?;
    if json {
        // From the manifest just written: the files streamed during the run are in it too.
        let files: Vec<serde_json::Value> = impact::output::listed_files(&dir)?
            .into_iter()
            .map(|(path, bytes, sha256)| serde_json::json!({ "path": path, "bytes": bytes, "sha256": sha256 }))
            .collect();
        let findings: Vec<serde_json::Value> = artifacts
            .paths()
            .filter(|p| p.file_name().is_some_and(|n| n == "findings.json"))
            .filter_map(|p| serde_json::from_slice(artifacts.get(&p.to_string_lossy())?).ok())
            .collect();
        let doc = serde_json::json!({
            "provenance": Provenance::of(scene),
            "directory": dir.to_string_lossy(),
            "findings": findings,
            "files": files,
        });
        out(&format!("{}\n", serde_json::to_string_pretty(&doc)?))?;
    }
    Ok(())
}

/// Prints `value` as JSON with the scene's provenance as its first key.
fn print_json(scene: &Scene, value: &impl serde::Serialize) -> Result<(), Failure> {
    let doc = Provenance::of(scene).stamp_json(serde_json::to_string_pretty(value)?.as_bytes());
    out(&format!("{}\n", String::from_utf8(doc)?))
}

/// The JSON document of a run: the results with what a reader needs to trust them.
#[derive(serde::Serialize)]
struct Document<'a> {
    provenance: Provenance,
    program: &'static str,
    version: &'static str,
    units: &'static str,
    status: &'a str,
    summary: coupled::plan::Summary,
    /// The rows in the one column schema's keys (`contact_force_N`, ...), as in the CSV
    /// files and the Python columns.
    results: studies::columns::Rows<'a>,
}

fn emit(c: &Common, target: Option<OutputDir>, scene: &Scene, results: Results) -> Result<(), Failure> {
    let status = impact::run::status_line(&results);
    // Serialized straight from the rows (no intermediate JSON tree), and only when asked for:
    // a sweep of many points must not hold its results several times over.
    let json = || -> Result<String, Failure> {
        Ok(serde_json::to_string_pretty(&Document {
            provenance: Provenance::of(scene),
            program: "impact",
            version: env!("CARGO_PKG_VERSION"),
            units: "SI (m, m/s, N, m/N, J ratios)",
            status: &status,
            summary: results.summary(),
            results: studies::columns::Rows(&results),
        })?)
    };
    if let Some(target) = target {
        let mut a = Artifacts::new();
        // File names from the support set's position in the scene (unique), not its name.
        for (kind, tables) in [("responses", response_tables(&results)), ("yield", yield_tables(&results))] {
            for (i, t) in tables.iter().enumerate() {
                a.add(format!("{kind}-{}.csv", i + 1), t.to_csv());
            }
        }
        a.add("results.json", json()?);
        Provenance::of(scene).stamp(&mut a);
        commit(target, &a)?;
    }
    if c.json {
        out(&format!("{}\n", json()?))?;
        // The JSON carries the status too; the terminal gets it on standard error.
        note(&status);
    } else {
        let mut text = format!("scene: {}\n{}\n", scene.name, wrap(&scene.description, 100));
        let tables: Vec<Table> = response_tables(&results).into_iter().chain(yield_tables(&results)).collect();
        for t in c.view(&tables)? {
            text.push('\n');
            text.push_str(&t.to_text());
        }
        text.push_str(&format!("\n{}\n", if c.wide { status.clone() } else { wrap(&status, 118) }));
        out(&text)?;
    }
    Ok(())
}
