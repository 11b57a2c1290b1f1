//! The `[ensemble]` table: the random impacts of the identification study, checked in the
//! file's units and converted to SI once.
//!
//! Every random variable is either a number (fixed) or a table naming its law:
//!
//! ```toml
//! radius_mm = { distribution = "rosin-rammler", scale = 30.0, shape = 2.0, min = 10.0, max = 60.0 }
//! density_kg_m3 = { distribution = "normal", mean = 1380.0, sd = 60.0, min = 1200.0, max = 1600.0 }
//! youngs_modulus_gpa = { distribution = "lognormal", median = 2.26, sigma_log = 0.3, min = 1.0, max = 6.0 }
//! fall_height_m = { distribution = "uniform", min = 0.3, max = 2.0 }
//! velocity_m_per_s = { distribution = "choice", values = [0.008, 0.0025] }
//! ```
//!
//! The bounds of every continuous law are required: they confine the draws to the field's
//! allowed range, so nothing drawn can leave it.

use super::{count, limits, other, Invalid};
use analytic::params::{check, Range, FRICTION_ANGLE_DEG, POISSON_RATIO};
use identify::distribution::InvalidDistribution;
use identify::{Class, Distribution, Ensemble, Family, Region, Speed, Study, Variable};
use serde::Deserialize;

