//! Mutations of the small `[signals]`, `[ensemble]` and identification scenes, and the checks
//! their accepted forms must pass: the reduced model's impacts (a signals scene) or the first
//! impacts of the ensemble on its first support set (as Python's shards run them) end without a
//! panic, with every number finite (a first contact still open at the window's end has no
//! duration nor restitution: NaN there, and only there, is the model's answer).

#![allow(dead_code)]

use super::*;
use coupled::reduced::ReducedModel;

/// A scene to mutate and its numeric fields.
pub struct Base {
    pub name: &'static str,
    pub root: Value,
    pub fields: Vec<Field>,
}

/// The three bases: `[signals]` on one impact (Con 3, 16 modes, 5 ms at 10 kHz, a sensor),
/// the small ensemble (8 spheres a family on Con 2, 16 modes) and the identification study's
/// tiny ensemble (12 a family on Con 1).
pub fn bases() -> Vec<Base> {
    use crate::common::scenes::{signals, small_ensemble, TINY_IDENTIFY};
    let value = |t: &str| Value::Table(toml::from_str(t).expect("a test scene is TOML"));
    let f = |path: &'static str, range: Range| Field { path, range, also: unconstrained };
    let reduced = || {
        vec![
            f("signals.window_ms", limits::SIGNAL_WINDOW_MS),
            f("signals.rate_hz", limits::SAMPLE_RATE_HZ),
            f("signals.damping_ratio", coupled::reduced::ReducedSettings::DAMPING_RATIO),
            f("signals.modes", limits::MODES),
            f("signals.truncation_check_fraction", limits::TRUNCATION_CHECK),
            f("signals.sensors_mm[0][0]", POS_MM),
            f("plate.thickness_mm", limits::THICKNESS_MM),
            f("plate.width_mm", limits::PLATE_SIZE_MM),
        ]
    };
    let mut signals_fields = reduced();
    signals_fields.extend([
        f("velocities.m_per_s[0]", limits::VELOCITY_M_PER_S),
        f("bodies[0].radius_mm", limits::RADIUS_MM),
        f("conditions[0].spring_stiffness_n_per_m", limits::SPRING_N_PER_M),
    ]);
    let family =
        |i: usize, k: &str| -> &'static str { Box::leak(format!("ensemble.families[{i}].{k}").into_boxed_str()) };
    let mut ensemble_fields = reduced();
    ensemble_fields.extend([
        f("ensemble.seed", Range::closed(0.0, 1e18)),
        f("ensemble.placement.x_count", limits::POINT_COUNT),
        f("ensemble.velocity_m_per_s.max", limits::VELOCITY_M_PER_S),
        f(family(0, "count"), Range::closed(1.0, 1e6)),
        f(family(0, "radius_mm.min"), limits::RADIUS_MM),
        f(family(1, "radius_mm.max"), limits::RADIUS_MM),
        f(family(1, "density_kg_m3"), limits::DENSITY_KG_M3),
        f(family(0, "youngs_modulus_gpa"), limits::MODULUS_GPA),
    ]);
    vec![
        // 16 modes, as the ensembles: each accepted scene builds its reduced model.
        Base { name: "signals", root: value(&edit(&signals(), "modes = 40", "modes = 16")), fields: signals_fields },
        Base { name: "ensemble", root: value(&small_ensemble()), fields: ensemble_fields.clone() },
        Base { name: "identify", root: value(TINY_IDENTIFY), fields: ensemble_fields },
    ]
}

