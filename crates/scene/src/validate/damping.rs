//! `[plate_damping]`: the plate's Rayleigh damping, given as a damping ratio reached at two
//! frequencies, for the transient and the reduced model alike.

use super::{other, pair, Invalid};
use crate::limits;
use crate::raw::RawPlateDamping;
use analytic::params::check;
use plate_fem::dynamics::Rayleigh;
use std::f64::consts::PI;

/// `[plate_damping]`: ζ in its range and two frequencies f_a ≤ f_b in theirs, converted to
/// Rayleigh's α and β (ζ at both, Chopra eq. 11.4.9).
pub(super) fn validate_plate_damping(raw: &RawPlateDamping) -> Result<Rayleigh, Invalid> {
    let zeta = check("plate_damping.ratio", raw.ratio, limits::PLATE_DAMPING_RATIO, "")?;
    let (fa, fb) = pair("plate_damping.frequencies_hz", &raw.frequencies_hz, "[f_a, f_b]")?;
    let fa = check("plate_damping.frequencies_hz[0]", fa, limits::DAMPING_FREQUENCY_HZ, "Hz")?;
    let fb = check("plate_damping.frequencies_hz[1]", fb, limits::DAMPING_FREQUENCY_HZ, "Hz")?;
    if fa > fb {
        return Err(other(
            "plate_damping.frequencies_hz",
            format!("[{fa}, {fb}] Hz is not in increasing order; give [f_a, f_b] with f_a ≤ f_b"),
        ));
    }
    Ok(Rayleigh::through(zeta, 2.0 * PI * fa, 2.0 * PI * fb))
}
