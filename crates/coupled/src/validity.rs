//! Whether a result is inside the assumptions of the model that produced it.
//!
//! Beyond validity a number is still computed and printed, with its flag. Four criteria:
//!
//! - **Elastic range** (eqs. 51-54): the contact stays elastic while δ_max ≤ δ_my, the
//!   Drucker-Prager compression of eq. 51. Because δ_max grows monotonically with v, this
//!   is the same test as v ≤ v_y of the same model, and it applies to the transient model
//!   too.
//! - **Quasi-static validity**: the balance of eq. 14 assumes the plate deforms statically
//!   during contact, which needs the contact time t_c not small against the plate's
//!   fundamental period T₁. The transient study measured the quasi-static force off by 5 %
//!   to 70 % at t_c/T₁ = 0.05-0.12 on the paper's plate, and within about 3 % above 0.2 for
//!   the coal sphere on plates of other sizes and thicknesses. t_c here is the Hertz time on a
//!   rigid target, a lower bound of the real contact time. The regime map (heavier spheres,
//!   corner springs over five decades) shows the ratio alone is not enough: below 0.2 a thick
//!   plate is still quasi-static (the contact is the softer spring), and above it a heavy
//!   sphere can be off by up to 32 %; the regime rule beside it covers both.
//! - **Thin-plate range**: Kirchhoff theory leaves out transverse shear and the 3-D
//!   compliance under the load. Against shell and solid elements the paper's plate
//!   (h/B = 0.022) is +1 % at the centre and +3 % at the middle of an end; the neglected
//!   terms grow like (h/B)², so h/min(L, B) ≤ 0.05 keeps them to a few percent.
//! - **Re-contact** (transient only): the run follows the impact until the sphere has
//!   provably left; if it struck more than once, the first contact's numbers (the paper's
//!   quantities) do not describe the whole impact.
//! - **Impact finished** (transient only): the run ends when the stopping rule proves that no
//!   further contact can occur, or at the end of its window. A run whose window ended first
//!   has not shown the whole impact: a later contact may still follow, so its contact count,
//!   total impulse and final velocity are those of the window, not of the impact.
//! - **Discretisation** (transient, per-case tolerance): the error estimate of P_max and the
//!   contact time is within the tolerance the discretisation was chosen for; where the ladder's
//!   budget ran out first, the numbers are less accurate than asked.
//! - **Regime rule** (quasi-static models): the closed-form rule of [`crate::regimes`]
//!   bounds the balance's force error from t_H, a closed-form T₁ and Christoforou and
//!   Yigit's λ and ζ; valid where the bound is at most 3 %. On the measured regime map it
//!   trusted no case whose error exceeded 3 %, where t_c/T₁ ≥ 0.2 alone trusted cases off by
//!   up to 32 % (heavy spheres whose contact lasts about one plate period, the plate
//!   deflecting more than statically): a row is inside both only where both hold.

use serde::Serialize;

/// t_c/T₁ at and above which the quasi-static balance is within about 3 % (measured).
pub const QUASI_STATIC_MIN_RATIO: f64 = 0.2;
/// Largest h/min(L, B) of the thin-plate range.
pub const THIN_PLATE_MAX_RATIO: f64 = 0.05;
/// Largest h/min(L, B) of the moderately thick range of Reissner-Mindlin (first-order shear)
/// theory: side-to-thickness ratios down to 5, where it stays within a few per cent of
/// three-dimensional elasticity for the deflection (Reddy, *Theory and Analysis of Elastic
/// Plates and Shells*, 2nd ed., §10.2).
pub const MINDLIN_PLATE_MAX_RATIO: f64 = 0.2;

/// One criterion: a measured ratio against its limit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Criterion {
    /// What is measured, e.g. "δ_max/δ_my".
    pub measure: &'static str,
    /// Its value for this result.
    pub value: f64,
    /// The limit.
    pub limit: f64,
    /// Whether the result is inside the model's assumptions.
    pub valid: bool,
}

impl Criterion {
    /// Valid while `value` ≤ `limit`.
    pub fn at_most(measure: &'static str, value: f64, limit: f64) -> Self {
        Self { measure, value, limit, valid: value <= limit }
    }
    /// Valid while `value` ≥ `limit`.
    pub fn at_least(measure: &'static str, value: f64, limit: f64) -> Self {
        Self { measure, value, limit, valid: value >= limit }
    }
}

/// The validity of one result.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Validity {
    /// δ_max/δ_my ≤ 1 (responses); absent for yield rows, which sit on the limit.
    pub elastic: Option<Criterion>,
    /// t_c/T₁ ≥ 0.2, for quasi-static models.
    pub quasi_static: Option<Criterion>,
    /// h/min(L, B) ≤ 0.05.
    pub thin_plate: Criterion,
    /// The number of contacts (transient only), valid while 1.
    pub recontact: Option<Criterion>,
    /// The closed-form regime rule ([`crate::regimes::rule`]) for quasi-static models: its
    /// bound on the balance's force error, valid at most 3 %.
    pub regime: Option<Criterion>,
    /// Whether the transient run proved the sphere gone before its window ended ([`finished`]).
    pub finished: Option<Criterion>,
    /// The transient error estimate against the tolerance it was chosen for ([`discretisation`]).
    pub discretisation: Option<Criterion>,
}

impl Validity {
    /// Every criterion that applies, in a fixed order, with its short name.
    pub fn criteria(&self) -> Vec<(&'static str, Criterion)> {
        let mut out = Vec::new();
        if let Some(c) = self.elastic {
            out.push(("elastic", c));
        }
        if let Some(c) = self.quasi_static {
            out.push(("quasi-static", c));
        }
        if let Some(c) = self.regime {
            out.push(("regime rule", c));
        }
        out.push(("thin plate", self.thin_plate));
        if let Some(c) = self.recontact {
            out.push(("re-contact", c));
        }
        if let Some(c) = self.finished {
            out.push(("impact finished", c));
        }
        if let Some(c) = self.discretisation {
            out.push(("discretisation", c));
        }
        out
    }

