//! Scene files: what to compute, in TOML with units in the key names, validated once into
//! a [`Scene`] in SI units. Every error names the TOML field, the value as written and its
//! allowed range; ranges are checked in the file's units and chosen so that nothing
//! overflows or underflows after conversion to SI (a length of 1e300 mm is refused, not
//! turned into inf).

use analytic::params::{check, Range, FRICTION_ANGLE_DEG, POISSON_RATIO};
use analytic::{Elastic, InvalidParameter, Method, Plate, RockStrength, Sphere};
use coupled::reduced::SignalSettings;
pub use coupled::scene::{even_points, Analysis, Points, Scene};
use coupled::transient::LawKind;
pub use coupled::SupportSet;
use plate_fem::{CornerSupport, EdgeSupport, Supports};
use serde::{Deserialize, Serialize};
use std::path::Path;

mod ensemble;
pub mod limits;
pub mod reference;
pub use ensemble::{CANDIDATES_PER_SIDE, FALL_HEIGHT_M, FAMILY_COUNT, MAX_CANDIDATES_PER_SIDE, MAX_IMPACTS};

/// The embedded default scene: the paper's Table 1.
pub const DEFAULT_SCENE: &str = include_str!("../../../scenes/paper-table-1.toml");
/// How the default scene is named in messages.
pub const DEFAULT_ORIGIN: &str = "<default scene: paper Table 1>";
/// Largest scene file read, bytes: a scene is a few kilobytes; anything near this is not one.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;
/// Most impact points a scene may name (each costs one solve per mesh and one balance per
/// body, velocity and model; 1e5 points stay well inside this machine's memory).
pub const MAX_POINTS: usize = 100_000;

/// Longest name of a scene, body or support set, in characters: names title tables and
/// plots, and a name is not a description.
pub const MAX_NAME_CHARS: usize = 200;

/// Checks a display name: not empty, not too long, and distinct from the names before it
/// even after reduction to a file-name stem (reports name files after it: "A" and "a!"
/// would write the same file).
fn check_name(field: String, name: &str, earlier: &[&str]) -> Result<(), Invalid> {
    if name.trim().is_empty() {
        return Err(other(field, "is empty; give it a name"));
    }
    let n = name.chars().count();
    if n > MAX_NAME_CHARS {
        return Err(other(field, format!("is {n} characters long; the allowed range is [1, {MAX_NAME_CHARS}]")));
    }
    let stem = slug(name);
    if stem.is_empty() {
        return Err(other(field, format!("'{name}' has no letter or digit; file names are made from it")));
    }
    if let Some(e) = earlier.iter().find(|e| slug(e) == stem) {
        return Err(other(
            field,
            format!(
                "'{name}' and '{e}' give the same file name '{stem}'; names must differ in their letters or digits"
            ),
        ));
    }
    Ok(())
}

/// An invalid scene, with where it came from.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("cannot read scene file {path}: {source}")]
    Read { path: String, source: std::io::Error },
    /// The file is not one a scene can be (a device, a FIFO, a directory, too large).
    #[error("scene file {path}: {message}")]
    NotAFile { path: String, message: String },
    /// TOML syntax or layout.
    #[error("scene {origin}: {message}")]
    Syntax {
        origin: String,
        /// The parser's message with the offending line shown.
        message: String,
        /// The same without the line ("unknown field `colour`, expected one of ...").
        reason: String,
        /// Byte range of the offending key or value in the text, where the parser knows it.
        span: Option<std::ops::Range<usize>>,
    },
    /// A value outside its range.
    #[error("scene {origin}: {source}")]
    OutOfRange { origin: String, source: InvalidParameter },
    /// Values that do not fit together.
    #[error("scene {origin}: {field}: {message}")]
    Inconsistent { origin: String, field: String, message: String },
}

/// Reading a [`Scene`] from scene text or files.
pub trait SceneSource: Sized {
    /// The embedded default scene (the paper's Table 1).
    fn default_scene() -> Self;
    /// Reads and validates a scene file (a regular file of at most [`MAX_SCENE_BYTES`]).
    fn load(path: &Path) -> Result<Self, SceneError>;
    /// Parses and validates scene text; `origin` names it in errors.
    fn parse(text: &str, origin: &str) -> Result<Self, SceneError>;
}

