//! The caving-stream detection study (`[stream]`, `impact stream`): every bad value is an
//! error naming the key, the value and its range before anything runs; a run writes the
//! windows' and lumps' truth consistently with each other and with the Poisson process they
//! come from, the continuous signal at its rate with its metadata; and it is the same on one
//! and two threads.

mod common;

use common::scenes::{expect_refused as expect, with_stream, STREAM};
use common::{impact, tmp};
use identify::recording::Sidecar;
use impact::scene::{Scene, SceneSource};

#[test]
fn a_stream_is_read_in_si() {
    let s = Scene::parse(&with_stream(STREAM), "stream").unwrap();
    let st = s.stream.unwrap();
    assert_eq!((st.spec.rate_per_s, st.spec.duration, st.streams, st.blocks), (12.0, 6.0, 2, 4));
    assert_eq!((st.spec.profile.onset, st.spec.profile.ramp, st.window, st.hop), (3.0, 0.5, 0.5, 0.25));
    assert!(st.write_signal && st.rate_sweep.is_empty() && st.noise_sweep.is_empty() && st.size_sweep.is_empty());
}

/// `plate_sweep`: each entry is the scene's plate with the keys it gives converted to SI, named
/// by them; its lumps strike its whole face unless the scene gives a region, which they keep.
#[test]
fn a_plate_sweep_is_the_scenes_plate_with_the_keys_it_changes() {
    let sweep = "plate_sweep = [{ length_mm = 600.0, width_mm = 450.0 }, { thickness_mm = 10.0, youngs_modulus_gpa = 70.0, poisson_ratio = 0.33, density_kg_m3 = 2700.0 }]";
    let text = with_stream(&STREAM.replace("write_signal = true", &format!("write_signal = true\n{sweep}")));
    let s = Scene::parse(&text, "stream").unwrap();
    let [larger, aluminium] = &s.stream_plate_sweep[..] else { panic!("two plates: {:?}", s.stream_plate_sweep) };
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-15 * b.abs();
    let facts = |p: &analytic::Plate| {
        let m = p.material();
        [p.length(), p.width(), p.thickness(), m.youngs_modulus(), m.poisson_ratio(), p.density()]
    };
    let expected = [[0.6, 0.45, 0.008, 210e9, 0.3, 7850.0], [0.4584, 0.36, 0.010, 70e9, 0.33, 2700.0]];
    for (other, want) in [larger, aluminium].iter().zip(expected) {
        assert!(facts(&other.plate).iter().zip(want).all(|(&a, b)| close(a, b)), "{:?} against {want:?}", other.plate);
    }
    assert_eq!(larger.shift, "plate 600 mm long, 450 mm wide");
    assert_eq!(aluminium.shift, "plate 10 mm thick, E = 70 GPa, ν = 0.33, ρ = 2700 kg/m³");
    assert_eq!(larger.region.x, (0.0, larger.plate.length()));
    assert_eq!(larger.region.z, (0.0, larger.plate.width()));
    // A region the scene gives is where the lumps strike on every plate.
    let given =
        text.replace("placement = {", "region = { x_mm = [100.0, 300.0], z_mm = [50.0, 200.0] }\nplacement = {");
    let s = Scene::parse(&given, "stream").unwrap();
    let region = s.ensemble.as_ref().unwrap().ensemble.region;
    assert!(close(region.x.1, 0.3) && close(region.z.0, 0.05));
    assert!(s.stream_plate_sweep.iter().all(|o| o.region == region));
}

