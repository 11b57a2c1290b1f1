//! A caving stream cut in segments (`[stream] segment_s`), `scenes/caving-stream-detect.toml`
//! made small (Con 2, 40 modes, one stream of 12 s in segments of 3 s), against two
//! references:
//!
//! 1. The same stream in one piece, through the same chain with its background silenced, a
//!    32-bit ADC that does not clip and a 5 Hz high-pass (so that the plate's modes, not the
//!    filters, set the warm-up): the segments leave out the plate's and the filters' past
//!    before their warm-ups, which the tolerance ε = 1e-3 bounds; the recordings agree within
//!    a few ε of their peak plus an ADC step (the state left out is bounded by the sum of its
//!    modes' amplitudes, which a channel's peak need not reach, and a contact in the warm-up
//!    may pass it on; measured 1-2.7 ε; the quantiser may round a value on a code's edge
//!    either way).
//! 2. Each segment computed alone (`one_stream` with its number, as a Dask task computes it):
//!    the segments put together are the whole stream's recording and lumps, bit for bit.
//! 3. Segments so short that their warm-ups would more than double the samples run are
//!    refused, naming the key, the warm-up and the decay it follows from.

use scene::SceneSource;
use studies::stream::one_stream;
use test_scenes::edits;

const SCENE: &str = include_str!("../../../scenes/caving-stream-detect.toml");

fn small(segments: Option<&str>, noise: bool) -> scene::Scene {
    let mut text = edits(
        SCENE,
        &[
            ("modes = 160", "modes = 40"),
            ("duration_s = 90.0", "duration_s = 12.0"),
            ("streams = 3", "streams = 1"),
            ("onset_s = 45.0", "onset_s = 6.0"),
            ("ramp_s = 5.0", "ramp_s = 0.0"),
            ("window_s = 2.0", "window_s = 1.0"),
            ("blocks = 3", "blocks = 2"),
            ("rate_sweep_per_s = [5.0, 50.0]", "rate_sweep_per_s = []"),
            ("noise_sweep = [0.0, 10.0, 100.0]", "noise_sweep = []"),
            ("size_sweep = [1.5]", "size_sweep = []"),
            ("law_sweep = [\"flores\"]", "law_sweep = []"),
            ("plate_sweep = [{ thickness_mm = 12.0 }, { length_mm = 600.0, width_mm = 450.0 }]", "plate_sweep = []"),
            ("design_sensors = 3", ""),
        ],
    );
    if let Some(cut) = segments {
        text = edits(&text, &[("write_signal = false", &format!("write_signal = false\n{cut}"))]);
    }
    if !noise {
        text = edits(
            &text,
            &[
                ("noise_rms_m_s2 = 2.0", "noise_rms_m_s2 = 0.0"),
                ("tones_m_s2 = [[24.7, 0.5], [49.3, 0.3]]", "tones_m_s2 = []"),
                ("noise_rms_microstrain = 1.0", "noise_rms_microstrain = 0.0"),
                ("noise_rms_kn = 1.0", "noise_rms_kn = 0.0"),
                ("adc_range_m_s2 = 5000.0\nadc_bits = 16", "adc_range_m_s2 = 1e6\nadc_bits = 32"),
                ("adc_range_microstrain = 2000.0\nadc_bits = 16", "adc_range_microstrain = 1e5\nadc_bits = 32"),
                ("adc_range_kn = 2000.0\nadc_bits = 16", "adc_range_kn = 1e5\nadc_bits = 32"),
                ("high_pass_hz = 0.5", "high_pass_hz = 5.0"),
            ],
        );
    }
    scene::Scene::parse(&text, "caving-stream-detect (small)").unwrap()
}

fn run(
    scene: &scene::Scene,
    segment: Option<usize>,
) -> (studies::stream::RecordedSignal, Vec<studies::stream::LumpRow>) {
    let (study, ensemble) = (scene.stream.as_ref().unwrap(), scene.ensemble.as_ref().unwrap());
    let set = scene.conditions.iter().find(|c| c.name == "Con 2").unwrap();
    one_stream(scene, (study, ensemble), set, (0, segment)).unwrap()
}

