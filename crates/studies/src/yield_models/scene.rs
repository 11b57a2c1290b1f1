//! The three-model yield study on a scene of one's own: the yield velocity of every body
//! under every support set at the scene's transient points, by the beam (Con 1-3 only), the
//! quasi-static plate and the transient plate (with the scene's contact law), each with its
//! error estimate, and whether the transient v_y lies below the quasi-static plate's by more
//! than both errors.

use crate::progress::Progress;
use crate::settings::Settings;
use crate::verdict::Verdict;
use crate::Failure;
use coupled::plan::{self, ModelKind, YieldRow, YieldValues};
use coupled::{Analysis, BeamModel, PlateModel, Points, Validity};
use scene::Scene;
use serde::Serialize;

/// One cell: a body under a support set at a transient point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SceneYieldRow {
    /// Body name.
    pub body: String,
    /// Support set name.
    pub condition: String,
    /// The point, m.
    pub x: f64,
    /// z, m.
    pub z: f64,
    /// The beam's v_y, m/s, where the beam describes the set.
    pub beam: Option<f64>,
    /// The quasi-static plate's v_y, m/s.
    pub plate: f64,
    /// Its error estimate, m/s (0 where it has none).
    pub plate_error: f64,
    /// The transient v_y, m/s.
    pub transient: f64,
    /// Its error estimate (bracket and discretisation), m/s (0 where it has none).
    pub transient_error: f64,
    /// Whether the transient v_y lies below the plate's by more than both errors.
    pub below_plate: Verdict,
    /// The plate row's validity.
    pub plate_validity: Validity,
}

impl SceneYieldRow {
    /// plate/beam - 1, where the beam describes the set.
    pub fn plate_over_beam(&self) -> Option<f64> {
        self.beam.map(|b| self.plate / b - 1.0)
    }

    /// transient/plate - 1.
    pub fn transient_over_plate(&self) -> f64 {
        self.transient / self.plate - 1.0
    }
}

/// One body's cells in brief.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BodySummary {
    /// Body name.
    pub body: String,
    /// Lowest and highest transient v_y, m/s.
    pub transient: (f64, f64),
    /// Lowest and highest transient/plate - 1.
    pub transient_over_plate: (f64, f64),
    /// Cells where the transient v_y lies below the plate's.
    pub below: usize,
    /// Cells where the difference is within both errors.
    pub open: usize,
    /// Cells.
    pub cells: usize,
}

/// What the scene's three-model yield study computed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SceneYieldData {
    /// Elements along the length of the quasi-static plate's coarsest mesh.
    pub plate_base_mesh: usize,
    /// Of its finest.
    pub plate_finest_mesh: usize,
    /// Relative width of each transient root's final bracket.
    pub root_tolerance: f64,
    /// Every cell the transient model computed, by body in the scene's order.
    pub rows: Vec<SceneYieldRow>,
    /// Per body with at least one cell, in the scene's order.
    pub bodies: Vec<BodySummary>,
}

/// The row of `rows` for the same cell as `r`, if computed.
fn same(rows: &[YieldRow], r: &YieldRow) -> Option<YieldValues> {
    rows.iter()
        .find(|o| o.body == r.body && o.condition == r.condition && o.x == r.x && o.z == r.z)
        .and_then(|o| o.values().cloned())
}

/// One body's rows from the three models' yield rows.
fn body_rows(name: &str, beam: &[YieldRow], plate: &[YieldRow], transient: &[YieldRow]) -> Vec<SceneYieldRow> {
    let mut out = Vec::new();
    for tr in transient.iter().filter(|r| r.body == name) {
        let (Some(tv), Some(pv)) = (tr.values(), same(plate, tr)) else { continue };
        let (t_err, p_err) = (tv.yield_velocity_error.unwrap_or(0.0), pv.yield_velocity_error.unwrap_or(0.0));
        out.push(SceneYieldRow {
            body: tr.body.clone(),
            condition: tr.condition.clone(),
            x: tr.x,
            z: tr.z,
            beam: same(beam, tr).map(|b| b.yield_velocity),
            plate: pv.yield_velocity,
            plate_error: p_err,
            transient: tv.yield_velocity,
            transient_error: t_err,
            below_plate: Verdict::compare(pv.yield_velocity, tv.yield_velocity, t_err + p_err, true),
            plate_validity: pv.validity,
        });
    }
    out
}

/// A body's rows in brief.
fn summary(name: &str, rows: &[SceneYieldRow]) -> BodySummary {
    let mut s = BodySummary {
        body: name.to_string(),
        transient: (f64::INFINITY, f64::NEG_INFINITY),
        transient_over_plate: (f64::INFINITY, f64::NEG_INFINITY),
        below: 0,
        open: 0,
        cells: 0,
    };
    for r in rows {
        let rel = r.transient_over_plate();
        s.transient_over_plate = (s.transient_over_plate.0.min(rel), s.transient_over_plate.1.max(rel));
        s.transient = (s.transient.0.min(r.transient), s.transient.1.max(r.transient));
        s.cells += 1;
        match r.below_plate {
            Verdict::Holds => s.below += 1,
            Verdict::NotResolved => s.open += 1,
            _ => {}
        }
    }
    s
}

/// The study at the scene's transient points.
pub fn compute(scene: &Scene, settings: &Settings, progress: &dyn Progress) -> Result<SceneYieldData, Failure> {
    let mut sc = scene.clone();
    sc.points = Points::Pairs { pairs: scene.transient_points.clone() };
    sc.analyses = vec![Analysis::YieldVelocity];
    crate::run::check_budget(&sc, &[ModelKind::Transient])?;
    let points = sc.point_pairs();
    let periods = plan::fundamental_periods(&sc)?;
    let beam = plan::run(&sc, &BeamModel { plate: &sc.plate }, ModelKind::Beam, &periods)?.yields;
    let plate_model = PlateModel::compute(&sc.plate, &sc.conditions, &points, settings.base_mesh, settings.levels)?;
    let plate = plan::run(&sc, &plate_model, ModelKind::Plate, &periods)?.yields;
    progress.start(plan::transient_case_count(&sc), "transient yield velocities");
    let transient = plan::run_transient_observed(&sc, &mut || progress.advance(1))?.yields;
    progress.finish();
    let mut rows = Vec::new();
    let mut bodies = Vec::new();
    for body in &sc.bodies {
        let of = body_rows(&body.name, &beam, &plate, &transient);
        if !of.is_empty() {
            bodies.push(summary(&body.name, &of));
        }
        rows.extend(of);
    }
    Ok(SceneYieldData {
        plate_base_mesh: settings.base_mesh,
        plate_finest_mesh: settings.base_mesh << (settings.levels - 1),
        root_tolerance: super::ROOT_TOLERANCE,
        rows,
        bodies,
    })
}
