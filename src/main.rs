//! The `impact` command line.

use clap::{Args, Parser, Subcommand};
use impact::output::Artifacts;
use impact::run::{run, BeamModel, Results};
use impact::scene::{Analysis, Scene, DEFAULT_SCENE};
use impact::table::Table;
use impact::views::{response_tables, slug, yield_tables};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

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
}

#[derive(Subcommand)]
enum Command {
    /// Responses (and yield velocities, if the scene asks) at the scene's points.
    Solve(Common),
    /// Responses and yield velocities along the plate, evenly spaced.
    Sweep {
        #[command(flatten)]
        common: Common,
        /// Number of points on [0, L] (the paper uses 101).
        #[arg(long, default_value_t = 101)]
        count: usize,
    },
    /// Yield velocities at the scene's points (eqs. 51-54).
    Yield(Common),
    /// Beam against plate FE for a scene: tables, maps across the width, error against
    /// run time, into DIR (default reports/<scene name>).
    Compare {
        /// Scene file; default: the paper's Table 1.
        #[arg(long, value_name = "FILE")]
        scene: Option<PathBuf>,
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
    },
    /// Transient impact against the quasi-static models for a scene (default out:
    /// reports/<scene>/dynamic).
    Dynamic {
        /// Scene file; default: the paper's Table 1.
        #[arg(long, value_name = "FILE")]
        scene: Option<PathBuf>,
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
    },
    /// Reproduce the paper's Tables 2-12 and Figures 8-19 into DIR.
    Paper {
        #[arg(long, value_name = "DIR", default_value = "reports/paper")]
        out: PathBuf,
    },
    /// The main job on the default scene: every report into DIR.
    Report {
        #[arg(long, value_name = "DIR", default_value = "reports")]
        out: PathBuf,
    },
    /// Time the plate FE compliance map (101 x 21 points, Con 1-3) on the mesh that
    /// reaches the tolerance at the centre.
    FemBench {
        #[command(flatten)]
        common: Common,
        /// Relative error allowed at the plate centre, from the mesh convergence study.
        #[arg(long, default_value_t = 1e-4)]
        tolerance: f64,
        /// Impact points along the length.
        #[arg(long, default_value_t = 101)]
        nx: usize,
        /// Impact points across the width.
        #[arg(long, default_value_t = 21)]
        nz: usize,
    },
    /// Write the plate FE deflection field under a unit load (JSON for meshio; see
    /// reference/README.md).
    Field {
        /// Scene file; default: the paper's Table 1.
        #[arg(long, value_name = "FILE")]
        scene: Option<PathBuf>,
        /// Condition name from the scene.
        #[arg(long, default_value = "Con 1")]
        condition: String,
        /// Load position along the length, mm.
        #[arg(long)]
        x_mm: f64,
        /// Load position across the width, mm.
        #[arg(long)]
        z_mm: f64,
        /// Elements along the longer side.
        #[arg(long, default_value_t = 40)]
        elements: usize,
        /// Output file.
        #[arg(long, value_name = "FILE", default_value = "field.json")]
        out: PathBuf,
    },
    /// Print the embedded default scene (a template for your own).
    DefaultScene,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match execute(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

type Failure = Box<dyn std::error::Error>;

fn load(common: &Common) -> Result<Scene, Failure> {
    Ok(match &common.scene {
        Some(p) => Scene::load(p)?,
        None => Scene::default_scene(),
    })
}

fn execute(command: Command) -> Result<(), Failure> {
    match command {
        Command::Solve(c) => {
            let scene = load(&c)?;
            emit(&c, &scene, run(&scene, &BeamModel { plate: &scene.plate })?)
        }
        Command::Sweep { common, count } => {
            let scene = load(&common)?.with_sweep(count)?;
            emit(&common, &scene, run(&scene, &BeamModel { plate: &scene.plate })?)
        }
        Command::Yield(c) => {
            let mut scene = load(&c)?;
            scene.analyses = vec![Analysis::YieldVelocity];
            emit(&c, &scene, run(&scene, &BeamModel { plate: &scene.plate })?)
        }
        Command::Paper { out } => write(&out, &impact::paper::reproduce()?),
        Command::Dynamic { scene, out } => {
            let scene = load(&Common { scene, json: false, out: None })?;
            let dir = out.unwrap_or_else(|| PathBuf::from("reports").join(slug(&scene.name)).join("dynamic"));
            let points = impact::compare::scene_points(&scene);
            write(&dir, &impact::dynreport::report(&scene, &points)?)
        }
        Command::Compare { scene, out } => {
            let scene = load(&Common { scene, json: false, out: None })?;
            let dir = out.unwrap_or_else(|| PathBuf::from("reports").join(slug(&scene.name)));
            write(&dir, &impact::compare::report(&scene)?)
        }
        Command::Report { out } => {
            let mut all = Artifacts::new();
            all.nest("paper", impact::paper::reproduce()?);
            all.nest("fem", impact::femreport::report(&Scene::default_scene())?);
            let scene = Scene::default_scene();
            let mut cmp = impact::compare::report(&scene)?;
            impact::compare::add_paper_studies(&mut cmp)?;
            // The transient section at representative points: Area 2 and the midpoint on the
            // centreline, the midpoint of a free edge and of an end.
            let (l, b) = (scene.plate.length(), scene.plate.width());
            let points = [(l / 4.0, b / 2.0), (l / 2.0, b / 2.0), (l / 2.0, 0.0), (0.0, b / 2.0)];
            cmp.nest("dynamic", impact::dynreport::report(&scene, &points)?);
            all.nest(&slug(&scene.name), cmp);
            write(&out, &all)
        }
        Command::FemBench { common, tolerance, nx, nz } => {
            let scene = load(&common)?;
            if !(tolerance > 0.0 && tolerance < 1.0) {
                return Err(format!("--tolerance {tolerance} is outside the allowed range (0, 1)").into());
            }
            if nx < 2 || nz < 2 {
                return Err(format!("--nx {nx} and --nz {nz} must each be at least 2").into());
            }
            let r = impact::fem::bench(&scene, tolerance, nx, nz)?;
            if common.json {
                println!("{}", serde_json::to_string_pretty(&r)?);
            } else {
                for t in impact::fem::bench_tables(&r) {
                    println!();
                    print!("{}", t.to_text());
                }
            }
            Ok(())
        }
        Command::Field { scene, condition, x_mm, z_mm, elements, out } => {
            let scene = load(&Common { scene, json: false, out: None })?;
            let cond = scene.conditions.iter().find(|c| c.name == condition).ok_or_else(|| {
                let names: Vec<&str> = scene.conditions.iter().map(|c| c.name.as_str()).collect();
                format!("--condition '{condition}' is not in the scene; it has {names:?}")
            })?;
            if !(2..=2000).contains(&elements) {
                return Err(format!("--elements {elements} is outside the allowed range [2, 2000]").into());
            }
            let f = impact::field::field(&scene, cond, x_mm * 1e-3, z_mm * 1e-3, elements)?;
            let mut a = Artifacts::new();
            let name = out.file_name().ok_or("--out must name a file")?.to_owned();
            a.add(PathBuf::from(&name), serde_json::to_string(&f)?);
            let dir = out.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
            write(dir, &a)
        }
        Command::DefaultScene => {
            print!("{DEFAULT_SCENE}");
            Ok(())
        }
    }
}

fn write(dir: &Path, artifacts: &Artifacts) -> Result<(), Failure> {
    let written = artifacts.write_all(dir).map_err(|e| format!("writing into {}: {e}", dir.display()))?;
    eprintln!("wrote {} files under {}", written.len(), dir.display());
    Ok(())
}

fn emit(c: &Common, scene: &Scene, results: Results) -> Result<(), Failure> {
    let tables: Vec<Table> = response_tables(&results).into_iter().chain(yield_tables(&results)).collect();
    let json = serde_json::to_string_pretty(&results)?;
    if let Some(dir) = &c.out {
        let mut a = Artifacts::new();
        for t in &tables {
            let kind = if t.title.contains("yield") { "yield" } else { "responses" };
            let cond = t.title.split(" (").next().unwrap_or("condition");
            a.add(format!("{}-{}-{}.csv", slug(&scene.name), kind, slug(cond)), t.to_csv());
        }
        a.add(format!("{}.json", slug(&scene.name)), json.clone());
        write(dir, &a)?;
    }
    if c.json {
        println!("{json}");
    } else {
        println!("scene: {} ({})", scene.name, scene.description);
        for t in &tables {
            println!();
            print!("{}", t.to_text());
        }
    }
    Ok(())
}
