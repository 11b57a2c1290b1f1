//! `[measurement]`: the chain a data acquisition puts between the plate and the features
//! (`identify::measurement`), each key in its range in the file's units, converted to SI.
//!
//! ```toml
//! [measurement]
//! rate_hz = 10000.0                 # the ADC's rate: signals.rate_hz over a whole number
//! seed = 7                          # the backgrounds' seed
//! sensor = { resonance_hz = 12000.0, resonance_damping = 0.05, high_pass_hz = 1.0 }
//! anti_alias = { order = 8, corner_hz = 4000.0 }
//!
//! [measurement.acceleration]        # every sensor point's acceleration
//! adc_range_m_s2 = 2000.0
//! adc_bits = 16
//! noise = "pink"                    # "white", "pink" or "measured"
//! noise_rms_m_s2 = 5.0              # white or pink: the rms over 0 to rate_hz/2
//! pink_flat_below_hz = 10.0
//! tones_m_s2 = [[50.0, 1.0], [150.0, 0.5]]   # [frequency Hz, rms]
//!
//! [measurement.strain]              # a gauge along x on the unstruck face at every sensor point
//! adc_range_microstrain = 500.0
//! adc_bits = 24
//! noise = "white"
//! noise_rms_microstrain = 0.5
//!
//! [measurement.support_force]      # every prop's, jack's or held corner's force
//! adc_range_kn = 50.0
//! adc_bits = 16
//! noise = "measured"
//! noise_psd_kn2_per_hz = [[0.0, 1e-6], [2000.0, 1e-6], [5000.0, 1e-8]]
//! ```

use super::{count, other, pair, Invalid};
use crate::limits;
use analytic::params::{check, compact, Range};
use identify::measurement::noise::{Psd, Tone};
use identify::measurement::{AntiAlias, Chain, ChainSpec, Measurand, Recording, SensorBand, MAX_FILTER_ORDER};
use serde::Deserialize;

/// The chain's table as TOML reads it.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMeasurement {
    rate_hz: f64,
    #[serde(default)]
    seed: Option<u64>,
    #[serde(default)]
    band_tolerance: Option<f64>,
    #[serde(default)]
    sensor: Option<RawSensor>,
    #[serde(default)]
    anti_alias: Option<RawAntiAlias>,
    #[serde(default)]
    acceleration: Option<RawAcceleration>,
    #[serde(default)]
    support_force: Option<RawSupportForce>,
    #[serde(default)]
    strain: Option<RawStrain>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSensor {
    resonance_hz: Option<f64>,
    resonance_damping: Option<f64>,
    high_pass_hz: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawAntiAlias {
    order: f64,
    corner_hz: f64,
}

/// `[measurement.acceleration]`, in m/s².
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawAcceleration {
    adc_range_m_s2: f64,
    adc_bits: f64,
    noise: Option<String>,
    noise_rms_m_s2: Option<f64>,
    pink_flat_below_hz: Option<f64>,
    noise_psd_m2_s4_per_hz: Option<Vec<Vec<f64>>>,
    noise_psd_file: Option<String>,
    /// Where the points came from when read from `noise_psd_file` (for errors).
    #[serde(skip)]
    psd_origin: Option<String>,
    tones_m_s2: Option<Vec<Vec<f64>>>,
}

/// `[measurement.support_force]`, in kN.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSupportForce {
    adc_range_kn: f64,
    adc_bits: f64,
    noise: Option<String>,
    noise_rms_kn: Option<f64>,
    pink_flat_below_hz: Option<f64>,
    noise_psd_kn2_per_hz: Option<Vec<Vec<f64>>>,
    noise_psd_file: Option<String>,
    /// Where the points came from when read from `noise_psd_file` (for errors).
    #[serde(skip)]
    psd_origin: Option<String>,
    tones_kn: Option<Vec<Vec<f64>>>,
}

/// `[measurement.strain]`, in microstrain.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawStrain {
    adc_range_microstrain: f64,
    adc_bits: f64,
    noise: Option<String>,
    noise_rms_microstrain: Option<f64>,
    pink_flat_below_hz: Option<f64>,
    noise_psd_microstrain2_per_hz: Option<Vec<Vec<f64>>>,
    noise_psd_file: Option<String>,
    /// Where the points came from when read from `noise_psd_file` (for errors).
    #[serde(skip)]
    psd_origin: Option<String>,
    tones_microstrain: Option<Vec<Vec<f64>>>,
}

