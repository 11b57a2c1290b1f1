//! Scene files: what to compute, in TOML with units in the key names, validated once into
//! a [`Scene`] in SI units. Every error names the TOML field and its allowed range.

use analytic::params::{check, Range, FRICTION_ANGLE_DEG, POISSON_RATIO, POSITIVE, RESTITUTION};
use analytic::{Condition, Elastic, InvalidParameter, Method, Plate, RockStrength, Sphere};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The embedded default scene: the paper's Table 1.
pub const DEFAULT_SCENE: &str = include_str!("../scenes/paper-table-1.toml");
/// How the default scene is named in messages.
pub const DEFAULT_ORIGIN: &str = "<default scene: paper Table 1>";

/// An invalid scene, with where it came from.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("cannot read scene file {path}: {source}")]
    Read { path: String, source: std::io::Error },
    #[error("scene {origin}: {message}")]
    Syntax { origin: String, message: String },
    #[error("scene {origin}: {source}")]
    OutOfRange { origin: String, source: InvalidParameter },
    #[error("scene {origin}: {field}: {message}")]
    Inconsistent { origin: String, field: String, message: String },
}

// ---------------------------------------------------------------- raw file layout

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    name: String,
    #[serde(default)]
    description: String,
    restitution: f64,
    plate: RawPlate,
    bodies: Vec<RawBody>,
    conditions: Vec<RawCondition>,
    points: RawPoints,
    #[serde(default)]
    velocities: Option<RawVelocities>,
    #[serde(default = "all_analyses")]
    analyses: Vec<Analysis>,
    #[serde(default)]
    solver: RawSolver,
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

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
enum Supports {
    /// Con 1.
    BothFixed,
    /// Con 2.
    BothSprings,
    /// Con 3.
    FixedAndSprings,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCondition {
    name: Option<String>,
    supports: Supports,
    spring_stiffness_n_per_m: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPoints {
    x_mm: Option<Vec<f64>>,
    count: Option<usize>,
    z_mm: Option<Vec<f64>>,
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

#[derive(Debug, Clone, Copy, Deserialize)]
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
fn all_analyses() -> Vec<Analysis> {
    vec![Analysis::Responses, Analysis::YieldVelocity]
}

// ---------------------------------------------------------------- validated scene

/// What a scene asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Analysis {
    /// Responses at maximum compression for every velocity.
    Responses,
    /// Yield velocities (eqs. 52-54).
    YieldVelocity,
}

/// A support condition with the name the scene gave it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NamedCondition {
    pub name: String,
    pub condition: Condition,
}

/// Impact points: positions x along the length and z across the width, all pairs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Points {
    /// m from the left end, each in [0, L].
    pub x: Vec<f64>,
    /// m from the near edge, each in [0, B]; the beam model ignores z.
    pub z: Vec<f64>,
}

/// A validated scene in SI units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Scene {
    pub name: String,
    pub description: String,
    pub plate: Plate,
    pub bodies: Vec<Sphere>,
    pub restitution: f64,
    pub conditions: Vec<NamedCondition>,
    pub points: Points,
    /// m/s; empty only when no responses are asked for.
    pub velocities: Vec<f64>,
    pub analyses: Vec<Analysis>,
    pub solver: Method,
}

impl Scene {
    /// The embedded default scene (the paper's Table 1).
    pub fn default_scene() -> Self {
        Self::parse(DEFAULT_SCENE, DEFAULT_ORIGIN).expect("the embedded default scene is valid")
    }

    /// Reads and validates a scene file.
    pub fn load(path: &Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path)
            .map_err(|source| SceneError::Read { path: path.display().to_string(), source })?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Parses and validates scene text; `origin` names it in errors.
    pub fn parse(text: &str, origin: &str) -> Result<Self, SceneError> {
        let raw: RawScene = toml::from_str(text).map_err(|e| SceneError::Syntax {
            origin: origin.to_string(),
            message: e.to_string().trim_end().to_string(),
        })?;
        validate(raw).map_err(|e| match e {
            Invalid::Range(source) => SceneError::OutOfRange { origin: origin.to_string(), source },
            Invalid::Other { field, message } => {
                SceneError::Inconsistent { origin: origin.to_string(), field, message }
            }
        })
    }

