//! Validation: every field checked against its range in the file's units, then converted to
//! SI once, into a [`Scene`].

use crate::limits;
use crate::raw::*;
use analytic::params::{check, Range, FRICTION_ANGLE_DEG, POISSON_RATIO};
use analytic::{Elastic, InvalidParameter, Method, Plate, RockStrength, Sphere};
use coupled::compliance::tail_beam::TailBeamScene;
use coupled::reduced::SignalSettings;
use coupled::scene::{Analysis, Points, Scene};
use coupled::transient::LawKind;
use coupled::SupportSet;

mod damping;
pub(crate) mod measurement;
mod plate_sweep;
mod points;
mod psd_file;
pub(crate) mod shell_mesh;
mod signals;
pub(crate) mod stream;
mod supports;
mod tail_beam;

use crate::{ensemble, slug, MAX_NAME_CHARS};
use points::{transient_points, validate_points};
use signals::validate_signals;
use supports::validate_condition;

pub(crate) enum Invalid {
    Range(InvalidParameter),
    Other { field: String, message: String },
}

impl From<InvalidParameter> for Invalid {
    fn from(e: InvalidParameter) -> Self {
        Self::Range(e)
    }
}

pub(crate) fn other(field: impl Into<String>, message: impl Into<String>) -> Invalid {
    Invalid::Other { field: field.into(), message: message.into() }
}

pub(crate) const MM: f64 = 1e-3;
pub(crate) const GPA: f64 = 1e9;
pub(crate) const MPA: f64 = 1e6;

/// The file-name stems of the names checked so far, each with its name: a set, so that
/// checking n names is linear (a list compared each name with every earlier one, and 8,000
/// support sets took seconds to load).
pub(crate) type Names = std::collections::HashMap<String, String>;

/// Checks a display name: not empty, not too long, and distinct from the names before it
/// (`earlier`, to which it is added) even after reduction to a file-name stem (reports name
/// files after it: "A" and "a!" would write the same file).
pub(crate) fn check_name(field: String, name: &str, earlier: &mut Names) -> Result<(), Invalid> {
    if name.trim().is_empty() {
        return Err(other(field, "is empty; give it a name"));
    }
    let n = name.chars().count();
    if n > MAX_NAME_CHARS {
        return Err(other(field, format!("is {n} characters long; the allowed range is [1, {MAX_NAME_CHARS}]")));
    }
    let stem = slug(name);
    if stem.is_empty() {
        return Err(other(field, format!("'{name}' has no letter or digit; file names are made from it")));
    }
    if let Some(e) = earlier.get(&stem) {
        return Err(other(
            field,
            format!(
                "'{name}' and '{e}' give the same file name '{stem}'; names must differ in their letters or digits"
            ),
        ));
    }
    earlier.insert(stem, name.to_string());
    Ok(())
}

/// A whole count written as a TOML number, in `allowed` (a range of whole ends).
pub(crate) fn count(field: &str, value: f64, allowed: Range) -> Result<usize, Invalid> {
    let v = check(field, value, allowed, "")?;
    if v.fract() != 0.0 {
        return Err(other(field, format!("{value} is not a whole number; the allowed range is {allowed}")));
    }
    Ok(v as usize)
}

/// A list entry that must be exactly two numbers (`shape` says which, "[x, z]"): serde's
/// tuples read the first two of a longer TOML array and drop the rest without a word.
pub(crate) fn pair(field: &str, v: &[f64], shape: &str) -> Result<(f64, f64), Invalid> {
    match v {
        [a, b] => Ok((*a, *b)),
        _ => Err(other(field, format!("has {} numbers; give exactly two, {shape}", v.len()))),
    }
}

