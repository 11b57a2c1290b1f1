//! The plate through the whole impact and its ringing after, as a ParaView time series: one
//! `.vtu` per recorded step and a `.pvd` collection that names them with their times.
//!
//! The transient model (sphere, contact law and plate FE dynamics integrated together, the
//! same run as `impact dynamic`) is run once with the deflection and the moments recorded
//! every few steps, then the free plate rings on ([`studies::field_series`]). Each `.vtu` has
//! the point data `displacement_m` = (0, 0, w), so "Warp By Vector" bends the plate in every
//! frame, and `w_m`; the cell data the moments, the surface bending stresses and `near_load`
//! ([`crate::present::vtk::frame_vtu`]). Beside them, `history.csv` holds every step of the run
//! (time, force, compression, the struck point's deflection, the sphere's velocity), the
//! ringing included: the frame at time t is the step of the same t, so the two can be checked
//! against each other.

use crate::present::table::Table;
use crate::Failure;
use analytic::Sphere;
use output::Artifacts;
use scene::{Scene, SupportSet};
pub use studies::field_series::{FieldFrame, FieldSeries, FRAME_EVERY};

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
    point: (f64, f64),
    elements: usize,
) -> Result<Artifacts, Failure> {
    write(&studies::field_series::contact_series(scene, cond, body, velocity, point, elements)?)
}

/// The files of a recorded series.
pub fn write(series: &FieldSeries) -> Result<Artifacts, Failure> {
    let mut a = Artifacts::new();
    let mut listed = Vec::new();
    for f in &series.frames {
        let file = format!("frames/step-{:05}.vtu", f.step);
        let mesh = (&series.points[..], &series.quads[..]);
        let fields = (&f.w[..], &f.moments[..]);
        a.add(&file, crate::present::vtk::frame_vtu(&series.title, mesh, fields, series.thickness, series.load)?);
        listed.push((f.t, file));
    }
    a.add("contact.pvd", pvd(&listed));
    let mut h =
        Table::new("", &["t (s)", "force (N)", "compression (m)", "plate displacement (m)", "sphere velocity (m/s)"]);
    for smp in &series.history {
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
