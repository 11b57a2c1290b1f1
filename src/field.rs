//! `impact field`: the plate FE field under a point load, as JSON per unit load, as a .vtu
//! scaled by a given load or by an impact's quasi-static P_max, or, for the transient model,
//! as a ParaView time series of one contact.

use crate::cli::{FieldArgs, FieldFormat};
use crate::commands::load;
use crate::commit::commit_reporting;
use crate::written::{in_range, Written};
use crate::{note, out};
use coupled::SupportSet as Condition;
use impact::output::{OutputDir, OutputFile};
use impact::provenance::Provenance;
use impact::report::Failure;
use impact::scene::{limits, Scene};
use std::path::{Path, PathBuf};

/// The load of a .vtu: as given, or the impact's quasi-static P_max with the text and the
/// numbers that say so.
struct ImpactLoad {
    force: f64,
    text: String,
    numbers: Vec<(String, f64)>,
}

/// Runs `impact field`: every flag checked against the scene before the FE solve.
pub fn run(args: &FieldArgs) -> Result<(), Failure> {
    let scene = load(&args.scene)?;
    let (cond, force_n) = checked(args, &scene)?;
    let (x, z) = (args.x_mm * 1e-3, args.z_mm * 1e-3);
    if args.format == FieldFormat::Pvd {
        let (sphere, v) = impact_of(&scene, &args.body, &args.velocity_m_per_s)?;
        let target = OutputDir::prepare(args.out.clone().unwrap_or_else(|| PathBuf::from("field-series")))?;
        let mut a = impact::report::field_series::contact_series(&scene, cond, sphere, v, (x, z), args.elements)?;
        Provenance::of(&scene).stamp(&mut a);
        return commit_reporting(target, &a, &scene, args.json);
    }
    let path = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from(if args.format == FieldFormat::Json { "field.json" } else { "field.vtu" }));
    let target = OutputFile::prepare(&path)?;
    let f = impact::report::field::field(&scene, cond, x, z, args.elements)?;
    let (bytes, said) = match args.format {
        FieldFormat::Json => {
            (Provenance::of(&scene).stamp_json(format!("{}\n", serde_json::to_string(&f)?).as_bytes()), None)
        }
        FieldFormat::Vtu | FieldFormat::Pvd => vtu(args, &scene, cond, &f, force_n)?,
    };
    if target.is_stdout() {
        out(std::str::from_utf8(&bytes)?)?;
    } else if let Some(p) = target.commit(&bytes)? {
        note(&format!("wrote {}", p.display()));
        if args.json {
            print_written(&scene, &p, &bytes, said.as_ref())?;
        }
    }
    if let Some(load) = said {
        note(&load.text);
    }
    Ok(())
}

/// The scene's condition named by `--condition` and the load `--force-n`, after every check
/// of the flags against the scene and against each other.
fn checked<'a>(args: &FieldArgs, scene: &'a Scene) -> Result<(&'a Condition, Option<f64>), Failure> {
    if args.json && args.out.as_deref() == Some(Path::new("-")) {
        return Err("--json prints a summary of the files written; with --out - the field itself goes to standard output, so give one or the other".into());
    }
    let cond = scene.conditions.iter().find(|c| c.name == args.condition).ok_or_else(|| {
        let names: Vec<&str> = scene.conditions.iter().map(|c| c.name.as_str()).collect();
        format!("--condition '{}' is not in the scene; it has {names:?}", args.condition)
    })?;
    in_range("--elements", &args.elements.to_string(), args.elements as f64, limits::FIELD_ELEMENTS, "")?;
    let (l, b) = (scene.plate.length() * 1e3, scene.plate.width() * 1e3);
    if !(0.0..=l).contains(&args.x_mm) {
        return Err(format!("--x-mm {} is outside the plate: the allowed range is [0, {l}] mm", args.x_mm).into());
    }
    if !(0.0..=b).contains(&args.z_mm) {
        return Err(format!("--z-mm {} is outside the plate: the allowed range is [0, {b}] mm", args.z_mm).into());
    }
    let force_n = args.force_n.as_ref().map(|f| f.within("--force-n", limits::FORCE_N, "N")).transpose()?;
    // The JSON format is defined per unit load; a scaled JSON would read as one.
    if args.format != FieldFormat::Vtu && (force_n.is_some() || args.force_of_impact) {
        return Err("--force-n and --force-of-impact scale the .vtu only; add --format vtu (the JSON is per unit load, the .pvd at the impact's own force)".into());
    }
    if !(args.format == FieldFormat::Pvd || args.force_of_impact)
        && (args.body.is_some() || args.velocity_m_per_s.is_some())
    {
        return Err("--body and --velocity-m-per-s choose the impact of --format pvd or --force-of-impact only".into());
    }
    Ok((cond, force_n))
}