/// Most impacts of one ensemble (over all families): each costs a reduced-order run and its
/// feature row; a million is minutes per support set and hundreds of MB of features.
pub const MAX_IMPACTS: usize = 1_000_000;
/// Most candidate sensor points along one side of a placement grid.
pub const MAX_CANDIDATES_PER_SIDE: usize = 41;
/// Candidate sensor points along each side of a placement grid: two reach both edges.
pub const CANDIDATES_PER_SIDE: Range = Range::closed(2.0, MAX_CANDIDATES_PER_SIDE as f64);
/// Sensors a design chooses: step k fits a cross-validated classifier for every candidate
/// left on the 6k features of the k sensors, each fit of cost ~(6k)² per impact, so the whole
/// design grows as the budget to the fourth; eight sensors of one kind on one support are
/// beyond any rig.
pub const DESIGN_SENSORS: Range = Range::closed(1.0, 8.0);
/// Most backgrounds the sensor design is chosen again at: each reruns the ensemble on the
/// whole candidate grid, so eight levels cost eight main runs, about what the variability
/// study's held runs cost.
pub const MAX_DESIGN_BACKGROUNDS: usize = 8;
/// Impacts of one family.
pub const FAMILY_COUNT: Range = Range::closed(1.0, MAX_IMPACTS as f64);
/// Fall heights, m: up to 1 km (a free fall of 140 m/s, far beyond any caving).
pub const FALL_HEIGHT_M: Range = Range::closed(1e-12, 1e3);

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawEnsemble {
    seed: u64,
    #[serde(default)]
    hold: Option<Vec<String>>,
    #[serde(default)]
    pub(crate) region: Option<RawRegion>,
    #[serde(default)]
    pub(crate) fall_height_m: Option<toml::Value>,
    #[serde(default)]
    velocity_m_per_s: Option<toml::Value>,
    #[serde(default)]
    placement: Option<RawPlacement>,
    families: Vec<RawFamily>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRegion {
    x_mm: Vec<f64>,
    z_mm: Vec<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawPlacement {
    x_count: f64,
    z_count: f64,
    #[serde(default)]
    design_sensors: Option<f64>,
    #[serde(default)]
    design_backgrounds: Vec<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawFamily {
    name: String,
    class: String,
    count: f64,
    density_kg_m3: toml::Value,
    youngs_modulus_gpa: toml::Value,
    poisson_ratio: toml::Value,
    cohesion_mpa: toml::Value,
    friction_angle_deg: toml::Value,
    radius_mm: toml::Value,
}

/// The keys each law takes, besides `distribution`.
pub(super) const LAWS: [(&str, &[&str]); 5] = [
    ("uniform", &["min", "max"]),
    ("normal", &["mean", "sd", "min", "max"]),
    ("lognormal", &["median", "sigma_log", "min", "max"]),
    ("rosin-rammler", &["scale", "shape", "min", "max"]),
    ("choice", &["values"]),
];

fn number(field: &str, v: &toml::Value) -> Result<f64, Invalid> {
    match v {
        toml::Value::Float(f) => Ok(*f),
        toml::Value::Integer(i) => Ok(*i as f64),
        other_value => Err(other(field, format!("{other_value} is not a number"))),
    }
}

/// A number (fixed) or a law table, checked against `allowed` in the file's unit and
/// scaled by `to_si`.
fn distribution(
    field: &str,
    v: &toml::Value,
    allowed: Range,
    unit: &'static str,
    to_si: f64,
) -> Result<Distribution, Invalid> {
    let law = match v {
        toml::Value::Float(_) | toml::Value::Integer(_) => Distribution::Fixed { value: number(field, v)? },
        toml::Value::Table(t) => law_table(field, t)?,
        other_value => {
            return Err(other(field, format!("{other_value} is neither a number nor a {{ distribution = ... }} table")))
        }
    };
    let checked = law.checked(allowed, unit).map_err(|e| match e {
        InvalidDistribution::Range(mut p) => {
            p.name = if p.name == "value" { field.to_string() } else { format!("{field}.{}", p.name) };
            Invalid::Range(p)
        }
        InvalidDistribution::Inconsistent { parameter, message } => other(format!("{field}.{parameter}"), message),
    })?;
    let si = checked.scaled(to_si);
    if !si.is_drawable() {
        return Err(other(
            field,
            format!("{v} gives no finite draws between its bounds once converted to SI units; widen its spread or move its location toward the bounds"),
        ));
    }
    Ok(si)
}

/// A `{ distribution = "...", ... }` table: a law of [`LAWS`] with exactly its parameters.
fn law_table(field: &str, t: &toml::map::Map<String, toml::Value>) -> Result<Distribution, Invalid> {
    let names: Vec<&str> = LAWS.iter().map(|(n, _)| *n).collect();
    let Some(toml::Value::String(kind)) = t.get("distribution") else {
        return Err(other(
            format!("{field}.distribution"),
            format!("is required: one of {}, or give a plain number for a fixed value", names.join(", ")),
        ));
    };
    let kind = kind.as_str();
    let Some((_, keys)) = LAWS.iter().find(|(n, _)| *n == kind) else {
        return Err(other(
            format!("{field}.distribution"),
            format!("'{kind}' is not a distribution; allowed: {}", names.join(", ")),
        ));
    };
    if let Some(k) = t.keys().find(|k| *k != "distribution" && !keys.contains(&k.as_str())) {
        return Err(other(
            format!("{field}.{k}"),
            format!("is not a parameter of the {kind} law; it takes {}", keys.join(", ")),
        ));
    }
    let get = |k: &str| -> Result<f64, Invalid> {
        match t.get(k) {
            Some(v) => number(&format!("{field}.{k}"), v),
            None => Err(other(format!("{field}.{k}"), format!("is required by the {kind} law ({})", keys.join(", ")))),
        }
    };
    Ok(match kind {
        "uniform" => Distribution::Uniform { min: get("min")?, max: get("max")? },
        "normal" => Distribution::Normal { mean: get("mean")?, sd: get("sd")?, min: get("min")?, max: get("max")? },
        "lognormal" => Distribution::LogNormal {
            median: get("median")?,
            sigma_log: get("sigma_log")?,
            min: get("min")?,
            max: get("max")?,
        },
        "rosin-rammler" => Distribution::RosinRammler {
            scale: get("scale")?,
            shape: get("shape")?,
            min: get("min")?,
            max: get("max")?,
        },
        _ => {
            let Some(toml::Value::Array(list)) = t.get("values") else {
                return Err(other(format!("{field}.values"), "is required by the choice law: a list of numbers"));
            };
            let values = list
                .iter()
                .enumerate()
                .map(|(j, v)| number(&format!("{field}.values[{j}]"), v))
                .collect::<Result<Vec<f64>, Invalid>>()?;
            Distribution::Choice { values }
        }
    })
}

const MM: f64 = 1e-3;

/// Checks the `[ensemble]` table against the plate (length and width in mm).
pub(super) fn validate_ensemble(raw: &RawEnsemble, length_mm: f64, width_mm: f64) -> Result<Study, Invalid> {
    let region = region(raw.region.as_ref(), length_mm, width_mm)?;
    let speed = match (&raw.fall_height_m, &raw.velocity_m_per_s) {
        (Some(h), None) => Speed::FallHeight(distribution("ensemble.fall_height_m", h, FALL_HEIGHT_M, "m", 1.0)?),
        (None, Some(v)) => {
            Speed::Velocity(distribution("ensemble.velocity_m_per_s", v, limits::VELOCITY_M_PER_S, "m/s", 1.0)?)
        }
        _ => {
            return Err(other(
                "ensemble",
                "give exactly one of fall_height_m (free fall from rest, v = √(2gh)) or velocity_m_per_s",
            ))
        }
    };
    let families = families(&raw.families)?;
    let hold = hold(raw.hold.as_deref())?;
    let (candidates_x, candidates_z, design_sensors, design_backgrounds) = match &raw.placement {
        None => (vec![], vec![], 0, vec![]),
        Some(p) => {
            // A map needs two points a side: the grid runs from edge to edge.
            let nx = count("ensemble.placement.x_count", p.x_count, CANDIDATES_PER_SIDE)?;
            let nz = count("ensemble.placement.z_count", p.z_count, CANDIDATES_PER_SIDE)?;
            let design = match p.design_sensors {
                None => 0,
                Some(b) => count("ensemble.placement.design_sensors", b, DESIGN_SENSORS)?,
            };
            if design > nx * nz {
                return Err(other(
                    "ensemble.placement.design_sensors",
                    format!(
                        "{design} sensors among {} candidate points ({nx} x {nz}); allowed at most {}",
                        nx * nz,
                        nx * nz
                    ),
                ));
            }
            let backgrounds = design_backgrounds(&p.design_backgrounds, design)?;
            (super::even_points(length_mm * MM, nx), super::even_points(width_mm * MM, nz), design, backgrounds)
        }
    };
    let ensemble = Ensemble { region, speed, families, seed: raw.seed };
    Ok(Study { ensemble, candidates_x, candidates_z, hold, design_sensors, design_backgrounds })
}

/// `ensemble.placement.design_backgrounds`: scales of the chain's background, each in
/// [0, 1e6], for a design that exists (`design` sensors). Whether the scene has a chain to
/// scale is checked where the chain is read.
fn design_backgrounds(scales: &[f64], design: usize) -> Result<Vec<f64>, Invalid> {
    if !scales.is_empty() && design == 0 {
        return Err(other(
            "ensemble.placement.design_backgrounds",
            "repeats the sensor design at other backgrounds, and the scene asks for none: give design_sensors",
        ));
    }
    if scales.len() > MAX_DESIGN_BACKGROUNDS {
        return Err(other(
            "ensemble.placement.design_backgrounds",
            format!(
                "{} levels; allowed at most {MAX_DESIGN_BACKGROUNDS} (each reruns the ensemble on the whole grid)",
                scales.len()
            ),
        ));
    }
    let field = |i: usize| format!("ensemble.placement.design_backgrounds[{i}]");
    scales.iter().enumerate().map(|(i, &s)| Ok(check(&field(i), s, Range::closed(0.0, 1e6), "")?)).collect()
}

/// `ensemble.region`: where the lumps strike, inside the plate; the whole plate by default.
fn region(raw: Option<&RawRegion>, length_mm: f64, width_mm: f64) -> Result<Region, Invalid> {
    let Some(r) = raw else {
        return Ok(Region { x: (0.0, length_mm * MM), z: (0.0, width_mm * MM) });
    };
    let along = Range::closed(0.0, length_mm);
    let across = Range::closed(0.0, width_mm);
    let (x0, x1) = super::pair("ensemble.region.x_mm", &r.x_mm, "[low, high]")?;
    let (z0, z1) = super::pair("ensemble.region.z_mm", &r.z_mm, "[low, high]")?;
    let x0 = check("ensemble.region.x_mm[0]", x0, along, "mm")?;
    let x1 = check("ensemble.region.x_mm[1]", x1, along, "mm")?;
    let z0 = check("ensemble.region.z_mm[0]", z0, across, "mm")?;
    let z1 = check("ensemble.region.z_mm[1]", z1, across, "mm")?;
    if x0 > x1 || z0 > z1 {
        return Err(other("ensemble.region", "give each side as [low, high] with low ≤ high"));
    }
    Ok(Region { x: (x0 * MM, x1 * MM), z: (z0 * MM, z1 * MM) })
}

/// `[[ensemble.families]]`: distinct names, a class each, counts within the impact budget,
/// and both classes present (telling coal from gangue needs both).
fn families(raw: &[RawFamily]) -> Result<Vec<Family>, Invalid> {
    if raw.is_empty() {
        return Err(other("ensemble.families", "at least one [[ensemble.families]] entry is required"));
    }
    let mut families: Vec<Family> = Vec::with_capacity(raw.len());
    let mut total = 0usize;
    let mut names = super::validate::Names::new();
    for (i, f) in raw.iter().enumerate() {
        let key = |k: &str| format!("ensemble.families[{i}].{k}");
        super::check_name(key("name"), &f.name, &mut names)?;
        let class = match f.class.as_str() {
            "coal" => Class::Coal,
            "gangue" => Class::Gangue,
            c => return Err(other(key("class"), format!("'{c}' is not a class; allowed: \"coal\", \"gangue\""))),
        };
        let n = count(&key("count"), f.count, FAMILY_COUNT)?;
        total += n;
        if total > MAX_IMPACTS {
            return Err(other(
                key("count"),
                format!("the families' counts add up to {total}; at most {MAX_IMPACTS} impacts"),
            ));
        }
        families.push(family(f, class, n, &key)?);
    }
    for class in [Class::Coal, Class::Gangue] {
        if !families.iter().any(|f| f.class == class) {
            return Err(other(
                "ensemble.families",
                format!("no family has class = \"{}\"; telling coal from gangue needs both", class.key()),
            ));
        }
    }
    Ok(families)
}

/// One family's laws, each in its range and converted to SI.
fn family(f: &RawFamily, class: Class, count: usize, key: &dyn Fn(&str) -> String) -> Result<Family, Invalid> {
    Ok(Family {
        name: f.name.clone(),
        class,
        count,
        density: distribution(&key("density_kg_m3"), &f.density_kg_m3, limits::DENSITY_KG_M3, "kg/m^3", 1.0)?,
        youngs_modulus: distribution(
            &key("youngs_modulus_gpa"),
            &f.youngs_modulus_gpa,
            limits::MODULUS_GPA,
            "GPa",
            1e9,
        )?,
        poisson_ratio: distribution(&key("poisson_ratio"), &f.poisson_ratio, POISSON_RATIO, "", 1.0)?,
        cohesion: distribution(&key("cohesion_mpa"), &f.cohesion_mpa, limits::COHESION_MPA, "MPa", 1e6)?,
        friction_angle_deg: distribution(
            &key("friction_angle_deg"),
            &f.friction_angle_deg,
            FRICTION_ANGLE_DEG,
            "deg",
            1.0,
        )?,
        radius: distribution(&key("radius_mm"), &f.radius_mm, limits::RADIUS_MM, "mm", MM)?,
    })
}

/// `ensemble.hold`: the variables held at their medians one at a time (every variable by
/// default), each named once.
fn hold(raw: Option<&[String]>) -> Result<Vec<Variable>, Invalid> {
    let Some(list) = raw else { return Ok(Variable::ALL.to_vec()) };
    let mut out = Vec::new();
    for (j, name) in list.iter().enumerate() {
        let v = Variable::ALL.into_iter().find(|v| v.key() == name).ok_or_else(|| {
            let keys: Vec<&str> = Variable::ALL.iter().map(|v| v.key()).collect();
            other(format!("ensemble.hold[{j}]"), format!("'{name}' is not a variable; allowed: {}", keys.join(", ")))
        })?;
        if !out.contains(&v) {
            out.push(v);
        }
    }
    Ok(out)
}
