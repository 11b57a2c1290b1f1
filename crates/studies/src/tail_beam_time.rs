//! The tail beam in time: each lump of the tail-beam study struck on the box's own lowest modes
//! ([`coupled::reduced::structure`]), beside the three forces that bound it.
//!
//! The box is the study's shell structure on its middle mesh ([`IN_TIME_LEVEL`]), with the
//! lumped mass of its steel and its lowest [`IN_TIME_MODES`] modes; the contact is the study's
//! patch of side t, the law the scene's, the modes damped at the reduced model's ζ. P_max is,
//! as in the paper and the transient model, the law's force at the largest compression
//! (Kδ_max^{3/2}); the jacks' force is each jack's largest over one fundamental period from the
//! first touch, summed, against the quasi-static balance's jack force.
//!
//! **Error estimate.** Two differences, added: the truncation's, the same impact on half the
//! modes (the others joining the static correction, [`StructureModel::truncated`]); and the
//! mesh's, the same impact on the next coarser mesh. Neither is extrapolated (two meshes give
//! no rate), so the estimate is a difference, not asymptotic; from the coarser to the middle
//! mesh it is about three times the change from the middle to the finest (measured on the
//! shipped box: 0.1-1.0 % against 0.03-0.3 % in P_max).

use crate::tail_beam::{RigidTurning, TailBeamRow};
use crate::Failure;
use coupled::compliance::tail_beam::{contact_patch, TailBeamScene};
use coupled::plan::scene_striker;
use coupled::reduced::structure::{StructureImpact, StructureModel, StructureSettings};
use plate_fem::shell::ShellMass;
use scene::Scene;
use serde::Serialize;
use std::time::Instant;

/// The mesh of the time model: the ladder's second (the first halved).
pub const IN_TIME_LEVEL: u32 = 1;

/// The modes kept: the box's lowest 200 reach about 2.6 kHz on the shipped tail beam, and the
/// static correction carries the rest; P_max moves by 0.05-0.6 % from 100 to 200 modes there.
pub const IN_TIME_MODES: usize = 200;

/// One impact on the box in time.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InTimeRow {
    /// The body.
    pub body: String,
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// The struck point along the beam, m.
    pub x: f64,
    /// The struck point across the beam, m.
    pub z: f64,
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
    /// The jacks' largest forces over the period, summed, N.
    pub jack_force: f64,
    /// Its error estimate, N (as for P_max).
    pub jack_force_error: f64,
    /// The rigid box's answer to the contact's impulse J at x: Σk_j a_j · J x/(I ω_r), N
    /// ([`RigidTurning`]), an independent estimate of the jacks' force.
    pub jack_force_rigid_box: f64,
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
    /// The lowest and the highest kept mode's frequency, Hz.
    pub frequencies: (f64, f64),
    /// The window: one fundamental period, s.
    pub window: f64,
    /// One row per body, velocity and point, in the order of the study's rows.
    pub rows: Vec<InTimeRow>,
    /// Seconds it took (both meshes' modes and every impact).
    pub seconds: f64,
}

/// The box's model on mesh `level`: its lowest `modes` modes and the struck points' loads.
fn model(scene: &Scene, tb: &TailBeamScene, level: u32) -> Result<(StructureModel, usize), Failure> {
    let m = scene.plate.material();
    let built = tb.beam.build(m.youngs_modulus(), m.poisson_ratio(), tb.element, level)?;
    let fact = built.structure.factorize(&built.restraints)?;
    let mass = ShellMass::lumped(&built.structure, scene.plate.density());
    let loads = tb
        .points
        .iter()
        .map(|&(x, z)| built.structure.patch_load(built.top, &contact_patch(&tb.beam, x, z)))
        .collect::<Result<Vec<_>, _>>()?;
    let groups: Vec<_> = built.jacks.iter().map(|r| built.restraints.springs[r.clone()].to_vec()).collect();
    let settings = StructureSettings { modes: IN_TIME_MODES, ..StructureSettings::default() };
    Ok((StructureModel::new(&fact, &mass, &loads, &groups, settings)?, fact.unknowns()))
}

/// The impacts of the study's `rows` on the box in time.
pub fn compute(scene: &Scene, tb: &TailBeamScene, rows: &[TailBeamRow]) -> Result<InTime, Failure> {
    let t = Instant::now();
    let (fine, unknowns) = model(scene, tb, IN_TIME_LEVEL)?;
    let (coarse, _) = model(scene, tb, IN_TIME_LEVEL - 1)?;
    let half = fine.truncated(IN_TIME_MODES / 2)?;
    let f = fine.frequencies_hz();
    let window = 1.0 / f[0];
    let rigid = RigidTurning::of(&tb.beam, scene.plate.density());
    let omega_r = (rigid.stiffness / rigid.inertia).sqrt();
    let mut out = Vec::with_capacity(rows.len());
    for r in rows {
        let body = scene.bodies.iter().find(|b| b.name == r.body).ok_or("a row of an unknown body")?;
        let point = tb.points.iter().position(|&p| p == (r.x, r.z)).ok_or("a row at an unknown point")?;
        let s = scene_striker(scene, body, r.velocity);
        let run = |m: &StructureModel| -> Result<(f64, f64, StructureImpact), Failure> {
            let hit = m.impact(&s, point, window)?;
            let p = s.force_at_max_compression(hit.outcome.compression_max_interpolated);
            Ok((p, hit.group_force_max.iter().sum(), hit))
        };
        let (p, jacks, hit) = run(&fine)?;
        let (p_half, jacks_half, _) = run(&half)?;
        let (p_coarse, jacks_coarse, _) = run(&coarse)?;
        let (truncation, mesh) = (((p - p_half) / p).abs(), ((p - p_coarse) / p).abs());
        out.push(InTimeRow {
            body: r.body.clone(),
            velocity: r.velocity,
            x: r.x,
            z: r.z,
            p_max: p,
            p_max_error: (truncation + mesh) * p,
            truncation,
            mesh,
            contact_time: hit.outcome.contact_time,
            contacts: hit.outcome.contacts.len(),
            jack_force: jacks,
            jack_force_error: (jacks - jacks_half).abs() + (jacks - jacks_coarse).abs(),
            jack_force_rigid_box: rigid.jacks_force * hit.outcome.total_impulse * r.x / (rigid.inertia * omega_r),
        });
    }
    Ok(InTime {
        level: IN_TIME_LEVEL,
        unknowns,
        modes: IN_TIME_MODES,
        frequencies: (f[0], f[f.len() - 1]),
        window,
        rows: out,
        seconds: t.elapsed().as_secs_f64(),
    })
}
