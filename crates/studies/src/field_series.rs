//! The plate's deflection during the contact (`impact field --format pvd`): the transient
//! model (the same run as `impact dynamic`'s) with the deflection field recorded every few
//! steps (`coupled::transient::frames`), each frame with its time, and the mesh to draw them
//! on. The report crate writes them as a ParaView time series.

use crate::settings::STEPS_PER_CONTACT;
use crate::Failure;
use analytic::Sphere;
use coupled::plan::scene_striker;
use coupled::transient::frames::first_contact_frames;
use coupled::transient::{Sample, TransientCase, TransientSettings};
use scene::{Scene, SupportSet};
use serde::Serialize;

/// Every `FRAME_EVERY`-th step is a frame: 200 steps per contact time give about 40 frames
/// over the contact, smooth enough to play and small enough to open at once.
pub const FRAME_EVERY: usize = 5;

/// The run's window in Hertz contact times. The run stops at the first separation (on the
/// paper's plates within two Hertz times), so the window only bounds a first contact that
/// does not end: to at most 20 x 200 / [`FRAME_EVERY`] = 800 frames, where the library's
/// window for whole impact sequences (200) would allow ten times as many files.
pub const WINDOW_HERTZ_TIMES: f64 = 20.0;

/// One frame: the deflection at every node at one instant.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FieldFrame {
    /// Steps committed (0: at rest, at the touch).
    pub step: usize,
    /// Its time, s: that of the history sample of the same step.
    pub t: f64,
    /// w at every node, in the order of `points`, m.
    pub w: Vec<f64>,
}

/// The deflection during one first contact, with the mesh to draw it on.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FieldSeries {
    /// "scene, support set, body at v m/s".
    pub title: String,
    /// The mesh's nodes (x, z), m, row by row along x.
    pub points: Vec<[f64; 2]>,
    /// The elements as four node indices: (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1).
    pub quads: Vec<[usize; 4]>,
    /// The frames in time order.
    pub frames: Vec<FieldFrame>,
    /// Every step of the run.
    pub history: Vec<Sample>,
}

/// `body` at `velocity` striking (x, z) of the plate under `cond`, on a mesh of `elements`
/// along the longer side, with a frame every [`FRAME_EVERY`] steps and at the separation.
pub fn contact_series(
    scene: &Scene,
    cond: &SupportSet,
    body: &Sphere,
    velocity: f64,
    (x, z): (f64, f64),
    elements: usize,
) -> Result<FieldSeries, Failure> {
    let case = TransientCase::new(&scene.plate, TransientSettings { elements, ..TransientSettings::default() })?;
    let mesh = case.model().mesh();
    let s = scene_striker(scene, body, velocity);
    let dt = s.hertz_time() / STEPS_PER_CONTACT;
    let t_max = WINDOW_HERTZ_TIMES * s.hertz_time();
    let run = first_contact_frames(case.model(), cond.supports, &s, (x, z), dt, t_max, FRAME_EVERY)?;
    let (points, quads) = (mesh.node_points(), mesh.quads());
    let history = run.outcome.history;
    let frames = run
        .frames
        .into_iter()
        .filter_map(|f| {
            // Step k ends history sample k - 1; the start (k = 0) is t = 0.
            let t = if f.step == 0 { 0.0 } else { history.get(f.step - 1).map_or(f64::NAN, |h| h.t) };
            t.is_finite().then_some(FieldFrame { step: f.step, t, w: f.w })
        })
        .collect();
    let title = format!("{}, {}, {} at {velocity} m/s", scene.name, cond.name, body.name);
    Ok(FieldSeries { title, points, quads, frames, history })
}
