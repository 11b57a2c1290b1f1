//! A statement's verdict under one model: whether a model's results show what a statement
//! says, to within the model's own error estimate.

use serde::Serialize;

/// A statement's verdict under one model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// The data show it.
    Holds,
    /// The data contradict it.
    Fails,
    /// A difference it rests on is within the model's resolution (its error estimate), and
    /// nothing contradicts it: the model cannot tell.
    NotResolved,
    /// Not tested under this model.
    NotTested,
}

impl Verdict {
    /// The word tables and figures print.
    pub fn word(self) -> &'static str {
        match self {
            Verdict::Holds => "yes",
            Verdict::Fails => "no",
            Verdict::NotResolved => "not resolved",
            Verdict::NotTested => "–",
        }
    }

    /// The verdict on a statement made of parts: it fails if any part fails, holds if every
    /// part holds, and is not resolved otherwise (an empty statement holds).
    pub fn all(parts: impl IntoIterator<Item = Verdict>) -> Verdict {
        let mut out = Verdict::Holds;
        for v in parts {
            match v {
                Verdict::Fails => return Verdict::Fails,
                Verdict::NotResolved | Verdict::NotTested if out == Verdict::Holds => out = v,
                _ => {}
            }
        }
        out
    }

    /// Whether `a` exceeds `b` (`strict`) or is at least `b`, each known to within an absolute
    /// `resolution`: a difference within the resolution is not resolved (a zero resolution,
    /// an exact model, always decides).
    pub fn compare(a: f64, b: f64, resolution: f64, strict: bool) -> Verdict {
        let d = a - b;
        if resolution > 0.0 && d.abs() <= resolution {
            Verdict::NotResolved
        } else if d > 0.0 || (!strict && d == 0.0) {
            Verdict::Holds
        } else {
            Verdict::Fails
        }
    }
}

impl From<bool> for Verdict {
    fn from(holds: bool) -> Self {
        if holds {
            Verdict::Holds
        } else {
            Verdict::Fails
        }
    }
}

/// Values closer than this, relative to the larger extreme, count as equal in
/// [`extreme_indices`]: mirror points of a symmetric plate agree to rounding (1e-13 on the
/// paper's), which would otherwise decide between them.
pub const TIE: f64 = 1e-9;

/// The first index of the least and of the greatest of `values`, values within [`TIE`] of an
/// extreme (relative to the largest finite magnitude) counting as equal to it; NaN is never an
/// extreme, an infinity only ties with itself; None when no value is a number.
pub fn extreme_indices(values: &[f64]) -> Option<(usize, usize)> {
    let lowest = values.iter().copied().fold(f64::INFINITY, f64::min);
    let highest = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let tie = TIE * values.iter().filter(|v| v.is_finite()).fold(0.0f64, |m, v| m.max(v.abs()));
    let first = |at: &dyn Fn(f64) -> bool| values.iter().position(|&v| at(v));
    Some((first(&|v| v <= lowest + tie)?, first(&|v| v >= highest - tie)?))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verdicts_combine_and_compare_within_resolution() {
        use Verdict::*;
        assert_eq!(Verdict::all([Holds, Holds]), Holds);
        assert_eq!(Verdict::all([Holds, NotResolved, Holds]), NotResolved);
        assert_eq!(Verdict::all([NotResolved, Fails]), Fails);
        // A difference smaller than what the model resolves decides nothing.
        assert_eq!(Verdict::compare(1.0 + 1e-5, 1.0, 3.5e-5, true), NotResolved);
        assert_eq!(Verdict::compare(1.0 - 1e-5, 1.0, 3.5e-5, true), NotResolved);
        assert_eq!(Verdict::compare(1.0 + 1e-4, 1.0, 3.5e-5, true), Holds);
        assert_eq!(Verdict::compare(1.0 - 1e-4, 1.0, 3.5e-5, true), Fails);
        // An exact model decides every difference, and "at least" admits equality.
        assert_eq!(Verdict::compare(1.0, 1.0, 0.0, false), Holds);
        assert_eq!(Verdict::compare(1.0, 1.0, 0.0, true), Fails);
    }
}
