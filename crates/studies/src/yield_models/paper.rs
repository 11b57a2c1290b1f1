//! The three-model yield study on the paper's own scene (Table 1), whatever scene asks for
//! it: Table 2 at the printed x of Areas 1-7, Table 5's minimum over the plate and Figs. 8-9
//! on the centreline, each by the beam, the quasi-static plate and the transient plate, with
//! the transient discretisation error measured on three cells, and the paper's statements
//! about yield velocities tested on the results ([`super::statements`]).

use super::statements::{self, Statement, Summary};
use super::{QuasiStatic, Transients, FINE, GRID, SWEEP, TRANSIENT_SWEEP};
use crate::progress::Progress;
use crate::settings::Settings;
use crate::Failure;
use analytic::Sphere;
use coupled::plan::{self, ModelKind, YieldValues};
use coupled::scene::even_points;
use coupled::transient::{TransientCase, TransientSettings};
use coupled::yield_root::{Root, TransientYield, YieldSearch};
use coupled::{Analysis, BeamModel, PlateModel, Points, SupportSet};
use rayon::prelude::*;
use scene::{Scene, SceneSource};
use serde::Serialize;
use std::collections::HashMap;
use std::time::Instant;

/// What the paper prints that the study computes with: where Areas 1-7 are, Table 2's v_y
/// and section IV-D's quoted numbers. The `report` crate reads them from the printed tables.
#[derive(Debug, Clone, PartialEq)]
pub struct Printed {
    /// x of Areas 1-7 on the centreline, m, as printed.
    pub areas: Vec<f64>,
    /// Table 2's rows: a body under a condition, v_y at each area.
    pub table2: Vec<PrintedRow>,
    /// Section IV-D: the lowest v_y of Table 5, m/s.
    pub min_yield_velocity: f64,
    /// Section IV-D: coal's minimum v_y exceeds this, m/s.
    pub coal_min_exceeds: Quoted,
    /// Section IV-D: coal's minimum is more than this many times the gangues'.
    pub coal_over_gangue_exceeds: Quoted,
}

/// One printed row of Table 2.
#[derive(Debug, Clone, PartialEq)]
pub struct PrintedRow {
    /// The body's name in the paper's scene.
    pub body: String,
    /// Con 1, 2 or 3.
    pub condition: usize,
    /// v_y at Areas 1-7, m/s.
    pub values: Vec<f64>,
}

/// A quoted number and its text as printed (the statements quote the text).
#[derive(Debug, Clone, PartialEq)]
pub struct Quoted {
    /// The value.
    pub value: f64,
    /// As printed.
    pub text: String,
}

/// One cell of Table 2 under the three models.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Table2Cell {
    /// Body name.
    pub body: String,
    /// Con 1, 2 or 3.
    pub condition: usize,
    /// Area 1-7.
    pub area: usize,
    /// x on the centreline, m.
    pub x: f64,
    /// The printed v_y, m/s.
    pub printed: f64,
    /// The beam's v_y (eqs. 51-54), m/s.
    pub beam: f64,
    /// The quasi-static plate's v_y, m/s.
    pub plate: f64,
    /// Its error estimate (the compliance's carried through the formula), m/s.
    pub plate_error: f64,
    /// The transient root.
    pub transient: TransientYield,
}

/// One cell recomputed with the finer transient discretisation [`FINE`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DiscretisationRow {
    /// Body name.
    pub body: String,
    /// Support set name.
    pub condition: String,
    /// x on the centreline, m.
    pub x: f64,
    /// The root at the default discretisation.
    pub coarse: TransientYield,
    /// The root at [`FINE`].
    pub fine: TransientYield,
    /// fine/coarse - 1 of v_y.
    pub relative: f64,
}

/// The transient root of one cell against `coupled::plan::dynamic_yield`'s.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CrossCheck {
    /// This study's root: coal, Con 1, the midpoint.
    pub ours: TransientYield,
    /// `dynamic_yield` on the same cell.
    pub dynamic_yield: YieldValues,
}