impl SceneSource for Scene {
    fn default_scene() -> Self {
        // The embedded text is part of the program and is checked by a test; a failure
        // here is a build defect, not a user error.
        Self::parse(DEFAULT_SCENE, DEFAULT_ORIGIN).expect("the embedded default scene is valid")
    }

    fn load(path: &Path) -> Result<Self, SceneError> {
        let shown = path.display().to_string();
        let meta = std::fs::metadata(path).map_err(|source| SceneError::Read { path: shown.clone(), source })?;
        if !meta.is_file() {
            return Err(SceneError::NotAFile {
                path: shown,
                message: "is not a regular file (a directory, device or FIFO cannot hold a scene)".into(),
            });
        }
        if meta.len() > MAX_SCENE_BYTES {
            return Err(SceneError::NotAFile {
                path: shown,
                message: format!("is {} bytes; a scene file has at most {MAX_SCENE_BYTES} bytes", meta.len()),
            });
        }
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read { path: shown.clone(), source })?;
        Self::parse(&text, &shown)
    }

    fn parse(text: &str, origin: &str) -> Result<Self, SceneError> {
        let raw: RawScene = toml::from_str(text).map_err(|e| SceneError::Syntax {
            origin: origin.to_string(),
            message: e.to_string().trim_end().to_string(),
            reason: e.message().trim_end().to_string(),
            span: e.span(),
        })?;
        validate(raw).map_err(|e| match e {
            Invalid::Range(source) => SceneError::OutOfRange { origin: origin.to_string(), source },
            Invalid::Other { field, message } => {
                SceneError::Inconsistent { origin: origin.to_string(), field, message }
            }
        })
    }
}

// ---------------------------------------------------------------- raw file layout

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    name: String,
    #[serde(default)]
    description: String,
    restitution: f64,
    #[serde(default)]
    contact_law: Option<String>,
    plate: RawPlate,
    #[serde(default)]
    bodies: Vec<RawBody>,
    conditions: Vec<RawCondition>,
    #[serde(default)]
    points: Option<RawPoints>,
    #[serde(default)]
    velocities: Option<RawVelocities>,
    #[serde(default = "default_analyses")]
    analyses: Vec<Analysis>,
    #[serde(default)]
    solver: RawSolver,
    #[serde(default)]
    transient: Option<RawTransient>,
    #[serde(default)]
    ensemble: Option<ensemble::RawEnsemble>,
    #[serde(default)]
    signals: Option<RawSignals>,
}

/// The reduced model's sensor signals.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSignals {
    window_ms: Option<f64>,
    rate_hz: Option<f64>,
    damping_ratio: Option<f64>,
    modes: Option<f64>,
    sensors_mm: Option<Vec<(f64, f64)>>,
}

/// Where the transient study strikes, if not at the scene's points.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTransient {
    pairs_mm: Vec<(f64, f64)>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPlate {
    length_mm: f64,
    width_mm: f64,
    thickness_mm: f64,
    youngs_modulus_gpa: f64,
    poisson_ratio: f64,
    density_kg_m3: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBody {
    name: String,
    density_kg_m3: f64,
    youngs_modulus_gpa: f64,
    poisson_ratio: f64,
    cohesion_mpa: f64,
    friction_angle_deg: f64,
    radius_mm: f64,
}

/// The paper's support conditions as shorthands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
enum Preset {
    /// Con 1.
    BothFixed,
    /// Con 2.
    BothSprings,
    /// Con 3.
    FixedAndSprings,
}

impl Preset {
    /// Every preset, in the paper's order.
    const ALL: [Preset; 3] = [Preset::BothFixed, Preset::BothSprings, Preset::FixedAndSprings];

    /// The support set's name when the scene gives none: the paper's.
    fn default_name(self) -> &'static str {
        match self {
            Preset::BothFixed => "Con 1",
            Preset::BothSprings => "Con 2",
            Preset::FixedAndSprings => "Con 3",
        }
    }
}

/// The name of a support set that gives neither a name nor a preset, by its position from 1.
fn default_set_name(number: impl std::fmt::Display) -> String {
    format!("support set {number}")
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCondition {
    name: Option<String>,
    supports: Option<Preset>,
    spring_stiffness_n_per_m: Option<f64>,
    corners: Option<RawCorners>,
    edges: Option<RawEdges>,
}

#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
enum CornerKind {
    Fixed,
    Free,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(untagged)]
enum RawCorner {
    Kind(CornerKind),
    Spring { spring_n_per_m: f64 },
}

/// Corners by position: (x, z) = (0, 0), (L, 0), (0, B), (L, B).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCorners {
    left_near: Option<RawCorner>,
    right_near: Option<RawCorner>,
    left_far: Option<RawCorner>,
    right_far: Option<RawCorner>,
}

