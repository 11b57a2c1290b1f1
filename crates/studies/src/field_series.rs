//! The plate through the whole impact and the ringing after it (`impact field --format pvd`):
//! the transient model (the same run as `impact dynamic`'s) with the deflection and the
//! element-centre moments recorded every few steps (`coupled::transient::frames`), then the
//! free plate for [`RINGING_PERIODS`] fundamental periods after the sphere has provably left,
//! each frame with its time, and the mesh to draw them on. The report crate writes them as a
//! ParaView time series.

use crate::settings::STEPS_PER_CONTACT;
use crate::Failure;
use analytic::Sphere;
use coupled::plan::scene_striker;
use coupled::transient::frames::{impact_frames, Ringing};
use coupled::transient::{Sample, TransientCase, TransientSettings};
use scene::{Scene, SupportSet};
use serde::Serialize;

/// Every `FRAME_EVERY`-th step is a frame: 200 steps per contact time give about 40 frames
/// over the contact, smooth enough to play and small enough to open at once.
pub const FRAME_EVERY: usize = 5;

/// The run's window in Hertz contact times. The run stops once the sphere has provably left
/// (on the paper's plates after one contact, within two Hertz times), so the window only
/// bounds an impact that does not end: to at most 20 x 200 / [`FRAME_EVERY`] = 800 frames,
/// where the library's window for whole impact sequences (200) would allow ten times as many
/// files.
pub const WINDOW_HERTZ_TIMES: f64 = 20.0;

/// The plate rings on after the sphere has left for this many fundamental periods T₁ (of the
/// supported plate), long enough to see its lowest mode swing both ways twice.
pub const RINGING_PERIODS: f64 = 2.0;

/// Frames per fundamental period while the plate rings: its lowest mode drawn smoothly, and
/// 40 more frames in all.
pub const RINGING_FRAMES_PER_PERIOD: f64 = 20.0;

/// One frame: the deflection at every node at one instant.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FieldFrame {
    /// Steps committed (0: at rest, at the touch).
    pub step: usize,
    /// Its time, s: that of the history sample of the same step.
    pub t: f64,
    /// w at every node, in the order of `points`, m.
    pub w: Vec<f64>,
    /// The element-centre bending moments M_x, M_z, M_xz per element (in the order of
    /// `quads`), N·m/m.
    pub moments: Vec<[f64; 3]>,
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
    /// The plate's thickness h, m (the surface bending stress is σ = 6M/h²).
    pub thickness: f64,
    /// The struck point (x, z), m.
    pub load: [f64; 2],
    /// The frames in time order.
    pub frames: Vec<FieldFrame>,
    /// Every step of the run: its contacts, the flight until the sphere provably left, and the
    /// ringing.
    pub history: Vec<Sample>,
    /// When the sphere left for good (None: the window ended first, and no ringing follows), s.
    pub left_at: Option<f64>,
}

/// `body` at `velocity` striking (x, z) of the plate under `cond`, on a mesh of `elements`
/// along the longer side, with a frame every [`FRAME_EVERY`] steps and at the run's end, then
/// [`RINGING_FRAMES_PER_PERIOD`] per period for [`RINGING_PERIODS`] periods of ringing.
pub fn contact_series(
    scene: &Scene,
    cond: &SupportSet,
    body: &Sphere,
    velocity: f64,
    (x, z): (f64, f64),
    elements: usize,
) -> Result<FieldSeries, Failure> {
    let case = TransientCase::new(
        &scene.plate,
        TransientSettings { elements, damping: scene.plate_damping, ..TransientSettings::default() },
    )?;
    let mesh = case.model().mesh();
    let s = scene_striker(scene, body, velocity);
    let dt = s.hertz_time() / STEPS_PER_CONTACT;
    let t_max = WINDOW_HERTZ_TIMES * s.hertz_time();
    let period = case.fundamental_period(&cond.supports)?;
    let ringing = Ringing {
        duration: RINGING_PERIODS * period,
        every: ((period / RINGING_FRAMES_PER_PERIOD / dt).round() as usize).max(1),
    };
    let run = impact_frames(&case, cond.supports, &s, (x, z), dt, t_max, FRAME_EVERY, ringing)?;
    let (points, quads) = (mesh.node_points(), mesh.quads());
    let frames =
        run.frames.into_iter().map(|f| FieldFrame { step: f.step, t: f.t, w: f.w, moments: f.moments }).collect();
    let left_at = run.outcome.left_at;
    let history = [run.outcome.history, run.outcome.later_history, run.ringing].concat();
    let title = format!("{}, {}, {} at {velocity} m/s", scene.name, cond.name, body.name);
    let thickness = scene.plate.thickness();
    Ok(FieldSeries { title, points, quads, thickness, load: [x, z], frames, history, left_at })
}
