//! The rows of the transient model: the impact integrated in time, read at the instant of
//! maximum compression on the integrator's interpolant, each value with the error estimate
//! of its discretisation.

use super::rows::{Evidence, ResponseRow, ResponseValues, Results, RowOutcome, StateErrors, YieldRow};
use super::yield_velocity::{dynamic_yield_with, HERTZ_SLOPE};
use super::{impact_of, thin_plate, ModelKind};
use crate::compliance::plate::corner_weights;
use crate::error::ModelError;
use crate::scene::{Analysis, Scene};
use crate::supports::SupportSet;
use crate::transient::estimate::{Discretisation, Estimated, Ladder};
use crate::transient::{case::striker, LawKind, Outcome, Striker};
use crate::validity::{self, Validity};
use crate::yield_root::YieldSearch;
use analytic::{contact_stiffness, yield_velocity, DruckerPrager, Sphere};
use plate_fem::Corner;

/// The transient responses of one case, at the instant of maximum compression on the
/// integrator's interpolant, with the error estimates of `errors` when given.
#[allow(clippy::too_many_arguments)]
pub fn transient_values(
    scene: &Scene,
    set: &SupportSet,
    body: &Sphere,
    o: &Outcome,
    s: &crate::transient::Striker,
    dt: f64,
    (x, z): (f64, f64),
    errors: Option<&Estimated>,
) -> ResponseValues {
    let e0 = 0.5 * s.mass * s.velocity * s.velocity;
    let m = o.at_max_compression_interpolated;
    let (l, b) = (scene.plate.length(), scene.plate.width());
    let delta = o.compression_max_interpolated;
    let p = s.force_at_max_compression(delta);
    let dp = DruckerPrager::of(body);
    let d_my = dp.yield_compression(body.radius(), s.k);
    let weights = corner_weights(x, z, l, b);
    let springs = SpringCorners::of(set, o.corners_at_max_compression_interpolated, &weights);
    ResponseValues {
        compliance: None,
        compliance_error: None,
        contact_force: p,
        contact_force_error: errors.map(|e| e.error.force_at_max_compression),
        compression: delta,
        compression_error: errors.map(|e| e.error.compression),
        deflection: m.plate_displacement - springs.support_plane,
        spring_forces: springs.forces.clone(),
        rock_total_ratio: (m.contact + m.dissipated) / e0,
        rock_stored_ratio: m.contact / e0,
        plate_ratio: (m.plate_kinetic + m.plate_strain) / e0,
        spring_ratio: m.springs / e0,
        sphere_kinetic_ratio: m.sphere_kinetic / e0,
        state_errors: errors.map(|e| state_errors(e, &springs, &weights, e0)),
        evidence: transient_evidence(o, s, (dt, scene.main_contact_share), errors),
        validity: transient_validity(scene, o, s, delta, d_my, errors),
    }
}

/// The corner springs at maximum compression: their forces k w_c (the paper's eqs. 29-30,
/// 36), the bilinear plane through the sprung corners' deflections (zero at held corners)
/// that the plate's own deflection is measured from, as in the quasi-static plate model,
/// and which corners they are.
struct SpringCorners {
    forces: Vec<analytic::SpringForce>,
    support_plane: f64,
    /// (corner index, k) of every spring, in [`Corner::ALL`] order.
    springs: Vec<(usize, f64)>,
}

impl SpringCorners {
    /// From the corner deflections `corners` and the bilinear `weights` of the point.
    fn of(set: &SupportSet, corners: [f64; 4], weights: &[f64; 4]) -> Self {
        let mut support_plane = 0.0;
        let mut forces = Vec::new();
        let mut springs = Vec::new();
        for c in Corner::ALL {
            let i = c.index();
            if let plate_fem::CornerSupport::Spring(k) = set.supports.corners[i] {
                forces.push(analytic::SpringForce { name: format!("spring at {}", c.name()), force: k * corners[i] });
                support_plane += weights[i] * corners[i];
                springs.push((i, k));
            }
        }
        Self { forces, support_plane, springs }
    }
}

/// The errors of the state at maximum compression from the estimate `e`: the deflection's
/// is w's plus the weighted errors of the corner deflections the support plane subtracts
/// (a bound: the errors add), a spring force's is k times its corner's, the energy shares'
/// are their stores' over E₀ = `e0`.
fn state_errors(e: &Estimated, springs: &SpringCorners, weights: &[f64; 4], e0: f64) -> StateErrors {
    let se = e.state_error;
    StateErrors {
        deflection: se.plate_displacement
            + springs.springs.iter().map(|&(i, _)| weights[i].abs() * se.corners[i]).sum::<f64>(),
        spring_forces: springs.springs.iter().map(|&(i, k)| k * se.corners[i]).collect(),
        rock_total_ratio: se.rock_total / e0,
        rock_stored_ratio: se.rock_stored / e0,
        plate_ratio: se.plate / e0,
        spring_ratio: se.springs / e0,
        sphere_kinetic_ratio: se.sphere_kinetic / e0,
    }
}

