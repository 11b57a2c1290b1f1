//! The transient yield velocity: the v at which the transient δ_max reaches δ_my of eq. 51,
//! found as a root in ln v.

use super::rows::YieldValues;
use super::thin_plate;
use crate::error::ModelError;
use crate::scene::Scene;
use crate::supports::SupportSet;
use crate::transient::TransientCase;
use crate::validity::Validity;
use crate::yield_root::{Root, YieldSearch};
use analytic::{Impact, Method, Sphere};

/// Relative width to which the transient yield velocity is found.
pub const YIELD_ROOT_TOLERANCE: f64 = 1e-6;

/// d ln δ_max / d ln v of Hertz's contact on a rigid target (δ_max ∝ v^{4/5}): the first
/// step of the root search.
pub const HERTZ_SLOPE: f64 = 0.8;

/// The root of an increasing f(ln v) from `start`: (ln lo, ln hi) with f(lo) < 0 ≤ f(hi)
/// and hi/lo - 1 ≤ `tol`. Bracketed by secant steps from the slope [`HERTZ_SLOPE`], closed
/// by Illinois false position kept at least ~tol/2 inside the bracket (so the bracket
/// closes from both sides).
pub fn log_root(
    f: &mut impl FnMut(f64) -> Result<f64, ModelError>,
    start: f64,
    tol: f64,
) -> Result<(f64, f64), ModelError> {
    let (a, fa) = (start, f(start)?);
    let b = a - fa / HERTZ_SLOPE;
    let fb = f(b)?;
    let (lo, hi, n) = expand(f, (a, fa), (b, fb), tol)?;
    close(f, lo, hi, tol, n)
}

/// A point of a root search: (ln v, f(ln v)).
type Point = (f64, f64);

/// The error of a search that could not bracket the root.
fn lost() -> ModelError {
    ModelError::Missing("the transient yield velocity could not be bracketed".into())
}

/// From two points (a, f(a)) and (b, f(b)), b the later, secant steps (slope at least 0.1,
/// else [`HERTZ_SLOPE`]; at most a factor 2 in v; overshooting by 0.1 % and one bracket
/// width) until f changes sign: the bracket as ((lo, f(lo)), (hi, f(hi))) with f(lo) < 0 ≤
/// f(hi), and the steps taken.
fn expand(
    f: &mut impl FnMut(f64) -> Result<f64, ModelError>,
    (mut a, mut fa): Point,
    (mut b, mut fb): Point,
    tol: f64,
) -> Result<(Point, Point, usize), ModelError> {
    let width = tol.ln_1p();
    let mut n = 0;
    while (fa < 0.0) == (fb < 0.0) {
        n += 1;
        if n > 60 || !fb.is_finite() {
            return Err(lost());
        }
        let slope = (fb - fa) / (b - a);
        let slope = if slope.is_finite() && slope > 0.1 { slope } else { HERTZ_SLOPE };
        let step = (-fb / slope).clamp(-std::f64::consts::LN_2, std::f64::consts::LN_2);
        // Overshoot a little so that the next point straddles the root.
        let step = step * 1.001 + step.signum() * width;
        (a, fa) = (b, fb);
        b += step;
        fb = f(b)?;
    }
    let (lo, hi) = if fa < 0.0 { ((a, fa), (b, fb)) } else { ((b, fb), (a, fa)) };
    Ok((lo, hi, n))
}

