//! Scene validation: every bad input is a clear error naming the field and its allowed
//! range, never a panic; and the command line writes nothing when the scene is bad.

mod common;

use common::scenes::{edit, expect_refused as expect};
use common::{impact, tmp};
use impact::scene::{Points, Scene, SceneSource, DEFAULT_SCENE};
use plate_fem::{CornerSupport, EdgeSupport};

fn with(from: &str, to: &str) -> String {
    edit(DEFAULT_SCENE, from, to)
}

#[test]
fn default_scene_is_valid() {
    let s = Scene::default_scene();
    assert_eq!(s.bodies.len(), 3);
    assert_eq!(s.conditions.len(), 3);
    assert!((s.plate.length() - 0.4584).abs() < 1e-15);
}

#[test]
fn every_shipped_scene_is_valid() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut n = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let p = entry.unwrap().path();
        if p.extension().is_some_and(|e| e == "toml") {
            Scene::load(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            n += 1;
        }
    }
    assert!(n >= 2);
}

#[test]
fn missing_key() {
    expect(&with("width_mm = 360.0\n", ""), &["width_mm", "missing"]);
}

#[test]
fn unknown_key() {
    expect(&with("width_mm = 360.0", "width_mm = 360.0\nwidht_mm = 1.0"), &["widht_mm", "unknown field"]);
}

#[test]
fn wrong_type() {
    expect(&with("thickness_mm = 8.0", "thickness_mm = \"eight\""), &["thickness_mm", "invalid type"]);
}

#[test]
fn nan_and_infinity() {
    expect(&with("length_mm = 458.4", "length_mm = nan"), &["plate.length_mm = NaN", "[1, 100000] mm"]);
    expect(
        &with("youngs_modulus_gpa = 210.0", "youngs_modulus_gpa = inf"),
        &["plate.youngs_modulus_gpa", "[0.000001, 10000] GPa"],
    );
}

#[test]
fn zero_or_negative_sizes() {
    expect(&with("thickness_mm = 8.0", "thickness_mm = 0.0"), &["plate.thickness_mm = 0", "[0.001, 10000] mm"]);
    expect(&with("width_mm = 360.0", "width_mm = -1.0"), &["plate.width_mm = -1", "[1, 100000] mm"]);
    expect(&with("radius_mm = 25.0", "radius_mm = 0.0"), &["bodies[0].radius_mm = 0", "[0.001, 10000] mm"]);
    expect(&with("density_kg_m3 = 1380.0", "density_kg_m3 = -5.0"), &["bodies[0].density_kg_m3", "[1, 100000]"]);
}

#[test]
fn poisson_ratio_outside_open_interval() {
    expect(&with("poisson_ratio = 0.3", "poisson_ratio = 0.5"), &["plate.poisson_ratio = 0.5", "(0, 0.5)"]);
    expect(&with("poisson_ratio = 0.28", "poisson_ratio = -0.1"), &["bodies[0].poisson_ratio = -0.1", "(0, 0.5)"]);
}

#[test]
fn restitution_outside_half_open_interval() {
    expect(&with("restitution = 0.65", "restitution = 0.0"), &["restitution = 0", "(0.01, 1]"]);
    expect(&with("restitution = 0.65", "restitution = 1.2"), &["restitution = 1.2", "(0.01, 1]"]);
    assert!(Scene::parse(&with("restitution = 0.65", "restitution = 1.0"), "t").is_ok(), "e = 1 is allowed");
}

#[test]
fn impact_point_outside_plate() {
    expect(&with("x_mm = [0.0,", "x_mm = [-1.0,"), &["points.x_mm[0] = -1", "[0, 458.4] mm"]);
    expect(&with("458.4]", "458.5]"), &["points.x_mm[8] = 458.5", "[0, 458.4] mm"]);
    expect(&with("x_mm = [0.0,", "pairs_mm = [[1.0, 400.0]]\n#"), &["points.pairs_mm[0][1] (z) = 400", "[0, 360] mm"]);
}

#[test]
fn non_positive_velocity() {
    expect(&with("m_per_s = [0.008,", "m_per_s = [0.0,"), &["velocities.m_per_s[0] = 0", "[1e-9, 1000] m/s"]);
    expect(&with("m_per_s = [0.008,", "m_per_s = [-0.008,"), &["velocities.m_per_s[0] = -0.008"]);
}

