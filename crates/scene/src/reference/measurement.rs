//! The reference's sections of `[measurement]`: the chain between the reduced model's signals
//! and the identification's features (`identify::measurement`).

use super::{key, num, whole, Section, NO_UNIT, NUMBER, REQUIRED, STRING, TABLE};
use crate::limits;
use crate::validate::measurement::{
    ADC_BITS, ADC_RANGE, BAND_TOLERANCE, DEFAULT_BAND_TOLERANCE, DEFAULT_SEED, MAX_POINTS, NOISE_RMS, RESONANCE_DAMPING,
};
use analytic::params::{compact, Range};
use identify::measurement::MAX_FILTER_ORDER;

const NOISE: &str = "`\"white\"`, `\"pink\"`, `\"measured\"`";

/// The keys of one recorded quantity, in `unit` (the file's; `psd_unit` its square per Hz).
fn recording(
    title: &'static str,
    about: &str,
    names: [&'static str; 4],
    unit: &'static str,
    psd_unit: &'static str,
) -> Section {
    let [range, rms, psd, tones] = names;
    Section {
        title,
        about: about.into(),
        keys: vec![
            num(
                range,
                unit,
                ADC_RANGE,
                REQUIRED,
                "The ADC's full scale ±R: values beyond clip, and the report counts them",
            ),
            whole("adc_bits", ADC_BITS, REQUIRED, "The ADC's bits b: the step is 2R/2^b"),
            key(
                "noise",
                STRING,
                NO_UNIT,
                NOISE,
                "none: the ADC's step alone",
                "The stationary background's spectrum, as recorded at the ADC's input",
            ),
            num(rms, unit, NOISE_RMS, "required by white and pink", "The background's rms over 0 to rate_hz/2"),
            key(
                "pink_flat_below_hz",
                NUMBER,
                "Hz",
                "(0, rate_hz/2)",
                "required by pink",
                "Pink noise falls as 1/f above this frequency and is flat below it",
            ),
            key(
                psd,
                "list of [f, S]",
                psd_unit,
                format!("2 to {MAX_POINTS} points, frequencies rising from 0 Hz or above, S ≥ 0"),
                "required by measured",
                "A measured one-sided PSD: linear between its points, zero outside them",
            ),
            key(
                "noise_psd_file",
                STRING,
                NO_UNIT,
                format!("a path, relative to the scene file's folder; one point a line, [f, S] as `{psd}`"),
                "none",
                "The measured PSD read from a file (CSV or whitespace; `#` lines and one header skipped), in place of the points inline",
            ),
            key(
                tones,
                "list of [f, rms]",
                unit,
                format!("f in (0, rate_hz/2), rms in {NOISE_RMS}; at most {MAX_POINTS}"),
                "none",
                "Tonal machinery lines, each with a random phase per window",
            ),
        ],
    }
}

/// `[measurement]` and its sub-tables.
pub(super) fn sections() -> Vec<Section> {
    vec![
        Section {
            title: "[measurement]",
            about: "The measurement chain of the identification (\"identify\" only): each recorded channel of the reduced model passes the sensor's band, the anti-aliasing filter, the ADC's sampler, a seeded background and the ADC, and every feature is computed on what comes out. Velocity and deflection are not recorded under a chain; strain gauges are (`[measurement.strain]`). The filters act on the model's samples as their bilinear images, so every filter frequency must lie below 0.45 × `signals.rate_hz`.".into(),
            keys: vec![
                num("rate_hz", "Hz", limits::SAMPLE_RATE_HZ, REQUIRED, "The ADC's sample rate: `signals.rate_hz` divided by a whole number"),
                key("seed", "whole number", NO_UNIT, "0 to 2^63 - 1 (a TOML integer)", DEFAULT_SEED.to_string(), "Seed of the backgrounds (each impact's window its own stream)"),
                num("band_tolerance", NO_UNIT, BAND_TOLERANCE, compact(DEFAULT_BAND_TOLERANCE), "The chain's gain below which a frequency is outside its band: the report checks that the modes the model leaves out lie there"),
                key("sensor", TABLE, NO_UNIT, "see `[measurement.sensor]`", "an ideal sensor", "The sensor's own band"),
                key("anti_alias", TABLE, NO_UNIT, "see `[measurement.anti_alias]`", "none", "The anti-aliasing filter"),
                key("acceleration", TABLE, NO_UNIT, "see `[measurement.acceleration]`", "not recorded", "The accelerometers at every sensor point"),
                key("strain", TABLE, NO_UNIT, "see `[measurement.strain]`", "not recorded", "The strain gauges at every sensor point"),
                key("support_force", TABLE, NO_UNIT, "see `[measurement.support_force]`", "not recorded", "The force at every spring or held corner (the props' and jacks' transducers)"),
            ],
        },
        Section {
            title: "[measurement.sensor]",
            about: "Give both resonance keys or neither.".into(),
            keys: vec![
                key("resonance_hz", NUMBER, "Hz", "(0, 0.45 × signals.rate_hz)", "none", "The mounted resonance f_r: ω_r²/(s² + 2ζω_r s + ω_r²)"),
                num("resonance_damping", NO_UNIT, RESONANCE_DAMPING, "none", "Its damping ratio ζ (a peak of 1/(2ζ) at f_r)"),
                key("high_pass_hz", NUMBER, "Hz", "(0, 0.45 × signals.rate_hz)", "none", "The AC coupling's corner: s/(s + ω_h)"),
            ],
        },
        Section {
            title: "[measurement.anti_alias]",
            about: "A Butterworth low-pass.".into(),
            keys: vec![
                whole("order", Range::closed(1.0, MAX_FILTER_ORDER as f64), REQUIRED, "Its order n: the gain falls as (f_c/f)^n"),
                key("corner_hz", NUMBER, "Hz", "(0, rate_hz/2) and below 0.45 × signals.rate_hz", REQUIRED, "Its -3 dB corner f_c"),
            ],
        },
        recording(
            "[measurement.acceleration]",
            "How the accelerations are recorded, in m/s².",
            ["adc_range_m_s2", "noise_rms_m_s2", "noise_psd_m2_s4_per_hz", "tones_m_s2"],
            "m/s²",
            "(m/s²)²/Hz",
        ),
        recording(
            "[measurement.strain]",
            "How the strain gauges are recorded (one at every sensor point, along x on the face away from the impact: ε_x = -(h/2) ∂²w/∂x²), in microstrain.",
            ["adc_range_microstrain", "noise_rms_microstrain", "noise_psd_microstrain2_per_hz", "tones_microstrain"],
            "µε",
            "µε²/Hz",
        ),
        recording(
            "[measurement.support_force]",
            "How the props' and jacks' forces (and held corners' reactions) are recorded, in kN.",
            ["adc_range_kn", "noise_rms_kn", "noise_psd_kn2_per_hz", "tones_kn"],
            "kN",
            "kN²/Hz",
        ),
    ]
}
