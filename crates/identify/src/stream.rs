//! A continuous caving stream: lumps reaching the support one after another, as a mine sees
//! them, instead of one isolated impact per window.
//!
//! Arrivals form a homogeneous Poisson process of rate λ (Cox & Isham, *Point Processes*,
//! 1980, ch. 2): the gaps between lumps are independent exponentials of mean 1/λ. Each lump
//! carries a class mark drawn at its arrival time t from the gangue share p(t) of a
//! [`Profile`] (coal, then a transition, then gangue-rich: the draw of a caving cycle), so the
//! coal and gangue arrivals are two independent Poisson processes of rates λ(1 - p(t)) and
//! λ p(t) (marking theorem, Kingman, *Poisson Processes*, 1993, section 5.2). Within its class
//! a lump's family is chosen in proportion to the families' counts, and its point, size, speed
//! and material are drawn as an ensemble's impact is ([`Ensemble::draw_of`]), from its own
//! stream: lump k's variables depend only on the ensemble's seed mixed with the stream's
//! ([`lump_seed`]), k and its family, so two streams of different seeds share no lump.

use crate::ensemble::{impact_stream, open_uniform, Class, Draw, Ensemble, Held};
use serde::Serialize;

/// The gangue share p(t) of a stream: `before` until `onset`, then linear to `after` over
/// `ramp` seconds, then `after`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Profile {
    /// Share of gangue before the onset, in [0, 1].
    pub before: f64,
    /// Share of gangue after the transition, in [0, 1].
    pub after: f64,
    /// When the transition starts, s.
    pub onset: f64,
    /// How long it takes, s (0: a step).
    pub ramp: f64,
}

impl Profile {
    /// p(t).
    pub fn share(&self, t: f64) -> f64 {
        if t < self.onset {
            self.before
        } else if self.ramp <= 0.0 || t >= self.onset + self.ramp {
            self.after
        } else {
            self.before + (self.after - self.before) * (t - self.onset) / self.ramp
        }
    }

    /// The mean of p over the window [t₀, t₁): the expected gangue share of its lumps, the
    /// truth a window's detector is scored against.
    pub fn mean_share(&self, t0: f64, t1: f64) -> f64 {
        // p is piecewise linear with breaks at the onset and the ramp's end: Simpson's rule on
        // each piece is exact.
        let mut cuts = vec![t0];
        for b in [self.onset, self.onset + self.ramp] {
            if b > t0 && b < t1 {
                cuts.push(b);
            }
        }
        cuts.push(t1);
        let mut total = 0.0;
        for w in cuts.windows(2) {
            let (a, b) = (w[0], w[1]);
            total += (b - a) * (self.share(a) + 4.0 * self.share(0.5 * (a + b)) + self.share(b)) / 6.0;
        }
        if t1 > t0 {
            total / (t1 - t0)
        } else {
            self.share(t0)
        }
    }
}

/// A stream: its arrival rate, length, gangue profile and seed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StreamSpec {
    /// λ, lumps per second.
    pub rate_per_s: f64,
    /// Length of the stream, s.
    pub duration: f64,
    /// The gangue share over time.
    pub profile: Profile,
    /// The seed of the arrivals and their class marks (stream [`ARRIVALS`] of it); lump k's
    /// variables come from the ensemble's own seed, on stream k.
    pub seed: u64,
}

/// A caving-stream detection study: independent streams of one spec (stream r drawn with
/// the seed `spec.seed + r`), the windows its detector reads, and the sweeps.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StreamStudy {
    /// The stream: arrival rate, length, gangue profile, seed.
    pub spec: StreamSpec,
    /// Independent streams.
    pub streams: usize,
    /// Window length W, s.
    pub window: f64,
    /// Window hop H, s.
    pub hop: f64,
    /// Time blocks of the cross-validation.
    pub blocks: usize,
    /// The out-of-fold probability at which the detector raises an alarm.
    pub alarm_probability: f64,
    /// Further arrival rates, lumps per second, each run as a whole study.
    pub rate_sweep: Vec<f64>,
    /// Scales of the chain's background, each run on the same streams (empty without a chain).
    pub noise_sweep: Vec<f64>,
    /// Scales of every family's radius law (that of R·scale, [`crate::distribution::Distribution::scaled`]),
    /// each run on streams of its own: the same lumps, each that many times as large, for the
    /// detector carried to them. Left out of the serialised scene when empty, so that a scene without
    /// it keeps its provenance hash.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub size_sweep: Vec<f64>,
    /// How every stream is cut in time to run in segments (None: each stream in one piece).
    /// Left out of the serialised scene when None, so that a scene without it keeps its
    /// provenance hash.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub segments: Option<Segmenting>,
    /// The window-level sensor design (None: none). Left out of the serialised scene when
    /// None.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub design: Option<StreamDesign>,
    /// Whether to write the first stream's continuous signals.
    pub write_signal: bool,
    /// The file they are written as. Left out of the serialised scene as CSV, so that a
    /// scene without it keeps its provenance hash.
    #[serde(skip_serializing_if = "SignalFormat::is_csv")]
    pub signal_format: SignalFormat,
}