/// Every entry of `plate_sweep` is checked as `[plate]` is, under its own name, and must carry
/// the scene's sensors and region.
#[test]
fn bad_plate_sweeps_name_the_entry_the_key_and_the_value() {
    let bad = |from: &str, to: &str, needles: &[&str]| expect(&with_stream(&STREAM.replace(from, to)), needles);
    let sweep = |entries: &str| format!("write_signal = true\nplate_sweep = [{entries}]");
    bad(
        "write_signal = true",
        &sweep("{ thickness_mm = 8.0 }, { thickness_mm = 400.0 }"),
        &[
            "stream.plate_sweep[1].thickness_mm",
            "400 mm is more than the plate's smaller side 360 mm",
            "[0.001, 360] mm",
        ],
    );
    bad(
        "write_signal = true",
        &sweep("{ thickness_mm = 0.0 }"),
        &["stream.plate_sweep[0].thickness_mm = 0", "[0.001,"],
    );
    bad(
        "write_signal = true",
        &sweep("{ youngs_modulus_gpa = -1.0 }"),
        &["stream.plate_sweep[0].youngs_modulus_gpa = -1"],
    );
    bad("write_signal = true", &sweep("{ poisson_ratio = 0.5 }"), &["stream.plate_sweep[0].poisson_ratio = 0.5"]);
    bad("write_signal = true", &sweep("{ density_kg_m3 = nan }"), &["stream.plate_sweep[0].density_kg_m3 = NaN"]);
    bad(
        "write_signal = true",
        &sweep("{ length_mm = 40000.0 }"),
        &["stream.plate_sweep[0].length_mm and stream.plate_sweep[0].width_mm", "aspect ratio"],
    );
    bad("write_signal = true", &sweep("{}"), &["stream.plate_sweep[0]", "changes nothing", "length_mm, width_mm"]);
    bad("write_signal = true", &sweep("{ thickness = 9.0 }"), &["unknown field", "thickness"]);
    bad(
        "write_signal = true",
        "thickness_sweep_mm = [12.0]",
        &["stream.thickness_sweep_mm", "replaced by plate_sweep", "plate_sweep = [{ thickness_mm = 12.0 }]"],
    );
    // The sensors stay at their points in mm: one at x = 400 mm is off a 300 mm plate.
    bad(
        "write_signal = true",
        &sweep("{ length_mm = 300.0 }"),
        &["stream.plate_sweep[0]", "signals.sensors_mm[1] = (400, 90) mm is off the 300 x 360 mm plate"],
    );
    expect(
        &with_stream(&STREAM.replace("write_signal = true", &sweep("{ width_mm = 200.0 }")))
            .replace("placement = {", "region = { x_mm = [0.0, 300.0], z_mm = [0.0, 300.0] }\nplacement = {")
            .replace("[400.0, 90.0]", "[400.0, 50.0]")
            .replace("[229.2, 180.0]", "[229.2, 100.0]"),
        &["stream.plate_sweep[0]", "ensemble.region reaches (300, 300) mm, off the 458.4 x 200 mm plate"],
    );
}

