//! The paper's law (Flores, eqs. 1-2): P = Kδ^{3/2}(1 + 8(1-e)/(5e) δ̇/δ̇⁻), never negative,
//! with δ̇⁻ the contact's approach velocity: v₀ for the first contact (the paper's form), the
//! relative velocity at touch for a later one, as Flores et al. define it per contact.
//! Elastic with hysteretic damping: the damping term vanishes at maximum compression
//! (δ̇ = 0) and takes work on both loading and unloading, so the law conserves energy only
//! at e ≥ 1. It has no memory; the energy it holds is the Hertz part, (2/5)Kδ^{5/2}.

use super::{hertz, ContactState, Law};
use analytic::contact::flores_force;
use analytic::Sphere;
use serde::Serialize;

/// Flores (eqs. 1-2) with the striker's restitution e and the contact's approach velocity.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Flores;

impl Law for Flores {
    const KEY: &'static str = "flores";
    const NAME: &'static str = "Flores";
    const ELASTIC: bool = true;

    fn for_body(_: &Sphere) -> Self {
        Flores
    }

    #[inline]
    fn loading(&self, c: &ContactState, delta: f64, rate: f64) -> f64 {
        flores_force(c.k, c.restitution, delta, rate, c.velocity).max(0.0)
    }

    #[inline]
    fn energy(&self, c: &ContactState, delta: f64) -> f64 {
        hertz::energy(c.k, delta)
    }

    fn conserves(&self, c: &ContactState) -> bool {
        c.restitution >= 1.0
    }
}
