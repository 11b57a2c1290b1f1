//! The comparison's own studies: how the plate/beam ratio depends on the width, both models
//! on extreme inputs, and the plate model's error against its run time.

use super::scene_points;
use crate::settings::{BASE_MESH, LEVELS};
use crate::Failure;
use analytic::Condition;
use coupled::{BeamModel, ComplianceModel, PlateModel};
use scene::{Scene, SupportSet};
use serde::Serialize;
use std::time::Instant;

/// The widths of the width study, as B/L.
pub const WIDTH_RATIOS: [f64; 7] = [0.1, 0.25, 0.5, 0.785, 1.0, 1.5, 2.0];
/// The spring stiffnesses of the extreme cases, N/m.
pub const EXTREME_SPRINGS: [f64; 4] = [1.0, 5e4, 5.11545e8, 1e15];
/// The velocities of the extreme cases, m/s.
pub const EXTREME_VELOCITIES: [f64; 4] = [1e-6, 1e-3, 1.0, 10.0];
/// The thicknesses of the extreme cases, m.
pub const EXTREME_THICKNESSES: [f64; 2] = [0.5e-3, 80e-3];
/// The velocity of the extreme spring and thickness cases, m/s (the paper's Table 3).
const EXTREME_VELOCITY: f64 = 0.008;
/// The tolerances the error-against-time study recommends a mesh for.
pub const TOLERANCES: [f64; 4] = [1e-2, 1e-3, 1e-4, 1e-5];

/// One width of the width study: C_plate/C_beam (Con 1) at three points.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WidthRow {
    /// B/L.
    pub width_ratio: f64,
    /// At x = L/2 on the centreline.
    pub centre: f64,
    /// At x = L/2 on the free edge z = 0.
    pub free_edge: f64,
    /// At Area 2 (x = L/4) on the centreline.
    pub quarter_span: f64,
    /// The FE error estimate of the centre compliance, relative to it.
    pub fe_error: f64,
}

/// Ratio C_plate/C_beam at x = L/2 on the centreline and the free edge, Con 1, for a range
/// of widths (the beam is the same B-proportional stiffness at every width).
pub fn width_dependence(scene: &Scene) -> Result<Vec<WidthRow>, Failure> {
    let l = scene.plate.length();
    let mut rows = Vec::new();
    for bl in WIDTH_RATIOS {
        let plate = scene.plate.with_width(bl * l)?;
        let s = Scene { plate, ..scene.clone() };
        let cond = SupportSet::preset("Con 1", Condition::BothFixed);
        let b = plate.width();
        let pts = [(l / 2.0, b / 2.0), (l / 2.0, 0.0), (l / 4.0, b / 2.0)];
        // Near-square elements, 20 (then 40) along the longer side.
        let model = PlateModel::compute(&s.plate, std::slice::from_ref(&cond), &pts, BASE_MESH, LEVELS)?;
        let beam = BeamModel { plate: &s.plate };
        let r = |p: (f64, f64)| -> Result<(f64, f64), Failure> {
            let fe = model.get("Con 1", p.0, p.1).ok_or("missing")?;
            Ok((
                fe.compliance.total() / beam.compliance(&cond, p.0, 0.0)?.compliance.total(),
                fe.error_estimate / fe.compliance.total(),
            ))
        };
        let (centre, fe_error) = r(pts[0])?;
        rows.push(WidthRow { width_ratio: bl, centre, free_edge: r(pts[1])?.0, quarter_span: r(pts[2])?.0, fe_error });
    }
    Ok(rows)
}

/// An extreme input.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum ExtremeCase {
    /// Con 2 with corner springs `k_t` (N/m).
    Spring {
        /// k_T, N/m.
        k_t: f64,
        /// m/s.
        velocity: f64,
    },
    /// Con 1 at velocity `velocity` (m/s).
    Velocity {
        /// m/s.
        velocity: f64,
    },
    /// Con 1 on a plate of thickness `thickness` (m).
    Thickness {
        /// h, m.
        thickness: f64,
        /// m/s.
        velocity: f64,
    },
}

/// Both models on one extreme input at one point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExtremeRow {
    /// The input.
    pub case: ExtremeCase,
    /// The point's name.
    pub point: String,
    /// The beam's P_max, N (NaN where the balance did not converge).
    pub beam_force: f64,
    /// The plate's P_max, N.
    pub plate_force: f64,
    /// The beam balance's residual.
    pub beam_residual: f64,
    /// The plate balance's residual.
    pub plate_residual: f64,
    /// The plate's FE error estimate, relative.
    pub fe_error: f64,
    /// Both converged, finite.
    pub stable: bool,
}

/// The extreme inputs of `scene` as (case, scene, support set, velocity).
fn extreme_inputs(scene: &Scene) -> Result<Vec<(ExtremeCase, Scene, SupportSet, f64)>, Failure> {
    let (l, b) = (scene.plate.length(), scene.plate.width());
    let v = EXTREME_VELOCITY;
    let mut cases = Vec::new();
    for k in EXTREME_SPRINGS {
        let con2 = SupportSet::preset("Con 2", Condition::BothSprings { k_t: k });
        cases.push((ExtremeCase::Spring { k_t: k, velocity: v }, scene.clone(), con2, v));
    }
    let con1 = SupportSet::preset("Con 1", Condition::BothFixed);
    for vv in EXTREME_VELOCITIES {
        cases.push((ExtremeCase::Velocity { velocity: vv }, scene.clone(), con1.clone(), vv));
    }
    for h in EXTREME_THICKNESSES {
        let plate = analytic::Plate::new(l, b, h, scene.plate.density(), scene.plate.material())?;
        cases.push((
            ExtremeCase::Thickness { thickness: h, velocity: v },
            Scene { plate, ..scene.clone() },
            con1.clone(),
            v,
        ));
    }
    Ok(cases)
}