/// How the transient values were found: the run's steps and contacts, its in-step maxima and
/// the error estimates of `errors` when given.
fn transient_evidence(o: &Outcome, s: &Striker, (dt, share): (f64, f64), errors: Option<&Estimated>) -> Evidence {
    let all: Vec<_> = o.contacts.iter().chain(&o.unfinished_contact).copied().collect();
    let split = crate::transient::chatter::split(&all, s.mass * s.velocity, share);
    let sequence = errors.and_then(|e| e.sequence.as_ref());
    // One contact that ended: the rebound is the first contact's, -e v₀, so the final
    // velocity and the impulse m(v₀ - v_f) carry v₀ times the restitution's error. After
    // several contacts both come from the levels followed through every contact, where those
    // agree on the count.
    let single = o.contacts.len() == 1 && o.unfinished_contact.is_none() && o.left_at.is_some();
    let end = sequence.and_then(|q| q.end_error);
    let final_velocity_error = match errors {
        Some(e) if single => Some(s.velocity * e.error.restitution.abs()),
        _ => end.map(|e| e.final_velocity),
    };
    let total_impulse_error = match errors {
        Some(_) if single => final_velocity_error.map(|dv| s.mass * dv),
        _ => end.map(|e| e.total_impulse),
    };
    Evidence::Transient {
        steps: o.steps,
        time_step: dt,
        peak_force: o.force_max_interpolated,
        peak_force_error: errors.map(|e| e.error.peak_force),
        contact_time: o.contacts.first().map(|c| c.duration),
        contact_time_error: errors.map(|e| e.error.contact_time),
        apparent_restitution: o.apparent_restitution,
        restitution_error: errors.map(|e| e.error.restitution),
        elements: errors.map_or(0, |e| e.elements),
        steps_per_contact: s.hertz_time() / dt,
        relative_error: errors.map(|e| e.relative_error()),
        tolerance: errors.and_then(|e| e.tolerance),
        met_tolerance: errors.is_none_or(|e| e.met_tolerance),
        contacts: all.len(),
        main_contacts: split.main,
        micro_contacts: split.micro,
        micro_impulse: split.micro_impulse,
        contact_count_changes: errors.map(|_| sequence.is_some_and(|q| q.count_changes())),
        total_impulse: o.total_impulse,
        total_impulse_error,
        final_velocity: o.final_velocity,
        final_velocity_error,
        left_for_good: o.left_at.is_some() && o.returns_at.is_none(),
        returns_at: o.returns_at,
    }
}

/// Whether the transient values are inside the model's assumptions: the elastic range of
/// the contact law (δ_max against δ_my = `d_my`, eq. 51), one contact, a run that ended with
/// the sphere gone, and the error estimate within its tolerance.
fn transient_validity(
    scene: &Scene,
    o: &Outcome,
    s: &Striker,
    delta: f64,
    d_my: f64,
    errors: Option<&Estimated>,
) -> Validity {
    Validity {
        // Compressions beyond δ_my leave an elastic law's range; Thornton's law describes
        // the plastic contact beyond it (its yield onset is δ_my), so it carries no flag.
        elastic: s.law.is_elastic().then(|| validity::elastic(delta, d_my)),
        quasi_static: None,
        thin_plate: thin_plate(scene),
        // The first contact's numbers describe the whole impact only if there is no other.
        recontact: Some(validity::Criterion::at_most("contacts", o.contacts.len() as f64, 1.0)),
        regime: None,
        finished: Some(validity::finished(o.left_at.is_some())),
        // Where the ladder's budget ran out before the estimate met the tolerance, the
        // numbers are less accurate than asked: the status says so, not only the
        // discretisation column.
        discretisation: errors.and_then(|e| e.tolerance.map(|tol| validity::discretisation(e.relative_error(), tol))),
    }
}

/// The striker of `body` on the scene's plate at `velocity`, with the scene's restitution and
/// contact law.
pub fn scene_striker(scene: &Scene, body: &Sphere, velocity: f64) -> Striker {
    law_striker(scene, body, velocity, scene.contact_law)
}

/// The striker of `body` on the scene's plate at `velocity` with the scene's restitution and
/// the contact law `law` in place of the scene's: the same sphere under Hertz, Flores or
/// Thornton, for comparing the laws on one impact.
pub fn law_striker(scene: &Scene, body: &Sphere, velocity: f64, law: LawKind) -> Striker {
    Striker {
        law: law.law_for(body),
        gravity: scene.gravity,
        ..striker(&scene.plate, body, scene.restitution, velocity)
    }
}

