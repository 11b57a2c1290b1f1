//! The yield velocity as a root of the transient model: the impact velocity at which the
//! first contact's largest compression δ_max reaches δ_my of eq. 51, on a plate that is
//! integrated in time rather than reduced to one quasi-static compliance.
//!
//! ln(δ_max/δ_my) increases with ln v (δ_max ∝ v^{4/5} on a rigid target, steeper where the
//! plate gives way), so [`log_root`] brackets it from the rigid-target value of the balance
//! (eq. 14 with C = 0, the smallest v that reaches δ_my) with the Hertz slope and closes the
//! bracket by Illinois false position, in about 6-8 transient runs.

use crate::error::ModelError;
use crate::plan::{impact_of, log_root, scene_striker, YIELD_ROOT_TOLERANCE};
use crate::scene::Scene;
use crate::supports::SupportSet;
use crate::transient::TransientCase;
use analytic::{contact_stiffness, yield_velocity, DruckerPrager, Sphere};
use serde::Serialize;

/// A transient yield velocity and how it was found.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TransientYield {
    /// v_y, m/s: the geometric middle of the final bracket.
    pub velocity: f64,
    /// Width of the final bracket hi - lo, m/s: f(lo) < 0 ≤ f(hi).
    pub width: f64,
    /// Transient runs it took.
    pub runs: usize,
    /// δ_my of eq. 51, m.
    pub yield_compression: f64,
}

/// δ_my of eq. 51: the compression at which the Drucker-Prager criterion is first met at
/// the sphere's contact, with the Hertz stiffness against the scene's plate.
fn yield_compression(scene: &Scene, body: &Sphere) -> f64 {
    let k = contact_stiffness(body, scene.plate.material());
    DruckerPrager::of(body).yield_compression(body.radius(), k)
}

/// The quasi-static yield velocity (eqs. 51-54) of rigid contact, C = 0 (eq. 14 with C = 0).
/// On any plate that gives way the transient root lies above it: this is where the search
/// starts.
pub fn rigid_yield(scene: &Scene, body: &Sphere) -> f64 {
    yield_velocity(body, &impact_of(scene, body, 1.0), 0.0, yield_compression(scene, body))
}

/// The transient yield velocity of `body` at (x, z) on the plate held by `set`, with the
/// scene's contact law: the v at which the transient δ_max reaches δ_my of eq. 51, to a
/// relative width [`YIELD_ROOT_TOLERANCE`].
pub fn transient_yield(
    scene: &Scene,
    case: &TransientCase,
    set: &SupportSet,
    body: &Sphere,
    x: f64,
    z: f64,
) -> Result<TransientYield, ModelError> {
    transient_yield_with(scene, case, case.settings().steps_per_contact, set, body, x, z)
}

/// [`transient_yield`] with `steps_per_contact` steps per Hertz time on `case`'s mesh.
pub fn transient_yield_with(
    scene: &Scene,
    case: &TransientCase,
    steps_per_contact: f64,
    set: &SupportSet,
    body: &Sphere,
    x: f64,
    z: f64,
) -> Result<TransientYield, ModelError> {
    let d_my = yield_compression(scene, body);
    let v_rigid = yield_velocity(body, &impact_of(scene, body, 1.0), 0.0, d_my);
    let mut runs = 0;
    let (lo, hi) = {
        let mut reach = |lv: f64| -> Result<f64, ModelError> {
            runs += 1;
            let s = scene_striker(scene, body, lv.exp());
            // δ_max is the first contact's: the run need not follow the later ones.
            Ok((case.first_contact(set, &s, x, z, steps_per_contact)?.compression_max / d_my).ln())
        };
        log_root(&mut reach, v_rigid.ln(), YIELD_ROOT_TOLERANCE)?
    };
    Ok(TransientYield { velocity: (0.5 * (lo + hi)).exp(), width: hi.exp() - lo.exp(), runs, yield_compression: d_my })
}
