//! Measured drops against the model, on "measured" recordings made by another path than the
//! one under test: the full Newmark model of the plate (every DOF of the mesh, stepped at a
//! sixteenth of the model's sample interval, the sphere followed through every contact to the
//! window's end, the acceleration read from the FE field at each sensor) put through the
//! scene's measurement chain with its own background, written to CSV and a JSON sidecar and
//! read back. The comparison under test runs the reduced modal model instead.
//!
//! Each drop touches between two ADC samples (1/4, 2/4 and 3/4 of an interval after one), as
//! a real drop does. The known answers: with the drops stated as made, no row of any drop
//! leaves its bar; with one drop's height stated as half the real one, that drop disagrees
//! and no other does.

mod full_model;

use analytic::{Elastic, RockStrength, Sphere};
use coupled::transient::Striker;
use full_model::{plate_model, strike, FullRun};
use identify::measurement::{Chain, Measurand};
use identify::recording::Sidecar;
use scene::{Scene, SceneSource};
use std::sync::OnceLock;
use studies::drops::compute;
use studies::progress::Silent;

/// The shipped drop rig: the paper's plate on Con 1 with two accelerometers, Rayleigh damping
/// shared by both models, and a chain with a 12 kHz sensor, an 8th-order 4 kHz anti-aliasing
/// filter, 10 kHz 16-bit ADCs and a pink background of 2 m/s² rms with two motor lines.
const SCENE: &str = include_str!("../../../scenes/drop-rig.toml");

/// Newmark steps per model sample: Δt = 1.5625 µs, a period error (ωΔt)²/12 of 1.2e-4 at
/// the anti-aliasing corner and 200-430 steps per contact. At 8 the measured peaks sit up to
/// 0.23 % (5 m/s²) from these, more than the reduced model's own error: the "measurement"
/// must be the more accurate of the two.
const SUBSTEPS: usize = 16;
/// ADC samples of background before each touch.
const PRE: usize = 100;

/// A drop as made: lump, height and point.
#[derive(Clone, Copy)]
struct Made {
    radius_mm: f64,
    density: f64,
    modulus_gpa: f64,
    cohesion_mpa: f64,
    friction_deg: f64,
    height_m: f64,
    point_mm: (f64, f64),
}

const DROPS: [Made; 3] = [
    Made {
        radius_mm: 25.0,
        density: 2400.0,
        modulus_gpa: 16.0,
        cohesion_mpa: 37.68,
        friction_deg: 37.0,
        height_m: 0.45,
        point_mm: (229.2, 180.0),
    },
    Made {
        radius_mm: 30.0,
        density: 1380.0,
        modulus_gpa: 2.26,
        cohesion_mpa: 8.39,
        friction_deg: 25.0,
        height_m: 0.8,
        point_mm: (150.0, 120.0),
    },
    Made {
        radius_mm: 20.0,
        density: 2400.0,
        modulus_gpa: 16.0,
        cohesion_mpa: 37.68,
        friction_deg: 37.0,
        height_m: 0.3,
        point_mm: (330.0, 200.0),
    },
];

/// The full model's run of a drop as made.
fn full_model(scene: &Scene, model: &plate_fem::Model, d: &Made) -> FullRun {
    let sphere = Sphere::new(
        "lump",
        d.density,
        d.radius_mm * 1e-3,
        Elastic::new(d.modulus_gpa * 1e9, 0.28).unwrap(),
        RockStrength::new(d.cohesion_mpa * 1e6, d.friction_deg).unwrap(),
    )
    .unwrap();
    let striker = Striker {
        k: analytic::contact_stiffness(&sphere, scene.plate.material()),
        restitution: scene.restitution,
        mass: sphere.mass(),
        velocity: (2.0 * 9.80665 * d.height_m).sqrt(),
        law: scene.contact_law.law_for(&sphere),
        gravity: scene.gravity,
    };
    let point = (d.point_mm.0 * 1e-3, d.point_mm.1 * 1e-3);
    strike(scene, model, scene.conditions[0].supports, &striker, point, SUBSTEPS)
}

