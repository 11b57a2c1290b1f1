//! Navier's series for the hard simply supported Mindlin plate under a patch load.
//!
//! On an a x b plate with all four edges hard simply supported (w = 0, M_n = 0, θ along the
//! edge = 0) the fields w = Σ W_mn sin(α_m x) sin(β_n z), θ_x ∝ cos sin, θ_z ∝ sin cos meet
//! every boundary condition, and each harmonic of the load q_mn decouples:
//!
//! ```text
//! W_mn = q_mn / (D k⁴) + q_mn / (k_s G h k²),    k² = α_m² + β_n², α_m = mπ/a, β_n = nπ/b
//! ```
//!
//! the Kirchhoff term plus the shear term (Reddy, *Theory and Analysis of Elastic Plates and
//! Shells*, 2nd ed., §10.2.2; the same as Wang, Reddy & Lee's w_M = w_K + M_K/(k_s G h) for
//! simply supported polygonal plates, with M_K the Marcus moment). A uniform pressure P/(uv)
//! over the patch [x₀ ± u/2] x [z₀ ± v/2] has
//!
//! ```text
//! q_mn = 4P/(ab uv) I_m I_n,   I_m = ∫ sin(α_m x) dx over the patch = (2/α_m) sin(α_m x₀) sin(α_m u/2)
//! ```
//!
//! and the work-conjugate compliance C = (1/P²) ∫ p w dA = Σ 4 (I_m J_n)² F_mn / (ab u²v²),
//! with F_mn = 1/(Dk⁴) + 1/(k_s G h k²) and J_n the same integral along z.
//!
//! **Truncation.** Both |I_m| ≤ 2/α_m, so a term is bounded by c/(m² n² k²): the tail
//! beyond m or n = M is O(1/M³) of the sum. The series is summed to [`TERMS`] in each
//! direction, and its error estimated as the change from [`TERMS`]/2 (reported).

use super::{Patch, SHEAR_CORRECTION};
use crate::{FemError, PlateProperties};
use serde::Serialize;
use std::f64::consts::PI;

/// Harmonics summed in each direction.
pub const TERMS: usize = 2000;

/// The series' compliance and its parts (m/N), with the truncation estimate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SeriesCompliance {
    /// Work-conjugate compliance of the Mindlin plate: Kirchhoff plus shear.
    pub compliance: f64,
    /// Kirchhoff's part (the series without the shear term).
    pub kirchhoff: f64,
    /// The shear term's part.
    pub shear: f64,
    /// Deflection at the patch centre per unit force (Mindlin).
    pub centre_deflection: f64,
    /// |C(TERMS) - C(TERMS/2)|: an upper estimate of the truncation error of `compliance`.
    pub truncation: f64,
}

/// ∫ sin(kx) dx over [c - s/2, c + s/2], divided by s: the patch mean of the harmonic.
fn mean_sine(k: f64, centre: f64, side: f64) -> f64 {
    2.0 * (k * centre).sin() * (k * side / 2.0).sin() / (k * side)
}