#[test]
fn friction_angle_outside_open_interval() {
    expect(
        &with("friction_angle_deg = 25.0", "friction_angle_deg = 90.0"),
        &["bodies[0].friction_angle_deg = 90", "(0, 90) deg"],
    );
    expect(&with("friction_angle_deg = 37.0", "friction_angle_deg = 0.0"), &["bodies[1].friction_angle_deg = 0"]);
}

#[test]
fn spring_stiffness_rules() {
    expect(
        &with("spring_stiffness_n_per_m = 5.11545e8", "spring_stiffness_n_per_m = 0.0"),
        &["conditions[1].spring_stiffness_n_per_m = 0", "[0.001, 1e18] N/m"],
    );
    expect(
        &with("spring_stiffness_n_per_m = 5.11545e8\n", ""),
        &["conditions[1].spring_stiffness_n_per_m", "required"],
    );
    expect(
        &with("supports = \"both-fixed\"", "supports = \"both-fixed\"\nspring_stiffness_n_per_m = 1.0"),
        &["conditions[0].spring_stiffness_n_per_m", "does not apply"],
    );
    expect(&with("supports = \"both-fixed\"", "supports = \"glued\""), &["supports", "unknown variant"]);
    // A general set and a preset at once, and a set that leaves the plate free to move.
    expect(
        &with("supports = \"both-fixed\"", "supports = \"both-fixed\"\n[conditions.edges]\nleft = \"clamped\""),
        &["conditions[0]", "not both"],
    );
    expect(
        &with("supports = \"both-fixed\"", "[conditions.corners]\nleft_near = \"fixed\""),
        &["conditions[0]", "rigid"],
    );
}

#[test]
fn points_need_exactly_one_of_list_or_count() {
    expect(&with("[points]\n", "[points]\ncount = 5\n"), &["points", "exactly one of"]);
    // z_mm beside x_mm used to form a grid silently; now the scene must say which it means.
    expect(&with("[points]\n", "[points]\nz_mm = [90.0]\n"), &["points.z_mm", "pairs_mm", "[points.grid]"]);
    expect(&with("x_mm = [0.0,", "count = 1e9\n#"), &["points.count = 1000000000", "[2, 100000]"]);
    expect(&with("x_mm = [0.0,", "count = 2.5\n#"), &["points.count", "whole number"]);
}

#[test]
fn empty_lists_are_rejected() {
    expect(&with("m_per_s = [0.008, 0.0025]", "m_per_s = []"), &["velocities.m_per_s", "empty"]);
    let text = DEFAULT_SCENE.replace(
        &DEFAULT_SCENE[DEFAULT_SCENE.find("analyses = [").unwrap()..DEFAULT_SCENE.find("]\n\n[plate]").unwrap() + 1],
        "analyses = []",
    );
    expect(&text, &["analyses", "empty"]);
}

#[test]
fn not_toml_at_all() {
    expect("this is not = = toml", &["test.toml"]);
    expect("", &["missing field"]);
}

/// The binary reports a bad scene on stderr with exit code 1, does not panic, and writes
/// nothing into --out.
#[test]
fn command_line_rejects_bad_scene_without_writing() {
    let dir = tmp();
    let scene = dir.write("bad.toml", with("restitution = 0.65", "restitution = 7.0"));
    let out = dir.join("out");
    let o = impact(["solve", "--scene"]).arg(&scene).arg("--out").arg(&out).fails_with(1);
    let err = o.stderr;
    assert!(err.contains("restitution = 7") && err.contains("(0.01, 1]"), "{err}");
    assert!(!err.contains("panicked"));
    assert!(!out.exists());
}

#[test]
fn command_line_missing_file() {
    let o = impact(["yield", "--scene", "/nonexistent/x.toml"]).fails_with(1);
    assert!(o.stderr.contains("/nonexistent/x.toml"));
}

