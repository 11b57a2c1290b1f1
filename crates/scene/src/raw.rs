//! The scene file's layout as TOML reads it: every table and key, in the file's units, before
//! validation. Unknown keys are refused (`deny_unknown_fields`), so a misspelt key is an
//! error, not a silently ignored line.

use coupled::scene::Analysis;
use serde::{Deserialize, Serialize};

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawScene {
    pub(crate) name: String,
    #[serde(default)]
    pub(crate) description: String,
    pub(crate) restitution: f64,
    #[serde(default)]
    pub(crate) contact_law: Option<String>,
    #[serde(default)]
    pub(crate) gravity_m_per_s2: Option<f64>,
    pub(crate) plate: RawPlate,
    #[serde(default)]
    pub(crate) bodies: Vec<RawBody>,
    pub(crate) conditions: Vec<RawCondition>,
    #[serde(default)]
    pub(crate) points: Option<RawPoints>,
    #[serde(default)]
    pub(crate) velocities: Option<RawVelocities>,
    #[serde(default = "default_analyses")]
    pub(crate) analyses: Vec<Analysis>,
    #[serde(default)]
    pub(crate) solver: RawSolver,
    #[serde(default)]
    pub(crate) transient: Option<RawTransient>,
    #[serde(default)]
    pub(crate) ensemble: Option<crate::ensemble::RawEnsemble>,
    #[serde(default)]
    pub(crate) signals: Option<RawSignals>,
    #[serde(default)]
    pub(crate) plate_damping: Option<RawPlateDamping>,
    #[serde(default)]
    pub(crate) measurement: Option<crate::validate::measurement::RawMeasurement>,
    #[serde(default)]
    pub(crate) stream: Option<crate::validate::stream::RawStream>,
    #[serde(default)]
    pub(crate) tail_beam: Option<RawTailBeam>,
    #[serde(default)]
    pub(crate) shell_mesh: Option<RawShellMesh>,
}

/// `[shell_mesh]`: a shell structure read from a Gmsh MSH file with named groups.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawShellMesh {
    pub(crate) file: String,
    #[serde(default = "one")]
    pub(crate) unit_mm: f64,
    pub(crate) thickness_mm: std::collections::BTreeMap<String, f64>,
    #[serde(default)]
    pub(crate) holds: Vec<RawHold>,
    #[serde(default)]
    pub(crate) springs: Vec<RawGroupSpring>,
    pub(crate) struck: String,
    pub(crate) points_mm: Vec<Vec<f64>>,
    #[serde(default = "default_mesh_levels")]
    pub(crate) levels: u32,
    /// The file's bytes, read before validation (relative to the scene's folder).
    #[serde(skip)]
    pub(crate) bytes: Option<Vec<u8>>,
}

fn one() -> f64 {
    1.0
}

pub(crate) fn default_mesh_levels() -> u32 {
    3
}

/// `[[shell_mesh.holds]]`: DOFs held at every node of a group.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawHold {
    pub(crate) group: String,
    pub(crate) dofs: Vec<String>,
}

/// `[[shell_mesh.springs]]`: a spring to ground shared by a group's nodes.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawGroupSpring {
    pub(crate) group: String,
    pub(crate) stiffness_n_per_m: f64,
    pub(crate) direction: Vec<f64>,
}

/// `[tail_beam]`: a box-section tail beam of flat shell walls.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawTailBeam {
    pub(crate) length_mm: f64,
    pub(crate) width_mm: f64,
    pub(crate) height_mm: f64,
    pub(crate) top_mm: f64,
    pub(crate) bottom_mm: f64,
    pub(crate) webs_mm: f64,
    pub(crate) ends_mm: f64,
    #[serde(default)]
    pub(crate) ribs_z_mm: Vec<f64>,
    #[serde(default)]
    pub(crate) rib_mm: Option<f64>,
    #[serde(default)]
    pub(crate) diaphragms_x_mm: Vec<f64>,
    #[serde(default)]
    pub(crate) diaphragm_mm: Option<f64>,
    pub(crate) pin_height_mm: f64,
    pub(crate) pins_z_mm: Vec<Vec<f64>>,
    pub(crate) element_mm: f64,
    pub(crate) points_mm: Vec<Vec<f64>>,
    pub(crate) jacks: Vec<RawJack>,
}

/// `[[tail_beam.jacks]]`: a jack on a pad of the bottom plate.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawJack {
    pub(crate) x_mm: f64,
    pub(crate) z_mm: f64,
    pub(crate) pad_mm: f64,
    pub(crate) stiffness_n_per_m: f64,
    pub(crate) angle_deg: f64,
}

/// The plate's Rayleigh damping: a ratio reached at two frequencies.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawPlateDamping {
    pub(crate) ratio: f64,
    pub(crate) frequencies_hz: Vec<f64>,
}

