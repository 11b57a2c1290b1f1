//! The scene format as Markdown (`impact reference scenes`, committed as `docs/scenes.md`):
//! every table and key with its unit, allowed values, default and meaning, then the embedded
//! default scene. Ranges and defaults are the parser's own constants and the allowed words
//! the serde names of its types, so the reference says what the parser does; the tests check
//! that every key of every table is described and nothing else.

use super::ensemble::{CANDIDATES_PER_SIDE, FALL_HEIGHT_M, FAMILY_COUNT, LAWS, MAX_IMPACTS};
use super::{
    default_analyses, default_max_iterations, default_method, default_set_name, default_tolerance, limits, CornerKind,
    MethodName, Preset, RawEdge, DEFAULT_SCENE, MAX_NAME_CHARS, MAX_POINTS, MAX_SCENE_BYTES,
};
use analytic::params::{compact, Range, FRICTION_ANGLE_DEG, POISSON_RATIO};
use coupled::reduced::{ReducedSettings, SignalSettings};
use coupled::scene::Analysis;
use identify::{Class, Variable};
use serde::Serialize;

mod measurement;
mod shell_mesh;
mod stream;
mod tail_beam;

/// One key of a table.
struct Key {
    name: &'static str,
    /// Its TOML type.
    kind: &'static str,
    unit: &'static str,
    allowed: String,
    /// The default, or "required" (or when it is required).
    default: String,
    meaning: String,
}

/// One TOML table (or array of tables) and its keys.
struct Section {
    /// The table as written in a scene (`[plate]`, `[[bodies]]`), or "Top level".
    title: &'static str,
    about: String,
    keys: Vec<Key>,
}

const REQUIRED: &str = "required";
const NUMBER: &str = "number";
const STRING: &str = "string";
const TABLE: &str = "table";
const NO_UNIT: &str = "-";
/// The values of a random variable of `[ensemble]`.
const RANDOM: &str = "number or law table";

fn key(
    name: &'static str,
    kind: &'static str,
    unit: &'static str,
    allowed: impl Into<String>,
    default: impl Into<String>,
    meaning: impl Into<String>,
) -> Key {
    Key { name, kind, unit, allowed: allowed.into(), default: default.into(), meaning: meaning.into() }
}

/// A number in `allowed`, in the file's `unit`.
fn num(name: &'static str, unit: &'static str, allowed: Range, default: impl Into<String>, meaning: &str) -> Key {
    key(name, NUMBER, unit, allowed.to_string(), default, meaning)
}

/// A whole number in `allowed`.
fn whole(name: &'static str, allowed: Range, default: impl Into<String>, meaning: &str) -> Key {
    key(name, "whole number", NO_UNIT, allowed.to_string(), default, meaning)
}

/// A sub-table, described in its own section.
fn table(name: &'static str, kind: &'static str, section: &str, default: impl Into<String>, meaning: &str) -> Key {
    key(name, kind, NO_UNIT, format!("see `{section}`"), default, meaning)
}

/// A value as a scene file writes it (a unit variant by its serde name, a list of them), as
/// code.
fn word<T: Serialize>(value: T) -> String {
    format!("`{}`", toml::Value::try_from(value).expect("a TOML value"))
}

/// TOML strings, as a list to choose from.
fn words<'a>(names: impl IntoIterator<Item = &'a str>) -> String {
    names.into_iter().map(word).collect::<Vec<_>>().join(", ")
}

/// What a name may be; `of` names its siblings, from which it must differ.
fn name_rule(of: Option<&str>) -> String {
    let rule = format!("1 to {MAX_NAME_CHARS} characters with a letter or digit");
    match of {
        None => rule,
        Some(of) => format!("{rule}; differs from the other {of}' names in its letters or digits"),
    }
}