/// How a stream is cut in time: segments of one length, each run and recorded alone from
/// rest after a warm-up long enough for the past the warm-up leaves out to have decayed to a
/// tolerance (`coupled::reduced::stream::span`, [`crate::measurement::segments`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Segmenting {
    /// A segment's length, s.
    pub length: f64,
    /// ε: the share of the state at a warm-up's start left by its end.
    pub tolerance: f64,
}

/// A window-level sensor design: `sensors` sensors recording `measurand`, chosen one at a
/// time among the candidate points of the ensemble's placement grid, each set scored by the
/// window AUC of its detector on the study's streams and folds ([`crate::design::forward_selection`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StreamDesign {
    /// The budget of sensors.
    pub sensors: usize,
    /// What each records (a plate quantity at a point, not a support's force).
    pub measurand: crate::measurement::Measurand,
}

/// The file a recorded signal is written as, beside its JSON sidecar
/// ([`crate::recording`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SignalFormat {
    /// `signal.csv`: text, one line a sample.
    #[default]
    Csv,
    /// `signal.parquet`: columns of doubles ([`crate::recording::parquet`]), for long streams.
    Parquet,
}

impl SignalFormat {
    /// Whether this is [`SignalFormat::Csv`].
    pub fn is_csv(&self) -> bool {
        *self == SignalFormat::Csv
    }

    /// The data file's name.
    pub fn file_name(&self) -> &'static str {
        match self {
            SignalFormat::Csv => "signal.csv",
            SignalFormat::Parquet => "signal.parquet",
        }
    }
}

/// The stream number of the arrival process (far above any lump's number).
pub const ARRIVALS: usize = usize::MAX;

/// One lump of a stream.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Lump {
    /// Its arrival (first touch), s from the stream's start.
    pub time: f64,
    /// Its variables; `draw.index` is its number in the stream.
    pub draw: Draw,
}

/// Why a stream cannot be drawn.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StreamError {
    /// A rate, duration, time or share outside its range.
    #[error("{field} = {value} is outside {allowed}")]
    Range {
        /// What.
        field: &'static str,
        /// Its value.
        value: f64,
        /// Its allowed range.
        allowed: &'static str,
    },
    /// The ensemble has no family of a class the profile asks for.
    #[error("the gangue share reaches {share} but the ensemble has no {class} family")]
    MissingClass {
        /// The class.
        class: &'static str,
        /// The share that needs it.
        share: f64,
    },
}

/// The lumps of `spec` with the families, region and speeds of `ensemble`, in arrival order.
pub fn lumps(ensemble: &Ensemble, spec: &StreamSpec) -> Result<Vec<Lump>, StreamError> {
    check(spec)?;
    let weights = |class: Class| -> Vec<(usize, f64)> {
        ensemble
            .families
            .iter()
            .enumerate()
            .filter(|(_, f)| f.class == class)
            .map(|(i, f)| (i, f.count as f64))
            .collect()
    };
    let (coal, gangue) = (weights(Class::Coal), weights(Class::Gangue));
    let p = spec.profile;
    if (p.before < 1.0 || p.after < 1.0) && coal.is_empty() {
        return Err(StreamError::MissingClass { class: "coal", share: p.before.min(p.after) });
    }
    if (p.before > 0.0 || p.after > 0.0) && gangue.is_empty() {
        return Err(StreamError::MissingClass { class: "gangue", share: p.before.max(p.after) });
    }
    let lumps_of = Ensemble { seed: lump_seed(ensemble.seed, spec.seed), ..ensemble.clone() };
    let mut rng = impact_stream(spec.seed, ARRIVALS);
    let mut out = Vec::new();
    let mut t = 0.0;
    loop {
        // Exponential gap by inversion: -ln(U)/λ with U in (0, 1).
        t += -open_uniform(&mut rng).ln() / spec.rate_per_s;
        if t >= spec.duration {
            return Ok(out);
        }
        let is_gangue = open_uniform(&mut rng) < p.share(t);
        let family = pick(if is_gangue { &gangue } else { &coal }, open_uniform(&mut rng));
        let draw = lumps_of.draw_of(out.len(), family, Held::NONE);
        out.push(Lump { time: t, draw });
    }
}

