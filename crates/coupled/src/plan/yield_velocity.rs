//! The transient yield velocity: the v at which the transient δ_max reaches δ_my of eq. 51,
//! found as a root in ln v.

use super::rows::YieldValues;
use super::thin_plate;
use crate::error::ModelError;
use crate::scene::Scene;
use crate::supports::SupportSet;
use crate::transient::TransientCase;
use crate::validity::Validity;
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
    let width = tol.ln_1p();
    let lost = || ModelError::Missing("the transient yield velocity could not be bracketed".into());
    let (mut a, mut fa) = (start, f(start)?);
    let mut b = a - fa / HERTZ_SLOPE;
    let mut fb = f(b)?;
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
    let (mut lo, mut flo, mut hi, mut fhi) = if fa < 0.0 { (a, fa, b, fb) } else { (b, fb, a, fa) };
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

/// The dynamic yield velocity: the v at which the transient δ_max reaches δ_my of eq. 51
/// ([`crate::yield_root`]). The error is the final bracket's width, to a relative
/// [`YIELD_ROOT_TOLERANCE`].
pub fn dynamic_yield(
    scene: &Scene,
    case: &TransientCase,
    set: &SupportSet,
    body: &Sphere,
    x: f64,
    z: f64,
) -> Result<YieldValues, ModelError> {
    dynamic_yield_with(scene, case, case.settings().steps_per_contact, set, body, x, z)
}

/// [`dynamic_yield`] with `steps_per_contact` steps per Hertz time on `case`'s mesh.
pub fn dynamic_yield_with(
    scene: &Scene,
    case: &TransientCase,
    steps_per_contact: f64,
    set: &SupportSet,
    body: &Sphere,
    x: f64,
    z: f64,
) -> Result<YieldValues, ModelError> {
    let root = crate::yield_root::transient_yield_with(scene, case, steps_per_contact, set, body, x, z)?;
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
