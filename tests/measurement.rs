//! The measurement chain of the identification (`[measurement]`): every bad value is an error
//! naming the key, the value and its range, before anything runs; a transparent chain gives
//! the features of the model's own signals; a background's level reaches the features as
//! stated; and a run under a chain is the same on one and two threads.

mod common;

use common::scenes::{edit, expect_refused as expect, ENSEMBLE};
use common::{impact, tmp};
use impact::scene::{Scene, SceneSource};

/// [`ENSEMBLE`] with a 5 ms window and `measurement` appended.
fn with_chain(measurement: &str) -> String {
    format!("{}\n{measurement}", edit(ENSEMBLE, "modes = 24", "modes = 24\nwindow_ms = 5.0"))
}

/// A chain on the model's 20 kHz: the ADC at 10 kHz, accelerations only.
const CHAIN: &str = r#"
[measurement]
rate_hz = 10000.0
sensor = { resonance_hz = 8000.0, resonance_damping = 0.05, high_pass_hz = 0.5 }
anti_alias = { order = 8, corner_hz = 4000.0 }

[measurement.acceleration]
adc_range_m_s2 = 100.0
adc_bits = 16
noise = "pink"
noise_rms_m_s2 = 0.01
pink_flat_below_hz = 10.0
tones_m_s2 = [[24.7, 0.005]]
"#;

#[test]
fn a_chain_is_read_in_si() {
    let s = Scene::parse(&with_chain(CHAIN), "chain").unwrap();
    let c = s.measurement.unwrap();
    assert_eq!(c.rate_hz, 10_000.0);
    assert_eq!(c.sensor.resonance, Some((8000.0, 0.05)));
    assert_eq!(c.recordings.len(), 1);
    let force = with_chain(&format!(
        "{CHAIN}\n[measurement.support_force]\nadc_range_kn = 2.0\nadc_bits = 12\nnoise = \"white\"\nnoise_rms_kn = 0.5\n"
    ));
    let s = Scene::parse(&force, "chain").unwrap();
    let f = &s.measurement.unwrap().recordings[1];
    // kN to N, and the white background's rms over 0-5 kHz is what was written.
    assert_eq!(f.range, 2000.0);
    assert!((f.noise_rms(10_000.0) - (500f64.powi(2) + f.step().powi(2) / 12.0).sqrt()).abs() < 1e-9);
    // Microstrain to strain.
    let gauges = with_chain(&format!("{CHAIN}\n[measurement.strain]\nadc_range_microstrain = 500.0\nadc_bits = 24\n"));
    let s = Scene::parse(&gauges, "chain").unwrap();
    let g = &s.measurement.unwrap().recordings[1];
    assert_eq!((g.measurand, g.range), (identify::measurement::Measurand::Strain, 500e-6));
}

