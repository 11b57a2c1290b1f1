//! A random impact ensemble over the transient model, split into shards by impact index.
//!
//! Impact `i` draws its position, velocity and size from its own ChaCha8 stream (the seed,
//! stream `i`), and its family (body) is the `i mod n`-th of the given ones, so the impact
//! depends only on (seed, i): a shard [start, stop) gives the same rows whether it runs alone,
//! beside other shards on other machines, or as part of one run from 0. That is what lets
//! `impact.dask` merge shards into exactly the single-process result.
//!
//! Each impact is one transient run (no error estimate: an ensemble's spread is its
//! statistic) on a mesh built once per shard. Features per impact: the peak contact force,
//! the largest compression, the contact time, the apparent restitution, the deflection at
//! maximum compression, the impulse and the number of contacts, with each row's validity.

use crate::columns::{Kind, Table};
use crate::errors::{argument_error, argument_message, model_error};
use analytic::params::{check, Range};
use analytic::Sphere;
use coupled::plan::{scene_striker, transient_values};
use coupled::transient::{TransientCase, TransientSettings};
use impact::scene::limits;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The ensemble's columns, the same for every shard (an empty one included).
const SCHEMA: [(&str, Kind); 18] = [
    ("index", Kind::Int),
    ("family", Kind::Text),
    ("x_m", Kind::Num),
    ("z_m", Kind::Num),
    ("velocity_m_per_s", Kind::Num),
    ("radius_m", Kind::Num),
    ("mass_kg", Kind::Num),
    ("peak_force_n", Kind::Num),
    ("compression_m", Kind::Num),
    ("deflection_m", Kind::Num),
    ("plate_ratio", Kind::Num),
    ("contact_time_s", Kind::Num),
    ("apparent_restitution", Kind::Num),
    ("impulse_n_s", Kind::Num),
    ("contacts", Kind::Num),
    ("valid", Kind::Flag),
    ("flags", Kind::Text),
    ("elastic_ratio", Kind::Num),
];

/// Most impacts one shard may hold: a shard is a unit of work of seconds to minutes.
const MAX_SHARD: f64 = 100_000.0;
/// Largest impact index (and so ensemble size).
const MAX_INDEX: f64 = 1e12;

