//! The contact laws the transient model offers: Hertz (elastic), Flores (eqs. 1-2, the
//! paper's, elastic with hysteretic damping) and Thornton's elastic-perfectly-plastic law.
//!
//! **Thornton's law** (C. Thornton, J. Appl. Mech. 64 (1997) 383-386). With a = √(R δ) the
//! contact radius and p₀ = 3P/(2πa²) the centre pressure of the Hertz distribution, the
//! contact is Hertzian, P = Kδ^{3/2}, until p₀ reaches the limiting pressure p_y, at
//! δ_y = (2πR p_y/(3K))² (K = (4/3)E*√R, so this is Thornton's δ_y = (πp_y/2E*)²R). Beyond,
//! the pressure is capped at p_y over a growing area and the loading branch is
//! P = P_y + πp_y R (δ - δ_y), P_y = Kδ_y^{3/2}; its slope πp_yR = (3/2)Kδ_y^{1/2} is the Hertz
//! slope at δ_y, so the force is C¹ there. Unloading from (δ_m, P_m) is Hertzian with the
//! enlarged radius R_p = 4E*a_m³/(3P_m) that carries P_m on the contact radius a_m = √(Rδ_m):
//! P = K_p (δ - δ_p)^{3/2}, δ_m - δ_p = a_m²/R_p = P_m/(Kδ_m^{1/2}), K_p = P_m/(δ_m - δ_p)^{3/2}.
//! δ_p is the permanent compression; the energy then stored is (2/5)P(δ - δ_p), and the
//! work beyond it is dissipated in plastic flow.
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
//! p_y = 3K√δ_my/(2πR) = 3k/(6Θ₁ + √3Θ₂) ([`ContactLaw::thornton_for`]): the centre
//! pressure, 3/2 of that mean pressure, independent of R and of the plate's modulus.

use analytic::contact::flores_force;
use analytic::{DruckerPrager, Sphere};
use serde::{Deserialize, Serialize};

/// Which contact law a scene asks for.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum LawKind {
    /// The paper's Flores law (eqs. 1-2).
    #[default]
    Flores,
    /// Hertz, P = Kδ^{3/2}, no damping.
    Hertz,
    /// Thornton's elastic-perfectly-plastic law, p_y from the rock's strength.
    Thornton,
}

impl LawKind {
    /// The name used in scene files.
    pub fn key(self) -> &'static str {
        match self {
            LawKind::Flores => "flores",
            LawKind::Hertz => "hertz",
            LawKind::Thornton => "thornton",
        }
    }

    /// Whether the law is elastic, so that compressions beyond δ_my leave its range.
    pub fn is_elastic(self) -> bool {
        !matches!(self, LawKind::Thornton)
    }

    /// The law for `body`: Thornton's with p_y of [`ContactLaw::thornton_for`].
    pub fn law_for(self, body: &Sphere) -> ContactLaw {
        match self {
            LawKind::Flores => ContactLaw::Flores,
            LawKind::Hertz => ContactLaw::Hertz,
            LawKind::Thornton => ContactLaw::thornton_for(body),
        }
    }
}

/// A contact law with its parameters (K, e and v₀ are the striker's).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub enum ContactLaw {
    /// Flores (eqs. 1-2) with the striker's restitution.
    #[default]
    Flores,
    /// Hertz, P = Kδ^{3/2}.
    Hertz,
    /// Thornton's elastic-perfectly-plastic law.
    Thornton {
        /// Limiting (centre) contact pressure p_y, Pa.
        yield_pressure: f64,
        /// Effective radius R* (the sphere's radius on a flat plate), m.
        radius: f64,
    },
}

impl ContactLaw {
    /// Thornton's law with δ_y = δ_my of eq. 51: p_y = 3k/(6Θ₁ + √3Θ₂) (see the module).
    pub fn thornton_for(body: &Sphere) -> Self {
        let dp = DruckerPrager::of(body);
        let p_y = 3.0 * dp.k / (6.0 * dp.theta1 + 3f64.sqrt() * dp.theta2);
        ContactLaw::Thornton { yield_pressure: p_y, radius: body.radius() }
    }

