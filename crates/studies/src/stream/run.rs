//! One support set's stream study: simulate, record, window, score.

use super::plates::Plates;
use super::recorder::Recorder;
use super::score::Windows;
use super::segments::{self, Pieces};
use super::transfer::Shifted;
use super::{
    channel_name, Baseline, ConditionStream, LumpRow, NoisePoint, RatePoint, RecordedSignal, Simulation, WindowRow,
};
use crate::channel::ChannelInfo;
use crate::identify::sensors::{channel_infos, spec};
use crate::progress::Progress;
use crate::Failure;
use analytic::params::compact;
use coupled::identification::{measurand, Instrument};
use coupled::reduced::stream::StreamResponse;
use coupled::reduced::{ChannelKind, ReducedModel};
use identify::detect::{time_block_folds, windows, Window};
use identify::detector::{scale_flags, window_features, ChannelSpec, Detector, Provenance};
use identify::features::FEATURES;
use identify::stream::{lumps, Lump, StreamSpec, StreamStudy};
use rayon::prelude::*;
use scene::{Scene, SupportSet};
use std::time::Instant;

/// The background streams of the stream study's recordings start here, apart from every
/// single impact's (which are numbered by impact): stream r's is the chain's stream
/// `RECORDING_KEY + r`.
pub const RECORDING_KEY: usize = 1 << 48;

/// One simulated stream: its lumps, the model's response and the seconds it took; where
/// the study cuts it, how, and its segments' warm-up samples.
pub(super) struct Simulated {
    pub lumps: Vec<Lump>,
    pub response: StreamResponse,
    pub seconds: f64,
    pub pieces: Option<Pieces>,
}

/// The stream study on `set`, the `index`-th support set of `scene`, on its plates' models
/// `plates` ([`super::plates`]).
pub(super) fn condition(
    scene: &Scene,
    (study, ensemble): (&StreamStudy, &identify::Study),
    (set, index, plates): (&SupportSet, usize, &Plates),
    progress: &dyn Progress,
) -> Result<(ConditionStream, Shifted), Failure> {
    let plate = &scene.plate;
    let model = &plates.main;
    let sensors = scene.signals.sensors.clone();
    let instrument = Instrument::new(model, plate, &spec(scene, sensors.clone()), scene)?;
    let target = Target {
        name: &set.name,
        index,
        recorder: &instrument,
        infos: channel_infos(&instrument, &sensors, plate),
        sensors: sensors.len(),
        extra_runs: 0,
    };
    let sweeps = |w: &Windows| -> Result<Vec<Condition>, Failure> {
        let mut out = other_lumps((ensemble, study), (&instrument, w), progress)?;
        out.extend(other_laws(scene, (ensemble, study), (model, w), progress)?);
        out.extend(other_plates(scene, (ensemble, study), (&plates.swept, w), progress)?);
        Ok(out)
    };
    let (mut data, shifted) = scored(scene, (study, ensemble), &target, &sweeps, progress)?;
    if study.design.is_some() {
        progress.start(study.streams, &format!("{}: design streams", set.name));
        data.design = super::design::window_design(scene, (ensemble, study), (model, &shifted.windows), progress)?;
        progress.finish();
    }
    Ok((data, shifted))
}

/// A struck model as the study scores it: its name and number among the study's, what
/// records it, its channels' names and its sensors.
pub(super) struct Target<'a> {
    pub name: &'a str,
    pub index: usize,
    pub recorder: &'a dyn Recorder,
    pub infos: Vec<ChannelInfo>,
    pub sensors: usize,
    /// Runs of the study's streams its own `sweeps` add beyond the scene's sweeps.
    pub extra_runs: usize,
}