/// Navier's series for a unit force spread over `patch` on the hard simply supported plate;
/// the plate and the patch (positive sides, on the plate) are checked first.
pub fn navier_patch(props: &PlateProperties, patch: &Patch) -> Result<SeriesCompliance, FemError> {
    props.validate()?;
    patch.validate(props.length, props.width)?;
    let (a, b) = (props.length, props.width);
    let d = props.rigidity();
    let gh =
        super::element::shear_rigidity(props.youngs_modulus, props.poisson_ratio, props.thickness, SHEAR_CORRECTION);
    let sum = |terms: usize| {
        let mx: Vec<(f64, f64, f64)> = (1..=terms)
            .map(|m| {
                let k = m as f64 * PI / a;
                (k, mean_sine(k, patch.x, patch.side_x), (k * patch.x).sin())
            })
            .collect();
        let nz: Vec<(f64, f64, f64)> = (1..=terms)
            .map(|n| {
                let k = n as f64 * PI / b;
                (k, mean_sine(k, patch.z, patch.side_z), (k * patch.z).sin())
            })
            .collect();
        let (mut kirchhoff, mut shear, mut centre) = (0.0, 0.0, 0.0);
        for &(al, im, sx) in &mx {
            for &(be, jn, sz) in &nz {
                let k2 = al * al + be * be;
                // q_mn / P = (4/ab) Im Jn (the means), and the patch mean of the mode.
                let q = 4.0 / (a * b) * im * jn;
                let (fk, fs) = (1.0 / (d * k2 * k2), 1.0 / (gh * k2));
                kirchhoff += q * im * jn * fk;
                shear += q * im * jn * fs;
                centre += q * sx * sz * (fk + fs);
            }
        }
        (kirchhoff, shear, centre)
    };
    let (kirchhoff, shear, centre_deflection) = sum(TERMS);
    let (k_half, s_half, _) = sum(TERMS / 2);
    let compliance = kirchhoff + shear;
    Ok(SeriesCompliance {
        compliance,
        kirchhoff,
        shear,
        centre_deflection,
        truncation: (compliance - (k_half + s_half)).abs(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(h: f64) -> PlateProperties {
        PlateProperties {
            length: 1.0,
            width: 1.0,
            thickness: h,
            youngs_modulus: 210e9,
            poisson_ratio: 0.3,
            density: 7850.0,
        }
    }

    /// A uniform load q over the whole square (the patch is the plate): the centre
    /// deflection is 4.062e-3 q a⁴/D for Kirchhoff (Timoshenko & Woinowsky-Krieger, Table 8:
    /// 0.00406) and 4.273e-3 q a⁴/D with shear at a/h = 10, ν = 0.3, k_s = 5/6 (Reddy,
    /// *Theory and Analysis of Elastic Plates and Shells*, 2nd ed., Table 10.2.2, FSDT).
    #[test]
    fn uniform_load_matches_the_tabulated_centre_deflections() {
        let props = square(0.1);
        let whole = navier_patch(&props, &Patch { x: 0.5, z: 0.5, side_x: 1.0, side_z: 1.0 }).unwrap();
        let d = props.rigidity();
        // q = P/a² with P = 1 and a = 1: w D/(q a⁴) = w D.
        let mindlin = whole.centre_deflection * d;
        assert!((mindlin / 4.273e-3 - 1.0).abs() < 2e-4, "{mindlin:e}");
        let thin = navier_patch(&square(1e-4), &Patch { x: 0.5, z: 0.5, side_x: 1.0, side_z: 1.0 }).unwrap();
        let kirchhoff = thin.centre_deflection * square(1e-4).rigidity();
        assert!((kirchhoff / 4.062e-3 - 1.0).abs() < 2e-4, "{kirchhoff:e}");
    }

    /// Shrinking the patch at the centre, Kirchhoff's part tends to Navier's point compliance
    /// 0.01160 P a²/D (Timoshenko & Woinowsky-Krieger, Table 23: 0.011601), while the shear
    /// part grows like ln(a/c)/(2π k_s G h): a Mindlin plate has no point compliance.
    #[test]
    fn kirchhoff_part_tends_to_the_point_value_and_shear_part_diverges_logarithmically() {
        let props = square(0.05);
        let d = props.rigidity();
        let at = |c: f64| navier_patch(&props, &Patch { x: 0.5, z: 0.5, side_x: c, side_z: c }).unwrap();
        let small = at(0.005);
        assert!((small.kirchhoff * d / 0.011_601 - 1.0).abs() < 2e-3, "{}", small.kirchhoff * d);
        let gh = super::super::element::shear_rigidity(210e9, 0.3, 0.05, SHEAR_CORRECTION);
        // The shear deflection of a point force on an infinite sheet is ln(1/r)/(2π k_s G h):
        // halving the patch adds ln 2 / (2π k_s G h) once the patch is small.
        let step = at(0.005).shear - at(0.01).shear;
        let expected = 2f64.ln() / (2.0 * PI * gh);
        assert!((step / expected - 1.0).abs() < 0.02, "{step:e} against {expected:e}");
        assert!(small.truncation < 1e-4 * small.compliance, "{:e}", small.truncation / small.compliance);
    }

    /// A patch of zero side, or off the plate, is refused with the field named, not summed
    /// into NaN or a silently wrong value.
    #[test]
    fn bad_patches_are_refused() {
        let props = square(0.05);
        let zero = navier_patch(&props, &Patch { x: 0.5, z: 0.5, side_x: 0.0, side_z: 0.1 });
        assert!(matches!(zero, Err(crate::FemError::Property { name: "patch side_x", .. })), "{zero:?}");
        let off = navier_patch(&props, &Patch { x: 0.98, z: 0.5, side_x: 0.1, side_z: 0.1 });
        assert!(matches!(off, Err(crate::FemError::OutsidePlate { .. })), "{off:?}");
    }
}