fn top_level() -> Section {
    let analyses: Vec<&str> = Analysis::ALL.iter().map(|a| a.key()).collect();
    let mut keys = vec![
        key(
            "name",
            STRING,
            NO_UNIT,
            name_rule(None),
            REQUIRED,
            "Names the scene in tables, reports and default output folders",
        ),
        key("description", STRING, NO_UNIT, "any", word(""), "One line on what the scene is"),
        num(
            "restitution",
            NO_UNIT,
            limits::RESTITUTION,
            REQUIRED,
            "Coefficient of restitution e of the Flores contact law (eq. 1)",
        ),
        key(
            "contact_law",
            STRING,
            NO_UNIT,
            words(coupled::transient::LawKind::ALL.iter().map(|l| l.key())),
            word(coupled::transient::LawKind::default().key()),
            "The transient and reduced models' contact law (the quasi-static models use the paper's Flores law)",
        ),
        num(
            "gravity_m_per_s2",
            "m/s²",
            limits::GRAVITY_M_PER_S2,
            "9.80665 with an [ensemble] of fall heights (a caving stream) or the \"drops\" analysis, else 0",
            "Gravity on the sphere toward the plate in the transient and reduced models: the free lump flies on a parabola and falls back (the paper's impact has none)",
        ),
        key(
            "analyses",
            "list of strings",
            NO_UNIT,
            words(analyses),
            word(default_analyses()),
            "What to compute: nothing else is assembled, simulated or written",
        ),
    ];
    keys.extend(tables());
    Section { title: "Top level", about: String::new(), keys }
}

/// The top level's tables, each described in its own section.
fn tables() -> Vec<Key> {
    vec![
        table("plate", TABLE, "[plate]", REQUIRED, "The plate"),
        table(
            "bodies",
            "array of tables",
            "[[bodies]]",
            "required (none if the analyses are only \"identify\" and \"drops\")",
            "The striking spheres",
        ),
        table("conditions", "array of tables", "[[conditions]]", "required, at least one", "The support sets"),
        table(
            "points",
            TABLE,
            "[points]",
            "required (none if the analyses are only \"identify\" and \"drops\")",
            "The impact points",
        ),
        table(
            "velocities",
            TABLE,
            "[velocities]",
            "required with \"responses\", \"transient\", \"size-map\", \"regime-maps\" or \"tail-beam\"",
            "The impact velocities",
        ),
        table("solver", TABLE, "[solver]", "its keys' defaults", "The energy-balance solver"),
        table("transient", TABLE, "[transient]", "the scene's points", "Where the transient study strikes"),
        table(
            "signals",
            TABLE,
            "[signals]",
            "its keys' defaults",
            "The reduced model's sensor signals (`impact signals`, \"identify\")",
        ),
        table(
            "plate_damping",
            TABLE,
            "[plate_damping]",
            "none: the transient plate undamped, the reduced model's modes at `[signals]`'s ratio",
            "The plate's Rayleigh damping, the same in the transient and the reduced model",
        ),
        table(
            "ensemble",
            TABLE,
            "[ensemble]",
            "required with \"identify\", refused without",
            "The random impacts of the identification study",
        ),
        table(
            "measurement",
            TABLE,
            "[measurement]",
            "none: the features read the model's exact samples (required with \"drops\")",
            "The measurement chain of the identification and of a drop rig (\"identify\" and \"drops\" only)",
        ),
        table(
            "stream",
            TABLE,
            "[stream]",
            "none: no stream study",
            "A caving-stream detection study on the ensemble (\"identify\" only; `impact stream`): on the plate's support sets, or on the tail beam where the scene has a [tail_beam]",
        ),
        table(
            "tail_beam",
            TABLE,
            "[tail_beam]",
            "required with \"tail-beam\", refused without",
            "A box-section tail beam struck by the scene's bodies (\"tail-beam\"); with \"identify\" too, the identification strikes it: the [ensemble] region and the [signals] sensors lie on its top plate, and `impact stream` records its jacks and accelerometers",
        ),
        table(
            "shell_mesh",
            TABLE,
            "[shell_mesh]",
            "required with \"shell-mesh\", refused without",
            "A shell structure read from a Gmsh mesh file, struck by the scene's bodies (\"shell-mesh\" only)",
        ),
    ]
}