/// Both models on extreme inputs: do they stay finite, converged and stable?
pub fn extreme_cases(scene: &Scene) -> Result<Vec<ExtremeRow>, Failure> {
    let body = scene.bodies.first().ok_or("the scene has no body")?;
    let (l, b) = (scene.plate.length(), scene.plate.width());
    let points = [("centre", (l / 2.0, b / 2.0)), ("end (0, B/2)", (0.0, b / 2.0)), ("edge (L/2, 0)", (l / 2.0, 0.0))];
    let mut out = Vec::new();
    for (case, s, cond, v) in extreme_inputs(scene)? {
        let pts: Vec<(f64, f64)> = points.iter().map(|p| p.1).collect();
        let model = PlateModel::compute(&s.plate, std::slice::from_ref(&cond), &pts, BASE_MESH, LEVELS)?;
        let beam = BeamModel { plate: &s.plate };
        let imp = coupled::plan::impact_of(&s, body, v);
        for (pname, (x, z)) in points {
            let cb = beam.compliance(&cond, x, z)?.compliance;
            let fe = model.get(&cond.name, x, z).ok_or("missing")?;
            let rb = analytic::respond(&imp, &cb, s.solver);
            let rp = analytic::respond(&imp, &fe.compliance, s.solver);
            let force = |r: &Result<analytic::Response, analytic::NotConverged>| {
                r.as_ref().map_or(f64::NAN, |r| r.contact_force)
            };
            let res = |r: &Result<analytic::Response, analytic::NotConverged>| {
                r.as_ref().map_or(f64::NAN, |r| r.solution.residual)
            };
            let (pb, pp) = (force(&rb), force(&rp));
            out.push(ExtremeRow {
                case,
                point: pname.into(),
                beam_force: pb,
                plate_force: pp,
                beam_residual: res(&rb),
                plate_residual: res(&rp),
                fe_error: fe.error_estimate / fe.compliance.total(),
                stable: rb.is_ok()
                    && rp.is_ok()
                    && pb.is_finite()
                    && pp.is_finite()
                    && fe.compliance.total().is_finite(),
            });
        }
    }
    Ok(out)
}

/// One mesh of the error-against-time ladder.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MeshRun {
    /// Elements along the length.
    pub nx: usize,
    /// Elements across the width.
    pub nz: usize,
    /// Degrees of freedom.
    pub dofs: usize,
    /// Its run time, s.
    pub seconds: f64,
    /// The largest relative error over the scene's points and support sets.
    pub max_error: f64,
    /// The median.
    pub median_error: f64,
}

/// The coarsest mesh within a tolerance.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Recommendation {
    /// The tolerance on the largest relative error.
    pub tolerance: f64,
    /// The index in [`ErrorVsTime::runs`] of the coarsest mesh within it; none when only a
    /// mesh finer than the ladder would do.
    pub run: Option<usize>,
}

/// The plate compliance's error against run time.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorVsTime {
    /// Every mesh of the ladder but the finest, coarsest first.
    pub runs: Vec<MeshRun>,
    /// The coarsest mesh for each of [`TOLERANCES`].
    pub recommended: Vec<Recommendation>,
    /// The two finest meshes (nx, nz), whose Richardson value is the reference.
    pub reference_meshes: [(usize, usize); 2],
}

/// Error of the plate compliances at the scene's points against run time, for a ladder of
/// five meshes; the reference is the Richardson value of the two finest.
pub fn error_vs_time(scene: &Scene) -> Result<ErrorVsTime, Failure> {
    let pts = scene_points(scene);
    let mut runs: Vec<(usize, usize, usize, f64, Vec<f64>)> = Vec::new();
    for mesh in coupled::discretisation::ladder_meshes(&coupled::discretisation::plate_properties(&scene.plate), 10, 5)?
    {
        let t = Instant::now();
        let m = PlateModel::on_meshes(&scene.plate, &scene.conditions, &pts, vec![mesh])?;
        let secs = t.elapsed().as_secs_f64();
        let lv = m.levels.last().ok_or("no level")?.clone();
        let mut vals = Vec::new();
        for c in &scene.conditions {
            for &(x, z) in &pts {
                vals.push(m.get(&c.name, x, z).ok_or("missing")?.compliance.total());
            }
        }
        runs.push((lv.nx, lv.nz, lv.dofs, secs, vals));
    }
    let n = runs.len();
    let reference: Vec<f64> = runs[n - 1].4.iter().zip(&runs[n - 2].4).map(|(f, c)| f + (f - c) / 3.0).collect();
    let mut out = Vec::new();
    for (nx, nz, dofs, secs, vals) in &runs[..n - 1] {
        let mut e: Vec<f64> =
            vals.iter().zip(&reference).filter(|(_, r)| r.abs() > 0.0).map(|(v, r)| (v - r).abs() / r.abs()).collect();
        e.sort_by(f64::total_cmp);
        let max_error = *e.last().unwrap_or(&0.0);
        let median_error = e.get(e.len() / 2).copied().unwrap_or(0.0);
        out.push(MeshRun { nx: *nx, nz: *nz, dofs: *dofs, seconds: *secs, max_error, median_error });
    }
    let recommended = TOLERANCES
        .iter()
        .map(|&tolerance| Recommendation { tolerance, run: out.iter().position(|r| r.max_error <= tolerance) })
        .collect();
    let mesh = |r: &(usize, usize, usize, f64, Vec<f64>)| (r.0, r.1);
    Ok(ErrorVsTime { runs: out, recommended, reference_meshes: [mesh(&runs[n - 2]), mesh(&runs[n - 1])] })
}