/// The study on `target`: the main run and its scores by channel group, the baselines, the
/// noise and rate sweeps, then the target's own `sweeps` (for the transfer), the detector to
/// take away.
pub(super) fn scored(
    scene: &Scene,
    (study, ensemble): (&StreamStudy, &identify::Study),
    target: &Target<'_>,
    sweeps: &dyn Fn(&Windows) -> Result<Vec<Condition>, Failure>,
    progress: &dyn Progress,
) -> Result<(ConditionStream, Shifted), Failure> {
    let recorder = target.recorder;
    let seed = study.spec.seed ^ (target.index as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    let runs = 1
        + study.rate_sweep.len()
        + study.size_sweep.len()
        + scene.stream_plate_sweep.len()
        + scene.stream_law_sweep.len()
        + target.extra_runs;
    progress.start(study.streams * runs, &format!("{}: streams", target.name));
    let w = window_set(study, seed);
    let main = simulate(recorder, ensemble, study, study.spec.rate_per_s, progress)?;
    let simulation = simulation(recorder, ensemble, study, &main)?;
    let (recorded, rate) = record(recorder, &main, 1.0);
    let rows = features(&recorded, rate, &w.windows, study);
    let kinds = recorder.channels();
    let mut groups = Vec::new();
    let (every, scores) = w.score("every channel", &rows, &scale_flags(kinds.len()))?;
    groups.push(every.clone());
    let mut on_sensors = Vec::new();
    for (name, members) in channel_groups(&kinds, target.sensors) {
        let sub = select(&rows, &members);
        groups.push(w.score(&name, &sub, &scale_flags(members.len()))?.0);
        if name != SUPPORTS {
            on_sensors.extend(members);
        }
    }
    let detector = detector(scene, study, target.name, (&w, &rows, rate), &target.infos)?;
    let baselines = baselines(&w, &main);
    let (noise_sweep, mut others) = noise_sweep(recorder, study, &main, &w, (&recorded, &every))?;
    let mut rate_sweep = Vec::new();
    for &rate_per_s in &study.rate_sweep {
        let (sims, rows) = windowed(recorder, (ensemble, study, rate_per_s), &w, progress)?;
        let score = w.score("every channel", &rows, &scale_flags(kinds.len()))?.0;
        rate_sweep.push(RatePoint { rate_per_s, overlapped_share: overlapped_share(&sims), score });
        others.push((format!("{} lumps/s", compact(rate_per_s)), rows));
    }
    others.extend(sweeps(&w)?);
    progress.finish();
    let names: Vec<String> = target.infos.iter().map(channel_name).collect();
    let signal = study.write_signal.then(|| RecordedSignal {
        rate_hz: rate,
        names: names.clone(),
        columns: recorded.first().cloned().unwrap_or_default(),
    });
    let data = ConditionStream {
        name: target.name.to_string(),
        channels: names,
        simulation,
        groups,
        baselines,
        noise_sweep,
        rate_sweep,
        windows: window_rows(&w, &main, &scores, &study.spec.profile),
        lumps: lump_rows(ensemble, &main),
        signal,
        detector,
        design: None,
    };
    let shifted = Shifted {
        name: target.name.to_string(),
        channels: on_sensors.len(),
        main: select(&rows, &on_sensors),
        others: others.into_iter().map(|(shift, rows)| (shift, select(&rows, &on_sensors))).collect(),
        windows: w,
    };
    Ok((data, shifted))
}

/// The every-channel detector fitted on all the main run's windows, to be taken away: what
/// the cross-validation scores, fitted once more on everything.
fn detector(
    scene: &Scene,
    study: &StreamStudy,
    name: &str,
    (w, rows, rate): (&Windows, &[Vec<f64>], f64),
    infos: &[ChannelInfo],
) -> Result<Detector, Failure> {
    let channels = infos.iter().map(|i| ChannelSpec { name: i.label(), unit: i.unit.to_string() }).collect();
    let provenance = Provenance {
        scene: scene.name.clone(),
        support_set: name.to_string(),
        chain: scene.measurement.as_ref().and_then(|c| serde_json::to_value(c).ok()),
        program: "impact".into(),
        version: env!("CARGO_PKG_VERSION").into(),
        units: "SI".into(),
        ..Provenance::default()
    };
    let timing = (study.window, study.hop, rate);
    Detector::fit(rows, &w.labels, timing, channels, study.alarm_probability, provenance)
        .map_err(|e| Failure::from(e.to_string()))
}

/// The size sweep: the main run's streams with every lump's radius scaled (the same
/// target, chain and lumps, each that many times as large), each with its window features,
/// for the transfer.
pub(super) fn other_lumps(
    (ensemble, study): (&identify::Study, &StreamStudy),
    (recorder, w): (&dyn Recorder, &Windows),
    progress: &dyn Progress,
) -> Result<Vec<Condition>, Failure> {
    let mut out = Vec::new();
    for &scale in &study.size_sweep {
        let rows = windowed(recorder, (&sized(ensemble, scale), study, study.spec.rate_per_s), w, progress)?.1;
        out.push((format!("radii x {}", compact(scale)), rows));
    }
    Ok(out)
}

/// The law sweep: the main run's streams struck under each other contact law (the same
/// plate, chain and lumps; only the contact's force law differs), for the transfer.
fn other_laws(
    scene: &Scene,
    (ensemble, study): (&identify::Study, &StreamStudy),
    (model, w): (&ReducedModel, &Windows),
    progress: &dyn Progress,
) -> Result<Vec<Condition>, Failure> {
    let mut out = Vec::new();
    for &law in &scene.stream_law_sweep {
        let with_law = Scene { contact_law: law, ..scene.clone() };
        let striking = Instrument::new(model, &scene.plate, &spec(scene, scene.signals.sensors.clone()), &with_law)?;
        let rows = windowed(&striking, (ensemble, study, study.spec.rate_per_s), w, progress)?.1;
        out.push((law_shift(law), rows));
    }
    Ok(out)
}

/// The name of the shift to contact law `law`.
pub(super) fn law_shift(law: coupled::transient::LawKind) -> String {
    format!("{} contact law", law.key())
}

/// The plate sweep: the main run's streams on each of the scene's other plates, on their
/// models `swept` ([`super::plates`]: the same supports, sensor points, quantities and chain,
/// so the channels are the detector's), the lumps' uniforms mapped onto the plate's region,
/// each with its window features, for the transfer.
fn other_plates(
    scene: &Scene,
    (ensemble, study): (&identify::Study, &StreamStudy),
    (swept, w): (&[(Scene, ReducedModel)], &Windows),
    progress: &dyn Progress,
) -> Result<Vec<Condition>, Failure> {
    let mut out = Vec::new();
    for (other, (on, model)) in scene.stream_plate_sweep.iter().zip(swept) {
        let mut struck = ensemble.clone();
        struck.ensemble.region = other.region;
        let rows = || -> Result<Vec<Vec<f64>>, Failure> {
            let instrument = Instrument::new(model, &on.plate, &spec(on, on.signals.sensors.clone()), on)?;
            Ok(windowed(&instrument, (&struck, study, study.spec.rate_per_s), w, progress)?.1)
        };
        // Name the plate in what goes wrong on it.
        let rows = rows().map_err(|e| format!("stream.plate_sweep, the {}: {e}", other.shift))?;
        out.push((other.shift.clone(), rows));
    }
    Ok(out)
}

/// The study's streams of `ensemble` at `rate_per_s`, recorded through `instrument` as it
/// stands, and their window features.
pub(super) fn windowed(
    instrument: &dyn Recorder,
    (ensemble, study, rate_per_s): (&identify::Study, &StreamStudy, f64),
    w: &Windows,
    progress: &dyn Progress,
) -> Result<(Vec<Simulated>, Vec<Vec<f64>>), Failure> {
    let sims = simulate(instrument, ensemble, study, rate_per_s, progress)?;
    let (rec, r) = record(instrument, &sims, 1.0);
    let rows = features(&rec, r, &w.windows, study);
    Ok((sims, rows))
}

/// `ensemble` with every family's radius law that of R·`scale` ([`identify::distribution::Distribution::scaled`]):
/// each lump draws the same uniforms, so the same streams arrive at the same instants and
/// points with the same speeds and materials, every lump `scale` times as large.
fn sized(ensemble: &identify::Study, scale: f64) -> identify::Study {
    let mut out = ensemble.clone();
    for f in &mut out.ensemble.families {
        f.radius = f.radius.scaled(scale);
    }
    out
}

/// The study's streams at `rate_per_s` (stream r from seed + r), simulated in parallel.
fn simulate(
    instrument: &dyn Recorder,
    ensemble: &identify::Study,
    study: &StreamStudy,
    rate_per_s: f64,
    progress: &dyn Progress,
) -> Result<Vec<Simulated>, Failure> {
    let cutting = segments::cutting(instrument, study)?;
    let runs: Vec<Result<Simulated, String>> = (0..study.streams)
        .into_par_iter()
        .map(|r| {
            let sim = simulate_one(instrument, ensemble, study, (rate_per_s, r), cutting);
            progress.advance(1);
            sim
        })
        .collect();
    runs.into_iter().map(|r| r.map_err(Failure::from)).collect()
}

/// Stream `r` of the study at `rate_per_s` (drawn from seed + r), simulated on `instrument`
/// cut as `cutting` says.
pub(super) fn simulate_one(
    instrument: &dyn Recorder,
    ensemble: &identify::Study,
    study: &StreamStudy,
    (rate_per_s, r): (f64, usize),
    cutting: Option<segments::Cutting>,
) -> Result<Simulated, String> {
    let names: Vec<String> = ensemble.ensemble.families.iter().map(|f| f.name.clone()).collect();
    let spec = StreamSpec { rate_per_s, seed: study.spec.seed.wrapping_add(r as u64), ..study.spec };
    let lumps = lumps(&ensemble.ensemble, &spec).map_err(|e| format!("stream {r}: {e}"))?;
    let t0 = Instant::now();
    let (response, pieces) =
        segments::run(instrument, (&lumps, &names), spec.duration, cutting).map_err(|e| format!("stream {r}: {e}"))?;
    Ok(Simulated { lumps, response, seconds: t0.elapsed().as_secs_f64(), pieces })
}

/// The main run's lumps, overlaps and cost, with the free plate's cost over one stream's
/// length measured in the same run as the reference.
fn simulation(
    instrument: &dyn Recorder,
    ensemble: &identify::Study,
    study: &StreamStudy,
    main: &[Simulated],
) -> Result<Simulation, Failure> {
    let names: Vec<String> = ensemble.ensemble.families.iter().map(|f| f.name.clone()).collect();
    let t0 = Instant::now();
    instrument.stream(&[], &names, (study.spec.duration, None))?;
    let free_seconds = t0.elapsed().as_secs_f64();
    let seconds: f64 = main.iter().map(|s| s.seconds).sum();
    let simulated = study.spec.duration * main.len() as f64;
    let lumps: usize = main.iter().map(|s| s.response.lumps.len()).sum();
    let steps: usize = main.iter().map(|s| s.response.steps).sum();
    Ok(Simulation {
        lumps,
        steps_per_lump: steps as f64 / lumps.max(1) as f64,
        overlapped_share: overlapped_share(main),
        joint_steps: main.iter().map(|s| s.response.joint_steps).sum(),
        unconverged_steps: main.iter().map(|s| s.response.unconverged_steps).sum(),
        released_in_contact: main.iter().map(|s| s.response.released_in_contact).sum(),
        cross_residual_bound: main.iter().map(|s| s.response.cross_residual_bound).fold(0.0, f64::max),
        real_time_factor: simulated / seconds.max(1e-9),
        free_real_time_factor: study.spec.duration / free_seconds.max(1e-9),
        modes: instrument.modes(),
        model_rate_hz: instrument.model_rate_hz(),
        segments: main.first().and_then(|s| s.pieces.as_ref()).map(|p| p.cutting.facts),
    })
}

/// The share of the lumps that were in contact together with another.
fn overlapped_share(sims: &[Simulated]) -> f64 {
    let (n, o) =
        sims.iter().flat_map(|s| &s.response.lumps).fold((0, 0), |(n, o), l| (n + 1, o + usize::from(l.overlapped)));
    if n == 0 {
        0.0
    } else {
        o as f64 / n as f64
    }
}

/// Every stream's channels as recorded (through the chain, its background scaled by
/// `scale`, or as the model gives them without one) and the recording's rate.
fn record(instrument: &dyn Recorder, sims: &[Simulated], scale: f64) -> (Vec<Vec<Vec<f64>>>, f64) {
    let rate = instrument.chain().map_or_else(|| instrument.model_rate_hz(), |c| c.spec().rate_hz);
    let out = sims.par_iter().enumerate().map(|(r, s)| record_one(instrument, r, s, scale)).collect();
    (out, rate)
}

/// Stream `r`'s channels as recorded: through the chain with the background of its own
/// stream of random numbers (scaled by `scale`), or as the model gives them without one.
pub(super) fn record_one(instrument: &dyn Recorder, r: usize, s: &Simulated, scale: f64) -> Vec<Vec<f64>> {
    let channels = &s.response.signals.channels;
    let Some(chain) = instrument.chain() else { return channels.iter().map(|c| c.samples.clone()).collect() };
    if let Some(pieces) = &s.pieces {
        return segments::record(chain, pieces, &s.response, scale, RECORDING_KEY + r);
    }
    let mut rng = chain.stream(RECORDING_KEY + r);
    channels
        .iter()
        .map(|c| chain.measure(measurand(c.kind), &c.samples, scale, &mut rng).map_or_else(Vec::new, |m| m.samples))
        .collect()
}

/// The windows of every stream on a common time axis (stream r from r(T + W), so that no two
/// streams' windows touch), labelled by the profile, with their time-block folds: what the
/// detector is scored on, known before any stream is simulated.
pub(super) fn window_set(study: &StreamStudy, seed: u64) -> Windows {
    let (t, w) = (study.spec.duration, study.window);
    let offsets: Vec<f64> = (0..study.streams).map(|r| r as f64 * (t + w)).collect();
    let all: Vec<Window> = offsets.iter().enumerate().flat_map(|(r, &o)| windows(r, o, t, w, study.hop)).collect();
    let p = study.spec.profile;
    let middle = 0.5 * (p.before + p.after);
    let labels = all
        .iter()
        .map(|win| {
            let o = offsets[win.stream];
            let share = p.mean_share(win.start - o, win.end - o);
            // The scene refuses a falling profile: gangue-rich is the later state.
            share >= middle
        })
        .collect();
    let folds = time_block_folds(&all, study.blocks);
    Windows { windows: all, labels, folds, offsets, onset: p.onset, alarm: study.alarm_probability, seed }
}

/// One row per window: every channel's features, channel-major ([`window_features`]).
fn features(recorded: &[Vec<Vec<f64>>], rate: f64, wins: &[Window], study: &StreamStudy) -> Vec<Vec<f64>> {
    let mut rows = vec![Vec::new(); wins.len()];
    for (r, channels) in recorded.iter().enumerate() {
        for (i, row) in features_of(r, channels, rate, wins, study) {
            rows[i] = row;
        }
    }
    rows
}

/// The rows of stream `r`'s windows among `wins` (each with its place in `wins`), from its
/// recorded `channels` at `rate`.
pub(super) fn features_of(
    r: usize,
    channels: &[Vec<f64>],
    rate: f64,
    wins: &[Window],
    study: &StreamStudy,
) -> Vec<(usize, Vec<f64>)> {
    let offset = |w: &Window| w.stream as f64 * (study.spec.duration + study.window);
    let members: Vec<usize> = (0..wins.len()).filter(|&i| wins[i].stream == r).collect();
    let mine: Vec<Window> = members.iter().map(|&i| wins[i]).collect();
    let channels: Vec<&[f64]> = channels.iter().map(Vec::as_slice).collect();
    members.into_iter().zip(window_features(&channels, rate, &mine, study.window, offset)).collect()
}

/// The columns of `members`' features.
pub(super) fn select(rows: &[Vec<f64>], members: &[usize]) -> Vec<Vec<f64>> {
    let k = FEATURES.len();
    rows.iter().map(|r| members.iter().flat_map(|&c| r[c * k..(c + 1) * k].iter().copied()).collect()).collect()
}

/// The name of the supports' channel group.
const SUPPORTS: &str = "supports";

/// Each sensor's channels, then the supports' channels: (name, channel indices).
fn channel_groups(kinds: &[ChannelKind], sensors: usize) -> Vec<(String, Vec<usize>)> {
    let sensor_of = |k: &ChannelKind| match *k {
        ChannelKind::Displacement { sensor }
        | ChannelKind::Velocity { sensor }
        | ChannelKind::Acceleration { sensor }
        | ChannelKind::Strain { sensor } => Some(sensor),
        ChannelKind::SpringForce { .. } | ChannelKind::Reaction { .. } | ChannelKind::JackForce { .. } => None,
    };
    let mut out: Vec<(String, Vec<usize>)> = (0..sensors)
        .map(|s| (format!("sensor {}", s + 1), (0..kinds.len()).filter(|&c| sensor_of(&kinds[c]) == Some(s)).collect()))
        .collect();
    out.push((SUPPORTS.into(), (0..kinds.len()).filter(|&c| sensor_of(&kinds[c]).is_none()).collect()));
    out.retain(|(_, m)| !m.is_empty());
    out
}

/// A lump's mass ρ·4πR³/3, kg.
fn mass(l: &Lump) -> f64 {
    l.draw.density * 4.0 / 3.0 * std::f64::consts::PI * l.draw.radius.powi(3)
}

/// A lump and what it did.
type LumpOf<'a> = (&'a Lump, &'a coupled::reduced::stream::LumpResponse);

/// The lumps of the window `w` of stream `sims[w.stream]`, with their responses.
fn lumps_in<'a>(sims: &'a [Simulated], w: &Window, offset: f64) -> impl Iterator<Item = LumpOf<'a>> {
    let s = &sims[w.stream];
    let (a, b) = (w.start - offset, w.end - offset);
    s.lumps.iter().zip(&s.response.lumps).filter(move |(l, _)| l.time >= a && l.time < b)
}

