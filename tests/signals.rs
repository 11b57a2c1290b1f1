//! `impact signals`: the reduced model's time series written as CSV with units in the
//! headers, the summary as JSON, nothing written for a bad scene.

mod common;

use common::scenes::{edit, signals};
use common::{impact, tmp};

#[test]
fn writes_time_series_with_units_and_a_json_summary() {
    let dir = tmp();
    let scene = dir.write("s.toml", signals());
    let out = dir.join("out");
    let v = impact(["signals", "--json", "--scene"]).arg(&scene).arg("--out").arg(&out).success().json();
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
    let dir = tmp();
    let scene = dir.write("s.toml", edit(&signals(), "modes = 40", "modes = 0"));
    let out = dir.join("out");
    let o = impact(["signals", "--scene"]).arg(&scene).arg("--out").arg(&out).fails();
    assert!(o.stderr.contains("signals.modes = 0"));
    assert!(!out.exists());
}
