//! Hertz's law, P = Kδ^{3/2}: elastic, no damping, no memory. Its curve and its energy
//! (2/5)Kδ^{5/2} are also the elastic part of Flores's law and Thornton's law below yield.

use super::{ContactState, Law};
use analytic::Sphere;
use serde::Serialize;

/// Hertz, P = Kδ^{3/2}, no damping.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Hertz;

/// The Hertz force Kδ^{3/2}, as Kδ√δ (this runs every step, and δ√δ is cheaper than powf).
#[inline]
pub fn force(k: f64, delta: f64) -> f64 {
    k * delta * delta.sqrt()
}

/// The Hertz energy (2/5)Kδ^{5/2}, as (2/5)Kδ²√δ, without powf (this runs every step).
#[inline]
pub fn energy(k: f64, delta: f64) -> f64 {
    0.4 * k * delta * delta * delta.sqrt()
}

impl Law for Hertz {
    const KEY: &'static str = "hertz";
    const NAME: &'static str = "Hertz";
    const ELASTIC: bool = true;

    fn for_body(_: &Sphere) -> Self {
        Hertz
    }

    #[inline]
    fn loading(&self, c: &ContactState, delta: f64, _rate: f64) -> f64 {
        force(c.k, delta)
    }

    #[inline]
    fn energy(&self, c: &ContactState, delta: f64) -> f64 {
        energy(c.k, delta)
    }

    fn conserves(&self, _: &ContactState) -> bool {
        true
    }
}
