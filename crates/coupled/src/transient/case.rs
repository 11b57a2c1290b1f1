//! One transient case on a scene's plate: the sphere, the support set, the point and the
//! velocity, with the discretisation the transient study validated.

use super::{law::Flores, simulate_with, ContactLaw, Outcome, PlateFacts, Striker};
use crate::discretisation::{mesh_for, plate_properties};
use crate::error::ModelError;
use crate::supports::SupportSet;
use analytic::{contact_stiffness, Plate, Sphere};
use plate_fem::dynamics::{fundamental_frequency, Newmark, Rayleigh};
use plate_fem::{CornerSupport, Mesh, Model, Supports};
use serde::Serialize;

/// How finely the transient model is discretised.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TransientSettings {
    /// Elements along the longer side of the plate.
    pub elements: usize,
    /// Time steps per Hertz contact time: 200 puts the force error near 4e-5 and the
    /// energy error near 5e-5 (second order, measured against Hertz and e = 1).
    pub steps_per_contact: f64,
    /// The run stops after this many Hertz contact times if the sphere has not left
    /// ([`WINDOW_HERTZ_TIMES`] by default).
    pub window_contacts: f64,
    /// The plate's Rayleigh damping C = αM + βK; None (the default, the paper's plate) for
    /// none.
    pub damping: Option<Rayleigh>,
}

/// The window of a run, in Hertz contact times: the stopping rule ends most runs long
/// before it. A heavy sphere on a flexible plate is caught again and again by the plate for
/// about one plate period T₁: on a 3 mm version of the paper's plate struck by a 60 mm gangue
/// sphere (T₁ = 22-52 Hertz times) every impact left within 54 Hertz times, 2-13 contacts
/// (0.008-0.54 m/s, four points, Flores and Hertz), where a window of 20 ended 13 of 24 such
/// runs before the sphere had left. The window costs only runs that have not left: at most
/// 200 x the steps per Hertz time, 40,000 steps at 200 (about 15 s on the 20-element mesh).
/// A run still unfinished at its end is flagged ([`crate::validity::finished`]).
pub const WINDOW_HERTZ_TIMES: f64 = 200.0;

impl Default for TransientSettings {
    fn default() -> Self {
        Self { elements: 20, steps_per_contact: 200.0, window_contacts: WINDOW_HERTZ_TIMES, damping: None }
    }
}

/// The sphere of `body` striking `plate` at `velocity` with the Flores law of restitution
/// `restitution` (set `law` for another).
pub fn striker(plate: &Plate, body: &Sphere, restitution: f64, velocity: f64) -> Striker {
    Striker {
        k: contact_stiffness(body, plate.material()),
        restitution,
        mass: body.mass(),
        velocity,
        law: ContactLaw::Flores(Flores),
        gravity: 0.0,
    }
}

/// The corner spring stiffnesses of `supports` in [`plate_fem::Corner::ALL`] order, N/m
/// (0 where a corner is free or held).
pub fn corner_springs(supports: &Supports) -> [f64; 4] {
    supports.corners.map(|c| match c {
        CornerSupport::Spring(k) => k,
        _ => 0.0,
    })
}

/// The plate's transient model: one mesh, shared by every case on it.
pub struct TransientCase {
    plate: Plate,
    model: Model,
    settings: TransientSettings,
}

impl TransientCase {
    /// Builds the mesh and the plate's matrices.
    pub fn new(plate: &Plate, settings: TransientSettings) -> Result<Self, ModelError> {
        let props = plate_properties(plate);
        Self::on_mesh(plate, mesh_for(&props, settings.elements)?, settings)
    }

    /// The plate's transient model on a given mesh (`settings.elements` is then only a label).
    pub fn on_mesh(plate: &Plate, mesh: Mesh, settings: TransientSettings) -> Result<Self, ModelError> {
        let model = Model::new(plate_properties(plate), mesh)?;
        Ok(Self { plate: *plate, model, settings })
    }

    /// The same plate on the mesh with every element split in four (h halved exactly, every
    /// node kept), for the mesh part of the error estimate.
    pub fn refined(&self, plate: &Plate) -> Result<Self, ModelError> {
        let m = self.model.mesh();
        let mesh = Mesh::uniform(plate.length(), plate.width(), 2 * m.nx(), 2 * m.nz())?;
        Self::on_mesh(plate, mesh, TransientSettings { elements: 2 * self.settings.elements, ..self.settings })
    }

