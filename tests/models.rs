//! Every model behind every command, one row schema, "not applicable" rows, and validity
//! flags on both sides of each threshold, through the command line and the library.

mod common;

use common::reference::{contact_over_period_bound, COAL, PAPER_PLATE};
use common::scenes::{edit, two_sets, CLAMPED_PROPS, CON_1};
use common::{impact, tmp, BIN};
use coupled::plan::{fundamental_periods, run, run_transient, ModelKind, RowOutcome};
use coupled::transient::{Discretisation, TransientSettings};
use coupled::validity::QUASI_STATIC_MIN_RATIO;
use coupled::{BeamModel, PlateModel};
use impact::scene::{Scene, SceneSource};
use std::process::Command;

fn small() -> Scene {
    Scene::parse(&two_sets(), "small").unwrap()
}

/// What `impact ARGS --scene SCENE --json` printed.
fn json_of(args: &[&str], scene: &str) -> serde_json::Value {
    let dir = tmp();
    let path = dir.write("s.toml", scene);
    impact(args).arg("--scene").arg(&path).arg("--json").success().json()
}

/// solve, sweep and yield with each model: rows carry the model, z is the scene's z, and
/// the beam answers "not applicable" for the general set and numbers for Con 1.
#[test]
fn each_model_behind_each_command() {
    let small = two_sets();
    for model in ["beam", "plate", "transient", "mindlin"] {
        // A loose tolerance keeps each transient case on the starting discretisation.
        let v = json_of(&["solve", "--model", model, "--tolerance", "1e-2"], &small);
        let rows = v["results"]["responses"].as_array().unwrap();
        assert_eq!(rows.len(), 2, "{model}: one row per support set");
        for r in rows {
            assert_eq!(r["model"], model);
            assert!((r["z_m"].as_f64().unwrap() - 0.12).abs() < 1e-15, "z honoured: {r}");
        }
        let general = rows.iter().find(|r| r["condition"] == "clamped + props").unwrap();
        assert_eq!(general["applicable"], model != "beam", "{model}");
        assert!(v["status"].as_str().unwrap().starts_with("status: "));
    }
    // The sweep honours --count and keeps the model column.
    let v = json_of(&["sweep", "--count", "3", "--model", "plate"], &small);
    let rows = v["results"]["responses"].as_array().unwrap();
    assert_eq!(rows.len(), 3 * 2);
    assert!(rows.iter().all(|r| r["model"] == "plate"));
    // yield: beam and plate agree in kind, the beam not applicable to the general set.
    let v = json_of(&["yield", "--model", "all", "--tolerance", "1e-2"], &edit(&small, CON_1, ""));
    let rows = v["results"]["yields"].as_array().unwrap();
    assert_eq!(rows.len(), 4);
    for r in rows {
        let applicable = r["model"] != "beam";
        assert_eq!(r["applicable"], applicable, "{r}");
    }
}

/// Each plate theory is judged against its own range: a 30 mm plate (h/B = 0.083) is beyond
/// Kirchhoff's (0.05) and inside Reissner-Mindlin's (0.2); Mindlin's compliance is above
/// Kirchhoff's there (shear), and its rows judge the quasi-static criterion by its own, longer,
/// fundamental period (shear and rotary inertia lower the frequency).
#[test]
fn mindlin_is_judged_against_its_own_range() {
    let thick = edit(&two_sets(), "thickness_mm = 8.0", "thickness_mm = 30.0");
    let flag = "beyond the plate theory's range";
    let rows = |model: &str| json_of(&["solve", "--model", model], &thick)["results"]["responses"].clone();
    let (plate, mindlin) = (rows("plate"), rows("mindlin"));
    for (k, m) in plate.as_array().unwrap().iter().zip(mindlin.as_array().unwrap()) {
        let flags = |r: &serde_json::Value| r["validity_flags"].to_string();
        assert!(flags(k).contains(flag), "{k}");
        assert!(!flags(m).contains(flag), "{m}");
        assert!(m["compliance_m_per_N"].as_f64() > k["compliance_m_per_N"].as_f64(), "{k} {m}");
        assert!(m["quasi_static_ratio"].as_f64() < k["quasi_static_ratio"].as_f64(), "{k} {m}");
    }
}