fn plate_and_bodies() -> Vec<Section> {
    let plate = vec![
        num("length_mm", "mm", limits::PLATE_SIZE_MM, REQUIRED, "Length L, along x"),
        num("width_mm", "mm", limits::PLATE_SIZE_MM, REQUIRED, "Width B, along z"),
        num("thickness_mm", "mm", limits::THICKNESS_MM, REQUIRED, "Thickness h; at most the smaller side"),
        num("youngs_modulus_gpa", "GPa", limits::MODULUS_GPA, REQUIRED, "Young's modulus E"),
        num("poisson_ratio", NO_UNIT, POISSON_RATIO, REQUIRED, "Poisson's ratio μ"),
        num("density_kg_m3", "kg/m³", limits::DENSITY_KG_M3, REQUIRED, "Density ρ"),
    ];
    let bodies = vec![
        key("name", STRING, NO_UNIT, name_rule(Some("bodies")), REQUIRED, "Names the body in tables and files"),
        num("density_kg_m3", "kg/m³", limits::DENSITY_KG_M3, REQUIRED, "Density ρ₁"),
        num("youngs_modulus_gpa", "GPa", limits::MODULUS_GPA, REQUIRED, "Young's modulus E₁"),
        num("poisson_ratio", NO_UNIT, POISSON_RATIO, REQUIRED, "Poisson's ratio μ₁"),
        num("cohesion_mpa", "MPa", limits::COHESION_MPA, REQUIRED, "Drucker-Prager cohesion of the rock (eq. 51)"),
        num("friction_angle_deg", "deg", FRICTION_ANGLE_DEG, REQUIRED, "Internal friction angle φ (eq. 51)"),
        num("radius_mm", "mm", limits::RADIUS_MM, REQUIRED, "Sphere radius R"),
    ];
    vec![
        Section {
            title: "[plate]",
            about: format!(
                "The plate, x along its length from the left end and z across its width from the near edge. Its longer side is at most {} times its shorter.",
                compact(limits::MAX_ASPECT_RATIO)
            ),
            keys: plate,
        },
        Section { title: "[[bodies]]", about: "One table per striking sphere.".into(), keys: bodies },
    ]
}

fn conditions() -> Vec<Section> {
    let presets: Vec<String> = Preset::ALL.iter().map(|&p| format!("{} ({})", word(p), p.default_name())).collect();
    let default_names: Vec<String> = Preset::ALL.iter().map(|p| word(p.default_name())).collect();
    let spring = limits::SPRING_N_PER_M;
    let set = vec![
        key("name", STRING, NO_UNIT, name_rule(Some("support sets")), format!("{} by `supports`; {} (N its position from 1) otherwise", default_names.join(", "), word(default_set_name("N"))), "Names the support set in tables and files"),
        key("supports", STRING, NO_UNIT, presets.join(", "), "none: give `corners` and `edges`", "The paper's support conditions: four fixed corners; four corner springs; fixed corners at x = 0 and springs at x = L"),
        num("spring_stiffness_n_per_m", "N/m", spring, format!("required with {} and {}", word(Preset::BothSprings), word(Preset::FixedAndSprings)), "Stiffness k_T of each corner spring of a preset"),
        table("corners", TABLE, "[conditions.corners]", "every corner free", "General supports: each corner (not with `supports`)"),
        table("edges", TABLE, "[conditions.edges]", "every edge free", "General supports: each edge (not with `supports`)"),
    ];
    let corner_kinds = [CornerKind::Fixed, CornerKind::Free].map(word).join(", ");
    let corner = |name, at| {
        key(
            name,
            "string or table",
            "N/m",
            format!("{corner_kinds} or `{{ spring_n_per_m = k }}`, k in {spring}"),
            word(CornerKind::Free),
            format!("The corner at {at}"),
        )
    };
    let edge_kinds = [RawEdge::Free, RawEdge::SimplySupported, RawEdge::Clamped].map(word).join(", ");
    let edge = |name, at| key(name, STRING, NO_UNIT, edge_kinds.clone(), word(RawEdge::Free), format!("The edge {at}"));
    vec![
        Section {
            title: "[[conditions]]",
            about: "One table per support set: a preset (`supports`) or general supports (`corners` and `edges`), not both. General supports must hold the plate against every rigid-body motion.".into(),
            keys: set,
        },
        Section {
            title: "[conditions.corners]",
            about: "Each corner fixed, free or on a spring.".into(),
            keys: vec![
                corner("left_near", "(x, z) = (0, 0)"),
                corner("right_near", "(L, 0)"),
                corner("left_far", "(0, B)"),
                corner("right_far", "(L, B)"),
            ],
        },
        Section {
            title: "[conditions.edges]",
            about: "Each edge free, simply supported or clamped.".into(),
            keys: vec![edge("left", "x = 0"), edge("right", "x = L"), edge("near", "z = 0"), edge("far", "z = B")],
        },
    ]
}

