//! The command line's definition: every command, option and help text, and the terminal's
//! view of a result table (`--wide`, `--columns`).

use crate::written::Written;
use clap::{Args, Parser, Subcommand, ValueEnum};
use coupled::plan::ModelKind;
use coupled::transient::chatter::MAIN_CONTACT_SHARE;
use coupled::transient::{Discretisation, DEFAULT_TOLERANCE};
use impact::present::rows::{narrow, NARROW};
use impact::present::table::Table;
use impact::report::Failure;
use impact::scene::{limits, Scene};
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "impact",
    version,
    about = "Rock-sphere impact on supported steel plates: the paper's beam model and its checks"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Args, Clone)]
pub struct Common {
    /// Scene file (TOML); the embedded default is the paper's Table 1.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// Print JSON instead of tables.
    #[arg(long)]
    pub json: bool,
    /// Also write CSV and JSON files into DIR.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Which model answers: the paper's beam, the Kirchhoff plate finite elements
    /// (quasi-static), the transient plate, the Reissner-Mindlin plate finite elements
    /// (quasi-static, with transverse shear), or all four.
    #[arg(long, value_enum, default_value_t = ModelChoice::Beam)]
    pub model: ModelChoice,
    #[command(flatten)]
    pub transient: TransientArgs,
    /// Show every column on the terminal (the compliance and its error, δ_max, deflection,
    /// spring forces, energy shares, solver evidence, each validity criterion with its value
    /// and limit); the default shows the case, P_max or v_y with its error and one validity
    /// word. Files (--out, --json) always hold every column.
    #[arg(long, conflicts_with = "columns")]
    pub wide: bool,
    /// Show these columns on the terminal, comma-separated, by header or CSV key (e.g.
    /// `body,velocity_m_per_s,contact_force_N,deflection_m,validity`); `--wide` lists them all.
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    pub columns: Vec<String>,
}

impl Common {
    /// The terminal's view of `tables`: every column (`--wide`), the chosen ones (`--columns`,
    /// each in the tables that have it; one that no table has is an error), or the narrow
    /// default ([`NARROW`]).
    pub fn view(&self, tables: &[Table]) -> Result<Vec<Table>, Failure> {
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
pub struct TransientArgs {
    // The help states the range from its one definition, hence no doc comment.
    #[arg(long, default_value_t = Written::from(DEFAULT_TOLERANCE), value_name = "REL", help = format!(
        "Relative error allowed on the transient model's P_max (the force at maximum compression) and contact time: each case's mesh and time step are chosen so that its error estimate is within it (in {})",
        limits::TRANSIENT_TOLERANCE
    ))]
    pub tolerance: Written,
    #[arg(long, default_value_t = Written::from(MAIN_CONTACT_SHARE), value_name = "SHARE", help = format!(
        "Share of the sphere's momentum m·v₀ a contact's impulse must reach to count as one of the impact's main contacts; the others are micro-contacts (chatter), counted with their total impulse (in {})",
        limits::MAIN_CONTACT_SHARE
    ))]
    pub main_contact_share: Written,
}

impl TransientArgs {
    /// The scene with this discretisation and contact split, or an error naming the flag.
    pub fn apply(&self, mut scene: Scene) -> Result<Scene, Failure> {
        let tolerance = self.tolerance.within("--tolerance", limits::TRANSIENT_TOLERANCE, "")?;
        scene.transient_discretisation = Discretisation::tolerance(tolerance);
        scene.main_contact_share =
            self.main_contact_share.within("--main-contact-share", limits::MAIN_CONTACT_SHARE, "")?;
        Ok(scene)
    }
}

/// The `impact field --format` choice.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum FieldFormat {
    /// `impact-plate-field/1` JSON, per unit load (reference/README.md).
    Json,
    /// VTK XML UnstructuredGrid, with stresses and the near-load flag.
    Vtu,
    /// The transient model's plate through the whole impact and two fundamental periods of
    /// ringing after: a ParaView time series (`.pvd` with one `.vtu` per frame: deflection,
    /// moments, stresses; and the run's history.csv) into a directory.
    Pvd,
}

/// The `--model` choice.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ModelChoice {
    Beam,
    Plate,
    Transient,
    Mindlin,
    All,
}

impl ModelChoice {
    pub fn kinds(self) -> Vec<ModelKind> {
        match self {
            ModelChoice::Beam => vec![ModelKind::Beam],
            ModelChoice::Plate => vec![ModelKind::Plate],
            ModelChoice::Transient => vec![ModelKind::Transient],
            ModelChoice::Mindlin => vec![ModelKind::Mindlin],
            ModelChoice::All => ModelKind::ALL.to_vec(),
        }
    }
}

