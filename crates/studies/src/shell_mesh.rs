//! A shell structure read from a mesh file (`[shell_mesh]`): the scene's bodies at its
//! velocities striking its named face, with the three forces of the tail-beam study
//! ([`crate::tail_beam`]) beside each other:
//!
//! - **quasi-static**: the paper's energy balance (eqs. 14-20) with the whole structure's
//!   compliance at the point (walls, springs), valid for contacts slow against the
//!   fundamental period, t_c/T₁ ≥ 0.2;
//! - **wave controlled**: Christoforou and Yigit's infinite-plate asymptote for a plate of the
//!   struck face's thickness, F̄_∞(ζ)·P_rigid, the answer where the contact is over before
//!   flexural waves return from the face's edges;
//! - **rigid target**: the balance with C = 0 under the same law, the unit of the other two.
//!
//! The mesh says nothing of panels, so Olsson's mass ratio, which the tail-beam study takes
//! from the panel the point lies on, is not given here; the struck face's own geometry decides
//! which limit holds, and the report says so.

use crate::in_time::{InTime, OnMesh, IN_TIME_LEVEL};
use crate::tail_beam::{share, three_forces, ThreeForces};
use crate::Failure;
use analytic::{yield_velocity, Plate, StoreKind};
use coupled::compliance::shell_mesh::{MeshLevel, ShellMeshModel, ShellMeshScene};
use coupled::validity::{self, Criterion};
use plate_fem::shell::DISC_RULE;
use scene::Scene;
use serde::Serialize;
use std::time::Instant;

/// One impact on the structure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShellMeshRow {
    /// The body.
    pub body: String,
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// The struck point (m).
    pub at: [f64; 3],
    /// The compliance at the point (extrapolated), m/N.
    pub compliance: f64,
    /// Its error estimate, m/N.
    pub compliance_error: f64,
    /// Whether the ladder was in its asymptotic range (an observed rate within the accepted
    /// range, consistent on the last meshes).
    pub asymptotic: bool,
    /// The shares of the compliance in the walls' membrane, bending and shear and in the
    /// springs.
    pub shares: [f64; 4],
    /// P_max by the quasi-static balance with the whole compliance, N.
    pub p_quasi_static: f64,
    /// The springs' force then, N (their sum).
    pub spring_force: f64,
    /// P_max in the wave-controlled limit, F̄_∞(ζ)·P_rigid, N.
    pub p_wave: f64,
    /// P_max on a rigid target under the same law, N.
    pub p_rigid: f64,
    /// Hertz's contact time on a rigid target, s.
    pub contact_time: f64,
    /// Christoforou and Yigit's relative stiffness λ = k_α C with the whole compliance.
    pub lambda: f64,
    /// Their loss factor ζ of the struck face.
    pub zeta: f64,
    /// The yield velocity (eqs. 51-54) with the whole compliance, m/s.
    pub yield_velocity: f64,
    /// δ_max/δ_my of the quasi-static balance.
    pub elastic: Criterion,
    /// t_c/T₁ of the quasi-static balance.
    pub quasi_static: Criterion,
}

/// The study's data.
#[derive(Debug, Clone, Serialize)]
pub struct ShellMeshData {
    /// The scene's structure.
    pub scene: ShellMeshScene,
    /// The struck face's thickness, m (the contact disc's diameter).
    pub struck_thickness: f64,
    /// The meshes of the ladder.
    pub levels: Vec<MeshLevel>,
    /// Each point's observed convergence rate (None where none was clear).
    pub rates: Vec<Option<f64>>,
    /// The fundamental frequency (Hz) on the finest mesh and its change from the mesh before.
    pub frequency: (f64, f64),
    /// The structure's mass, kg.
    pub mass: f64,
    /// One row per body, velocity and point.
    pub rows: Vec<ShellMeshRow>,
    /// Seconds the ladder took.
    pub seconds: f64,
    /// The impacts on the structure's own modes in time, one per row.
    pub in_time: InTime,
}

