//! The paper's beam model of the supported plate (section II): the plate is a beam of
//! bending stiffness E₂I₂ = E B h³/12 along its length L, loaded at x from the left end,
//! y = L - x from the right end.

use crate::compliance::{PointCompliance, SpringReaction, Store, StoreKind};
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
    BothSprings { k_t: f64 },
    /// Con 3: left end fixed, right end on two springs of stiffness `k_t` each.
    FixedAndSprings { k_t: f64 },
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
    pub x: f64,
    pub length: f64,
}

/// Bending compliance of a simply supported beam under its own load point,
/// x²y²/(3EIL): eqs. 10-12 with L² - x² - y² = 2xy.
pub fn simply_supported_compliance(ei: f64, length: f64, x: f64) -> f64 {
    let y = length - x;
    x * x * y * y / (3.0 * ei * length)
}

/// Compliance of the two end spring pairs of Con 2, (x² + y²)/(2L²k_T) (eq. 23).
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
        Self { spring_share: s / d, cantilever_share: t / d, d }
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
pub fn beam_compliance(plate: &Plate, condition: Condition, x: f64) -> Result<PointCompliance, OutsideBeam> {
    let length = plate.length();
    if !(x.is_finite() && (0.0..=length).contains(&x)) {
        return Err(OutsideBeam { x, length });
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
    Ok(PointCompliance::new(stores, springs, deflection)
        .expect("beam stores are finite and non-negative for valid inputs"))
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
