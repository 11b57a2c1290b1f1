//! The plate's fields recorded through a whole impact and the ringing after it: a recorder
//! sits between the transient loop and the plate's Newmark state and copies the deflection
//! w and the element-centre moments every few steps, so the run is the same run as without it
//! (the recorder only reads the state after each commit). Once the sphere has provably left,
//! the plate is stepped on free of force (the same Newmark rule, the same Δt) for a stated
//! time, and the frames go on at their own spacing.

use super::Sample;
use super::{simulate_with, Outcome, Striker, Target, TransientCase};
use crate::error::ModelError;
use plate_fem::dynamics::{Newmark, PlateEnergy};
use plate_fem::{Model, Supports};
use serde::Serialize;

/// One recorded field.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Frame {
    /// Steps committed when it was taken: 0 is the plate at rest at the touch.
    pub step: usize,
    /// Its time, s: the sum of the steps, as the run's history samples take it.
    pub t: f64,
    /// The deflection w at every node, in the mesh's node order, m.
    pub w: Vec<f64>,
    /// The element-centre bending moments M_x, M_z, M_xz per element, N·m/m.
    pub moments: Vec<[f64; 3]>,
}

/// A whole impact, the plate's free ringing after it, and the frames recorded through both.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Recorded {
    /// The run, exactly as without the recorder.
    pub outcome: Outcome,
    /// The steps of the ringing after the sphere left: no force, the sphere in uniform
    /// flight at its final velocity.
    pub ringing: Vec<Sample>,
    /// The rest state, every `every`-th step of the impact, every `every_after`-th of the
    /// ringing, and the last step when it is not one of them.
    pub frames: Vec<Frame>,
}

/// How long the plate rings on after the sphere has left, and the frames' spacing then.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ringing {
    /// Time, s (0: none).
    pub duration: f64,
    /// A frame every this many steps (0 is taken as 1).
    pub every: usize,
}

/// A plate target that records the fields every `every` commits.
struct Recorder<'a, 'm> {
    model: &'m Model,
    plate: &'a mut Newmark<'m>,
    every: usize,
    commits: usize,
    dt: f64,
    t: f64,
    frames: Vec<Frame>,
}

impl Recorder<'_, '_> {
    fn snapshot(&mut self) {
        let field = self.plate.field();
        // Four DOFs per node (w, w_x, w_z, w_xz), w first.
        let w: Vec<f64> = field.iter().step_by(4).copied().collect();
        let moments = self.model.centre_moments(field);
        self.frames.push(Frame { step: self.commits, t: self.t, w, moments });
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
        // The loop's own clock (t += Δt per step), so a frame's time is its sample's bit for bit.
        self.t += self.dt;
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
    fn damping_loss(&self) -> f64 {
        self.plate.damping_loss()
    }
}

/// One impact of `s` at (x, z) on the plate of `case` held by `supports`, followed through
/// every contact until the sphere has provably left or `t_max` ends (as
/// [`super::TransientCase::run`], with the step `dt`), with the fields recorded at the touch,
/// every `every` steps (0 is taken as 1) and at the run's last step; then, if the sphere has
/// provably left, `ringing` of the free plate.
#[allow(clippy::too_many_arguments)]
pub fn impact_frames(
    case: &TransientCase,
    supports: Supports,
    s: &Striker,
    (x, z): (f64, f64),
    dt: f64,
    t_max: f64,
    every: usize,
    ringing: Ringing,
) -> Result<Recorded, ModelError> {
    let model = case.model();
    let mut nm = Newmark::damped(model, supports, dt, (x, z), case.settings().damping)?;
    if nm.field().len() != 4 * model.mesh().nodes() {
        return Err(ModelError::Missing("the plate's field does not have four DOFs per node".into()));
    }
    let every = every.max(1);
    let mut rec = Recorder { model, plate: &mut nm, every, commits: 0, dt, t: 0.0, frames: Vec::new() };
    rec.snapshot();
    let outcome = simulate_with(s, Some(&mut rec), case.facts(&supports, x, z), dt, t_max);
    if rec.commits % rec.every != 0 {
        rec.snapshot();
    }
    let ringing = match (outcome.left_at, outcome.later_history.last().or(outcome.history.last())) {
        (Some(_), Some(last)) => ring(&mut rec, s, last, ringing),
        _ => Vec::new(),
    };
    Ok(Recorded { outcome, ringing, frames: rec.frames })
}

/// The free plate for `r.duration` after the run's `last` sample, a frame every `r.every`
/// steps and at the end; the sphere flies on at its final velocity.
fn ring(rec: &mut Recorder<'_, '_>, s: &Striker, last: &Sample, r: Ringing) -> Vec<Sample> {
    let steps = (r.duration / rec.dt).ceil() as usize;
    let (start, every) = (rec.commits, r.every.max(1));
    let e0 = 0.5 * s.mass * s.velocity * s.velocity;
    let sphere_at_end = last.compression + last.plate_displacement;
    let mut out = Vec::with_capacity(steps);
    for k in 1..=steps {
        rec.plate.predict();
        rec.plate.commit(0.0);
        rec.commits += 1;
        rec.t += rec.dt;
        let (wp, _) = rec.plate.point_state();
        let e = rec.plate.energy();
        let kin = 0.5 * s.mass * last.sphere_velocity * last.sphere_velocity;
        let sphere = sphere_at_end + last.sphere_velocity * (rec.t - last.t);
        out.push(Sample {
            t: rec.t,
            force: 0.0,
            compression: sphere - wp,
            sphere_velocity: last.sphere_velocity,
            plate_displacement: wp,
            sphere_kinetic: kin,
            contact: 0.0,
            plate_kinetic: e.kinetic,
            plate_strain: e.strain,
            springs: e.springs,
            dissipated: e0 - (kin + e.kinetic + e.strain + e.springs),
        });
        if k % every == 0 || k == steps {
            rec.snapshot();
        }
    }
    debug_assert_eq!(rec.commits, start + steps);
    out
}