fn points() -> Vec<Section> {
    let count = limits::POINT_COUNT;
    let points = vec![
        key("x_mm", "list of numbers", "mm", "each in [0, L]", "-", "Positions on the centreline z = B/2"),
        whole("count", count, "-", "Points evenly spaced on the centreline from x = 0 to L"),
        key("pairs_mm", "list of [x, z]", "mm", "x in [0, L], z in [0, B]", "-", "Explicit points, in the order given"),
        table("grid", TABLE, "[points.grid]", "-", "Every x with every z"),
        key(
            "z_mm",
            "-",
            "-",
            "refused",
            "-",
            "Not a key: beside `x_mm` it would silently form a grid; write `pairs_mm` or `[points.grid]`",
        ),
    ];
    let grid = vec![
        key("x_mm", "list of numbers", "mm", "each in [0, L]", "-", "Positions along the length"),
        whole("x_count", count, "-", "Positions evenly spaced from x = 0 to L"),
        key("z_mm", "list of numbers", "mm", "each in [0, B]", "-", "Positions across the width"),
        whole("z_count", count, "-", "Positions evenly spaced from z = 0 to B"),
    ];
    vec![
        Section {
            title: "[points]",
            about: format!(
                "Where the bodies strike: exactly one of `x_mm`, `count`, `pairs_mm` or `[points.grid]`; at most {MAX_POINTS} points, and support sets x points x bodies x velocities within the quasi-static budget of {:.0} s ({:.0} ms a support set, {:.2} ms a point on each, {:.2} ms a result row, estimated when the scene is read).",
                limits::QUASI_STATIC_BUDGET_S,
                limits::SECONDS_PER_SUPPORT_SET * 1e3,
                limits::SECONDS_PER_POINT * 1e3,
                limits::SECONDS_PER_ROW * 1e3
            ),
            keys: points,
        },
        Section {
            title: "[points.grid]",
            about: "One of `x_mm` or `x_count`, and one of `z_mm` or `z_count`.".into(),
            keys: grid,
        },
    ]
}