/// The .vtu of field `f`, scaled by `--force-n` (default 1 N) or by the impact's P_max.
fn vtu(
    args: &FieldArgs,
    scene: &Scene,
    cond: &Condition,
    f: &impact::report::field::FieldFile,
    force_n: Option<f64>,
) -> Result<(Vec<u8>, Option<ImpactLoad>), Failure> {
    let (x, z) = (args.x_mm * 1e-3, args.z_mm * 1e-3);
    let mut meta = impact::present::vtk::Metadata {
        provenance: Provenance::of(scene),
        lines: vec![format!(
            "impact field: the plate FE deflection, moments and stresses of '{}' under a point load at ({}, {}) mm on {} elements along the longer side",
            cond.name, args.x_mm, args.z_mm, args.elements
        )],
        numbers: vec![("load_x_m".into(), x), ("load_z_m".into(), z)],
    };
    let said = if args.force_of_impact { Some(impact_load(args, scene, cond)?) } else { None };
    let force = match &said {
        Some(load) => {
            meta.lines.push(load.text.clone());
            meta.numbers.extend(load.numbers.iter().cloned());
            load.force
        }
        None => {
            meta.lines.push(format!("scaled by the load given, {} N", force_n.unwrap_or(1.0)));
            force_n.unwrap_or(1.0)
        }
    };
    Ok((impact::present::vtk::to_vtu(f, force, &meta)?, said))
}

/// The quasi-static P_max of `--body` at `--velocity-m-per-s` at the load point, with its
/// error and validity as text and as the .vtu's field numbers.
fn impact_load(args: &FieldArgs, scene: &Scene, cond: &Condition) -> Result<ImpactLoad, Failure> {
    let (sphere, v) = impact_of(scene, &args.body, &args.velocity_m_per_s)?;
    let (x, z) = (args.x_mm * 1e-3, args.z_mm * 1e-3);
    let case = impact::report::field::quasi_static_impact(scene, cond, sphere, v, x, z)?;
    let what = format!("{} at {v} m/s on {} at ({}, {}) mm", sphere.name, cond.name, args.x_mm, args.z_mm);
    let text = impact::report::field::p_max_text(&case, &what)?;
    Ok(ImpactLoad { force: case.contact_force, text, numbers: case_numbers(&case, v) })
}

/// The impact `impact field` strikes: `--body` (default the scene's first) at
/// `--velocity-m-per-s` (default the scene's first), checked against the scene's ranges.
fn impact_of<'a>(
    scene: &'a Scene,
    body: &Option<String>,
    velocity: &Option<Written>,
) -> Result<(&'a analytic::Sphere, f64), Failure> {
    let sphere = match body {
        None => scene.bodies.first().ok_or("the scene has no body; give one in [[bodies]]")?,
        Some(b) => scene.bodies.iter().find(|s| &s.name == b).ok_or_else(|| {
            let names: Vec<&str> = scene.bodies.iter().map(|s| s.name.as_str()).collect();
            format!("--body '{b}' is not in the scene; it has {names:?}")
        })?,
    };
    let v = match velocity {
        Some(v) => v.within("--velocity-m-per-s", limits::VELOCITY_M_PER_S, "m/s")?,
        None => *scene.velocities.first().ok_or("the scene has no velocity; give --velocity-m-per-s")?,
    };
    Ok((sphere, v))
}

/// The field data of a .vtu scaled to a case's quasi-static P_max: the force's error, the
/// velocity, and every validity criterion's value and limit with `valid` (1 or 0).
fn case_numbers(case: &coupled::plan::ResponseValues, v: f64) -> Vec<(String, f64)> {
    let mut n = vec![("contact_force_N".to_string(), case.contact_force), ("velocity_m_per_s".into(), v)];
    if let Some(e) = case.contact_force_error {
        n.push(("contact_force_error_N".into(), e));
    }
    for (name, c) in case.validity.criteria() {
        let key = name.replace([' ', '-'], "_");
        n.push((format!("{key}_value"), c.value));
        n.push((format!("{key}_limit"), c.limit));
    }
    n.push(("valid".into(), f64::from(u8::from(case.validity.all_valid()))));
    n
}

/// The JSON summary of the file written: its path, size and SHA-256, and with
/// `--force-of-impact` what the load is, as the file's field data says; the provenance first,
/// as in every JSON document of ours.
fn print_written(scene: &Scene, path: &Path, bytes: &[u8], said: Option<&ImpactLoad>) -> Result<(), Failure> {
    let mut doc = serde_json::json!({
        "files": [{
            "path": path.to_string_lossy(),
            "bytes": bytes.len(),
            "sha256": impact::output::sha256_hex(bytes),
        }],
    });
    if let Some(load) = said {
        let map: serde_json::Map<String, serde_json::Value> =
            load.numbers.iter().map(|(k, v)| (k.clone(), serde_json::json!(v))).collect();
        doc["quasi_static_p_max"] = serde_json::json!({ "text": load.text, "numbers": map });
    }
    let doc = Provenance::of(scene).stamp_json(serde_json::to_string_pretty(&doc)?.as_bytes());
    out(&format!("{}\n", String::from_utf8(doc)?))
}