/// A recording's background kind, PSD file, inline points and where they came from.
type PsdKeys<'a> = (Option<&'a str>, &'a Option<String>, &'a mut Option<Vec<Vec<f64>>>, &'a mut Option<String>);

/// Reads each recording's `noise_psd_file` (relative to `base`) into its inline points, so
/// that validation sees one list either way; both at once is refused.
pub(crate) fn read_psd_files(raw: &mut RawMeasurement, base: Option<&std::path::Path>) -> Result<(), Invalid> {
    let tables: [(&str, &str, Option<PsdKeys<'_>>); 3] = [
        (
            "measurement.acceleration",
            "noise_psd_m2_s4_per_hz",
            raw.acceleration
                .as_mut()
                .map(|a| (a.noise.as_deref(), &a.noise_psd_file, &mut a.noise_psd_m2_s4_per_hz, &mut a.psd_origin)),
        ),
        (
            "measurement.strain",
            "noise_psd_microstrain2_per_hz",
            raw.strain.as_mut().map(|a| {
                (a.noise.as_deref(), &a.noise_psd_file, &mut a.noise_psd_microstrain2_per_hz, &mut a.psd_origin)
            }),
        ),
        (
            "measurement.support_force",
            "noise_psd_kn2_per_hz",
            raw.support_force
                .as_mut()
                .map(|a| (a.noise.as_deref(), &a.noise_psd_file, &mut a.noise_psd_kn2_per_hz, &mut a.psd_origin)),
        ),
    ];
    for (table, inline, keys) in tables {
        let Some((noise, file, points, origin)) = keys else { continue };
        let Some(path) = file.as_deref() else { continue };
        let field = format!("{table}.noise_psd_file");
        if noise != Some("measured") {
            return Err(other(field, "is read only by noise = \"measured\""));
        }
        if points.is_some() {
            return Err(other(field, format!("and {table}.{inline} are both given; give one")));
        }
        *points = Some(super::psd_file::read(&field, path, base)?);
        *origin = Some(format!("{field} ('{path}'), point"));
    }
    Ok(())
}

/// One recording's keys, whatever their unit; `scale` converts the file's unit to SI.
struct Keys<'a> {
    table: &'static str,
    /// The unit-bearing keys: the ADC's range, the rms, the measured PSD, the tones.
    names: [&'static str; 4],
    scale: f64,
    range: f64,
    bits: f64,
    noise: Option<&'a str>,
    rms: Option<f64>,
    flat_below: Option<f64>,
    psd: Option<&'a [Vec<f64>]>,
    /// The points' name in errors when they were read from a file.
    psd_origin: Option<&'a str>,
    tones: Option<&'a [Vec<f64>]>,
}

/// ADC full scales, in the file's unit (m/s², microstrain or kN): 1e-9 to 1e9.
pub(crate) const ADC_RANGE: Range = Range::closed(1e-9, 1e9);
/// ADC bits: 1 to 32 (a DAQ's are 12 to 24).
pub(crate) const ADC_BITS: Range = Range::closed(1.0, 32.0);
/// Background and tone rms, in the file's unit: 0 (none) to 1e9.
pub(crate) const NOISE_RMS: Range = Range::closed(0.0, 1e9);
/// A sensor's resonance damping ratio.
pub(crate) const RESONANCE_DAMPING: Range = Range::closed(1e-3, 1.0);
/// The gain below which a frequency is outside the chain's band.
pub(crate) const BAND_TOLERANCE: Range = Range::closed(1e-9, 0.5);
/// Most points of a measured PSD and most tones.
pub(crate) const MAX_POINTS: usize = 10_000;
/// The default seed of the backgrounds.
pub(crate) const DEFAULT_SEED: u64 = 1;
/// The default band tolerance: a part of the response the chain passes at below 0.1 % is
/// below a 16-bit ADC's step at a tenth of its range.
pub(crate) const DEFAULT_BAND_TOLERANCE: f64 = 1e-3;

/// `[measurement]` on signals of `model_samples` samples a window at `model_rate_hz`
/// (`[signals]`).
pub(crate) fn validate_measurement(
    raw: &RawMeasurement,
    model_rate_hz: f64,
    model_samples: f64,
) -> Result<ChainSpec, Invalid> {
    let rate_hz = check("measurement.rate_hz", raw.rate_hz, limits::SAMPLE_RATE_HZ, "Hz")?;
    let sensor =
        raw.sensor.as_ref().map(sensor_band).transpose()?.unwrap_or(SensorBand { resonance: None, high_pass_hz: None });
    let anti_alias = match &raw.anti_alias {
        None => None,
        Some(a) => Some(AntiAlias {
            order: count("measurement.anti_alias.order", a.order, Range::closed(1.0, MAX_FILTER_ORDER as f64))?,
            corner_hz: check("measurement.anti_alias.corner_hz", a.corner_hz, Range::open(0.0, 0.5 * rate_hz), "Hz")?,
        }),
    };
    let recordings = recordings(raw, rate_hz)?;
    let band_tolerance = match raw.band_tolerance {
        Some(t) => check("measurement.band_tolerance", t, BAND_TOLERANCE, "")?,
        None => DEFAULT_BAND_TOLERANCE,
    };
    let spec =
        ChainSpec { sensor, anti_alias, rate_hz, recordings, seed: raw.seed.unwrap_or(DEFAULT_SEED), band_tolerance };
    // The rates and the filters' realisability on the model's samples, before any work.
    let chain = Chain::new(spec.clone(), model_rate_hz).map_err(|e| other("measurement", e.to_string()))?;
    let adc_samples = chain.samples(model_samples.ceil() as usize);
    if (adc_samples as f64) < limits::MIN_SAMPLES {
        return Err(other(
            "measurement.rate_hz",
            format!(
                "{} Hz leaves {adc_samples} samples of the window; the features need at least {} (raise the rate or lengthen signals.window_ms)",
                compact(rate_hz),
                limits::MIN_SAMPLES
            ),
        ));
    }
    Ok(spec)
}

/// `[measurement.sensor]`: both resonance keys or neither, and the AC coupling.
fn sensor_band(s: &RawSensor) -> Result<SensorBand, Invalid> {
    let resonance = match (s.resonance_hz, s.resonance_damping) {
        (None, None) => None,
        (Some(f), Some(z)) => Some((
            check("measurement.sensor.resonance_hz", f, Range::open(0.0, 1e7), "Hz")?,
            check("measurement.sensor.resonance_damping", z, RESONANCE_DAMPING, "")?,
        )),
        _ => {
            return Err(other(
                "measurement.sensor",
                "gives one of resonance_hz and resonance_damping; a mounted resonance needs both",
            ))
        }
    };
    let high_pass_hz =
        s.high_pass_hz.map(|f| check("measurement.sensor.high_pass_hz", f, Range::open(0.0, 1e7), "Hz")).transpose()?;
    Ok(SensorBand { resonance, high_pass_hz })
}

/// The recorded measurands' tables, each with its unit's keys; at least one.
fn recordings(raw: &RawMeasurement, rate_hz: f64) -> Result<Vec<Recording>, Invalid> {
    let mut out = Vec::new();
    if let Some(a) = &raw.acceleration {
        let keys = Keys {
            table: "measurement.acceleration",
            names: ["adc_range_m_s2", "noise_rms_m_s2", "noise_psd_m2_s4_per_hz", "tones_m_s2"],
            scale: 1.0,
            range: a.adc_range_m_s2,
            bits: a.adc_bits,
            noise: a.noise.as_deref(),
            rms: a.noise_rms_m_s2,
            flat_below: a.pink_flat_below_hz,
            psd: a.noise_psd_m2_s4_per_hz.as_deref(),
            psd_origin: a.psd_origin.as_deref(),
            tones: a.tones_m_s2.as_deref(),
        };
        out.push(recording(Measurand::Acceleration, keys, rate_hz)?);
    }
    if let Some(s) = &raw.strain {
        let keys = Keys {
            table: "measurement.strain",
            names: [
                "adc_range_microstrain",
                "noise_rms_microstrain",
                "noise_psd_microstrain2_per_hz",
                "tones_microstrain",
            ],
            scale: 1e-6,
            range: s.adc_range_microstrain,
            bits: s.adc_bits,
            noise: s.noise.as_deref(),
            rms: s.noise_rms_microstrain,
            flat_below: s.pink_flat_below_hz,
            psd: s.noise_psd_microstrain2_per_hz.as_deref(),
            psd_origin: s.psd_origin.as_deref(),
            tones: s.tones_microstrain.as_deref(),
        };
        out.push(recording(Measurand::Strain, keys, rate_hz)?);
    }
    if let Some(f) = &raw.support_force {
        let keys = Keys {
            table: "measurement.support_force",
            names: ["adc_range_kn", "noise_rms_kn", "noise_psd_kn2_per_hz", "tones_kn"],
            scale: 1e3,
            range: f.adc_range_kn,
            bits: f.adc_bits,
            noise: f.noise.as_deref(),
            rms: f.noise_rms_kn,
            flat_below: f.pink_flat_below_hz,
            psd: f.noise_psd_kn2_per_hz.as_deref(),
            psd_origin: f.psd_origin.as_deref(),
            tones: f.tones_kn.as_deref(),
        };
        out.push(recording(Measurand::SupportForce, keys, rate_hz)?);
    }
    if out.is_empty() {
        return Err(other(
            "measurement",
            "records nothing; give [measurement.acceleration], [measurement.strain] or [measurement.support_force]",
        ));
    }
    Ok(out)
}

/// One measurand's ADC and background from its keys.
fn recording(measurand: Measurand, k: Keys<'_>, rate_hz: f64) -> Result<Recording, Invalid> {
    let field = |key: &str| format!("{}.{key}", k.table);
    let [range_key, rms_key, psd_key, tones_key] = k.names;
    let range = check(&field(range_key), k.range, ADC_RANGE, "")? * k.scale;
    let bits = count(&field("adc_bits"), k.bits, ADC_BITS)? as u32;
    let band = 0.5 * rate_hz;
    let rms = |need: &str| -> Result<f64, Invalid> {
        let key = field(rms_key);
        let v = k.rms.ok_or_else(|| other(&key, format!("is required by noise = \"{need}\"")))?;
        Ok(check(&key, v, NOISE_RMS, "")? * k.scale)
    };
    if k.psd.is_some() && k.noise != Some("measured") {
        return Err(other(field(psd_key), "is read only by noise = \"measured\""));
    }
    let background = match k.noise {
        None => None,
        Some("white") => Some(Psd::white(rms("white")?, band)),
        Some("pink") => {
            let key = field("pink_flat_below_hz");
            let flat = k.flat_below.ok_or_else(|| other(&key, "is required by noise = \"pink\""))?;
            let flat = check(&key, flat, Range::open(0.0, band), "Hz")?;
            Some(Psd::pink(rms("pink")?, flat, band))
        }
        Some("measured") => {
            Some(measured_psd(&k.psd_origin.map_or_else(|| field(psd_key), str::to_string), k.psd, k.scale)?)
        }
        Some(other_kind) => {
            return Err(other(
                field("noise"),
                format!("'{other_kind}' is not a background; allowed: \"white\", \"pink\", \"measured\""),
            ))
        }
    };
    let tones = match k.tones {
        None => Vec::new(),
        Some(list) => {
            if list.len() > MAX_POINTS {
                return Err(other(field(tones_key), format!("{} tones; at most {MAX_POINTS}", list.len())));
            }
            let mut out = Vec::with_capacity(list.len());
            for (j, t) in list.iter().enumerate() {
                let f = format!("{}[{j}]", field(tones_key));
                let (hz, r) = pair(&f, t, "[frequency Hz, rms]")?;
                out.push(Tone {
                    frequency_hz: check(&format!("{f}[0] (frequency)"), hz, Range::open(0.0, band), "Hz")?,
                    rms: check(&format!("{f}[1] (rms)"), r, NOISE_RMS, "")? * k.scale,
                });
            }
            out
        }
    };
    Ok(Recording { measurand, range, bits, background, tones })
}

/// A measured PSD's points: 2 to [`MAX_POINTS`], frequencies rising from 0 or above, densities
/// not negative; scaled to SI by `scale`².
fn measured_psd(field: &str, points: Option<&[Vec<f64>]>, scale: f64) -> Result<Psd, Invalid> {
    let points = points.ok_or_else(|| other(field, "is required by noise = \"measured\""))?;
    if !(2..=MAX_POINTS).contains(&points.len()) {
        return Err(other(
            field,
            format!("has {} points; give 2 to {MAX_POINTS} [frequency Hz, density]", points.len()),
        ));
    }
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(points.len());
    for (j, p) in points.iter().enumerate() {
        let f = format!("{field}[{j}]");
        let (hz, s) = pair(&f, p, "[frequency Hz, density]")?;
        let hz = check(&format!("{f}[0] (frequency)"), hz, Range::closed(0.0, 1e7), "Hz")?;
        let s = check(&format!("{f}[1] (density)"), s, Range::closed(0.0, 1e18), "")?;
        if let Some(&(before, _)) = out.last() {
            if hz <= before {
                return Err(other(
                    format!("{f}[0] (frequency)"),
                    format!("{} Hz does not rise above the point before it, {} Hz", compact(hz), compact(before)),
                ));
            }
        }
        out.push((hz, s * scale * scale));
    }
    Ok(Psd::Table { points: out })
}
