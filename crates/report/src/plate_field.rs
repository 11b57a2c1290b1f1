//! The plate at the impact's maximum force as colour maps: the deflection field w(x, z) and the
//! surface bending stress ([`studies::field::plate_at_peak`] computes them).
//!
//! It is the quasi-static field: where the case is not quasi-static the transient deflection
//! differs, and the captions carry the case's validity to say so. The stress is shown away
//! from the load only: under a point load the Kirchhoff moment is logarithmically singular, so
//! on the elements touching the load point it grows without bound as the mesh is refined (in
//! reality the contact patch, of radius a = √(Rδ), bounds it).

use crate::present::plot::{Axis, ColourMap, Mark};
use crate::Failure;
use scene::{Scene, SupportSet};
pub use studies::field::{PlateAtPeak, FIELD_ELEMENTS};

/// The two figures and the numbers the text quotes.
pub struct PeakField {
    /// The deflection's colour map.
    pub deflection_svg: String,
    /// The von Mises stress's colour map.
    pub stress_svg: String,
    /// The numbers behind them.
    pub data: PlateAtPeak,
}

/// The field of `cond` under `p_max` (N) at (x, z) (m) as two colour maps, each carrying
/// `notes` (the case and its validity).
pub fn peak_field(
    scene: &Scene,
    cond: &SupportSet,
    x: f64,
    z: f64,
    p_max: f64,
    notes: &[String],
) -> Result<PeakField, Failure> {
    let d = studies::field::plate_at_peak(scene, cond, x, z, p_max)?;
    let mm = |v: &[f64]| v.iter().map(|v| v * 1e3).collect::<Vec<_>>();
    let impact = Mark { x: x * 1e3, y: z * 1e3, label: format!("impact point ({:.1}, {:.1}) mm", x * 1e3, z * 1e3) };
    let deflection = ColourMap {
        title: format!(
            "{}: quasi-static deflection w at the quasi-static P_max = {} N",
            cond.name,
            crate::present::table::sig(p_max, 3)
        ),
        x: Axis::linear("x (mm)"),
        y: Axis::linear("z (mm)"),
        xs: mm(&d.xs),
        ys: mm(&d.zs),
        edges: false,
        values: d.w.iter().map(|col| col.iter().map(|w| w * 1e6).collect()).collect(),
        bar: Axis::linear("w (µm)"),
        missing: None,
        marks: vec![impact.clone()],
        notes: notes.to_vec(),
    };
    let (unit, unit_name) = if d.stress_max >= 1e6 { (1e6, "MPa") } else { (1e3, "kPa") };
    let stress = ColourMap {
        title: format!("{}: quasi-static surface bending stress (von Mises) at P_max", cond.name),
        x: Axis::linear("x (mm)"),
        y: Axis::linear("z (mm)"),
        xs: mm(&d.xs),
        ys: mm(&d.zs),
        edges: true,
        values: d.von_mises.iter().map(|col| col.iter().map(|s| s.map_or(f64::NAN, |s| s / unit)).collect()).collect(),
        bar: Axis::linear(format!("σ_vM of σ = 6M/h² ({unit_name})")),
        missing: Some(
            "within one plate thickness of the load: thin-plate theory does not hold there, and the point-load moment is singular".into(),
        ),
        marks: vec![impact],
        notes: notes.to_vec(),
    };
    Ok(PeakField { deflection_svg: deflection.svg(), stress_svg: stress.svg(), data: d })
}
