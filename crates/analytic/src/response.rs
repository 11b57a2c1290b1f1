//! Responses at maximum compression (section II, eqs. 20, 28-30, 11, 41) and the energy
//! split over E₀ = ½mv² (Figs. 10, 13).

use crate::balance::{EnergyBalance, Method, NotConverged, Solution};
use crate::compliance::{PointCompliance, StoreKind};
use crate::contact::{rock_energy_stored, rock_energy_total};
use crate::params::{check, InvalidParameter, POSITIVE, RESTITUTION};
use serde::Serialize;

/// One impact: the contact stiffness, the sphere, the restitution and the velocity.
///
/// [`Impact::new`] is the checked way to build one. The fields stay public so that an
/// impact can be written literally or copied with one field changed, but such a value is
/// not checked: with v = 0 the balance has E₀ = 0 and no positive root (its solvers then
/// return [`NotConverged`]), and with e = 0 eq. 7 divides by zero.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Impact {
    /// K of eq. 3 (N/m^{3/2}), positive.
    pub contact_stiffness: f64,
    /// m (kg), positive.
    pub mass: f64,
    /// e in (0, 1].
    pub restitution: f64,
    /// v (m/s), positive.
    pub velocity: f64,
}

impl Impact {
    /// An impact with every value checked against its range in [`crate::params`]: K, m and
    /// v positive and finite, e in (0, 1]. A sphere at rest (v = 0) is an input error here,
    /// not a balance with E₀ = 0 whose relative residual would be 0/0.
    pub fn new(contact_stiffness: f64, mass: f64, restitution: f64, velocity: f64) -> Result<Self, InvalidParameter> {
        Ok(Self {
            contact_stiffness: check("contact_stiffness", contact_stiffness, POSITIVE, "N/m^(3/2)")?,
            mass: check("mass", mass, POSITIVE, "kg")?,
            restitution: check("restitution", restitution, RESTITUTION, "")?,
            velocity: check("velocity", velocity, POSITIVE, "m/s")?,
        })
    }

    /// Kinetic energy E₀ = ½ m v².
    pub fn energy(&self) -> f64 {
        0.5 * self.mass * self.velocity * self.velocity
    }
    /// The balance of eq. 14/25/46 for a plate of total compliance `c`.
    pub fn balance(&self, c: f64) -> EnergyBalance {
        EnergyBalance::new(self.contact_stiffness, self.restitution, c, self.mass, self.velocity)
    }
}

/// A spring force at maximum compression.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpringForce {
    /// Which spring, as in [`crate::SpringReaction::name`].
    pub name: String,
    /// N.
    pub force: f64,
}

/// Everything the paper reports at maximum compression.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Response {
    /// P_max = K δ_max^{3/2} (eq. 20).
    pub contact_force: f64,
    /// δ_max (m).
    pub compression: f64,
    /// Plate deflection at the impact point (eq. 11; eq. 41 in Con 3), m.
    pub deflection: f64,
    /// Spring forces (eqs. 29-30, 36), N.
    pub spring_forces: Vec<SpringForce>,
    /// (2K/5e)δ^{5/2}/E₀: energy absorbed and dissipated by the rock (eq. 7).
    pub rock_total_ratio: f64,
    /// (2K/5)δ^{5/2}/E₀: elastic energy stored in the rock.
    pub rock_stored_ratio: f64,
    /// Plate strain energy over E₀.
    pub plate_ratio: f64,
    /// Spring energy over E₀.
    pub spring_ratio: f64,
    /// How the balance was solved.
    pub solution: Solution,
}

/// Solves the balance for `impact` on a plate of compliance `c` and evaluates the responses.
pub fn respond(impact: &Impact, c: &PointCompliance, method: Method) -> Result<Response, NotConverged> {
    let solution = impact.balance(c.total()).solve(method)?;
    Ok(evaluate(impact, c, solution))
}

/// The responses at a known maximum compression.
pub fn evaluate(impact: &Impact, c: &PointCompliance, solution: Solution) -> Response {
    let k = impact.contact_stiffness;
    let delta = solution.delta;
    let p = k * delta.powf(1.5);
    let e0 = impact.energy();
    let store_ratio = |kind| 0.5 * c.of_kind(kind) * p * p / e0;
    Response {
        contact_force: p,
        compression: delta,
        deflection: c.deflection_per_unit_load() * p,
        spring_forces: c
            .springs()
            .iter()
            .map(|s| SpringForce { name: s.name.clone(), force: s.per_unit_load * p })
            .collect(),
        rock_total_ratio: rock_energy_total(k, impact.restitution, delta) / e0,
        rock_stored_ratio: rock_energy_stored(k, delta) / e0,
        plate_ratio: store_ratio(StoreKind::Plate),
        spring_ratio: store_ratio(StoreKind::Spring),
        solution,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_velocity_is_an_input_error() {
        let e = Impact::new(5.11545e8, 0.09, 0.65, 0.0).unwrap_err();
        assert_eq!(e.name, "velocity");
        assert!(e.to_string().contains("velocity"), "{e}");
    }

    #[test]
    fn every_value_is_checked() {
        let ok = (5.11545e8, 0.09, 0.65, 0.008);
        assert!(Impact::new(ok.0, ok.1, ok.2, ok.3).is_ok());
        assert!(Impact::new(ok.0, ok.1, 1.0, ok.3).is_ok());
        let cases = [
            ("contact_stiffness", Impact::new(0.0, ok.1, ok.2, ok.3)),
            ("contact_stiffness", Impact::new(f64::INFINITY, ok.1, ok.2, ok.3)),
            ("mass", Impact::new(ok.0, -1.0, ok.2, ok.3)),
            ("mass", Impact::new(ok.0, f64::NAN, ok.2, ok.3)),
            ("restitution", Impact::new(ok.0, ok.1, 0.0, ok.3)),
            ("restitution", Impact::new(ok.0, ok.1, 1.01, ok.3)),
            ("velocity", Impact::new(ok.0, ok.1, ok.2, -0.008)),
            ("velocity", Impact::new(ok.0, ok.1, ok.2, f64::NAN)),
        ];
        for (name, r) in cases {
            assert_eq!(r.unwrap_err().name, name);
        }
    }

    /// A literal impact with v = 0 bypasses the check; the balance then refuses to solve
    /// instead of returning a NaN compression.
    #[test]
    fn unchecked_zero_velocity_is_not_converged() {
        let imp = Impact { contact_stiffness: 5.11545e8, mass: 0.09, restitution: 0.65, velocity: 0.0 };
        let c = PointCompliance::new(vec![], vec![], 0.0).unwrap();
        assert!(respond(&imp, &c, Method::default()).is_err());
    }
}
