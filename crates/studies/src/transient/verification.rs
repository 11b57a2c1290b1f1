//! The transient model against closed forms: Hertz on a rigid target (the step ladder), the
//! Flores law's restitution, the energy balance without damping, mesh convergence, and a large
//! plate against Zener's infinite plate.

use crate::settings::{DYNAMIC_MESH, STEPS_PER_CONTACT};
use crate::Failure;
use analytic::Sphere;
use coupled::discretisation::plate_properties;
use coupled::transient::case::striker;
use coupled::transient::{first_contact_on, simulate, zener, Striker, TransientCase, TransientSettings};
use plate_fem::{Mesh, Supports};
use scene::{Scene, SceneSource, SupportSet};
use serde::Serialize;
use std::time::Instant;

/// Impact velocity of the verification runs, m/s.
pub const VERIFICATION_VELOCITY: f64 = 0.008;
/// The restitutions from which on the Flores deviation is summarised as a multiple of 1 - e.
pub const FLORES_NEAR_ONE: f64 = 0.8;
/// The corner springs of the energy check (the paper's k_T), N/m.
const ENERGY_SPRINGS: f64 = 5.11545e8;
/// The steps per Hertz time of the step ladders.
const STEP_LADDER: [f64; 4] = [50.0, 100.0, 200.0, 400.0];

/// Hertz's impact on a rigid target at one step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HertzRow {
    /// Steps per Hertz time.
    pub steps: f64,
    /// P_max/Hertz - 1.
    pub force_error: f64,
    /// t_c/Hertz - 1.
    pub time_error: Option<f64>,
    /// Apparent e - 1.
    pub restitution_error: Option<f64>,
    /// Largest |E - E₀|/E₀.
    pub energy_error: f64,
}

/// The Flores law at one restitution on a rigid target.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FloresRow {
    /// The law's e.
    pub restitution: f64,
    /// The apparent restitution of the run.
    pub apparent: Option<f64>,
    /// Apparent over e, minus 1.
    pub deviation: Option<f64>,
    /// δ_max over eq. 14 with C = 0, minus 1.
    pub compression_error: f64,
    /// Peak force over Kδ_max^{3/2}.
    pub force_ratio: f64,
}

/// The energy balance on the plate at one step (e = 1, Con 2, centre).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EnergyRow {
    /// Steps per Hertz time.
    pub steps: f64,
    /// Largest |E - E₀|/E₀.
    pub energy_error: f64,
    /// P_max, N.
    pub force_max: f64,
    /// Wall-clock time of the run, s.
    pub seconds: f64,
}

/// One mesh of the convergence ladder (Con 1, centre, the scene's e).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeshRow {
    /// Elements along the length and across the width.
    pub elements: (usize, usize),
    /// Degrees of freedom.
    pub dofs: usize,
    /// P_max, N.
    pub force_max: f64,
    /// |P_max - P_max of the next finer mesh| over the latter; `None` on the finest.
    pub change: Option<f64>,
    /// Contact time, s.
    pub contact_time: Option<f64>,
    /// Wall-clock time of the run, s.
    pub seconds: f64,
}

/// One mesh of the large plate against Zener.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ZenerRow {
    /// Elements along each side.
    pub elements: usize,
    /// P_max, N.
    pub force_max: f64,
    /// P_max/Zener - 1.
    pub force_error: f64,
    /// Contact time, s.
    pub contact_time: Option<f64>,
    /// t_c/Zener - 1.
    pub time_error: Option<f64>,
    /// Apparent restitution.
    pub restitution: Option<f64>,
}

/// The large plate against Zener's infinite plate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Zener {
    /// The plate's length, width and thickness, m.
    pub plate: (f64, f64, f64),
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// The plate's point impedance 8√(Dρh), N·s/m.
    pub impedance: f64,
    /// Zener's P_max, N.
    pub force: f64,
    /// Zener's contact time, s.
    pub time: f64,
    /// Hertz's P_max on a rigid target, N.
    pub hertz_force: f64,
    /// The FE runs.
    pub rows: Vec<ZenerRow>,
}