/// Illinois false position on a bracket f(lo) < 0 ≤ f(hi) of an increasing f(ln v), each
/// point kept at least 0.45 of the final width inside the bracket (so that it closes from
/// both sides), until hi/lo - 1 ≤ `tol`; `n` steps already taken count toward the limit.
pub fn close(
    f: &mut impl FnMut(f64) -> Result<f64, ModelError>,
    (mut lo, mut flo): Point,
    (mut hi, mut fhi): Point,
    tol: f64,
    mut n: usize,
) -> Result<(f64, f64), ModelError> {
    let width = tol.ln_1p();
    let mut side = 0;
    while hi - lo > width {
        n += 1;
        if n > 200 {
            return Err(lost());
        }
        let gap = (0.45 * width).min(0.5 * (hi - lo));
        let c = (lo * fhi - hi * flo) / (fhi - flo);
        let c = if c.is_finite() { c } else { 0.5 * (lo + hi) };
        let c = c.clamp(lo + gap, hi - gap);
        let fc = f(c)?;
        if fc < 0.0 {
            (lo, flo) = (c, fc);
            if side == -1 {
                fhi *= 0.5;
            }
            side = -1;
        } else {
            (hi, fhi) = (c, fc);
            if side == 1 {
                flo *= 0.5;
            }
            side = 1;
        }
    }
    Ok((lo, hi))
}

/// How close a guess is to the root, and how well its model knows the slope there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Guess {
    /// ln v of the guessed root.
    pub at: f64,
    /// d f/d ln v of the guessing model at its root.
    pub slope: f64,
    /// The farthest the root may lie from `at`, in ln v: no point of the search leaves it.
    pub reach: f64,
    /// The relative disagreement allowed between the guessing model's slope and f's.
    pub slope_spread: f64,
}

/// The root of an increasing f(ln v) near the root of another model of it (`guess`): f at
/// the guess, then one Newton step with the guessing model's slope, lengthened by
/// `slope_spread`·|step| + 0.15 tol so that it passes the root when the two slopes differ by no
/// more than `slope_spread`; if these two points straddle the root, the bracket is closed by
/// [`close`] as in [`log_root`]. When the slopes differ by well under `slope_spread` and the
/// step is small enough that `slope_spread`·|step| stays under 0.3 tol, the step lands less
/// than 0.45 of the final width past the root, so [`close`]'s first point, held 0.45 of it
/// inside, closes the bracket: three evaluations of f.
///
/// None when the two points do not straddle the root or the step would leave the guess's
/// reach: the guess is then not good enough and the caller searches otherwise (the
/// evaluations spent are its own to count).
pub fn log_root_near(
    f: &mut impl FnMut(f64) -> Result<f64, ModelError>,
    guess: Guess,
    tol: f64,
) -> Result<Option<(f64, f64)>, ModelError> {
    let width = tol.ln_1p();
    let (a, fa) = (guess.at, f(guess.at)?);
    if !fa.is_finite() {
        return Ok(None);
    }
    let slope = if guess.slope.is_finite() && guess.slope > 0.1 { guess.slope } else { HERTZ_SLOPE };
    let newton = -fa / slope;
    // f(a) ≥ 0 puts the root at or below a (f(lo) < 0 ≤ f(hi)).
    let dir = if fa < 0.0 { 1.0 } else { -1.0 };
    let b = a + newton + dir * (guess.slope_spread * newton.abs() + 0.15 * width);
    if (b - a).abs() > guess.reach {
        return Ok(None);
    }
    let fb = f(b)?;
    if !fb.is_finite() || (fa < 0.0) == (fb < 0.0) {
        return Ok(None);
    }
    let (lo, hi) = if fa < 0.0 { ((a, fa), (b, fb)) } else { ((b, fb), (a, fa)) };
    close(f, lo, hi, tol, 0).map(Some)
}

/// The dynamic yield velocity: the v at which the transient δ_max reaches δ_my of eq. 51
/// ([`crate::yield_root`]), by `search` (which keeps its reduced models for later roots).
/// The error is the final bracket's width, to a relative [`YIELD_ROOT_TOLERANCE`].
pub fn dynamic_yield(
    scene: &Scene,
    case: &TransientCase,
    search: &mut YieldSearch,
    set: &SupportSet,
    body: &Sphere,
    (x, z): (f64, f64),
) -> Result<YieldValues, ModelError> {
    dynamic_yield_with(scene, case, case.settings().steps_per_contact, search, set, body, (x, z))
}