/// Checks every field against its range, in the units of the file, then converts to SI.
pub(crate) fn validate(raw: RawScene) -> Result<Scene, Invalid> {
    let restitution = check("restitution", raw.restitution, limits::RESTITUTION, "")?;
    let contact_law = contact_law(raw.contact_law.as_deref())?;
    check_name("name".into(), &raw.name, &mut Names::new())?;
    let plate = validate_plate(&raw.plate, "plate")?;
    let (length_mm, width_mm) = (raw.plate.length_mm, raw.plate.width_mm);
    let analyses = validate_analyses(&raw.analyses)?;
    // Every analysis but identification and the drops strikes the scene's bodies at its
    // points; the identification study draws its own from [ensemble], the drops come with
    // their recording.
    let needs_bodies = analyses.iter().any(|a| !matches!(a, Analysis::Identify | Analysis::Drops));
    if raw.bodies.is_empty() && needs_bodies {
        return Err(other("bodies", "at least one [[bodies]] entry is required"));
    }
    let bodies = validate_bodies(&raw.bodies)?;
    let conditions = validate_conditions(&raw.conditions, &plate)?;
    // A structure from a mesh file is struck at its own points, in its own frame.
    let needs_points =
        analyses.iter().any(|a| !matches!(a, Analysis::Identify | Analysis::Drops | Analysis::ShellMesh));
    let points = match &raw.points {
        Some(p) => validate_points(p, &plate, length_mm, width_mm)?,
        None if needs_points => {
            return Err(other("points", "a [points] table is required (x_mm, count, pairs_mm or [points.grid])"))
        }
        None => Points::Pairs { pairs: vec![] },
    };
    let gravity = gravity(&raw, &analyses)?;
    let plate_damping = raw.plate_damping.as_ref().map(damping::validate_plate_damping).transpose()?;
    let transient_points = match &raw.transient {
        None => points.pairs(),
        Some(t) => transient_points(t, &plate, length_mm, width_mm)?,
    };
    let velocities = validate_velocities(raw.velocities.as_ref(), &analyses)?;
    let responses = if analyses.contains(&Analysis::Responses) { velocities.len() } else { 0 };
    let yields = analyses.contains(&Analysis::YieldVelocity);
    if let Some(why) = limits::quasi_static_excess(conditions.len(), points.len(), bodies.len(), responses, yields) {
        return Err(other("conditions, points, bodies and velocities", why));
    }
    let tail_beam = tail_beam::table(raw.tail_beam.as_ref(), &analyses)?;
    let face_mm = struck_face(tail_beam.as_ref(), &analyses, (length_mm, width_mm));
    let signals = validate_signals(raw.signals.as_ref(), face_mm.0, face_mm.1, plate_damping, face_mm.2)?;
    let ensemble = validate_ensemble(raw.ensemble.as_ref(), &analyses, face_mm.0, face_mm.1)?;
    let (measurement, stream, stream_law_sweep) =
        chain_and_stream(&raw, &analyses, &signals, conditions.len(), ensemble.as_ref())?;
    tail_beam::check_stream(!face_mm.2, &signals, measurement.as_ref())?;
    let stream_plate_sweep = plate_sweep::validate(&raw, face_mm.2, &signals, ensemble.as_ref())?;
    if let (Some(study), Some(ensemble)) = (&stream, &ensemble) {
        stream::check_design(study, ensemble, measurement.as_ref(), (face_mm.2, signals.rate_hz))?;
    }
    let shell_mesh = shell_mesh::table(raw.shell_mesh.as_ref(), &analyses, &plate)?;
    Ok(Scene {
        velocities,
        signals,
        measurement,
        stream,
        stream_law_sweep,
        stream_plate_sweep,
        solver: validate_solver(&raw.solver)?,
        ensemble,
        name: raw.name,
        description: raw.description,
        plate,
        bodies,
        restitution,
        contact_law,
        gravity,
        plate_damping,
        conditions,
        points,
        transient_points,
        analyses,
        transient_discretisation: coupled::transient::Discretisation::default(),
        main_contact_share: coupled::transient::chatter::MAIN_CONTACT_SHARE,
        tail_beam,
        shell_mesh,
    })
}

/// The face the identification's lumps strike, (length, width) in mm, and whether it is the
/// plate's: a tail-beam scene's identification strikes the box, its lumps' region and its
/// sensors on the box's top face (x along the beam, z across).
fn struck_face(tail_beam: Option<&TailBeamScene>, analyses: &[Analysis], plate_mm: (f64, f64)) -> (f64, f64, bool) {
    match tail_beam {
        Some(tb) if analyses.contains(&Analysis::Identify) => (tb.beam.length / MM, tb.beam.width / MM, false),
        _ => (plate_mm.0, plate_mm.1, true),
    }
}

