//! Hostile inputs a scene reader once let through: a third number in a pair, an unknown key
//! in a corner spring, two sensors of one channel name, a window of one sample, signals
//! beyond memory, degenerate ensemble laws (a denormal spread, bounds that meet), and nesting
//! deeper than any scene. Each is refused naming its field, or (a point law) computed.

mod common;

use common::scenes::{edit, expect_refused as expect, small_ensemble, CON_1, CON_2, ENSEMBLE, ONE_IMPACT};
use common::{impact, tmp};
use impact::scene::{Scene, SceneSource, DEFAULT_SCENE};

fn signals(table: &str) -> String {
    format!("{ONE_IMPACT}\n[signals]\n{table}\n")
}

#[test]
fn every_pair_has_exactly_two_numbers() {
    let points = "[points]\npairs_mm = [[229.2, 180.0]]";
    for (pairs, n) in [("[[1.0, 2.0, 3.0]]", 3), ("[[1.0]]", 1), ("[[]]", 0)] {
        let text = edit(ONE_IMPACT, points, &format!("[points]\npairs_mm = {pairs}"));
        expect(&text, &["points.pairs_mm[0]", &format!("has {n} numbers"), "[x, z]"]);
    }
    let text = edit(ONE_IMPACT, points, "[points]\npairs_mm = [[1.0, 2.0], [3.0, 4.0, 5.0]]");
    expect(&text, &["points.pairs_mm[1]", "has 3 numbers"]);
    expect(
        &format!("{ONE_IMPACT}\n[transient]\npairs_mm = [[1.0, 2.0, 0.0]]\n"),
        &["transient.pairs_mm[0]", "3 numbers"],
    );
    expect(&signals("sensors_mm = [[229.2, 180.0, 7.0]]"), &["signals.sensors_mm[0]", "has 3 numbers"]);
    let region = edit(ENSEMBLE, "seed = 11", "seed = 11\nregion = { x_mm = [0.0, 10.0, 20.0], z_mm = [0.0, 10.0] }");
    expect(&region, &["ensemble.region.x_mm", "has 3 numbers", "[low, high]"]);
}

#[test]
fn corner_tables_refuse_unknown_keys_and_name_the_corner() {
    let corners = |right_near: &str| {
        let set = format!("[[conditions]]\nname = \"props\"\n[conditions.edges]\nleft = \"clamped\"\n[conditions.corners]\nright_near = {right_near}\nright_far = {{ spring_n_per_m = 1e6 }}\n");
        edit(ONE_IMPACT, "[[conditions]]\nname = \"Con 1\"\nsupports = \"both-fixed\"\n", &set)
    };
    assert!(Scene::parse(&corners("{ spring_n_per_m = 1e6 }"), "t").is_ok());
    assert!(Scene::parse(&corners("\"fixed\""), "t").is_ok());
    expect(
        &corners("{ spring_n_per_m = 1e6, damping = 3.0 }"),
        &["conditions[0].corners.right_near.damping", "not a key of a corner spring"],
    );
    expect(&corners("{ stiffness = 1e6 }"), &["conditions[0].corners.right_near.stiffness"]);
    expect(&corners("{}"), &["conditions[0].corners.right_near.spring_n_per_m", "is required"]);
    expect(&corners("\"pinned\""), &["conditions[0].corners.right_near", "'pinned' is not a corner support"]);
    expect(&corners("{ spring_n_per_m = \"stiff\" }"), &["right_near.spring_n_per_m", "is not a number"]);
    expect(&corners("{ spring_n_per_m = 1e-9 }"), &["right_near.spring_n_per_m = 1e-9", "N/m"]);
    expect(&corners("3.0"), &["conditions[0].corners.right_near", "is not a corner support"]);
}

#[test]
fn sensors_of_one_channel_name_are_refused() {
    // 0.04 mm apart: both labelled (229.2, 180) mm, so every column name would be shared.
    expect(
        &signals("sensors_mm = [[229.2, 180.0], [100.0, 100.0], [229.24, 180.0]]"),
        &["signals.sensors_mm[2]", "(229.2, 180) mm", "signals.sensors_mm[0]", "0.1 mm apart"],
    );
    expect(&signals("sensors_mm = [[1.0, 1.0], [1.0, 1.0]]"), &["signals.sensors_mm[1]"]);
    let s = Scene::parse(&signals("sensors_mm = [[229.2, 180.0], [229.3, 180.0]]"), "t").unwrap();
    assert_eq!(s.signals.sensors.len(), 2);
}

