//! `[signals]`: the reduced model's window, sampling rate, damping, modes and sensors.

use super::{count, other, Invalid, MM};
use crate::limits;
use crate::raw::*;
use analytic::params::{check, Range};
use coupled::reduced::{Arithmetic, SignalSettings};

/// `[signals]`: each key in its range (the file's units), converted to SI; absent keys take
/// the defaults of [`SignalSettings`]. The scene's plate damping `rayleigh` replaces the
/// modal ratio, so a scene may not give both.
pub(super) fn validate_signals(
    raw: Option<&RawSignals>,
    l_mm: f64,
    b_mm: f64,
    rayleigh: Option<plate_fem::dynamics::Rayleigh>,
    on_plate: bool,
) -> Result<SignalSettings, Invalid> {
    let d = SignalSettings { rayleigh, ..SignalSettings::default() };
    let Some(raw) = raw else { return Ok(d) };
    if let (Some(z), Some(_)) = (raw.damping_ratio, rayleigh) {
        return Err(other(
            "signals.damping_ratio",
            format!("{z} is a second definition of the plate's damping beside [plate_damping]; give one (the [plate_damping] table damps the transient and the reduced model alike)"),
        ));
    }
    let window_ms = match raw.window_ms {
        Some(w) => check("signals.window_ms", w, limits::SIGNAL_WINDOW_MS, "ms")?,
        None => d.window * 1e3,
    };
    let rate_hz = match raw.rate_hz {
        Some(r) => check("signals.rate_hz", r, limits::SAMPLE_RATE_HZ, "Hz")?,
        None => d.rate_hz,
    };
    let samples = window_ms * 1e-3 * rate_hz;
    if samples < limits::MIN_SAMPLES {
        return Err(other(
            "signals.window_ms and signals.rate_hz",
            format!(
                "{window_ms} ms at {rate_hz} Hz is {} samples per channel; at least {} are needed (lengthen the window or raise the rate)",
                analytic::params::compact(samples),
                limits::MIN_SAMPLES
            ),
        ));
    }
    if samples > limits::MAX_SAMPLES {
        return Err(other(
            "signals.window_ms and signals.rate_hz",
            format!(
                "{window_ms} ms at {rate_hz} Hz is {} samples per channel; at most {} are allowed",
                analytic::params::compact(samples.ceil()),
                analytic::params::compact(limits::MAX_SAMPLES)
            ),
        ));
    }
    let damping_ratio = match raw.damping_ratio {
        Some(z) => check("signals.damping_ratio", z, coupled::reduced::ReducedSettings::DAMPING_RATIO, "")?,
        None => d.damping_ratio,
    };
    let (modes, modes_from_chain) = modes(raw.modes.as_ref(), on_plate.then_some((l_mm, b_mm)))?;
    let sensors = sensors(raw.sensors_mm.as_deref(), (l_mm, b_mm))?;
    check_sensors(&sensors, samples)?;
    let truncation_check = match raw.truncation_check_fraction {
        Some(f) => check("signals.truncation_check_fraction", f, limits::TRUNCATION_CHECK, "")?,
        None => d.truncation_check,
    };
    let arithmetic = arithmetic(raw.arithmetic.as_deref())?;
    Ok(SignalSettings {
        window: window_ms * 1e-3,
        rate_hz,
        damping_ratio,
        rayleigh,
        modes,
        modes_from_chain,
        sensors,
        truncation_check,
        arithmetic,
    })
}

/// `signals.arithmetic` as written: "exact" (the default) or "fast".
fn arithmetic(written: Option<&str>) -> Result<Arithmetic, Invalid> {
    match written {
        None | Some("exact") => Ok(Arithmetic::Exact),
        Some("fast") => Ok(Arithmetic::Fast),
        Some(w) => {
            Err(other("signals.arithmetic", format!("\"{w}\" is not an arithmetic; allowed \"exact\", \"fast\"")))
        }
    }
}

