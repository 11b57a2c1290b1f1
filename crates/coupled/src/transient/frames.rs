//! The plate's deflection field recorded during a first contact: a recorder sits between the
//! transient loop and the plate's Newmark state and copies the w DOFs every few steps, so the
//! run is the same run as without it (the recorder only reads the state after each commit).

use super::{simulate_with, Outcome, PlateFacts, Striker, Target};
use crate::error::ModelError;
use crate::transient::case::corner_springs;
use plate_fem::dynamics::{Newmark, PlateEnergy};
use plate_fem::{Model, Supports};
use serde::Serialize;

/// One recorded deflection field.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Frame {
    /// Steps committed when it was taken: 0 is the plate at rest at the touch, step k ends at
    /// the time of the run's history sample k - 1.
    pub step: usize,
    /// The deflection w at every node, in the mesh's node order, m.
    pub w: Vec<f64>,
}

/// A first contact and the frames recorded during it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Recorded {
    /// The run, exactly as [`super::case::first_contact_on`] gives it.
    pub outcome: Outcome,
    /// The rest state, every `every`-th step, and the last step when it is not one of them.
    pub frames: Vec<Frame>,
}

/// A plate target that records the deflection field (the w DOFs) every `every` commits.
struct Recorder<'a, 'm> {
    plate: &'a mut Newmark<'m>,
    every: usize,
    commits: usize,
    frames: Vec<Frame>,
}

impl Recorder<'_, '_> {
    fn snapshot(&mut self) {
        // Four DOFs per node (w, w_x, w_z, w_xz), w first.
        let w: Vec<f64> = self.plate.field().iter().step_by(4).copied().collect();
        self.frames.push(Frame { step: self.commits, w });
    }
}

impl Target for Recorder<'_, '_> {
    fn point_flexibility(&self) -> f64 {
        self.plate.point_flexibility()
    }
    fn predict(&mut self) -> (f64, f64) {
        self.plate.predict()
    }
    fn commit(&mut self, f: f64) {
        self.plate.commit(f);
        self.commits += 1;
        if self.commits % self.every == 0 {
            self.snapshot();
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

/// [`super::case::first_contact_on`] with the deflection field recorded at the touch, every
/// `every` steps (0 is taken as 1) and at the last step, the separation.
pub fn first_contact_frames(
    model: &Model,
    supports: Supports,
    s: &Striker,
    (x, z): (f64, f64),
    dt: f64,
    t_max: f64,
    every: usize,
) -> Result<Recorded, ModelError> {
    let mut nm = Newmark::new(model, supports, dt, x, z)?;
    if nm.field().len() != 4 * model.mesh().nodes() {
        return Err(ModelError::Missing("the plate's field does not have four DOFs per node".into()));
    }
    let every = every.max(1);
    let mut rec = Recorder { plate: &mut nm, every, commits: 0, frames: Vec::new() };
    rec.snapshot();
    let facts = PlateFacts { corner_springs: Some(corner_springs(&supports)), ..PlateFacts::default() };
    let outcome = simulate_with(s, Some(&mut rec), facts, dt, t_max);
    if rec.commits % every != 0 {
        rec.snapshot();
    }
    Ok(Recorded { outcome, frames: rec.frames })
}
