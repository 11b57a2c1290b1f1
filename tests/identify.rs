//! `impact identify` and its scene section: every bad `[ensemble]` value is an error naming
//! the field, the value and the allowed range; a small ensemble runs end to end, writes its
//! rows and report as one output set, gives the same rows on one and two threads, and
//! separates coal from gangue perfectly once everything but the material is held.

mod common;

use common::scenes::{edit, expect_refused as expect, CON_2, ENSEMBLE};
use common::{impact, tmp, Impact};
use impact::scene::{Scene, SceneSource};
use std::path::Path;

fn with(from: &str, to: &str) -> String {
    edit(ENSEMBLE, from, to)
}

#[test]
fn small_scene_is_valid_and_in_si() {
    let s = Scene::parse(ENSEMBLE, "small").unwrap();
    let study = s.ensemble.unwrap();
    assert_eq!(study.ensemble.len(), 40);
    assert_eq!(study.ensemble.class_counts(), (20, 20));
    // Radii converted from mm (the truncated law's median is the same law's in mm, times
    // 1e-3), moduli from GPa, the candidate grid spans the plate.
    let in_mm = identify::Distribution::LogNormal { median: 25.0, sigma_log: 0.2, min: 15.0, max: 40.0 };
    assert!((study.ensemble.families[0].radius.median() / (in_mm.median() * 1e-3) - 1.0).abs() < 1e-15);
    assert_eq!(study.ensemble.families[1].youngs_modulus.median(), 16e9);
    assert_eq!(study.candidates_x, vec![0.0, 0.2292, 0.4584]);
    assert_eq!(study.candidates_z, vec![0.0, 0.36]);
    assert_eq!(study.hold.len(), 4);
}

#[test]
fn ensemble_and_identify_come_together() {
    let start = ENSEMBLE.find("[ensemble]").unwrap();
    expect(&ENSEMBLE[..start], &["ensemble", "identify"]);
    // An [ensemble] beside analyses that do not read it.
    let text = format!("{}\n{}", impact::scene::DEFAULT_SCENE, &ENSEMBLE[start..]);
    expect(&text, &["ensemble", "is read only by the \"identify\" analysis"]);
}

#[test]
fn the_truncation_checks_share_is_within_zero_and_one() {
    for bad in ["0.0", "1.5", "-0.25", "nan"] {
        let text = with("modes = 24", &format!("modes = 24\ntruncation_check_fraction = {bad}"));
        expect(&text, &["signals.truncation_check_fraction", "(0, 1]"]);
    }
    let text = with("modes = 24", "modes = 24\ntruncation_check_fraction = 0.25");
    assert_eq!(Scene::parse(&text, "small").unwrap().signals.truncation_check, 0.25);
    assert_eq!(Scene::parse(ENSEMBLE, "small").unwrap().signals.truncation_check, 1.0);
}

#[test]
fn the_arithmetic_is_a_word_of_two() {
    for bad in ["\"f32\"", "\"Fast\""] {
        let text = with("modes = 24", &format!("modes = 24\narithmetic = {bad}"));
        expect(&text, &["signals.arithmetic", bad]);
    }
    // A value of the wrong type is refused by the parser at its line, key and value shown.
    expect(&with("modes = 24", "modes = 24\narithmetic = 1"), &["arithmetic = 1", "expected a string"]);
    let text = with("modes = 24", "modes = 24\narithmetic = \"f32\"");
    expect(&text, &["\"f32\" is not an arithmetic", "\"exact\", \"fast\""]);
    let text = with("modes = 24", "modes = 24\narithmetic = \"fast\"");
    let fast = Scene::parse(&text, "small").unwrap();
    assert_eq!(fast.signals.arithmetic, coupled::reduced::Arithmetic::Fast);
    assert_eq!(fast.signals.reduced().arithmetic, coupled::reduced::Arithmetic::Fast);
    assert_eq!(Scene::parse(ENSEMBLE, "small").unwrap().signals.arithmetic, coupled::reduced::Arithmetic::Exact);
}

