//! The page's measurement-chain section: the chain as the scene states it, each support set's
//! SNR, clipping and band check, and the background sweep.

use crate::present::table::{sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use identify::measurement::noise::Psd;
use identify::measurement::{ChainSpec, Measurand, Recording};
use scene::Scene;
use studies::identify::baselines::oriented;
use studies::identify::measured::SWEEP_SNR_DB;
use studies::identify::{ConditionResult, Ranked, Summary};

const MEASUREMENT: &str = include_str!("../templates/identify/measurement.md");
const SWEEP_TEXT: &str = include_str!("../templates/identify/measurement-sweep.md");
const NONE: &str = include_str!("../templates/identify/measurement-none.md");

/// A level in dB to a tenth (a ratio's third digit), with no negative zero.
fn db(v: f64) -> String {
    let s = format!("{v:.1}");
    if s == "-0.0" {
        "0.0".into()
    } else {
        s
    }
}

/// What each impact records, in words.
pub(super) fn recorded(scene: &Scene) -> String {
    match &scene.measurement {
        None => "displacement, velocity and acceleration at every sensor point, and the force at every spring or fixed corner".into(),
        Some(c) => c
            .recordings
            .iter()
            .map(|r| match r.measurand {
                Measurand::SupportForce => "the force at every spring or fixed corner".to_string(),
                Measurand::Strain => "the bending strain along x on the unstruck face at every sensor point".to_string(),
                m => format!("the {} at every sensor point", m.key()),
            })
            .collect::<Vec<_>>()
            .join(" and "),
    }
}

/// The sensor's band in words.
fn sensor(c: &ChainSpec) -> String {
    let mut parts = Vec::new();
    if let Some((f, z)) = c.sensor.resonance {
        parts.push(format!("a mounted resonance at {} Hz (damping ratio {})", sig(f, 3), sig(z, 3)));
    }
    if let Some(f) = c.sensor.high_pass_hz {
        parts.push(format!("an AC coupling of corner {} Hz (first-order high-pass)", sig(f, 3)));
    }
    if parts.is_empty() {
        "an ideal sensor (no resonance, no AC coupling)".into()
    } else {
        format!("the sensor's band: {}", parts.join(" and "))
    }
}

/// A measurand's unit as the page writes it after a number (none for a strain).
fn shown_unit(m: Measurand) -> &'static str {
    match m.unit() {
        "1" => "",
        u => u,
    }
}

/// One recording's ADC and background in words.
fn recording(r: &Recording, rate_hz: f64) -> String {
    let unit = shown_unit(r.measurand);
    let rms = |p: &Psd| sig(p.power(rate_hz / 2.0).sqrt(), 3);
    let background = match &r.background {
        None => "no stationary background".to_string(),
        Some(p @ Psd::White { .. }) => format!("white noise of rms {} {unit}", rms(p)),
        Some(p @ Psd::Pink { f_low, .. }) => {
            format!("pink noise (1/f, flat below {} Hz) of rms {} {unit}", sig(*f_low, 3), rms(p))
        }
        Some(p @ Psd::Table { points }) => format!(
            "a measured PSD of {} points, rms {} {unit} over 0 to {} Hz",
            points.len(),
            rms(p),
            sig(rate_hz / 2.0, 3)
        ),
    };
    let tones = if r.tones.is_empty() {
        String::new()
    } else {
        let list: Vec<String> =
            r.tones.iter().map(|t| format!("{} Hz at {} {unit} rms", sig(t.frequency_hz, 3), sig(t.rms, 3))).collect();
        format!(" plus tonal lines at {}", list.join(", "))
    };
    format!(
        "{}: {background}{tones}, an ADC of ±{} {unit} and {} bits (step {} {unit})",
        r.measurand.key(),
        sig(r.range, 3),
        r.bits,
        sig(r.step(), 3)
    )
}