/// A lowest v_y and where: m/s at (x, z) in m.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Minimum {
    /// v_y, m/s.
    pub velocity: f64,
    /// x, m.
    pub x: f64,
    /// z, m.
    pub z: f64,
}

/// One row of Table 5: the lowest v_y of a body under a condition, per model (beam, plate,
/// transient).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Table5Row {
    /// Body name.
    pub body: String,
    /// Support set name.
    pub condition: String,
    /// Beam (over the centreline), plate (over the grid), transient (over the candidates).
    pub minima: [Minimum; 3],
}

/// The lowest v_y of one model over every body and condition.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Overall {
    /// Body name.
    pub body: String,
    /// Support set name.
    pub condition: String,
    /// v_y and where.
    pub at: Minimum,
}

/// One body's centreline curves (Fig. 8 or 9 redone): (x, v_y) per model and condition.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Figure {
    /// The paper's figure number.
    pub number: u32,
    /// Body name.
    pub body: String,
    /// Per support set, in the scene's order.
    pub curves: Vec<ConditionCurves>,
}

/// The three models' curves under one support set, (x in m, v_y in m/s).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ConditionCurves {
    /// Support set name.
    pub condition: String,
    /// The beam over [`SWEEP`] points.
    pub beam: Vec<(f64, f64)>,
    /// The quasi-static plate over [`SWEEP`] points.
    pub plate: Vec<(f64, f64)>,
    /// The transient plate over [`TRANSIENT_SWEEP`] points.
    pub transient: Vec<(f64, f64)>,
}

impl ConditionCurves {
    /// Model `m`'s curve: 0 beam, 1 plate, 2 transient.
    pub fn of(&self, m: usize) -> &[(f64, f64)] {
        match m {
            0 => &self.beam,
            1 => &self.plate,
            _ => &self.transient,
        }
    }
}

/// Wall-clock seconds of the study's parts (the only numbers that change between runs).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Timing {
    /// The quasi-static beam and plate at every point.
    pub quasi_static: f64,
    /// Table 2's transient roots.
    pub table2: f64,
    /// The discretisation check.
    pub discretisation: f64,
    /// The `dynamic_yield` cross-check.
    pub cross_check: f64,
    /// Table 5's transient candidates.
    pub table5: f64,
    /// The transient curves of Figs. 8-9.
    pub figures: f64,
    /// The whole study.
    pub total: f64,
    /// The threads the transient roots ran on.
    pub threads: usize,
}

/// What the paper's three-model yield study computed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PaperYieldData {
    /// The plate's length L and width B, m.
    pub length: f64,
    /// B, m.
    pub width: f64,
    /// Elements along the length of the quasi-static plate's coarsest mesh.
    pub plate_base_mesh: usize,
    /// Elements along the length of its finest.
    pub plate_finest_mesh: usize,
    /// The transient discretisation of every root.
    pub transient: TransientSettings,
    /// The finer one of the discretisation check.
    pub fine: TransientSettings,
    /// Relative width of each root's final bracket.
    pub root_tolerance: f64,
    /// Points of the beam and plate curves.
    pub sweep: usize,
    /// Points of the transient curves.
    pub transient_sweep: usize,
    /// The plate's search grid for Table 5 (x, z points).
    pub grid: (usize, usize),
    /// The transient's candidate points for Table 5.
    pub candidates: usize,
    /// Table 2 under three models.
    pub table2: Vec<Table2Cell>,
    /// The discretisation check.
    pub discretisation: Vec<DiscretisationRow>,
    /// Its largest |relative change|: every transient cell's discretisation error estimate.
    pub discretisation_error: f64,
    /// The cross-check against `dynamic_yield`.
    pub cross_check: CrossCheck,
    /// Table 5 under three models.
    pub table5: Vec<Table5Row>,
    /// Per model (beam, plate, transient): the lowest v_y of all.
    pub overall: [Overall; 3],
    /// Figs. 8-9 redone.
    pub figures: Vec<Figure>,
    /// The paper's statements under three models.
    pub statements: Vec<Statement>,
    /// The numbers the prose quotes.
    pub summary: Summary,
    /// Transient roots computed.
    pub transient_cells: usize,
    /// Runs of the full transient model they took.
    pub transient_runs: usize,
    /// Runs of the reduced model that bracketed them.
    pub reduced_runs: usize,
    /// Run times.
    pub timing: Timing,
}