/// One mutation of a base: a hostile number in one of its fields, a key removed, or a
/// table replaced by a value of another type.
pub fn base_op(base: &Base, field: usize, pick: prop::sample::Index, kind: u8) -> Op {
    let f = &base.fields[field % base.fields.len()];
    let mut hints = vec![f.path.to_string(), leaf(f.path)];
    let parent = f.path.rsplit_once('.').map_or(f.path, |(p, _)| p);
    hints.push(parent.split('[').next().unwrap_or(parent).to_string());
    // A narrower plate moves the points and sensors off it.
    hints.extend(["pairs_mm".into(), "sensors_mm".into(), "plate".into()]);
    let (label, edit) = match kind % 8 {
        0 => (format!("{}: {} removed", base.name, f.path), Edit::Remove(f.path.into())),
        1 => (format!("{}: {} = a table", base.name, parent), Edit::Set(parent.into(), Value::Integer(3))),
        _ => {
            let o = get(&base.root, f.path).as_ref().and_then(num).unwrap_or(1.0);
            let v = pick.get(&hostile_values(o, f.range)).clone();
            (format!("{}: {} = {v:?}", base.name, f.path), Edit::Set(f.path.into(), v))
        }
    };
    Op { label, hints, expect: Expect::Unknown, edit }
}

/// Computes an accepted scene of a base: the impacts of a signals scene (one support set, body,
/// point and velocity), or the first `impacts` of an ensemble on its first support set.
pub fn run_reduced(stats: &mut Stats, label: &str, scene: &Scene, impacts: usize) {
    let outcome = guarded(|| -> Result<Vec<f64>, String> {
        if scene.ensemble.is_some() {
            ensemble_numbers(scene, impacts)
        } else {
            signals_numbers(scene)
        }
    });
    match outcome {
        Err(msg) => stats.fail("panic in the reduced model", || format!("{label} | {msg}")),
        Ok(Err(e)) => stats.run_error("reduced model", format!("{label} | {e}")),
        Ok(Ok(numbers)) => {
            stats.plate_runs += 1;
            stats.rows_checked += 1;
            if numbers.iter().any(|x| !x.is_finite()) {
                stats.fail("non-finite number from the reduced model", || label.to_string());
            }
        }
    }
}

/// The first contact's numbers and every sample of a signals scene's first impact.
fn signals_numbers(scene: &Scene) -> Result<Vec<f64>, String> {
    let mut s = limited(scene, 1, 1, 1, 1);
    s.transient_points.truncate(1);
    let (_, impacts) = coupled::reduced::plan::run(&s).map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    for i in &impacts {
        for q in [&i.quantities, &i.errors] {
            out.extend([q.peak_force, q.force_at_max_compression, q.compression]);
            // NaN while the first contact is still open at the window's end.
            out.extend([q.contact_time, q.restitution].into_iter().filter(|x| !x.is_nan()));
        }
        out.extend(i.result.signals.channels.iter().flat_map(|c| c.samples.iter().copied()));
    }
    Ok(out)
}

/// The contact numbers and features of the first `impacts` of the ensemble on its first set.
fn ensemble_numbers(scene: &Scene, impacts: usize) -> Result<Vec<f64>, String> {
    let set = &scene.conditions[0];
    let model = ReducedModel::new(&scene.plate, set, scene.signals.reduced()).map_err(|e| e.to_string())?;
    let n = scene.ensemble.as_ref().map_or(0, |e| e.ensemble.len()).min(impacts);
    let shard =
        studies::identify::ensemble::shard(scene, &model, &scene.signals.sensors, 0..n).map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    for (_, r) in &shard.records {
        out.extend([r.force_max, r.compression_ratio, r.hertz_time_ratio]);
        out.extend(r.contact_time);
        out.extend(r.features.iter().copied());
    }
    Ok(out)
}

/// Parses `text` and checks the refusal, or runs the reduced model on the accepted scene.
pub fn check_reduced_scene(stats: &mut Stats, label: &str, text: &str, hints: &[String], impacts: usize) {
    stats.generated += 1;
    match guarded(|| Scene::parse(text, "fuzz")) {
        Err(msg) => stats.fail("panic in Scene::parse", || format!("{label} | {msg}")),
        Ok(Err(e)) => check_refusal(stats, label, text, hints, Expect::Unknown, &e.to_string()),
        Ok(Ok(scene)) => {
            stats.parsed += 1;
            run_reduced(stats, label, &scene, impacts);
        }
    }
}