/// The three models on the paper's Con 1 at one point: the beam and the plate differ only
/// through C (the same balance); the plate is more compliant than the beam here (reports:
/// +20 % at the centre), so its P_max is lower; the transient force at maximum compression
/// lies between the quasi-static plate and the rigid target (the plate near the load moves,
/// the rest does not).
#[test]
fn three_models_order_as_the_physics_says() {
    let s = small();
    let periods = fundamental_periods(&s).unwrap();
    let beam = run(&s, &BeamModel { plate: &s.plate }, ModelKind::Beam, &periods).unwrap();
    let fe = PlateModel::compute(&s.plate, &s.conditions, &s.point_pairs(), 20, 2).unwrap();
    let plate = run(&s, &fe, ModelKind::Plate, &periods).unwrap();
    let mut t = s.clone();
    t.analyses = vec![coupled::Analysis::Responses];
    t.transient_discretisation = Discretisation::Fixed { settings: TransientSettings::default() };
    let transient = run_transient(&t).unwrap();
    let p = |r: &coupled::Results| r.responses[0].values().unwrap().contact_force;
    let imp = coupled::plan::impact_of(&s, &s.bodies[0], 0.008);
    let rigid = imp.contact_stiffness
        * (5.0 * s.restitution * imp.mass * 0.008f64.powi(2) / (4.0 * imp.contact_stiffness)).powf(0.6);
    assert!(p(&plate) < p(&beam), "plate {} beam {}", p(&plate), p(&beam));
    assert!(p(&plate) < p(&transient) && p(&transient) < 1.01 * rigid);
    // Energy identity of every computed quasi-static row: the stores sum to E₀.
    for r in plate.responses.iter().chain(&beam.responses) {
        if let RowOutcome::Computed(v) = &r.outcome {
            let sum = v.rock_total_ratio + v.plate_ratio + v.spring_ratio;
            assert!((sum - 1.0).abs() < 1e-9, "{sum}");
        }
    }
}

/// Coal's yield velocity of eq. 54 under the paper's beam at mid-span (Con 1, simply supported:
/// C = x²(L - x)²/(3EIL), I = Bh³/12), written out here; δ_my is eq. 51 (analytic's
/// Drucker-Prager constants, checked against the paper's Table 2 in `paper_tables`).
fn coal_yield_velocity_mid_span() -> f64 {
    let (rho, e_coal, nu_coal, r) = COAL;
    let (l, b, h, e, nu, _) = PAPER_PLATE;
    let e_star = 1.0 / ((1.0 - nu_coal * nu_coal) / e_coal + (1.0 - nu * nu) / e);
    let k = 4.0 / 3.0 * r.sqrt() * e_star;
    let m = rho * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let coal = &Scene::default_scene().bodies[0];
    let d_my = analytic::DruckerPrager::of(coal).yield_compression(r, k);
    let x = l / 2.0;
    let c = (x * (l - x)).powi(2) / (3.0 * e * b * h.powi(3) / 12.0 * l);
    (2.0 / m * (2.0 * k / (5.0 * 0.65) * d_my.powf(2.5) + 0.5 * c * k * k * d_my.powi(3))).sqrt()
}

