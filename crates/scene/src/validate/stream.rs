//! `[stream]`: a caving-stream detection study (`identify::stream`, `identify::detect`) on
//! the scene's ensemble, each key in its range in the file's units, converted to SI, and the
//! study's memory and time budgets checked before any work.
//!
//! ```toml
//! [stream]
//! rate_per_s = 20.0         # lumps per second (Poisson)
//! duration_s = 90.0         # each stream's length
//! streams = 3               # independent streams (seeds seed, seed + 1, ...)
//! seed = 1
//! gangue_before = 0.05      # the gangue share before the change
//! gangue_after = 0.6        # ... and after it
//! onset_s = 45.0            # when the change starts
//! ramp_s = 5.0              # how long it takes
//! window_s = 2.0            # the detector's window
//! hop_s = 0.5               # ... and its hop
//! blocks = 6                # time blocks of the cross-validation
//! alarm_probability = 0.5   # the out-of-fold probability that raises an alarm
//! rate_sweep_per_s = [5.0, 50.0]
//! noise_sweep = [0.0, 10.0, 100.0]   # scales of [measurement]'s background
//! size_sweep = [1.5]        # scales of every family's radius law, for the transfer
//! law_sweep = ["flores"]    # other contact laws, for the transfer
//! plate_sweep = [{ thickness_mm = 12.0 }]   # other plates, for the transfer
//! segment_s = 30.0          # cut every stream into segments run alone (bit for bit apart)
//! design_sensors = 3        # choose 3 sensors among [ensemble.placement]'s grid by window AUC
//! design_quantity = "acceleration"
//! write_signal = true       # the first stream's continuous signals as a file
//! signal_format = "parquet" # ... as Parquet (or "csv", the default)
//! ```

use super::{count, other, Invalid};
use crate::limits;
use analytic::params::{check, Range};
use coupled::reduced::SignalSettings;
use coupled::transient::LawKind;
use identify::measurement::Measurand;
use identify::stream::{Profile, Segmenting, SignalFormat, StreamDesign, StreamSpec, StreamStudy};
use serde::Deserialize;

/// The stream's table as TOML reads it.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawStream {
    rate_per_s: f64,
    duration_s: f64,
    #[serde(default)]
    streams: Option<f64>,
    #[serde(default)]
    seed: Option<u64>,
    gangue_before: f64,
    gangue_after: f64,
    onset_s: f64,
    #[serde(default)]
    ramp_s: Option<f64>,
    window_s: f64,
    hop_s: f64,
    #[serde(default)]
    blocks: Option<f64>,
    #[serde(default)]
    alarm_probability: Option<f64>,
    #[serde(default)]
    rate_sweep_per_s: Vec<f64>,
    #[serde(default)]
    noise_sweep: Vec<f64>,
    #[serde(default)]
    size_sweep: Vec<f64>,
    #[serde(default)]
    law_sweep: Vec<String>,
    #[serde(default)]
    pub(super) plate_sweep: Vec<super::plate_sweep::RawPlateChange>,
    /// The key `plate_sweep` replaced: read only to say so.
    #[serde(default)]
    thickness_sweep_mm: Option<toml::Value>,
    #[serde(default)]
    segment_s: Option<f64>,
    #[serde(default)]
    segment_tolerance: Option<f64>,
    #[serde(default)]
    design_sensors: Option<f64>,
    #[serde(default)]
    design_quantity: Option<String>,
    #[serde(default)]
    write_signal: bool,
    #[serde(default)]
    signal_format: Option<String>,
}

