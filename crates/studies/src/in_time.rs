//! Impacts in time on a shell structure's own modes ([`coupled::reduced::structure`]): the
//! tail beam's and a mesh file's lumps beside the three forces that bound them.
//!
//! The structure is taken on the middle mesh of its ladder (the first refinement), with the
//! lumped mass of its steel and its lowest [`IN_TIME_MODES`] modes (fewer where a mesh is
//! small or large: [`modes_for`]); the contact is the study's
//! own load at each point (the tail beam's patch of side t, a mesh's disc of diameter t), the
//! law the scene's, the modes damped at the reduced model's ζ. P_max is, as in the paper and
//! the transient model, the law's force at the largest compression (Kδ_max^{3/2}); the springs'
//! force (the jacks') is each group's largest over one fundamental period from the first
//! touch, summed, against the quasi-static balance's.
//!
//! **Error estimate.** Two differences, added: the truncation's, the same impact on half the
//! modes (the others joining the static correction, [`StructureModel::truncated`]); and the
//! mesh's, the same impact on the coarser mesh. Neither is extrapolated (two meshes give no
//! rate), so the estimate is a difference, not asymptotic; on the shipped tail beam the change
//! from the coarser to the middle mesh (up to 0.52 % in P_max) is about twice the change from
//! the middle to the finest (up to 0.23 %), so the estimate covers the middle mesh's error.

use crate::Failure;
use coupled::plan::scene_striker;
use coupled::reduced::structure::{Readings, StructureImpact, StructureModel, StructureSettings};
use coupled::reduced::ModalDamping;
use plate_fem::shell::{Restraints, ShellMass, Spring, Structure};
use scene::Scene;
use serde::Serialize;
use std::time::Instant;

/// The modes kept: the shipped tail beam's lowest 200 reach about 2.6 kHz, and the static
/// correction carries the rest; P_max moves by 0.003-0.21 % from 100 to 200 modes there.
pub const IN_TIME_MODES: usize = 200;

/// The mesh of the time model in its structure's ladder: the second (the first refined); the
/// first gives the mesh's error.
pub const IN_TIME_LEVEL: u32 = 1;
const _: () = assert!(IN_TIME_LEVEL >= 1, "the mesh error needs a coarser mesh");

/// One impact on the structure in time.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InTimeRow {
    /// The body.
    pub body: String,
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// The struck point's index among the scene's points.
    pub point: usize,
    /// P_max = Kδ_max^{3/2}, N.
    pub p_max: f64,
    /// Its error estimate, N (the truncation's and the mesh's differences, added).
    pub p_max_error: f64,
    /// The truncation's part, |P(N) - P(N/2)|/P.
    pub truncation: f64,
    /// The mesh's part, |P(middle) - P(coarser)|/P.
    pub mesh: f64,
    /// The first contact's duration, s (None if it had not ended in the period).
    pub contact_time: Option<f64>,
    /// Contacts within the period.
    pub contacts: usize,
    /// The contacts' total impulse, N s.
    pub impulse: f64,
    /// The spring groups' (jacks') largest forces over the period, summed, N.
    pub spring_force: f64,
    /// Its error estimate, N (as for P_max).
    pub spring_force_error: f64,
}

/// The time model's data.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InTime {
    /// The mesh level.
    pub level: u32,
    /// Unknowns on it.
    pub unknowns: usize,
    /// Modes kept.
    pub modes: usize,
    /// The modes' damping: the scene's (`[signals] damping_ratio` or `[plate_damping]`).
    pub damping: ModalDamping,
    /// The lowest and the highest kept mode's frequency, Hz.
    pub frequencies: (f64, f64),
    /// The window: one fundamental period, s.
    pub window: f64,
    /// One row per impact asked for, in that order.
    pub rows: Vec<InTimeRow>,
    /// Seconds it took (both meshes' modes and every impact).
    pub seconds: f64,
}

/// A structure on one mesh as the time model takes it: restrained, with each struck point's
/// load (unit resultant) and each spring group.
pub struct OnMesh {
    /// The structure.
    pub structure: Structure,
    /// What holds it.
    pub restraints: Restraints,
    /// Each struck point's load vector.
    pub loads: Vec<Vec<f64>>,
    /// Each spring group (a jack's pad).
    pub groups: Vec<Vec<Spring>>,
}

/// The most memory the Krylov basis of the modes may take: about 3N + 32 vectors of three
/// arrays over the unknowns.
pub const BASIS_BYTES: f64 = 2.0 * 1024.0 * 1024.0 * 1024.0;