#[test]
fn bad_chains_name_the_key_the_value_and_the_range() {
    let bad = |from: &str, to: &str, needles: &[&str]| expect(&with_chain(&CHAIN.replace(from, to)), needles);
    bad("rate_hz = 10000.0", "rate_hz = 15000.0", &["measurement", "15000", "20000", "whole number"]);
    bad("corner_hz = 4000.0", "corner_hz = 6000.0", &["measurement.anti_alias.corner_hz = 6000", "(0, 5000)"]);
    bad("resonance_hz = 8000.0", "resonance_hz = 12000.0", &["measurement.sensor.resonance_hz = 12000", "0.45"]);
    bad("order = 8", "order = 20", &["measurement.anti_alias.order = 20", "[1, 16]"]);
    bad("order = 8", "order = 2.5", &["measurement.anti_alias.order", "not a whole number"]);
    bad("adc_bits = 16", "adc_bits = 40", &["measurement.acceleration.adc_bits = 40", "[1, 32]"]);
    bad("adc_range_m_s2 = 100.0", "adc_range_m_s2 = -1.0", &["measurement.acceleration.adc_range_m_s2 = -1"]);
    bad("pink_flat_below_hz = 10.0", "", &["measurement.acceleration.pink_flat_below_hz", "required"]);
    bad("noise = \"pink\"", "noise = \"brown\"", &["measurement.acceleration.noise", "'brown'", "\"measured\""]);
    bad("noise_rms_m_s2 = 0.01", "noise_rms_m_s2 = nan", &["measurement.acceleration.noise_rms_m_s2 = NaN"]);
    bad("[[24.7, 0.005]]", "[[6000.0, 0.005]]", &["tones_m_s2[0][0] (frequency) = 6000", "(0, 5000)"]);
    bad("[[24.7, 0.005]]", "[[24.7]]", &["tones_m_s2[0]", "exactly two"]);
    bad("resonance_damping = 0.05, ", "", &["measurement.sensor", "needs both"]);
    bad(
        "noise = \"pink\"",
        "noise = \"measured\"\nnoise_psd_m2_s4_per_hz = [[0.0, 1e-6], [100.0, 1e-6], [50.0, 1e-7]]",
        &["noise_psd_m2_s4_per_hz[2][0] (frequency)", "50 Hz does not rise above", "100 Hz"],
    );
    bad("noise = \"pink\"", "noise = \"measured\"", &["noise_psd_m2_s4_per_hz", "required"]);
    bad("[measurement.acceleration]", "[measurement.velocity]", &["unknown field", "velocity"]);
    // A chain that records nothing, and a chain without the analysis that reads it.
    let start = CHAIN.find("[measurement.acceleration]").unwrap();
    expect(&with_chain(&CHAIN[..start]), &["measurement", "records nothing"]);
    let text = format!("{}\n{CHAIN}", impact::scene::DEFAULT_SCENE);
    expect(&text, &["measurement", "is read only by the \"identify\" and \"drops\" analyses"]);
}

/// The features of `dir/features.csv`'s acceleration rows: (condition, impact, channel) → the
/// peak, RMS and spectral centroid columns.
fn acceleration_features(dir: &std::path::Path) -> Vec<(String, [f64; 3])> {
    let text = std::fs::read_to_string(dir.join("features.csv")).unwrap();
    let mut lines = text.lines().skip(1);
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col =
        |name: &str| header.iter().position(|h| h.starts_with(name)).unwrap_or_else(|| panic!("{name}: {header:?}"));
    let (quantity, peak, rms, centroid) = (col("quantity"), col("peak"), col("rms"), col("spectral_centroid"));
    lines
        .filter_map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[quantity] == "acceleration").then(|| {
                let v = |i: usize| f[i].parse::<f64>().unwrap();
                (format!("{},{},{}", f[0], f[1], f[2..quantity + 3].join(",")), [v(peak), v(rms), v(centroid)])
            })
        })
        .collect()
}

/// An ideal sensor, no filter, the ADC at the model's rate with a step of 2e3/2^32 m/s² and no
/// background: the chain is the identity to half a step, so every acceleration feature is the
/// noise-free run's (which never enters the chain's code) to that step.
#[test]
fn a_transparent_chain_gives_the_model_features() {
    let dir = tmp();
    let plain = dir.write("plain.toml", with_chain(""));
    let transparent = dir.write(
        "transparent.toml",
        with_chain(
            "[measurement]\nrate_hz = 20000.0\n[measurement.acceleration]\nadc_range_m_s2 = 1000.0\nadc_bits = 32\n",
        ),
    );
    impact(["identify", "--scene"]).arg(&plain).arg("--out").arg(dir.join("a")).arg("--json").success();
    impact(["identify", "--scene"]).arg(&transparent).arg("--out").arg(dir.join("b")).arg("--json").success();
    let (a, b) = (acceleration_features(&dir.join("a")), acceleration_features(&dir.join("b")));
    assert_eq!(a.len(), b.len());
    assert!(!a.is_empty());
    let q = 2000.0 / 2f64.powi(32);
    for ((ka, fa), (kb, fb)) in a.iter().zip(&b) {
        assert_eq!(ka, kb);
        assert!((fa[0] - fb[0]).abs() <= 0.5 * q + 1e-15 * fa[0], "{ka}: peak {} against {}", fa[0], fb[0]);
        assert!((fa[1] - fb[1]).abs() <= 0.5 * q + 1e-15 * fa[1], "{ka}: rms {} against {}", fa[1], fb[1]);
        // The centroid Σf P/Σ P moves by at most about 2‖δx‖/‖x‖ of the Nyquist frequency
        // for a perturbation δx of the samples: with abs(δx) ≤ q/2, 2 (q/2)/rms × 10 kHz.
        let bound = q / fa[1] * 1e4;
        assert!((fa[2] - fb[2]).abs() <= bound, "{ka}: centroid {} against {} (bound {bound})", fa[2], fb[2]);
    }
}

