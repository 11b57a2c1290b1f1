//! The map's runs: each plate of the map (a size and a thickness) as one job, every support
//! family, impact point and sphere on it, the jobs spread over threads; and the sample rerun
//! with h and Δt halved.

use super::{Check, Family, MapRow, Slice, CHECK_EVERY, MAP_MESH, MAP_STEPS, RADIUS_FACTORS};
use crate::progress::Progress;
use crate::settings::Settings;
use crate::Failure;
use analytic::{respond, Plate, Sphere};
use coupled::plan::impact_of;
use coupled::regimes::{mass_ratio, measure, period_estimate, RuleInputs};
use coupled::transient::{case::striker, Striker, TransientCase, TransientSettings};
use coupled::{ComplianceModel, PlateModel};
use scene::{Scene, SupportSet};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// One job of the map: a plate and what to run on it.
pub(super) struct Job {
    pub slice: Slice,
    pub scale: f64,
    pub thickness_factor: f64,
}

/// The support sets of a job (family, set, corner spring) and its impact points.
type JobCases = (Vec<(String, SupportSet, Option<f64>)>, Vec<(f64, f64)>);
/// Each job's rows, or its failure as text, in job order (None until it has run).
type JobSlots = Mutex<Vec<Option<Result<Vec<MapRow>, String>>>>;

/// The scene's plate scaled in size and thickness.
fn scaled_plate(scene: &Scene, scale: f64, thickness_factor: f64) -> Result<Plate, Failure> {
    let p = &scene.plate;
    Ok(Plate::new(p.length() * scale, p.width() * scale, p.thickness() * thickness_factor, p.density(), p.material())?)
}

/// The scene's first body with its radius times `factor`.
fn scaled_body(body: &Sphere, factor: f64) -> Result<Sphere, Failure> {
    Ok(Sphere::new(
        format!("{} x{factor}", body.name),
        body.density(),
        body.radius() * factor,
        body.material(),
        body.strength(),
    )?)
}

/// The map's striker: `sphere` on `plate` at `v` with the scene's restitution and the
/// paper's Flores law, whatever law the scene names (the maps measure the paper's balance).
fn map_striker(scene: &Scene, plate: &Plate, sphere: &Sphere, v: f64) -> Striker {
    striker(plate, sphere, scene.restitution, v)
}

/// Every case of one plate.
fn run_job(scene: &Scene, settings: &Settings, job: &Job, families: &[Family]) -> Result<Vec<MapRow>, Failure> {
    let plate = scaled_plate(scene, job.scale, job.thickness_factor)?;
    let (sets, points): JobCases = match job.slice {
        Slice::Centre => (
            families.iter().map(|f| (f.family.clone(), f.set.clone(), f.spring)).collect(),
            vec![(plate.length() / 2.0, plate.width() / 2.0)],
        ),
        Slice::Points => (
            scene.conditions.iter().map(|c| (c.name.clone(), c.clone(), c.spring_stiffnesses().next())).collect(),
            scene.transient_points.clone(),
        ),
    };
    let set_list: Vec<SupportSet> = sets.iter().map(|s| s.1.clone()).collect();
    let case = TransientCase::new(&plate, TransientSettings { elements: MAP_MESH, ..Default::default() })?;
    let qs = PlateModel::compute(&plate, &set_list, &points, settings.base_mesh, settings.levels)?;
    let body = scene.bodies.first().ok_or("the scene has no body")?;
    let v = scene.velocities.first().copied().ok_or("the scene has no velocity")?;
    let on_plate = Scene { plate, ..scene.clone() };
    let mut rows = Vec::new();
    for (family, set, spring) in &sets {
        let period = case.fundamental_period(&set.supports)?;
        for &(x, z) in &points {
            let facts = case.facts(&set.supports, x, z);
            let c = qs.compliance(set, x, z)?;
            for factor in RADIUS_FACTORS {
                let sphere = scaled_body(body, factor)?;
                let s = map_striker(scene, &plate, &sphere, v);
                let imp = impact_of(&on_plate, &sphere, v);
                let qs_force = respond(&imp, &c.compliance, settings.method)?.contact_force;
                let total = c.compliance.total();
                let measured = measure(&case, set, facts, &s, (x, z), total, qs_force, MAP_STEPS)?;
                rows.push(MapRow {
                    slice: job.slice,
                    condition: set.name.clone(),
                    family: family.clone(),
                    spring: *spring,
                    scale: job.scale,
                    thickness: plate.thickness(),
                    radius: sphere.radius(),
                    point: (x, z),
                    mass_ratio: mass_ratio(s.mass, &plate),
                    period,
                    period_estimate: period_estimate(&plate, set),
                    hertz_time: s.hertz_time(),
                    compliance: total,
                    rule: RuleInputs::of(&s, &plate, set, total),
                    measured,
                });
            }
        }
    }
    Ok(rows)
}