    /// Thornton's yield compression δ_y = (2πR p_y/(3K))² (None for the elastic laws).
    pub fn yield_compression(&self, k: f64) -> Option<f64> {
        match *self {
            ContactLaw::Thornton { yield_pressure, radius } => {
                let q = 2.0 * std::f64::consts::PI * radius * yield_pressure / (3.0 * k);
                Some(q * q)
            }
            _ => None,
        }
    }

    /// Whether the law is elastic (all but Thornton's), so that compressions beyond δ_my
    /// leave the range it describes.
    pub fn is_elastic(&self) -> bool {
        !matches!(self, ContactLaw::Thornton { .. })
    }

    /// Whether the law stores all the work done on it (no damping, no plastic flow)
    /// whatever the compression: Hertz, and Flores at e ≥ 1.
    pub fn conserves(&self, restitution: f64) -> bool {
        match self {
            ContactLaw::Flores => restitution >= 1.0,
            ContactLaw::Hertz => true,
            ContactLaw::Thornton { .. } => false,
        }
    }

    /// The force at compression δ, rate δ̇, after a largest compression `dmax` so far,
    /// never negative. For the history-free laws `dmax` is ignored; for Thornton's it
    /// selects the loading branch (δ ≥ dmax) or the unloading curve from dmax. In every
    /// case the force is continuous and nondecreasing in δ.
    pub fn force(&self, k: f64, restitution: f64, v0: f64, delta: f64, rate: f64, dmax: f64) -> f64 {
        if delta <= 0.0 {
            return 0.0;
        }
        match *self {
            ContactLaw::Flores => flores_force(k, restitution, delta, rate, v0).max(0.0),
            ContactLaw::Hertz => k * delta * delta.sqrt(),
            ContactLaw::Thornton { .. } => {
                let dy = self.yield_compression(k).unwrap_or(f64::INFINITY);
                if delta >= dmax {
                    thornton_loading(k, dy, delta)
                } else if dmax <= dy {
                    // Never yielded: the unloading curve is the Hertz curve itself.
                    k * delta * delta.sqrt()
                } else {
                    let (dp, kp) = thornton_unloading(k, dy, dmax);
                    if delta <= dp {
                        0.0
                    } else {
                        kp * (delta - dp).powf(1.5)
                    }
                }
            }
        }
    }

    /// The permanent compression δ_p left by a largest compression `dmax` (zero for the
    /// elastic laws and below yield): the contact opens at δ = δ_p.
    pub fn permanent_set(&self, k: f64, dmax: f64) -> f64 {
        match self.yield_compression(k) {
            Some(dy) if dmax > dy => thornton_unloading(k, dy, dmax).0,
            _ => 0.0,
        }
    }

    /// The elastic energy stored in the contact at δ after a largest compression `dmax`
    /// (what unloading from δ would return): (2/5)Kδ^{5/2} for the elastic laws and below
    /// yield, (2/5)K_p(δ - δ_p)^{5/2} after it.
    pub fn stored_energy(&self, k: f64, delta: f64, dmax: f64) -> f64 {
        if delta <= 0.0 {
            return 0.0;
        }
        match self.yield_compression(k) {
            Some(dy) if dmax.max(delta) > dy => {
                let (dp, kp) = thornton_unloading(k, dy, dmax.max(delta));
                if delta <= dp {
                    0.0
                } else {
                    0.4 * kp * (delta - dp).powf(2.5)
                }
            }
            // δ²√δ = δ^{5/2}, without powf (this runs every step).
            _ => 0.4 * k * delta * delta * delta.sqrt(),
        }
    }
}

/// Thornton's virgin loading curve: Kδ^{3/2} up to δ_y, then P_y + πp_yR(δ - δ_y) with
/// πp_yR = (3/2)Kδ_y^{1/2}.
fn thornton_loading(k: f64, dy: f64, delta: f64) -> f64 {
    if delta <= dy {
        k * delta * delta.sqrt()
    } else {
        let py = k * dy * dy.sqrt();
        py + 1.5 * k * dy.sqrt() * (delta - dy)
    }
}

/// (δ_p, K_p) of the unloading curve from δ_m > δ_y: δ_m - δ_p = P_m/(Kδ_m^{1/2}) (the
/// contact radius √(Rδ_m) carried over to the radius R_p), K_p = P_m/(δ_m - δ_p)^{3/2}.
fn thornton_unloading(k: f64, dy: f64, dm: f64) -> (f64, f64) {
    let pm = thornton_loading(k, dy, dm);
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
