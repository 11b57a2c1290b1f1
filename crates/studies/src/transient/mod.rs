//! The transient study (`impact dynamic`, and the main report's transient section): the
//! transient model against the quasi-static ones on the scene's cases ([`cases`]), the
//! contact laws side by side above the yield velocity ([`laws()`]), the quasi-static error
//! over plate size and thickness ([`size_map`]), the model against closed forms
//! ([`verification`]), and the numbers the findings quote ([`findings`]). Every run is the
//! coupled library's (`coupled::transient`); the report crate renders the data.

pub mod cases;
pub mod findings;
pub mod laws;
pub mod size_map;
pub mod verification;

pub use cases::{comparison, contact_count, median, TransientCase};
pub use laws::{end_state, laws, peak_over_contacts, LawCase, LAW_RATIOS};

use crate::progress::Progress;
use crate::settings::{Settings, STEPS_PER_CONTACT};
use crate::Failure;
use coupled::transient::case::{striker, WINDOW_HERTZ_TIMES};
use coupled::transient::{first_contact_on, simulate, Outcome, Sample, Striker};
use plate_fem::{Model, Supports};
use scene::{Analysis, Scene};
use serde::Serialize;
use std::time::Instant;

/// What the transient study computed; the parts the scene did not ask for are `None`.
#[derive(Debug, Clone, Serialize)]
pub struct TransientData {
    /// Transient against quasi-static at the scene's transient points.
    pub cases: Vec<TransientCase>,
    /// Wall-clock time of all the cases, s.
    pub comparison_seconds: f64,
    /// The threads the cases ran on.
    pub threads: usize,
    /// The first case's sphere on a rigid target with e = 1 (Hertz's impact, the stiff limit
    /// of its force history); empty without cases.
    pub rigid_hertz: Vec<Sample>,
    /// The contact laws side by side ("contact-laws").
    pub laws: Option<Vec<LawCase>>,
    /// The size map ("size-map").
    pub size_map: Option<Vec<size_map::SizeRow>>,
    /// The verification ("verification").
    pub verification: Option<verification::Verification>,
    /// The numbers the findings quote.
    pub findings: findings::Findings,
}

/// Runs the transient study of `scene`.
pub fn compute(scene: &Scene, settings: &Settings, progress: &dyn Progress) -> Result<TransientData, Failure> {
    crate::run::check_transient_comparison(scene)?;
    let verification = if scene.wants(Analysis::Verification) { Some(verification::verify(scene)?) } else { None };
    let t0 = Instant::now();
    let cases = comparison(scene, settings, &scene.transient_points, progress)?;
    let comparison_seconds = t0.elapsed().as_secs_f64();
    let laws = if scene.wants(Analysis::ContactLaws) { Some(laws(scene, progress)?) } else { None };
    let size_map = if scene.wants(Analysis::SizeMap) { Some(size_map::size_map(scene, settings)?) } else { None };
    Ok(TransientData {
        rigid_hertz: rigid_hertz(scene, &cases),
        findings: findings::findings(scene, &cases),
        cases,
        comparison_seconds,
        threads: rayon::current_num_threads(),
        laws,
        size_map,
        verification,
    })
}

/// The first case's sphere at its velocity on a rigid target with e = 1, over 1.5 Hertz
/// times (the whole contact).
fn rigid_hertz(scene: &Scene, cases: &[TransientCase]) -> Vec<Sample> {
    let Some(first) = cases.first() else { return Vec::new() };
    let Some(body) = scene.bodies.iter().find(|b| b.name == first.body) else { return Vec::new() };
    let hertz = striker(&scene.plate, body, 1.0, first.velocity);
    let tc = hertz.hertz_time();
    simulate(&hertz, None, tc / STEPS_PER_CONTACT, 1.5 * tc).history
}

/// The first contact of `s` at (x, z) on `model` held by `supports`, `steps` steps per Hertz
/// time, in the library's window ([`WINDOW_HERTZ_TIMES`]): the run stops at the first
/// separation, so the window only bounds a first contact that has not ended.
pub fn first_contact(
    model: &Model,
    supports: Supports,
    s: &Striker,
    x: f64,
    z: f64,
    steps: f64,
) -> Result<Outcome, Failure> {
    let dt = s.hertz_time() / steps;
    Ok(first_contact_on(model, (supports, None), s, (x, z), dt, WINDOW_HERTZ_TIMES * s.hertz_time())?)
}