/// [`dynamic_yield`] with `steps_per_contact` steps per Hertz time on `case`'s mesh.
pub fn dynamic_yield_with(
    scene: &Scene,
    case: &TransientCase,
    steps_per_contact: f64,
    search: &mut YieldSearch,
    set: &SupportSet,
    body: &Sphere,
    (x, z): (f64, f64),
) -> Result<YieldValues, ModelError> {
    let root = search.root(&Root { scene, case, steps_per_contact, set, body, at: (x, z) })?;
    Ok(YieldValues {
        compliance: None,
        compliance_error: None,
        yield_compression: root.yield_compression,
        yield_velocity: root.velocity,
        yield_velocity_error: Some(root.width),
        validity: Validity {
            elastic: None,
            quasi_static: None,
            thin_plate: thin_plate(scene),
            recontact: None,
            regime: None,
            finished: None,
            discretisation: None,
        },
    })
}

/// Solves one case with the paper's recursion and with the bracketed solver, converged or
/// not, for the solver study.
pub fn both_solvers(imp: &Impact, c: f64) -> (analytic::Solution, analytic::Solution) {
    let bal = imp.balance(c);
    (bal.attempt(Method::paper()), bal.attempt(Method::default()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// f(ln v) = s (ln v - ln r) + c (ln v - ln r)², increasing near its root r; each call
    /// counted.
    fn model(r: f64, s: f64, c: f64, calls: &mut usize) -> impl FnMut(f64) -> Result<f64, ModelError> + '_ {
        move |lv| {
            *calls += 1;
            let d = lv - r.ln();
            Ok(s * d + c * d * d)
        }
    }

    /// A guess 1e-4 off the root (in ln v, either side) with a slope within 5e-4 of the true
    /// one: the Newton step passes the root by less than 0.45 of the final width, so three
    /// evaluations close a bracket that holds the root and is no wider than the tolerance.
    #[test]
    fn a_good_guess_closes_in_three_evaluations() {
        let tol = YIELD_ROOT_TOLERANCE;
        for (off, slope_error) in [(1e-4, 5e-4), (-1e-4, -5e-4), (3e-5, -5e-4), (-2e-6, 5e-4), (0.0, 0.0)] {
            let (r, s): (f64, f64) = (3.2e-3, 0.78);
            let mut calls = 0;
            let guess = Guess { at: r.ln() + off, slope: s * (1.0 + slope_error), reach: 3e-4, slope_spread: 2e-3 };
            let found = log_root_near(&mut model(r, s, 0.05, &mut calls), guess, tol).unwrap();
            let (lo, hi) = found.expect("the guess brackets the root");
            assert!(lo < r.ln() && r.ln() <= hi, "offset {off}: [{lo}, {hi}] misses ln {r}");
            assert!(hi.exp() / lo.exp() - 1.0 <= tol, "offset {off}: width {}", hi - lo);
            assert!(calls <= 3, "offset {off}, slope error {slope_error}: {calls} evaluations");
        }
    }

    /// The search never leaves the guess's reach: a root farther away, or a slope so wrong
    /// that the step does not pass the root, gives None after at most two evaluations.
    #[test]
    fn a_poor_guess_is_refused() {
        let tol = YIELD_ROOT_TOLERANCE;
        let r: f64 = 3.2e-3;
        for (off, slope) in [(5e-4, 0.78), (-5e-4, 0.78), (2e-4, 0.9), (-2e-4, 0.9)] {
            let mut calls = 0;
            let guess = Guess { at: r.ln() + off, slope, reach: 3e-4, slope_spread: 2e-3 };
            let found = log_root_near(&mut model(r, 0.78, 0.0, &mut calls), guess, tol).unwrap();
            assert_eq!(found, None, "offset {off}, slope {slope}");
            assert!(calls <= 2);
        }
    }
}