/// Each validity criterion flips where it should, in scenes built to sit on either side, each
/// side placed by a closed form that shares no code with the criterion.
///
/// - Elastic: the beam's v_y of coal at this point (x = L/2; the beam does not see z) by eq.
///   54 written out; 0.008 m/s must lie below it and 0.02 above, by more than the 1e-6
///   relative the balance's solver leaves.
/// - Quasi-static: t_c is Hertz's time on a rigid target (Johnson's 2.94 δ_m/v), T₁ is
///   bounded below by Rayleigh's quotient of the corner-held plate
///   ([`rayleigh_corner_omega`]), so t_c ω_R/2π bounds t_c/T₁ from above: on the paper's
///   plate it is below the 0.2 limit, so no FE T₁ can make the case quasi-static, and the
///   criterion's own t_c/T₁ may not exceed it. On the small thick plate struck by a soft
///   heavy sphere, the bound is 40 times the limit; the trial shape (one half-wave each way,
///   nodes only at the corners, as the fundamental's) puts ω_R above ω₁ by far less than a
///   factor 2 (the Rayleigh error is second order in the shape's), so half the bound, a
///   lower estimate of t_c/T₁, is still beyond the limit, and the criterion's value must lie
///   between half the bound and the bound.
#[test]
fn validity_flags_on_both_sides() {
    let flags = |text: &str| {
        let s = Scene::parse(text, "t").unwrap();
        let periods = fundamental_periods(&s).unwrap();
        let r = run(&s, &BeamModel { plate: &s.plate }, ModelKind::Beam, &periods).unwrap();
        r.responses[0].values().unwrap().validity
    };
    let small = two_sets();
    let v_y = coal_yield_velocity_mid_span();
    assert!(0.008 < v_y * (1.0 - 1e-6) && v_y * (1.0 + 1e-6) < 0.02, "v_y = {v_y}");
    assert!(flags(&small).elastic.unwrap().valid);
    assert!(!flags(&edit(&small, "m_per_s = [0.008]", "m_per_s = [0.02]")).elastic.unwrap().valid);
    // Thin plate: 8 mm on 360 mm is 0.022; 20 mm is 0.056.
    assert!(flags(&small).thin_plate.valid);
    assert!(!flags(&edit(&small, "thickness_mm = 8.0", "thickness_mm = 20.0")).thin_plate.valid);
    let limit = QUASI_STATIC_MIN_RATIO;
    let paper = contact_over_period_bound(COAL, PAPER_PLATE, 0.008);
    assert!(paper < limit, "bound {paper}");
    let q = flags(&small).quasi_static.unwrap();
    assert!(!q.valid && q.value <= paper, "t_c/T₁ = {} above its bound {paper}", q.value);
    let slow = common::scenes::edits(
        &small,
        &[
            ("length_mm = 458.4", "length_mm = 100.0"),
            ("width_mm = 360.0", "width_mm = 100.0"),
            ("thickness_mm = 8.0", "thickness_mm = 5.0"),
            ("youngs_modulus_gpa = 2.26", "youngs_modulus_gpa = 0.01"),
            ("pairs_mm = [[229.2, 120.0]]", "pairs_mm = [[50.0, 50.0]]"),
            (CLAMPED_PROPS, "[[conditions]]\nname = \"Con 1b\"\nsupports = \"both-fixed\"\n"),
        ],
    );
    let soft = (COAL.0, 0.01e9, COAL.2, COAL.3);
    let bound = contact_over_period_bound(soft, (0.1, 0.1, 0.005, 210e9, 0.3, 7850.0), 0.008);
    assert!(0.5 * bound > limit, "bound {bound}");
    let q = flags(&slow).quasi_static.unwrap();
    assert!(q.valid && (0.5 * bound..=bound).contains(&q.value), "t_c/T₁ = {} against {bound}", q.value);
}

