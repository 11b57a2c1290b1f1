//! Transverse shear: the Reissner-Mindlin plate against Kirchhoff's at the scene's points.
//!
//! Both plates through the same energy balance; only the compliance differs. Against
//! Kirchhoff's point value (what changing `--model` changes) the difference mixes the shear
//! deflection with the contact's spreading over the Mindlin model's patch (clipped at an edge,
//! its centroid h/4 inside; [`coupled::compliance::mindlin`]). Kirchhoff's plate under the
//! same patch (BFS, the ladder's finest mesh) separates them: Mindlin against it is shear
//! alone.

use crate::settings::{BASE_MESH, LEVELS};
use crate::Failure;
use coupled::compliance::mindlin::{contact_patch, MINDLIN_BASE_MESH, MINDLIN_LEVELS};
use coupled::compliance::{ComplianceModel, MindlinModel};
use coupled::discretisation::{ladder_meshes, plate_properties};
use coupled::plan::{run, ModelKind, ResponseRow, Results};
use coupled::PlateModel;
use plate_fem::Model;
use scene::{Analysis, Scene};
use serde::Serialize;
use std::time::Instant;

use super::{same_case, MeshLevel};

/// Both plates at one (support set, point).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShearRow {
    /// The support set.
    pub condition: String,
    /// The point, m.
    pub x: f64,
    /// The point, m.
    pub z: f64,
    /// Kirchhoff's compliance (BFS, extrapolated), m/N.
    pub kirchhoff: f64,
    /// Its error estimate, m/N.
    pub kirchhoff_error: f64,
    /// Mindlin's compliance (MITC4, extrapolated, the contact over a square of side h), m/N.
    pub mindlin: f64,
    /// Its error estimate, m/N.
    pub mindlin_error: f64,
    /// The part of Mindlin's compliance stored as shear energy, m/N.
    pub shear: f64,
    /// Kirchhoff's compliance under Mindlin's contact patch (BFS on the ladder's finest
    /// mesh), m/N.
    pub kirchhoff_patch: f64,
    /// P_max of the scene's first body at its first velocity: Kirchhoff's, then Mindlin's, N
    /// (none without responses or where a row is not computed).
    pub p_max: Option<(f64, f64)>,
}

/// The shear study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Shear {
    /// h/min(L, B) of the scene's plate.
    pub thickness_ratio: f64,
    /// One row per support set and point.
    pub rows: Vec<ShearRow>,
    /// The Mindlin model's meshes.
    pub levels: Vec<MeshLevel>,
    /// Seconds the Mindlin model took.
    pub seconds: f64,
}

/// Mindlin's plate at the scene's points beside the Kirchhoff model `kirchhoff` and its rows.
pub fn shear(scene: &Scene, kirchhoff: &PlateModel, kirchhoff_rows: &Results) -> Result<Shear, Failure> {
    let t = Instant::now();
    let points = scene.point_pairs();
    let model = MindlinModel::compute(&scene.plate, &scene.conditions, &points, MINDLIN_BASE_MESH, MINDLIN_LEVELS)?;
    let seconds = t.elapsed().as_secs_f64();
    let mindlin_rows = if scene.wants(Analysis::Responses) {
        Some(run(scene, &model, ModelKind::Mindlin, &model.periods)?)
    } else {
        None
    };
    let props = plate_properties(&scene.plate);
    let bfs = Model::new(props, ladder_meshes(&props, BASE_MESH, LEVELS)?.pop().ok_or("the ladder has meshes")?)?;
    let mut rows = Vec::new();
    for set in &scene.conditions {
        let factor = bfs.factorize(&set.supports)?;
        for &(x, z) in &points {
            let kirchhoff_patch = factor.respond_patch(&contact_patch(&props, x, z))?;
            let (k, m) = (kirchhoff.compliance(set, x, z)?, model.compliance(set, x, z)?);
            let shear = m.compliance.stores().iter().filter(|s| s.name == "plate shear").map(|s| s.compliance).sum();
            let p_max = mindlin_rows.as_ref().and_then(|mr| {
                let row = first_case(scene, kirchhoff_rows, &set.name, (x, z))?;
                let pm = same_case(mr, row)?.values()?.contact_force;
                Some((row.values()?.contact_force, pm))
            });
            rows.push(ShearRow {
                condition: set.name.clone(),
                x,
                z,
                kirchhoff: k.compliance.total(),
                kirchhoff_error: k.error_estimate,
                mindlin: m.compliance.total(),
                mindlin_error: m.error_estimate,
                shear,
                kirchhoff_patch,
                p_max,
            });
        }
    }
    let p = &scene.plate;
    Ok(Shear {
        thickness_ratio: p.thickness() / p.length().min(p.width()),
        rows,
        levels: model.levels.iter().map(|c| MeshLevel { nx: c.nx, nz: c.nz, dofs: c.dofs }).collect(),
        seconds,
    })
}

/// The row of `rows` for the scene's first body at its first velocity, under `set` at `at`.
fn first_case<'a>(scene: &Scene, rows: &'a Results, set: &str, at: (f64, f64)) -> Option<&'a ResponseRow> {
    let (body, v) = (scene.bodies.first()?, *scene.velocities.first()?);
    rows.responses.iter().find(|r| r.condition == set && r.body == body.name && r.velocity == v && (r.x, r.z) == at)
}