#[test]
fn bad_streams_name_the_key_the_value_and_the_range() {
    let bad = |from: &str, to: &str, needles: &[&str]| expect(&with_stream(&STREAM.replace(from, to)), needles);
    bad("rate_per_s = 12.0", "rate_per_s = 0.0", &["stream.rate_per_s = 0", "(0, 10000]"]);
    bad("rate_per_s = 12.0", "rate_per_s = nan", &["stream.rate_per_s = NaN"]);
    bad("duration_s = 6.0", "duration_s = 1e6", &["stream.duration_s = 1000000", "(0, 86400]"]);
    bad("gangue_after = 1.0", "gangue_after = 1.5", &["stream.gangue_after = 1.5", "[0, 1]"]);
    bad("gangue_after = 1.0", "gangue_after = 0.0", &["stream.gangue_after", "no change to detect"]);
    let falling = ("gangue_before = 0.0\ngangue_after = 1.0", "gangue_before = 0.8\ngangue_after = 0.3");
    bad(
        falling.0,
        falling.1,
        &["stream.gangue_after", "0.3 is below gangue_before = 0.8", "turn to gangue-rich", "(0.8, 1]"],
    );
    bad("onset_s = 3.0", "onset_s = 7.0", &["stream.onset_s = 7", "(0, 6)"]);
    bad("ramp_s = 0.5", "ramp_s = 4.0", &["stream.ramp_s = 4", "[0, 3]"]);
    bad("window_s = 0.5", "window_s = 4.0", &["stream.window_s = 4", "0.0008", "3]"]);
    bad("hop_s = 0.25", "hop_s = 0.75", &["stream.hop_s = 0.75", "0.5]"]);
    bad("streams = 2", "streams = 2.5", &["stream.streams", "not a whole number"]);
    bad("streams = 2", "streams = 100", &["stream.streams = 100", "[1, 64]"]);
    bad("blocks = 4", "blocks = 1", &["stream.blocks = 1", "[2, 1000]"]);
    bad("blocks = 4", "blocks = 900", &["stream.blocks", "900 blocks for 46 windows"]);
    bad("alarm_probability = 0.5", "alarm_probability = 1.0", &["stream.alarm_probability = 1", "(0, 1)"]);
    bad("write_signal = true", "noise_sweep = [1.0]", &["stream.noise_sweep", "no [measurement]"]);
    bad("write_signal = true", "rate_sweep_per_s = [5.0, -1.0]", &["stream.rate_sweep_per_s[1] = -1"]);
    bad("write_signal = true", "size_sweep = [1.5, 0.0]", &["stream.size_sweep[1] = 0", "[0.1, 10]"]);
    bad(
        "write_signal = true",
        "law_sweep = [\"flores\", \"elastic\"]",
        &["stream.law_sweep[1]", "'elastic' is not a contact law", "\"thornton\""],
    );
    bad(
        "write_signal = true",
        "law_sweep = [\"hertz\", \"hertz\"]",
        &["stream.law_sweep[1]", "'hertz' is named twice"],
    );
    let huge = with_stream(&STREAM.replace("write_signal = true", "size_sweep = [10.0]"))
        .replace("max = 40.0 }", "max = 2000.0 }");
    expect(&huge, &["stream.size_sweep[0]", "10 scales family", "20000 mm", "outside the allowed"]);
    bad("write_signal = true", "wrte_signal = true", &["unknown field", "wrte_signal"]);
    bad("write_signal = true", "signal_format = \"parquet\"", &["stream.signal_format", "write_signal is not true"]);
    bad(
        "write_signal = true",
        "write_signal = true\nsignal_format = \"hdf5\"",
        &["stream.signal_format", "\"hdf5\" is not a format", "\"csv\", \"parquet\""],
    );
    bad("write_signal = true", "segment_s = 0.5", &["stream.segment_s = 0.5", "[1, 6] s"]);
    bad("write_signal = true", "segment_s = 7.0", &["stream.segment_s = 7", "[1, 6] s"]);
    bad(
        "write_signal = true",
        "segment_s = 2.0\nsegment_tolerance = 0.5",
        &["stream.segment_tolerance = 0.5", "[1e-15, 0.01]"],
    );
    bad("write_signal = true", "segment_tolerance = 1e-6", &["stream.segment_tolerance", "segment_s is not"]);
    bad("duration_s = 6.0", "duration_s = 80000.0", &["stream.duration_s", "MB of signal", "budget"]);
    let crowded =
        STREAM.replace("rate_per_s = 12.0", "rate_per_s = 9000.0").replace("duration_s = 6.0", "duration_s = 10.0");
    expect(
        &with_stream(&crowded.replace("streams = 2", "streams = 64")),
        &[
            "expect 11520000 lumps",
            "every stream, rate, size law, plate, contact law and support set",
            "budget of 10000000",
        ],
    );
    let fine = STREAM.replace("duration_s = 6.0", "duration_s = 60.0").replace("hop_s = 0.25", "hop_s = 0.00005");
    expect(&with_stream(&fine), &["stream.hop_s", "windows, above the budget of 1000000"]);
    let text = format!("{}\n{STREAM}", impact::scene::DEFAULT_SCENE);
    expect(&text, &["stream", "read only by the \"identify\" analysis"]);
}

/// The rows of a CSV file written by impact (its provenance line first), split at commas.
fn rows(path: &std::path::Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().skip(1);
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    (header, lines.map(|l| l.split(',').map(String::from).collect()).collect())
}