    /// Whether every applicable criterion holds.
    pub fn all_valid(&self) -> bool {
        self.criteria().iter().all(|(_, c)| c.valid)
    }

    /// The names of the criteria that fail ("beyond elastic range", ...).
    pub fn flags(&self) -> Vec<&'static str> {
        self.criteria().into_iter().filter(|(_, c)| !c.valid).map(|(name, _)| flag_of(name)).collect()
    }
}

/// The flag of a failed criterion, by the criterion's short name in [`Validity::criteria`].
fn flag_of(name: &str) -> &'static str {
    match name {
        "elastic" => FLAG_ELASTIC,
        "quasi-static" => FLAG_QUASI_STATIC,
        "thin plate" => FLAG_THIN_PLATE,
        "regime rule" => FLAG_REGIME,
        "impact finished" => FLAG_UNFINISHED,
        "discretisation" => FLAG_DISCRETISATION,
        _ => FLAG_RECONTACT,
    }
}

/// The flag of a result beyond the elastic range.
pub const FLAG_ELASTIC: &str = "beyond elastic range";
/// The flag of a quasi-static result whose contact is short against T₁.
pub const FLAG_QUASI_STATIC: &str = "not quasi-static";
/// The flag of a plate too thick for its plate theory (Kirchhoff's or the beam's, or
/// Reissner-Mindlin's).
pub const FLAG_THIN_PLATE: &str = "beyond the plate theory's range";
/// The flag of a quasi-static result the regime rule does not trust.
pub const FLAG_REGIME: &str = "outside the quasi-static regime rule";
/// The flag of a transient impact with more than one contact.
pub const FLAG_RECONTACT: &str = "re-contact";
/// The flag of a transient run whose window ended before the sphere had provably left.
pub const FLAG_UNFINISHED: &str = "impact not finished in the window";
/// The flag of a transient case whose error estimate stayed above its tolerance.
pub const FLAG_DISCRETISATION: &str = "discretisation error above tolerance";

/// The impact-finished criterion: valid when the stopping rule proved the sphere gone
/// (`left`), failed when the window ended first (value 1: unfinished).
pub fn finished(left: bool) -> Criterion {
    Criterion::at_most("unfinished at the end of the window (1 = yes)", if left { 0.0 } else { 1.0 }, 0.0)
}

/// The discretisation criterion: the relative error `estimate` of P_max and the contact time
/// against the `tolerance` the discretisation was chosen for.
pub fn discretisation(estimate: f64, tolerance: f64) -> Criterion {
    Criterion::at_most("error estimate on P_max and t_c (relative)", estimate, tolerance)
}

/// The thin-plate criterion for a plate of thickness `h`, length `l` and width `b`.
pub fn thin_plate(h: f64, l: f64, b: f64) -> Criterion {
    Criterion::at_most("h/min(L, B)", h / l.min(b), THIN_PLATE_MAX_RATIO)
}

/// The Reissner-Mindlin range for a plate of thickness `h`, length `l` and width `b`.
pub fn moderately_thick_plate(h: f64, l: f64, b: f64) -> Criterion {
    Criterion::at_most("h/min(L, B)", h / l.min(b), MINDLIN_PLATE_MAX_RATIO)
}

/// The quasi-static criterion for a contact time `t_c` and fundamental period `t1`.
pub fn quasi_static(t_c: f64, t1: f64) -> Criterion {
    Criterion::at_least("t_c/T₁", t_c / t1, QUASI_STATIC_MIN_RATIO)
}

/// The elastic-range criterion for a maximum compression `delta` and the yield
/// compression `delta_my` of eq. 51.
pub fn elastic(delta: f64, delta_my: f64) -> Criterion {
    Criterion::at_most("δ_max/δ_my", delta / delta_my, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn criteria_flip_at_their_limits() {
        assert!(elastic(0.99, 1.0).valid && !elastic(1.01, 1.0).valid);
        assert!(quasi_static(0.21, 1.0).valid && !quasi_static(0.19, 1.0).valid);
        assert!(thin_plate(0.008, 0.4584, 0.36).valid);
        assert!(!thin_plate(0.5, 0.4584, 0.36).valid);
        assert!(finished(true).valid && !finished(false).valid);
        assert!(discretisation(1e-4, 1e-4).valid && !discretisation(1.1e-4, 1e-4).valid);
    }

    /// Every failed criterion is named by its own flag, and a run that did not finish or did
    /// not reach its tolerance is not valid.
    #[test]
    fn unfinished_and_inaccurate_runs_are_flagged() {
        let base = Validity {
            elastic: None,
            quasi_static: None,
            thin_plate: thin_plate(0.008, 0.4584, 0.36),
            recontact: Some(Criterion::at_most("contacts", 1.0, 1.0)),
            regime: None,
            finished: Some(finished(true)),
            discretisation: Some(discretisation(5e-5, 1e-4)),
        };
        assert!(base.all_valid() && base.flags().is_empty());
        let open = Validity { finished: Some(finished(false)), ..base };
        assert!(!open.all_valid());
        assert_eq!(open.flags(), vec![FLAG_UNFINISHED]);
        let coarse = Validity { discretisation: Some(discretisation(4.5e-4, 1e-4)), ..base };
        assert_eq!(coarse.flags(), vec![FLAG_DISCRETISATION]);
    }
}