/// A white background far above the signal: each window's RMS feature is the background's σ
/// to its sampling error. Over n = 100 samples a window the mean square of a Gaussian is
/// σ²(1 ± √(2/n)), so the RMS is σ(1 - 1/(4n) ± 1/√(2n)) to first order, and the mean of the
/// relative error over N independent windows lies within 4/√(2nN) of -1/(4n).
#[test]
fn a_background_reaches_the_features_at_its_level() {
    let dir = tmp();
    let chain = "[measurement]\nrate_hz = 20000.0\nseed = 4\n[measurement.acceleration]\nadc_range_m_s2 = 1e6\nadc_bits = 24\nnoise = \"white\"\nnoise_rms_m_s2 = 1000.0\n";
    let scene = dir.write("noisy.toml", with_chain(chain));
    impact(["identify", "--scene"]).arg(&scene).arg("--out").arg(dir.join("n")).arg("--json").success();
    let rows = acceleration_features(&dir.join("n"));
    let sigma = (1e6f64 + (2e6 / 2f64.powi(24)).powi(2) / 12.0).sqrt();
    let mean: f64 = rows.iter().map(|(_, f)| f[1] / sigma - 1.0).sum::<f64>() / rows.len() as f64;
    let (n, windows) = (100.0, rows.len() as f64);
    let bound = 4.0 / (2.0 * n * windows).sqrt();
    assert!(
        (mean + 1.0 / (4.0 * n)).abs() < bound,
        "mean relative error of the RMS {mean} over {windows} windows (bound {bound})"
    );
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("n").join("summary.json")).unwrap()).unwrap();
    for c in summary["conditions"].as_array().unwrap() {
        assert_eq!(c["measurement"]["clipped_share"], 0.0, "nothing clips at a range 1000 σ wide");
    }
}

/// The backgrounds are drawn per impact from their own streams: a run under a chain writes
/// the same rows on one and two threads.
#[test]
fn a_run_under_a_chain_is_the_same_on_one_and_two_threads() {
    let dir = tmp();
    let scene = dir.write("chain.toml", with_chain(CHAIN));
    for (out, threads) in [("one", "1"), ("two", "2")] {
        impact(["identify", "--scene"])
            .arg(&scene)
            .arg("--out")
            .arg(dir.join(out))
            .arg("--json")
            .env("RAYON_NUM_THREADS", threads)
            .success();
    }
    for f in ["impacts.csv", "features.csv"] {
        assert!(
            std::fs::read(dir.join("one").join(f)).unwrap() == std::fs::read(dir.join("two").join(f)).unwrap(),
            "{f} differs"
        );
    }
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("one").join("summary.json")).unwrap()).unwrap();
    let m = &summary["conditions"][0]["measurement"];
    assert_eq!(m["decimation"], 2);
    assert!(m["snr"][0]["snr_db"][1].as_f64().unwrap().is_finite());
}