/// The seed of a stream's lumps: the ensemble's seed mixed with the stream's (by the golden
/// ratio's odd multiplier, so that neighbouring stream seeds give unrelated lump seeds).
pub fn lump_seed(ensemble_seed: u64, stream_seed: u64) -> u64 {
    ensemble_seed ^ stream_seed.wrapping_add(1).wrapping_mul(0x9e37_79b9_7f4a_7c15)
}

/// Every number of `spec` in its range: a positive finite rate and duration whose expected
/// count λT is at most [`MAX_EXPECTED_LUMPS`], finite times, shares in [0, 1].
fn check(spec: &StreamSpec) -> Result<(), StreamError> {
    let p = spec.profile;
    let positive = |field, value: f64| {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(StreamError::Range { field, value, allowed: "(0, ∞)" })
        }
    };
    positive("rate_per_s", spec.rate_per_s)?;
    positive("duration", spec.duration)?;
    let count = spec.rate_per_s * spec.duration;
    if count > MAX_EXPECTED_LUMPS {
        return Err(StreamError::Range { field: "rate_per_s × duration", value: count, allowed: "[0, 1e7] lumps" });
    }
    for (field, value) in [("profile.before", p.before), ("profile.after", p.after)] {
        if !(0.0..=1.0).contains(&value) {
            return Err(StreamError::Range { field, value, allowed: "[0, 1]" });
        }
    }
    for (field, value) in [("profile.onset", p.onset), ("profile.ramp", p.ramp)] {
        if !value.is_finite() || value < 0.0 {
            return Err(StreamError::Range { field, value, allowed: "[0, ∞)" });
        }
    }
    Ok(())
}

/// The most lumps a stream may expect (λT): ten million, a day at over 100 a second.
pub const MAX_EXPECTED_LUMPS: f64 = 1e7;