    pub fn wants(&self, analysis: Analysis) -> bool {
        self.analyses.contains(&analysis)
    }

    /// A copy whose points are `count` evenly spaced positions on [0, L] (the paper divides
    /// L into 100 parts: 101 points).
    pub fn with_sweep(&self, count: usize) -> Result<Self, SceneError> {
        if count < 2 {
            return Err(SceneError::Inconsistent {
                origin: self.name.clone(),
                field: "count".into(),
                message: format!("{count} points cannot span the plate: the allowed range is [2, inf)"),
            });
        }
        let mut s = self.clone();
        s.points.x = even_points(self.plate.length(), count);
        Ok(s)
    }
}

/// `count` points from 0 to `length` inclusive; the ends are exact.
pub fn even_points(length: f64, count: usize) -> Vec<f64> {
    (0..count).map(|i| if i + 1 == count { length } else { length * i as f64 / (count - 1) as f64 }).collect()
}

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

/// Checks every field against its range, in the units of the file, then converts to SI.
fn validate(raw: RawScene) -> Result<Scene, Invalid> {
    let restitution = check("restitution", raw.restitution, RESTITUTION, "")?;

    let p = &raw.plate;
    let plate_material = Elastic::new(
        check("plate.youngs_modulus_gpa", p.youngs_modulus_gpa, POSITIVE, "GPa")? * GPA,
        check("plate.poisson_ratio", p.poisson_ratio, POISSON_RATIO, "")?,
    )?;
    let plate = Plate::new(
        check("plate.length_mm", p.length_mm, POSITIVE, "mm")? * MM,
        check("plate.width_mm", p.width_mm, POSITIVE, "mm")? * MM,
        check("plate.thickness_mm", p.thickness_mm, POSITIVE, "mm")? * MM,
        check("plate.density_kg_m3", p.density_kg_m3, POSITIVE, "kg/m^3")?,
        plate_material,
    )?;

    if raw.bodies.is_empty() {
        return Err(other("bodies", "at least one [[bodies]] entry is required"));
    }
    let mut bodies = Vec::with_capacity(raw.bodies.len());
    for (i, b) in raw.bodies.iter().enumerate() {
        let f = |k: &str| format!("bodies[{i}].{k}");
        let material = Elastic::new(
            check(&f("youngs_modulus_gpa"), b.youngs_modulus_gpa, POSITIVE, "GPa")? * GPA,
            check(&f("poisson_ratio"), b.poisson_ratio, POISSON_RATIO, "")?,
        )?;
        let strength = RockStrength::new(
            check(&f("cohesion_mpa"), b.cohesion_mpa, POSITIVE, "MPa")? * MPA,
            check(&f("friction_angle_deg"), b.friction_angle_deg, FRICTION_ANGLE_DEG, "deg")?,
        )?;
        let density = check(&f("density_kg_m3"), b.density_kg_m3, POSITIVE, "kg/m^3")?;
        let radius = check(&f("radius_mm"), b.radius_mm, POSITIVE, "mm")? * MM;
        if bodies.iter().any(|s: &Sphere| s.name == b.name) {
            return Err(other(f("name"), format!("'{}' names two bodies; names must be unique", b.name)));
        }
        bodies.push(Sphere::new(b.name.clone(), density, radius, material, strength)?);
    }

    if raw.conditions.is_empty() {
        return Err(other("conditions", "at least one [[conditions]] entry is required"));
    }
    let mut conditions: Vec<NamedCondition> = Vec::with_capacity(raw.conditions.len());
    for (i, c) in raw.conditions.iter().enumerate() {
        let key = format!("conditions[{i}].spring_stiffness_n_per_m");
        let k_t = |c: &RawCondition| match c.spring_stiffness_n_per_m {
            Some(k) => Ok(check(&key, k, POSITIVE, "N/m")?),
            None => Err(other(&key, "is required for supports with springs; the allowed range is (0, inf) N/m")),
        };
        let condition = match c.supports {
            Supports::BothFixed => {
                if c.spring_stiffness_n_per_m.is_some() {
                    return Err(other(&key, "does not apply to supports = \"both-fixed\" (Con 1 has no springs)"));
                }
                Condition::BothFixed
            }
            Supports::BothSprings => Condition::BothSprings { k_t: k_t(c)? },
            Supports::FixedAndSprings => Condition::FixedAndSprings { k_t: k_t(c)? },
        };
        let name = c.name.clone().unwrap_or_else(|| condition.label().to_string());
        if conditions.iter().any(|n| n.name == name) {
            return Err(other(
                format!("conditions[{i}].name"),
                format!("'{name}' names two conditions; names must be unique"),
            ));
        }
        conditions.push(NamedCondition { name, condition });
    }

    let length_mm = p.length_mm;
    let x = match (&raw.points.x_mm, raw.points.count) {
        (Some(_), Some(_)) => return Err(other("points", "give either x_mm or count, not both")),
        (None, None) => {
            return Err(other("points", "give x_mm (a list of positions) or count (evenly spaced on [0, L])"))
        }
        (None, Some(n)) if n < 2 => {
            return Err(other("points.count", format!("{n} is outside the allowed range [2, inf)")));
        }
        (None, Some(n)) => even_points(plate.length(), n),
        (Some(xs), None) => {
            if xs.is_empty() {
                return Err(other("points.x_mm", "the list is empty; give at least one position"));
            }
            let mut out = Vec::with_capacity(xs.len());
            for (j, &x) in xs.iter().enumerate() {
                out.push(check(&format!("points.x_mm[{j}]"), x, Range::closed(0.0, length_mm), "mm")? * MM);
            }
            out
        }
    };
    let z = match &raw.points.z_mm {
        None => vec![plate.width() / 2.0],
        Some(zs) if zs.is_empty() => return Err(other("points.z_mm", "the list is empty; omit it for the centreline")),
        Some(zs) => {
            let mut out = Vec::with_capacity(zs.len());
            for (j, &z) in zs.iter().enumerate() {
                out.push(check(&format!("points.z_mm[{j}]"), z, Range::closed(0.0, p.width_mm), "mm")? * MM);
            }
            out
        }
    };

    if raw.analyses.is_empty() {
        return Err(other("analyses", "the list is empty; allowed entries: \"responses\", \"yield-velocity\""));
    }
    let mut analyses = raw.analyses.clone();
    analyses.dedup();
    let velocities = match &raw.velocities {
        Some(v) => {
            if v.m_per_s.is_empty() {
                return Err(other("velocities.m_per_s", "the list is empty; give at least one velocity"));
            }
            let mut out = Vec::with_capacity(v.m_per_s.len());
            for (j, &vel) in v.m_per_s.iter().enumerate() {
                out.push(check(&format!("velocities.m_per_s[{j}]"), vel, POSITIVE, "m/s")?);
            }
            out
        }
        None if analyses.contains(&Analysis::Responses) => {
            return Err(other("velocities.m_per_s", "is required when analyses include \"responses\""));
        }
        None => vec![],
    };

    let tolerance = check("solver.tolerance", raw.solver.tolerance, Range::open(0.0, 1.0), "")?;
    if raw.solver.max_iterations == 0 {
        return Err(other("solver.max_iterations", "0 is outside the allowed range [1, 4294967295]"));
    }
    let solver = match raw.solver.method {
        MethodName::Recursion => Method::Recursion { tolerance, max_iterations: raw.solver.max_iterations },
        MethodName::Bracketed => Method::Bracketed { tolerance, max_iterations: raw.solver.max_iterations },
    };

    Ok(Scene {
        name: raw.name,
        description: raw.description,
        plate,
        bodies,
        restitution,
        conditions,
        points: Points { x, z },
        velocities,
        analyses,
        solver,
    })
}
