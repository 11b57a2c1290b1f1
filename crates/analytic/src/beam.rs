//! The paper's beam model of the supported plate (section II): the plate is a beam of
//! bending stiffness E₂I₂ = E B h³/12 along its length L, loaded at x from the left end,
//! y = L - x from the right end.
//!
//! # Example
//!
//! Con 1 at midspan: the simply supported beam's x²y²/(3EIL) with x = y = L/2 is the
//! textbook L³/(48EI), all of it plate strain energy.
//!
//! ```
//! use analytic::{beam_compliance, Condition, Elastic, Plate, StoreKind};
//!
//! // The paper's plate: 458.4 x 360 x 8 mm steel.
//! let plate = Plate::new(0.4584, 0.36, 0.008, 7850.0, Elastic::new(210e9, 0.3)?)?;
//! let (l, ei) = (plate.length(), plate.beam_bending_stiffness());
//! let c = beam_compliance(&plate, Condition::BothFixed, l / 2.0)?;
//! let expected = l.powi(3) / (48.0 * ei); // ≈ 1.04e-7 m/N
//! assert!((c.total() / expected - 1.0).abs() < 1e-14);
//! assert_eq!(c.of_kind(StoreKind::Plate), c.total());
//! assert_eq!(c.deflection_per_unit_load(), c.total()); // eq. 11 at the load point
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::compliance::{InvalidCompliance, PointCompliance, SpringReaction, Store, StoreKind};
use crate::material::Plate;
use crate::params::{check, InvalidParameter, POSITIVE};
use serde::Serialize;

/// The paper's three support conditions (Fig. 3).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Condition {
    /// Con 1: both ends fixed (four fixed corners).
    BothFixed,
    /// Con 2: both ends on springs, two per end, each of stiffness `k_t` (N/m).
    BothSprings {
        /// Stiffness k_T of each of the four springs (N/m), positive and finite.
        k_t: f64,
    },
    /// Con 3: left end fixed, right end on two springs of stiffness `k_t` each.
    FixedAndSprings {
        /// Stiffness k_T of each of the two right-end springs (N/m), positive and finite.
        k_t: f64,
    },
}

impl Condition {
    /// Con 2 with a validated spring stiffness.
    pub fn both_springs(k_t: f64) -> Result<Self, InvalidParameter> {
        Ok(Self::BothSprings { k_t: check("spring_stiffness", k_t, POSITIVE, "N/m")? })
    }
    /// Con 3 with a validated spring stiffness.
    pub fn fixed_and_springs(k_t: f64) -> Result<Self, InvalidParameter> {
        Ok(Self::FixedAndSprings { k_t: check("spring_stiffness", k_t, POSITIVE, "N/m")? })
    }
    /// The paper's label.
    pub fn label(&self) -> &'static str {
        match self {
            Self::BothFixed => "Con 1",
            Self::BothSprings { .. } => "Con 2",
            Self::FixedAndSprings { .. } => "Con 3",
        }
    }
    /// The spring stiffness k_T (N/m) of Con 2 and Con 3; `None` for Con 1.
    pub fn spring_stiffness(&self) -> Option<f64> {
        match *self {
            Self::BothFixed => None,
            Self::BothSprings { k_t } | Self::FixedAndSprings { k_t } => Some(k_t),
        }
    }
}

/// The impact position x is outside the beam [0, L].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("impact position x = {x} m is outside the plate [0, {length}] m")]
pub struct OutsideBeam {
    /// The requested impact position (m from the left end).
    pub x: f64,
    /// The beam length L (m).
    pub length: f64,
}