/// `[measurement]` and `[stream]`, both read only by the identification: the chain, the
/// stream study and its law sweep, the size sweep's radii checked against `ensemble`'s laws.
#[allow(clippy::type_complexity)]
fn chain_and_stream(
    raw: &RawScene,
    analyses: &[Analysis],
    signals: &SignalSettings,
    conditions: usize,
    ensemble: Option<&identify::Study>,
) -> Result<(Option<identify::measurement::ChainSpec>, Option<identify::stream::StreamStudy>, Vec<LawKind>), Invalid> {
    let reads_chain = analyses.iter().any(|a| matches!(a, Analysis::Identify | Analysis::Drops));
    let measurement = match (&raw.measurement, reads_chain) {
        (None, _) => None,
        (Some(m), true) => {
            Some(measurement::validate_measurement(m, signals.rate_hz, signals.window * signals.rate_hz)?)
        }
        (Some(_), false) => {
            return Err(other(
                "measurement",
                "is read only by the \"identify\" and \"drops\" analyses; add one to analyses or remove the table",
            ))
        }
    };
    if analyses.contains(&Analysis::Drops) && measurement.is_none() {
        return Err(other(
            "measurement",
            "the \"drops\" analysis reads recordings through the rig's measurement chain, and the scene has no [measurement] table (its sensors' band, ADC and background make the bar's noise term)",
        ));
    }
    if ensemble.is_some_and(|e| !e.design_backgrounds.is_empty()) {
        let stated =
            measurement.as_ref().map(|m| m.recordings.iter().any(|r| r.background.is_some() || !r.tones.is_empty()));
        let why = match stated {
            None => Some("scales [measurement]'s background; the scene has no [measurement]"),
            Some(false) => Some("scales [measurement]'s background, and its recordings state none (no noise, no tones): every level would be the stated one"),
            Some(true) => None,
        };
        if let Some(why) = why {
            return Err(other("ensemble.placement.design_backgrounds", why));
        }
    }
    if signals.modes_from_chain && measurement.is_none() {
        return Err(other(
            "signals.modes",
            "\"chain\" keeps the modes the measurement chain needs; the scene has no [measurement]",
        ));
    }
    let (stream, laws) = match (&raw.stream, analyses.contains(&Analysis::Identify)) {
        (None, _) => (None, Vec::new()),
        (Some(s), true) => {
            let adc = measurement.as_ref().map_or(signals.rate_hz, |m| m.rate_hz);
            let (study, laws) = stream::validate_stream(s, signals, (adc, measurement.is_some()), conditions)?;
            (Some(study), laws)
        }
        (Some(_), false) => {
            return Err(other(
                "stream",
                "draws its lumps from [ensemble], read only by the \"identify\" analysis; add \"identify\" to analyses or remove the table",
            ))
        }
    };
    if let (Some(study), Some(ensemble)) = (&stream, ensemble) {
        stream::check_size_sweep(study, ensemble)?;
    }
    Ok((measurement, stream, laws))
}

/// `gravity_m_per_s2`, m/s². A caving stream's lumps fall onto the plate (its speeds are fall
/// heights), and so do a drop test's, so gravity acts on them by default there; an ensemble of
/// given velocities is the paper's impact.
fn gravity(raw: &RawScene, analyses: &[Analysis]) -> Result<f64, Invalid> {
    let falls = raw.ensemble.as_ref().is_some_and(|e| e.fall_height_m.is_some()) || analyses.contains(&Analysis::Drops);
    Ok(match raw.gravity_m_per_s2 {
        Some(g) => check("gravity_m_per_s2", g, limits::GRAVITY_M_PER_S2, "m/s²")?,
        None if falls => identify::ensemble::GRAVITY,
        None => 0.0,
    })
}

/// `contact_law`: a key of the law registry, or the default law.
fn contact_law(name: Option<&str>) -> Result<LawKind, Invalid> {
    name.map_or(Ok(LawKind::default()), |name| law_key("contact_law", name))
}

