//! `impact signals`: the reduced model's time series written as CSV with units in the
//! headers, the summary as JSON, nothing written for a bad scene.

use std::process::Command;

const SCENE: &str = r#"
name = "one impact"
restitution = 0.65
analyses = ["responses"]

[plate]
length_mm = 458.4
width_mm = 360.0
thickness_mm = 8.0
youngs_modulus_gpa = 210.0
poisson_ratio = 0.3
density_kg_m3 = 7850.0

[[bodies]]
name = "coal"
density_kg_m3 = 1380.0
youngs_modulus_gpa = 2.26
poisson_ratio = 0.28
cohesion_mpa = 8.39
friction_angle_deg = 25.0
radius_mm = 25.0

[[conditions]]
name = "Con 3"
supports = "fixed-and-springs"
spring_stiffness_n_per_m = 5.11545e8

[points]
pairs_mm = [[229.2, 180.0]]

[velocities]
m_per_s = [0.008]

[signals]
window_ms = 5.0
rate_hz = 10000.0
modes = 40
sensors_mm = [[100.0, 100.0]]
"#;

#[test]
fn writes_time_series_with_units_and_a_json_summary() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("s.toml");
    std::fs::write(&scene, SCENE).unwrap();
    let out = dir.path().join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(["signals", "--json", "--scene"])
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let impacts = v["impacts"].as_array().unwrap();
    assert_eq!(impacts.len(), 1);
    let file = impacts[0]["file"].as_str().unwrap();
    assert_eq!(file, "signals/con-3/coal-0001.csv");
    assert!(impacts[0]["quantities"]["peak_force"].as_f64().unwrap() > 0.0);
    assert_eq!(v["models"][0]["settings"]["modes"], 40);
    let csv = std::fs::read_to_string(out.join(file)).unwrap();
    let mut lines = csv.lines();
    // The provenance comment, then the header in the CSV key style (quantity, SI unit).
    assert!(lines.next().unwrap().starts_with("# impact "));
    let header = lines.next().unwrap();
    for h in [
        "t_s",
        "displacement_s1_m",
        "velocity_s1_m_per_s",
        "acceleration_s1_m_per_s2",
        "reaction_corner_0_0_N",
        "spring_force_corner_L_B_N",
    ] {
        assert!(header.contains(h), "{header}");
    }
    // 5 ms at 10 kHz: 50 samples, t_k = k/rate.
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 50);
    let t49: f64 = rows[49].split(',').next().unwrap().parse().unwrap();
    assert!((t49 - 4.9e-3).abs() < 1e-12);
    for name in ["impacts.csv", "models.csv", "sensors.csv", "signals.json", ".impact-manifest.json"] {
        assert!(out.join(name).is_file(), "{name}");
    }
}

#[test]
fn a_bad_signals_table_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("s.toml");
    std::fs::write(&scene, SCENE.replace("modes = 40", "modes = 0")).unwrap();
    let out = dir.path().join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(["signals", "--scene"])
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("signals.modes = 0"));
    assert!(!out.exists());
}