/// The paper's scene as the study runs it, and the points it asks for.
struct Setup {
    scene: Scene,
    /// Coal, gangue 1, gangue 2.
    bodies: [Sphere; 3],
    conds: Vec<SupportSet>,
    length: f64,
    width: f64,
    /// The centreline z = B/2.
    zc: f64,
    areas: Vec<f64>,
    sweep: Vec<f64>,
    tsweep: Vec<f64>,
    grid: Vec<(f64, f64)>,
    /// The transient's Table 5 candidates: the corners (0, 0) and (L, 0), the midpoints of
    /// both ends, of a free edge and of the plate (the plate is symmetric in z).
    candidates: [(f64, f64); 6],
}

impl Setup {
    fn new(printed: &Printed) -> Result<Self, Failure> {
        let mut scene = Scene::default_scene();
        let bodies: [Sphere; 3] = scene
            .bodies
            .clone()
            .try_into()
            .map_err(|_| "the paper's scene has coal, gangue 1 and gangue 2 and no other body")?;
        let (l, b) = (scene.plate.length(), scene.plate.width());
        let zc = b / 2.0;
        let areas = printed.areas.clone();
        let sweep = even_points(l, SWEEP);
        let grid: Vec<(f64, f64)> = even_points(l, GRID.0)
            .into_iter()
            .flat_map(|x| even_points(b, GRID.1).into_iter().map(move |z| (x, z)))
            .collect();
        let mut points: Vec<(f64, f64)> = Vec::new();
        for p in areas.iter().map(|&x| (x, zc)).chain(sweep.iter().map(|&x| (x, zc))).chain(grid.iter().copied()) {
            if !points.iter().any(|q| super::key(q.0) == super::key(p.0) && super::key(q.1) == super::key(p.1)) {
                points.push(p);
            }
        }
        scene.points = Points::Pairs { pairs: points };
        scene.analyses = vec![Analysis::YieldVelocity];
        scene.bodies = bodies.to_vec();
        Ok(Self {
            conds: scene.conditions.clone(),
            candidates: [(0.0, 0.0), (l, 0.0), (0.0, zc), (l, zc), (l / 2.0, 0.0), (l / 2.0, zc)],
            tsweep: even_points(l, TRANSIENT_SWEEP),
            scene,
            bodies,
            length: l,
            width: b,
            zc,
            areas,
            sweep,
            grid,
        })
    }

    /// Con `n` (from 1).
    fn cond(&self, n: usize) -> Result<&SupportSet, Failure> {
        self.conds.get(n - 1).ok_or_else(|| format!("the paper's scene has no Con {n}").into())
    }

    fn body(&self, name: &str) -> Result<&Sphere, Failure> {
        Ok(self.bodies.iter().find(|s| s.name == name).ok_or_else(|| format!("no body {name}"))?)
    }
}

/// The quasi-static beam and plate at every point of the study.
fn quasi_static(setup: &Setup, settings: &Settings) -> Result<(QuasiStatic, QuasiStatic), Failure> {
    let sc = &setup.scene;
    let points = sc.point_pairs();
    let periods = plan::fundamental_periods(sc)?;
    let beam_rows = plan::run(sc, &BeamModel { plate: &sc.plate }, ModelKind::Beam, &periods)?;
    let plate_model = PlateModel::compute(&sc.plate, &sc.conditions, &points, settings.base_mesh, settings.levels)?;
    let plate_rows = plan::run(sc, &plate_model, ModelKind::Plate, &periods)?;
    Ok((QuasiStatic::new(beam_rows.yields), QuasiStatic::new(plate_rows.yields)))
}