/// Checks `[stream]` against the signals it will be recorded with: `signals` (the model's
/// rate and channels) and `adc_rate_hz` (the chain's rate, or the model's without one), and
/// the study, and the contact laws of its law sweep (the plate sweep is
/// [`super::plate_sweep`]'s).
pub(crate) fn validate_stream(
    raw: &RawStream,
    signals: &SignalSettings,
    (adc_rate_hz, has_chain): (f64, bool),
    conditions: usize,
) -> Result<(StreamStudy, Vec<LawKind>), Invalid> {
    if raw.thickness_sweep_mm.is_some() {
        return Err(other(
            "stream.thickness_sweep_mm",
            "is replaced by plate_sweep, which changes any of [plate]'s keys: write plate_sweep = [{ thickness_mm = 12.0 }] for a plate 12 mm thick",
        ));
    }
    let rate = check("stream.rate_per_s", raw.rate_per_s, limits::STREAM_RATE_PER_S, "1/s")?;
    let duration = check("stream.duration_s", raw.duration_s, limits::STREAM_DURATION_S, "s")?;
    let share = Range::closed(0.0, 1.0);
    let before = check("stream.gangue_before", raw.gangue_before, share, "")?;
    let after = check("stream.gangue_after", raw.gangue_after, share, "")?;
    if before == after {
        return Err(other(
            "stream.gangue_after",
            format!("{after} equals gangue_before: the stream has no change to detect"),
        ));
    }
    // The detector's positive class is "gangue-rich", the later state; a stream turning
    // coal-rich would make an alarm mean the opposite under the same name.
    if after < before {
        return Err(other(
            "stream.gangue_after",
            format!(
                "{after} is below gangue_before = {before}: the study detects a turn to gangue-rich; allowed ({before}, 1]"
            ),
        ));
    }
    let onset = check("stream.onset_s", raw.onset_s, Range::open(0.0, duration), "s")?;
    let ramp = check("stream.ramp_s", raw.ramp_s.unwrap_or(0.0), Range::closed(0.0, duration - onset), "s")?;
    // The features need 16 samples of the recording in a window.
    let shortest = limits::MIN_SAMPLES / adc_rate_hz;
    let window = check("stream.window_s", raw.window_s, Range::closed(shortest, onset.min(duration - onset)), "s")?;
    let hop = check("stream.hop_s", raw.hop_s, Range::closed(1.0 / adc_rate_hz, window), "s")?;
    let streams = count("stream.streams", raw.streams.unwrap_or(1.0), limits::STREAMS)?;
    let blocks = count("stream.blocks", raw.blocks.unwrap_or(5.0), limits::STREAM_BLOCKS)?;
    let alarm_probability =
        check("stream.alarm_probability", raw.alarm_probability.unwrap_or(0.5), Range::open(0.0, 1.0), "")?;
    let Sweeps { rate_sweep, noise_sweep, size_sweep, laws } = sweeps(raw, has_chain)?;
    let spec = StreamSpec {
        rate_per_s: rate,
        duration,
        profile: Profile { before, after, onset, ramp },
        seed: raw.seed.unwrap_or(1),
    };
    let study = StreamStudy {
        spec,
        streams,
        window,
        hop,
        blocks,
        alarm_probability,
        rate_sweep,
        noise_sweep,
        size_sweep,
        segments: segmenting(raw, (window, duration))?,
        design: design(raw)?,
        write_signal: raw.write_signal,
        signal_format: signal_format(raw.signal_format.as_deref(), raw.write_signal)?,
    };
    budgets(&study, signals, conditions, laws.len() + raw.plate_sweep.len())?;
    Ok((study, laws))
}

/// The cut of every stream, if `segment_s` asks for one: segments at least
/// [`limits::MIN_SEGMENT_S`] and a window long, at most the stream.
fn segmenting(raw: &RawStream, (window, duration): (f64, f64)) -> Result<Option<Segmenting>, Invalid> {
    let Some(length) = raw.segment_s else {
        if let Some(t) = raw.segment_tolerance {
            return Err(other(
                "stream.segment_tolerance",
                format!("{t} is given but segment_s is not: nothing is cut"),
            ));
        }
        return Ok(None);
    };
    let shortest = limits::MIN_SEGMENT_S.max(window).min(duration);
    let length = check("stream.segment_s", length, Range::closed(shortest, duration), "s")?;
    // Each segment draws its backgrounds from its own blocks of the recording's random numbers.
    if (duration / length).ceil() > identify::measurement::segments::MAX_SEGMENTS as f64 {
        return Err(other(
            "stream.segment_s",
            format!(
                "{length} s cuts a {duration} s stream into more than {} segments",
                identify::measurement::segments::MAX_SEGMENTS
            ),
        ));
    }
    let tolerance =
        check("stream.segment_tolerance", raw.segment_tolerance.unwrap_or(1e-9), limits::SEGMENT_TOLERANCE, "")?;
    Ok(Some(Segmenting { length, tolerance }))
}

/// The study's sweeps as checked: rates, background scales, size scales and contact laws.
struct Sweeps {
    rate_sweep: Vec<f64>,
    noise_sweep: Vec<f64>,
    size_sweep: Vec<f64>,
    laws: Vec<LawKind>,
}