#[test]
fn a_stream_run_writes_consistent_truth_and_the_signal() {
    let dir = tmp();
    let scene = dir.write(
        "stream.toml",
        with_stream(&format!(
            "{STREAM}size_sweep = [1.0]\nlaw_sweep = [\"flores\"]\nplate_sweep = [{{ thickness_mm = 8.0 }}, {{ thickness_mm = 16.0 }}]\n"
        )),
    );
    for (out, threads) in [("one", "1"), ("two", "2")] {
        impact(["stream", "--scene"])
            .arg(&scene)
            .arg("--out")
            .arg(dir.join(out))
            .arg("--json")
            .env("RAYON_NUM_THREADS", threads)
            .success();
    }
    for f in ["con-1/windows.csv", "con-1/lumps.csv", "con-2/signal.csv"] {
        let (a, b) = (std::fs::read(dir.join("one").join(f)).unwrap(), std::fs::read(dir.join("two").join(f)).unwrap());
        assert!(a == b, "{f} differs between one and two threads");
    }
    let run = dir.join("one").join("con-1");
    let (_, lumps) = rows(&run.join("lumps.csv"));
    // Two streams of 6 s at 12 a second: 144 lumps expected, Poisson, within 4 σ = 48.
    assert!((lumps.len() as f64 - 144.0).abs() < 48.0, "{} lumps", lumps.len());
    // The profile is all coal before the onset and all gangue after its ramp.
    for l in &lumps {
        let t: f64 = l[1].parse().unwrap();
        if t < 3.0 {
            assert_eq!(l[3], "0", "{l:?}");
        } else if t >= 3.5 {
            assert_eq!(l[3], "1", "{l:?}");
        }
    }
    // Every window's lump and gangue counts are those of lumps.csv in its span.
    let (_, windows) = rows(&run.join("windows.csv"));
    assert_eq!(windows.len(), 2 * 23);
    for w in &windows {
        let (s, a, b): (&str, f64, f64) = (&w[0], w[1].parse().unwrap(), w[2].parse().unwrap());
        let inside: Vec<_> =
            lumps.iter().filter(|l| l[0] == s && (a..b).contains(&l[1].parse::<f64>().unwrap())).collect();
        assert_eq!(w[3].parse::<usize>().unwrap(), inside.len(), "{w:?}");
        assert_eq!(w[4].parse::<usize>().unwrap(), inside.iter().filter(|l| l[3] == "1").count(), "{w:?}");
    }
    the_signal_has_its_sidecar(&dir.join("one").join("con-2"));
    detect_reads_the_run(&dir.join("one").join("con-2"), &dir);
    let data: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("one").join("stream.json")).unwrap()).unwrap();
    let every = &data["conditions"][0]["groups"][0];
    assert_eq!(every["group"], "every channel");
    let auc = every["auc"].as_f64().unwrap();
    assert!((0.0..=1.0).contains(&auc));
    // Radii scaled by one, the scene's own contact law (Flores) and its own plate thickness
    // (8 mm, the plate rebuilt through the sweep's path) are the same lumps and the same
    // signals: the detector carried to them is fitted on the same training blocks as the
    // matched one and scores the same held-out windows, so the two agree exactly; a
    // misaligned carry (rows, labels or blocks of another condition) would not.
    let same: Vec<&serde_json::Value> = data["transfer"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| ["radii x 1", "flores contact law", "plate 8 mm thick"].contains(&p["shift"].as_str().unwrap()))
        .collect();
    assert_eq!(same.len(), 6, "three shifts per support set");
    // A plate twice as thick is another plate: its detector carried there scores other
    // windows than the matched one (a sweep that ignored the thickness would score the same).
    let thick: Vec<&serde_json::Value> =
        data["transfer"].as_array().unwrap().iter().filter(|p| p["shift"] == "plate 16 mm thick").collect();
    assert_eq!(thick.len(), 2);
    assert!(thick.iter().all(|p| p["transferred"] != p["matched"]), "{thick:?}");
    for p in same {
        assert_eq!(p["transferred"], p["matched"], "{p}");
    }
    the_bands_scale_as_a_kirchhoff_plate(&data);
}

/// The band table of the run above (no chain): every plate on every support set, its 24
/// modes' highest frequency. The 8 mm swept plate is the scene's plate, to the bit; a
/// Kirchhoff plate's frequencies are ω = (λ²/L²)√(D/ρh) with D ∝ h³ on the same mesh and
/// held edges, so on Con 1 (both ends fixed) the 16 mm plate's are twice the 8 mm plate's (to
/// the eigensolver's tolerance, 1e-8 relative); Con 2's springs keep their stiffness, so
/// there they are not.
fn the_bands_scale_as_a_kirchhoff_plate(data: &serde_json::Value) {
    let bands = data["bands"].as_array().expect("a plate stream has its bands");
    assert_eq!(bands.len(), 2 * 3, "two support sets, three plates each");
    for set in ["Con 1", "Con 2"] {
        let of = |plate: &str| {
            let b = bands.iter().find(|b| b["support_set"] == set && b["plate"] == plate).expect(plate);
            assert_eq!(b["modes"], 24);
            assert!(b["gain_above_highest"].is_null() && b["resolved"].is_null(), "no chain: {b}");
            b["highest_mode_hz"].as_f64().unwrap()
        };
        let (scene, same, thick) = (of("the scene's plate"), of("plate 8 mm thick"), of("plate 16 mm thick"));
        assert_eq!(scene, same, "{set}");
        if set == "Con 1" {
            assert!((thick / (2.0 * same) - 1.0).abs() < 1e-8, "{set}: {thick} Hz against 2 x {same} Hz");
        }
    }
}