/// A measured PSD given as a file beside the scene is the same chain as its points written
/// inline; a file and inline points at once, a missing file and a bad line are refused with
/// the key and the file named.
#[test]
fn a_measured_psd_file_is_its_points() {
    let dir = tmp();
    let inline = "noise = \"measured\"\nnoise_psd_m2_s4_per_hz = [[0.0, 1e-6], [100.0, 1e-6], [2000.0, 1e-8]]";
    let by_file = "noise = \"measured\"\nnoise_psd_file = \"psd/measured.csv\"";
    std::fs::create_dir_all(dir.join("psd")).unwrap();
    std::fs::write(
        dir.join("psd/measured.csv"),
        "# tail beam, shearer running\nfrequency_hz,psd\n0,1e-6\n100,1e-6\n2000,1e-8\n",
    )
    .unwrap();
    let chain =
        |noise: &str| with_chain(&CHAIN.replace("noise = \"pink\"", noise).replace("noise_rms_m_s2 = 0.01\n", ""));
    let a = Scene::parse(&chain(inline), "inline").unwrap();
    let b = Scene::load(&dir.write("by-file.toml", chain(by_file))).unwrap();
    assert_eq!(a.measurement, b.measurement);
    let both = format!("{inline}\nnoise_psd_file = \"psd/measured.csv\"");
    let refused = |path: &std::path::Path, needles: &[&str]| {
        let e = Scene::load(path).unwrap_err().to_string();
        for n in needles {
            assert!(e.contains(n), "'{e}' does not mention '{n}'");
        }
    };
    refused(&dir.write("both.toml", chain(&both)), &["measurement.acceleration.noise_psd_file", "both given"]);
    refused(
        &dir.write("missing.toml", chain(&by_file.replace("measured.csv", "nothing.csv"))),
        &["measurement.acceleration.noise_psd_file", "nothing.csv", "cannot be read"],
    );
    refused(
        &dir.write("white.toml", chain(&by_file.replace("\"measured\"", "\"white\"\nnoise_rms_m_s2 = 0.01"))),
        &["measurement.acceleration.noise_psd_file", "read only by noise = \"measured\""],
    );
    std::fs::write(dir.join("psd/falling.csv"), "0,1e-6\n100,1e-6\n50,1e-7\n").unwrap();
    refused(
        &dir.write("falling.toml", chain(&by_file.replace("measured.csv", "falling.csv"))),
        &["noise_psd_file ('psd/falling.csv'), point[2][0] (frequency)", "does not rise"],
    );
    std::fs::write(dir.join("psd/bad.csv"), "0,1e-6\n100\n").unwrap();
    refused(
        &dir.write("bad.toml", chain(&by_file.replace("measured.csv", "bad.csv"))),
        &["noise_psd_file", "bad.csv", "line 2", "has 1 numbers"],
    );
}

/// `[signals] modes = "chain"`: on each support set the reduced model keeps the fewest modes
/// whose highest the chain's gain above stays within the band tolerance, and one fewer would
/// not (checked on the plate's own frequencies and the chain's analog gain); the page says
/// so. Without a chain, or as another word, it is refused with the key named.
#[test]
fn the_chain_chooses_the_modes() {
    use coupled::reduced::frequencies_hz;
    use identify::measurement::Chain;
    // An 8th-order Butterworth at 2 kHz: its gain falls to 1e-3 at 2.37 × 2 kHz = 4.7 kHz,
    // within the reach of 24-plus modes of the paper's plate.
    let chain = "[measurement]\nrate_hz = 10000.0\nanti_alias = { order = 8, corner_hz = 2000.0 }\n[measurement.acceleration]\nadc_range_m_s2 = 1000.0\nadc_bits = 24\n";
    let text = with_chain(chain).replace("modes = 24", "modes = \"chain\"");
    let dir = tmp();
    let scene_file = dir.write("chain-modes.toml", &text);
    let scene = Scene::parse(&text, "chain").unwrap();
    assert!(scene.signals.modes_from_chain);
    impact(["identify", "--scene"]).arg(&scene_file).arg("--out").arg(dir.join("o")).arg("--json").success();
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("o").join("summary.json")).unwrap()).unwrap();
    let c = Chain::new(scene.measurement.clone().unwrap(), scene.signals.rate_hz).unwrap();
    for (set, result) in scene.conditions.iter().zip(summary["conditions"].as_array().unwrap()) {
        let n = result["chain_modes"].as_u64().unwrap() as usize;
        let f = frequencies_hz(&scene.plate, set, scene.signals.reduced()).unwrap();
        assert!(n < f.len(), "{}: {n} of {} modes", set.name, f.len());
        assert!(c.gain_above(f[n - 1]) <= 1e-3 && c.gain_above(f[n - 2]) > 1e-3, "{}: {n}", set.name);
    }
    let page = std::fs::read_to_string(dir.join("o").join("index.md")).unwrap();
    assert!(page.contains("the fewest the measurement chain needs"), "{page}");
    expect(&edit(ENSEMBLE, "modes = 24", "modes = \"chain\""), &["signals.modes", "no [measurement]"]);
    expect(&with_chain(chain).replace("modes = 24", "modes = \"auto\""), &["signals.modes", "'auto'", "\"chain\""]);
}