/// `signals.sensors_mm`: at most [`limits::MAX_SENSORS`] points (x, z) on the plate of
/// `(l_mm, b_mm)`, in m.
fn sensors(list: Option<&[Vec<f64>]>, (l_mm, b_mm): (f64, f64)) -> Result<Vec<(f64, f64)>, Invalid> {
    let Some(list) = list else { return Ok(Vec::new()) };
    if list.len() > limits::MAX_SENSORS {
        return Err(other(
            "signals.sensors_mm",
            format!("{} sensors; at most {} are allowed", list.len(), limits::MAX_SENSORS),
        ));
    }
    let (along, across) = (Range::closed(0.0, l_mm), Range::closed(0.0, b_mm));
    let mut out = Vec::with_capacity(list.len());
    for (j, pair) in list.iter().enumerate() {
        let (x, z) = super::pair(&format!("signals.sensors_mm[{j}]"), pair, "[x, z]")?;
        let x = check(&format!("signals.sensors_mm[{j}][0] (x)"), x, along, "mm")? * MM;
        let z = check(&format!("signals.sensors_mm[{j}][1] (z)"), z, across, "mm")? * MM;
        out.push((x, z));
    }
    Ok(out)
}

/// `signals.modes`: a whole number within [`limits::MODES`] and, on a plate of `plate_mm`
/// (length, width), the plate's [`limits::max_modes`] (a structure's own mesh bounds its
/// modes when it is built); absent, the default or the plate's most, whichever is fewer;
/// `"chain"`, the plate's most with each support set keeping those the chain needs. Returns
/// the count and whether the chain chooses.
fn modes(raw: Option<&RawModes>, plate_mm: Option<(f64, f64)>) -> Result<(usize, bool), Invalid> {
    let most = plate_mm.map_or(limits::MAX_MODES, |(l, b)| limits::max_modes(l, b));
    let n = match raw {
        None => return Ok((SignalSettings::default().modes.min(most), false)),
        Some(RawModes::Word(w)) if w == "chain" => return Ok((most, true)),
        Some(RawModes::Word(w)) => {
            return Err(other("signals.modes", format!("'{w}' is neither a number of modes nor \"chain\"")))
        }
        Some(RawModes::Count(n)) => *n,
    };
    if let (Some((l_mm, b_mm)), true) = (plate_mm, n > most as f64) {
        return Err(other(
            "signals.modes",
            format!(
                "{} is outside [1, {most}] for this {} x {} mm plate: the reduced model's mesh of it resolves at most {most} modes (an eighth of its degrees of freedom); ask for fewer",
                analytic::params::compact(n),
                analytic::params::compact(l_mm),
                analytic::params::compact(b_mm)
            ),
        ));
    }
    Ok((count("signals.modes", n, limits::MODES)?, false))
}

/// The sensors as a whole: distinct channel names, and one impact's signals within
/// [`limits::MAX_IMPACT_SIGNAL_BYTES`].
fn check_sensors(sensors: &[(f64, f64)], samples: f64) -> Result<(), Invalid> {
    // Labels round to 0.1 mm; more digits would rename every channel of every report, and two
    // sensors closer than that record the same signal.
    if let Some((field, message)) = crate::sensor_label_refusal("signals.sensors_mm", sensors) {
        return Err(other(field, message));
    }
    let channels = 3 * sensors.len() + 4;
    let bytes = samples.ceil() * channels as f64 * 8.0;
    if bytes > limits::MAX_IMPACT_SIGNAL_BYTES {
        return Err(other(
            "signals.window_ms, signals.rate_hz and signals.sensors_mm",
            format!(
                "{} samples x {channels} channels (3 a sensor, up to 4 corners) is {} MB of signals an impact; at most {} MB",
                analytic::params::compact(samples.ceil()),
                analytic::params::compact((bytes / 1e6).round()),
                analytic::params::compact((limits::MAX_IMPACT_SIGNAL_BYTES / 1e6).round()),
            ),
        ));
    }
    Ok(())
}