/// The signal of `run`: 6 s at the model's 20 kHz, its metadata beside it naming its columns.
fn the_signal_has_its_sidecar(run: &std::path::Path) {
    let (header, signal) = rows(&run.join("signal.csv"));
    assert_eq!(signal.len(), 120_000);
    assert_eq!(header[0], "t_s");
    let meta: serde_json::Value = serde_json::from_slice(&std::fs::read(run.join("signal.json")).unwrap()).unwrap();
    assert_eq!(meta["rate_hz"], 20_000.0);
    assert_eq!(meta["channels"].as_array().unwrap().len(), header.len() - 1);
    assert_eq!(meta["time_column"], header[0]);
    let columns: Vec<&str> = meta["columns"].as_array().unwrap().iter().map(|c| c.as_str().unwrap()).collect();
    assert_eq!(columns, header[1..]);
    assert_eq!(
        (meta["format"].as_str(), meta["data"].as_str(), meta["onset_s"].as_f64()),
        (Some("impact-signal/1"), Some("signal.csv"), Some(3.0))
    );
}

/// `impact detect` reads the run's own detector and signal: the stream's 23 windows, each
/// alarm at the detector's probability, the onset from the sidecar; a sidecar of another
/// rate, a missing column or a detector of another format is refused before anything is
/// written, naming it.
fn detect_reads_the_run(run: &std::path::Path, dir: &common::tmp::Tmp) {
    let out = dir.join("detected");
    let args = |signal: &std::path::Path, out: &std::path::Path| {
        impact(["detect", "--detector"])
            .arg(run.join("detector.json"))
            .arg("--signal")
            .arg(signal)
            .arg("--out")
            .arg(out)
    };
    let ok = args(&run.join("signal.json"), &out).arg("--json").within(60).success();
    let answer = ok.json();
    assert_eq!(answer["windows"], 23);
    assert_eq!(answer["assessment"]["onset_s"], 3.0);
    // Windows ending by 3 s: starts 0 to 2.5 s; starting from 3 s: 3 to 5.5 s.
    assert_eq!(
        (answer["assessment"]["windows_before"].as_u64(), answer["assessment"]["windows_after"].as_u64()),
        (Some(11), Some(11))
    );
    let (header, scores) = rows(&out.join("scores.csv"));
    assert_eq!(header, ["start_s", "end_s", "probability_gangue_rich", "alarm"]);
    assert_eq!(scores.len(), 23);
    for s in &scores {
        let p: f64 = s[2].parse().unwrap();
        assert!((0.0..=1.0).contains(&p));
        assert_eq!(s[3], if p >= 0.5 { "1" } else { "0" }, "{s:?}");
    }
    let sidecar = std::fs::read_to_string(run.join("signal.json")).unwrap();
    let meta: serde_json::Value = serde_json::from_str(&sidecar).unwrap();
    let first_column = format!("\"{}\"", meta["columns"][0].as_str().unwrap());
    for (name, from, to, words) in [
        ("rate.json", "\"rate_hz\": 20000.0".to_string(), "\"rate_hz\": 10000.0", &["rate_hz = 10000", "20000 Hz"][..]),
        ("column.json", first_column, "\"no_such_column\"", &["no column \"no_such_column\""][..]),
    ] {
        assert!(sidecar.contains(&from), "{from}");
        let bad = run.join(name);
        std::fs::write(&bad, sidecar.replacen(&from, to, 1)).unwrap();
        let refused = args(&bad, &dir.join(name)).within(60).fails();
        assert!(words.iter().all(|w| refused.stderr.contains(w)), "{}", refused.stderr);
        assert!(!dir.join(name).exists());
    }
    let other = run.join("other-detector.json");
    let text = std::fs::read_to_string(run.join("detector.json")).unwrap();
    std::fs::write(&other, text.replace("impact-detector/1", "impact-detector/0")).unwrap();
    let refused = impact(["detect", "--detector"])
        .arg(&other)
        .arg("--signal")
        .arg(run.join("signal.json"))
        .arg("--out")
        .arg(dir.join("other"))
        .within(60)
        .fails();
    assert!(refused.stderr.contains("\"impact-detector/0\""), "{}", refused.stderr);
    assert!(!dir.join("other").exists());
}

