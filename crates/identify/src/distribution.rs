//! Probability distributions of one impact variable, sampled by inverse transform.
//!
//! Every draw is x = F⁻¹(u) with u uniform on (0, 1): one uniform per variable and impact,
//! so a variable can be held at its median, F⁻¹(½), without changing the draws of the
//! others (common random numbers: a run with the position held and a run with it free see
//! the same sizes, velocities and materials). Continuous distributions are truncated to
//! [min, max]: F⁻¹ of the truncated law is F⁻¹(F(min) + u (F(max) - F(min))), exact and
//! without rejection, and the bounds keep every draw inside the physical range the scene
//! allows (a normal density is never negative, a lognormal radius never 10 m).
//!
//! Which law for what (the scene chooses; see the example scenes for the sources):
//! - Rosin-Rammler (Weibull), F(x) = 1 - exp(-(x/x₆₃)ⁿ): the classical law of broken rock
//!   and coal fragment sizes (Rosin & Rammler 1933; the Kuz-Ram fragmentation model,
//!   Cunningham 1983); x₆₃ is the size 63.2 % of the material is finer than.
//! - Lognormal: the other law fitted to fragment sizes and to the caving groups' ensembles
//!   (design.md section 7), and to rock moduli, which spread over a factor rather than a sum.
//! - Normal: densities, Poisson ratios, friction angles, which spread by a few percent.
//! - Uniform: a range with nothing known inside it (fall heights between the tail beam and
//!   the lowest and highest caving top coal).
//! - Choice: a few values with equal weight (the paper's two velocities).

use analytic::params::{check, compact, Range};
use analytic::InvalidParameter;
use serde::Serialize;

/// A distribution of one real variable.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "distribution", rename_all = "kebab-case")]
pub enum Distribution {
    /// Always `value`.
    Fixed {
        /// The value.
        value: f64,
    },
    /// Uniform on [min, max].
    Uniform {
        /// Lower end.
        min: f64,
        /// Upper end.
        max: f64,
    },
    /// Normal N(mean, sd²) truncated to [min, max].
    Normal {
        /// Mean of the untruncated law.
        mean: f64,
        /// Standard deviation of the untruncated law.
        sd: f64,
        /// Lower truncation bound.
        min: f64,
        /// Upper truncation bound.
        max: f64,
    },
    /// Lognormal: ln x ~ N(ln median, sigma_log²), truncated to [min, max].
    LogNormal {
        /// Median of the untruncated law.
        median: f64,
        /// Standard deviation of ln x.
        sigma_log: f64,
        /// Lower truncation bound.
        min: f64,
        /// Upper truncation bound.
        max: f64,
    },
    /// Rosin-Rammler (Weibull) F(x) = 1 - exp(-(x/scale)^shape), truncated to [min, max].
    RosinRammler {
        /// x₆₃, the value below which 1 - 1/e = 63.2 % of the untruncated law lies.
        scale: f64,
        /// Uniformity index n (the Weibull shape).
        shape: f64,
        /// Lower truncation bound.
        min: f64,
        /// Upper truncation bound.
        max: f64,
    },
    /// One of `values`, each with probability 1/len.
    Choice {
        /// The values, at least one.
        values: Vec<f64>,
    },
}

/// A distribution whose parameters do not fit together.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InvalidDistribution {
    /// A parameter outside its range; its name is the parameter's (`min`, `values[2]`).
    #[error(transparent)]
    Range(#[from] InvalidParameter),
    /// Parameters that contradict each other.
    #[error("{parameter}: {message}")]
    Inconsistent {
        /// The parameter named in the message.
        parameter: &'static str,
        /// What is wrong.
        message: String,
    },
}

/// Smallest spread or location (sd, median, scale) of a law, as a fraction of its bounds'
/// magnitude max(|min|, |max|): a spread of 1e-12 of the value is still far above double
/// precision's 2e-16, so the law draws distinct values, and it stays a normal number through
/// any change of unit the scene makes (mm to m, GPa to Pa).
pub const RELATIVE_FLOOR: f64 = 1e-12;

/// Largest number of values of a [`Distribution::Choice`].
pub const MAX_CHOICES: usize = 1000;

