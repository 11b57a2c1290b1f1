//! Support sets: what holds each corner (fixed, a spring of its own stiffness, free) and
//! each edge (free, simply supported, clamped) of the plate, with a name.
//!
//! The plate model takes any set that leaves no rigid-body motion free. The paper's beam
//! model (section II) describes only three of them, its Con 1-3: [`SupportSet::beam_condition`]
//! recognises those and answers `None` for every other set, so the beam model can say
//! "not applicable" instead of answering a different question.

use analytic::Condition;
use plate_fem::{CornerSupport, EdgeSupport, Supports};
use serde::Serialize;

/// A named support set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SupportSet {
    /// The name the scene gave it ("Con 1", "clamped left edge", ...).
    pub name: String,
    /// Corners in the order (0, 0), (L, 0), (0, B), (L, B); edges x = 0, x = L, z = 0, z = B.
    pub supports: Supports,
}

impl SupportSet {
    /// A set with a name.
    pub fn new(name: impl Into<String>, supports: Supports) -> Self {
        Self { name: name.into(), supports }
    }

    /// One of the paper's conditions as a support set of the plate: the beam's two ends
    /// are the plate's edges x = 0 and x = L, each held at its two corners (Fig. 3).
    pub fn preset(name: impl Into<String>, condition: Condition) -> Self {
        Self::new(name, corner_supports(condition))
    }

    /// The paper's condition this set is, if it is one of Con 1-3: all edges free, and the
    /// corners of each end both fixed or both on springs of one stiffness, the same at both
    /// ends in Con 2 (eqs. 21-30) and only at the right end in Con 3 (eqs. 31-44).
    pub fn beam_condition(&self) -> Option<Condition> {
        use CornerSupport::{Fixed, Spring};
        let s = &self.supports;
        if s.edges != [EdgeSupport::Free; 4] {
            return None;
        }
        match s.corners {
            [Fixed, Fixed, Fixed, Fixed] => Some(Condition::BothFixed),
            [Spring(a), Spring(b), Spring(c), Spring(d)] if a == b && a == c && a == d => {
                Some(Condition::BothSprings { k_t: a })
            }
            [Fixed, Spring(b), Fixed, Spring(d)] if b == d => Some(Condition::FixedAndSprings { k_t: b }),
            _ => None,
        }
    }

    /// Stiffnesses of the set's corner springs, N/m.
    pub fn spring_stiffnesses(&self) -> impl Iterator<Item = f64> + '_ {
        self.supports.corners.iter().filter_map(|c| match *c {
            CornerSupport::Spring(k) => Some(k),
            _ => None,
        })
    }

    /// Whether any corner is on a spring.
    pub fn has_springs(&self) -> bool {
        self.spring_stiffnesses().next().is_some()
    }
}

/// The paper's conditions on the plate's four corners (Fig. 3): Con 1 all fixed, Con 2 all
/// on springs, Con 3 fixed at x = 0 and on springs at x = L.
pub fn corner_supports(condition: Condition) -> Supports {
    use CornerSupport::*;
    Supports::corners(match condition {
        Condition::BothFixed => [Fixed; 4],
        Condition::BothSprings { k_t } => [Spring(k_t); 4],
        Condition::FixedAndSprings { k_t } => [Fixed, Spring(k_t), Fixed, Spring(k_t)],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_recognised_and_others_are_not() {
        for c in [Condition::BothFixed, Condition::BothSprings { k_t: 3e8 }, Condition::FixedAndSprings { k_t: 2e7 }] {
            assert_eq!(SupportSet::preset("c", c).beam_condition(), Some(c));
        }
        use CornerSupport::*;
        let unequal = Supports::corners([Spring(1e8), Spring(2e8), Spring(1e8), Spring(2e8)]);
        assert_eq!(SupportSet::new("u", unequal).beam_condition(), None);
        let mirrored = Supports::corners([Spring(1e8), Fixed, Spring(1e8), Fixed]);
        assert_eq!(SupportSet::new("m", mirrored).beam_condition(), None);
        let edge = Supports {
            edges: [EdgeSupport::Clamped, EdgeSupport::Free, EdgeSupport::Free, EdgeSupport::Free],
            ..Supports::con1()
        };
        assert_eq!(SupportSet::new("e", edge).beam_condition(), None);
    }
}