/// Each support set's SNR, clipping and band check.
fn table(summary: &Summary) -> Table {
    let mut t = Table::new(
        "",
        &[
            "support set",
            "quantity",
            "σ",
            "channels (silent)",
            "SNR over channels, dB (min / median / max)",
            "SNR of the best feature's channel, dB",
            "samples clipped",
            "highest mode (Hz)",
            "chain's gain above it",
            "truncation outside the band",
            "chain's gain above the model's Nyquist",
            "chain's gain above the ADC's Nyquist (what folds at the ADC)",
            "realised chain against the analog: largest gain deviation in the ADC's band, over the passband gain",
        ],
    );
    for c in &summary.conditions {
        let Some(m) = &c.measurement else { continue };
        for (k, q) in m.snr.iter().enumerate() {
            // The support set's own columns once, on its first row.
            let best = if k == 0 { m.best_channel_snr_db.map_or_else(|| "-".into(), db) } else { String::new() };
            t.push(vec![
                c.condition.clone().into(),
                q.quantity.into(),
                Cell::Text(
                    format!("{} {}", sig(q.noise_rms, 3), if q.unit == "1" { "" } else { q.unit })
                        .trim_end()
                        .to_string(),
                ),
                Cell::Text(format!("{} ({})", q.channels, q.silent)),
                Cell::Text(
                    q.snr_db.map_or_else(|| "-".into(), |(a, b, c)| format!("{} / {} / {}", db(a), db(b), db(c))),
                ),
                Cell::Text(best),
                Cell::Text(sig(m.clipped_share, 2)),
                Cell::Text(sig(m.highest_mode_hz, 4)),
                Cell::Text(sig(m.gain_above_highest_mode, 2)),
                Cell::Text(if m.truncation_outside_band { "yes".into() } else { "no: raise signals.modes".into() }),
                Cell::Text(sig(m.gain_above_model_nyquist, 2)),
                Cell::Text(sig(m.gain_above_adc_nyquist, 2)),
                Cell::Text(sig(m.realisation_error, 2)),
            ]);
        }
    }
    t
}

/// A ranked feature as "separation (interval), feature of channel".
fn scored(r: &Ranked) -> String {
    let (s, (lo, hi)) = oriented(r.auc.auc, r.interval);
    format!("{} ({}-{}): {} of the {}", sig(s, 3), sig(lo, 3), sig(hi, 3), r.feature.name(), r.channel)
}

/// The sweep's table over all support sets.
fn sweep(summary: &Summary) -> Result<String, Failure> {
    let mut t = Table::new(
        "",
        &["support set", "background × stated", "SNR of the tracked channel (dB)", "tracked feature", "best feature"],
    );
    for c in &summary.conditions {
        let Some(m) = &c.measurement else { continue };
        for p in &m.sweep {
            t.push(vec![
                c.condition.clone().into(),
                Cell::Text(sig(p.scale, 3)),
                Cell::Text(p.snr_db.map_or_else(|| "-".into(), db)),
                Cell::Text(scored(&p.tracked)),
                Cell::Text(scored(&p.best)),
            ]);
        }
    }
    if t.rows.is_empty() {
        return Ok(String::new());
    }
    Ok(render(
        "identify/measurement-sweep.md",
        SWEEP_TEXT,
        &[
            ("levels", SWEEP_SNR_DB.iter().map(|v| analytic::params::compact(*v)).collect::<Vec<_>>().join(", ")),
            ("table", t.to_markdown()),
        ],
    )?)
}

/// The section: the chain, or a statement that there is none.
pub(super) fn section(scene: &Scene, summary: &Summary) -> Result<String, Failure> {
    let Some(c) = &scene.measurement else { return Ok(NONE.to_string()) };
    let decimation = summary.conditions.iter().find_map(|r| r.measurement.as_ref()).map_or(1, |m| m.decimation);
    let anti_alias = match c.anti_alias {
        None => "no anti-aliasing filter".to_string(),
        Some(a) => {
            format!("an anti-aliasing Butterworth low-pass of order {} and corner {} Hz", a.order, sig(a.corner_hz, 3))
        }
    };
    let recordings: Vec<String> = c.recordings.iter().map(|r| recording(r, c.rate_hz)).collect();
    Ok(render(
        "identify/measurement.md",
        MEASUREMENT,
        &[
            ("model_rate_hz", sig(summary.signals.rate_hz, 3)),
            ("sensor", sensor(c)),
            ("anti_alias", anti_alias),
            ("decimation", decimation.to_string()),
            ("rate_hz", sig(c.rate_hz, 3)),
            ("recordings", recordings.join("; ")),
            ("seed", c.seed.to_string()),
            ("tolerance", sig(c.band_tolerance, 2)),
            ("table", table(summary).to_markdown()),
            ("sweep", sweep(summary)?),
        ],
    )?)
}

/// The signals a support set's features read, for a table cell: "noise-free" or the SNR of
/// the best feature's channel.
pub(super) fn signals_cell(r: &ConditionResult) -> String {
    match &r.measurement {
        None => "noise-free".into(),
        Some(m) => m.best_channel_snr_db.map_or_else(|| "measured".into(), |v| format!("measured, {} dB SNR", db(v))),
    }
}

/// The finding's sentence on the noise a support set's features ran at.
pub(super) fn finding_noise(r: &ConditionResult) -> String {
    match &r.measurement {
        None => " The signals are the model's, free of noise.".into(),
        Some(m) => {
            let snr = m.best_channel_snr_db.map_or_else(|| "-".into(), db);
            let band = if m.truncation_outside_band {
                ""
            } else {
                " The model's truncation lies inside the chain's band (raise signals.modes)."
            };
            format!(" Measured through the chain: the best feature's channel at an SNR of {snr} dB, {} of the samples clipped.{band}", sig(m.clipped_share, 2))
        }
    }
}
