//! The window detector and the recording reader against hand-computed references.
//!
//! 1. A detector whose model reads only the peak (log-scaled) scores each window of a
//!    signal built so that its peak is known exactly (a quarter-rate tone 0, A, 0, -A, …):
//!    P = σ(b + w(ln A - μ)/s), computed here by hand.
//! 2. The file: a detector written and read back is the same to the bit; a file of another
//!    format, with unknown features or a model of the wrong size is refused.
//! 3. A recording of the wrong rate, channel count or with a non-finite sample is refused,
//!    naming what is wrong.
//! 4. The recording reader: comments skipped, columns picked by key, numbers written in
//!    their shortest form read back to the same bits, every bad line named.

use identify::classify::{Column, Logistic};
use identify::detector::{assess, ChannelSpec, Detector, DetectorError, Provenance, WindowScore, FORMAT};
use identify::features::FEATURES;
use identify::recording::{Sidecar, FORMAT as SIGNAL_FORMAT};

const RATE: f64 = 1000.0;

/// One channel; the model sees only ln(peak), standardised by (μ, s) = (0, 0.5), weight 2,
/// intercept -1.
fn peak_detector() -> Detector {
    let k = FEATURES.len();
    let peak = FEATURES.iter().position(|f| f.key() == "peak").unwrap();
    let mut columns = vec![Column { log: false, mean: 0.0, sd: 0.0 }; k];
    columns[peak] = Column { log: true, mean: 0.0, sd: 0.5 };
    let mut weights = vec![0.0; k];
    weights[peak] = 2.0;
    Detector {
        format: FORMAT.into(),
        window_s: 0.1,
        hop_s: 0.1,
        rate_hz: RATE,
        channels: vec![ChannelSpec { name: "sensor".into(), unit: "m/s²".into() }],
        features: FEATURES.iter().map(|f| f.key().to_string()).collect(),
        alarm_probability: 0.5,
        model: Logistic { intercept: -1.0, weights, columns, iterations: 0 },
        provenance: Provenance::default(),
    }
}

/// Window k (100 samples) a quarter-rate tone of amplitude `amps[k]`: its peak is exactly it.
fn tones(amps: &[f64]) -> Vec<f64> {
    amps.iter().flat_map(|&a| (0..100).map(move |j| [0.0, a, 0.0, -a][j % 4])).collect()
}

#[test]
fn a_peak_detector_scores_each_window_by_its_known_peak() {
    let amps = [0.2, 0.9, 1.0, 1.7, 3.5, 0.05];
    let d = peak_detector();
    let x = tones(&amps);
    let scores = d.score(&[&x], RATE).unwrap();
    // (0.6 s - 0.1 s)/0.1 s + 1 = 6 windows, each on its own tone.
    assert_eq!(scores.len(), amps.len());
    for (k, (s, a)) in scores.iter().zip(amps).enumerate() {
        let t = -1.0 + 2.0 * (a.ln() - 0.0) / 0.5;
        let p = 1.0 / (1.0 + (-t).exp());
        let got = s.probability.unwrap();
        assert!((got - p).abs() <= 1e-14, "window {k}: {got} against {p}");
        assert!((s.start_s - 0.1 * k as f64).abs() < 1e-12 && (s.end_s - s.start_s - 0.1).abs() < 1e-12);
        assert_eq!(s.alarm, p >= 0.5);
    }
}

#[test]
fn a_detector_file_reads_back_to_the_same_bits() {
    let mut d = peak_detector();
    // Numbers with all 53 bits in use.
    d.model.intercept = std::f64::consts::PI / 7.0;
    d.model.weights[0] = -1.0 / 3.0;
    d.model.columns[1] = Column { log: false, mean: 0.1 + 0.2, sd: std::f64::consts::E * 1e-9 };
    let back = Detector::from_json(&d.to_json()).unwrap();
    assert_eq!(back, d);
    assert_eq!(back.model.intercept.to_bits(), d.model.intercept.to_bits());
}