#[derive(Subcommand)]
pub enum Command {
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
    Compare(StudyArgs),
    /// Transient impact against the quasi-static models for a scene (default out:
    /// impact-out/<scene name>-dynamic).
    Dynamic(StudyArgs),
    /// Sensor signals of the scene's impacts by the reduced-order model (its `[signals]`
    /// table): every support set, body, transient point and velocity; the time series as CSV
    /// (default out: impact-out/<scene name>-signals), the first-contact numbers with their
    /// truncation errors on the terminal.
    Signals {
        /// Scene file; default: the paper's Table 1.
        #[arg(long, value_name = "FILE")]
        scene: Option<PathBuf>,
        /// Directory for the files, written whole or not at all (an existing one only if empty or
        /// an earlier output of impact); default
        /// impact-out/<scene name>-<command>.
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
        /// Directory for the files, written whole or not at all (an existing one only if empty or
        /// an earlier output of impact); default
        /// impact-out/<scene name>-<command>.
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
    /// Gangue detection on a continuous caving stream ([stream]): the scene's ensemble arriving
    /// as Poisson streams whose gangue share changes, simulated as one signal, recorded through
    /// [measurement], scored over sliding windows by a detector cross-validated by time blocks,
    /// into DIR (default impact-out/<scene name>-stream).
    Stream {
        /// Scene file with [ensemble] and [stream] tables and "identify" among its analyses.
        #[arg(long, value_name = "FILE")]
        scene: PathBuf,
        /// Directory for the files, written whole or not at all (an existing one only if empty or
        /// an earlier output of impact); default
        /// impact-out/<scene name>-<command>.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Print the results as JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// Apply a window detector (a detector.json written by impact stream) to a recording (a
    /// signal.json sidecar beside its CSV or Parquet file, docs/guide.md): every window's probability of
    /// gangue-rich into DIR/scores.csv, and, where the sidecar states onset_s, the delay,
    /// false alarms per hour and AUC into DIR/detect.json (default
    /// impact-out/<detector's scene name>-detect).
    Detect {
        /// The detector (JSON, format impact-detector/1).
        #[arg(long, value_name = "FILE")]
        detector: PathBuf,
        /// The recording's sidecar (JSON, format impact-signal/1); its data file (CSV, or
        /// Parquet where the name ends in .parquet) is read from the sidecar's folder.
        #[arg(long, value_name = "FILE")]
        signal: PathBuf,
        /// Directory for the files, written whole or not at all (an existing one only if empty or
        /// an earlier output of impact); default
        /// impact-out/<scene name>-<command>.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Print the results as JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// Compare recorded drop tests with the model: every drop a recording's sidecar lists
    /// (touch time, point, lump, height; docs/guide.md) thrown on the scene's reduced model of
    /// the same support set through its measurement chain, each channel's peak and spectral
    /// centroid, and P_max and t_c where measured, beside the prediction and its error bar,
    /// into DIR/drops.csv and DIR/drops.json (default impact-out/<scene name>-drops).
    Drops {
        /// Scene file with "drops" among its analyses: the plate, support sets, sensors and
        /// measurement chain of the rig.
        #[arg(long, value_name = "FILE")]
        scene: PathBuf,
        /// The recording's sidecar (JSON, format impact-signal/1, with "drops"); its data file
        /// (CSV or Parquet) is read from the sidecar's folder.
        #[arg(long, value_name = "FILE")]
        signal: PathBuf,
        /// Directory for the files, written whole or not at all (an existing one only if empty or
        /// an earlier output of impact); default
        /// impact-out/<scene name>-<command>.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Print the results as JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// Reproduce the paper's Tables 2-12 and Figures 8-19 into DIR.
    Paper {
        /// Directory for the files, written whole or not at all (an existing one only if empty or
        /// an earlier output of impact).
        #[arg(long, value_name = "DIR", default_value = "impact-out/paper")]
        out: PathBuf,
        /// Print a JSON summary of the run (provenance, findings, files written) to stdout.
        #[arg(long)]
        json: bool,
    },
    /// The main job on the default scene: every report into DIR, and the coal-gangue
    /// identification of the shipped scenes (scenes/caving-stream.toml,
    /// scenes/caving-stream-measured.toml, scenes/paper-velocities-ensemble.toml) into
    /// DIR/identify/<scene name>/.
    Report {
        /// Directory for the files, written whole or not at all (an existing one only if empty or
        /// an earlier output of impact).
        #[arg(long, value_name = "DIR", default_value = "reports")]
        out: PathBuf,
        /// Print a JSON summary of the run (provenance, findings, files written) to stdout.
        #[arg(long)]
        json: bool,
    },
    /// Time the plate FE compliance map (101 x 21 points, Con 1-3) on the mesh that
    /// reaches the tolerance at the centre.
    FemBench(FemBenchArgs),
    /// Write the plate FE deflection field under a point load: JSON for meshio (see
    /// reference/README.md) or a .vtu that ParaView opens directly.
    ///
    /// The .vtu has point data `displacement` (0, 0, w) for "Warp By Vector" and w, w_x, w_z;
    /// cell data the element-centre moments M_x, M_z, M_xz, the surface bending stresses
    /// sigma = 6M/h², and `near_load` = 1 on the elements touching the load point. There the
    /// Kirchhoff moment of a point load is singular and the values grow with refinement: read
    /// stress maxima from the other elements.
    Field(FieldArgs),
    /// Write a scene's tail beam ([tail_beam]) as a Gmsh mesh file, DIR/<scene name>.msh (MSH
    /// 4.1, millimetres; default DIR impact-out/<scene name>-mesh): its coarsest mesh with the
    /// walls ("top", "bottom", "webs", "ribs", "ends", "diaphragms"), the pins ("pins") and each jack's pad
    /// ("jack 1", ...) as named groups, to edit in Gmsh and read back through [shell_mesh].
    Mesh {
        /// Scene file with a [tail_beam] table.
        #[arg(long, value_name = "FILE")]
        scene: PathBuf,
        /// Directory for the file, written whole or not at all (an existing one only if empty or
        /// an earlier output of impact).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Print a JSON summary of the run (provenance, files written) to stdout.
        #[arg(long)]
        json: bool,
    },
    /// Print a shell completion script to standard output (e.g. `impact completions bash >
    /// ~/.local/share/bash-completion/completions/impact`).
    Completions {
        /// The shell the script is for.
        #[arg(value_enum)]
        shell: clap_complete::Shell,
    },
    /// Print the embedded default scene (a template for your own).
    DefaultScene,
    /// Print a generated reference: docs/cli.md or docs/scenes.md (a test keeps them equal).
    #[command(hide = true)]
    Reference {
        /// Which reference.
        #[arg(value_enum)]
        what: crate::cli_doc::Reference,
    },
}

// The options of `impact field` (no doc comment: the variant's is the help).
#[derive(Args)]
pub struct FieldArgs {
    /// Scene file; default: the paper's Table 1.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// Condition name from the scene.
    #[arg(long, default_value = "Con 1")]
    pub condition: String,
    /// Load position along the length, mm.
    #[arg(long, allow_negative_numbers = true)]
    pub x_mm: f64,
    /// Load position across the width, mm.
    #[arg(long, allow_negative_numbers = true)]
    pub z_mm: f64,
    #[arg(long, default_value_t = 40, help = format!("Elements along the longer side (in {})", limits::FIELD_ELEMENTS))]
    pub elements: usize,
    /// Output file (a regular file or a new one; `-` for standard output); default
    /// field.json or field.vtu by --format.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// File format.
    #[arg(long, value_enum, default_value_t = FieldFormat::Json)]
    pub format: FieldFormat,
    #[arg(long, value_name = "F", allow_negative_numbers = true, help = format!(
        "Load, N, that scales every value in the .vtu (fields are linear in it), in {} N (default 1 N); the JSON is always per unit load",
        limits::FORCE_N
    ))]
    pub force_n: Option<Written>,
    /// Scale the .vtu by the impact's maximum force instead: P_max of --body at
    /// --velocity-m-per-s at the load point by the quasi-static plate model (the paper's
    /// energy balance on the plate FE compliance, as `impact solve --model plate`). The
    /// terminal and the file say so, with P_max's error and the case's validity.
    #[arg(long, conflicts_with = "force_n")]
    pub force_of_impact: bool,
    /// --format pvd or --force-of-impact: the striking body (a name from the scene;
    /// default its first).
    #[arg(long)]
    pub body: Option<String>,
    /// --format pvd or --force-of-impact: impact velocity, m/s (default the scene's first).
    #[arg(long, value_name = "V", allow_negative_numbers = true)]
    pub velocity_m_per_s: Option<Written>,
    /// Print a JSON summary of what was written (provenance, every file with its size and
    /// SHA-256) to stdout; not with `--out -`, which prints the field itself.
    #[arg(long)]
    pub json: bool,
}

// The options of `impact fem-bench` (no doc comment: the variant's is the help).
#[derive(Args)]
pub struct FemBenchArgs {
    /// Scene file; default: the paper's Table 1.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// Print JSON instead of tables.
    #[arg(long)]
    pub json: bool,
    #[arg(long, default_value_t = Written::from(1e-4), help = format!(
        "Relative error allowed at the plate centre, from the mesh convergence study (in {})",
        limits::FEM_BENCH_TOLERANCE
    ))]
    pub tolerance: Written,
    #[arg(long, default_value_t = 101, help = format!("Impact points along the length (in {})", limits::FEM_BENCH_POINTS))]
    pub nx: usize,
    #[arg(long, default_value_t = 21, help = format!("Impact points across the width (in {})", limits::FEM_BENCH_POINTS))]
    pub nz: usize,
}

// The options of `impact compare` and `impact dynamic` (no doc comment: each variant's is its
// help).
#[derive(Args)]
pub struct StudyArgs {
    /// Scene file; default: the paper's Table 1.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// Directory for the files, written whole or not at all (an existing one only if empty or
    /// an earlier output of impact); default
    /// impact-out/<scene name>-<command>.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    #[command(flatten)]
    pub transient: TransientArgs,
    /// Print a JSON summary of the run (provenance, findings, files written) to stdout.
    #[arg(long)]
    pub json: bool,
}
