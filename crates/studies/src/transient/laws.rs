//! The contact laws side by side: Hertz, Flores and Thornton on the same impact, below the
//! rigid-target yield velocity and far above it, each run to the scene's discretisation with
//! its error estimate.

use crate::progress::Progress;
use crate::Failure;
use analytic::DruckerPrager;
use coupled::plan::{impact_of, law_striker};
use coupled::transient::{Estimated, LawKind, Outcome};
use scene::Scene;
use serde::Serialize;

/// Multiples of the rigid-target yield velocity at which the contact laws are compared: one
/// below yield, and 10, 100 and 200 times above (2 m/s for the paper's coal).
pub const LAW_RATIOS: [f64; 4] = [0.5, 10.0, 100.0, 200.0];

/// One contact law at one velocity.
#[derive(Debug, Clone, Serialize)]
pub struct LawCase {
    /// The contact law.
    pub law: LawKind,
    /// v over the rigid-target yield velocity.
    pub ratio: f64,
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// δ_my of eq. 51, m.
    pub yield_compression: f64,
    /// The sphere's E₀, J.
    pub energy: f64,
    /// The Hertz contact time of the sphere at this velocity on a rigid target, s (the time
    /// scale the laws' force histories are drawn against).
    pub hertz_time: f64,
    /// Values, errors and the whole run.
    pub estimate: Estimated,
    /// Thornton's permanent compression after the impact, m (zero for the elastic laws).
    pub permanent_set: f64,
}

/// Hertz, Flores and Thornton side by side on the scene's plate: the first body at the
/// centre under the first condition, at [`LAW_RATIOS`] times its rigid-target yield velocity.
pub fn laws(scene: &Scene, progress: &dyn Progress) -> Result<Vec<LawCase>, Failure> {
    let body = scene.bodies.first().ok_or("no body")?;
    let cond = scene.conditions.first().ok_or("no condition")?;
    let (x, z) = (scene.plate.length() / 2.0, scene.plate.width() / 2.0);
    let k = impact_of(scene, body, 1.0).contact_stiffness;
    let d_my = DruckerPrager::of(body).yield_compression(body.radius(), k);
    let v_y = analytic::yield_velocity(body, &impact_of(scene, body, 1.0), 0.0, d_my);
    let disc = scene.transient_discretisation;
    let ladder = coupled::transient::Ladder::new(&scene.plate, scene.transient_start())?;
    let mut out = Vec::new();
    progress.start(LawKind::ALL.len() * LAW_RATIOS.len(), "contact-law runs");
    for &law in LawKind::ALL {
        for ratio in LAW_RATIOS {
            let v = ratio * v_y;
            let s = law_striker(scene, body, v, law);
            let e = disc.estimate(&ladder, cond, &s, (x, z))?;
            let deepest =
                e.outcome.history.iter().chain(&e.outcome.later_history).map(|h| h.compression).fold(0.0, f64::max);
            out.push(LawCase {
                law,
                ratio,
                velocity: v,
                yield_compression: d_my,
                energy: 0.5 * s.mass * v * v,
                hertz_time: s.hertz_time(),
                permanent_set: s.permanent_set(deepest),
                estimate: e,
            });
            progress.advance(1);
        }
    }
    progress.finish();
    Ok(out)
}

/// How a run ended: the sphere provably gone, or the window ended with the sphere still
/// approaching the plate, in contact, or moving away but within the plate's reach.
pub fn end_state(o: &Outcome) -> &'static str {
    match (o.left_at, o.unfinished_contact, o.final_velocity > 0.0) {
        (Some(_), _, _) => "sphere left",
        (None, Some(_), _) => "window ended in contact",
        (None, None, true) => "window ended, sphere still approaching",
        (None, None, false) => "window ended, sphere within the plate's reach",
    }
}

/// The largest force of every contact of a run: the first contact's peak on the interpolant,
/// the later ones' sampled at the steps.
pub fn peak_over_contacts(o: &Outcome) -> f64 {
    o.contacts
        .iter()
        .chain(&o.unfinished_contact)
        .skip(1)
        .map(|c| c.peak_force)
        .fold(o.force_max_interpolated, f64::max)
}