#[test]
fn a_bad_detector_file_is_refused_naming_why() {
    let d = peak_detector();
    let text = d.to_json();
    let refused = |t: &str, words: &[&str]| {
        let e = Detector::from_json(t).unwrap_err().to_string();
        assert!(words.iter().all(|w| e.contains(w)), "{e}");
    };
    refused("[1, 2", &["not JSON"]);
    refused(&text.replace(FORMAT, "impact-detector/9"), &["\"impact-detector/9\"", FORMAT]);
    refused(&text.replace("\"spectral_centroid\"", "\"kurtosis\""), &["kurtosis"]);
    let mut short = d.clone();
    short.model.weights.pop();
    refused(&short.to_json(), &["model columns", "5 weights"]);
    let mut p = d.clone();
    p.alarm_probability = 1.0;
    refused(&p.to_json(), &["alarm_probability = 1"]);
}

#[test]
fn a_recording_that_does_not_match_is_refused() {
    let d = peak_detector();
    let x = tones(&[1.0, 2.0]);
    let e = |r: Result<Vec<WindowScore>, DetectorError>| r.unwrap_err().to_string();
    assert!(e(d.score(&[&x], 2000.0)).contains("rate_hz = 2000"));
    assert!(e(d.score(&[&x, &x], RATE)).contains("2 channels given"));
    let mut bad = x.clone();
    bad[17] = f64::NAN;
    assert!(e(d.score(&[&bad], RATE)).contains("sample 17 is NaN"));
    assert!(e(d.score(&[&x[..99]], RATE)).contains("99 samples, fewer than one window of 100"));
    assert!(e(d.score(&[&[]], RATE)).contains("0 samples"));
    let mut tiny_hop = d.clone();
    tiny_hop.hop_s = 1e-9;
    assert!(Detector::from_json(&tiny_hop.to_json()).unwrap_err().to_string().contains("less than one sample"));
    let mut huge = d.clone();
    huge.window_s = 1e9;
    assert!(Detector::from_json(&huge.to_json()).unwrap_err().to_string().contains("allowed 2 to"));
}

/// A window in which the channel is silent (every sample zero: ln of its peak is -∞) is
/// left unscored, not given a probability, and passed over by the operating answer.
#[test]
fn a_silent_window_is_left_unscored() {
    let d = peak_detector();
    let scores = d.score(&[&tones(&[1.0, 0.0, 2.0])], RATE).unwrap();
    assert!(scores[0].probability.is_some() && scores[2].probability.is_some());
    assert_eq!((scores[1].probability, scores[1].alarm), (None, false));
}

#[test]
fn the_operating_answer_counts_before_and_after_the_onset() {
    // Five windows before the onset at 0.5 s, one alarmed; five after, the second alarmed.
    let amps = [0.5, 0.5, 3.0, 0.5, 0.5, 0.5, 3.0, 3.0, 0.5, 3.0];
    let d = peak_detector();
    let scores = d.score(&[&tones(&amps)], RATE).unwrap();
    let a = assess(&scores, 0.5, 0.5);
    assert_eq!((a.windows_before, a.windows_after, a.false_alarms), (5, 5, 1));
    // The first alarmed window after the onset ends at 0.7 s.
    assert!((a.delay_s.unwrap() - 0.2).abs() < 1e-12);
    // After: three of five high; before: one of five. Mann-Whitney by hand: each high
    // after beats the four low before and ties the one high (3 × (4 + ½)); each low after
    // ties the four low before (2 × 4 × ½) = 13.5 + 4 = 17.5 of 25.
    assert!((a.auc.unwrap() - 17.5 / 25.0).abs() < 1e-12, "{:?}", a.auc);
}

#[test]
fn a_recording_reads_its_columns_to_the_same_bits() {
    let values = [std::f64::consts::PI, -1.0 / 3.0, 6.02214076e23, 1e-300];
    let mut csv = String::from("# written by hand\nt_s,a,b\n");
    for (i, v) in values.iter().enumerate() {
        csv += &format!("{:e},{v:e},{:e}\n", i as f64 * 1e-3, -v);
    }
    let side = format!(
        r#"{{"format": "{SIGNAL_FORMAT}", "data": "x.csv", "rate_hz": 1000.0, "columns": ["b", "a"], "onset_s": 0.002}}"#
    );
    let s = Sidecar::parse(&side, "x.json").unwrap();
    let r = s.read(&csv, "x.csv").unwrap();
    assert_eq!(r.names, ["b", "a"]);
    for (i, v) in values.iter().enumerate() {
        assert_eq!(r.channels[1][i].to_bits(), v.to_bits());
        assert_eq!(r.channels[0][i].to_bits(), (-v).to_bits());
    }
    assert_eq!(r.onset_s, Some(0.002));
}