#[test]
fn a_stream_in_segments_is_the_stream() {
    // 1. Against the stream in one piece, the background silenced.
    const CUT: &str = "segment_s = 3.0\nsegment_tolerance = 1e-3";
    let (whole, whole_lumps) = run(&small(None, false), None);
    let (cut, cut_lumps) = run(&small(Some(CUT), false), None);
    assert_eq!(whole.names, cut.names);
    assert_eq!(whole_lumps.len(), cut_lumps.len());
    for (a, b) in whole_lumps.iter().zip(&cut_lumps) {
        assert_eq!(a.time, b.time);
        assert!((a.force_max / b.force_max - 1.0).abs() < 1e-3, "{a:?} against {b:?}");
    }
    for (name, (a, b)) in whole.names.iter().zip(whole.columns.iter().zip(&cut.columns)) {
        assert_eq!(a.len(), b.len(), "{name}");
        let peak = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        // The ADC's step, as the smallest change between samples.
        let step = a
            .iter()
            .zip(a.iter().skip(1))
            .map(|(x, y)| (x - y).abs())
            .filter(|d| *d > 0.0)
            .fold(f64::INFINITY, f64::min);
        let diff = a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
        eprintln!("{name}: largest difference {diff:e} against a peak of {peak:e} (step {step:e})");
        assert!(diff > 0.0 && diff <= 5e-3 * peak + 1.01 * step, "{name}: {diff:e} against {peak:e}");
    }
    // 2. Each segment alone, with the background: put together, the stream bit for bit.
    let noisy = small(Some(CUT), true);
    let (stream, lumps) = run(&noisy, None);
    let mut columns = vec![Vec::new(); stream.columns.len()];
    let mut rows = Vec::new();
    for b in 0..4 {
        let (seg, seg_lumps) = run(&noisy, Some(b));
        for (all, part) in columns.iter_mut().zip(seg.columns) {
            all.extend(part);
        }
        rows.extend(seg_lumps);
    }
    assert_eq!(columns, stream.columns);
    assert_eq!(rows.len(), lumps.len());
    assert!(rows.iter().zip(&lumps).all(|(a, b)| a.time == b.time && a.force_max == b.force_max));
    let (study, ensemble) = (noisy.stream.as_ref().unwrap(), noisy.ensemble.as_ref().unwrap());
    let set = &noisy.conditions[0];
    let e = one_stream(&noisy, (study, ensemble), set, (0, Some(4))).unwrap_err().to_string();
    assert!(e.contains("segment 4: allowed 0 to 3"), "{e}");
    // 3. Warm-ups that would more than double the work.
    let short = small(Some("segment_s = 1.0\nsegment_tolerance = 1e-15"), true);
    let study = short.stream.as_ref().unwrap();
    let Err(e) = one_stream(&short, (study, ensemble), set, (0, None)) else { panic!("segments of 1 s are refused") };
    let e = e.to_string();
    assert!(
        e.contains("stream.segment_s = 1 s") && e.contains("warms up for") && e.contains("above the allowed 100 %"),
        "{e}"
    );
    // The warm-up quoted is ln(1/ε)/r itself (here longer than the 12 s stream, where the run
    // caps it), and ε reads as written.
    let number_after = |key: &str| -> f64 {
        let rest = &e[e.find(key).unwrap_or_else(|| panic!("{key} in {e}")) + key.len()..];
        rest.split_whitespace().next().unwrap().parse().unwrap()
    };
    let (w, r) = (number_after("ln(1/ε)/r = "), number_after(", r = "));
    assert!(e.contains("ε = segment_tolerance = 1e-15"), "{e}");
    assert!(w > 12.0 && e.contains("too short to cut"), "a warm-up past the stream advises against cutting: {e}");
    assert!((w - 1e15_f64.ln() / r).abs() <= 1e-3 * w + 5e-4 * 1e15_f64.ln() / r, "W = {w} s, r = {r} 1/s: {e}");
}
