//! The plate's deflection during the contact, as a ParaView time series: one `.vtu` per
//! recorded step and a `.pvd` collection that names them with their times.
//!
//! The transient model (sphere, contact law and plate FE dynamics integrated together, the
//! same run as `impact dynamic`) is run once; a recorder between the integrator and the plate
//! copies the deflection field every few steps. Each `.vtu` has the point data `displacement`
//! = (0, 0, w), so "Warp By Vector" bends the plate in every frame, and `w`. Beside them,
//! `history.csv` holds every step of the run (time, force, compression, the struck point's
//! deflection): the frame at time t is the step of the same t, so the two can be checked
//! against each other.

use crate::present::table::Table;
use crate::transient::{striker, STEPS_PER_CONTACT};
use crate::Failure;
use analytic::Sphere;
use coupled::discretisation::{mesh_for, plate_properties};
use coupled::transient::{simulate_with, PlateFacts, Target};
use output::Artifacts;
use plate_fem::dynamics::{Newmark, PlateEnergy};
use plate_fem::Model;
use scene::{Scene, SupportSet};

/// Every `FRAME_EVERY`-th step is a frame: 200 steps per contact time give about 40 frames
/// over the contact, smooth enough to play and small enough to open at once.
pub const FRAME_EVERY: usize = 5;

/// A plate target that records the deflection field (the w DOFs) every `every` commits.
struct Recorder<'a, 'm> {
    plate: &'a mut Newmark<'m>,
    every: usize,
    commits: usize,
    /// (commit number, w at every node).
    frames: Vec<(usize, Vec<f64>)>,
}

impl Recorder<'_, '_> {
    fn snapshot(&mut self) {
        let w: Vec<f64> = self.plate.field().iter().step_by(4).copied().collect();
        self.frames.push((self.commits, w));
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

/// The `.pvd` collection: each data set with its time, in order.
pub fn pvd(frames: &[(f64, String)]) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for (t, file) in frames {
        // Shortest round-trip decimal: the time reads back as the same f64 as history.csv's.
        s.push_str(&format!("    <DataSet timestep=\"{t:?}\" group=\"\" part=\"0\" file=\"{file}\"/>\n"));
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    s
}

/// The series of `body` at `velocity` striking (x, z) of the plate under `cond`, on a mesh of
/// `elements` along the longer side: `contact.pvd`, `frames/step-NNNNN.vtu` and `history.csv`.
pub fn contact_series(
    scene: &Scene,
    cond: &SupportSet,
    body: &Sphere,
    velocity: f64,
    (x, z): (f64, f64),
    elements: usize,
) -> Result<Artifacts, Failure> {
    let props = plate_properties(&scene.plate);
    let mesh = mesh_for(&props, elements)?;
    let model = Model::new(props, mesh.clone())?;
    let s = striker(scene, body, velocity);
    let dt = s.hertz_time() / STEPS_PER_CONTACT;
    let mut nm = Newmark::new(&model, cond.supports, dt, x, z)?;
    if nm.field().len() != 4 * mesh.nodes() {
        return Err("the plate's field does not have four DOFs per node".into());
    }
    let mut rec = Recorder { plate: &mut nm, every: FRAME_EVERY, commits: 0, frames: vec![] };
    rec.snapshot();
    let o = simulate_with(&s, Some(&mut rec), PlateFacts::default(), dt, 20.0 * s.hertz_time());
    let mut frames = std::mem::take(&mut rec.frames);
    // The last step of the contact (separation) as the closing frame.
    if rec.commits % FRAME_EVERY != 0 {
        rec.snapshot();
        frames.append(&mut rec.frames);
    }
    let (nx, nz) = (mesh.nx(), mesh.nz());
    let mut points = Vec::with_capacity(mesh.nodes());
    for j in 0..=nz {
        for i in 0..=nx {
            points.push([mesh.xs()[i], mesh.zs()[j]]);
        }
    }
    let mut quads = Vec::with_capacity(mesh.elements());
    for ez in 0..nz {
        for ex in 0..nx {
            quads.push([mesh.node(ex, ez), mesh.node(ex + 1, ez), mesh.node(ex + 1, ez + 1), mesh.node(ex, ez + 1)]);
        }
    }
    let mut a = Artifacts::new();
    let mut listed = Vec::new();
    let title = format!("{}, {}, {} at {velocity} m/s", scene.name, cond.name, body.name);
    for (k, w) in &frames {
        // Commit k ends history sample k - 1; the start (k = 0) is t = 0.
        let t = if *k == 0 { 0.0 } else { o.history.get(k - 1).map_or(f64::NAN, |h| h.t) };
        if !t.is_finite() {
            continue;
        }
        let file = format!("frames/step-{k:05}.vtu");
        a.add(&file, crate::present::vtk::deflection_vtu(&title, &points, &quads, w)?);
        listed.push((t, file));
    }
    a.add("contact.pvd", pvd(&listed));
    let mut h =
        Table::new("", &["t (s)", "force (N)", "compression (m)", "plate displacement (m)", "sphere velocity (m/s)"]);
    for smp in &o.history {
        h.push(vec![
            smp.t.into(),
            smp.force.into(),
            smp.compression.into(),
            smp.plate_displacement.into(),
            smp.sphere_velocity.into(),
        ]);
    }
    a.add("history.csv", h.to_csv());
    Ok(a)
}