/// The sensor design chosen again at other backgrounds (`[ensemble.placement]
/// design_backgrounds`): refused without a design, without a chain and out of range; at the
/// stated background (× 1) it is the main design number for number, though made by another
/// path (a second instrument, the ensemble run again through the chain); where the background
/// drowns the signals (× 1e4, beyond the ADC's range) the first sensor separates less.
#[test]
fn the_design_is_chosen_again_at_other_backgrounds() {
    let placement = "placement = { x_count = 3, z_count = 2 }";
    let with = |to: &str, chain: &str| format!("{}\n{chain}", edit(&with_chain(""), placement, to));
    let design = "placement = { x_count = 3, z_count = 2, design_sensors = 2, design_backgrounds = [1.0, 1e4] }";
    expect(
        &with("placement = { x_count = 3, z_count = 2, design_backgrounds = [2.0] }", CHAIN),
        &["ensemble.placement.design_backgrounds", "give design_sensors"],
    );
    expect(&with(design, ""), &["ensemble.placement.design_backgrounds", "no [measurement]"]);
    let quiet = "[measurement]\nrate_hz = 10000.0\n[measurement.acceleration]\nadc_range_m_s2 = 100.0\nadc_bits = 16\n";
    expect(&with(design, quiet), &["ensemble.placement.design_backgrounds", "state none (no noise, no tones)"]);
    expect(
        &with(&design.replace("[1.0, 1e4]", "[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]"), CHAIN),
        &["ensemble.placement.design_backgrounds", "9 levels; allowed at most 8"],
    );
    expect(
        &with(&design.replace("[1.0, 1e4]", "[1.0, -1.0]"), CHAIN),
        &["ensemble.placement.design_backgrounds[1] = -1", "[0, 1000000]"],
    );
    let dir = tmp();
    let scene = dir.write("design.toml", with(design, CHAIN));
    let run = impact(["identify", "--scene"]).arg(&scene).arg("--out").arg(dir.join("out")).arg("--json").success();
    let summary: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    for c in summary["conditions"].as_array().unwrap() {
        let at = c["design_backgrounds"].as_array().unwrap();
        assert_eq!((at.len(), at[0]["scale"].as_f64(), at[1]["scale"].as_f64()), (2, Some(1.0), Some(1e4)));
        assert_eq!(at[0]["design"], c["design"], "× 1 is the main design");
        let first = |d: &serde_json::Value| d["steps"][0]["auc"]["auc"].as_f64().unwrap();
        assert!(first(&c["design"]) > 0.6, "the stated background leaves the classes apart: {}", c["design"]);
        assert!(first(&at[1]["design"]) < first(&c["design"]), "{}", at[1]["design"]);
    }
    let page = std::fs::read_to_string(dir.join("out").join("index.md")).unwrap();
    assert!(page.contains("##### The design at other backgrounds"), "the page shows the designs by background");
}