/// A good run writes CSV and JSON, and the JSON parses.
#[test]
fn command_line_writes_csv_and_json() {
    let dir = tmp();
    impact(["solve", "--out"]).arg(dir.path()).success();
    let json = std::fs::read_to_string(dir.join("results.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["results"]["responses"].as_array().unwrap().len(), 9 * 3 * 3 * 2);
    assert_eq!(v["version"], env!("CARGO_PKG_VERSION"));
    // One CSV per support set, named by its position in the scene (names need not be
    // file-name safe or unique after slugging).
    assert!(dir.join("responses-2.csv").exists());
    // Con 1 has no springs: its table has no spring column.
    let con1 = std::fs::read_to_string(dir.join("responses-1.csv")).unwrap();
    // The first line is the provenance comment, the second the header.
    let mut lines = con1.lines();
    assert!(lines
        .next()
        .unwrap()
        .starts_with(&format!("# impact {}; scene paper-table-1; scene_sha256 ", env!("CARGO_PKG_VERSION"))));
    let header = lines.next().unwrap();
    assert!(
        header.starts_with("model,body,condition,x_m,z_m,velocity_m_per_s,") && !header.contains("spring"),
        "{header}"
    );
    assert_eq!(v["provenance"]["scene"], "paper-table-1");
}

/// Huge values that pass a "positive" check would overflow after conversion to SI (1e300 mm
/// cubed); they are refused in the file's units with the field and the range.
#[test]
fn values_that_would_overflow_in_si_are_refused() {
    expect(&with("length_mm = 458.4", "length_mm = 1e300"), &["plate.length_mm = 1e300", "[1, 100000] mm"]);
    expect(&with("radius_mm = 25.0", "radius_mm = 1e-300"), &["bodies[0].radius_mm = 1e-300", "mm"]);
    expect(
        &with("spring_stiffness_n_per_m = 5.11545e8", "spring_stiffness_n_per_m = 5e-324"),
        &["conditions[1].spring_stiffness_n_per_m = 5e-324"],
    );
    expect(&with("thickness_mm = 8.0", "thickness_mm = 400.0"), &["plate.thickness_mm", "not a plate"]);
    expect(&with("m_per_s = [0.008,", "m_per_s = [1e9,"), &["velocities.m_per_s[0] = 1000000000", "1000] m/s"]);
}

/// A general support set: per-corner springs of their own stiffness, a clamped edge, and
/// the beam's view of it.
#[test]
fn general_support_set_in_a_scene() {
    let text = with(
        "[[conditions]]\nname = \"Con 1\"\nsupports = \"both-fixed\"",
        "[[conditions]]\nname = \"props\"\n[conditions.edges]\nleft = \"clamped\"\n[conditions.corners]\nright_near = { spring_n_per_m = 1e6 }\nright_far = { spring_n_per_m = 2e6 }",
    );
    let s = Scene::parse(&text, "t").unwrap();
    let set = &s.conditions[0];
    assert_eq!(set.name, "props");
    assert_eq!(set.supports.edges, [EdgeSupport::Clamped, EdgeSupport::Free, EdgeSupport::Free, EdgeSupport::Free]);
    assert_eq!(set.supports.corners[1], CornerSupport::Spring(1e6));
    assert_eq!(set.supports.corners[3], CornerSupport::Spring(2e6));
    assert_eq!(set.beam_condition(), None);
    // The presets stay the paper's conditions.
    assert!(s.conditions[1].beam_condition().is_some());
}

/// Points are explicit pairs, or a grid the scene names as a grid: the same positions in
/// either form give the same points.
#[test]
fn pairs_and_grid() {
    let pairs = with("x_mm = [0.0,", "pairs_mm = [[100.0, 0.0], [100.0, 90.0], [200.0, 0.0], [200.0, 90.0]]\n#");
    let grid = with("x_mm = [0.0,", "[points.grid]\nx_mm = [100.0, 200.0]\nz_mm = [0.0, 90.0]\n#");
    let (a, b) = (Scene::parse(&pairs, "p").unwrap(), Scene::parse(&grid, "g").unwrap());
    assert!(matches!(a.points, Points::Pairs { .. }));
    assert!(matches!(b.points, Points::Grid { .. }));
    assert_eq!(a.point_pairs(), b.point_pairs());
    assert_eq!(a.point_pairs().len(), 4);
    // x_mm alone is the centreline.
    let d = Scene::default_scene();
    assert!(d.point_pairs().iter().all(|&(_, z)| z == d.plate.width() / 2.0));
}

/// A scene "file" that is a device, a FIFO or a directory is refused before it is read.
#[test]
fn non_regular_scene_files_are_refused() {
    for path in ["/dev/zero", "/tmp"] {
        let e = Scene::load(std::path::Path::new(path)).unwrap_err().to_string();
        assert!(e.contains("not a regular file"), "{path}: {e}");
    }
}

/// Names title tables and name files: empty, overlong, or equal after reduction to a file
/// stem ("A" and "a!") are refused; a very long name would also have broken the table layout.
#[test]
fn names_are_checked() {
    expect(&with("name = \"coal\"", "name = \"\""), &["bodies[0].name", "empty"]);
    expect(
        &with("name = \"coal\"", &format!("name = \"{}\"", "c".repeat(70_000))),
        &["bodies[0].name", "70000 characters"],
    );
    expect(&with("name = \"gangue 1\"", "name = \"COAL!\""), &["bodies[1].name", "same file name"]);
    expect(&with("name = \"Con 2\"", "name = \"con-1\""), &["conditions[1].name", "same file name"]);
    expect(&with("name = \"coal\"", "name = \"!!\""), &["bodies[0].name", "no letter or digit"]);
}

/// A loose solver tolerance used to return the rigid-plate starting value marked converged;
/// the tolerance is bounded to what a root means.
#[test]
fn solver_tolerance_is_bounded() {
    let text = format!("{DEFAULT_SCENE}\n[solver]\ntolerance = 0.999999\n");
    expect(&text, &["solver.tolerance = 0.999999", "[1e-14, 0.001]"]);
    let text = format!("{DEFAULT_SCENE}\n[solver]\ntolerance = 1e-300\n");
    expect(&text, &["solver.tolerance = 1e-300"]);
}

/// The contact law is a scene choice: the paper's Flores law by default, every law of the
/// registry by its key, anything else refused naming the key.
#[test]
fn contact_law_is_a_scene_choice() {
    use coupled::transient::law::LawKind;
    assert_eq!(Scene::default_scene().contact_law, LawKind::Flores);
    assert_eq!(LawKind::from_key("thornton"), Some(LawKind::Thornton));
    for &kind in LawKind::ALL {
        let s = Scene::parse(&format!("contact_law = \"{}\"\n{DEFAULT_SCENE}", kind.key()), "t").unwrap();
        assert_eq!(s.contact_law, kind);
    }
    expect(&format!("contact_law = \"glue\"\n{DEFAULT_SCENE}"), &["contact_law", "'glue' is not a contact law"]);
    // The refusal lists every key of the registry.
    let keys: Vec<String> = LawKind::ALL.iter().map(|l| format!("\"{}\"", l.key())).collect();
    expect(&format!("contact_law = \"glue\"\n{DEFAULT_SCENE}"), &keys.iter().map(String::as_str).collect::<Vec<_>>());
}

/// `[signals]`: defaults when absent, values in SI when given, and every bad value named
/// with its range before anything is computed.
#[test]
fn signals_table() {
    let s = Scene::default_scene();
    assert_eq!(s.signals, coupled::reduced::SignalSettings::default());
    let text = format!(
        "{DEFAULT_SCENE}\n[signals]\nwindow_ms = 10.0\nrate_hz = 50000.0\ndamping_ratio = 0.01\nmodes = 40\nsensors_mm = [[100.0, 90.0], [458.4, 0.0]]\n"
    );
    let s = Scene::parse(&text, "t").unwrap();
    assert_eq!(s.signals.window, 0.010);
    assert_eq!((s.signals.rate_hz, s.signals.damping_ratio, s.signals.modes), (50000.0, 0.01, 40));
    assert_eq!(s.signals.sensors, vec![(0.1, 0.09), (0.4584, 0.0)]);
    let spec = s.signals.spec();
    assert_eq!((spec.samples(), spec.sensors.len()), (500, 2));
    let bad = |table: &str, needles: &[&str]| expect(&format!("{DEFAULT_SCENE}\n[signals]\n{table}\n"), needles);
    bad("window_ms = 0.0", &["signals.window_ms = 0", "[0.1, 1000] ms"]);
    bad("rate_hz = 1e300", &["signals.rate_hz = 1e300", "Hz"]);
    bad(
        "window_ms = 1000.0\nrate_hz = 1e7",
        &["signals.window_ms and signals.rate_hz", "10000000 samples per channel; at most 1000000"],
    );
    bad("damping_ratio = -0.1", &["signals.damping_ratio = -0.1", "[0, 0.5]"]);
    bad("damping_ratio = nan", &["signals.damping_ratio = NaN"]);
    bad("modes = 2.5", &["signals.modes", "not a whole number"]);
    bad("modes = 0", &["signals.modes = 0", "[1, 220]"]);
    bad("sensors_mm = [[500.0, 10.0]]", &["signals.sensors_mm[0][0] (x) = 500", "[0, 458.4] mm"]);
    bad("sensors_mm = [[10.0, -1.0]]", &["signals.sensors_mm[0][1] (z) = -1"]);
    bad("sensor_mm = [[10.0, 1.0]]", &["sensor_mm", "unknown field"]);
}

/// Gravity and the plate's damping: off in the paper's scene, gravity on by default in a
/// caving stream (a scene with `[ensemble]`), Rayleigh's α and β from the ratio at the two
/// frequencies (Chopra eq. 11.4.9, written out here), the same damping handed to the reduced
/// model, and every bad value or second definition named before anything is computed.
#[test]
fn gravity_and_plate_damping() {
    use std::f64::consts::PI;
    let paper = Scene::default_scene();
    assert_eq!((paper.gravity, paper.plate_damping, paper.signals.rayleigh), (0.0, None, None));
    let caving = Scene::parse(&std::fs::read_to_string("scenes/caving-stream.toml").unwrap(), "t").unwrap();
    assert_eq!(caving.gravity, 9.80665);
    // An ensemble of given velocities is the paper's impact, without gravity.
    let paper_ensemble =
        Scene::parse(&std::fs::read_to_string("scenes/paper-velocities-ensemble.toml").unwrap(), "t").unwrap();
    assert_eq!(paper_ensemble.gravity, 0.0);
    let s = Scene::parse(&format!("gravity_m_per_s2 = 0.0\n{DEFAULT_SCENE}"), "t").unwrap();
    assert_eq!(s.gravity, 0.0);
    let text = format!(
        "gravity_m_per_s2 = 9.81\n{DEFAULT_SCENE}\n[plate_damping]\nratio = 0.02\nfrequencies_hz = [100.0, 3000.0]\n"
    );
    let s = Scene::parse(&text, "t").unwrap();
    assert_eq!(s.gravity, 9.81);
    let r = s.plate_damping.expect("given");
    let (wa, wb) = (2.0 * PI * 100.0, 2.0 * PI * 3000.0);
    assert!((r.alpha - 2.0 * 0.02 * wa * wb / (wa + wb)).abs() < 1e-12 * r.alpha);
    assert!((r.beta - 2.0 * 0.02 / (wa + wb)).abs() < 1e-12 * r.beta);
    assert_eq!(s.signals.rayleigh, Some(r));
    assert_eq!(s.transient_start().damping, Some(r));
    expect(&format!("gravity_m_per_s2 = -1.0\n{DEFAULT_SCENE}"), &["gravity_m_per_s2 = -1", "[0, 100] m/s²"]);
    expect(&format!("gravity_m_per_s2 = 9806.65\n{DEFAULT_SCENE}"), &["gravity_m_per_s2 = 9806.65"]);
    let bad = |table: &str, needles: &[&str]| expect(&format!("{DEFAULT_SCENE}\n[plate_damping]\n{table}\n"), needles);
    bad("ratio = 0.0\nfrequencies_hz = [1.0, 2.0]", &["plate_damping.ratio = 0", "(0, 0.5]"]);
    bad("ratio = 0.01\nfrequencies_hz = [2.0, 1.0]", &["plate_damping.frequencies_hz", "increasing order"]);
    bad("ratio = 0.01\nfrequencies_hz = [1.0, 2.0, 3.0]", &["plate_damping.frequencies_hz", "exactly two"]);
    bad("ratio = 0.01\nfrequencies_hz = [0.0, 2.0]", &["plate_damping.frequencies_hz[0] = 0", "Hz"]);
    bad("ratio = 0.01", &["frequencies_hz"]);
    bad("ratio = 0.01\nfrequencies_hz = [1.0, 2.0]\nalpha = 3.0", &["alpha", "unknown field"]);
    expect(
        &format!("{DEFAULT_SCENE}\n[plate_damping]\nratio = 0.01\nfrequencies_hz = [1.0, 2.0]\n[signals]\ndamping_ratio = 0.01\n"),
        &["signals.damping_ratio", "[plate_damping]"],
    );
}