fn runs() -> Vec<Section> {
    let d = SignalSettings::default();
    let methods = [MethodName::Recursion, MethodName::Bracketed].map(word).join(", ");
    vec![
        Section {
            title: "[velocities]",
            about: String::new(),
            keys: vec![key("m_per_s", "list of numbers", "m/s", format!("each in {}", limits::VELOCITY_M_PER_S), REQUIRED, "Impact velocities")],
        },
        Section {
            title: "[solver]",
            about: "The energy balance of the quasi-static models (eq. 14).".into(),
            keys: vec![
                key("method", STRING, NO_UNIT, methods, word(default_method()), "The paper's recursion (eqs. 15-19), or Newton's method from a bracket safeguarded by bisection"),
                num("tolerance", NO_UNIT, limits::SOLVER_TOLERANCE, compact(default_tolerance()), "Largest accepted relative residual of the energy balance"),
                whole("max_iterations", limits::SOLVER_ITERATIONS, default_max_iterations().to_string(), "Largest number of iterations"),
            ],
        },
        Section {
            title: "[transient]",
            about: "The transient study's points (each a time integration), if not the scene's.".into(),
            keys: vec![key("pairs_mm", "list of [x, z]", "mm", "x in [0, L], z in [0, B]", REQUIRED, "Where the transient study strikes")],
        },
        Section {
            title: "[signals]",
            about: format!(
                "The reduced model's sensor signals. A window holds {} to {} samples a channel (window_ms x rate_hz / 1000), and one impact's signals at most {} MB (8 bytes a sample, 3 channels a sensor and up to 4 corners).",
                compact(limits::MIN_SAMPLES),
                compact(limits::MAX_SAMPLES),
                compact((limits::MAX_IMPACT_SIGNAL_BYTES / 1e6).round())
            ),
            keys: vec![
                num("window_ms", "ms", limits::SIGNAL_WINDOW_MS, compact(d.window * 1e3), "Length of each signal from first touch"),
                num("rate_hz", "Hz", limits::SAMPLE_RATE_HZ, compact(d.rate_hz), "Sampling rate"),
                num("damping_ratio", NO_UNIT, ReducedSettings::DAMPING_RATIO, compact(d.damping_ratio), "Modal damping ratio ζ of every mode (not with [plate_damping], which replaces it)"),
                key("modes", "whole number or `\"chain\"`", NO_UNIT, format!("{} and the plate's most, or `\"chain\"` (needs `[measurement]`)", limits::MODES), d.modes.to_string(), "Modes the reduced model keeps: at most an eighth of the degrees of freedom of its mesh of the plate (178 on a 458.4 x 360 mm plate, 220 on a square one); by default 80, or that many where fewer. `\"chain\"`: on each support set the fewest whose highest the measurement chain's gain above stays within `measurement.band_tolerance`, the plate's most if none does. On a tail beam (where the identification strikes it): a number, at most what its mesh allows (200, half its DOFs with mass, a 2 GiB Krylov basis), refused above that when the mesh is built"),
                key("sensors_mm", "list of [x, z]", "mm", format!("x in [0, L], z in [0, B]; at most {}, at least 0.1 mm apart (channels are named by position to 0.1 mm)", limits::MAX_SENSORS), "none: the corner channels only", "Sensor points on the plate; on a tail beam's top plate (x along it from the pins, z across) where the identification strikes the tail beam, each an accelerometer at its nearest node"),
                key("truncation_check_fraction", "number", NO_UNIT, format!("{}", limits::TRUNCATION_CHECK), "1: every impact", "The share of each family's impacts that \"identify\" strikes again on N/2 modes to say what each AUC owes to the modal truncation: a stratified random subsample (at least two impacts a family, all of a smaller one), its change of every AUC given with DeLong's paired error times the finite population correction. Below 1 the check costs that share of the main run; at 1 the report also shows how well subsamples of a tenth, a quarter and a half would have stood for it"),
                key("arithmetic", "string", NO_UNIT, "\"exact\", \"fast\"", "\"exact\"", "How each window's free part is summed into its channels. \"exact\": f64, each product then each sum in a fixed order, the same bits on every processor. \"fast\": the modes still propagated in f64 (with fused multiply-adds), each channel's sum over the modes in f32 with fused multiply-adds, within γ(n+2)·Σ|cᵢsᵢ| of the exact sum (u = 2⁻²⁴, Higham's bound; n terms); the contact steps and the features stay f64. The difference it makes on the shipped scenes is measured in docs/performance.md"),
            ],
        },
        Section {
            title: "[plate_damping]",
            about: "Rayleigh damping C = αM + βK of the plate, given as the ratio ζ it has at two frequencies (α = 2ζω_aω_b/(ω_a + ω_b), β = 2ζ/(ω_a + ω_b)); a mode of frequency f then has ζ(f) = α/(4πf) + πβf, below ζ between the two and above it outside. The transient model damps its FE plate with C, the reduced model each mode with ζ(f), so both answer the same question.".into(),
            keys: vec![
                num("ratio", NO_UNIT, limits::PLATE_DAMPING_RATIO, REQUIRED, "Damping ratio ζ at both frequencies"),
                key("frequencies_hz", "[f_a, f_b]", "Hz", format!("each in {}, f_a ≤ f_b", limits::DAMPING_FREQUENCY_HZ), REQUIRED, "The two frequencies with ratio ζ (e.g. the fundamental and the highest mode that matters)"),
            ],
        },
    ]
}

