//! One transient case on a scene's plate: the sphere, the support set, the point and the
//! velocity, with the discretisation the transient study validated.

use super::{simulate, Outcome, Striker};
use crate::discretisation::{mesh_for, plate_properties};
use crate::error::ModelError;
use crate::supports::SupportSet;
use analytic::{contact_stiffness, Plate, Sphere};
use plate_fem::dynamics::{fundamental_frequency, Newmark};
use plate_fem::{Model, Supports};
use serde::Serialize;

/// How finely the transient model is discretised.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TransientSettings {
    /// Elements along the longer side of the plate.
    pub elements: usize,
    /// Time steps per Hertz contact time: 200 puts the force error near 4e-5 and the
    /// energy error near 5e-5 (second order, measured against Hertz and e = 1).
    pub steps_per_contact: f64,
    /// The run stops after this many Hertz contact times if the sphere has not left.
    pub window_contacts: f64,
}

impl Default for TransientSettings {
    fn default() -> Self {
        Self { elements: 20, steps_per_contact: 200.0, window_contacts: 20.0 }
    }
}

/// The sphere of `body` striking `plate` at `velocity` with restitution `restitution`.
pub fn striker(plate: &Plate, body: &Sphere, restitution: f64, velocity: f64) -> Striker {
    Striker { k: contact_stiffness(body, plate.material()), restitution, mass: body.mass(), velocity }
}

/// The plate's transient model: one mesh, shared by every case on it.
pub struct TransientCase {
    model: Model,
    settings: TransientSettings,
}

impl TransientCase {
    /// Builds the mesh and the plate's matrices.
    pub fn new(plate: &Plate, settings: TransientSettings) -> Result<Self, ModelError> {
        let props = plate_properties(plate);
        let model = Model::new(props, mesh_for(&props, settings.elements)?)?;
        Ok(Self { model, settings })
    }

    /// The finite-element model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The settings.
    pub fn settings(&self) -> TransientSettings {
        self.settings
    }

    /// The fundamental period T₁ of the plate on `supports`, s.
    pub fn fundamental_period(&self, supports: &Supports) -> Result<f64, ModelError> {
        let (w1, _) = fundamental_frequency(&self.model, supports, 200)?;
        Ok(2.0 * std::f64::consts::PI / w1)
    }

    /// One impact of `s` at (x, z) on the plate held by `set`.
    pub fn run(&self, set: &SupportSet, s: &Striker, x: f64, z: f64) -> Result<Outcome, ModelError> {
        let dt = s.hertz_time() / self.settings.steps_per_contact;
        let mut nm = Newmark::new(&self.model, set.supports, dt, x, z)?;
        Ok(simulate(s, Some(&mut nm), dt, self.settings.window_contacts * s.hertz_time()))
    }
}
