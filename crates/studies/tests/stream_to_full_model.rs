//! The window detector of a caving-stream study, trained on the reduced model's streams, taken
//! to a "measured" stream made by another path: the full Newmark model of the plate (every
//! DOF, the sphere followed through every contact) struck by each lump of the stream from
//! rest, the lumps' accelerations superposed at their arrivals, through the same measurement
//! chain with the same background, written to the recording format (`signal.json` beside a
//! CSV) and read back as `impact detect` reads a user's recording.
//!
//! The plate is damped so that a lump's response has died (to under 1 %) by the end of its
//! 30 ms window, and the lumps arrive at 3 a second: the plate is at rest when the next one
//! strikes, save for the few that arrive within a window of another, so the superposition
//! of single impacts from rest is the stream the reduced model runs, up to the model.
//!
//! The known answer: the detector scores the Newmark-made stream as it scores the reduced
//! model's stream of the same lumps and background. Its AUC of the windows after the change
//! against those before differs between the two by less than the half-width of the study's
//! block-bootstrap interval of its cross-validated AUC (the model moves the answer by less
//! than the study's own sampling uncertainty); no window's probability moves by more than a
//! tenth. Measured: AUC 0.728 on the reduced model's stream and 0.716 on the Newmark-made
//! one (53 lumps), the largest window moving by 0.053, against a study AUC of 0.662
//! (0.526-0.803).

mod full_model;

use coupled::identification::Instrument;
use coupled::reduced::{ChannelKind, ReducedModel};
use full_model::{plate_model, strike};
use identify::detector::assess;
use identify::measurement::Measurand;
use identify::recording::Sidecar;
use identify::stream::{lumps, StreamSpec};
use rayon::prelude::*;
use scene::{Scene, SceneSource};
use studies::identify::sensors::{reduced_settings, spec};
use studies::progress::Silent;
use studies::stream::{one_stream, RECORDING_KEY};

const SCENE: &str = include_str!("transfer_to_full_model.rs");

/// Newmark steps per model sample: 12.5 µs, 18 or more across a contact of the ensemble; the
/// features are read below the anti-aliasing corner of 2 kHz.
const SUBSTEPS: usize = 4;

/// The stream tested: a number past the study's own streams, so an independent stream.
const TESTED: usize = 10;

/// `transfer_to_full_model.rs`'s scene, damped at 5 % (Rayleigh) with a 30 ms window and a
/// background of 5 m/s², and a stream study on it: 4 streams of 20 s at 3 lumps a second,
/// the gangue share rising from 10 % to 80 % at 10 s.
fn scene() -> Scene {
    let start = SCENE.find("name = \"transfer-to-full-model\"").unwrap();
    let text = &SCENE[start..SCENE[start..].find("\"#;").unwrap() + start];
    let text = text
        .replace("ratio = 0.005", "ratio = 0.05")
        .replace("window_ms = 10.0", "window_ms = 30.0")
        .replace("noise_rms_m_s2 = 20.0", "noise_rms_m_s2 = 5.0")
        .replace("name = \"transfer-to-full-model\"", "name = \"stream-to-full-model\"");
    let stream = "\n[stream]\nrate_per_s = 3.0\nduration_s = 20.0\nstreams = 4\nseed = 11\ngangue_before = 0.1\n\
                  gangue_after = 0.8\nonset_s = 10.0\nwindow_s = 2.0\nhop_s = 1.0\nblocks = 4\n";
    Scene::parse(&format!("{text}{stream}"), "stream-to-full-model").unwrap()
}

/// The Newmark-made stream of `lumps`: each lump's accelerations at the sensors on the full
/// model from rest, added in at its arrival sample; `total` samples per sensor.
fn newmark_stream(
    scene: &Scene,
    instrument: &Instrument<'_>,
    lumps: &[identify::stream::Lump],
    total: usize,
) -> Vec<Vec<f64>> {
    let plate = plate_model(scene);
    let e = &scene.ensemble.as_ref().unwrap().ensemble;
    let rate = scene.signals.rate_hz;
    let runs: Vec<(usize, Vec<Vec<f64>>)> = lumps
        .par_iter()
        .map(|l| {
            let (_, striker) = instrument.striker(&l.draw, &e.families[l.draw.family].name).unwrap();
            let run = strike(scene, &plate, scene.conditions[0].supports, &striker, (l.draw.x, l.draw.z), SUBSTEPS);
            ((l.time * rate).round() as usize, run.accelerations)
        })
        .collect();
    let mut out = vec![vec![0.0; total]; scene.signals.sensors.len()];
    for (at, a) in runs {
        for (o, a) in out.iter_mut().zip(&a) {
            for (k, v) in a.iter().enumerate().filter(|(k, _)| at + k < total) {
                o[at + k] += v;
            }
        }
    }
    out
}