impl Distribution {
    /// Checks the parameters against `allowed` (the range of the variable, in the caller's
    /// units) and against each other; returns the distribution unchanged if they pass.
    /// Location parameters (mean, median, scale) need not lie in `allowed`, only the bounds
    /// and the fixed or chosen values, because the bounds confine every draw. The law must
    /// also put some probability between its bounds (a normal truncated 40 standard
    /// deviations out has none in double precision).
    pub fn checked(self, allowed: Range, unit: &'static str) -> Result<Self, InvalidDistribution> {
        let bounds = |min: f64, max: f64| -> Result<(), InvalidDistribution> {
            check("min", min, allowed, unit)?;
            check("max", max, allowed, unit)?;
            if min > max {
                return Err(InvalidDistribution::Inconsistent {
                    parameter: "max",
                    message: format!("max = {} is below min = {}; give min ≤ max", compact(max), compact(min)),
                });
            }
            Ok(())
        };
        // A spread or location parameter below this fraction of the bounds' magnitude makes
        // no law double precision can draw from: (min - mean)/sd overflows, and after a change
        // of unit (mm to m) a denormal sd or scale becomes 0 and the quantile NaN.
        let floor = |min: f64, max: f64| match RELATIVE_FLOOR * min.abs().max(max.abs()) {
            f if f > 0.0 => Range::closed(f, f64::MAX),
            _ => Range::open(0.0, f64::MAX),
        };
        if let Some((min, max)) = self.continuous_bounds() {
            bounds(min, max)?;
            // Bounds that meet leave one value: a point law, whatever the other parameters say.
            if min == max {
                return Ok(Distribution::Fixed { value: min });
            }
        }
        match &self {
            Distribution::Fixed { value } => {
                check("value", *value, allowed, unit)?;
            }
            Distribution::Uniform { min, max } => bounds(*min, *max)?,
            Distribution::Normal { mean, sd, min, max } => {
                check("mean", *mean, Range::open(-f64::MAX, f64::MAX), unit)?;
                bounds(*min, *max)?;
                check("sd", *sd, floor(*min, *max), unit)?;
            }
            Distribution::LogNormal { median, sigma_log, min, max } => {
                check("sigma_log", *sigma_log, Range::closed(1e-6, 10.0), "")?;
                bounds(*min, *max)?;
                check("median", *median, floor(*min, *max), unit)?;
                if *min <= 0.0 {
                    return Err(InvalidDistribution::Inconsistent {
                        parameter: "min",
                        message: format!("min = {} is not positive; a lognormal lives on (0, inf)", compact(*min)),
                    });
                }
            }
            Distribution::RosinRammler { scale, shape, min, max } => {
                check("shape", *shape, Range::closed(0.1, 100.0), "")?;
                bounds(*min, *max)?;
                check("scale", *scale, floor(*min, *max), unit)?;
                if *min < 0.0 {
                    return Err(InvalidDistribution::Inconsistent {
                        parameter: "min",
                        message: format!("min = {} is negative; a Rosin-Rammler law lives on [0, inf)", compact(*min)),
                    });
                }
            }
            Distribution::Choice { values } => {
                if values.is_empty() || values.len() > MAX_CHOICES {
                    return Err(InvalidDistribution::Inconsistent {
                        parameter: "values",
                        message: format!("{} values; give 1 to {MAX_CHOICES}", values.len()),
                    });
                }
                for (j, v) in values.iter().enumerate() {
                    check(&format!("values[{j}]"), *v, allowed, unit)?;
                }
            }
        }
        if let Some(mass) = self.mass_within_bounds() {
            if mass <= 0.0 && self.bounds().is_some_and(|(a, b)| a < b) {
                return Err(InvalidDistribution::Inconsistent {
                    parameter: "min",
                    message: "the law has no probability between min and max (they lie too far in one tail); move them toward the median".into(),
                });
            }
        }
        Ok(self)
    }

    /// The truncation bounds of the laws that have them.
    fn continuous_bounds(&self) -> Option<(f64, f64)> {
        match self {
            Distribution::Normal { min, max, .. }
            | Distribution::LogNormal { min, max, .. }
            | Distribution::RosinRammler { min, max, .. } => Some((*min, *max)),
            _ => None,
        }
    }