#[test]
fn windows_hold_enough_samples_and_signals_fit_in_memory() {
    for (window, rate) in [(0.1, 100.0), (0.1, 10000.0), (1.0, 15000.0)] {
        expect(
            &signals(&format!("window_ms = {window}\nrate_hz = {rate}")),
            &["signals.window_ms and signals.rate_hz", "samples per channel; at least 16"],
        );
    }
    assert!(Scene::parse(&signals("window_ms = 1.0\nrate_hz = 16000.0"), "t").is_ok());
    // 1e6 samples on 64 sensors: 1.5 GB an impact, refused before any work.
    let sensors: Vec<String> = (0..64).map(|j| format!("[{}.0, 100.0]", 2 * j + 1)).collect();
    let table = format!("window_ms = 100.0\nrate_hz = 1e7\nsensors_mm = [{}]", sensors.join(", "));
    expect(
        &signals(&table),
        &["signals.window_ms, signals.rate_hz and signals.sensors_mm", "1568 MB", "at most 537 MB"],
    );
    let few = format!("window_ms = 100.0\nrate_hz = 1e7\nsensors_mm = [{}]", sensors[..4].join(", "));
    assert!(Scene::parse(&signals(&few), "t").is_ok());
}

const RADIUS: &str =
    "radius_mm = { distribution = \"lognormal\", median = 25.0, sigma_log = 0.2, min = 15.0, max = 40.0 }";

#[test]
fn degenerate_laws_are_refused_naming_the_parameter() {
    let radius = |law: &str| edit(ENSEMBLE, RADIUS, &format!("radius_mm = {{ {law} }}"));
    let field = "ensemble.families[0].radius_mm";
    for (law, needles) in [
        ("distribution = \"normal\", mean = 25.0, sd = 5e-324, min = 15.0, max = 40.0", vec!["radius_mm.sd = 5e-324"]),
        ("distribution = \"normal\", mean = 15.0, sd = 5e-324, min = 15.0, max = 40.0", vec!["radius_mm.sd = 5e-324"]),
        (
            "distribution = \"lognormal\", median = 5e-324, sigma_log = 10.0, min = 15.0, max = 40.0",
            vec!["radius_mm.median = 5e-324"],
        ),
        (
            "distribution = \"rosin-rammler\", scale = 5e-324, shape = 1.5, min = 15.0, max = 40.0",
            vec!["radius_mm.scale = 5e-324"],
        ),
        ("distribution = \"normal\", mean = nan, sd = 1.0, min = 15.0, max = 40.0", vec!["radius_mm.mean = NaN"]),
    ] {
        let mut all = needles.clone();
        all.push(field);
        expect(&radius(law), &all);
    }
    // A spread just above the floor (1e-12 of the bounds) is a law.
    let s = Scene::parse(&radius("distribution = \"normal\", mean = 25.0, sd = 4e-11, min = 15.0, max = 40.0"), "t");
    assert!(s.is_ok(), "{s:?}");
}

#[test]
fn bounds_that_meet_are_a_point_law() {
    let radius = |law: &str| edit(ENSEMBLE, RADIUS, &format!("radius_mm = {{ {law} }}"));
    for law in [
        "distribution = \"normal\", mean = 25.0, sd = 1.0, min = 25.0, max = 25.0",
        "distribution = \"normal\", mean = 25.0, sd = 5e-324, min = 25.0, max = 25.0",
        "distribution = \"lognormal\", median = 25.0, sigma_log = 0.2, min = 25.0, max = 25.0",
        "distribution = \"rosin-rammler\", scale = 25.0, shape = 1.5, min = 25.0, max = 25.0",
    ] {
        let s = Scene::parse(&radius(law), "t").unwrap_or_else(|e| panic!("{law}: {e}"));
        let f = &s.ensemble.unwrap().ensemble.families[0];
        assert_eq!(f.radius, identify::Distribution::Fixed { value: 0.025 }, "{law}");
    }
}

#[test]
fn identify_on_a_point_law_with_mean_min_and_max_equal_runs() {
    // Once a stack overflow (the truncated normal reflected [0, 0] for ever).
    let dir = tmp();
    let law = "{ distribution = \"normal\", mean = 1380.0, sd = 70.0, min = 1380.0, max = 1380.0 }";
    let scene = dir
        .write("point-law.toml", edit(&small_ensemble(), "density_kg_m3 = 1380.0", &format!("density_kg_m3 = {law}")));
    impact(["identify", "--no-features-csv", "--scene"]).arg(&scene).arg("--out").arg(dir.join("out")).success();
}

