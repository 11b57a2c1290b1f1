//! Thornton's elastic-perfectly-plastic law (C. Thornton, J. Appl. Mech. 64 (1997) 383-386).
//!
//! With a = √(R δ) the contact radius and p₀ = 3P/(2πa²) the centre pressure of the Hertz
//! distribution, the contact is Hertzian, P = Kδ^{3/2}, until p₀ reaches the limiting
//! pressure p_y, at δ_y = (2πR p_y/(3K))² (K = (4/3)E*√R, so this is Thornton's
//! δ_y = (πp_y/2E*)²R). Beyond, the pressure is capped at p_y over a growing area and the
//! loading branch is P = P_y + πp_y R (δ - δ_y), P_y = Kδ_y^{3/2}; its slope πp_yR =
//! (3/2)Kδ_y^{1/2} is the Hertz slope at δ_y, so the force is C¹ there. Unloading from
//! (δ_m, P_m) is Hertzian with the enlarged radius R_p = 4E*a_m³/(3P_m) that carries P_m on
//! the contact radius a_m = √(Rδ_m): P = K_p (δ - δ_p)^{3/2}, δ_m - δ_p = a_m²/R_p =
//! P_m/(Kδ_m^{1/2}), K_p = P_m/(δ_m - δ_p)^{3/2}. δ_p is the permanent compression; the
//! energy then stored is (2/5)P(δ - δ_p), and the work beyond it is dissipated in plastic
//! flow.
//!
//! **Restitution on a rigid target.** With x = δ_m/δ_y and V = v/v_y, ½mv_y² = (2/5)P_yδ_y:
//! the work of loading, (2/5)P_yδ_y + P_yδ_y[(3/4)(x² - 1) - (x - 1)/2] = ½mv², gives
//! 15x² - 10x + 3 = 8V², x = (1 + 2Vs)/3 with s = √(6/5 - 1/(5V²)); the energy returned on
//! unloading, (2/5)P_m(δ_m - δ_p) = (2/5)P_yδ_y ((3x - 1)/2)² x^{-1/2}, gives
//! e² = s² (3/(1 + 2Vs))^{1/2}, i.e. Thornton's
//! e = (6√3/5)^{1/2} [1 - (1/6)(v_y/v)²]^{1/2} [(v_y/v)/((v_y/v) + 2√(6/5 - (1/5)(v_y/v)²))]^{1/4}
//! ([`thornton_restitution`]). It needs the yield at the *centre* pressure p₀ = p_y: were
//! the limit put on the mean pressure P/(πa²) the plastic slope would be 2/3 of the Hertz
//! slope and the restitution would be ((4V² + 1)/5)^{3/8}/V instead.
//!
//! **p_y from the rock's strength.** The paper's Drucker-Prager onset (eq. 51) is
//! δ_my = [2πRk/(K(6Θ₁ + √3Θ₂))]², where the Hertz mean pressure Kδ^{1/2}/(πR) equals
//! 2k/(6Θ₁ + √3Θ₂). Thornton's yield onset coincides with it, δ_y = δ_my, when
//! p_y = 3K√δ_my/(2πR) = 3k/(6Θ₁ + √3Θ₂) (Thornton's [`Law::for_body`]): the
//! centre pressure, 3/2 of that mean pressure, independent of R and of the plate's modulus.

use super::{hertz, ContactState, Law};
use analytic::{DruckerPrager, Sphere};
use serde::Serialize;
use std::cell::Cell;

/// Thornton's elastic-perfectly-plastic law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Thornton {
    /// Limiting (centre) contact pressure p_y, Pa.
    pub yield_pressure: f64,
    /// Effective radius R* (the sphere's radius on a flat plate), m.
    pub radius: f64,
}

impl Thornton {
    /// The yield compression δ_y = (2πR p_y/(3K))².
    pub fn yield_compression(&self, k: f64) -> f64 {
        let q = 2.0 * std::f64::consts::PI * self.radius * self.yield_pressure / (3.0 * k);
        q * q
    }
}

impl Law for Thornton {
    const KEY: &'static str = "thornton";
    const NAME: &'static str = "Thornton's elastic-perfectly-plastic law";
    const ELASTIC: bool = false;

    /// δ_y = δ_my of eq. 51: p_y = 3k/(6Θ₁ + √3Θ₂) (see the module).
    fn for_body(body: &Sphere) -> Self {
        let dp = DruckerPrager::of(body);
        let p_y = 3.0 * dp.k / (6.0 * dp.theta1 + 3f64.sqrt() * dp.theta2);
        Thornton { yield_pressure: p_y, radius: body.radius() }
    }