/// The recording of `drops` (each captured with `PRE` samples of background before its
/// touch, one after the other), written as CSV and sidecar into `dir`, the sidecar stating
/// `stated` heights; returns the sidecar's path.
fn record(scene: &Scene, stated: &[f64], dir: &std::path::Path) -> std::path::PathBuf {
    let chain = Chain::new(scene.measurement.clone().unwrap(), scene.signals.rate_hz).unwrap();
    // A background stream no prediction draws (those start at 2⁴⁰).
    let mut rng = chain.stream(3 << 44);
    let mut columns = vec![Vec::new(); scene.signals.sensors.len()];
    let mut meta = Vec::new();
    static MADE: OnceLock<Vec<FullRun>> = OnceLock::new();
    let made = MADE.get_or_init(|| {
        let model = plate_model(scene);
        DROPS.iter().map(|d| full_model(scene, &model, d)).collect()
    });
    let m = chain.decimation();
    for (i, ((d, h), run)) in DROPS.iter().zip(stated).zip(made).enumerate() {
        // The touch i + 1 model samples (of m an ADC sample) after the PRE-th ADC sample.
        let lead = PRE * m + i + 1;
        let touch = ((columns[0].len() * m + lead) as f64) / (1e4 * m as f64);
        for (column, a) in columns.iter_mut().zip(&run.accelerations) {
            let mut y = vec![0.0; lead];
            y.extend(a);
            column.extend(chain.measure(Measurand::Acceleration, &y, 1.0, &mut rng).unwrap().samples);
        }
        meta.push(serde_json::json!({
            "touch_s": touch, "point_mm": [d.point_mm.0, d.point_mm.1], "radius_mm": d.radius_mm,
            "density_kg_m3": d.density, "youngs_modulus_gpa": d.modulus_gpa, "poisson_ratio": 0.28,
            "cohesion_mpa": d.cohesion_mpa, "friction_angle_deg": d.friction_deg, "fall_height_m": h,
            "force_max_kn": run.force_max * 1e-3,
            "contact_time_ms": run.contact_time.expect("the first contact ends") * 1e3,
        }));
    }
    let mut csv = String::from("t_s,a1,a2\n");
    for (k, (a1, a2)) in columns[0].iter().zip(&columns[1]).enumerate() {
        csv += &format!("{},{a1},{a2}\n", k as f64 / 1e4);
    }
    std::fs::write(dir.join("signal.csv"), csv).unwrap();
    let sidecar = serde_json::json!({
        "format": "impact-signal/1", "data": "signal.csv", "rate_hz": 1e4, "columns": ["a1", "a2"],
        "condition": "Con 1", "drops": meta,
    });
    let path = dir.join("signal.json");
    std::fs::write(&path, serde_json::to_string_pretty(&sidecar).unwrap()).unwrap();
    path
}

fn compare(stated: &[f64], tag: &str) -> studies::drops::DropsData {
    let scene = Scene::parse(SCENE, "drop-rig").unwrap();
    let dir = std::env::temp_dir().join(format!("impact-drops-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = record(&scene, stated, &dir);
    let sidecar = Sidecar::parse(&std::fs::read_to_string(&path).unwrap(), "signal.json").unwrap();
    let csv = std::fs::read_to_string(sidecar.data_path(&path)).unwrap();
    let recording = sidecar.read(&csv, "signal.csv").unwrap();
    std::fs::remove_dir_all(&dir).ok();
    compute(&scene, &recording, "signal.json", &Silent).unwrap()
}

fn show(data: &studies::drops::DropsData) -> String {
    let mut s = String::new();
    for d in &data.drops {
        for r in &d.rows {
            s += &format!(
                "drop {} {}: measured {:.6e} predicted {:.6e} bar {:.3e} (trunc {:.2e}, step {:.2e}, chain {:.2e}, sd {:.2e}) {}\n",
                d.index,
                r.quantity,
                r.measured,
                r.predicted,
                r.bar,
                r.truncation,
                r.step,
                r.chain,
                r.noise_sd,
                if r.disagrees { "DISAGREES" } else { "" }
            );
        }
    }
    s
}

#[test]
fn drops_made_by_the_full_model_agree_with_the_reduced_one_within_their_bars() {
    let heights: Vec<f64> = DROPS.iter().map(|d| d.height_m).collect();
    let data = compare(&heights, "right");
    let table = show(&data);
    eprintln!("{table}");
    assert_eq!(data.drops.len(), 3);
    // Two channels x (peak, centroid) + P_max + t_c.
    assert!(data.drops.iter().all(|d| d.rows.len() == 6), "{table}");
    assert!(data.drops.iter().all(|d| d.disagreeing == 0), "{table}");
    // The recording passed the same digital chain as the prediction, so the chain term has
    // nothing to cover here: the model's two terms and the noise alone must hold for the
    // peaks, P_max and t_c. The spectral centroid is the exception: at the centre sensor
    // the reduced model reads drop 1's 0.18 % (2.9 Hz) below the full model's, 1.04 times
    // its model-and-noise bar (the N/2 truncation estimate, 0.36 Hz, understates the
    // reduced model's error in the centroid there); it is held to the whole bar above.
    for r in data.drops.iter().flat_map(|d| &d.rows).filter(|r| !r.quantity.starts_with("spectral centroid")) {
        assert!((r.measured - r.predicted).abs() <= r.bar - r.chain, "{}\n{table}", r.quantity);
    }
}

#[test]
fn a_wrong_drop_height_is_flagged_on_that_drop_alone() {
    let mut heights: Vec<f64> = DROPS.iter().map(|d| d.height_m).collect();
    heights[1] *= 0.5;
    let data = compare(&heights, "wrong");
    let table = show(&data);
    eprintln!("{table}");
    assert!(data.drops[1].disagreeing > 0, "{table}");
    assert!(data.drops[0].disagreeing == 0 && data.drops[2].disagreeing == 0, "{table}");
}