#[test]
fn nesting_deeper_than_any_scene_is_refused_not_a_crash() {
    let n = 100_000;
    for text in [
        format!("{DEFAULT_SCENE}\nx = {}{}\n", "[".repeat(n), "]".repeat(n)),
        format!("{DEFAULT_SCENE}\nx = {}1{}\n", "{a = ".repeat(n), "}".repeat(n)),
        edit(ENSEMBLE, "seed = 11", &format!("seed = 11\nvelocity_m_per_s.{}b = 1", "a.".repeat(n))),
    ] {
        assert!(Scene::parse(&text, "deep.toml").is_err());
    }
}

#[test]
fn dynamic_refuses_scenes_without_cases_or_beyond_the_run_budget() {
    let dir = tmp();
    // No velocities: once a panic in the empty table's CSV.
    let no_velocities = edit(ONE_IMPACT, "[velocities]\nm_per_s = [0.008]", "");
    let no_velocities = edit(&no_velocities, "analyses = [\"responses\"]", "analyses = [\"yield-velocity\"]");
    let scene = dir.write("no-velocities.toml", no_velocities);
    let run = impact(["dynamic", "--scene"]).arg(&scene).arg("--out").arg(dir.join("a")).fails();
    let err = &run.stderr;
    assert!(err.contains("velocities.m_per_s has 0 velocities") && !err.contains("panicked"), "{err}");
    // 5,000 points: refused like solve --model transient, before any work.
    let many = edit(ONE_IMPACT, "[points]\npairs_mm = [[229.2, 180.0]]", "[points]\ncount = 5000");
    let scene = dir.write("many.toml", many);
    let run = impact(["dynamic", "--scene"]).arg(&scene).arg("--out").arg(dir.join("b")).fails();
    let err = &run.stderr;
    assert!(err.contains("50000 transient runs") && err.contains("[transient] pairs_mm"), "{err}");
}

#[test]
fn loading_is_linear_in_the_number_of_names() {
    // 8,000 support sets once took 9.7 s to load (each name compared with every earlier one).
    // The transient comparison alone: the quasi-static rows of 8,000 sets are beyond their
    // budget (`quasi_static_work_beyond_the_budget_is_refused_when_the_scene_is_read`).
    let sets: String =
        (0..8000).map(|i| format!("[[conditions]]\nname = \"set {i}\"\nsupports = \"both-fixed\"\n")).collect();
    let transient = edit(ONE_IMPACT, "analyses = [\"responses\"]", "analyses = [\"transient\"]");
    let text = edit(&transient, "[[conditions]]\nname = \"Con 1\"\nsupports = \"both-fixed\"\n", &sets);
    let t0 = std::time::Instant::now();
    let s = Scene::parse(&text, "many.toml").unwrap();
    let seconds = t0.elapsed().as_secs_f64();
    assert_eq!(s.conditions.len(), 8000);
    assert!(seconds < 2.0, "8,000 support sets took {seconds:.2} s to load");
    // A repeat far down the list is still found, naming both.
    let repeated = edit(&text, "name = \"set 7999\"", "name = \"SET 12\"");
    expect(&repeated, &["conditions[7999].name", "'SET 12' and 'set 12'"]);
}

#[test]
fn signals_beyond_memory_are_refused_before_work() {
    // 1e6 samples on 10 sensors is 272 MB an impact (within the scene's limit); ten
    // velocities make 2.7 GB, refused by `impact signals` at once, naming the keys.
    let sensors: Vec<String> = (0..10).map(|j| format!("[{}.0, 100.0]", 10 * j + 5)).collect();
    let table = format!("window_ms = 100.0\nrate_hz = 1e7\nsensors_mm = [{}]", sensors.join(", "));
    let velocities = "m_per_s = [0.001, 0.002, 0.003, 0.004, 0.005, 0.006, 0.007, 0.008, 0.009, 0.01]";
    let text = edit(&signals(&table), "m_per_s = [0.008]", velocities);
    let dir = tmp();
    let scene = dir.write("big.toml", text);
    let t0 = std::time::Instant::now();
    let run = impact(["signals", "--scene"]).arg(&scene).arg("--out").arg(dir.join("out")).fails();
    assert!(run.stderr.contains("signals.window_ms x signals.rate_hz and signals.sensors_mm"), "{}", run.stderr);
    assert!(run.stderr.contains("10 impacts x 34 channels x 1000000 samples"), "{}", run.stderr);
    assert!(t0.elapsed().as_secs_f64() < 30.0, "refused only after work");
}

/// The modes the reduced model's mesh of the plate resolves: 4 degrees of freedom at each of
/// the (nx + 1)(nz + 1) nodes of its mesh, 20 elements along the longer side, an eighth of them.
fn most_modes(nx: usize, nz: usize) -> usize {
    4 * (nx + 1) * (nz + 1) / 8
}