/// The modes a mesh of `free` unknowns, `massive` of them with mass, is taken on:
/// [`IN_TIME_MODES`], at most half the DOFs with mass (the search needs room beyond the modes
/// it returns), and at most what a basis of [`BASIS_BYTES`] holds.
pub fn modes_for(free: usize, massive: usize) -> usize {
    let by_memory = ((BASIS_BYTES / (24.0 * free.max(1) as f64) - 32.0) / 3.0).max(0.0) as usize;
    IN_TIME_MODES.min(massive / 2).min(by_memory)
}

/// The models of the middle mesh `fine` (with its unknowns) and the coarser `coarse`, on the
/// same number of modes ([`modes_for`] of both), with the lumped mass of steel of density
/// `rho`, the modes damped by `damping`.
pub fn models(
    fine: &OnMesh,
    coarse: &OnMesh,
    (rho, damping): (f64, ModalDamping),
) -> Result<((StructureModel, usize), StructureModel), Failure> {
    let masses = [ShellMass::lumped(&fine.structure, rho), ShellMass::lumped(&coarse.structure, rho)];
    let sizes = [masses[0].free_dofs(&fine.restraints), masses[1].free_dofs(&coarse.restraints)];
    let modes = sizes.iter().map(|&(free, massive)| modes_for(free, massive)).min().unwrap_or(0);
    if modes < 2 {
        return Err(format!(
            "the structure in time needs at least 2 modes on each mesh; its meshes allow {modes} (free DOFs and DOFs with mass {sizes:?}, a basis of at most {BASIS_BYTES:e} bytes)"
        )
        .into());
    }
    let settings = StructureSettings { modes, damping, ..StructureSettings::default() };
    let model = |m: &OnMesh, mass: &ShellMass| -> Result<(StructureModel, usize), Failure> {
        let fact = m.structure.factorize(&m.restraints)?;
        Ok((
            StructureModel::new(
                &fact,
                mass,
                &m.loads,
                Readings { groups: &m.groups, ..Readings::default() },
                settings,
            )?,
            fact.unknowns(),
        ))
    };
    let fine = model(fine, &masses[0])?;
    let (coarse, _) = model(coarse, &masses[1])?;
    Ok((fine, coarse))
}

/// The `impacts` (body, velocity, point index) on `fine` (the middle mesh, with its unknowns)
/// and, for the mesh's error, on `coarse`; `started` is when building the models began.
pub fn compute(
    scene: &Scene,
    (fine, unknowns): (StructureModel, usize),
    coarse: StructureModel,
    impacts: &[(String, f64, usize)],
    started: Instant,
) -> Result<InTime, Failure> {
    let f = fine.frequencies_hz();
    let half = fine.truncated(f.len() / 2)?;
    let window = 1.0 / f[0];
    let mut rows = Vec::with_capacity(impacts.len());
    for (name, v, point) in impacts {
        let body = scene.bodies.iter().find(|b| &b.name == name).ok_or("an impact of an unknown body")?;
        let s = scene_striker(scene, body, *v);
        let run = |m: &StructureModel| -> Result<(f64, f64, StructureImpact), Failure> {
            let hit = m.impact(&s, *point, window)?;
            let p = s.force_at_max_compression(hit.outcome.compression_max_interpolated);
            Ok((p, hit.group_force_max.iter().sum(), hit))
        };
        let (p, springs, hit) = run(&fine)?;
        let (p_half, springs_half, _) = run(&half)?;
        let (p_coarse, springs_coarse, _) = run(&coarse)?;
        let (truncation, mesh) = (((p - p_half) / p).abs(), ((p - p_coarse) / p).abs());
        rows.push(InTimeRow {
            body: name.clone(),
            velocity: *v,
            point: *point,
            p_max: p,
            p_max_error: (truncation + mesh) * p,
            truncation,
            mesh,
            contact_time: hit.outcome.contact_time,
            contacts: hit.outcome.contacts.len(),
            impulse: hit.outcome.total_impulse,
            spring_force: springs,
            spring_force_error: (springs - springs_half).abs() + (springs - springs_coarse).abs(),
        });
    }
    Ok(InTime {
        level: IN_TIME_LEVEL,
        unknowns,
        modes: f.len(),
        damping: fine.damping(),
        frequencies: (f[0], f[f.len() - 1]),
        window,
        rows,
        seconds: started.elapsed().as_secs_f64(),
    })
}
