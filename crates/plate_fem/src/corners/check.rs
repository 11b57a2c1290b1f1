//! The a-posteriori check every corner response passes before it is returned (module
//! docs of [`super`]): finite values, non-negative stores that add up to C within the
//! round-off of the terms that cancelled, equilibrium with free edges, and for the update
//! a well-conditioned 4 x 4 solve.

use super::{Audit, BasePoint, CornerFamily, EQUILIBRIUM_TOLERANCE, ROUNDOFF_ULPS, UPDATE_SOLVE_BOUND};
use crate::model::PointResponse;
use crate::supports::{Corner, CornerSupport, EdgeSupport};
use crate::FemError;

impl CornerFamily<'_> {
    /// The a-posteriori check (module docs).
    pub(super) fn check(
        &self,
        p: &BasePoint,
        corners: &[CornerSupport; 4],
        r: &PointResponse,
        a: &Audit,
    ) -> Result<(), FemError> {
        let eps = f64::EPSILON;
        let springs: f64 = r.corners.iter().map(|c| c.spring_compliance).sum();
        let fail = |what: String| Err(self.failure(corners, what));
        let finite = r.compliance.is_finite()
            && r.plate_compliance.is_finite()
            && r.corners.iter().all(|c| c.reaction.is_finite() && c.spring_compliance.is_finite());
        if !finite {
            return fail(format!(
                "non-finite result (C = {:e} m/N, plate store {:e} m/N) at (x = {}, z = {}) m",
                r.compliance, r.plate_compliance, p.x, p.z
            ));
        }
        if let Some((i, c)) = r.corners.iter().enumerate().find(|(_, c)| c.spring_compliance < 0.0) {
            return fail(format!("negative spring store {:e} m/N at {}", c.spring_compliance, Corner::ALL[i].name()));
        }
        let allowance = ROUNDOFF_ULPS * eps * (a.scale + springs);
        if r.compliance < -allowance {
            return fail(format!(
                "negative compliance C = {:e} m/N under a positive load at (x = {}, z = {}) m (round-off allowance {:e})",
                r.compliance, p.x, p.z, allowance
            ));
        }
        if r.plate_compliance < -allowance {
            return fail(format!(
                "negative plate store {:e} m/N at (x = {}, z = {}) m (C = {:e} m/N, spring stores {:e} m/N, round-off allowance {:e})",
                r.plate_compliance, p.x, p.z, r.compliance, springs, allowance
            ));
        }
        let bookkeeping = (r.compliance - r.plate_compliance - springs).abs();
        if bookkeeping > allowance.max(ROUNDOFF_ULPS * eps * r.compliance.abs()) {
            return fail(format!(
                "stores do not add up: C = {:e} m/N, plate {:e} m/N, springs {:e} m/N",
                r.compliance, r.plate_compliance, springs
            ));
        }
        if self.edges == [EdgeSupport::Free; 4] {
            let sum = r.total_reaction();
            if (sum - 1.0).abs() > EQUILIBRIUM_TOLERANCE {
                return fail(format!(
                    "reactions sum to {sum} of the unit load at (x = {}, z = {}) m (allowed error {EQUILIBRIUM_TOLERANCE:e})",
                    p.x, p.z
                ));
            }
        }
        if let Some((cond, residual)) = a.system {
            if cond.is_nan() || cond * eps > UPDATE_SOLVE_BOUND {
                return fail(format!(
                    "the 4 x 4 update matrix has condition {cond:e}: its solve may keep fewer than {:.0} digits",
                    -(UPDATE_SOLVE_BOUND.log10())
                ));
            }
            if residual.is_nan() || residual > ROUNDOFF_ULPS * eps {
                return fail(format!("the 4 x 4 update solve has relative residual {residual:e}"));
            }
        }
        Ok(())
    }
}
