//! The comparison cases: every support set, body, velocity and transient point of a scene,
//! the transient model (each case on the discretisation the scene asks for, with its error
//! estimate) beside the quasi-static plate and beam balances of the same impact.

use crate::progress::Progress;
use crate::settings::Settings;
use crate::Failure;
use analytic::{respond, DruckerPrager, Sphere};
use coupled::plan::{impact_of, scene_striker, transient_values};
use coupled::regimes::{mass_ratio, RuleInputs};
use coupled::transient::{Estimated, Ladder, Outcome};
use coupled::{BeamModel, ComplianceModel, PlateModel, Validity};
use rayon::prelude::*;
use scene::{Scene, SupportSet};
use serde::Serialize;
use std::time::Instant;

/// One case of the transient comparison: a condition, body, point and velocity.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TransientCase {
    /// The support set's name.
    pub condition: String,
    /// The body's name.
    pub body: String,
    /// The impact point along the length, m.
    pub x: f64,
    /// The impact point across the width, m.
    pub z: f64,
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// The fundamental period T₁ of the supported plate, s.
    pub period: f64,
    /// The law's force at maximum compression of the transient run, at the instant δ̇ = 0 on
    /// the integrator's interpolant (the paper's P_max), N.
    pub force_at_max_compression: f64,
    /// P_max of the quasi-static balance with the plate's compliance, N.
    pub quasi_static_plate_force: f64,
    /// δ_max of that balance, m.
    pub quasi_static_plate_compression: f64,
    /// The plate's static compliance there (springs included), m/N.
    pub quasi_static_plate_compliance: f64,
    /// P_max of the quasi-static balance with the beam's compliance, N; `None` for a
    /// support set the beam does not describe.
    pub quasi_static_beam_force: Option<f64>,
    /// Plate energy (kinetic and strain) at maximum compression, over E₀.
    pub plate_energy: f64,
    /// The plate energy of the quasi-static plate balance, over E₀.
    pub quasi_static_plate_energy: f64,
    /// Sphere kinetic energy left at maximum compression, over E₀.
    pub sphere_energy_left: f64,
    /// δ_max over the Drucker-Prager yield compression δ_my of eq. 51.
    pub yield_ratio: f64,
    /// The closed-form regime rule's inputs, with the plate's compliance.
    pub rule: RuleInputs,
    /// M_i/M_p.
    pub mass_ratio: f64,
    /// The sphere's mass, kg.
    pub sphere_mass: f64,
    /// The Hertz contact time on a rigid target, s.
    pub hertz_time: f64,
    /// The values at their instants, their error estimates and the whole run (every contact).
    pub estimate: Estimated,
    /// Wall-clock time of the case (its discretisation's choice and estimate), s.
    pub seconds: f64,
    /// The case's validity status, as `impact solve --model transient` gives it for the same
    /// case (elastic range, re-contact, impact finished in its window, discretisation).
    pub validity: Validity,
}

impl TransientCase {
    /// The whole run.
    pub fn outcome(&self) -> &Outcome {
        &self.estimate.outcome
    }

    /// The first contact's duration on the interpolant, s.
    pub fn contact_time(&self) -> Option<f64> {
        self.outcome().contacts.first().map(|c| c.duration)
    }

    /// t_c/T₁; `None` if the sphere had not separated at the end of the run.
    pub fn contact_ratio(&self) -> Option<f64> {
        self.contact_time().map(|t| t / self.period)
    }

    /// The error of the quasi-static plate's P_max: the transient force at maximum
    /// compression / QS - 1.
    pub fn force_error(&self) -> f64 {
        self.force_at_max_compression / self.quasi_static_plate_force - 1.0
    }
}

/// The number of contacts of a run, an unfinished one included.
pub fn contact_count(o: &Outcome) -> usize {
    o.contacts.len() + usize::from(o.unfinished_contact.is_some())
}

/// The median of `values` (the mean of the two middle ones for an even count); None for none.
pub fn median(values: &[f64]) -> Option<f64> {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| !x.is_nan()).collect();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(v[n / 2]),
        _ => Some(0.5 * (v[n / 2 - 1] + v[n / 2])),
    }
}