/// Table 2: every printed cell under the three models.
fn table2(
    setup: &Setup,
    printed: &Printed,
    beam: &QuasiStatic,
    plate: &QuasiStatic,
    tr: &mut Transients,
) -> Result<Vec<Table2Cell>, Failure> {
    let zc = setup.zc;
    let mut cells = Vec::new();
    for row in &printed.table2 {
        let (body, set) = (setup.body(&row.body)?, setup.cond(row.condition)?);
        cells.extend(setup.areas.iter().map(|&x| (body, set, x, zc)));
    }
    tr.prefetch(&cells)?;
    let mut t2 = Vec::new();
    for row in &printed.table2 {
        let body = setup.body(&row.body)?;
        let set = setup.cond(row.condition)?;
        for (i, (&x, &p)) in setup.areas.iter().zip(&row.values).enumerate() {
            let pv = plate.get(&body.name, &set.name, x, zc)?;
            t2.push(Table2Cell {
                body: body.name.clone(),
                condition: row.condition,
                area: i + 1,
                x,
                printed: p,
                beam: beam.v(&body.name, &set.name, x, zc)?,
                plate: pv.yield_velocity,
                plate_error: pv.yield_velocity_error.unwrap_or(f64::NAN),
                transient: tr.get(body, set, x, zc)?,
            });
        }
    }
    Ok(t2)
}

/// The transient discretisation error: three cells again with [`FINE`] (coal and gangue 1
/// at the midpoint under Con 1, gangue 1 at Area 1 under Con 2), and the largest change.
fn discretisation(setup: &Setup, tr: &mut Transients) -> Result<(Vec<DiscretisationRow>, f64), Failure> {
    let (l, zc) = (setup.length, setup.zc);
    let fine_case = TransientCase::new(&setup.scene.plate, FINE)?;
    let area1 = setup.areas.first().copied().ok_or("the paper prints no Area 1")?;
    let [coal, gangue1, _] = &setup.bodies;
    let cells = [(coal, 1, l / 2.0), (gangue1, 1, l / 2.0), (gangue1, 2, area1)]
        .into_iter()
        .map(|(body, n, x)| Ok((body, setup.cond(n)?, x, zc)))
        .collect::<Result<Vec<_>, Failure>>()?;
    tr.prefetch(&cells)?;
    for &(_, set, _, _) in &cells {
        tr.search.prepare(&fine_case, set);
    }
    let (scene, search) = (&setup.scene, &tr.search);
    let fine: Vec<Result<TransientYield, String>> = cells
        .par_iter()
        .map(|&(body, set, x, z)| {
            let root =
                Root { scene, case: &fine_case, steps_per_contact: FINE.steps_per_contact, set, body, at: (x, z) };
            search.root_prepared(&root).map_err(|e| e.to_string())
        })
        .collect();
    let mut rows = Vec::new();
    let mut largest: f64 = 0.0;
    for (&(body, set, x, _), fine) in cells.iter().zip(fine) {
        let (coarse, fine) = (tr.get(body, set, x, zc)?, fine?);
        let relative = fine.velocity / coarse.velocity - 1.0;
        largest = largest.max(relative.abs());
        rows.push(DiscretisationRow {
            body: body.name.clone(),
            condition: set.name.clone(),
            x,
            coarse,
            fine,
            relative,
        });
    }
    Ok((rows, largest))
}

