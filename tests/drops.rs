//! `impact drops` on the command line: every bad recording or drop is refused naming the key,
//! the value and its range before any model is built or anything written; a run writes one
//! row per drop and quantity, and its JSON carries the same rows. (The comparison's numbers
//! against recordings made by the full model are tested in crates/studies/tests/drops.rs.)

mod common;

use common::{impact, tmp};

const SCENE: &str = "scenes/drop-rig.toml";

/// A recording of `samples` quiet samples on both channels at `rate_hz`, with `drops`.
fn recording(dir: &std::path::Path, rate_hz: f64, samples: usize, drops: &str) -> std::path::PathBuf {
    let mut csv = String::from("t_s,a1,a2\n");
    for k in 0..samples {
        csv += &format!("{},{},{}\n", k as f64 / rate_hz, 0.01 * (k as f64).sin(), 0.0);
    }
    std::fs::write(dir.join("signal.csv"), csv).unwrap();
    let sidecar = format!(
        r#"{{"format": "impact-signal/1", "data": "signal.csv", "rate_hz": {rate_hz}, "columns": ["a1", "a2"],
            "condition": "Con 1", "drops": [{drops}]}}"#
    );
    let path = dir.join("signal.json");
    std::fs::write(&path, sidecar).unwrap();
    path
}

const DROP: &str = r#"{"touch_s": 0.01, "point_mm": [229.2, 180.0], "radius_mm": 25.0, "density_kg_m3": 2400.0,
    "youngs_modulus_gpa": 16.0, "poisson_ratio": 0.28, "cohesion_mpa": 37.68, "friction_angle_deg": 37.0,
    "fall_height_m": 0.45}"#;

#[test]
fn bad_recordings_and_drops_are_refused_before_anything_runs() {
    let dir = tmp();
    let out = dir.join("out");
    let refused = |signal: &std::path::Path, scene: &str, words: &[&str]| {
        let r = impact(["drops", "--scene", scene, "--signal"]).arg(signal).arg("--out").arg(&out).within(30).fails();
        for w in words {
            assert!(r.stderr.contains(w), "missing {w:?} in {}", r.stderr);
        }
        assert!(!out.exists(), "nothing is written for a refused run");
    };
    let ok = recording(dir.path(), 1e4, 400, DROP);
    refused(&ok, "scenes/paper-table-1.toml", &["add \"drops\" to its analyses"]);
    refused(&recording(dir.path(), 1e4, 400, ""), SCENE, &["lists no drops"]);
    let bad = DROP.replace("\"radius_mm\": 25.0", "\"radius_mm\": -2.0");
    refused(&recording(dir.path(), 1e4, 400, &bad), SCENE, &["drops[0].radius_mm = -2", "mm"]);
    let both = DROP.replace("\"fall_height_m\": 0.45", "\"fall_height_m\": 0.45, \"velocity_m_per_s\": 3.0");
    refused(&recording(dir.path(), 1e4, 400, &both), SCENE, &["drops[0]", "exactly one of fall_height_m"]);
    let unknown = DROP.replace("\"fall_height_m\"", "\"height_m\": 1.0, \"fall_height_m\"");
    refused(&recording(dir.path(), 1e4, 400, &unknown), SCENE, &["drops[0]", "unknown field `height_m`"]);
    let late = DROP.replace("\"touch_s\": 0.01", "\"touch_s\": 0.03");
    refused(&recording(dir.path(), 1e4, 400, &late), SCENE, &["drops[0].touch_s = 0.03", "allowed [0, 0.02] s"]);
    refused(&recording(dir.path(), 2e4, 800, DROP), SCENE, &["rate_hz = 20000", "10000 Hz"]);
}

#[test]
fn a_run_writes_a_row_per_drop_and_quantity() {
    let dir = tmp();
    let second =
        DROP.replace("\"touch_s\": 0.01", "\"touch_s\": 0.015").replace("0.45}", "0.45, \"class\": \"gangue\"}");
    let signal = recording(dir.path(), 1e4, 400, &format!("{DROP}, {second}"));
    let out = dir.join("out");
    let r = impact(["drops", "--scene", SCENE, "--json", "--signal"]).arg(&signal).arg("--out").arg(&out).within(120);
    let answer = r.success().json();
    let drops = answer["drops"].as_array().unwrap_or_else(|| panic!("{answer}"));
    assert_eq!(drops.len(), 2);
    // Two channels x (peak, spectral centroid); no measured P_max or t_c.
    for d in drops {
        assert_eq!(d["rows"].as_array().unwrap().len(), 4, "{d}");
        // A quiet recording is not a drop: every peak falls far outside its bar.
        assert!(d["disagreeing"].as_u64().unwrap() >= 2, "{d}");
    }
    assert_eq!(drops[1]["class"], "gangue");
    assert!(drops[0]["class"].is_null());
    let csv = std::fs::read_to_string(out.join("drops.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(lines.len(), 1 + 8, "{csv}");
    assert!(lines[0].starts_with("drop,touch_s,class,quantity,unit,measured,predicted,bar"), "{}", lines[0]);
    assert!(out.join("drops.json").exists());
}