/// `compare` and `dynamic` without --out write under impact-out/ in the working directory,
/// never into reports/.
#[test]
fn scene_reports_do_not_land_in_committed_reports() {
    let dir = tmp();
    std::fs::create_dir(dir.join("reports")).unwrap();
    let scene = dir.write(
        "s.toml",
        edit(&two_sets(), "analyses = [\"responses\", \"yield-velocity\"]", "analyses = [\"responses\"]"),
    );
    for cmd in ["compare", "dynamic"] {
        impact([cmd, "--tolerance", "1e-2", "--scene"]).arg(&scene).current_dir(dir.path()).success();
        assert!(dir.join("impact-out").join(format!("small-{cmd}")).join("index.md").exists(), "{cmd}");
    }
    assert_eq!(std::fs::read_dir(dir.join("reports")).unwrap().count(), 0);
}

/// A reader that stops early (`impact solve | head -1`) ends the program quietly: exit 0,
/// no panic. The pipe is closed before the program writes.
#[test]
fn closed_stdout_is_a_normal_end() {
    use std::process::Stdio;
    let mut child = Command::new(BIN)
        .args(["sweep", "--count", "2000"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success() && !err.contains("panicked"), "{:?}: {err}", o.status);
}

/// A request beyond the memory budget is refused before any work, saying how big it is.
#[test]
fn oversized_requests_are_refused_with_their_size() {
    let o = impact(["sweep", "--count", "100000"]).fails_with(1);
    let err = o.stderr;
    assert!(err.contains("100000 points") && err.contains("GB") && err.contains("at most"), "{err}");
    // The Mindlin plate's patch responses have their own budget: 3 sets x 1001 points.
    let err = impact(["sweep", "--count", "1001", "--model", "mindlin"]).fails_with(1).stderr;
    assert!(err.contains("3003 patch responses") && err.contains("2000"), "{err}");
}

/// `--json` on the report commands: the run's provenance and every file written, each
/// listed with the size and SHA-256 it has on disk; every CSV opens with the same provenance
/// line and every JSON with the same provenance object; the findings are those the report
/// wrote. The scene's hash does not change with how the file is written (comments, spacing).
#[test]
fn report_commands_print_json_with_provenance() {
    let dir = tmp();
    let small = edit(&two_sets(), "analyses = [\"responses\", \"yield-velocity\"]", "analyses = [\"responses\"]");
    let hash_of = |text: &str, name: &str| -> String {
        let scene = dir.write(name, text);
        let out = dir.join(format!("{name}-out"));
        let v = impact(["compare", "--json", "--scene"]).arg(&scene).arg("--out").arg(&out).success().json();
        let hash = v["provenance"]["scene_sha256"].as_str().unwrap().to_string();
        assert_eq!(hash.len(), 64);
        assert_eq!(v["provenance"]["version"], env!("CARGO_PKG_VERSION"));
        let files = v["files"].as_array().unwrap();
        assert!(files.len() >= 4);
        for f in files {
            let path = out.join(f["path"].as_str().unwrap());
            let bytes = std::fs::read(&path).unwrap();
            assert_eq!(bytes.len() as u64, f["bytes"].as_u64().unwrap(), "{}", path.display());
            let text = String::from_utf8_lossy(&bytes);
            if path.extension().is_some_and(|e| e == "csv") {
                let first = text.lines().next().unwrap();
                assert!(first.starts_with("# impact ") && first.contains(&hash), "{}: {first}", path.display());
            }
            if path.extension().is_some_and(|e| e == "json") {
                let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
                assert_eq!(doc["provenance"]["scene_sha256"], hash.as_str(), "{}", path.display());
            }
        }
        let findings = v["findings"][0]["findings"].as_array().expect("the comparison's findings");
        assert!(findings.iter().any(|f| f.as_str().unwrap().contains("more compliant than the beam")));
        hash
    };
    let a = hash_of(&small, "a.toml");
    let b = hash_of(&format!("# the same scene\n{}", small.replace(" = ", "  =  ")), "b.toml");
    assert_eq!(a, b, "comments and spacing do not change the scene's hash");
    let c = hash_of(&edit(&small, "restitution = 0.65", "restitution = 0.66"), "c.toml");
    assert_ne!(a, c, "a different scene has a different hash");
}