/// Table 5: per body and condition the lowest v_y of each model (the beam over the
/// centreline, the plate over the grid, the transient over the candidates), and per model
/// the lowest of all.
fn table5(
    setup: &Setup,
    beam: &QuasiStatic,
    plate: &QuasiStatic,
    tr: &mut Transients,
) -> Result<(Vec<Table5Row>, [Overall; 3]), Failure> {
    let zc = setup.zc;
    let none = Minimum { velocity: f64::INFINITY, x: 0.0, z: 0.0 };
    let mut overall: [Overall; 3] =
        std::array::from_fn(|_| Overall { body: String::new(), condition: String::new(), at: none });
    let cells: Vec<_> = setup
        .bodies
        .iter()
        .flat_map(|body| {
            setup.conds.iter().flat_map(move |set| setup.candidates.iter().map(move |&(x, z)| (body, set, x, z)))
        })
        .collect();
    tr.prefetch(&cells)?;
    let mut rows = Vec::new();
    for body in &setup.bodies {
        for set in &setup.conds {
            let mut mins = [none; 3];
            let mut lower = |m: usize, velocity: f64, x: f64, z: f64| {
                if velocity < mins[m].velocity {
                    mins[m] = Minimum { velocity, x, z };
                }
            };
            for &x in &setup.sweep {
                lower(0, beam.v(&body.name, &set.name, x, zc)?, x, zc);
            }
            for &(x, z) in &setup.grid {
                lower(1, plate.v(&body.name, &set.name, x, z)?, x, z);
            }
            for &(x, z) in &setup.candidates {
                lower(2, tr.get(body, set, x, z)?.velocity, x, z);
            }
            for (m, at) in mins.iter().enumerate() {
                if at.velocity < overall[m].at.velocity {
                    overall[m] = Overall { body: body.name.clone(), condition: set.name.clone(), at: *at };
                }
            }
            rows.push(Table5Row { body: body.name.clone(), condition: set.name.clone(), minima: mins });
        }
    }
    Ok((rows, overall))
}

/// Figs. 8 (coal) and 9 (gangue 1): the three models' v_y along the centreline.
fn figures(
    setup: &Setup,
    beam: &QuasiStatic,
    plate: &QuasiStatic,
    tr: &mut Transients,
) -> Result<Vec<Figure>, Failure> {
    let zc = setup.zc;
    let cells: Vec<_> = [&setup.bodies[0], &setup.bodies[1]]
        .into_iter()
        .flat_map(|body| setup.conds.iter().flat_map(move |set| setup.tsweep.iter().map(move |&x| (body, set, x, zc))))
        .collect();
    tr.prefetch(&cells)?;
    let mut out = Vec::new();
    for (number, body) in [(8, &setup.bodies[0]), (9, &setup.bodies[1])] {
        let mut curves = Vec::new();
        for set in &setup.conds {
            let along = |model: &QuasiStatic| -> Result<Vec<(f64, f64)>, Failure> {
                setup.sweep.iter().map(|&x| Ok((x, model.v(&body.name, &set.name, x, zc)?))).collect()
            };
            let (b, p) = (along(beam)?, along(plate)?);
            let mut t = Vec::new();
            for &x in &setup.tsweep {
                t.push((x, tr.get(body, set, x, zc)?.velocity));
            }
            curves.push(ConditionCurves { condition: set.name.clone(), beam: b, plate: p, transient: t });
        }
        out.push(Figure { number, body: body.name.clone(), curves });
    }
    Ok(out)
}

/// The same root by `coupled::plan::dynamic_yield` at one cell: coal, Con 1, the midpoint.
fn cross_check(setup: &Setup, tr: &mut Transients) -> Result<CrossCheck, Failure> {
    let (coal, mid, set) = (&setup.bodies[0], setup.length / 2.0, setup.cond(1)?);
    let dy = plan::dynamic_yield(&setup.scene, &tr.case, &mut tr.search, set, coal, (mid, setup.zc))?;
    Ok(CrossCheck { ours: tr.get(coal, set, mid, setup.zc)?, dynamic_yield: dy })
}