/// A uniform number in [0, 1) from the top 53 bits of the stream.
fn uniform(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// What one impact draws.
struct Draw {
    x: f64,
    z: f64,
    velocity: f64,
    radius_factor: f64,
}

/// The draws of impact `index` of the ensemble `seed`: its own stream, four numbers in a
/// fixed order.
fn draw(seed: u64, index: u64, region: [f64; 4], velocity: (f64, f64), spread: f64) -> Draw {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(index);
    let [x0, x1, z0, z1] = region;
    let x = x0 + (x1 - x0) * uniform(&mut rng);
    let z = z0 + (z1 - z0) * uniform(&mut rng);
    let v = velocity.0 + (velocity.1 - velocity.0) * uniform(&mut rng);
    let radius_factor = 1.0 + spread * (2.0 * uniform(&mut rng) - 1.0);
    Draw { x, z, velocity: v, radius_factor }
}

/// Impacts `start..stop` of the ensemble `seed`: `families` (body names of the scene) taken
/// in turn, on the support set `condition`, uniformly over the region `region_mm` = (x0, x1,
/// z0, z1) (default the whole plate), velocities uniform in `velocity_m_per_s`, radii the
/// body's times a factor uniform in [1 - `radius_spread`, 1 + `radius_spread`].
#[pyfunction]
#[pyo3(signature = (scene, condition, families, start, stop, seed, velocity_m_per_s, radius_spread = 0.0, region_mm = None, elements = 12.0, steps_per_contact = 100.0))]
#[allow(clippy::too_many_arguments)]
pub fn ensemble<'py>(
    py: Python<'py>,
    scene: &crate::scene::Scene,
    condition: &str,
    families: Vec<String>,
    start: f64,
    stop: f64,
    seed: u64,
    velocity_m_per_s: (f64, f64),
    radius_spread: f64,
    region_mm: Option<(f64, f64, f64, f64)>,
    elements: f64,
    steps_per_contact: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let s = &scene.scene;
    let arg =
        |name: &str, v: f64, r: Range, unit: &'static str| check(name, v, r, unit).map_err(|e| argument_error(&e));
    let whole = |name: &str, v: f64| {
        if v.fract() == 0.0 {
            Ok(v)
        } else {
            Err(argument_message(name, format!("{v} is not a whole number")))
        }
    };
    let start = whole("start", arg("start", start, Range::closed(0.0, MAX_INDEX), "")?)?;
    let stop = whole("stop", arg("stop", stop, Range::closed(start, start + MAX_SHARD), "")?)?;
    let set = s
        .conditions
        .iter()
        .find(|c| c.name == condition)
        .ok_or_else(|| argument_message("condition", format!("'{condition}' is not in the scene")))?;
    if families.is_empty() {
        return Err(argument_message("families", "the list is empty; name at least one body of the scene".into()));
    }
    let bodies: Vec<&Sphere> = families
        .iter()
        .map(|f| {
            s.bodies.iter().find(|b| &b.name == f).ok_or_else(|| {
                let names: Vec<&str> = s.bodies.iter().map(|b| b.name.as_str()).collect();
                argument_message("families", format!("'{f}' is not a body of the scene; it has {names:?}"))
            })
        })
        .collect::<PyResult<_>>()?;
    let (v_lo, v_hi) = velocity_m_per_s;
    let v_lo = arg("velocity_m_per_s[0]", v_lo, limits::VELOCITY_M_PER_S, "m/s")?;
    let v_hi = arg("velocity_m_per_s[1]", v_hi, Range::closed(v_lo, limits::VELOCITY_M_PER_S.hi), "m/s")?;
    // Radii stay positive and within a factor 3 of the body's.
    let spread = arg("radius_spread", radius_spread, Range::closed(0.0, 0.5), "")?;
    let (l_mm, b_mm) = (s.plate.length() * 1e3, s.plate.width() * 1e3);
    let (x0, x1, z0, z1) = region_mm.unwrap_or((0.0, l_mm, 0.0, b_mm));
    let x0 = arg("region_mm[0] (x0)", x0, Range::closed(0.0, l_mm), "mm")?;
    let x1 = arg("region_mm[1] (x1)", x1, Range::closed(x0, l_mm), "mm")?;
    let z0 = arg("region_mm[2] (z0)", z0, Range::closed(0.0, b_mm), "mm")?;
    let z1 = arg("region_mm[3] (z1)", z1, Range::closed(z0, b_mm), "mm")?;
    let region = [x0 * 1e-3, x1 * 1e-3, z0 * 1e-3, z1 * 1e-3];
    let elements = whole("elements", arg("elements", elements, Range::closed(4.0, 80.0), "")?)?;
    let steps = arg("steps_per_contact", steps_per_contact, Range::closed(20.0, 2000.0), "")?;
    let settings =
        TransientSettings { elements: elements as usize, steps_per_contact: steps, ..TransientSettings::default() };
    let (start, stop) = (start as u64, stop as u64);

    let rows = py
        .detach(|| -> Result<Vec<_>, String> {
            if start == stop {
                return Ok(vec![]);
            }
            let case = TransientCase::new(&s.plate, settings).map_err(|e| e.to_string())?;
            (start..stop)
                .map(|i| {
                    let d = draw(seed, i, region, (v_lo, v_hi), spread);
                    let family = bodies[(i % bodies.len() as u64) as usize];
                    let body = Sphere::new(
                        family.name.clone(),
                        family.density(),
                        family.radius() * d.radius_factor,
                        family.material(),
                        family.strength(),
                    )
                    .map_err(|e| e.to_string())?;
                    let striker = scene_striker(s, &body, d.velocity);
                    let o = case.run(set, &striker, d.x, d.z).map_err(|e| format!("impact {i}: {e}"))?;
                    let values =
                        transient_values(s, set, &body, &o, &striker, striker.hertz_time() / steps, (d.x, d.z), None);
                    Ok((i, d, body, values))
                })
                .collect()
        })
        .map_err(model_error)?;

    let mut t = Table::new(rows.len(), &SCHEMA);
    for (row, (i, d, body, v)) in rows.iter().enumerate() {
        t.int("index", row, *i as i64);
        t.text("family", row, &body.name);
        t.num("x_m", row, d.x);
        t.num("z_m", row, d.z);
        t.num("velocity_m_per_s", row, d.velocity);
        t.num("radius_m", row, body.radius());
        t.num("mass_kg", row, body.mass());
        t.num(
            "peak_force_n",
            row,
            match v.evidence {
                coupled::plan::Evidence::Transient { peak_force, .. } => peak_force,
                coupled::plan::Evidence::Balance { .. } => v.contact_force,
            },
        );
        t.num("compression_m", row, v.compression);
        t.num("deflection_m", row, v.deflection);
        t.num("plate_ratio", row, v.plate_ratio);
        if let coupled::plan::Evidence::Transient {
            contact_time, apparent_restitution, total_impulse, contacts, ..
        } = v.evidence
        {
            // An impact whose first contact outlasted the window has no contact time or
            // restitution: NaN, the one "does not apply" of these columns.
            t.num("contact_time_s", row, contact_time.unwrap_or(f64::NAN));
            t.num("apparent_restitution", row, apparent_restitution.unwrap_or(f64::NAN));
            t.num("impulse_n_s", row, total_impulse);
            t.num("contacts", row, contacts as f64);
        }
        t.flag("valid", row, v.validity.all_valid());
        t.text("flags", row, &v.validity.flags().join("; "));
        t.opt("elastic_ratio", row, v.validity.elastic.map(|c| c.value));
    }
    t.into_py_all(py)
}
