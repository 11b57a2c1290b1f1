//! The plate at the impact's maximum force: the deflection field w(x, z) and the surface
//! bending stress, as colour maps.
//!
//! The plate model is linear, so the field under the quasi-static maximum force P_max is the
//! unit-load field ([`crate::field`]) times P_max. It is the quasi-static field: where
//! the case is not quasi-static the transient deflection differs, and the captions carry the
//! case's validity to say so. The stress is the von Mises stress
//! of the surface bending stresses σ = 6M/h² (M_x, M_z, M_xz at the element centres),
//! σ_vM = √(σ_x² − σ_xσ_z + σ_z² + 3τ_xz²), the quantity a steel plate's yield is judged by.
//! It is shown away from the load only: under a point load the Kirchhoff moment is
//! logarithmically singular, so on the elements touching the load point it grows without
//! bound as the mesh is refined (in reality the contact patch, of radius a = √(Rδ), bounds it).

use crate::field::{field, FieldFile};
use crate::present::plot::{Axis, ColourMap, Mark};
use crate::Failure;
use scene::{Scene, SupportSet};

/// Elements along the longer side of the field's mesh: fine enough that the colour map is
/// smooth at figure size (81 x 64 nodes on the paper's plate), a fraction of a second.
pub const FIELD_ELEMENTS: usize = 80;

/// The two figures and the numbers the text quotes.
pub struct PeakField {
    pub deflection_svg: String,
    pub stress_svg: String,
    /// Largest deflection, m, and where (x, z) in m.
    pub w_max: f64,
    pub w_max_at: (f64, f64),
    /// Largest von Mises surface stress away from the load, Pa, and where.
    pub stress_max: f64,
    pub stress_max_at: (f64, f64),
    /// Elements left out around the load point (within one thickness, or touching it).
    pub left_out: usize,
}

/// Von Mises stress of plane stress (σ_x, σ_z, τ_xz).
fn von_mises(sx: f64, sz: f64, t: f64) -> f64 {
    (sx * sx - sx * sz + sz * sz + 3.0 * t * t).sqrt()
}

/// Node values as a grid [i][j] over the mesh's x and z lines.
fn node_grid(f: &FieldFile, v: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<Vec<f64>>) {
    let mut xs: Vec<f64> = f.points.iter().map(|p| p[0]).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let mut zs: Vec<f64> = f.points.iter().map(|p| p[1]).collect();
    zs.sort_by(f64::total_cmp);
    zs.dedup();
    // Node (i, j) is number j·(nx+1) + i.
    let nx1 = xs.len();
    let grid = (0..xs.len()).map(|i| (0..zs.len()).map(|j| v[j * nx1 + i]).collect()).collect();
    (xs, zs, grid)
}

/// The quasi-static field of `cond` under the quasi-static force `p_max` (N) at (x, z) (m),
/// with the caption's notes (the case, its validity).
pub fn peak_field(
    scene: &Scene,
    cond: &SupportSet,
    x: f64,
    z: f64,
    p_max: f64,
    notes: &[String],
) -> Result<PeakField, Failure> {
    let f = field(scene, cond, x, z, FIELD_ELEMENTS)?;
    let w: Vec<f64> = f.point_data.w.iter().map(|w| w * p_max).collect();
    let (xs, zs, grid) = node_grid(&f, &w);
    let (imax, _) = w.iter().enumerate().fold((0, f64::NEG_INFINITY), |a, (i, &v)| if v > a.1 { (i, v) } else { a });
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
        xs: mm(&xs),
        ys: mm(&zs),
        edges: false,
        values: grid.iter().map(|col| col.iter().map(|w| w * 1e6).collect()).collect(),
        bar: Axis::linear("w (µm)"),
        missing: None,
        marks: vec![impact.clone()],
        notes: notes.to_vec(),
    };

    let [sx, sz, sxz] = f.stresses();
    // Element centres, in the mesh's element order (ex fastest).
    let cx: Vec<f64> = xs.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
    let cz: Vec<f64> = zs.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
    let ne = cx.len();
    // Left out: the elements touching the load, and every element whose centre is within one
    // plate thickness of it, where thin-plate theory does not describe the stress (the
    // contact's 3-D stress state) and the sampled singularity still dominates.
    let h = scene.plate.thickness();
    let touching = f.near_load();
    let near: Vec<bool> = (0..sx.len()).map(|e| touching[e] || (cx[e % ne] - x).hypot(cz[e / ne] - z) < h).collect();
    let vm: Vec<f64> =
        (0..sx.len()).map(|e| if near[e] { f64::NAN } else { p_max * von_mises(sx[e], sz[e], sxz[e]) }).collect();
    let (emax, smax) =
        vm.iter().enumerate().fold((0, f64::NEG_INFINITY), |a, (e, &v)| if v > a.1 { (e, v) } else { a });
    let (unit, unit_name) = if smax >= 1e6 { (1e6, "MPa") } else { (1e3, "kPa") };
    let stress = ColourMap {
        title: format!("{}: quasi-static surface bending stress (von Mises) at P_max", cond.name),
        x: Axis::linear("x (mm)"),
        y: Axis::linear("z (mm)"),
        xs: mm(&xs),
        ys: mm(&zs),
        edges: true,
        values: (0..ne).map(|i| (0..cz.len()).map(|j| vm[j * ne + i] / unit).collect()).collect(),
        bar: Axis::linear(format!("σ_vM of σ = 6M/h² ({unit_name})")),
        missing: Some(
            "within one plate thickness of the load: thin-plate theory does not hold there, and the point-load moment is singular".into(),
        ),
        marks: vec![impact],
        notes: notes.to_vec(),
    };
    Ok(PeakField {
        deflection_svg: deflection.svg(),
        stress_svg: stress.svg(),
        w_max: w[imax],
        w_max_at: (f.points[imax][0], f.points[imax][1]),
        stress_max: smax,
        stress_max_at: (cx[emax % ne], cz[emax / ne]),
        left_out: near.iter().filter(|&&n| n).count(),
    })
}