/// Runs `jobs` on up to `threads` threads, in order of the jobs.
pub(super) fn run_jobs(
    scene: &Scene,
    settings: &Settings,
    jobs: &[Job],
    families: &[Family],
    threads: usize,
    progress: &dyn Progress,
) -> Result<Vec<MapRow>, Failure> {
    let next = AtomicUsize::new(0);
    let results: JobSlots = Mutex::new(jobs.iter().map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..threads.max(1) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(job) = jobs.get(i) else { break };
                let r = run_job(scene, settings, job, families).map_err(|e| e.to_string());
                if let Ok(mut all) = results.lock() {
                    all[i] = Some(r);
                }
                progress.advance(1);
            });
        }
    });
    let mut rows = Vec::new();
    for r in results.into_inner().map_err(|_| "a map thread panicked")? {
        rows.extend(r.ok_or("a map job did not run")??);
    }
    Ok(rows)
}

/// Every [`CHECK_EVERY`]th centre case rerun with h and Δt halved: the largest changes of
/// the measured quantities.
pub(super) fn discretisation_check(scene: &Scene, rows: &[MapRow], families: &[Family]) -> Result<Check, Failure> {
    let body = scene.bodies.first().ok_or("the scene has no body")?;
    let v = scene.velocities.first().copied().ok_or("the scene has no velocity")?;
    let mut c = Check::default();
    for r in rows.iter().filter(|r| r.slice == Slice::Centre).step_by(CHECK_EVERY) {
        let set = &families.iter().find(|f| f.set.name == r.condition).ok_or("lost a support family")?.set;
        let plate = Plate::new(
            scene.plate.length() * r.scale,
            scene.plate.width() * r.scale,
            r.thickness,
            scene.plate.density(),
            scene.plate.material(),
        )?;
        let case = TransientCase::new(&plate, TransientSettings { elements: 2 * MAP_MESH, ..Default::default() })?;
        let sphere = scaled_body(body, r.radius / body.radius())?;
        let s = map_striker(scene, &plate, &sphere, v);
        let facts = case.facts(&set.supports, r.point.0, r.point.1);
        let m = measure(&case, set, facts, &s, r.point, r.compliance, r.measured.quasi_static_force, 2.0 * MAP_STEPS)?;
        let old = &r.measured;
        c.force = c
            .force
            .max((m.transient_force / old.transient_force - 1.0).abs())
            .max((m.impact_force / old.impact_force - 1.0).abs());
        if r.error() < 0.1 {
            c.near = c
                .near
                .max((m.force_error() - old.force_error()).abs())
                .max((m.impact_force_error() - old.impact_force_error()).abs());
        }
        if let (Some(a), Some(b)) = (m.time_error(), old.time_error()) {
            c.time = c.time.max((a - b).abs());
        }
        c.recount += usize::from(m.contacts != old.contacts);
        c.cases += 1;
    }
    Ok(c)
}