/// The keys of `[ensemble]` itself.
fn ensemble_keys() -> Vec<Key> {
    let variables: Vec<&str> = Variable::ALL.iter().map(|v| v.key()).collect();
    vec![
        key(
            "seed",
            "integer",
            NO_UNIT,
            format!("[0, {}]", u64::MAX),
            REQUIRED,
            "Seed of every impact's random stream: the same seed, the same impacts on any number of threads",
        ),
        key(
            "hold",
            "list of strings",
            NO_UNIT,
            words(variables.iter().copied()),
            word(&variables),
            "The variables held at their medians, one at a time, to find which variability hides the difference",
        ),
        table("region", TABLE, "[ensemble.region]", "the whole plate", "Where the impacts land, uniformly (on a tail beam's top plate, where the identification strikes the tail beam: each lump at the nearest node of its mesh)"),
        key(
            "fall_height_m",
            RANDOM,
            "m",
            FALL_HEIGHT_M.to_string(),
            "-",
            "Free fall from rest, v = √(2gh); give this or `velocity_m_per_s`",
        ),
        key(
            "velocity_m_per_s",
            RANDOM,
            "m/s",
            limits::VELOCITY_M_PER_S.to_string(),
            "-",
            "The impact velocity; give this or `fall_height_m`",
        ),
        table(
            "placement",
            TABLE,
            "[ensemble.placement]",
            "no placement maps",
            "The candidate sensor grid of the placement maps",
        ),
        table(
            "families",
            "array of tables",
            "[[ensemble.families]]",
            "required, at least one of each class",
            "The material families of the stream",
        ),
    ]
}

fn ensemble() -> Vec<Section> {
    let ensemble = ensemble_keys();
    let laws: Vec<String> = LAWS.iter().map(|(law, keys)| format!("{} ({})", word(law), keys.join(", "))).collect();
    vec![
        Section {
            title: "[ensemble]",
            about: format!(
                "The random impacts of the identification study. A random variable is a number (fixed) or a table naming its law: `{{ distribution = ..., ... }}`, one of {}. The bounds of every continuous law are required and lie in the variable's allowed range, so nothing drawn can leave it.",
                laws.join(", ")
            ),
            keys: ensemble,
        },
        Section {
            title: "[ensemble.region]",
            about: String::new(),
            keys: vec![
                key("x_mm", "[low, high]", "mm", "in [0, L], low ≤ high", REQUIRED, "The region along the length"),
                key("z_mm", "[low, high]", "mm", "in [0, B], low ≤ high", REQUIRED, "The region across the width"),
            ],
        },
        Section {
            title: "[ensemble.placement]",
            about: String::new(),
            keys: vec![
                whole("x_count", CANDIDATES_PER_SIDE, REQUIRED, "Candidate sensor points along the length, edge to edge"),
                whole("z_count", CANDIDATES_PER_SIDE, REQUIRED, "Candidate sensor points across the width, edge to edge"),
                whole(
                    "design_sensors",
                    crate::ensemble::DESIGN_SENSORS,
                    "none",
                    "Sensors of the quantity with the best placement map chosen one at a time among the candidates (greedy, by cross-validated AUC), each with its gain",
                ),
                key(
                    "design_backgrounds",
                    "list of numbers",
                    NO_UNIT,
                    "[0, 1e6], at most 8 levels; needs `design_sensors` and a `[measurement]` that states a background",
                    "none",
                    "Scales of the chain's background at which the design is chosen again on the whole candidate grid (besides the background as stated): where to put the sensors at another noise level",
                ),
            ],
        },
    ]
}