    #[inline]
    fn loading(&self, c: &ContactState, delta: f64, _rate: f64) -> f64 {
        loading(c.k, self.yield_compression(c.k), delta)
    }

    /// The Hertz curve itself if δ_m never passed yield, else the unloading curve from δ_m.
    #[inline]
    fn unloading(&self, c: &ContactState, delta: f64, _rate: f64) -> f64 {
        let (dy, dm) = (self.yield_compression(c.k), c.max_compression);
        if dm <= dy {
            return hertz::force(c.k, delta);
        }
        let (dp, kp) = unloading(c.k, dy, dm);
        if delta <= dp {
            0.0
        } else {
            kp * (delta - dp).powf(1.5)
        }
    }

    /// (2/5)Kδ^{5/2} below yield, (2/5)K_p(δ - δ_p)^{5/2} after it (δ_m at least δ).
    #[inline]
    fn energy(&self, c: &ContactState, delta: f64) -> f64 {
        let (dy, dm) = (self.yield_compression(c.k), c.max_compression.max(delta));
        if dm > dy {
            let (dp, kp) = unloading(c.k, dy, dm);
            if delta <= dp {
                0.0
            } else {
                0.4 * kp * (delta - dp).powf(2.5)
            }
        } else {
            hertz::energy(c.k, delta)
        }
    }

    #[inline]
    fn permanent_set(&self, c: &ContactState) -> f64 {
        let dy = self.yield_compression(c.k);
        if c.max_compression > dy {
            unloading(c.k, dy, c.max_compression).0
        } else {
            0.0
        }
    }

    fn conserves(&self, _: &ContactState) -> bool {
        false
    }
}

/// Thornton's virgin loading curve: Kδ^{3/2} up to δ_y, then P_y + πp_yR(δ - δ_y) with
/// πp_yR = (3/2)Kδ_y^{1/2}.
fn loading(k: f64, dy: f64, delta: f64) -> f64 {
    if delta <= dy {
        hertz::force(k, delta)
    } else {
        let py = hertz::force(k, dy);
        py + 1.5 * k * dy.sqrt() * (delta - dy)
    }
}

/// An unloading curve (δ_p, K_p) by the bits of the (K, δ_y, δ_m) it was formed from.
type KeptCurve = Option<([u64; 3], (f64, f64))>;

thread_local! {
    /// The unloading curve last formed on this thread.
    static LAST_CURVE: Cell<KeptCurve> = const { Cell::new(None) };
}

/// (δ_p, K_p) of the unloading curve from δ_m > δ_y ([`unloading_curve`]). A contact's
/// force is solved at many compressions on the same curve (δ_m fixed within a step), so the
/// curve last formed is kept: the same numbers, without its power.
fn unloading(k: f64, dy: f64, dm: f64) -> (f64, f64) {
    let key = [k.to_bits(), dy.to_bits(), dm.to_bits()];
    LAST_CURVE.with(|last| match last.get() {
        Some((at, curve)) if at == key => curve,
        _ => {
            let curve = unloading_curve(k, dy, dm);
            last.set(Some((key, curve)));
            curve
        }
    })
}

/// (δ_p, K_p) of the unloading curve from δ_m > δ_y: δ_m - δ_p = P_m/(Kδ_m^{1/2}) (the
/// contact radius √(Rδ_m) carried over to the radius R_p), K_p = P_m/(δ_m - δ_p)^{3/2}.
fn unloading_curve(k: f64, dy: f64, dm: f64) -> (f64, f64) {
    let pm = loading(k, dy, dm);
    let elastic = pm / (k * dm.sqrt());
    (dm - elastic, pm / elastic.powf(1.5))
}

/// Thornton's restitution of a sphere on a rigid target at v/v_y = `ratio` (1 for ratio ≤ 1).
pub fn thornton_restitution(ratio: f64) -> f64 {
    if ratio <= 1.0 {
        return 1.0;
    }
    let y = 1.0 / ratio;
    let s = (1.2 - 0.2 * y * y).sqrt();
    (6.0 * 3f64.sqrt() / 5.0).sqrt() * (1.0 - y * y / 6.0).sqrt() * (y / (y + 2.0 * s)).powf(0.25)
}