    /// Whether every parameter is finite, every spread and location a positive normal number
    /// and the quantile finite inside the bounds: a law checked in one unit may not survive
    /// its conversion to SI (a denormal scale in mm is 0 in m).
    pub fn is_drawable(&self) -> bool {
        let normal = |v: f64| v.is_normal() && v > 0.0;
        let params_ok = match *self {
            Distribution::Fixed { value } => value.is_finite(),
            Distribution::Uniform { min, max } => min.is_finite() && max.is_finite(),
            Distribution::Normal { mean, sd, min, max } => {
                mean.is_finite() && normal(sd) && min.is_finite() && max.is_finite()
            }
            Distribution::LogNormal { median, sigma_log, min, max } => {
                normal(median) && normal(sigma_log) && normal(min) && max.is_finite()
            }
            Distribution::RosinRammler { scale, shape, min, max } => {
                normal(scale) && normal(shape) && min.is_finite() && max.is_finite()
            }
            Distribution::Choice { ref values } => !values.is_empty() && values.iter().all(|v| v.is_finite()),
        };
        let Some((lo, hi)) = self.bounds() else { return params_ok };
        params_ok
            && [0.0, 1e-12, 0.25, 0.5, 0.75, 1.0 - 1e-12, 1.0].iter().all(|&u| {
                let x = self.quantile_unclamped(u);
                x.is_finite() && x >= lo && x <= hi
            })
    }

    /// The same law for the variable multiplied by `factor` > 0 (a change of unit).
    pub fn scaled(&self, factor: f64) -> Self {
        match self {
            Distribution::Fixed { value } => Distribution::Fixed { value: value * factor },
            Distribution::Uniform { min, max } => Distribution::Uniform { min: min * factor, max: max * factor },
            Distribution::Normal { mean, sd, min, max } => {
                Distribution::Normal { mean: mean * factor, sd: sd * factor, min: min * factor, max: max * factor }
            }
            Distribution::LogNormal { median, sigma_log, min, max } => Distribution::LogNormal {
                median: median * factor,
                sigma_log: *sigma_log,
                min: min * factor,
                max: max * factor,
            },
            Distribution::RosinRammler { scale, shape, min, max } => Distribution::RosinRammler {
                scale: scale * factor,
                shape: *shape,
                min: min * factor,
                max: max * factor,
            },
            Distribution::Choice { values } => {
                Distribution::Choice { values: values.iter().map(|v| v * factor).collect() }
            }
        }
    }

