//! `impact compare`: the paper's beam model and the plate FE model through the same energy
//! balance (eqs. 14, 25, 46) and yield model (eqs. 51-54), and where and by how much they
//! differ.
//!
//! * [`findings`]: the ranges of plate/beam - 1 at the scene's points, per support set;
//! * [`maps`](mod@maps): both models' compliance over the plate, and its statistics away from the ends
//!   (where the beam's C falls to 0 and the ratio diverges);
//! * [`extra`]: the width study (the plate tends to the beam as B/L → 0), both models on
//!   extreme inputs, and the plate model's error against run time;
//! * [`shear`](mod@shear): the Reissner-Mindlin plate against Kirchhoff's at the scene's points.
//!
//! The beam describes only Con 1-3; the plate every support set. One plate model (one
//! factorization per mesh) holds the scene's points and the map grid.

pub mod extra;
pub mod findings;
pub mod maps;
pub mod shear;

pub use extra::{
    error_vs_time, extreme_cases, width_dependence, ErrorVsTime, ExtremeCase, ExtremeRow, MeshRun, Recommendation,
    WidthRow, EXTREME_SPRINGS, EXTREME_THICKNESSES, EXTREME_VELOCITIES, WIDTH_RATIOS,
};
pub use findings::{point_findings, PointFinding};
pub use maps::{map_findings, map_points, maps, maps_from, MapFinding, Maps, INNER};
pub use shear::{Shear, ShearRow};

use crate::progress::Progress;
use crate::settings::{BASE_MESH, LEVELS};
use crate::Failure;
use coupled::plan::{fundamental_periods, run, ModelKind, Results};
use coupled::{BeamModel, PlateModel, Validity};
use scene::{Analysis, Scene};
use serde::Serialize;
use std::time::Instant;

/// Beam and plate results for the same scene, with the plate model that gave them.
pub struct Pair {
    /// The beam's rows.
    pub beam: Results,
    /// The plate's rows.
    pub plate: Results,
    /// The plate model.
    pub model: PlateModel,
}

/// All (x, z) pairs of the scene's points.
pub fn scene_points(scene: &Scene) -> Vec<(f64, f64)> {
    scene.point_pairs()
}

/// Runs both models on the scene's own points.
pub fn pair(scene: &Scene) -> Result<Pair, Failure> {
    pair_on(scene, PlateModel::compute(&scene.plate, &scene.conditions, &scene_points(scene), BASE_MESH, LEVELS)?)
}

/// Runs both models on the scene's points with a plate model already computed there.
pub fn pair_on(scene: &Scene, model: PlateModel) -> Result<Pair, Failure> {
    let periods = fundamental_periods(scene)?;
    let beam = run(scene, &BeamModel { plate: &scene.plate }, ModelKind::Beam, &periods)?;
    let plate = run(scene, &model, ModelKind::Plate, &periods)?;
    Ok(Pair { beam, plate, model })
}

/// The row of `other` for the same case (support set, body, point and velocity) as `row`.
pub fn same_case<'a>(other: &'a Results, row: &coupled::ResponseRow) -> Option<&'a coupled::ResponseRow> {
    other.responses.iter().find(|b| {
        b.condition == row.condition && b.body == row.body && b.x == row.x && b.z == row.z && b.velocity == row.velocity
    })
}

/// The row of `other` for the same yield cell (support set, body and point) as `row`.
pub fn same_cell<'a>(other: &'a Results, row: &coupled::YieldRow) -> Option<&'a coupled::YieldRow> {
    other.yields.iter().find(|b| b.condition == row.condition && b.body == row.body && b.x == row.x && b.z == row.z)
}

/// One mesh of the plate model's ladder.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MeshLevel {
    /// Elements along the length.
    pub nx: usize,
    /// Elements across the width.
    pub nz: usize,
    /// Degrees of freedom.
    pub dofs: usize,
}

/// The impact whose plate at P_max the report shows: the first support set, body and velocity
/// of the scene at its point nearest the plate's centre (the typical impact).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PeakCase {
    /// The support set's name.
    pub condition: String,
    /// The body's name.
    pub body: String,
    /// The impact velocity, m/s.
    pub velocity: f64,
    /// The impact point, m.
    pub point: (f64, f64),
    /// The plate model's quasi-static P_max, N.
    pub p_max: f64,
    /// The case's validity.
    pub validity: Validity,
}