/// The signal written as Parquet is the CSV's signal to the bit: the same columns under the
/// same keys, the sidecar's JSON inside the file, and `impact detect` scores both alike.
#[test]
fn a_parquet_signal_is_the_csv_signal_to_the_bit() {
    let dir = tmp();
    let one = STREAM.replace("streams = 2", "streams = 1").replace("blocks = 4", "blocks = 3");
    let csv = dir.write("csv.toml", with_stream(&one));
    let parquet = dir.write("parquet.toml", with_stream(&format!("{one}signal_format = \"parquet\"\n")));
    for (scene, out) in [(&csv, "csv"), (&parquet, "parquet")] {
        impact(["stream", "--scene"]).arg(scene).arg("--out").arg(dir.join(out)).within(120).success();
    }
    let read = |out: &str| {
        let path = dir.join(out).join("con-1").join("signal.json");
        let text = std::fs::read_to_string(&path).unwrap();
        let sidecar = Sidecar::parse(&text, "signal.json").unwrap();
        let bytes = std::fs::read(sidecar.data_path(&path)).unwrap();
        // Every column, the time's first.
        let all = Sidecar {
            columns: [vec!["t_s".to_string()], sidecar.columns.clone()].concat(),
            channels: vec![],
            ..sidecar.clone()
        };
        (sidecar, text, bytes.clone(), all.read_data(bytes, out).unwrap())
    };
    let (c, _, _, from_csv) = read("csv");
    let (p, p_text, p_bytes, from_parquet) = read("parquet");
    assert_eq!((c.data.as_str(), p.data.as_str()), ("signal.csv", "signal.parquet"));
    assert_eq!(c.columns, p.columns);
    assert_eq!(from_csv.channels.len(), 1 + c.columns.len());
    assert_eq!(from_csv.channels[0].len(), 120_000);
    for (k, (a, b)) in from_csv.channels.iter().zip(&from_parquet.channels).enumerate() {
        assert_eq!(a.len(), b.len(), "column {k}");
        assert!(a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits()), "column {k} differs");
    }
    let (_, inside) = identify::recording::parquet::read(p_bytes, &p.columns, "signal.parquet").unwrap();
    assert_eq!(inside.as_deref(), Some(p_text.as_str()));
    let scores = |out: &str| {
        let run = dir.join(out).join("con-1");
        let to = dir.join(format!("{out}-detect"));
        impact(["detect", "--detector"])
            .arg(run.join("detector.json"))
            .arg("--signal")
            .arg(run.join("signal.json"))
            .arg("--out")
            .arg(&to)
            .within(60)
            .success();
        rows(&to.join("scores.csv")).1
    };
    assert_eq!(scores("csv"), scores("parquet"));
}

/// A cross-validation that cannot score (one stream cut into two blocks at its change: each
/// block's training windows are of the other class only) is refused before any stream runs,
/// naming the key; the output folder is not created.
#[test]
fn a_cross_validation_that_cannot_score_is_refused() {
    let dir = tmp();
    let scene = dir.write(
        "one.toml",
        with_stream(&STREAM.replace("streams = 2", "streams = 1").replace("blocks = 4", "blocks = 2")),
    );
    let run = impact(["stream", "--scene"]).arg(&scene).arg("--out").arg(dir.join("out")).within(30).fails();
    assert!(run.stderr.contains("stream.blocks") && run.stderr.contains("one class only"), "{}", run.stderr);
    assert!(!dir.join("out").exists());
}

/// A swept plate whose modes decay too slowly for the scene's segments (a plate four times as
/// long and wide: its fundamental, and with it the slowest decay ζω₁, a sixteenth of the
/// scene's plate's, so its warm-up reaches back to every segment's stream start) is refused
/// once its model is built, naming the plate and the warm-up, before any stream of any
/// support set runs. The scene's own plate, checked first, passes (a 12 s stream in segments
/// of 2 s at ε = 1e-2: W = ln 100/2.52 s = 1.83 s adds 76 %, the larger plate's 250 %), or
/// the refusal would not name the swept one.
#[test]
fn a_swept_plate_too_slow_for_the_segments_is_refused_before_any_stream() {
    let dir = tmp();
    let extra =
        "segment_s = 2.0\nsegment_tolerance = 1e-2\nplate_sweep = [{ length_mm = 1833.6, width_mm = 1440.0 }]\n";
    let scene = dir.write(
        "slow.toml",
        with_stream(&format!("{}{extra}", STREAM.replace("duration_s = 6.0", "duration_s = 12.0"))),
    );
    let run = impact(["stream", "--scene"]).arg(&scene).arg("--out").arg(dir.join("out")).within(120).fails();
    for needle in ["stream.plate_sweep, the plate 1833.6 mm long, 1440 mm wide", "warm-up"] {
        assert!(run.stderr.contains(needle), "no '{needle}' in: {}", run.stderr);
    }
    assert!(!run.stderr.contains("streams:"), "a stream ran before the refusal: {}", run.stderr);
    assert!(!dir.join("out").exists());
}
