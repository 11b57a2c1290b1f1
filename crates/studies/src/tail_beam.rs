//! The tail beam: the scene's bodies, at its velocities, striking a box-section tail beam
//! (`[tail_beam]`), beside the paper's beam and Kirchhoff plate under the same impacts.
//!
//! Three forces bound what a lump feels on a tail beam:
//!
//! - **quasi-static**: the paper's energy balance (eqs. 14-20) with the whole structure's
//!   compliance at the struck point (walls, box, jacks). Valid for slow contacts, t_c/T₁ ≥ 0.2;
//! - **wave controlled**: Christoforou and Yigit's infinite-plate asymptote for the top plate,
//!   F̄_∞(ζ)·P_H ([`coupled::regimes::ChristoforouYigit`]): the contact is over before the
//!   flexural waves reach a support, so only the plate's impedance 8√(Dρh) matters. Olsson's
//!   mass criterion puts an impact here when the lump is light against the structure
//!   (M_i/M_p < 0.23);
//! - **half-space**: Hertz's force on a rigid target, P_H, an upper bound of both.
//!
//! A lump on a tail beam is light against a box of hundreds of kilograms and its contact
//! lasts a fraction of a millisecond against a fundamental period set by the jacks: the
//! wave-controlled force is the answer, and the quasi-static one shows what the paper's
//! balance would say with the whole structure behind the point.

use crate::settings::{BASE_MESH, LEVELS};
use crate::Failure;
use analytic::{respond, yield_velocity, DruckerPrager, Plate};
use coupled::compliance::tail_beam::{contact_patch, TailBeamModel, TailBeamScene, TAIL_BEAM_LEVELS};
use coupled::compliance::{BeamModel, ComplianceModel, PlateModel};
use coupled::plan::impact_of;
use coupled::regimes::{ChristoforouYigit, OlssonRegime};
use coupled::transient::{law::Flores, ContactLaw, Striker};
use coupled::validity::{self, Criterion, MINDLIN_PLATE_MAX_RATIO};
use scene::Scene;
use serde::Serialize;
use std::time::Instant;

/// One impact on the tail beam.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TailBeamRow {
    /// The body.
    pub body: String,
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// The struck point along the beam, m.
    pub x: f64,
    /// The struck point across the beam, m.
    pub z: f64,
    /// The structure's compliance at the point (extrapolated), m/N.
    pub compliance: f64,
    /// Its error estimate, m/N.
    pub compliance_error: f64,
    /// The shares of the compliance stored in the walls' membrane, bending and shear, and in
    /// the jacks.
    pub shares: [f64; 4],
    /// P_max by the quasi-static balance with the whole compliance, N.
    pub p_quasi_static: f64,
    /// The jacks' force then, N (their sum).
    pub jack_force: f64,
    /// P_max in the wave-controlled limit, F̄_∞(ζ)·P_H, N.
    pub p_wave: f64,
    /// Hertz's P_max on a rigid target, N.
    pub p_half_space: f64,
    /// Hertz's contact time on a rigid target, s.
    pub contact_time: f64,
    /// Christoforou and Yigit's relative stiffness λ = k_α C with the whole compliance.
    pub lambda: f64,
    /// Their loss factor ζ of the top plate.
    pub zeta: f64,
    /// The lump's mass over the structure's.
    pub mass_ratio: f64,
    /// Olsson's regime by it.
    pub regime: OlssonRegime,
    /// The yield velocity (eqs. 51-54) with the whole compliance, m/s.
    pub yield_velocity: f64,
    /// The yield velocity on a rigid target (C = 0), m/s.
    pub yield_velocity_rigid: f64,
    /// δ_max/δ_my of the quasi-static balance.
    pub elastic: Criterion,
    /// t_c/T₁ of the quasi-static balance.
    pub quasi_static: Criterion,
}

/// The paper's plate under the same impact: its beam and Kirchhoff plate at the plate's centre
/// under the scene's first support set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PaperRow {
    /// The body.
    pub body: String,
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// The support set.
    pub condition: String,
    /// P_max by the beam, N.
    pub beam: f64,
    /// P_max by the Kirchhoff plate, N.
    pub plate: f64,
}

/// The study's data.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TailBeamData {
    /// The scene's tail beam.
    pub scene: TailBeamScene,
    /// The meshes: (elements along x, elements across z, unknowns, seconds).
    pub levels: Vec<(usize, usize, usize, f64)>,
    /// The finest element's side, m.
    pub finest_element: f64,
    /// The fundamental frequency, Hz, and its change from the mesh before (relative).
    pub frequency: (f64, f64),
    /// The walls' mass, kg.
    pub mass: f64,
    /// The walls' largest thickness over the shortest span of their panel, against the
    /// Reissner-Mindlin range.
    pub thickness_range: Criterion,
    /// The finest element's side over the contact patch's.
    pub resolution: Criterion,
    /// One row per body, velocity and point.
    pub rows: Vec<TailBeamRow>,
    /// The paper's plate under the same impacts.
    pub paper: Vec<PaperRow>,
    /// Seconds the shell model took.
    pub seconds: f64,
}