/// Transient against quasi-static at the given points, for every condition, body and
/// velocity of the scene, each case on the discretisation the scene asks for
/// ([`Scene::transient_discretisation`]) with its error estimate.
pub fn comparison(
    scene: &Scene,
    settings: &Settings,
    points: &[(f64, f64)],
    progress: &dyn Progress,
) -> Result<Vec<TransientCase>, Failure> {
    let runner = Runner {
        scene,
        settings,
        ladder: Ladder::new(&scene.plate, scene.transient_start())?,
        quasi_static: PlateModel::compute(
            &scene.plate,
            &scene.conditions,
            points,
            settings.base_mesh,
            settings.levels,
        )?,
    };
    let mut jobs = Vec::new();
    for cond in &scene.conditions {
        let t1 = runner.ladder.levels(0)?.0.fundamental_period(&cond.supports)?;
        for body in &scene.bodies {
            for &v in &scene.velocities {
                jobs.extend(points.iter().map(|&point| ((cond, t1), body, v, point)));
            }
        }
    }
    progress.start(jobs.len(), "transient cases");
    // The cases are independent (each builds its own time integration on the shared,
    // read-only meshes), so they run on every core; the order of the list is kept.
    let cases: Result<Vec<TransientCase>, String> = jobs
        .into_par_iter()
        .map(|(cond, body, v, point)| {
            let case = runner.case(cond, body, v, point).map_err(|e| e.to_string());
            progress.advance(1);
            case
        })
        .collect();
    progress.finish();
    Ok(cases?)
}

/// What every case of a comparison shares: the transient model's meshes and the
/// quasi-static plate's compliances at the points.
struct Runner<'a> {
    scene: &'a Scene,
    settings: &'a Settings,
    ladder: Ladder,
    quasi_static: PlateModel,
}

impl Runner<'_> {
    /// One case: the transient run with its estimate, the quasi-static balances of the same
    /// impact, and the numbers the tables compare.
    fn case(
        &self,
        (cond, t1): (&SupportSet, f64),
        body: &Sphere,
        v: f64,
        (x, z): (f64, f64),
    ) -> Result<TransientCase, Failure> {
        let (scene, method) = (self.scene, self.settings.method);
        let d_my =
            DruckerPrager::of(body).yield_compression(body.radius(), impact_of(scene, body, 1.0).contact_stiffness);
        let s = scene_striker(scene, body, v);
        let imp = impact_of(scene, body, v);
        let t0 = Instant::now();
        let e = scene.transient_discretisation.estimate(&self.ladder, cond, &s, (x, z))?;
        let seconds = t0.elapsed().as_secs_f64();
        let c = self.quasi_static.compliance(cond, x, z)?;
        let rp = respond(&imp, &c.compliance, method)?;
        // The beam describes only the paper's Con 1-3; for any other set it has no value to
        // show.
        let rb = match (BeamModel { plate: &scene.plate }).compliance(cond, x, z) {
            Ok(c) => Some(respond(&imp, &c.compliance, method)?.contact_force),
            Err(coupled::ModelError::NotApplicable { .. }) => None,
            Err(e) => return Err(e.into()),
        };
        let e0 = 0.5 * s.mass * v * v;
        let m = e.outcome.at_max_compression_interpolated;
        let dt = s.hertz_time() / e.steps_per_contact;
        let validity = transient_values(scene, cond, body, &e.outcome, &s, dt, (x, z), Some(&e)).validity;
        Ok(TransientCase {
            condition: cond.name.clone(),
            body: body.name.clone(),
            x,
            z,
            velocity: v,
            period: t1,
            force_at_max_compression: e.values.force_at_max_compression,
            quasi_static_plate_force: rp.contact_force,
            quasi_static_plate_compression: rp.compression,
            quasi_static_plate_compliance: c.compliance.total(),
            quasi_static_beam_force: rb,
            plate_energy: (m.plate_kinetic + m.plate_strain) / e0,
            quasi_static_plate_energy: rp.plate_ratio,
            sphere_energy_left: m.sphere_kinetic / e0,
            yield_ratio: e.values.compression / d_my,
            rule: RuleInputs::of(&s, &scene.plate, cond, c.compliance.total()),
            mass_ratio: mass_ratio(s.mass, &scene.plate),
            sphere_mass: s.mass,
            hertz_time: s.hertz_time(),
            estimate: e,
            seconds,
            validity,
        })
    }
}