#[test]
fn modes_beyond_what_the_plates_mesh_resolves_are_refused_before_work() {
    // The paper's plate, 1 mm thick: its mesh is 20 x 16 elements.
    let thin = |modes: &str| edit(&signals(&format!("modes = {modes}")), "thickness_mm = 8.0", "thickness_mm = 1.0");
    let most = most_modes(20, 16);
    expect(&thin("1000"), &["signals.modes", "1000", &format!("[1, {most}]"), "458.4 x 360 mm"]);
    expect(&thin(&(most + 1).to_string()), &["signals.modes", &format!("[1, {most}]")]);
    assert_eq!(Scene::parse(&thin(&most.to_string()), "t").unwrap().signals.modes, most);
    // 200 modes on Con 2's springs once searched the whole space of 1,428 vectors for 41 s
    // before an error; `impact signals` now refuses them at once.
    let dir = tmp();
    let scene = dir.write("thin.toml", edit(&thin("200"), CON_1, CON_2));
    let run = impact(["signals", "--scene"]).arg(&scene).arg("--out").arg(dir.join("out")).within(20).fails();
    assert!(run.stderr.contains("signals.modes") && run.stderr.contains(&format!("[1, {most}]")), "{}", run.stderr);
    // A square plate: 20 x 20 elements.
    let square = edit(&thin("1000"), "width_mm = 360.0", "width_mm = 458.4");
    expect(&square, &[&format!("[1, {}]", most_modes(20, 20))]);
    // A strip 458.4 x 60 mm: 20 x 2 elements (20 x 60/458.4 rounded to an even count, at
    // least 2). Asked for, 80 modes are refused; by default the modes are the plate's most.
    let strip = edit(&signals("modes = 80"), "width_mm = 360.0", "width_mm = 60.0");
    let strip = edit(&strip, "pairs_mm = [[229.2, 180.0]]", "pairs_mm = [[229.2, 30.0]]");
    expect(&strip, &["signals.modes", &format!("[1, {}]", most_modes(20, 2))]);
    let s = Scene::parse(&edit(&strip, "modes = 80", "rate_hz = 20000.0"), "t").unwrap();
    assert_eq!(s.signals.modes, most_modes(20, 2));
}

/// `n` support sets on springs, in place of Con 1.
fn sets(text: &str, n: usize) -> String {
    let sets: String = (0..n)
        .map(|i| {
            format!(
                "[[conditions]]\nname = \"set {i}\"\nsupports = \"both-springs\"\nspring_stiffness_n_per_m = {}e6\n",
                i + 1
            )
        })
        .collect();
    edit(text, CON_1, &sets)
}

#[test]
fn quasi_static_work_beyond_the_budget_is_refused_when_the_scene_is_read() {
    // 8,000 support sets at one point: each set's fundamental period (a factorization and an
    // eigensolution of the plate) took 20-35 ms, so `impact solve` ran for minutes.
    let many = sets(ONE_IMPACT, 8000);
    expect(&many, &["[[conditions]]", "8000", "budget"]);
    let dir = tmp();
    let scene = dir.write("many.toml", &many);
    let run = impact(["solve", "--scene"]).arg(&scene).within(20).fails();
    assert!(run.stderr.contains("8000 [[conditions]]") && run.stderr.contains("budget"), "{}", run.stderr);
    // 40 sets, 100 points and 1,000 velocities: four million result rows at about 0.04 ms each.
    let grid = edit(&sets(ONE_IMPACT, 40), "pairs_mm = [[229.2, 180.0]]", "count = 100");
    let velocities: Vec<String> = (1..=1000).map(|i| format!("{i}e-5")).collect();
    let grid = edit(&grid, "m_per_s = [0.008]", &format!("m_per_s = [{}]", velocities.join(", ")));
    expect(&grid, &["40 [[conditions]]", "100 points", "1000 velocities.m_per_s", "budget"]);
    // A sweep's points are counted too: 100 sets of 10,000 points each.
    let scene = dir.write("sets.toml", sets(ONE_IMPACT, 100));
    let run = impact(["sweep", "--count", "10000", "--scene"]).arg(&scene).within(20).fails();
    assert!(run.stderr.contains("10000 points") && run.stderr.contains("budget"), "{}", run.stderr);
    // Within the budget: a 316 x 316 grid of one case each, and 1,000 support sets.
    let big = edit(ONE_IMPACT, "pairs_mm = [[229.2, 180.0]]", "[points.grid]\nx_count = 316\nz_count = 316\n#");
    assert!(Scene::parse(&big, "t").is_ok());
    assert!(Scene::parse(&sets(ONE_IMPACT, 1000), "t").is_ok());
}
