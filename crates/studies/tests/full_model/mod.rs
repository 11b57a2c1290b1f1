//! "Measured" signals made by another path than the reduced model under test: the full
//! Newmark model of the plate (every DOF of the mesh the reduced model is built on, stepped at
//! `substeps` steps per model sample, the sphere followed through every contact to the
//! window's end), the acceleration read from the FE field at each sensor.

#![allow(dead_code)]

use coupled::transient::{simulate_with, PlateFacts, Striker, Target};
use plate_fem::dynamics::{Newmark, PlateEnergy};
use plate_fem::{Model, Supports};
use scene::Scene;

/// A Newmark plate that keeps the acceleration at the sensors every `substeps` commits.
struct Sensing<'a, 'm> {
    plate: &'a mut Newmark<'m>,
    model: &'m Model,
    sensors: &'a [(f64, f64)],
    substeps: usize,
    commits: usize,
    samples: Vec<Vec<f64>>,
}

impl Sensing<'_, '_> {
    fn sample(&mut self) {
        for (s, &(x, z)) in self.sensors.iter().enumerate() {
            let a = self.model.evaluate(self.plate.acceleration_field(), x, z).expect("a sensor on the plate");
            self.samples[s].push(a);
        }
    }
}

impl Target for Sensing<'_, '_> {
    fn point_flexibility(&self) -> f64 {
        self.plate.point_flexibility()
    }
    fn predict(&mut self) -> (f64, f64) {
        self.plate.predict()
    }
    fn commit(&mut self, f: f64) {
        self.plate.commit(f);
        self.commits += 1;
        if self.commits % self.substeps == 0 {
            self.sample();
        }
    }
    fn point_state(&self) -> (f64, f64) {
        self.plate.point_state()
    }
    fn energy(&self) -> PlateEnergy {
        self.plate.energy()
    }
    fn corner_displacements(&self) -> [f64; 4] {
        self.plate.corner_displacements()
    }
}

/// What the full model made of one impact.
#[derive(Debug, Clone)]
pub struct FullRun {
    /// The acceleration at every sensor at the model's rate, from the touch (sample 0, at
    /// rest) over the scene's window, m/s².
    pub accelerations: Vec<Vec<f64>>,
    /// The first contact's peak force, N.
    pub force_max: f64,
    /// The first contact's duration, s, if it ended in the window.
    pub contact_time: Option<f64>,
}

/// The plate of `scene` on the mesh the reduced model uses.
pub fn plate_model(scene: &Scene) -> Model {
    let props = coupled::discretisation::plate_properties(&scene.plate);
    let elements = coupled::reduced::ReducedSettings::default().elements;
    Model::new(props, coupled::discretisation::mesh_for(&props, elements).unwrap()).unwrap()
}

/// `striker` at (x, z) on `model` held by `supports`, damped as `scene` states, sampled at
/// the scene's sensors and rate over its window.
pub fn strike(
    scene: &Scene,
    model: &Model,
    supports: Supports,
    striker: &Striker,
    (x, z): (f64, f64),
    substeps: usize,
) -> FullRun {
    let samples = (scene.signals.window * scene.signals.rate_hz).round() as usize;
    let dt = 1.0 / (scene.signals.rate_hz * substeps as f64);
    let mut nm = Newmark::damped(model, supports, dt, (x, z), scene.plate_damping).unwrap();
    let sensors = &scene.signals.sensors;
    let mut rec =
        Sensing { plate: &mut nm, model, sensors, substeps, commits: 0, samples: vec![vec![0.0]; sensors.len()] };
    let facts = PlateFacts { static_compliance: None, corner_springs: None, follow_unbounded: true };
    let t_max = (samples - 1) as f64 / scene.signals.rate_hz + 0.5 * dt;
    let o = simulate_with(striker, Some(&mut rec), facts, dt, t_max);
    while rec.samples[0].len() < samples {
        rec.plate.predict();
        rec.commit(0.0);
    }
    FullRun {
        accelerations: rec.samples,
        force_max: o.force_max_interpolated.max(o.force_max),
        contact_time: o.contact_time,
    }
}
