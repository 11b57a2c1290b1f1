//! Richardson extrapolation of a quantity computed on meshes refined by a factor 2.
//!
//! For the point compliance the error is expected to behave like c h² (the Green's function
//! of the plate has an r² ln r singularity at the load; conforming elements then converge in
//! energy at O(h²), possibly with a logarithm). The observed rate is measured, not assumed.

use serde::Serialize;

/// A sequence of results on meshes h, h/2, h/4, ... and what it tells.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Extrapolation {
    /// The finest result.
    pub finest: f64,
    /// Richardson estimate of the mesh-converged value, from the two finest results with
    /// the observed rate (or 2 when only two results exist).
    pub extrapolated: f64,
    /// Estimated error of the finest result: |finest - extrapolated| where the sequence is
    /// in its asymptotic range, else the conservative |finest - previous|.
    pub error_estimate: f64,
    /// Observed order p from the three finest results, if there are three.
    pub observed_rate: Option<f64>,
    /// Whether the observed rate (if known) lies in [1.5, 2.5], so that the h² model
    /// behind the extrapolation holds.
    pub asymptotic: bool,
}

/// Observed order log2((q₁ - q₂)/(q₂ - q₃)) of three results on meshes h, h/2, h/4.
pub fn observed_rate(q1: f64, q2: f64, q3: f64) -> Option<f64> {
    let r = (q1 - q2) / (q2 - q3);
    (r.is_finite() && r > 0.0).then(|| r.log2())
}

/// Extrapolates `values` from meshes each twice as fine as the one before.
///
/// The extrapolation uses the nominal rate 2 (the theory for point loads); the observed
/// rate is reported beside it, so a user sees when the asymptotic regime is not reached.
pub fn richardson(values: &[f64]) -> Option<Extrapolation> {
    richardson_at_rate(values, 2.0)
}

/// [`richardson`] at the nominal rate p that the theory gives for the problem: the
/// extrapolated value q₂ + (q₂ - q₁)/(2ᵖ - 1), the sequence asymptotic where the observed
/// rate lies within ±0.5 of p. A rigid line support inside a membrane (a hinge pin's line on
/// a shell wall) has stress singularities at its ends like a crack's, r^(-1/2), under which the
/// energy, and so a compliance, converges at p = 1.
pub fn richardson_at_rate(values: &[f64], rate: f64) -> Option<Extrapolation> {
    let n = values.len();
    if n < 2 {
        return None;
    }
    let (q1, q2) = (values[n - 2], values[n - 1]);
    let extrapolated = q2 + (q2 - q1) / (2f64.powf(rate) - 1.0);
    let observed_rate = if n >= 3 { observed_rate(values[n - 3], q1, q2) } else { None };
    let asymptotic = observed_rate.is_none_or(|p| (rate - 0.5..=rate + 0.5).contains(&p));
    let error_estimate =
        if asymptotic { (q2 - extrapolated).abs() } else { (q2 - q1).abs().max((q2 - extrapolated).abs()) };
    Some(Extrapolation { finest: q2, extrapolated, error_estimate, observed_rate, asymptotic })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn exact_for_pure_h2_error() {
        let exact = 3.0;
        let v: Vec<f64> = [1.0, 0.5, 0.25].iter().map(|h| exact - 0.7 * h * h).collect();
        let e = richardson(&v).unwrap();
        assert_relative_eq!(e.extrapolated, exact, max_relative = 1e-14);
        assert_relative_eq!(e.observed_rate.unwrap(), 2.0, max_relative = 1e-12);
        assert!(e.asymptotic);
    }

    /// At rate 1 the extrapolation is exact for an error c·h, and a rate-2 sequence is not
    /// asymptotic for it.
    #[test]
    fn exact_for_pure_h1_error_at_rate_one() {
        let v: Vec<f64> = [1.0, 0.5, 0.25].iter().map(|h| 3.0 - 0.7 * h).collect();
        let e = richardson_at_rate(&v, 1.0).unwrap();
        assert_relative_eq!(e.extrapolated, 3.0, max_relative = 1e-14);
        assert!(e.asymptotic);
        assert!(!richardson(&v).unwrap().asymptotic);
    }

    /// Outside the asymptotic range the estimate falls back to the last difference.
    #[test]
    fn pre_asymptotic_sequence_is_flagged() {
        let v = [1.0, 1.5, 1.6]; // rate log2(0.5/0.1) = 2.32: asymptotic
        assert!(richardson(&v).unwrap().asymptotic);
        let v = [1.0, 1.1, 1.17]; // rate log2(0.1/0.07) = 0.51
        let e = richardson(&v).unwrap();
        assert!(!e.asymptotic);
        assert_relative_eq!(e.error_estimate, 0.07, max_relative = 1e-12);
    }
}