fn families() -> Section {
    let classes = words([Class::Coal, Class::Gangue].map(|c| c.key()));
    let random =
        |name, unit, allowed: Range, meaning: &str| key(name, RANDOM, unit, allowed.to_string(), REQUIRED, meaning);
    let families = vec![
        key("name", STRING, NO_UNIT, name_rule(Some("families")), REQUIRED, "Names the family in tables"),
        key("class", STRING, NO_UNIT, classes, REQUIRED, "What identification should call its impacts"),
        whole(
            "count",
            FAMILY_COUNT,
            REQUIRED,
            &format!("Impacts of this family (all families together at most {MAX_IMPACTS})"),
        ),
        random("density_kg_m3", "kg/m³", limits::DENSITY_KG_M3, "Density ρ₁"),
        random("youngs_modulus_gpa", "GPa", limits::MODULUS_GPA, "Young's modulus E₁"),
        random("poisson_ratio", NO_UNIT, POISSON_RATIO, "Poisson's ratio μ₁"),
        random("cohesion_mpa", "MPa", limits::COHESION_MPA, "Drucker-Prager cohesion (eq. 51)"),
        random("friction_angle_deg", "deg", FRICTION_ANGLE_DEG, "Internal friction angle φ (eq. 51)"),
        random("radius_mm", "mm", limits::RADIUS_MM, "Sphere radius R"),
    ];
    Section { title: "[[ensemble.families]]", about: "One table per material family.".into(), keys: families }
}

fn sections() -> Vec<Section> {
    let mut all = vec![top_level()];
    for part in [plate_and_bodies(), conditions(), points(), runs(), ensemble()] {
        all.extend(part);
    }
    all.push(families());
    all.extend(measurement::sections());
    all.extend(stream::sections());
    all.extend(tail_beam::sections());
    all.extend(shell_mesh::sections());
    all
}

/// A table cell: one line, no column break.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace('\n', " ")
}

/// The scene format as Markdown: every table and key, then the embedded default scene.
pub fn markdown() -> String {
    let mut md = String::from("# Scene files\n\n");
    md.push_str("<!-- Generated by `impact reference scenes` from crates/scene/src/reference.rs: do not edit. -->\n\n");
    md.push_str(&format!(
        "A scene is a TOML file of at most {MAX_SCENE_BYTES} bytes: what to compute, with the unit in each key's name. Every value is checked in the file's units against the range below, and an error names the key, the value as written and its range. `[a, b]` includes its ends, `(a, b)` excludes them; L and B are the plate's `length_mm` and `width_mm`. Unknown keys are refused. `impact default-scene` prints the example at the end, a template for your own.\n"
    ));
    for s in sections() {
        let title = if s.title.starts_with('[') { format!("`{}`", s.title) } else { s.title.to_string() };
        md.push_str(&format!("\n## {title}\n\n"));
        if !s.about.is_empty() {
            md.push_str(&format!("{}\n\n", s.about));
        }
        md.push_str("| Key | Type | Unit | Allowed | Default | Meaning |\n|---|---|---|---|---|---|\n");
        for k in &s.keys {
            md.push_str(&format!(
                "| `{}` | {} | {} | {} | {} | {} |\n",
                k.name,
                cell(k.kind),
                cell(k.unit),
                cell(&k.allowed),
                cell(&k.default),
                cell(&k.meaning)
            ));
        }
    }
    md.push_str("\n## Example: the default scene\n\nThe paper's Table 1, embedded in the program.\n\n```toml\n");
    md.push_str(DEFAULT_SCENE);
    if !DEFAULT_SCENE.ends_with('\n') {
        md.push('\n');
    }
    md.push_str("```\n");
    md
}

#[cfg(test)]
mod tests;