/// The baselines: each window's lumps' mean contact time, mean P_max, total mass and count.
fn baselines(w: &Windows, sims: &[Simulated]) -> Vec<Baseline> {
    let per_window = |f: &dyn Fn(&[LumpOf<'_>]) -> f64| -> Vec<f64> {
        w.windows
            .iter()
            .map(|win| {
                let ls: Vec<_> = lumps_in(sims, win, w.offsets[win.stream]).collect();
                f(&ls)
            })
            .collect()
    };
    let mean = |v: Vec<f64>| if v.is_empty() { f64::NAN } else { v.iter().sum::<f64>() / v.len() as f64 };
    vec![
        w.baseline("mean contact time t_c", &per_window(&|ls| mean(ls.iter().map(|(_, r)| r.contact_time).collect()))),
        w.baseline("mean contact force P_max", &per_window(&|ls| mean(ls.iter().map(|(_, r)| r.force_max).collect()))),
        w.baseline("total lump mass", &per_window(&|ls| ls.iter().map(|(l, _)| mass(l)).sum())),
        w.baseline("lump count", &per_window(&|ls| ls.len() as f64)),
    ]
}

/// A condition's name and its windows' feature rows.
pub(super) type Condition = (String, Vec<Vec<f64>>);

/// The every-channel detector with the chain's background as stated and scaled by each of
/// the study's scales, and the best channel's SNR there.
fn noise_sweep(
    instrument: &dyn Recorder,
    study: &StreamStudy,
    main: &[Simulated],
    w: &Windows,
    (stated, stated_score): (&[Vec<Vec<f64>>], &super::Score),
) -> Result<(Vec<NoisePoint>, Vec<Condition>), Failure> {
    if study.noise_sweep.is_empty() || instrument.chain().is_none() {
        return Ok((Vec::new(), Vec::new()));
    }
    let (clean, _) = record(instrument, main, 0.0);
    let channels = instrument.channels().len();
    // The stated background first: the main run's recording and score.
    let mut out = vec![NoisePoint { scale: 1.0, snr_db: best_snr(&clean, stated), score: stated_score.clone() }];
    let mut rows_at = Vec::new();
    for &scale in &study.noise_sweep {
        let (rec, rate) = record(instrument, main, scale);
        let rows = features(&rec, rate, &w.windows, study);
        let score = w.score("every channel", &rows, &scale_flags(channels))?.0;
        out.push(NoisePoint { scale, snr_db: best_snr(&clean, &rec), score });
        rows_at.push((format!("background × {}", compact(scale)), rows));
    }
    Ok((out, rows_at))
}

/// The largest SNR over the channels, 10 log₁₀(Σy²/Σ(ŷ - y)²) over every stream, with y the
/// recording without background and ŷ with it (None where no channel has noise).
fn best_snr(clean: &[Vec<Vec<f64>>], noisy: &[Vec<Vec<f64>>]) -> Option<f64> {
    let channels = clean.first().map_or(0, Vec::len);
    (0..channels)
        .filter_map(|c| {
            let (mut s, mut n) = (0.0, 0.0);
            for (a, b) in clean.iter().zip(noisy) {
                for (y, z) in a[c].iter().zip(&b[c]) {
                    s += y * y;
                    n += (z - y) * (z - y);
                }
            }
            (n > 0.0 && s > 0.0).then(|| 10.0 * (s / n).log10())
        })
        .max_by(f64::total_cmp)
}

/// The main run's windows with their truth and every-channel score.
fn window_rows(
    w: &Windows,
    sims: &[Simulated],
    scores: &[Option<f64>],
    p: &identify::stream::Profile,
) -> Vec<WindowRow> {
    w.windows
        .iter()
        .zip(&w.labels)
        .zip(scores)
        .map(|((win, &label), &score)| {
            let o = w.offsets[win.stream];
            let ls: Vec<_> = lumps_in(sims, win, o).collect();
            WindowRow {
                stream: win.stream,
                start: win.start - o,
                end: win.end - o,
                lumps: ls.len(),
                gangue: ls.iter().filter(|(l, _)| l.draw.class == identify::Class::Gangue).count(),
                expected_share: p.mean_share(win.start - o, win.end - o),
                gangue_rich: label,
                score,
            }
        })
        .collect()
}

/// The main run's lumps with what each did.
pub(super) fn lump_rows(ensemble: &identify::Study, sims: &[Simulated]) -> Vec<LumpRow> {
    sims.iter()
        .enumerate()
        .flat_map(|(r, s)| {
            s.lumps.iter().zip(&s.response.lumps).map(move |(l, resp)| LumpRow {
                stream: r,
                time: l.time,
                family: ensemble.ensemble.families[l.draw.family].name.clone(),
                gangue: l.draw.class == identify::Class::Gangue,
                mass: mass(l),
                velocity: l.draw.velocity,
                x: l.draw.x,
                z: l.draw.z,
                contacts: resp.contacts,
                contact_time: resp.contact_time,
                force_max: resp.force_max,
                overlapped: resp.overlapped,
            })
        })
        .collect()
}