/// Runs the study on a scene with a `[tail_beam]`.
pub fn compute(scene: &Scene) -> Result<TailBeamData, Failure> {
    let tb = scene.tail_beam.as_ref().ok_or("the scene has no [tail_beam]")?;
    let material = scene.plate.material();
    let t = Instant::now();
    let model = TailBeamModel::compute(
        &tb.beam,
        (material.youngs_modulus(), material.poisson_ratio(), scene.plate.density()),
        &tb.points,
        tb.element,
        TAIL_BEAM_LEVELS,
    )?;
    let seconds = t.elapsed().as_secs_f64();
    let top = Plate::new(tb.beam.length, tb.beam.width, tb.beam.top, scene.plate.density(), material)?;
    let mut rows = Vec::new();
    for body in &scene.bodies {
        for &v in &scene.velocities {
            for &(x, z) in &tb.points {
                rows.push(row(scene, &model, &top, body, v, (x, z))?);
            }
        }
    }
    Ok(TailBeamData {
        scene: tb.clone(),
        levels: model.levels.iter().map(|l| (l.nx, l.nz, l.dofs, l.seconds)).collect(),
        finest_element: model.finest_element,
        frequency: (model.frequency, model.frequency_change),
        mass: model.mass,
        thickness_range: thickness_range(tb),
        resolution: Criterion::at_most("element/patch side", model.finest_element / tb.beam.top, 1.0),
        rows,
        paper: paper_rows(scene)?,
        seconds,
    })
}

/// One impact of `body` at `v` on the tail beam at `at`.
fn row(
    scene: &Scene,
    model: &TailBeamModel,
    top: &Plate,
    body: &analytic::Sphere,
    v: f64,
    at: (f64, f64),
) -> Result<TailBeamRow, Failure> {
    let est = model.compliance(at.0, at.1)?;
    let c = est.compliance.total();
    let imp = impact_of(scene, body, v);
    let r = respond(&imp, &est.compliance, scene.solver)?;
    let striker = Striker {
        k: imp.contact_stiffness,
        restitution: imp.restitution,
        mass: imp.mass,
        velocity: v,
        law: ContactLaw::Flores(Flores),
        gravity: 0.0,
    };
    let cy = ChristoforouYigit::of(&striker, top, c);
    let p_half_space = striker.hertz_force();
    let share = |name: &str| -> f64 {
        let s: f64 = est.compliance.stores().iter().filter(|s| s.name.starts_with(name)).map(|s| s.compliance).sum();
        if c > 0.0 {
            s / c
        } else {
            0.0
        }
    };
    let jack_force = est.compliance.springs().iter().map(|s| s.per_unit_load).sum::<f64>() * r.contact_force;
    let dp = DruckerPrager::of(body);
    let d_my = dp.yield_compression(body.radius(), imp.contact_stiffness);
    let ratio = body.mass() / model.mass;
    let t_c = striker.hertz_time();
    Ok(TailBeamRow {
        body: body.name.clone(),
        velocity: v,
        x: at.0,
        z: at.1,
        compliance: c,
        compliance_error: est.error_estimate,
        shares: [share("walls membrane"), share("walls bending"), share("walls shear"), share("jack")],
        p_quasi_static: r.contact_force,
        jack_force,
        p_wave: cy.infinite_plate_force() * p_half_space,
        p_half_space,
        contact_time: t_c,
        lambda: cy.relative_stiffness,
        zeta: cy.loss_factor,
        mass_ratio: ratio,
        regime: OlssonRegime::of(ratio),
        yield_velocity: yield_velocity(body, &imp, c, d_my),
        yield_velocity_rigid: yield_velocity(body, &imp, 0.0, d_my),
        elastic: validity::elastic(r.compression, d_my),
        quasi_static: validity::quasi_static(t_c, 1.0 / model.frequency),
    })
}

/// The walls' largest t/(shortest span of the panel): the top and bottom plates between webs
/// and ribs, the webs and ribs over the depth, the end plates over the depth.
fn thickness_range(tb: &TailBeamScene) -> Criterion {
    let b = &tb.beam;
    let mut zs = vec![0.0, b.width];
    zs.extend(b.ribs.iter().copied());
    zs.sort_by(f64::total_cmp);
    let panel = zs.windows(2).map(|w| w[1] - w[0]).fold(b.length, f64::min);
    let ratios = [
        b.top / panel,
        b.bottom / panel,
        b.webs / b.height.min(b.length),
        b.ends / b.height.min(b.width),
        if b.ribs.is_empty() { 0.0 } else { b.rib / b.height.min(b.length) },
    ];
    Criterion::at_most("t/(shortest panel span)", ratios.into_iter().fold(0.0, f64::max), MINDLIN_PLATE_MAX_RATIO)
}

/// The beam's and the Kirchhoff plate's P_max at the centre of the scene's plate under its
/// first support set, for every body and velocity.
fn paper_rows(scene: &Scene) -> Result<Vec<PaperRow>, Failure> {
    let Some(set) = scene.conditions.first() else { return Ok(Vec::new()) };
    let centre = (scene.plate.length() / 2.0, scene.plate.width() / 2.0);
    let plate = PlateModel::compute(&scene.plate, std::slice::from_ref(set), &[centre], BASE_MESH, LEVELS)?;
    let beam = BeamModel { plate: &scene.plate };
    let (cb, cp) = (beam.compliance(set, centre.0, centre.1)?, plate.compliance(set, centre.0, centre.1)?);
    let mut out = Vec::new();
    for body in &scene.bodies {
        for &v in &scene.velocities {
            let imp = impact_of(scene, body, v);
            out.push(PaperRow {
                body: body.name.clone(),
                velocity: v,
                condition: set.name.clone(),
                beam: respond(&imp, &cb.compliance, scene.solver)?.contact_force,
                plate: respond(&imp, &cp.compliance, scene.solver)?.contact_force,
            });
        }
    }
    Ok(out)
}

/// The contact patch's side along x and z at `at` (m), for the report.
pub fn patch_sides(tb: &TailBeamScene, at: (f64, f64)) -> (f64, f64) {
    let p = contact_patch(&tb.beam, at.0, at.1);
    (p.side_z, p.side_x)
}