/// A key of the law registry at `field`.
pub(crate) fn law_key(field: &str, name: &str) -> Result<LawKind, Invalid> {
    LawKind::from_key(name).ok_or_else(|| {
        let keys: Vec<_> = LawKind::ALL.iter().map(|l| format!("\"{}\"", l.key())).collect();
        other(field, format!("'{name}' is not a contact law; allowed: {}", keys.join(", ")))
    })
}

/// `[plate]`: material, size and density, a plate (not a strip, not a block); each field
/// named under `table` ("plate", or a swept plate's "stream.plate_sweep[k]").
pub(crate) fn validate_plate(p: &RawPlate, table: &str) -> Result<Plate, Invalid> {
    let field = |key: &str| format!("{table}.{key}");
    let plate_material = Elastic::new(
        check(&field("youngs_modulus_gpa"), p.youngs_modulus_gpa, limits::MODULUS_GPA, "GPa")? * GPA,
        check(&field("poisson_ratio"), p.poisson_ratio, POISSON_RATIO, "")?,
    )?;
    let length_mm = check(&field("length_mm"), p.length_mm, limits::PLATE_SIZE_MM, "mm")?;
    let width_mm = check(&field("width_mm"), p.width_mm, limits::PLATE_SIZE_MM, "mm")?;
    let thickness_mm = check(&field("thickness_mm"), p.thickness_mm, limits::THICKNESS_MM, "mm")?;
    let aspect = length_mm.max(width_mm) / length_mm.min(width_mm);
    if aspect > limits::MAX_ASPECT_RATIO {
        return Err(other(
            format!("{} and {}", field("length_mm"), field("width_mm")),
            format!(
                "{length_mm} mm by {width_mm} mm is an aspect ratio of {}; the allowed range is [1, {}] (a narrower plate is a strip: model it as the beam it is)",
                analytic::params::compact(aspect),
                limits::MAX_ASPECT_RATIO
            ),
        ));
    }
    if thickness_mm > length_mm.min(width_mm) {
        return Err(other(
            field("thickness_mm"),
            format!(
                "{thickness_mm} mm is more than the plate's smaller side {} mm: not a plate; allowed [{}, {}] mm",
                length_mm.min(width_mm),
                limits::THICKNESS_MM.lo,
                length_mm.min(width_mm)
            ),
        ));
    }
    Ok(Plate::new(
        length_mm * MM,
        width_mm * MM,
        thickness_mm * MM,
        check(&field("density_kg_m3"), p.density_kg_m3, limits::DENSITY_KG_M3, "kg/m^3")?,
        plate_material,
    )?)
}

/// `analyses`: not empty; each named once (a repeat is dropped).
fn validate_analyses(raw: &[Analysis]) -> Result<Vec<Analysis>, Invalid> {
    if raw.is_empty() {
        let keys: Vec<&str> = Analysis::ALL.iter().map(|a| a.key()).collect();
        return Err(other("analyses", format!("the list is empty; allowed entries: {}", keys.join(", "))));
    }
    let mut analyses: Vec<Analysis> = Vec::new();
    for &a in raw {
        if !analyses.contains(&a) {
            analyses.push(a);
        }
    }
    Ok(analyses)
}

/// `[[bodies]]`: each sphere's material, strength, density, radius and a distinct name.
fn validate_bodies(raw: &[RawBody]) -> Result<Vec<Sphere>, Invalid> {
    let mut bodies = Vec::with_capacity(raw.len());
    let mut names = Names::new();
    for (i, b) in raw.iter().enumerate() {
        let f = |k: &str| format!("bodies[{i}].{k}");
        let material = Elastic::new(
            check(&f("youngs_modulus_gpa"), b.youngs_modulus_gpa, limits::MODULUS_GPA, "GPa")? * GPA,
            check(&f("poisson_ratio"), b.poisson_ratio, POISSON_RATIO, "")?,
        )?;
        let strength = RockStrength::new(
            check(&f("cohesion_mpa"), b.cohesion_mpa, limits::COHESION_MPA, "MPa")? * MPA,
            check(&f("friction_angle_deg"), b.friction_angle_deg, FRICTION_ANGLE_DEG, "deg")?,
        )?;
        let density = check(&f("density_kg_m3"), b.density_kg_m3, limits::DENSITY_KG_M3, "kg/m^3")?;
        let radius = check(&f("radius_mm"), b.radius_mm, limits::RADIUS_MM, "mm")? * MM;
        check_name(f("name"), &b.name, &mut names)?;
        bodies.push(Sphere::new(b.name.clone(), density, radius, material, strength)?);
    }
    Ok(bodies)
}