/// The reduced model's sensor signals.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSignals {
    pub(crate) window_ms: Option<f64>,
    pub(crate) rate_hz: Option<f64>,
    pub(crate) damping_ratio: Option<f64>,
    pub(crate) modes: Option<RawModes>,
    pub(crate) sensors_mm: Option<Vec<Vec<f64>>>,
    pub(crate) truncation_check_fraction: Option<f64>,
    pub(crate) arithmetic: Option<String>,
}

/// `signals.modes`: a number of modes, or a word ("chain").
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(crate) enum RawModes {
    Count(f64),
    Word(String),
}

/// Where the transient study strikes, if not at the scene's points.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawTransient {
    pub(crate) pairs_mm: Vec<Vec<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawPlate {
    pub(crate) length_mm: f64,
    pub(crate) width_mm: f64,
    pub(crate) thickness_mm: f64,
    pub(crate) youngs_modulus_gpa: f64,
    pub(crate) poisson_ratio: f64,
    pub(crate) density_kg_m3: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawBody {
    pub(crate) name: String,
    pub(crate) density_kg_m3: f64,
    pub(crate) youngs_modulus_gpa: f64,
    pub(crate) poisson_ratio: f64,
    pub(crate) cohesion_mpa: f64,
    pub(crate) friction_angle_deg: f64,
    pub(crate) radius_mm: f64,
}

/// The paper's support conditions as shorthands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub(crate) enum Preset {
    /// Con 1.
    BothFixed,
    /// Con 2.
    BothSprings,
    /// Con 3.
    FixedAndSprings,
}

impl Preset {
    /// Every preset, in the paper's order.
    pub(crate) const ALL: [Preset; 3] = [Preset::BothFixed, Preset::BothSprings, Preset::FixedAndSprings];

    /// The support set's name when the scene gives none: the paper's.
    pub(crate) fn default_name(self) -> &'static str {
        match self {
            Preset::BothFixed => "Con 1",
            Preset::BothSprings => "Con 2",
            Preset::FixedAndSprings => "Con 3",
        }
    }
}

/// The name of a support set that gives neither a name nor a preset, by its position from 1.
pub(crate) fn default_set_name(number: impl std::fmt::Display) -> String {
    format!("support set {number}")
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawCondition {
    pub(crate) name: Option<String>,
    pub(crate) supports: Option<Preset>,
    pub(crate) spring_stiffness_n_per_m: Option<f64>,
    pub(crate) corners: Option<RawCorners>,
    pub(crate) edges: Option<RawEdges>,
}

#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub(crate) enum CornerKind {
    Fixed,
    Free,
}

/// Corners by position: (x, z) = (0, 0), (L, 0), (0, B), (L, B). Each is a [`CornerKind`]
/// word or a `{ spring_n_per_m = k }` table, read as TOML values and checked in
/// `validate::supports`: an untagged serde enum would accept a spring table with unknown keys
/// beside `spring_n_per_m` and name no field when neither form fits.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawCorners {
    pub(crate) left_near: Option<toml::Value>,
    pub(crate) right_near: Option<toml::Value>,
    pub(crate) left_far: Option<toml::Value>,
    pub(crate) right_far: Option<toml::Value>,
}

#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub(crate) enum RawEdge {
    Free,
    SimplySupported,
    Clamped,
}

/// Edges: left x = 0, right x = L, near z = 0, far z = B.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawEdges {
    pub(crate) left: Option<RawEdge>,
    pub(crate) right: Option<RawEdge>,
    pub(crate) near: Option<RawEdge>,
    pub(crate) far: Option<RawEdge>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawPoints {
    pub(crate) x_mm: Option<Vec<f64>>,
    pub(crate) count: Option<f64>,
    pub(crate) pairs_mm: Option<Vec<Vec<f64>>>,
    pub(crate) grid: Option<RawGrid>,
    pub(crate) z_mm: Option<Vec<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawGrid {
    pub(crate) x_mm: Option<Vec<f64>>,
    pub(crate) x_count: Option<f64>,
    pub(crate) z_mm: Option<Vec<f64>>,
    pub(crate) z_count: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawVelocities {
    pub(crate) m_per_s: Vec<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSolver {
    #[serde(default = "default_method")]
    pub(crate) method: MethodName,
    #[serde(default = "default_tolerance")]
    pub(crate) tolerance: f64,
    #[serde(default = "default_max_iterations")]
    pub(crate) max_iterations: u32,
}

impl Default for RawSolver {
    fn default() -> Self {
        Self { method: default_method(), tolerance: default_tolerance(), max_iterations: default_max_iterations() }
    }
}

#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub(crate) enum MethodName {
    Recursion,
    Bracketed,
}

pub(crate) fn default_method() -> MethodName {
    MethodName::Bracketed
}
pub(crate) fn default_tolerance() -> f64 {
    1e-13
}
pub(crate) fn default_max_iterations() -> u32 {
    200
}
pub(crate) fn default_analyses() -> Vec<Analysis> {
    vec![Analysis::Responses, Analysis::YieldVelocity]
}