/// The statements' verdicts and the numbers the prose quotes.
fn judge(
    setup: &Setup,
    printed: &Printed,
    table2: &[Table2Cell],
    resolution: f64,
    figures: &[Figure],
    table5: &[Table5Row],
    overall: &[Overall; 3],
) -> Result<(Vec<Statement>, Summary), Failure> {
    let [coal, gangue1, gangue2] = &setup.bodies;
    let facts = statements::Facts {
        table2,
        resolution,
        length: setup.length,
        width: setup.width,
        figures,
        table5,
        overall,
        first_condition: setup.conds.first().map_or("", |c| c.name.as_str()),
        bodies: [&coal.name, &gangue1.name, &gangue2.name],
        printed,
    };
    let statements = facts.statements()?;
    // The rigid-target v_y of a body by name (coal's where the name is none of the three).
    let summary = facts.summary(&statements, |name| {
        let body = setup.bodies.iter().find(|s| s.name == name).unwrap_or(coal);
        super::rigid_yield(&setup.scene, body)
    })?;
    Ok((statements, summary))
}

/// Runs one part of the study, its wall-clock seconds into `secs`.
fn timed<T>(secs: &mut f64, part: impl FnOnce() -> Result<T, Failure>) -> Result<T, Failure> {
    let t0 = Instant::now();
    let out = part();
    *secs = t0.elapsed().as_secs_f64();
    out
}

/// The study: the paper's scene by the three models, against what the paper prints.
pub fn compute(printed: &Printed, settings: &Settings, progress: &dyn Progress) -> Result<PaperYieldData, Failure> {
    let t_start = Instant::now();
    let setup = Setup::new(printed)?;
    let mut timing = Timing { threads: rayon::current_num_threads(), ..Timing::default() };
    progress.start(6, "parts of the three-model yield study");
    let (beam, plate) = timed(&mut timing.quasi_static, || quasi_static(&setup, settings))?;
    progress.advance(1);
    let case = TransientCase::new(&setup.scene.plate, TransientSettings::default())?;
    let mut tr = Transients { scene: &setup.scene, case, search: YieldSearch::new(), cells: HashMap::new() };
    let table2 = timed(&mut timing.table2, || table2(&setup, printed, &beam, &plate, &mut tr))?;
    progress.advance(1);
    let (discretisation, disc_rel) = timed(&mut timing.discretisation, || discretisation(&setup, &mut tr))?;
    let cross_check = timed(&mut timing.cross_check, || cross_check(&setup, &mut tr))?;
    progress.advance(1);
    let (table5, overall) = timed(&mut timing.table5, || table5(&setup, &beam, &plate, &mut tr))?;
    progress.advance(1);
    let figures = timed(&mut timing.figures, || figures(&setup, &beam, &plate, &mut tr))?;
    progress.advance(1);
    let (statements, summary) = judge(&setup, printed, &table2, disc_rel, &figures, &table5, &overall)?;
    progress.advance(1);
    progress.finish();
    let transient = tr.case.settings();
    let (transient_cells, (transient_runs, reduced_runs)) = (tr.cells.len(), tr.runs());
    timing.total = t_start.elapsed().as_secs_f64();
    Ok(PaperYieldData {
        length: setup.length,
        width: setup.width,
        plate_base_mesh: settings.base_mesh,
        plate_finest_mesh: settings.base_mesh << (settings.levels - 1),
        transient,
        fine: FINE,
        root_tolerance: super::ROOT_TOLERANCE,
        sweep: SWEEP,
        transient_sweep: TRANSIENT_SWEEP,
        grid: GRID,
        candidates: setup.candidates.len(),
        table2,
        discretisation,
        discretisation_error: disc_rel,
        cross_check,
        table5,
        overall,
        figures,
        statements,
        summary,
        transient_cells,
        transient_runs,
        reduced_runs,
        timing,
    })
}