    /// The truncation bounds, or the range of the values.
    pub fn bounds(&self) -> Option<(f64, f64)> {
        match self {
            Distribution::Fixed { value } => Some((*value, *value)),
            Distribution::Uniform { min, max }
            | Distribution::Normal { min, max, .. }
            | Distribution::LogNormal { min, max, .. }
            | Distribution::RosinRammler { min, max, .. } => Some((*min, *max)),
            Distribution::Choice { values } => {
                Some(values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v))))
            }
        }
    }

    /// Whether every draw is the same value.
    pub fn is_fixed(&self) -> bool {
        self.bounds().is_some_and(|(a, b)| a == b)
    }

    /// The probability the untruncated law puts between the bounds, for the laws that have
    /// one, evaluated in the tail where it keeps its relative precision.
    fn mass_within_bounds(&self) -> Option<f64> {
        let normal_mass = |a: f64, b: f64| if a >= 0.0 { phi(-a) - phi(-b) } else { phi(b) - phi(a) };
        match *self {
            Distribution::Normal { mean, sd, min, max } => Some(normal_mass((min - mean) / sd, (max - mean) / sd)),
            Distribution::LogNormal { median, sigma_log, min, max } => {
                let z = |x: f64| (x.ln() - median.ln()) / sigma_log;
                Some(normal_mass(z(min), z(max)))
            }
            Distribution::RosinRammler { scale, shape, min, max } => {
                let s = |x: f64| (-(x / scale).powf(shape)).exp();
                Some(s(min) - s(max))
            }
            _ => None,
        }
    }

    /// The inverse distribution function F⁻¹(u) of the (truncated) law, u in (0, 1): the
    /// value whose probability of not being exceeded is u.
    pub fn quantile(&self, u: f64) -> f64 {
        let x = self.quantile_unclamped(u);
        match self.bounds() {
            // max/min rather than clamp: never a panic, whatever a law that was not checked holds.
            Some((lo, hi)) if lo <= hi => x.max(lo).min(hi),
            _ => x,
        }
    }

    /// F⁻¹(u) as computed, NaN where the parameters make no law; the clamp to the bounds only
    /// absorbs rounding.
    fn quantile_unclamped(&self, u: f64) -> f64 {
        let u = if u.is_nan() { 0.5 } else { u.clamp(0.0, 1.0) };
        let clamp = |x: f64, min: f64, max: f64| if x.is_nan() { x } else { x.max(min).min(max) };
        match self {
            Distribution::Fixed { value } => *value,
            Distribution::Uniform { min, max } => min + u * (max - min),
            Distribution::Normal { mean, sd, min, max } => {
                clamp(mean + sd * truncated_standard_normal((min - mean) / sd, (max - mean) / sd, u), *min, *max)
            }
            Distribution::LogNormal { median, sigma_log, min, max } => {
                let z = |x: f64| (x.ln() - median.ln()) / sigma_log;
                let t = truncated_standard_normal(z(*min), z(*max), u);
                clamp(median * (sigma_log * t).exp(), *min, *max)
            }
            Distribution::RosinRammler { scale, shape, min, max } => {
                // Through the survival function S(x) = exp(-(x/s)ⁿ), accurate in the upper tail.
                let s = |x: f64| (-(x / scale).powf(*shape)).exp();
                let (sa, sb) = (s(*min), s(*max));
                let sv = sa - u * (sa - sb);
                clamp(scale * (-sv.ln()).powf(1.0 / shape), *min, *max)
            }
            Distribution::Choice { values } => {
                let k = ((u * values.len() as f64) as usize).min(values.len() - 1);
                values[k]
            }
        }
    }

    /// The median, F⁻¹(½): the value a held variable takes.
    pub fn median(&self) -> f64 {
        self.quantile(0.5)
    }
}

/// The standard normal distribution function Φ(x) = ½ erfc(-x/√2).
///
/// erfc is libm's (FreeBSD's msun): within a few ulps of Φ over the bulk and the tails,
/// where statrs 0.18's normal distribution function is up to 1e-10 off, relative (both
/// measured against mpmath at 50 digits; statrs' worst near x = -0.7).
pub fn phi(x: f64) -> f64 {
    0.5 * libm::erfc(-x / std::f64::consts::SQRT_2)
}