/// What the comparison computed; a study the scene does not name is `None`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ComparisonData {
    /// The beam's rows at the scene's points.
    pub beam: Results,
    /// The plate's rows at the scene's points.
    pub plate: Results,
    /// The plate model's meshes, coarse to fine.
    pub mesh_levels: Vec<MeshLevel>,
    /// Per support set the beam describes, plate against beam at the scene's points.
    pub points: Vec<PointFinding>,
    /// The impact whose plate at P_max is shown (responses only).
    pub peak: Option<PeakCase>,
    /// The compliance maps.
    pub maps: Option<Maps>,
    /// The maps' statistics, per support set the beam describes.
    pub map_findings: Vec<MapFinding>,
    /// The width study.
    pub width: Option<Vec<WidthRow>>,
    /// The extreme cases.
    pub extremes: Option<Vec<ExtremeRow>>,
    /// The error against run time.
    pub error_vs_time: Option<ErrorVsTime>,
    /// Mindlin against Kirchhoff at the scene's points.
    pub shear: Option<Shear>,
    /// Seconds the comparison took.
    pub seconds: f64,
}

/// The impact of [`PeakCase`] among the plate's rows, if the scene has one.
pub fn peak_case(scene: &Scene, plate: &Results) -> Option<PeakCase> {
    let (cond, body, &v) = (scene.conditions.first()?, scene.bodies.first()?, scene.velocities.first()?);
    let (cx, cz) = (scene.plate.length() / 2.0, scene.plate.width() / 2.0);
    let row = plate
        .responses
        .iter()
        .filter(|r| r.condition == cond.name && r.body == body.name && r.velocity == v && r.values().is_some())
        .min_by(|a, b| (a.x - cx).hypot(a.z - cz).total_cmp(&(b.x - cx).hypot(b.z - cz)))?;
    let values = row.values()?;
    Some(PeakCase {
        condition: cond.name.clone(),
        body: body.name.clone(),
        velocity: v,
        point: (row.x, row.z),
        p_max: values.contact_force,
        validity: values.validity,
    })
}

/// The comparison of `scene`: both models at its points (and the map grid where the scene asks
/// for maps), then the studies it names.
pub fn compute(scene: &Scene, progress: &dyn Progress) -> Result<ComparisonData, Failure> {
    let t0 = Instant::now();
    progress.start(5, "beam against plate FE");
    let mut points = scene_points(scene);
    let want_maps = scene.wants(Analysis::WidthMaps);
    if want_maps {
        points.extend(map_points(scene));
    }
    let pr = pair_on(scene, PlateModel::compute(&scene.plate, &scene.conditions, &points, BASE_MESH, LEVELS)?)?;
    progress.advance(1);
    let maps = if want_maps { Some(maps_from(scene, &pr.model)?) } else { None };
    progress.advance(1);
    let map_findings = maps.as_ref().map_or_else(Vec::new, |m| map_findings(scene, m));
    progress.advance(1);
    let width = if scene.wants(Analysis::AspectRatio) { Some(width_dependence(scene)?) } else { None };
    progress.advance(1);
    let extremes = if scene.wants(Analysis::ExtremeCases) { Some(extreme_cases(scene)?) } else { None };
    let error_vs_time = if scene.wants(Analysis::ErrorVsTime) { Some(error_vs_time(scene)?) } else { None };
    let shear =
        if scene.wants(Analysis::TransverseShear) { Some(shear::shear(scene, &pr.model, &pr.plate)?) } else { None };
    progress.advance(1);
    progress.finish();
    let peak = if scene.wants(Analysis::Responses) { peak_case(scene, &pr.plate) } else { None };
    Ok(ComparisonData {
        points: point_findings(scene, &pr.beam, &pr.plate),
        peak,
        mesh_levels: pr.model.levels.iter().map(|c| MeshLevel { nx: c.nx, nz: c.nz, dofs: c.dofs }).collect(),
        beam: pr.beam,
        plate: pr.plate,
        maps,
        map_findings,
        width,
        extremes,
        error_vs_time,
        shear,
        seconds: t0.elapsed().as_secs_f64(),
    })
}