/// Every verification of the transient model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verification {
    /// The body of the runs (the scene's first).
    pub body: String,
    /// Its elastic striker (e = 1) at [`VERIFICATION_VELOCITY`].
    pub elastic: Striker,
    /// Hertz's impact over the step ladder.
    pub hertz: Vec<HertzRow>,
    /// The Flores law over restitutions.
    pub flores: Vec<FloresRow>,
    /// The mean of -(apparent/e - 1)/(1 - e) for e ≥ [`FLORES_NEAR_ONE`].
    pub flores_slope: f64,
    /// -(apparent/e - 1) at the paper's e.
    pub flores_paper: f64,
    /// The paper's e (its default scene's).
    pub paper_restitution: f64,
    /// The energy balance over the step ladder.
    pub energy: Vec<EnergyRow>,
    /// Mesh convergence.
    pub mesh: Vec<MeshRow>,
    /// The large plate against Zener.
    pub zener: Zener,
}

/// Runs every verification on the scene's plate with its first body.
pub fn verify(scene: &Scene) -> Result<Verification, Failure> {
    let coal = scene.bodies.first().ok_or("no body")?;
    let elastic = striker(&scene.plate, coal, 1.0, VERIFICATION_VELOCITY);
    // The paper's e is the restitution of its scene, the default one.
    let paper_restitution = Scene::default_scene().restitution;
    let (flores, flores_slope, flores_paper) = flores(&scene.plate, coal, paper_restitution);
    Ok(Verification {
        body: coal.name.clone(),
        elastic,
        hertz: hertz(&elastic),
        flores,
        flores_slope,
        flores_paper,
        paper_restitution,
        energy: energy(scene, &elastic)?,
        mesh: mesh(scene, coal)?,
        zener: large_plate(scene, coal)?,
    })
}

/// Hertz's impact on a rigid target over the step ladder.
fn hertz(elastic: &Striker) -> Vec<HertzRow> {
    let tc = elastic.hertz_time();
    STEP_LADDER
        .iter()
        .map(|&n| {
            let o = simulate(elastic, None, tc / n, 3.0 * tc);
            HertzRow {
                steps: n,
                force_error: o.force_max / elastic.hertz_force() - 1.0,
                time_error: o.contact_time.map(|t| t / tc - 1.0),
                restitution_error: o.apparent_restitution.map(|e| e - 1.0),
                energy_error: o.max_energy_error,
            }
        })
        .collect()
}

/// The Flores law on a rigid target over restitutions, with the slope of its deviation near
/// e = 1 and its deviation at the paper's e.
fn flores(plate: &analytic::Plate, body: &Sphere, paper_e: f64) -> (Vec<FloresRow>, f64, f64) {
    let mut rows = Vec::new();
    let mut slopes = Vec::new();
    let mut at_paper = f64::NAN;
    for e in [0.99, 0.95, 0.9, 0.8, paper_e, 0.5] {
        let s = striker(plate, body, e, VERIFICATION_VELOCITY);
        let tc = s.hertz_time();
        let o = simulate(&s, None, tc / 800.0, 3.0 * tc);
        let qs = (5.0 * e * s.mass * s.velocity.powi(2) / (4.0 * s.k)).powf(0.4);
        if let Some(a) = o.apparent_restitution {
            if e >= FLORES_NEAR_ONE {
                slopes.push(-(a / e - 1.0) / (1.0 - e));
            }
            if e == paper_e {
                at_paper = -(a / e - 1.0);
            }
        }
        rows.push(FloresRow {
            restitution: e,
            apparent: o.apparent_restitution,
            deviation: o.apparent_restitution.map(|a| a / e - 1.0),
            compression_error: o.compression_max / qs - 1.0,
            force_ratio: o.force_max / (s.k * o.compression_max.powf(1.5)),
        });
    }
    let slope = slopes.iter().sum::<f64>() / slopes.len() as f64;
    (rows, slope, at_paper)
}