/// The standard normal quantile Φ⁻¹(p), p in (0, 1): Acklam's rational approximation
/// (relative error 1.15e-9) refined by one Halley step on Φ (erfc from libm), which brings
/// it to a few ulps.
///
/// statrs' `Normal::inverse_cdf` is as accurate (its test here), but not bit for bit: in
/// place of this one it moves the normal and lognormal draws of `scenes/caving-stream.toml`
/// by an ulp or two in over half the impacts (no AUC, count or accuracy of the report, but
/// the draws of the committed `impacts.csv`, written to full precision). Every draw of an
/// ensemble goes through this function, so it stays.
pub fn phi_inverse(p: f64) -> f64 {
    if p <= 0.0 {
        return f64::NEG_INFINITY;
    }
    if p >= 1.0 {
        return f64::INFINITY;
    }
    const A: [f64; 6] = [
        -3.969683028665376e1,
        2.209460984245205e2,
        -2.759285104469687e2,
        1.38357751867269e2,
        -3.066479806614716e1,
        2.506628277459239,
    ];
    const B: [f64; 5] =
        [-5.447609879822406e1, 1.615858368580409e2, -1.556989798598866e2, 6.680131188771972e1, -1.328068155288572e1];
    const C: [f64; 6] = [
        -7.784894002430293e-3,
        -3.223964580411365e-1,
        -2.400758277161838,
        -2.549732539343734,
        4.374664141464968,
        2.938163982698783,
    ];
    const D: [f64; 4] = [7.784695709041462e-3, 3.224671290700398e-1, 2.445134137142996, 3.754408661907416];
    let low = 0.02425;
    let x = if p < low {
        let q = (-2.0 * p.ln()).sqrt();
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    } else if p <= 1.0 - low {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    } else {
        let q = (-2.0 * (1.0 - p).ln()).sqrt();
        -(((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    // Halley's step on Φ(x) - p, with Φ' = φ and Φ'' = -xφ.
    let e = phi(x) - p;
    let u = e * (2.0 * std::f64::consts::PI).sqrt() * (0.5 * x * x).exp();
    x - u / (1.0 + 0.5 * x * u)
}

/// Φ⁻¹ of the standard normal truncated to [a, b] at u: Φ⁻¹(Φ(a) + u(Φ(b) - Φ(a))),
/// evaluated in the lower tail (reflected when a ≥ 0) where Φ keeps its relative precision.
fn truncated_standard_normal(a: f64, b: f64, u: f64) -> f64 {
    // Strictly positive: at a = b = 0 the reflection is [-0, -0], and `-0.0 >= 0.0` would
    // reflect it back for ever.
    if a > 0.0 {
        return -truncated_standard_normal(-b, -a, 1.0 - u);
    }
    let (pa, pb) = (phi(a), phi(b));
    let x = phi_inverse(pa + u * (pb - pa));
    if x.is_nan() {
        x
    } else {
        x.max(a).min(b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_quantile_inverts_phi_to_rounding() {
        // Φ(Φ⁻¹(p)) = p over eleven decades of the lower tail and the bulk; and the textbook
        // quantiles 1.959963984540054 (p = 0.975) and 2.326347874040841 (p = 0.99).
        for p in [1e-12, 1e-6, 0.001, 0.02, 0.1, 0.3, 0.5, 0.7, 0.9, 0.975, 0.999] {
            let x = phi_inverse(p);
            assert!((phi(x) / p - 1.0).abs() < 1e-13, "p = {p}");
        }
        assert!((phi_inverse(0.975) - 1.959963984540054).abs() < 1e-14);
        assert!((phi_inverse(0.99) - 2.326347874040841).abs() < 1e-14);
    }

    #[test]
    fn quantiles_agree_with_statrs() {
        // An independent implementation (statrs: Φ⁻¹ through Boost's erfc⁻¹, the Weibull
        // quantile in closed form), over the bulk and 1e-40 deep into the lower tail. The two
        // Φ⁻¹ differ by a few ulps, most where p is near 1 and its own rounding dominates.
        use statrs::distribution::{ContinuousCDF, Normal, Weibull};
        let normal = Normal::standard();
        let weibull = Weibull::new(1.5, 25.0).unwrap();
        let rr = Distribution::RosinRammler { scale: 25.0, shape: 1.5, min: 0.0, max: f64::MAX };
        let mut rng = crate::ensemble::impact_stream(7, 0);
        for k in 0..20_000 {
            let u = crate::ensemble::open_uniform(&mut rng);
            let p = if k % 2 == 0 { u } else { u.powi(8) };
            let (x, y) = (phi_inverse(p), normal.inverse_cdf(p));
            assert!((x - y).abs() <= 1e-12 * x.abs().max(1.0), "p = {p:e}: {x} vs {y}");
            let v = 0.001 + 0.998 * u;
            let (x, y) = (rr.quantile(v), weibull.inverse_cdf(v));
            assert!((x / y - 1.0).abs() <= 1e-12, "u = {v}: {x} vs {y}");
        }
    }

    #[test]
    fn quantiles_are_those_of_the_laws() {
        // Uniform: linear. Normal without effective truncation: mean + sd Φ⁻¹(u). Lognormal:
        // median at ½. Rosin-Rammler: F(x₆₃) = 1 - 1/e.
        let u = Distribution::Uniform { min: 2.0, max: 6.0 };
        assert_eq!(u.quantile(0.25), 3.0);
        let n = Distribution::Normal { mean: 10.0, sd: 2.0, min: -1e3, max: 1e3 };
        assert!((n.quantile(0.975) - (10.0 + 2.0 * 1.959963984540054)).abs() < 1e-12);
        let l = Distribution::LogNormal { median: 25.0, sigma_log: 0.4, min: 1e-3, max: 1e6 };
        assert!((l.median() - 25.0).abs() < 1e-12);
        let r = Distribution::RosinRammler { scale: 30.0, shape: 1.5, min: 0.0, max: 1e9 };
        assert!((r.quantile(1.0 - (-1f64).exp()) - 30.0).abs() < 1e-10);
        let c = Distribution::Choice { values: vec![0.008, 0.0025] };
        assert_eq!((c.quantile(0.1), c.quantile(0.9)), (0.008, 0.0025));
    }

    #[test]
    fn truncation_confines_draws_and_keeps_shape() {
        // A normal truncated to [μ, μ + σ]: its median is Φ⁻¹((½ + Φ(1))/2) standard deviations up.
        let n = Distribution::Normal { mean: 0.0, sd: 1.0, min: 0.0, max: 1.0 };
        let expected = phi_inverse(0.5 * (0.5 + phi(1.0)));
        assert!((n.median() - expected).abs() < 1e-14);
        for k in 0..=100 {
            let x = n.quantile(k as f64 / 100.0);
            assert!((0.0..=1.0).contains(&x));
        }
        // Far in the upper tail (8σ to 9σ) the reflected evaluation stays accurate: the
        // draws are inside the bounds and increase with u.
        let t = Distribution::Normal { mean: 0.0, sd: 1.0, min: 8.0, max: 9.0 };
        let q: Vec<f64> = (1..10).map(|k| t.quantile(k as f64 / 10.0)).collect();
        assert!(q.windows(2).all(|w| w[0] < w[1]) && q[0] > 8.0 && q[8] < 9.0, "{q:?}");
    }

    #[test]
    fn degenerate_laws_never_panic_or_recurse() {
        // Bounds at the mean: the truncated normal on [0, 0] once reflected itself for ever.
        let n = Distribution::Normal { mean: 1.0, sd: 1.0, min: 1.0, max: 1.0 };
        assert_eq!(n.quantile(0.3), 1.0);
        assert_eq!(n.clone().checked(Range::closed(0.0, 2.0), "").unwrap(), Distribution::Fixed { value: 1.0 });
        // A spread scaled to 0 (or NaN parameters): a NaN or a bound, never a panic in clamp.
        let z = Distribution::Normal { mean: 10.0, sd: 0.0, min: 10.0, max: 60.0 };
        assert!(!z.is_drawable());
        let _ = z.quantile(0.5);
        let nan = Distribution::Normal { mean: f64::NAN, sd: f64::NAN, min: f64::NAN, max: f64::NAN };
        let _ = nan.quantile(f64::NAN);
        assert!(!nan.is_drawable());
        // Below the relative floor: refused naming sd.
        let e = Distribution::Normal { mean: 25.0, sd: 5e-324, min: 15.0, max: 40.0 }
            .checked(Range::closed(1e-3, 1e4), "mm")
            .unwrap_err();
        assert!(e.to_string().starts_with("sd = 5e-324 is outside the allowed range [4e-11, "), "{e}");
    }

    #[test]
    fn checks_name_the_parameter() {
        let allowed = Range::closed(1e-3, 1e4);
        let e = Distribution::Uniform { min: 0.0, max: 5.0 }.checked(allowed, "mm").unwrap_err();
        assert_eq!(e.to_string(), "min = 0 is outside the allowed range [0.001, 10000] mm");
        let e = Distribution::Uniform { min: 5.0, max: 1.0 }.checked(allowed, "mm").unwrap_err();
        assert!(e.to_string().starts_with("max: max = 1 is below min = 5"), "{e}");
        let e = Distribution::Normal { mean: 0.0, sd: 1.0, min: 50.0, max: 60.0 }.checked(allowed, "mm").unwrap_err();
        assert!(e.to_string().contains("no probability"), "{e}");
        assert!(Distribution::Choice { values: vec![] }.checked(allowed, "mm").is_err());
    }
}