#[test]
fn a_bad_recording_is_refused_naming_the_key_or_line() {
    let ok = format!(r#"{{"format": "{SIGNAL_FORMAT}", "data": "x.csv", "rate_hz": 1000.0, "columns": ["a"]}}"#);
    let side =
        |from: &str, to: &str| Sidecar::parse(&ok.replace(from, to), "x.json").map(|_| ()).unwrap_err().to_string();
    assert!(side(SIGNAL_FORMAT, "wav").contains("format is \"wav\""));
    assert!(side("1000.0", "-5.0").contains("rate_hz = -5"));
    assert!(side("[\"a\"]", "[]").contains("columns is empty"));
    assert!(side("\"columns\"", "\"onset_s\": -1, \"columns\"").contains("onset_s = -1"));
    let s = Sidecar::parse(&ok, "x.json").unwrap();
    let read = |csv: &str| s.read(csv, "x.csv").unwrap_err().to_string();
    assert!(read("t_s,b\n0,1\n").contains("no column \"a\""));
    let e = read("# c\nt_s,a\n0,1\n1,x\n");
    assert!(e.contains("line 4") && e.contains("\"x\" is not a finite number"), "{e}");
    assert!(read("t_s,a\n0,inf\n").contains("\"inf\" is not a finite number"));
    assert!(read("t_s,a\n").contains("no samples"));
}

/// A detector carried to another condition recovers the known answer. One feature, coal
/// N(0, 1) and gangue N(1.5, 1) on 400 windows, fitted on the first half; the same windows
/// recorded again (fresh draws) under a changed gain and offset (x → 3x + 7: a monotone
/// change) score on the second half exactly the AUC of their raw values (Mann-Whitney,
/// computed here), and under a sign flip exactly its complement; with nothing changed it is
/// the plain out-of-fold answer.
#[test]
fn a_carried_detector_recovers_the_known_answer() {
    use identify::detect::{out_of_fold, out_of_fold_across, Fold};
    let n = 400;
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut normal = || {
        // Box-Muller on a xorshift stream.
        let mut u = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            ((seed >> 11) as f64 + 0.5) / (1u64 << 53) as f64
        };
        let (a, b) = (u(), u());
        (-2.0 * a.ln()).sqrt() * (2.0 * std::f64::consts::PI * b).cos()
    };
    let labels: Vec<bool> = (0..n).map(|i| i % 2 == 1).collect();
    let fitted: Vec<Vec<f64>> = labels.iter().map(|&g| vec![normal() + if g { 1.5 } else { 0.0 }]).collect();
    let folds = vec![Fold { train: (0..n / 2).collect(), test: (n / 2..n).collect() }];
    let raw_auc = |rows: &[Vec<f64>]| {
        let (mut coal, mut gangue) = (Vec::new(), Vec::new());
        for i in n / 2..n {
            if labels[i] {
                gangue.push(rows[i][0])
            } else {
                coal.push(rows[i][0])
            }
        }
        let wins = gangue.iter().map(|g| coal.iter().filter(|c| *c < g).count()).sum::<usize>();
        wins as f64 / (coal.len() * gangue.len()) as f64
    };
    let carried_auc = |scored: &[Vec<f64>]| {
        let p = out_of_fold_across(&fitted, scored, &labels, &[false], &folds).unwrap();
        let as_rows: Vec<Vec<f64>> = p.iter().map(|p| vec![p.unwrap_or(f64::NAN)]).collect();
        raw_auc(&as_rows)
    };
    // The scored condition: fresh draws of the same classes under a gain and offset, so its
    // raw AUC is its own, not the fitted rows'.
    let gained: Vec<Vec<f64>> =
        labels.iter().map(|&g| vec![3.0 * (normal() + if g { 1.5 } else { 0.0 }) + 7.0]).collect();
    let flipped: Vec<Vec<f64>> = gained.iter().map(|r| vec![-r[0]]).collect();
    assert!(raw_auc(&fitted) > 0.8, "the classes separate: {}", raw_auc(&fitted));
    assert_ne!(raw_auc(&gained), raw_auc(&fitted));
    assert_eq!(carried_auc(&gained), raw_auc(&gained));
    assert!((carried_auc(&flipped) - (1.0 - raw_auc(&gained))).abs() < 1e-12);
    assert_eq!(
        out_of_fold_across(&fitted, &fitted, &labels, &[false], &folds),
        out_of_fold(&fitted, &labels, &[false], &folds)
    );
}