    /// The same plate on the mesh with h doubled, if every node line of that mesh (the
    /// centre lines included) is one of this mesh's: None unless both counts are multiples
    /// of 4. It gives the third level from which the mesh order is observed.
    pub fn coarsened(&self, plate: &Plate) -> Option<Result<Self, ModelError>> {
        let m = self.model.mesh();
        (m.nx() % 4 == 0 && m.nz() % 4 == 0).then(|| {
            let mesh = Mesh::uniform(plate.length(), plate.width(), m.nx() / 2, m.nz() / 2)?;
            Self::on_mesh(plate, mesh, TransientSettings { elements: self.settings.elements / 2, ..self.settings })
        })
    }

    /// What the stopping rule and the interpolated spring energy need: the static
    /// compliance Nᵀ K⁻¹ N at (x, z) (None if the supports leave the plate free to move as a
    /// rigid body) and the corner springs.
    pub fn facts(&self, supports: &Supports, x: f64, z: f64) -> PlateFacts {
        let static_compliance = self.model.factorize(supports).ok().and_then(|f| {
            let n = f.load_vector(x, z).ok()?;
            let w = f.deflection_field(x, z).ok()?;
            let c: f64 = n.iter().zip(&w).map(|(a, b)| a * b).sum();
            (c.is_finite() && c > 0.0).then_some(c)
        });
        PlateFacts { static_compliance, corner_springs: Some(corner_springs(supports)), follow_unbounded: true }
    }

    /// The plate.
    pub fn plate(&self) -> &Plate {
        &self.plate
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

    /// One impact of `s` at (x, z) on the plate held by `set`, followed through every
    /// contact until the sphere has provably left or the window ends
    /// ([`super::simulate_with`] with [`Self::facts`]).
    pub fn run(&self, set: &SupportSet, s: &Striker, x: f64, z: f64) -> Result<Outcome, ModelError> {
        self.run_steps(set, s, x, z, self.settings.steps_per_contact)
    }

    /// The first contact only, with `steps_per_contact` steps per Hertz time: the run stops
    /// at the first separation and needs no static factorization for the stopping rule.
    /// Its first-contact quantities are those of [`Self::run_steps`]
    /// ([`super::simulate_with`] is the same up to the first separation).
    pub fn first_contact(
        &self,
        set: &SupportSet,
        s: &Striker,
        x: f64,
        z: f64,
        steps_per_contact: f64,
    ) -> Result<Outcome, ModelError> {
        let dt = s.hertz_time() / steps_per_contact;
        let t_max = self.settings.window_contacts * s.hertz_time();
        first_contact_on(&self.model, (set.supports, self.settings.damping), s, (x, z), dt, t_max)
    }

    /// One impact with `steps_per_contact` steps per Hertz time instead of the settings'.
    pub fn run_steps(
        &self,
        set: &SupportSet,
        s: &Striker,
        x: f64,
        z: f64,
        steps_per_contact: f64,
    ) -> Result<Outcome, ModelError> {
        let dt = s.hertz_time() / steps_per_contact;
        let mut nm = Newmark::damped(&self.model, set.supports, dt, (x, z), self.settings.damping)?;
        let facts = self.facts(&set.supports, x, z);
        Ok(simulate_with(s, Some(&mut nm), facts, dt, self.settings.window_contacts * s.hertz_time()))
    }
}

/// The first contact of `s` at (x, z) on `model` held by `supports` with the plate
/// `damping` (None: undamped), with the time step `dt`
/// and the window `t_max` (both in seconds) given directly: for runs timed by another
/// contact time than Hertz's (Zener's on a large plate) and for plate models built outside a
/// [`TransientCase`]. The run stops at the first separation: without the static compliance
/// nothing bounds the plate's later excursions ([`super::PlateFacts`]), so that is the last
/// instant its sequence is known to be the first contact's. The corner springs are known, so
/// the spring energy at maximum compression is exact rather than interpolated.
pub fn first_contact_on(
    model: &Model,
    (supports, damping): (Supports, Option<Rayleigh>),
    s: &Striker,
    (x, z): (f64, f64),
    dt: f64,
    t_max: f64,
) -> Result<Outcome, ModelError> {
    let mut nm = Newmark::damped(model, supports, dt, (x, z), damping)?;
    let facts = PlateFacts { corner_springs: Some(corner_springs(&supports)), ..PlateFacts::default() };
    Ok(simulate_with(s, Some(&mut nm), facts, dt, t_max))
}