/// `[[conditions]]`: at least one support set, each with a distinct name.
fn validate_conditions(raw: &[RawCondition], plate: &Plate) -> Result<Vec<SupportSet>, Invalid> {
    if raw.is_empty() {
        return Err(other("conditions", "at least one [[conditions]] entry is required"));
    }
    let mut conditions: Vec<SupportSet> = Vec::with_capacity(raw.len());
    let mut names = Names::new();
    for (i, c) in raw.iter().enumerate() {
        let set = validate_condition(i, c, plate)?;
        check_name(format!("conditions[{i}].name"), &set.name, &mut names)?;
        conditions.push(set);
    }
    Ok(conditions)
}

/// `[velocities]`: required by the analyses that strike at a velocity, each in range.
fn validate_velocities(raw: Option<&RawVelocities>, analyses: &[Analysis]) -> Result<Vec<f64>, Invalid> {
    let needs_velocity = analyses.iter().any(|a| {
        matches!(
            a,
            Analysis::Responses
                | Analysis::Transient
                | Analysis::SizeMap
                | Analysis::RegimeMaps
                | Analysis::TailBeam
                | Analysis::ShellMesh
        )
    });
    match raw {
        Some(v) => {
            if v.m_per_s.is_empty() {
                return Err(other("velocities.m_per_s", "the list is empty; give at least one velocity"));
            }
            let mut out = Vec::with_capacity(v.m_per_s.len());
            for (j, &vel) in v.m_per_s.iter().enumerate() {
                out.push(check(&format!("velocities.m_per_s[{j}]"), vel, limits::VELOCITY_M_PER_S, "m/s")?);
            }
            Ok(out)
        }
        None if needs_velocity => Err(other(
            "velocities.m_per_s",
            "is required when analyses include \"responses\", \"transient\", \"size-map\", \"regime-maps\", \"tail-beam\" or \"shell-mesh\"",
        )),
        None => Ok(vec![]),
    }
}

/// `[solver]`: the root finder of the energy balance with its tolerance and iteration cap.
fn validate_solver(raw: &RawSolver) -> Result<Method, Invalid> {
    let tolerance = check("solver.tolerance", raw.tolerance, limits::SOLVER_TOLERANCE, "")?;
    if !limits::SOLVER_ITERATIONS.contains(f64::from(raw.max_iterations)) {
        return Err(other(
            "solver.max_iterations",
            format!("{} is outside the allowed range {}", raw.max_iterations, limits::SOLVER_ITERATIONS),
        ));
    }
    Ok(match raw.method {
        MethodName::Recursion => Method::Recursion { tolerance, max_iterations: raw.max_iterations },
        MethodName::Bracketed => Method::Bracketed { tolerance, max_iterations: raw.max_iterations },
    })
}

/// `[ensemble]`: present exactly when the "identify" analysis is asked for.
fn validate_ensemble(
    raw: Option<&ensemble::RawEnsemble>,
    analyses: &[Analysis],
    length_mm: f64,
    width_mm: f64,
) -> Result<Option<identify::Study>, Invalid> {
    match (raw, analyses.contains(&Analysis::Identify)) {
        (Some(e), true) => Ok(Some(ensemble::validate_ensemble(e, length_mm, width_mm)?)),
        (None, false) => Ok(None),
        (None, true) => {
            Err(other("ensemble", "the \"identify\" analysis needs an [ensemble] table (the random impacts)"))
        }
        (Some(_), false) => Err(other(
            "ensemble",
            "is read only by the \"identify\" analysis; add \"identify\" to analyses or remove the table",
        )),
    }
}