#[test]
fn distribution_values_name_field_value_and_range() {
    expect(
        &with("min = 15.0, max = 40.0 }", "min = 0.0, max = 40.0 }"),
        &["ensemble.families[0].radius_mm.min = 0", "[0.001, 10000] mm"],
    );
    expect(
        &with("poisson_ratio = 0.28", "poisson_ratio = 0.6"),
        &["ensemble.families[0].poisson_ratio = 0.6", "(0, 0.5)"],
    );
    expect(
        &with("min = 0.002, max = 0.008", "min = 0.002, max = 1e300"),
        &["ensemble.velocity_m_per_s.max = 1e300", "m/s"],
    );
    expect(&with("min = 15.0, max = 40.0 }", "min = 40.0, max = 15.0 }"), &["radius_mm.max", "below min"]);
    expect(
        &with(r#"distribution = "lognormal""#, r#"distribution = "gaussian""#),
        &["radius_mm.distribution", "'gaussian'", "rosin-rammler"],
    );
    expect(
        &with("sigma_log = 0.2,", "sigma_log = 0.2, sd = 1.0,"),
        &["radius_mm.sd", "not a parameter of the lognormal law"],
    );
    expect(&with("median = 25.0, ", ""), &["radius_mm.median", "required"]);
    expect(&with("density_kg_m3 = 1380.0", r#"density_kg_m3 = "heavy""#), &["density_kg_m3", "neither a number"]);
    // A normal whose bounds lie 40 standard deviations out has no probability between them.
    expect(
        &with(
            "density_kg_m3 = 1380.0",
            r#"density_kg_m3 = { distribution = "normal", mean = 1380.0, sd = 1.0, min = 1500.0, max = 1600.0 }"#,
        ),
        &["density_kg_m3.min", "no probability"],
    );
}

#[test]
fn ensemble_structure_is_checked() {
    expect(
        &with(
            r#"velocity_m_per_s = { distribution = "uniform", min = 0.002, max = 0.008 }"#,
            "velocity_m_per_s = 0.008\nfall_height_m = 1.0",
        ),
        &["exactly one of fall_height_m", "velocity_m_per_s"],
    );
}

#[test]
fn counts_classes_regions_and_grids_are_checked() {
    expect(&with("count = 20", "count = 0"), &["ensemble.families[0].count = 0", "[1, 1000000]"]);
    expect(&with("count = 20", "count = 2.5"), &["ensemble.families[0].count", "not a whole number"]);
    expect(&with("count = 20", "count = 2e6"), &["ensemble.families[0].count", "[1, 1000000]"]);
    expect(&with(r#"class = "gangue""#, r#"class = "coal""#), &["ensemble.families", "class = \"gangue\""]);
    expect(&with(r#"class = "gangue""#, r#"class = "rock""#), &["ensemble.families[1].class", "'rock'"]);
    expect(&with(r#"name = "gangue""#, r#"name = "coal""#), &["ensemble.families[1].name", "same file name"]);
    expect(
        &with("seed = 11", "seed = 11\nregion = { x_mm = [0.0, 500.0], z_mm = [0.0, 360.0] }"),
        &["ensemble.region.x_mm[1] = 500", "[0, 458.4] mm"],
    );
    expect(&with("x_count = 3", "x_count = 100"), &["ensemble.placement.x_count = 100", "[2, 41]"]);
    expect(&with("seed = 11", "seed = 11\nhold = [\"colour\"]"), &["ensemble.hold[0]", "'colour'", "position"]);
    expect(&with("seed = 11", "seed = -1"), &["seed"]);
}

fn run(dir: &Path, scene: &Path, threads: &str) -> Impact {
    impact(["identify", "--scene"]).arg(scene).arg("--out").arg(dir).arg("--json").env("RAYON_NUM_THREADS", threads)
}

#[test]
fn identify_runs_streams_rows_and_is_identical_on_one_and_two_threads() {
    let dir = tmp();
    let scene = dir.write("small.toml", ENSEMBLE);
    let (one, two) = (dir.join("one"), dir.join("two"));
    let a = run(&one, &scene, "1").success();
    run(&two, &scene, "2").success();
    // One output set, the streamed files listed in its manifest with their hashes.
    impact::output::verify_set(&one).unwrap();
    for f in ["index.md", "summary.json", "impacts.csv", "features.csv", "c1-map-acceleration.svg", "c2-hist-best.svg"]
    {
        assert!(one.join(f).is_file(), "{f} is missing");
    }
    // The rows do not depend on the number of threads (timings in the report do).
    for f in ["impacts.csv", "features.csv"] {
        assert!(std::fs::read(one.join(f)).unwrap() == std::fs::read(two.join(f)).unwrap(), "{f} differs");
    }
    // One row per impact and support set; one per impact, channel and support set: Con 1
    // records 3 quantities at 6 candidates and 4 corner reactions, Con 2 as many spring forces.
    // Each after the provenance line and the header.
    let impacts = std::fs::read_to_string(one.join("impacts.csv")).unwrap();
    assert_eq!(impacts.lines().count(), 2 + 2 * 40);
    assert!(impacts
        .lines()
        .nth(1)
        .unwrap()
        .starts_with("condition,impact,family,class,x_m,z_m,radius_m,velocity_m_per_s"));
    let features = std::fs::read_to_string(one.join("features.csv")).unwrap();
    assert_eq!(features.lines().count(), 2 + 2 * 40 * (3 * 6 + 4));
    assert!(!features.contains("NaN") && !features.contains("inf"));

    let summary: serde_json::Value = serde_json::from_slice(&a.stdout).unwrap();
    let conditions = summary["conditions"].as_array().unwrap();
    assert_eq!(conditions.len(), 2);
    for c in conditions {
        for r in c["ranking"].as_array().unwrap() {
            let auc = r["auc"]["auc"].as_f64().unwrap();
            let (lo, hi) = (r["interval"][0].as_f64().unwrap(), r["interval"][1].as_f64().unwrap());
            assert!((0.0..=1.0).contains(&auc) && lo <= hi);
        }
        // Known answer: with position, size and speed held, coal and gangue are two fixed
        // spheres at one point and speed, so the reference feature (any that differs between
        // them) separates them perfectly.
        let paper = c["held"].as_array().unwrap().iter().find(|h| h["held"] == "position, size and speed").unwrap();
        let auc = paper["reference"]["auc"].as_f64().unwrap();
        assert!(auc == 1.0 || auc == 0.0, "{auc}");
        // Sizes vary and overlap: nothing separates perfectly without holding them.
        let best = c["ranking"][0]["auc"]["auc"].as_f64().unwrap();
        assert!(best.max(1.0 - best) < 1.0);
    }
}

/// In the fast arithmetic only the window's channel sums change: every impact's contact
/// numbers (impacts.csv below its provenance line) are the exact run's to the digit, the
/// summary records the arithmetic, and the page names it with its bound for the scene's 24
/// modes, at most 2·24 + 2 terms a channel: γ₅₂ = 52u/(1 - 52u) = 3.1e-6 (u = 2⁻²⁴).
#[test]
fn the_fast_arithmetic_changes_only_the_sums_and_says_so() {
    let dir = tmp();
    let exact = dir.write("exact.toml", ENSEMBLE);
    let fast = dir.write("fast.toml", with("modes = 24", "modes = 24\narithmetic = \"fast\""));
    let (a, b) = (dir.join("exact"), dir.join("fast"));
    run(&a, &exact, "2").success();
    let out = run(&b, &fast, "2").success();
    let body = |d: &Path| {
        let text = std::fs::read_to_string(d.join("impacts.csv")).unwrap();
        text.lines().skip(1).collect::<Vec<_>>().join("\n")
    };
    assert_eq!(body(&a), body(&b));
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(summary["signals"]["arithmetic"], "fast");
    let page = std::fs::read_to_string(b.join("index.md")).unwrap();
    assert!(page.contains("`[signals] arithmetic = \"fast\"`") && page.contains("γ = 3.1e-6"), "{page}");
    assert!(!std::fs::read_to_string(a.join("index.md")).unwrap().contains("fast arithmetic"));
}

#[test]
fn a_support_set_without_channels_is_refused_before_running() {
    // A cantilever plate (left edge clamped, corners free), no sensors, no grid: nothing to record.
    let text = ENSEMBLE.replacen("placement = { x_count = 3, z_count = 2 }\n", "", 1).replacen(CON_2, "", 1).replacen(
        "name = \"Con 1\"\nsupports = \"both-fixed\"",
        "name = \"cantilever\"\n[conditions.edges]\nleft = \"clamped\"",
        1,
    );
    assert!(text.contains("cantilever") && !text.contains("Con 2") && !text.contains("placement"));
    let dir = tmp();
    let scene = dir.write("cantilever.toml", text);
    let out = dir.join("out");
    let o = run(&out, &scene, "1").fails();
    assert!(o.stderr.contains("records no channel"), "{}", o.stderr);
    assert!(!out.exists());
}

#[test]
fn identify_needs_an_ensemble_and_writes_nothing_without_one() {
    let dir = tmp();
    let out = dir.join("out");
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let o = impact(["identify", "--scene"]).arg(scenes.join("paper-table-1.toml")).arg("--out").arg(&out).fails();
    assert!(o.stderr.contains("[ensemble]"));
    assert!(!out.exists());
    // And the other way round: a scene written only for identify has no bodies to solve.
    let o = impact(["solve", "--scene"]).arg(scenes.join("caving-stream.toml")).fails();
    assert!(o.stderr.contains("[[bodies]]"), "{}", o.stderr);
}

/// `impact report` writes the identification of its scenes through `impact identify`'s own
/// code path: the same files (features.csv left out, as `--no-features-csv` does), the rows
/// and figures byte for byte (the pages and the summary differ only in the timings).
#[test]
fn the_report_writes_what_identify_writes() {
    let dir = tmp();
    let scene_path = dir.write("small.toml", ENSEMBLE);
    let command = dir.join("command");
    impact(["identify", "--no-features-csv", "--scene"]).arg(&scene_path).arg("--out").arg(&command).success();
    assert!(!command.join("features.csv").exists());

    let scene = Scene::parse(ENSEMBLE, "small").unwrap();
    let nested = dir.join("report");
    let mut out = impact::output::OutputDir::prepare(&nested).unwrap();
    let (files, summary) = impact::report::identify::write(
        &scene,
        &mut out,
        "identify/small-identify",
        impact::report::identify::RowFiles::Impacts,
        &impact::report::Silent,
    )
    .unwrap();
    out.commit(&files).unwrap();
    let sub = nested.join("identify/small-identify");
    // The index page links the report where it is and opens with its answer.
    let index = impact::report::index_page(&[("small.toml", scene.clone(), summary)], &[], "").unwrap();
    assert!(index.contains("](identify/small-identify/index.md)"), "{index}");
    assert!(
        index.contains("scenes/small.toml") && index.contains("| Con 1 |") && index.contains("| Con 2 |"),
        "{index}"
    );
    let names = |d: &Path| {
        let mut v: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| !n.starts_with('.'))
            .collect();
        v.sort();
        v
    };
    assert_eq!(names(&sub), names(&command));
    for f in names(&command) {
        if f != "index.md" && f != "summary.json" {
            assert!(std::fs::read(sub.join(&f)).unwrap() == std::fs::read(command.join(&f)).unwrap(), "{f} differs");
        }
    }
}

/// The scenes `impact report` identifies are valid identification scenes with distinct
/// directories.
#[test]
fn the_reports_identification_scenes_are_valid() {
    let mut dirs = Vec::new();
    for (file, text) in impact::report::IDENTIFY_SCENES {
        let on_disk = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes").join(file)).unwrap();
        assert_eq!(text, on_disk, "{file} is embedded as shipped");
        let s = Scene::parse(text, file).unwrap();
        impact::report::identify::checked_study(&s).unwrap();
        dirs.push(impact::present::rows::slug(&s.name));
    }
    dirs.sort();
    dirs.dedup();
    assert_eq!(dirs.len(), impact::report::IDENTIFY_SCENES.len());
}

/// A named sensor on the candidate grid is one sensor: its channels are recorded, written and
/// ranked once (not once as the named sensor and again as the grid point), and the placement
/// maps still cover the whole grid.
#[test]
fn a_named_sensor_on_the_grid_is_ranked_once() {
    // The 3 x 2 grid has (229.2, 360) mm, the middle of the far free edge; Con 1 only.
    let text = with("modes = 24", "modes = 24\nsensors_mm = [[229.2, 360.0], [100.0, 100.0]]").replacen(CON_2, "", 1);
    assert!(!text.contains("Con 2"));
    let dir = tmp();
    let scene = dir.write("on-grid.toml", &text);
    let out = dir.join("out");
    let o = run(&out, &scene, "2").success();

    // 2 named sensors and the 5 grid points not at one: 7 sensors x 3 quantities, 4 corners.
    let features = std::fs::read_to_string(out.join("features.csv")).unwrap();
    let rows: Vec<&str> = features.lines().filter(|l| !l.starts_with('#')).skip(1).collect();
    assert_eq!(rows.len(), 40 * (3 * 7 + 4));
    // No impact has a channel twice: (condition, impact, class, quantity, x, z) are unique.
    let mut seen = std::collections::HashSet::new();
    for r in &rows {
        let key: Vec<&str> = r.split(',').take(6).collect();
        assert!(seen.insert(key.clone()), "channel recorded twice: {key:?}");
    }
    let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let ranking = summary["conditions"][0]["ranking"].as_array().unwrap();
    assert!(ranking.len() >= 5);
    let mut entries = std::collections::HashSet::new();
    for r in ranking {
        let key = (r["channel"].as_str().unwrap().to_string(), r["feature"].to_string());
        assert!(entries.insert(key.clone()), "ranked twice: {key:?}");
    }
    for q in ["displacement", "velocity", "acceleration"] {
        assert!(out.join(format!("c1-map-{q}.svg")).is_file(), "{q} map");
    }
}

/// The sensor design ([ensemble.placement] design_sensors): its budget is checked, and a run
/// chooses that many distinct grid points, the first where its own first map peaks, each
/// step's map leaving the points already chosen out.
#[test]
fn the_sensor_design_chooses_distinct_points_its_maps_rank_first() {
    expect(
        &with("x_count = 3, z_count = 2", "x_count = 3, z_count = 2, design_sensors = 9"),
        &["ensemble.placement.design_sensors = 9", "[1, 8]"],
    );
    expect(
        &with("x_count = 3, z_count = 2", "x_count = 3, z_count = 2, design_sensors = 7"),
        &["ensemble.placement.design_sensors", "7 sensors among 6 candidate points", "at most 6"],
    );
    let dir = tmp();
    let scene =
        dir.write("design.toml", with("x_count = 3, z_count = 2", "x_count = 3, z_count = 2, design_sensors = 2"));
    let out = run(&dir.join("out"), &scene, "2").success();
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for c in summary["conditions"].as_array().unwrap() {
        let d = &c["design"];
        let steps = d["steps"].as_array().unwrap_or_else(|| panic!("no design in {c}"));
        assert_eq!(steps.len(), 2);
        assert_ne!(steps[0]["at_mm"], steps[1]["at_mm"]);
        let x: Vec<f64> = d["x_mm"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        let z: Vec<f64> = d["z_mm"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        let map = |s: &serde_json::Value, i: usize, j: usize| s["map"][i][j].as_f64();
        let first = &steps[0];
        let best = (0..x.len())
            .flat_map(|i| (0..z.len()).map(move |j| (i, j)))
            .filter_map(|(i, j)| map(first, i, j))
            .fold(f64::MIN, f64::max);
        assert_eq!(first["auc"]["auc"].as_f64().unwrap(), best);
        let at = |s: &serde_json::Value| (s["at_mm"][0].as_f64().unwrap(), s["at_mm"][1].as_f64().unwrap());
        let (i, j) =
            (x.iter().position(|&v| v == at(first).0).unwrap(), z.iter().position(|&v| v == at(first).1).unwrap());
        assert_eq!(map(first, i, j), Some(best));
        assert_eq!(map(&steps[1], i, j), None, "a chosen point is not offered again");
        let gain = steps[1]["gain"].as_f64().unwrap();
        assert!((steps[1]["auc"]["auc"].as_f64().unwrap() - best - gain).abs() < 1e-12);
    }
    let page = std::fs::read_to_string(dir.join("out").join("index.md")).unwrap();
    assert!(page.contains("#### Sensor design: 2"), "the page shows the design");
}