/// `columns` written as a recording (a CSV and its sidecar) in `dir` and read back.
fn written_and_read(dir: &std::path::Path, columns: &[Vec<f64>], rate: f64, onset: f64) -> Vec<Vec<f64>> {
    let keys: Vec<String> = (0..columns.len()).map(|c| format!("sensor_{}_acceleration_m_per_s2", c + 1)).collect();
    let mut csv = format!("# made by the full Newmark model\n{}\n", keys.join(","));
    for k in 0..columns[0].len() {
        let row: Vec<String> = columns.iter().map(|c| format!("{}", c[k])).collect();
        csv.push_str(&row.join(","));
        csv.push('\n');
    }
    std::fs::write(dir.join("signal.csv"), csv).unwrap();
    let sidecar = serde_json::json!({
        "format": "impact-signal/1", "data": "signal.csv", "rate_hz": rate, "columns": keys, "onset_s": onset,
    });
    std::fs::write(dir.join("signal.json"), sidecar.to_string()).unwrap();
    let side = Sidecar::parse(&std::fs::read_to_string(dir.join("signal.json")).unwrap(), "signal.json").unwrap();
    let bytes = std::fs::read(side.data_path(&dir.join("signal.json"))).unwrap();
    side.read_data(bytes, "signal.csv").unwrap().channels
}

#[test]
fn a_detector_trained_on_the_reduced_model_scores_a_newmark_made_stream_as_its_own() {
    let scene = scene();
    let data = studies::stream::compute(&scene, &Silent).unwrap();
    let condition = &data.conditions[0];
    let detector = &condition.detector;
    let every = &condition.groups[0];
    let set = &scene.conditions[0];
    let model = ReducedModel::new(&scene.plate, set, reduced_settings(&scene, set).unwrap()).unwrap();
    let instrument =
        Instrument::new(&model, &scene.plate, &spec(&scene, scene.signals.sensors.clone()), &scene).unwrap();
    assert!(instrument.channels().iter().all(|k| matches!(k, ChannelKind::Acceleration { .. })));
    let (study, ensemble) = (scene.stream.as_ref().unwrap(), scene.ensemble.as_ref().unwrap());

    // The reduced model's stream TESTED, recorded as the study records it.
    let (reduced, _) = one_stream(&scene, (study, ensemble), set, (TESTED, None)).unwrap();
    // The same lumps on the full model, through the same chain and background.
    let spec = StreamSpec { seed: study.spec.seed.wrapping_add(TESTED as u64), ..study.spec };
    let drawn = lumps(&ensemble.ensemble, &spec).unwrap();
    let total = (spec.duration * scene.signals.rate_hz - 1e-9).ceil() as usize;
    let full = newmark_stream(&scene, &instrument, &drawn, total);
    let chain = instrument.chain().unwrap();
    let mut rng = chain.stream(RECORDING_KEY + TESTED);
    let measured: Vec<Vec<f64>> =
        full.iter().map(|y| chain.measure(Measurand::Acceleration, y, 1.0, &mut rng).unwrap().samples).collect();
    let dir = std::env::temp_dir().join(format!("impact-stream-to-full-model-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let read = written_and_read(&dir, &measured, reduced.rate_hz, study.spec.profile.onset);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(read, measured, "the recording reads back to the bit");

    let score = |columns: &[Vec<f64>]| {
        let refs: Vec<&[f64]> = columns.iter().map(|c| c.as_slice()).collect();
        detector.score(&refs, reduced.rate_hz).unwrap()
    };
    let (on_reduced, on_full) = (score(&reduced.columns), score(&read));
    let onset = study.spec.profile.onset;
    let (a_reduced, a_full) = (assess(&on_reduced, 0.5, onset).auc.unwrap(), assess(&on_full, 0.5, onset).auc.unwrap());
    let moved = on_reduced
        .iter()
        .zip(&on_full)
        .filter_map(|(a, b)| Some((a.probability? - b.probability?).abs()))
        .fold(0.0, f64::max);
    let report = format!(
        "study AUC {:.3} ({:.3}-{:.3}); stream {TESTED}: AUC {a_reduced:.3} on the reduced model, {a_full:.3} Newmark-made; largest change of a window's probability {moved:.3}; {} lumps",
        every.auc, every.interval.0, every.interval.1, drawn.len()
    );
    eprintln!("{report}");
    assert!(every.interval.1 - every.interval.0 > 0.0 && every.auc < 0.999, "the classes must overlap: {report}");
    assert!((a_full - a_reduced).abs() <= 0.5 * (every.interval.1 - every.interval.0), "{report}");
    assert!(moved < 0.1, "{report}");
}