/// The family whose cumulative weight first exceeds `u` × the total.
fn pick(weights: &[(usize, f64)], u: f64) -> usize {
    let total: f64 = weights.iter().map(|w| w.1).sum();
    let mut acc = 0.0;
    for &(i, w) in weights {
        acc += w;
        if u * total < acc {
            return i;
        }
    }
    weights.last().map_or(0, |w| w.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distribution::Distribution;
    use crate::ensemble::{Family, Region, Speed};

    fn ensemble() -> Ensemble {
        let family = |name: &str, class, count, density: f64| Family {
            name: name.into(),
            class,
            count,
            density: Distribution::Fixed { value: density },
            youngs_modulus: Distribution::Fixed { value: 2.26e9 },
            poisson_ratio: Distribution::Fixed { value: 0.28 },
            cohesion: Distribution::Fixed { value: 8.39e6 },
            friction_angle_deg: Distribution::Fixed { value: 25.0 },
            radius: Distribution::Uniform { min: 0.01, max: 0.05 },
        };
        Ensemble {
            region: Region { x: (0.0, 0.4584), z: (0.0, 0.36) },
            speed: Speed::Velocity(Distribution::Uniform { min: 1.0, max: 5.0 }),
            families: vec![
                family("coal", Class::Coal, 10, 1380.0),
                family("mudstone", Class::Gangue, 30, 2400.0),
                family("sandstone", Class::Gangue, 10, 2600.0),
            ],
            seed: 1,
        }
    }

    /// Over T = 2000 s at λ = 5/s the count is Poisson with mean λT = 10,000 (within 4√λT),
    /// the gaps' mean is 1/λ (within 4 standard errors, (1/λ)/√n), and the share of gaps
    /// above 1/λ is e⁻¹ (within 4 binomial standard errors).
    #[test]
    fn arrivals_are_poisson() {
        let spec = StreamSpec {
            rate_per_s: 5.0,
            duration: 2000.0,
            profile: Profile { before: 0.5, after: 0.5, onset: 0.0, ramp: 0.0 },
            seed: 9,
        };
        let l = lumps(&ensemble(), &spec).unwrap();
        let n = l.len() as f64;
        assert!((n - 1e4).abs() < 4.0 * 100.0, "{n}");
        let gaps: Vec<f64> = l.windows(2).map(|w| w[1].time - w[0].time).collect();
        let mean = gaps.iter().sum::<f64>() / gaps.len() as f64;
        assert!((mean - 0.2).abs() < 4.0 * 0.2 / n.sqrt(), "{mean}");
        let long = gaps.iter().filter(|g| **g > 0.2).count() as f64 / gaps.len() as f64;
        let e1 = (-1f64).exp();
        assert!((long - e1).abs() < 4.0 * (e1 * (1.0 - e1) / n).sqrt(), "{long}");
        assert!(l.windows(2).all(|w| w[0].time < w[1].time) && l.iter().enumerate().all(|(k, x)| x.draw.index == k));
    }

    /// The gangue share follows the profile: before the onset, over the ramp and after it,
    /// each bin's observed share lies within 4 binomial standard errors of its mean p; and the
    /// gangue families share their class 3 : 1 as their counts do.
    #[test]
    fn classes_follow_the_profile_and_families_their_counts() {
        let profile = Profile { before: 0.1, after: 0.8, onset: 600.0, ramp: 600.0 };
        let spec = StreamSpec { rate_per_s: 10.0, duration: 1800.0, profile, seed: 4 };
        let l = lumps(&ensemble(), &spec).unwrap();
        for (t0, t1) in [(0.0, 600.0), (600.0, 900.0), (900.0, 1200.0), (1200.0, 1800.0)] {
            let bin: Vec<&Lump> = l.iter().filter(|x| x.time >= t0 && x.time < t1).collect();
            let share = bin.iter().filter(|x| x.draw.class == Class::Gangue).count() as f64 / bin.len() as f64;
            let p = profile.mean_share(t0, t1);
            let se = (p * (1.0 - p) / bin.len() as f64).sqrt();
            assert!((share - p).abs() < 4.0 * se, "[{t0}, {t1}): {share} against {p}");
        }
        let gangue: Vec<&Lump> = l.iter().filter(|x| x.draw.class == Class::Gangue).collect();
        let mud = gangue.iter().filter(|x| x.draw.family == 1).count() as f64 / gangue.len() as f64;
        assert!((mud - 0.75).abs() < 4.0 * (0.75 * 0.25 / gangue.len() as f64).sqrt(), "{mud}");
    }

    /// A lump's variables are an ensemble impact's of the same number and family, drawn with
    /// the stream's lump seed; two streams share no lump.
    #[test]
    fn a_lump_is_drawn_as_an_impact() {
        let e = ensemble();
        let spec = StreamSpec {
            rate_per_s: 2.0,
            duration: 10.0,
            profile: Profile { before: 0.0, after: 1.0, onset: 5.0, ramp: 0.0 },
            seed: 2,
        };
        let seeded = Ensemble { seed: lump_seed(e.seed, spec.seed), ..e.clone() };
        let first = lumps(&e, &spec).unwrap();
        for lump in &first {
            assert_eq!(lump.draw, seeded.draw_of(lump.draw.index, lump.draw.family, Held::NONE));
            assert_eq!(lump.draw.class == Class::Gangue, lump.time >= 5.0);
        }
        let other = lumps(&e, &StreamSpec { seed: 3, ..spec }).unwrap();
        for a in &first {
            assert!(other
                .iter()
                .all(|b| (a.draw.x, a.draw.z, a.draw.velocity) != (b.draw.x, b.draw.z, b.draw.velocity)));
        }
        let coal_only = Ensemble { families: vec![e.families[0].clone()], ..e.clone() };
        assert!(matches!(lumps(&coal_only, &spec), Err(StreamError::MissingClass { class: "gangue", .. })));
        for bad in [
            StreamSpec { rate_per_s: 0.0, ..spec },
            StreamSpec { duration: f64::NAN, ..spec },
            StreamSpec { rate_per_s: 1e9, duration: 1e9, ..spec },
            StreamSpec { profile: Profile { after: 1.5, ..spec.profile }, ..spec },
            StreamSpec { profile: Profile { ramp: -1.0, ..spec.profile }, ..spec },
        ] {
            assert!(matches!(lumps(&e, &bad), Err(StreamError::Range { .. })), "{bad:?}");
        }
    }

    /// The mean share of a window is the integral of p over it: 0.1 + 0.7 × (fraction of the
    /// ramp's mean within the window) by hand for a window straddling the onset.
    #[test]
    fn mean_share_integrates_the_profile() {
        let p = Profile { before: 0.1, after: 0.8, onset: 10.0, ramp: 10.0 };
        // Over [5, 15): 5 s at 0.1, then 5 s rising from 0.1 to 0.45 (mean 0.275).
        assert!((p.mean_share(5.0, 15.0) - (0.1 * 5.0 + 0.275 * 5.0) / 10.0).abs() < 1e-15);
        assert_eq!(p.mean_share(25.0, 30.0), 0.8);
    }
}