/// `[stream]`'s sweeps, each entry in its range; a background scale needs a chain, a law is
/// named once.
fn sweeps(raw: &RawStream, has_chain: bool) -> Result<Sweeps, Invalid> {
    let mut rate_sweep = Vec::new();
    for (i, &r) in raw.rate_sweep_per_s.iter().enumerate() {
        rate_sweep.push(check(&format!("stream.rate_sweep_per_s[{i}]"), r, limits::STREAM_RATE_PER_S, "1/s")?);
    }
    if !raw.noise_sweep.is_empty() && !has_chain {
        return Err(other("stream.noise_sweep", "scales [measurement]'s background; the scene has no [measurement]"));
    }
    let mut noise_sweep = Vec::new();
    for (i, &s) in raw.noise_sweep.iter().enumerate() {
        noise_sweep.push(check(&format!("stream.noise_sweep[{i}]"), s, Range::closed(0.0, 1e6), "")?);
    }
    let mut size_sweep = Vec::new();
    for (i, &s) in raw.size_sweep.iter().enumerate() {
        size_sweep.push(check(&format!("stream.size_sweep[{i}]"), s, limits::STREAM_SIZE_SCALE, "")?);
    }
    let mut laws = Vec::new();
    for (i, k) in raw.law_sweep.iter().enumerate() {
        let field = format!("stream.law_sweep[{i}]");
        let law = super::law_key(&field, k)?;
        if laws.contains(&law) {
            return Err(other(&field, format!("'{k}' is named twice; name each law once")));
        }
        laws.push(law);
    }
    Ok(Sweeps { rate_sweep, noise_sweep, size_sweep, laws })
}

/// The plate quantities a window-level design may place, by key.
const DESIGN_QUANTITIES: [Measurand; 4] =
    [Measurand::Acceleration, Measurand::Velocity, Measurand::Displacement, Measurand::Strain];

/// The window-level sensor design, if `design_sensors` asks for one: its budget and what each
/// sensor records (`design_quantity`, acceleration by default).
fn design(raw: &RawStream) -> Result<Option<StreamDesign>, Invalid> {
    let Some(budget) = raw.design_sensors else {
        if let Some(q) = &raw.design_quantity {
            return Err(other(
                "stream.design_quantity",
                format!("\"{q}\" is given but design_sensors is not: nothing is designed"),
            ));
        }
        return Ok(None);
    };
    let sensors = count("stream.design_sensors", budget, crate::ensemble::DESIGN_SENSORS)?;
    let measurand = match raw.design_quantity.as_deref() {
        None => Measurand::Acceleration,
        Some(q) => DESIGN_QUANTITIES.into_iter().find(|m| m.key() == q).ok_or_else(|| {
            let keys: Vec<String> = DESIGN_QUANTITIES.iter().map(|m| format!("\"{}\"", m.key())).collect();
            other("stream.design_quantity", format!("\"{q}\" is not a plate quantity; allowed: {}", keys.join(", ")))
        })?,
    };
    Ok(Some(StreamDesign { sensors, measurand }))
}

/// What the window-level design needs beyond `[stream]`: a plate to place sensors on
/// (`on_plate`), the candidate grid of `[ensemble.placement]`, a chain (if any) that records
/// the design's quantity, and room for one stream's channels at every candidate (the design
/// runs its streams one at a time): the model's signals at `model_rate_hz` and their recording.
pub(crate) fn check_design(
    study: &StreamStudy,
    ensemble: &identify::Study,
    chain: Option<&identify::measurement::ChainSpec>,
    (on_plate, model_rate_hz): (bool, f64),
) -> Result<(), Invalid> {
    let Some(design) = study.design else { return Ok(()) };
    let field = "stream.design_sensors";
    if !on_plate {
        return Err(other(
            field,
            "chooses sensors among a plate's candidate points; a tail beam's stream strikes the box (leave it out)",
        ));
    }
    let candidates = ensemble.candidates().len();
    if candidates == 0 {
        return Err(other(
            field,
            "chooses among the candidate points of [ensemble.placement]; the scene has none (give x_count and z_count)",
        ));
    }
    if design.sensors > candidates {
        return Err(other(
            field,
            format!("{} sensors among {candidates} candidate points; allowed at most {candidates}", design.sensors),
        ));
    }
    if let Some(c) = chain {
        if !c.recordings.iter().any(|r| r.measurand == design.measurand) {
            let recorded: Vec<String> = c
                .recordings
                .iter()
                .filter(|r| DESIGN_QUANTITIES.contains(&r.measurand))
                .map(|r| format!("\"{}\"", r.measurand.key()))
                .collect();
            let allowed = if recorded.is_empty() {
                "the chain records no plate quantity to place (add one to [measurement])".to_string()
            } else {
                format!("allowed: {}", recorded.join(", "))
            };
            return Err(other(
                "stream.design_quantity",
                format!("\"{}\" is not recorded by [measurement]; {allowed}", design.measurand.key()),
            ));
        }
    }
    let bytes = signal_bytes(study, 1, (candidates, model_rate_hz));
    if bytes > limits::MAX_STREAM_SIGNAL_BYTES {
        return Err(other(
            field,
            format!(
                "a stream of {} s at {model_rate_hz} Hz at {candidates} candidate points, recorded, holds {:.0} MB of signal, above the {:.0} MB budget; use fewer candidates or shorter streams",
                study.spec.duration,
                bytes / 1e6,
                limits::MAX_STREAM_SIGNAL_BYTES / 1e6
            ),
        ));
    }
    Ok(())
}