/// The energy balance without damping on the scene's plate (Con 2, centre) over the step
/// ladder.
fn energy(scene: &Scene, elastic: &Striker) -> Result<Vec<EnergyRow>, Failure> {
    let p = &scene.plate;
    let case = TransientCase::new(p, TransientSettings { elements: DYNAMIC_MESH, ..Default::default() })?;
    let con2 = SupportSet::new("Con 2", Supports::con2(ENERGY_SPRINGS));
    let mut rows = Vec::new();
    for n in STEP_LADDER {
        let t0 = Instant::now();
        let o = case.first_contact(&con2, elastic, p.length() / 2.0, p.width() / 2.0, n)?;
        rows.push(EnergyRow {
            steps: n,
            energy_error: o.max_energy_error,
            force_max: o.force_max,
            seconds: t0.elapsed().as_secs_f64(),
        });
    }
    Ok(rows)
}

/// P_max on a ladder of meshes (Con 1, centre, the scene's e).
fn mesh(scene: &Scene, coal: &Sphere) -> Result<Vec<MeshRow>, Failure> {
    let p = &scene.plate;
    let s = striker(p, coal, scene.restitution, VERIFICATION_VELOCITY);
    let con1 = SupportSet::new("Con 1", Supports::con1());
    let mut rows: Vec<MeshRow> = Vec::new();
    for n in [10, 20, 40, 80] {
        let t0 = Instant::now();
        let case = TransientCase::new(p, TransientSettings { elements: n, ..Default::default() })?;
        let o = case.first_contact(&con1, &s, p.length() / 2.0, p.width() / 2.0, STEPS_PER_CONTACT)?;
        let m = case.model();
        rows.push(MeshRow {
            elements: (m.mesh().nx(), m.mesh().nz()),
            dofs: m.dofs(),
            force_max: o.force_max,
            change: None,
            contact_time: o.contact_time,
            seconds: t0.elapsed().as_secs_f64(),
        });
    }
    for i in 0..rows.len().saturating_sub(1) {
        let next = rows[i + 1].force_max;
        rows[i].change = Some((rows[i].force_max - next).abs() / next);
    }
    Ok(rows)
}

/// A 1 m x 1 m, 4 mm plate of the scene's steel, simply supported at its edges and struck at
/// its centre at 1 m/s (e = 1), against Zener's infinite plate: the contact ends before the
/// bending waves return from the edges.
fn large_plate(scene: &Scene, coal: &Sphere) -> Result<Zener, Failure> {
    let base = &scene.plate;
    let thin = analytic::Plate::new(1.0, 1.0, 0.004, base.density(), base.material())?;
    let props = plate_properties(&thin);
    let fast = striker(base, coal, 1.0, 1.0);
    let impedance = 8.0 * (props.rigidity() * props.density * props.thickness).sqrt();
    let (force, time) = zener(&fast, impedance, 20000);
    let time = time.ok_or("Zener's reference impact did not end within 100 Hertz times")?;
    let mut rows = Vec::new();
    for n in [16, 24, 32] {
        let mesh = Mesh::uniform(thin.length(), thin.width(), n, n)?;
        let case = TransientCase::on_mesh(&thin, mesh, TransientSettings::default())?;
        let centre = (thin.length() / 2.0, thin.width() / 2.0);
        // Timed by Zener's contact time, the shorter one on this plate.
        let dt = time / STEPS_PER_CONTACT;
        let o = first_contact_on(case.model(), (Supports::all_edges_simple(), None), &fast, centre, dt, 5.0 * time)?;
        rows.push(ZenerRow {
            elements: n,
            force_max: o.force_max,
            force_error: o.force_max / force - 1.0,
            contact_time: o.contact_time,
            time_error: o.contact_time.map(|t| t / time - 1.0),
            restitution: o.apparent_restitution,
        });
    }
    Ok(Zener {
        plate: (thin.length(), thin.width(), thin.thickness()),
        velocity: fast.velocity,
        impedance,
        force,
        time,
        hertz_force: fast.hertz_force(),
        rows,
    })
}
