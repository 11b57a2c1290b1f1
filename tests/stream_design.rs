//! The window-level sensor design of the stream study (`[stream] design_sensors`): its bad
//! values refused by name, and on a small scene the answer that the plate's supports dictate.
//! The both-fixed plate (Con 1) stands on its four corners, held: a corner cannot move, so its
//! accelerometer records zero and its windows carry nothing. Its window AUC is chance, and the
//! design must choose a point that moves. Con 2 stands on four springs, so every corner moves.

mod common;

use common::scenes::{expect_refused as expect, with_stream, STREAM};
use common::{impact, tmp};

/// [`STREAM`] on [`with_stream`]'s scene (a 3 x 2 candidate grid, edges included) asking for
/// two sensors, edited by `edits`. One time block per stream (leave-one-stream-out): every
/// block then holds the same share of gangue-rich windows, so a channel that carries nothing
/// is fitted the same intercept in every fold and scores chance. With blocks that cut the
/// streams unevenly across the change each fold's intercept follows the other blocks' class
/// balance, which runs against its own, and such a channel scores below chance (0 here with
/// four blocks), the known bias of cross-validated AUC on uninformative features.
fn scene(edits: &[(&str, &str)]) -> String {
    let stream = STREAM.replace("write_signal = true", "design_sensors = 2").replace("blocks = 4", "blocks = 2");
    with_stream(&edits.iter().fold(stream, |s, (a, b)| s.replace(a, b)))
}

#[test]
fn bad_designs_name_the_key_the_value_and_the_range() {
    let d = "design_sensors = 2";
    expect(&scene(&[(d, "design_sensors = 0")]), &["stream.design_sensors = 0", "[1, 8]"]);
    expect(&scene(&[(d, "design_sensors = 1.5")]), &["stream.design_sensors", "not a whole number"]);
    expect(
        &scene(&[(d, "design_sensors = 2\ndesign_quantity = \"force\"")]),
        &["stream.design_quantity", "\"force\" is not a plate quantity", "\"acceleration\", \"velocity\""],
    );
    expect(
        &scene(&[(d, "design_quantity = \"strain\"")]),
        &["stream.design_quantity", "is given but design_sensors is not"],
    );
    let no_grid = scene(&[]).replace("placement = { x_count = 3, z_count = 2 }\n", "");
    expect(&no_grid, &["stream.design_sensors", "[ensemble.placement]", "x_count and z_count"]);
    expect(
        &scene(&[(d, "design_sensors = 7")]),
        &["stream.design_sensors", "7 sensors among 6 candidate points", "at most 6"],
    );
    // 400 candidates over 60 s at 20 kHz, the model signal and its recording: 7.68 GB a
    // stream, over the 4 GiB budget.
    let fine = scene(&[("duration_s = 6.0", "duration_s = 60.0")])
        .replace("placement = { x_count = 3, z_count = 2 }", "placement = { x_count = 20, z_count = 20 }");
    expect(&fine, &["stream.design_sensors", "400 candidate points", "7680 MB", "above the 4295 MB budget"]);
    // A chain that records accelerations only cannot place strain gauges.
    let chain = "[measurement]\nrate_hz = 10000.0\nseed = 1\n\n[measurement.acceleration]\nadc_range_m_s2 = 5000.0\nadc_bits = 16\n\n[stream]";
    let measured = scene(&[(d, "design_sensors = 2\ndesign_quantity = \"strain\"")]).replace("[stream]", chain);
    expect(
        &measured,
        &["stream.design_quantity", "\"strain\" is not recorded by [measurement]", "allowed: \"acceleration\""],
    );
}

#[test]
fn the_design_leaves_a_held_corner_and_its_steps_add_up() {
    let dir = tmp();
    let path = dir.write("design.toml", scene(&[]));
    impact(["stream", "--scene"]).arg(&path).arg("--out").arg(dir.join("out")).arg("--json").success();
    let data: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("stream.json")).unwrap()).unwrap();
    let x_mm = |d: &serde_json::Value| -> Vec<f64> {
        d["x_mm"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect()
    };
    for c in data["conditions"].as_array().unwrap() {
        let d = &c["design"];
        assert_eq!(d["quantity"], "acceleration");
        assert_eq!(x_mm(d), [0.0, 229.2, 458.4]);
        let steps = d["steps"].as_array().unwrap();
        assert_eq!(steps.len(), 2);
        let auc = |s: &serde_json::Value| s["score"]["auc"].as_f64().unwrap();
        let map = |s: &serde_json::Value, i: usize, j: usize| s["map"][i][j].as_f64();
        let at = |s: &serde_json::Value| (s["at_mm"][0].as_f64().unwrap(), s["at_mm"][1].as_f64().unwrap());
        let cell = |s: &serde_json::Value| {
            let (x, z) = at(s);
            (x_mm(d).iter().position(|&v| v == x).unwrap(), if z == 0.0 { 0 } else { 1 })
        };
        // The map holds the chosen set's own score, and the chosen point is gone from the next map.
        let (i, j) = cell(&steps[0]);
        assert_eq!(map(&steps[0], i, j), Some(auc(&steps[0])));
        assert_eq!(map(&steps[1], i, j), None);
        // The first gain is over chance; the second is the difference of the two AUCs.
        assert!((steps[0]["gain"].as_f64().unwrap() - (auc(&steps[0]) - 0.5)).abs() < 1e-12);
        assert!((steps[1]["gain"].as_f64().unwrap() - (auc(&steps[1]) - auc(&steps[0]))).abs() < 1e-12);
        // Every feature of both sensors, largest weight first, each at a chosen point.
        let features = d["features"].as_array().unwrap();
        assert_eq!(features.len(), 2 * identify::features::FEATURES.len());
        let weight = |f: &serde_json::Value| f["weight"].as_f64().unwrap().abs();
        assert!(features.windows(2).all(|p| weight(&p[0]) >= weight(&p[1])));
        let chosen = [at(&steps[0]), at(&steps[1])];
        assert!(features
            .iter()
            .all(|f| chosen.contains(&(f["at_mm"][0].as_f64().unwrap(), f["at_mm"][1].as_f64().unwrap()))));
        let g = &steps[1]["gain_interval"];
        assert!(g[0].as_f64().unwrap() <= g[1].as_f64().unwrap());
        if c["name"] == "Con 1" {
            // The candidate grid's x = 0 and x = L columns are the four held corners (z = 0
            // and z = B): no signal, no information.
            for i in [0, 2] {
                for j in 0..2 {
                    let a = map(&steps[0], i, j).unwrap();
                    assert!((a - 0.5).abs() < 1e-12, "a held corner's window AUC {a} at x index {i}");
                }
            }
            assert_eq!(at(&steps[0]).0, 229.2, "the first sensor goes inside the plate");
            assert!(auc(&steps[0]) > 0.8, "{}", auc(&steps[0]));
        }
    }
    let page = std::fs::read_to_string(dir.join("out").join("index.md")).unwrap();
    assert!(page.contains("## Where to put the sensors") && page.contains("(229.2, "), "{page}");
}