/// Bytes that `streams` of the study's streams hold at once on `channels` channels at the
/// model's `rate_hz`: their model signals, their recording (at most as long again) and, where
/// the streams are cut, the segments' warm-ups (at most as many samples again, checked once
/// the model's decay is known).
fn signal_bytes(study: &StreamStudy, streams: usize, (channels, rate_hz): (usize, f64)) -> f64 {
    let copies = if study.segments.is_some() { 3.0 } else { 2.0 };
    copies * streams as f64 * study.spec.duration * rate_hz * channels as f64 * 8.0
}

/// `signal_format` as written: "csv" or "parquet", and only where a signal is written.
fn signal_format(written: Option<&str>, write_signal: bool) -> Result<SignalFormat, Invalid> {
    let field = "stream.signal_format";
    match written {
        None => Ok(SignalFormat::Csv),
        Some(_) if !write_signal => Err(other(field, "is given but write_signal is not true: no signal is written")),
        Some("csv") => Ok(SignalFormat::Csv),
        Some("parquet") => Ok(SignalFormat::Parquet),
        Some(f) => Err(other(field, format!("\"{f}\" is not a format; allowed \"csv\", \"parquet\""))),
    }
}

/// The study's streams are held at once (every stream's model signals and their recording),
/// so together they must fit the memory budget; its lumps (every stream, rate and support
/// set) and its windows must fit theirs. `others` counts the swept laws and plates.
fn budgets(study: &StreamStudy, signals: &SignalSettings, conditions: usize, others: usize) -> Result<(), Invalid> {
    // Every quantity at every sensor (3, or 4 with strain) and the four corners: a bound.
    let channels = 4 * signals.sensors.len() + 4;
    let bytes = signal_bytes(study, study.streams, (channels, signals.rate_hz));
    if bytes > limits::MAX_STREAM_SIGNAL_BYTES {
        return Err(other(
            "stream.duration_s and stream.streams",
            format!(
                "{} streams of {} s at {} Hz on up to {channels} channels, recorded, hold {:.0} MB of signal, above the {:.0} MB budget; shorten the streams or run fewer",
                study.streams,
                study.spec.duration,
                signals.rate_hz,
                bytes / 1e6,
                limits::MAX_STREAM_SIGNAL_BYTES / 1e6
            ),
        ));
    }
    // The size, plate and law sweeps run whole studies at the main rate.
    let at_main = 1 + study.size_sweep.len() + others;
    let rates: f64 = study.spec.rate_per_s * at_main as f64 + study.rate_sweep.iter().sum::<f64>();
    let lumps = rates * study.spec.duration * study.streams as f64 * conditions as f64;
    if lumps > limits::MAX_STREAM_LUMPS {
        return Err(other(
            "stream.rate_per_s, rate_sweep_per_s, size_sweep, plate_sweep, law_sweep, duration_s and streams",
            format!(
                "expect {lumps:.0} lumps over every stream, rate, size law, plate, contact law and support set, above the budget of {:.0}",
                limits::MAX_STREAM_LUMPS
            ),
        ));
    }
    let windows = (((study.spec.duration - study.window) / study.hop).floor() + 1.0) * study.streams as f64;
    if windows > limits::MAX_STREAM_WINDOWS {
        return Err(other(
            "stream.hop_s",
            format!("{windows:.0} windows, above the budget of {:.0}; lengthen the hop", limits::MAX_STREAM_WINDOWS),
        ));
    }
    if (study.blocks as f64) > windows {
        return Err(other(
            "stream.blocks",
            format!("{} blocks for {windows} windows; at most one block per window", study.blocks),
        ));
    }
    Ok(())
}

/// Every family's radius law scaled by each of `study`'s size scales stays within the radii a
/// scene may give ([`limits::RADIUS_MM`]).
pub(crate) fn check_size_sweep(study: &StreamStudy, ensemble: &identify::Study) -> Result<(), Invalid> {
    let (lo, hi) = (limits::RADIUS_MM.lo * 1e-3, limits::RADIUS_MM.hi * 1e-3);
    for (i, &scale) in study.size_sweep.iter().enumerate() {
        for f in &ensemble.ensemble.families {
            let Some((a, b)) = f.radius.scaled(scale).bounds() else { continue };
            if a < lo || b > hi {
                return Err(other(
                    format!("stream.size_sweep[{i}]"),
                    format!(
                        "{scale} scales family '{}' to radii {} to {} mm, outside the allowed {} mm",
                        f.name,
                        a * 1e3,
                        b * 1e3,
                        limits::RADIUS_MM
                    ),
                ));
            }
        }
    }
    Ok(())
}