/// Runs the study on a scene with a `[shell_mesh]`.
pub fn compute(scene: &Scene) -> Result<ShellMeshData, Failure> {
    let sm = scene.shell_mesh.as_ref().ok_or("the scene has no [shell_mesh]")?;
    let material = scene.plate.material();
    let t = Instant::now();
    let model =
        ShellMeshModel::compute(sm, (material.youngs_modulus(), material.poisson_ratio(), scene.plate.density()))?;
    let seconds = t.elapsed().as_secs_f64();
    let thickness = sm.struck_thickness()?;
    // The struck face as an infinite plate: only its rigidity and mass per area enter.
    let face = Plate::new(1.0, 1.0, thickness, scene.plate.density(), material)?;
    let mut rows = Vec::new();
    for body in &scene.bodies {
        for &v in &scene.velocities {
            for (at, est) in &model.points {
                rows.push(row(scene, &model, &face, body, v, *at, est)?);
            }
        }
    }
    let in_time = in_time_of(scene, sm, thickness, &rows)?;
    Ok(ShellMeshData {
        in_time,
        scene: sm.clone(),
        struck_thickness: thickness,
        levels: model.levels.clone(),
        rates: model.rates.clone(),
        frequency: (model.frequency, model.frequency_change),
        mass: model.mass,
        rows,
        seconds,
    })
}

/// The study's impacts in time ([`crate::in_time`]) on the file's mesh refined once, and on the
/// file's own for the mesh's error.
fn in_time_of(scene: &Scene, sm: &ShellMeshScene, thickness: f64, rows: &[ShellMeshRow]) -> Result<InTime, Failure> {
    let started = Instant::now();
    let (m, rho) = (scene.plate.material(), scene.plate.density());
    let on = |mesh: &plate_fem::shell::gmsh::MeshFile| -> Result<_, Failure> {
        let built = sm.build(mesh, m.youngs_modulus(), m.poisson_ratio())?;
        let s = &built.structure;
        let loads = sm
            .points
            .iter()
            .map(|&at| s.disc_load(at, thickness / 2.0, &built.struck, DISC_RULE))
            .collect::<Result<Vec<_>, _>>()?;
        let groups = built.springs.iter().map(|r| built.restraints.springs[r.clone()].to_vec()).collect();
        Ok(OnMesh { structure: built.structure, restraints: built.restraints, loads, groups })
    };
    let mut fine_mesh = sm.mesh.clone();
    for _ in 0..IN_TIME_LEVEL {
        fine_mesh = fine_mesh.refined();
    }
    let (fine, coarse) =
        crate::in_time::models(&on(&fine_mesh)?, &on(&sm.mesh)?, (rho, scene.signals.reduced().damping()))?;
    let impacts = rows
        .iter()
        .map(|r| {
            let point = sm.points.iter().position(|&p| p == r.at).ok_or("a row at an unknown point")?;
            Ok((r.body.clone(), r.velocity, point))
        })
        .collect::<Result<Vec<_>, Failure>>()?;
    crate::in_time::compute(scene, fine, coarse, &impacts, started)
}

/// One impact of `body` at `v` on the structure at `at`.
fn row(
    scene: &Scene,
    model: &ShellMeshModel,
    face: &Plate,
    body: &analytic::Sphere,
    v: f64,
    at: [f64; 3],
    est: &coupled::compliance::Estimate,
) -> Result<ShellMeshRow, Failure> {
    let c = est.compliance.total();
    let ThreeForces { imp, quasi_static: r, p_rigid, cy, striker, d_my } =
        three_forces(scene, body, v, &est.compliance, face)?;
    let share = |name: &str| share(&est.compliance, name);
    let springs: f64 =
        est.compliance.stores().iter().filter(|s| s.kind == StoreKind::Spring).map(|s| s.compliance).sum();
    Ok(ShellMeshRow {
        body: body.name.clone(),
        velocity: v,
        at,
        compliance: c,
        compliance_error: est.error_estimate,
        asymptotic: est.asymptotic,
        shares: [
            share("walls membrane"),
            share("walls bending"),
            share("walls shear"),
            if c > 0.0 { springs / c } else { 0.0 },
        ],
        p_quasi_static: r.contact_force,
        spring_force: est.compliance.springs().iter().map(|s| s.per_unit_load).sum::<f64>() * r.contact_force,
        p_wave: cy.infinite_plate_force() * p_rigid,
        p_rigid,
        contact_time: striker.hertz_time(),
        lambda: cy.relative_stiffness,
        zeta: cy.loss_factor,
        yield_velocity: yield_velocity(body, &imp, c, d_my),
        elastic: validity::elastic(r.compression, d_my),
        quasi_static: validity::quasi_static(striker.hertz_time(), 1.0 / model.frequency),
    })
}