#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
enum RawEdge {
    Free,
    SimplySupported,
    Clamped,
}

/// Edges: left x = 0, right x = L, near z = 0, far z = B.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEdges {
    left: Option<RawEdge>,
    right: Option<RawEdge>,
    near: Option<RawEdge>,
    far: Option<RawEdge>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPoints {
    x_mm: Option<Vec<f64>>,
    count: Option<f64>,
    pairs_mm: Option<Vec<(f64, f64)>>,
    grid: Option<RawGrid>,
    z_mm: Option<Vec<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGrid {
    x_mm: Option<Vec<f64>>,
    x_count: Option<f64>,
    z_mm: Option<Vec<f64>>,
    z_count: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawVelocities {
    m_per_s: Vec<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSolver {
    #[serde(default = "default_method")]
    method: MethodName,
    #[serde(default = "default_tolerance")]
    tolerance: f64,
    #[serde(default = "default_max_iterations")]
    max_iterations: u32,
}

impl Default for RawSolver {
    fn default() -> Self {
        Self { method: default_method(), tolerance: default_tolerance(), max_iterations: default_max_iterations() }
    }
}

#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
enum MethodName {
    Recursion,
    Bracketed,
}

fn default_method() -> MethodName {
    MethodName::Bracketed
}
fn default_tolerance() -> f64 {
    1e-13
}
fn default_max_iterations() -> u32 {
    200
}
fn default_analyses() -> Vec<Analysis> {
    vec![Analysis::Responses, Analysis::YieldVelocity]
}

// ---------------------------------------------------------------- validation

enum Invalid {
    Range(InvalidParameter),
    Other { field: String, message: String },
}

impl From<InvalidParameter> for Invalid {
    fn from(e: InvalidParameter) -> Self {
        Self::Range(e)
    }
}

fn other(field: impl Into<String>, message: impl Into<String>) -> Invalid {
    Invalid::Other { field: field.into(), message: message.into() }
}

const MM: f64 = 1e-3;
const GPA: f64 = 1e9;
const MPA: f64 = 1e6;

/// A whole count written as a TOML number, in `allowed` (a range of whole ends).
fn count(field: &str, value: f64, allowed: Range) -> Result<usize, Invalid> {
    let v = check(field, value, allowed, "")?;
    if v.fract() != 0.0 {
        return Err(other(field, format!("{value} is not a whole number; the allowed range is {allowed}")));
    }
    Ok(v as usize)
}

fn positions(field: &str, list: &[f64], range_mm: Range) -> Result<Vec<f64>, Invalid> {
    if list.is_empty() {
        return Err(other(field, "the list is empty; give at least one position"));
    }
    if list.len() > MAX_POINTS {
        return Err(other(field, format!("{} positions; at most {MAX_POINTS} are allowed", list.len())));
    }
    list.iter().enumerate().map(|(j, &v)| Ok(check(&format!("{field}[{j}]"), v, range_mm, "mm")? * MM)).collect()
}

fn validate_points(raw: &RawPoints, plate: &Plate, l_mm: f64, b_mm: f64) -> Result<Points, Invalid> {
    let (l, b) = (plate.length(), plate.width());
    let along = Range::closed(0.0, l_mm);
    let across = Range::closed(0.0, b_mm);
    if raw.z_mm.is_some() {
        return Err(other(
            "points.z_mm",
            "z_mm beside x_mm would silently form a grid; write pairs_mm = [[x, z], ...] for explicit points, or a [points.grid] table with x_mm and z_mm for every combination",
        ));
    }
    let given = [raw.x_mm.is_some(), raw.count.is_some(), raw.pairs_mm.is_some(), raw.grid.is_some()];
    if given.iter().filter(|g| **g).count() != 1 {
        return Err(other(
            "points",
            "give exactly one of x_mm (positions on the centreline z = B/2), count (evenly spaced on the centreline), pairs_mm (explicit [x, z] pairs) or [points.grid]",
        ));
    }
    if let Some(xs) = &raw.x_mm {
        let xs = positions("points.x_mm", xs, along)?;
        return Ok(Points::Pairs { pairs: xs.into_iter().map(|x| (x, b / 2.0)).collect() });
    }
    if let Some(n) = raw.count {
        return Ok(Points::centreline(l, b, count("points.count", n, limits::POINT_COUNT)?));
    }
    if let Some(pairs) = &raw.pairs_mm {
        if pairs.is_empty() {
            return Err(other("points.pairs_mm", "the list is empty; give at least one [x, z] pair"));
        }
        if pairs.len() > MAX_POINTS {
            return Err(other("points.pairs_mm", format!("{} pairs; at most {MAX_POINTS} are allowed", pairs.len())));
        }
        let mut out = Vec::with_capacity(pairs.len());
        for (j, &(x, z)) in pairs.iter().enumerate() {
            let x = check(&format!("points.pairs_mm[{j}][0] (x)"), x, along, "mm")? * MM;
            let z = check(&format!("points.pairs_mm[{j}][1] (z)"), z, across, "mm")? * MM;
            out.push((x, z));
        }
        return Ok(Points::Pairs { pairs: out });
    }
    let g = raw.grid.as_ref().ok_or_else(|| other("points", "no points given"))?;
    let axis = |list: &Option<Vec<f64>>, n: Option<f64>, name: &str, range: Range, extent: f64| match (list, n) {
        (Some(v), None) => positions(&format!("points.grid.{name}_mm"), v, range),
        (None, Some(n)) => {
            Ok(even_points(extent, count(&format!("points.grid.{name}_count"), n, limits::POINT_COUNT)?))
        }
        _ => Err(other(format!("points.grid.{name}"), format!("give exactly one of {name}_mm or {name}_count"))),
    };
    let x = axis(&g.x_mm, g.x_count, "x", along, l)?;
    let z = axis(&g.z_mm, g.z_count, "z", across, b)?;
    if x.len().saturating_mul(z.len()) > MAX_POINTS {
        return Err(other(
            "points.grid",
            format!("{} x {} = {} points; at most {MAX_POINTS} are allowed", x.len(), z.len(), x.len() * z.len()),
        ));
    }
    Ok(Points::Grid { x, z })
}

fn validate_condition(i: usize, c: &RawCondition, plate: &Plate) -> Result<SupportSet, Invalid> {
    let key = format!("conditions[{i}].spring_stiffness_n_per_m");
    let spring = |c: &RawCondition| match c.spring_stiffness_n_per_m {
        Some(k) => Ok(check(&key, k, limits::SPRING_N_PER_M, "N/m")?),
        None => Err(other(
            &key,
            format!("is required for supports with springs; the allowed range is {} N/m", limits::SPRING_N_PER_M),
        )),
    };
    let supports = match (c.supports, c.corners.is_some() || c.edges.is_some()) {
        (Some(_), true) => {
            return Err(other(
                format!("conditions[{i}]"),
                "give either supports = \"both-fixed\" | \"both-springs\" | \"fixed-and-springs\" (the paper's Con 1-3) or [conditions.corners] / [conditions.edges], not both",
            ))
        }
        (None, false) => {
            return Err(other(
                format!("conditions[{i}]"),
                "give supports = \"both-fixed\" | \"both-springs\" | \"fixed-and-springs\", or [conditions.corners] and [conditions.edges]",
            ))
        }
        (Some(Preset::BothFixed), false) => {
            if c.spring_stiffness_n_per_m.is_some() {
                return Err(other(&key, "does not apply to supports = \"both-fixed\" (Con 1 has no springs)"));
            }
            Supports::con1()
        }
        (Some(Preset::BothSprings), false) => Supports::con2(spring(c)?),
        (Some(Preset::FixedAndSprings), false) => Supports::con3(spring(c)?),
        (None, true) => {
            if c.spring_stiffness_n_per_m.is_some() {
                return Err(other(&key, "applies only to the presets; give each spring its own spring_n_per_m in [conditions.corners]"));
            }
            let corners = c.corners.as_ref();
            let corner = |name: &str, v: Option<RawCorner>| -> Result<CornerSupport, Invalid> {
                Ok(match v {
                    None | Some(RawCorner::Kind(CornerKind::Free)) => CornerSupport::Free,
                    Some(RawCorner::Kind(CornerKind::Fixed)) => CornerSupport::Fixed,
                    Some(RawCorner::Spring { spring_n_per_m }) => CornerSupport::Spring(check(
                        &format!("conditions[{i}].corners.{name}.spring_n_per_m"),
                        spring_n_per_m,
                        limits::SPRING_N_PER_M,
                        "N/m",
                    )?),
                })
            };
            let edges = c.edges.as_ref();
            let edge = |v: Option<RawEdge>| match v {
                None | Some(RawEdge::Free) => EdgeSupport::Free,
                Some(RawEdge::SimplySupported) => EdgeSupport::Simple,
                Some(RawEdge::Clamped) => EdgeSupport::Clamped,
            };
            let s = Supports {
                corners: [
                    corner("left_near", corners.and_then(|c| c.left_near))?,
                    corner("right_near", corners.and_then(|c| c.right_near))?,
                    corner("left_far", corners.and_then(|c| c.left_far))?,
                    corner("right_far", corners.and_then(|c| c.right_far))?,
                ],
                edges: [
                    edge(edges.and_then(|e| e.left)),
                    edge(edges.and_then(|e| e.right)),
                    edge(edges.and_then(|e| e.near)),
                    edge(edges.and_then(|e| e.far)),
                ],
            };
            // A rigid-body motion left free makes every plate model singular: refuse it
            // here, before anything is assembled.
            s.validate(plate.length(), plate.width())
                .map_err(|e| other(format!("conditions[{i}]"), format!("{e}")))?;
            s
        }
    };
    let default_name = match c.supports {
        Some(p) => p.default_name().to_string(),
        None => default_set_name(i + 1),
    };
    Ok(SupportSet::new(c.name.clone().unwrap_or(default_name), supports))
}

/// Checks every field against its range, in the units of the file, then converts to SI.
fn validate(raw: RawScene) -> Result<Scene, Invalid> {
    let restitution = check("restitution", raw.restitution, limits::RESTITUTION, "")?;
    let contact_law = match raw.contact_law.as_deref() {
        None => LawKind::default(),
        Some(name) => LawKind::from_key(name).ok_or_else(|| {
            let keys: Vec<_> = LawKind::ALL.iter().map(|l| format!("\"{}\"", l.key())).collect();
            other("contact_law", format!("'{name}' is not a contact law; allowed: {}", keys.join(", ")))
        })?,
    };
    check_name("name".into(), &raw.name, &[])?;

    let p = &raw.plate;
    let plate_material = Elastic::new(
        check("plate.youngs_modulus_gpa", p.youngs_modulus_gpa, limits::MODULUS_GPA, "GPa")? * GPA,
        check("plate.poisson_ratio", p.poisson_ratio, POISSON_RATIO, "")?,
    )?;
    let length_mm = check("plate.length_mm", p.length_mm, limits::PLATE_SIZE_MM, "mm")?;
    let width_mm = check("plate.width_mm", p.width_mm, limits::PLATE_SIZE_MM, "mm")?;
    let thickness_mm = check("plate.thickness_mm", p.thickness_mm, limits::THICKNESS_MM, "mm")?;
    let aspect = length_mm.max(width_mm) / length_mm.min(width_mm);
    if aspect > limits::MAX_ASPECT_RATIO {
        return Err(other(
            "plate.length_mm and plate.width_mm",
            format!(
                "{length_mm} mm by {width_mm} mm is an aspect ratio of {}; the allowed range is [1, {}] (a narrower plate is a strip: model it as the beam it is)",
                analytic::params::compact(aspect),
                limits::MAX_ASPECT_RATIO
            ),
        ));
    }
    if thickness_mm > length_mm.min(width_mm) {
        return Err(other(
            "plate.thickness_mm",
            format!(
                "{thickness_mm} mm is more than the plate's smaller side {} mm: not a plate",
                length_mm.min(width_mm)
            ),
        ));
    }
    let plate = Plate::new(
        length_mm * MM,
        width_mm * MM,
        thickness_mm * MM,
        check("plate.density_kg_m3", p.density_kg_m3, limits::DENSITY_KG_M3, "kg/m^3")?,
        plate_material,
    )?;

    if raw.analyses.is_empty() {
        let keys: Vec<&str> = Analysis::ALL.iter().map(|a| a.key()).collect();
        return Err(other("analyses", format!("the list is empty; allowed entries: {}", keys.join(", "))));
    }
    let mut analyses: Vec<Analysis> = Vec::new();
    for a in raw.analyses {
        if !analyses.contains(&a) {
            analyses.push(a);
        }
    }
    // Every analysis but identification strikes the scene's bodies at its points; the
    // identification study draws its own from [ensemble].
    let needs_bodies = analyses.iter().any(|a| *a != Analysis::Identify);
    if raw.bodies.is_empty() && needs_bodies {
        return Err(other("bodies", "at least one [[bodies]] entry is required"));
    }
    let mut bodies = Vec::with_capacity(raw.bodies.len());
    for (i, b) in raw.bodies.iter().enumerate() {
        let f = |k: &str| format!("bodies[{i}].{k}");
        let material = Elastic::new(
            check(&f("youngs_modulus_gpa"), b.youngs_modulus_gpa, limits::MODULUS_GPA, "GPa")? * GPA,
            check(&f("poisson_ratio"), b.poisson_ratio, POISSON_RATIO, "")?,
        )?;
        let strength = RockStrength::new(
            check(&f("cohesion_mpa"), b.cohesion_mpa, limits::COHESION_MPA, "MPa")? * MPA,
            check(&f("friction_angle_deg"), b.friction_angle_deg, FRICTION_ANGLE_DEG, "deg")?,
        )?;
        let density = check(&f("density_kg_m3"), b.density_kg_m3, limits::DENSITY_KG_M3, "kg/m^3")?;
        let radius = check(&f("radius_mm"), b.radius_mm, limits::RADIUS_MM, "mm")? * MM;
        let earlier: Vec<&str> = bodies.iter().map(|s: &Sphere| s.name.as_str()).collect();
        check_name(f("name"), &b.name, &earlier)?;
        bodies.push(Sphere::new(b.name.clone(), density, radius, material, strength)?);
    }

    if raw.conditions.is_empty() {
        return Err(other("conditions", "at least one [[conditions]] entry is required"));
    }
    let mut conditions: Vec<SupportSet> = Vec::with_capacity(raw.conditions.len());
    for (i, c) in raw.conditions.iter().enumerate() {
        let set = validate_condition(i, c, &plate)?;
        let earlier: Vec<&str> = conditions.iter().map(|n| n.name.as_str()).collect();
        check_name(format!("conditions[{i}].name"), &set.name, &earlier)?;
        conditions.push(set);
    }

    let points = match &raw.points {
        Some(p) => validate_points(p, &plate, length_mm, width_mm)?,
        None if needs_bodies => {
            return Err(other("points", "a [points] table is required (x_mm, count, pairs_mm or [points.grid])"))
        }
        None => Points::Pairs { pairs: vec![] },
    };
    let transient_points = match &raw.transient {
        None => points.pairs(),
        Some(t) => match validate_points(
            &RawPoints { x_mm: None, count: None, pairs_mm: Some(t.pairs_mm.clone()), grid: None, z_mm: None },
            &plate,
            length_mm,
            width_mm,
        ) {
            Ok(p) => p.pairs(),
            Err(Invalid::Range(mut e)) => {
                e.name = e.name.replacen("points.", "transient.", 1);
                return Err(Invalid::Range(e));
            }
            Err(Invalid::Other { field, message }) => {
                return Err(Invalid::Other { field: field.replacen("points.", "transient.", 1), message })
            }
        },
    };

    let needs_velocity = analyses
        .iter()
        .any(|a| matches!(a, Analysis::Responses | Analysis::Transient | Analysis::SizeMap | Analysis::RegimeMaps));
    let velocities = match &raw.velocities {
        Some(v) => {
            if v.m_per_s.is_empty() {
                return Err(other("velocities.m_per_s", "the list is empty; give at least one velocity"));
            }
            let mut out = Vec::with_capacity(v.m_per_s.len());
            for (j, &vel) in v.m_per_s.iter().enumerate() {
                out.push(check(&format!("velocities.m_per_s[{j}]"), vel, limits::VELOCITY_M_PER_S, "m/s")?);
            }
            out
        }
        None if needs_velocity => {
            return Err(other(
                "velocities.m_per_s",
                "is required when analyses include \"responses\", \"transient\", \"size-map\" or \"regime-maps\"",
            ));
        }
        None => vec![],
    };

    let signals = validate_signals(raw.signals.as_ref(), length_mm, width_mm)?;

    let tolerance = check("solver.tolerance", raw.solver.tolerance, limits::SOLVER_TOLERANCE, "")?;
    if !limits::SOLVER_ITERATIONS.contains(f64::from(raw.solver.max_iterations)) {
        return Err(other(
            "solver.max_iterations",
            format!("{} is outside the allowed range {}", raw.solver.max_iterations, limits::SOLVER_ITERATIONS),
        ));
    }
    let solver = match raw.solver.method {
        MethodName::Recursion => Method::Recursion { tolerance, max_iterations: raw.solver.max_iterations },
        MethodName::Bracketed => Method::Bracketed { tolerance, max_iterations: raw.solver.max_iterations },
    };

    let ensemble = match (&raw.ensemble, analyses.contains(&Analysis::Identify)) {
        (Some(e), true) => Some(ensemble::validate_ensemble(e, length_mm, width_mm)?),
        (None, false) => None,
        (None, true) => {
            return Err(other("ensemble", "the \"identify\" analysis needs an [ensemble] table (the random impacts)"))
        }
        (Some(_), false) => {
            return Err(other(
                "ensemble",
                "is read only by the \"identify\" analysis; add \"identify\" to analyses or remove the table",
            ))
        }
    };

    Ok(Scene {
        name: raw.name,
        description: raw.description,
        plate,
        bodies,
        restitution,
        contact_law,
        conditions,
        points,
        transient_points,
        velocities,
        analyses,
        solver,
        ensemble,
        signals,
        transient_discretisation: coupled::transient::Discretisation::default(),
    })
}

/// `[signals]`: each key in its range (the file's units), converted to SI; absent keys take
/// the defaults of [`SignalSettings`].
fn validate_signals(raw: Option<&RawSignals>, l_mm: f64, b_mm: f64) -> Result<SignalSettings, Invalid> {
    let d = SignalSettings::default();
    let Some(raw) = raw else { return Ok(d) };
    let window_ms = match raw.window_ms {
        Some(w) => check("signals.window_ms", w, limits::SIGNAL_WINDOW_MS, "ms")?,
        None => d.window * 1e3,
    };
    let rate_hz = match raw.rate_hz {
        Some(r) => check("signals.rate_hz", r, limits::SAMPLE_RATE_HZ, "Hz")?,
        None => d.rate_hz,
    };
    let samples = window_ms * 1e-3 * rate_hz;
    if samples > limits::MAX_SAMPLES {
        return Err(other(
            "signals.window_ms and signals.rate_hz",
            format!(
                "{window_ms} ms at {rate_hz} Hz is {} samples per channel; at most {} are allowed",
                analytic::params::compact(samples.ceil()),
                analytic::params::compact(limits::MAX_SAMPLES)
            ),
        ));
    }
    let damping_ratio = match raw.damping_ratio {
        Some(z) => check("signals.damping_ratio", z, coupled::reduced::ReducedSettings::DAMPING_RATIO, "")?,
        None => d.damping_ratio,
    };
    let modes = match raw.modes {
        Some(n) => count("signals.modes", n, limits::MODES)?,
        None => d.modes,
    };
    let sensors = match &raw.sensors_mm {
        None => Vec::new(),
        Some(list) => {
            if list.len() > limits::MAX_SENSORS {
                return Err(other(
                    "signals.sensors_mm",
                    format!("{} sensors; at most {} are allowed", list.len(), limits::MAX_SENSORS),
                ));
            }
            let (along, across) = (Range::closed(0.0, l_mm), Range::closed(0.0, b_mm));
            let mut out = Vec::with_capacity(list.len());
            for (j, &(x, z)) in list.iter().enumerate() {
                let x = check(&format!("signals.sensors_mm[{j}][0] (x)"), x, along, "mm")? * MM;
                let z = check(&format!("signals.sensors_mm[{j}][1] (z)"), z, across, "mm")? * MM;
                out.push((x, z));
            }
            out
        }
    };
    Ok(SignalSettings { window: window_ms * 1e-3, rate_hz, damping_ratio, modes, sensors })
}

/// The file-name stem of a display name: lower-case ASCII letters and digits, every other run
/// of characters one `-`, no `-` at either end. Two names are distinct only if their stems are.
pub fn slug(name: &str) -> String {
    let mut s = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            s.push(c.to_ascii_lowercase());
        } else if !s.ends_with('-') {
            s.push('-');
        }
    }
    s.trim_matches('-').to_string()
}
