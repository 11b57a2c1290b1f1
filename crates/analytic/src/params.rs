//! Allowed ranges of physical parameters, defined once.
//!
//! The scene reader and the constructors of this crate check the same ranges through
//! [`check`], so a value is rejected with the same words wherever it enters.

use std::fmt;

/// An interval of the real line, each end open or closed; infinite ends are open.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Lower end.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
    /// Whether `lo` itself is allowed.
    pub lo_closed: bool,
    /// Whether `hi` itself is allowed.
    pub hi_closed: bool,
}

impl Range {
    /// `(lo, hi)`.
    pub const fn open(lo: f64, hi: f64) -> Self {
        Self { lo, hi, lo_closed: false, hi_closed: false }
    }
    /// `(lo, hi]`.
    pub const fn open_closed(lo: f64, hi: f64) -> Self {
        Self { lo, hi, lo_closed: false, hi_closed: true }
    }
    /// `[lo, hi)`.
    pub const fn closed_open(lo: f64, hi: f64) -> Self {
        Self { lo, hi, lo_closed: true, hi_closed: false }
    }
    /// `[lo, hi]`.
    pub const fn closed(lo: f64, hi: f64) -> Self {
        Self { lo, hi, lo_closed: true, hi_closed: true }
    }

    /// Whether `v` lies in the range; NaN never does.
    pub fn contains(&self, v: f64) -> bool {
        if !v.is_finite() {
            return false;
        }
        let above = if self.lo_closed { v >= self.lo } else { v > self.lo };
        let below = if self.hi_closed { v <= self.hi } else { v < self.hi };
        above && below
    }
}

impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let l = if self.lo_closed { '[' } else { '(' };
        let r = if self.hi_closed { ']' } else { ')' };
        write!(f, "{l}{}, {}{r}", compact(self.lo), compact(self.hi))
    }
}

/// Strictly positive and finite: sizes, moduli, densities, stiffnesses, velocities.
pub const POSITIVE: Range = Range::open(0.0, f64::INFINITY);
/// Poisson's ratio of an isotropic solid that the model accepts.
pub const POISSON_RATIO: Range = Range::open(0.0, 0.5);
/// Restitution coefficient of the Flores model (eq. 1); e = 0 would make eq. 7 infinite.
pub const RESTITUTION: Range = Range::open_closed(0.0, 1.0);
/// Internal friction angle of the Drucker-Prager rock, degrees (eq. 51).
pub const FRICTION_ANGLE_DEG: Range = Range::open(0.0, 90.0);

/// A number as a person reads it: plain for moderate magnitudes, scientific beyond (1e300
/// is "1e300", not three hundred digits), "inf" and "NaN" as such.
pub fn compact(v: f64) -> String {
    if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.to_string()
    } else if v == 0.0 || v.is_nan() || (1e-6..1e16).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// A parameter outside its allowed range, named as the caller knows it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{name} = {} is outside the allowed range {allowed}{unit}", compact(*.value), unit = unit_suffix(.unit))]
pub struct InvalidParameter {
    /// The parameter as the caller names it (`velocity`, `bodies[0].radius`, ...).
    pub name: String,
    /// The refused value.
    pub value: f64,
    /// The range it had to lie in.
    pub allowed: Range,
    /// SI unit of value and range ("" for dimensionless).
    pub unit: &'static str,
}

fn unit_suffix(unit: &str) -> String {
    if unit.is_empty() {
        String::new()
    } else {
        format!(" {unit}")
    }
}

/// Returns `value` if it lies in `allowed`, else an error naming the parameter.
pub fn check(name: &str, value: f64, allowed: Range, unit: &'static str) -> Result<f64, InvalidParameter> {
    if allowed.contains(value) {
        Ok(value)
    } else {
        Err(InvalidParameter { name: name.to_string(), value, allowed, unit })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nan_and_infinity_are_never_in_range() {
        for r in [POSITIVE, POISSON_RATIO, RESTITUTION, FRICTION_ANGLE_DEG] {
            assert!(!r.contains(f64::NAN));
            assert!(!r.contains(f64::INFINITY));
            assert!(!r.contains(f64::NEG_INFINITY));
        }
    }

    #[test]
    fn ends_follow_their_closedness() {
        assert!(!RESTITUTION.contains(0.0));
        assert!(RESTITUTION.contains(1.0));
        assert!(!POISSON_RATIO.contains(0.5));
        assert!(!POSITIVE.contains(0.0));
        assert!(POSITIVE.contains(f64::MIN_POSITIVE));
    }

    #[test]
    fn message_names_field_and_range() {
        let e = check("bodies[0].poisson_ratio", 0.7, POISSON_RATIO, "").unwrap_err();
        assert_eq!(e.to_string(), "bodies[0].poisson_ratio = 0.7 is outside the allowed range (0, 0.5)");
        let e = check("velocity", -1.0, POSITIVE, "m/s").unwrap_err();
        assert_eq!(e.to_string(), "velocity = -1 is outside the allowed range (0, inf) m/s");
    }
}