/// Why the beam model has no compliance at a point.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BeamError {
    /// The impact position is not on the beam.
    #[error(transparent)]
    Outside(#[from] OutsideBeam),
    /// A store of eqs. 10-12, 23 or 43-44 is not a finite non-negative number in f64 for
    /// this plate and support, although each parameter lies in its range: x²y²/(3EIL)
    /// overflows for sizes near 1e77 m and beyond, and (x² + y²)/(2L²k_T) for a k_T near
    /// the smallest subnormal. The values, not the model, are out of reach.
    #[error("the beam model's compliance is not representable for this plate and support: {0}")]
    Compliance(#[from] InvalidCompliance),
}

/// Bending compliance of a simply supported beam under its own load point,
/// x²y²/(3EIL): eqs. 10-12 with L² - x² - y² = 2xy. `ei` in N·m², lengths in m, result
/// in m/N.
pub fn simply_supported_compliance(ei: f64, length: f64, x: f64) -> f64 {
    let y = length - x;
    x * x * y * y / (3.0 * ei * length)
}

/// Compliance of the two end spring pairs of Con 2, (x² + y²)/(2L²k_T) (eq. 23), in m/N
/// for `k_t` in N/m.
pub fn spring_pairs_compliance(k_t: f64, length: f64, x: f64) -> f64 {
    let y = length - x;
    (x * x + y * y) / (2.0 * length * length * k_t)
}

/// The Con 3 decomposition (eqs. 31-44), written with s = 2k_T L³ and d = s + 3EI so
/// that neither k_T → 0 nor k_T → ∞ overflows.
struct Con3 {
    /// s/d, the share of the right-end reaction F_T carried by the springs (eq. 36).
    spring_share: f64,
    /// 3EI/d.
    cantilever_share: f64,
    d: f64,
}

impl Con3 {
    fn new(ei: f64, length: f64, k_t: f64) -> Self {
        let s = 2.0 * k_t * length.powi(3);
        let t = 3.0 * ei;
        let d = s + t;
        if s.is_infinite() && t.is_finite() {
            // s = 2k_T L³ beyond f64 (stiff springs on a long beam): the right end is held
            // like the fixed end, the springs carry all of F_T and the cantilever nothing.
            // The limits of s/d and 3EI/d are taken here because inf/inf would be NaN.
            Self { spring_share: 1.0, cantilever_share: t / s, d }
        } else {
            Self { spring_share: s / d, cantilever_share: t / d, d }
        }
    }
    /// Spring store W_T = ½ [2k_T L⁴x²/d²] P² (eq. 43).
    fn springs(&self, length: f64, x: f64) -> f64 {
        self.spring_share * length * x * x / self.d
    }
    /// Cantilever store W_X = ½ [6EI x² L/d²] P² (eq. 44).
    fn cantilever(&self, length: f64, x: f64) -> f64 {
        2.0 * self.cantilever_share * x * x * length / self.d
    }
    /// Cantilever deflection of the impact point per unit load, x³(3L - x)/(2Ld) (eq. 40).
    fn cantilever_deflection(&self, length: f64, x: f64) -> f64 {
        x.powi(3) * (3.0 * length - x) / (2.0 * length * self.d)
    }
    /// Force of each right-end spring per unit load, k_T L² x/d = (s/d) x/(2L) (eq. 36 / 2).
    fn spring_force(&self, length: f64, x: f64) -> f64 {
        self.spring_share * x / (2.0 * length)
    }
}

/// Compliance and stores of the beam model at impact position x (m from the left end).
///
/// - Con 1: C = x²y²/(3EIL) (eqs. 8-12), all plate bending.
/// - Con 2: the same bending plus the two spring pairs, (x² + y²)/(2L²k_T) (eqs. 21-23);
///   each spring carries half its end's reaction, y/(2L) and x/(2L) of P.
/// - Con 3: the simply supported bending, the right-end springs 2k_T L⁴x²/d² and the
///   cantilever 6EI x² L/d² with d = 2k_T L³ + 3EI (eqs. 31-44); the deflection per unit
///   load adds the cantilever's x³(3L - x)/(2Ld) (eq. 41).
///
/// Errors: x outside [0, L] or not finite, or a store that is not representable in f64
/// ([`BeamError::Compliance`]); never a panic.
pub fn beam_compliance(plate: &Plate, condition: Condition, x: f64) -> Result<PointCompliance, BeamError> {
    let length = plate.length();
    if !(x.is_finite() && (0.0..=length).contains(&x)) {
        return Err(OutsideBeam { x, length }.into());
    }
    let ei = plate.beam_bending_stiffness();
    let y = length - x;
    let bending = simply_supported_compliance(ei, length, x);
    let store = |name: &str, kind, compliance| Store { name: name.into(), kind, compliance };
    let spring = |name: &str, per_unit_load| SpringReaction { name: name.into(), per_unit_load };
    let (stores, springs, deflection) = match condition {
        Condition::BothFixed => (vec![store("bending", StoreKind::Plate, bending)], vec![], bending),
        Condition::BothSprings { k_t } => (
            vec![
                store("bending", StoreKind::Plate, bending),
                store("springs", StoreKind::Spring, spring_pairs_compliance(k_t, length, x)),
            ],
            // eq. 21: each of the two springs at an end carries half that end's reaction (eq. 8).
            vec![spring("left spring", y / (2.0 * length)), spring("right spring", x / (2.0 * length))],
            bending,
        ),
        Condition::FixedAndSprings { k_t } => {
            let c3 = Con3::new(ei, length, k_t);
            (
                vec![
                    store("simply supported bending", StoreKind::Plate, bending),
                    store("springs", StoreKind::Spring, c3.springs(length, x)),
                    store("cantilever bending", StoreKind::Plate, c3.cantilever(length, x)),
                ],
                vec![spring("right spring", c3.spring_force(length, x))],
                bending + c3.cantilever_deflection(length, x),
            )
        }
    };
    Ok(PointCompliance::new(stores, springs, deflection)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Elastic;
    use approx::assert_relative_eq;

    fn plate() -> Plate {
        Plate::new(0.4584, 0.36, 0.008, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap()
    }

    #[test]
    fn ends_of_a_fixed_beam_take_no_energy() {
        let p = plate();
        for x in [0.0, p.length()] {
            assert_eq!(beam_compliance(&p, Condition::BothFixed, x).unwrap().total(), 0.0);
        }
    }

    /// At x = 0 (or L) in Con 2 the load sits on one spring pair: C = 1/(2k_T).
    #[test]
    fn con2_end_is_one_spring_pair() {
        let p = plate();
        let k = 5.11545e8;
        for x in [0.0, p.length()] {
            let c = beam_compliance(&p, Condition::both_springs(k).unwrap(), x).unwrap();
            assert_relative_eq!(c.total(), 0.5 / k, max_relative = 1e-14);
        }
    }

    /// At x = L in Con 3 the simply supported part carries nothing and the spring and
    /// cantilever stores sum to L³(2k_T L³ + 6EI)/(2k_T L³ + 3EI)² (eqs. 43-44 at x = L).
    #[test]
    fn con3_at_right_end_by_hand() {
        let p = plate();
        let (k, l, ei) = (5.11545e8, p.length(), p.beam_bending_stiffness());
        let c = beam_compliance(&p, Condition::fixed_and_springs(k).unwrap(), l).unwrap();
        let d = 2.0 * k * l.powi(3) + 3.0 * ei;
        assert_relative_eq!(c.total(), l.powi(3) * (2.0 * k * l.powi(3) + 6.0 * ei) / (d * d), max_relative = 1e-14);
        // eq. 41 at x = L: L³/d for the cantilever tip.
        assert_relative_eq!(c.deflection_per_unit_load(), l.powi(3) / d, max_relative = 1e-14);
    }

    /// k_T → ∞ turns Con 2 and Con 3 into Con 1, with the spring parts falling as 1/k_T.
    #[test]
    fn stiff_springs_tend_to_fixed_ends() {
        let p = plate();
        let x = 0.3 * p.length();
        let c1 = beam_compliance(&p, Condition::BothFixed, x).unwrap().total();
        for k in [1e12, 1e15, 1e18, 1e300] {
            for cond in [Condition::both_springs(k).unwrap(), Condition::fixed_and_springs(k).unwrap()] {
                let c = beam_compliance(&p, cond, x).unwrap().total();
                assert!(c.is_finite());
                // Spring parts are O(L²/(k_T L²)) = O(1/k_T) against c1 ~ 1e-7 m/N.
                assert_relative_eq!(c, c1, max_relative = 10.0 / (k * c1));
            }
        }
    }

    #[test]
    fn soft_springs_stay_finite() {
        let p = plate();
        let c = beam_compliance(&p, Condition::fixed_and_springs(1e-300).unwrap(), 0.2).unwrap();
        assert!(c.total().is_finite());
    }

    /// Parameters that each pass their range check but whose stores overflow or divide by
    /// an underflowed k_T L² are an error, not a panic: sizes of 1e300 mm make x²y²
    /// infinite, a subnormal k_T makes (x² + y²)/(2L²k_T) infinite.
    #[test]
    fn unrepresentable_stores_are_errors() {
        let steel = Elastic::new(210e9, 0.3).unwrap();
        let huge = Plate::new(1e297, 1e297, 1e297, 7850.0, steel).unwrap();
        for cond in
            [Condition::BothFixed, Condition::both_springs(1e6).unwrap(), Condition::fixed_and_springs(1e6).unwrap()]
        {
            let e = beam_compliance(&huge, cond, 0.3e297).unwrap_err();
            assert!(matches!(e, BeamError::Compliance(_)), "{e}");
        }
        let tiny = Plate::new(1e-6, 1e-6, 1e-6, 7850.0, steel).unwrap();
        let denormal = Condition::both_springs(5e-324).unwrap();
        assert!(matches!(beam_compliance(&tiny, denormal, 0.5e-6), Err(BeamError::Compliance(_))));
    }

    /// Stiff springs on a long beam overflow s = 2k_T L³; Con 3 then takes the limit of
    /// held springs (Con 1's compliance) instead of inf/inf.
    #[test]
    fn con3_with_overflowing_spring_term_is_con1() {
        let p = Plate::new(1e5, 1.0, 0.01, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap();
        let x = 0.3e5;
        let c1 = beam_compliance(&p, Condition::BothFixed, x).unwrap().total();
        let c3 = beam_compliance(&p, Condition::fixed_and_springs(1e300).unwrap(), x).unwrap();
        assert_eq!(c3.total(), c1);
        assert_relative_eq!(c3.springs()[0].per_unit_load, x / (2.0 * p.length()), max_relative = 1e-15);
    }

    #[test]
    fn position_outside_plate_is_rejected() {
        let p = plate();
        for x in [-1e-9, 0.4585, f64::NAN] {
            assert!(beam_compliance(&p, Condition::BothFixed, x).is_err());
        }
    }

    /// Reactions sum to the load: Con 2 spring forces 2(y + x)/(2L) = 1.
    #[test]
    fn con2_reactions_sum_to_one() {
        let p = plate();
        let c = beam_compliance(&p, Condition::both_springs(1e6).unwrap(), 0.1).unwrap();
        let sum: f64 = c.springs().iter().map(|s| 2.0 * s.per_unit_load).sum();
        assert_relative_eq!(sum, 1.0, max_relative = 1e-15);
    }
}