/// One transient response row's values with their error estimate, and the estimate itself
/// (its `outcome` is the run the values come from, with its history), on the discretisation
/// `disc` over the plate's mesh `ladder` ([`Discretisation::estimate`]). What
/// [`run_transient`] computes for each of its rows.
#[allow(clippy::too_many_arguments)]
pub fn transient_response(
    scene: &Scene,
    disc: Discretisation,
    ladder: &Ladder,
    set: &SupportSet,
    body: &Sphere,
    (x, z): (f64, f64),
    velocity: f64,
) -> Result<(ResponseValues, Estimated), ModelError> {
    let s = scene_striker(scene, body, velocity);
    let e = disc.estimate(ladder, set, &s, (x, z))?;
    let dt = s.hertz_time() / e.steps_per_contact;
    let values = transient_values(scene, set, body, &e.outcome, &s, dt, (x, z), Some(&e));
    Ok((values, e))
}

/// Runs the scene's responses with the transient model (yield velocities by the transient
/// model are the velocity at which the transient δ_max reaches δ_my). Every response carries
/// the error estimate of [`mod@crate::transient::estimate`] on the discretisation the scene asks
/// for ([`Scene::transient_discretisation`]): fixed settings, or per case the coarsest mesh
/// and step whose estimate meets a tolerance.
pub fn run_transient(scene: &Scene) -> Result<Results, ModelError> {
    run_transient_observed(scene, &mut || {})
}

/// How many cases [`run_transient`] computes for `scene`: one per body, support set, point
/// and velocity for the responses, and one per body, support set and point for the yield
/// velocities, as the scene asks.
pub fn transient_case_count(scene: &Scene) -> usize {
    let per_point = if scene.wants(Analysis::Responses) { scene.velocities.len() } else { 0 }
        + usize::from(scene.wants(Analysis::YieldVelocity));
    scene.bodies.len() * scene.conditions.len() * scene.points.len() * per_point
}

/// [`run_transient`], calling `done` after each of its [`transient_case_count`] cases (a
/// caller's progress display).
pub fn run_transient_observed(scene: &Scene, done: &mut dyn FnMut()) -> Result<Results, ModelError> {
    let disc = scene.transient_discretisation;
    let ladder = Ladder::new(&scene.plate, scene.transient_start())?;
    let mut search = YieldSearch::new();
    let points = scene.point_pairs();
    let mut responses = Vec::new();
    let mut yields = Vec::new();
    for body in &scene.bodies {
        for set in &scene.conditions {
            for &(x, z) in &points {
                if scene.wants(Analysis::Responses) {
                    for &v in &scene.velocities {
                        let (values, _) = transient_response(scene, disc, &ladder, set, body, (x, z), v)?;
                        responses.push(ResponseRow {
                            model: ModelKind::Transient,
                            body: body.name.clone(),
                            condition: set.name.clone(),
                            x,
                            z,
                            velocity: v,
                            outcome: RowOutcome::Computed(values),
                        });
                        done();
                    }
                }
                if scene.wants(Analysis::YieldVelocity) {
                    // The discretisation is chosen at the root search's start, the rigid-target
                    // yield velocity, and its relative error in δ_max carried to v_y through
                    // d ln δ_max/d ln v ≈ 0.8.
                    let k = contact_stiffness(body, scene.plate.material());
                    let d_my = DruckerPrager::of(body).yield_compression(body.radius(), k);
                    let v_rigid = yield_velocity(body, &impact_of(scene, body, 1.0), 0.0, d_my);
                    let s = scene_striker(scene, body, v_rigid);
                    let e = disc.estimate(&ladder, set, &s, (x, z))?;
                    let level = (e.elements / disc.start().elements).max(1).trailing_zeros() as usize;
                    let case = ladder.levels(level)?.0;
                    let mut y = dynamic_yield_with(scene, case, e.steps_per_contact, &mut search, set, body, (x, z))?;
                    let relative = e.error.compression / e.values.compression;
                    if let Some(w) = y.yield_velocity_error.as_mut() {
                        *w += y.yield_velocity * relative / HERTZ_SLOPE;
                    }
                    yields.push(YieldRow {
                        model: ModelKind::Transient,
                        body: body.name.clone(),
                        condition: set.name.clone(),
                        x,
                        z,
                        outcome: RowOutcome::Computed(y),
                    });
                    done();
                }
            }
        }
    }
    Ok(Results { scene: scene.name.clone(), responses, yields })
}
