//! The yield velocity under three models: the paper's beam (eqs. 51-54), the quasi-static
//! plate FE compliance through the same formula, and the transient plate (the v at which
//! the transient δ_max reaches δ_my of eq. 51). Table 2, Table 5's minimum and Figs. 8-9
//! redone with all three, and the paper's statements about yield velocities tested on the
//! results.
//!
//! The transient root is found here rather than by `coupled::plan::dynamic_yield`, which
//! brackets by doubling from the rigid value and bisects (about 25 runs a point): the same
//! function, ln(δ_max/δ_my) of ln v, is bracketed from the rigid value with the Hertz slope
//! and closed by Illinois false position to the same relative width (about 6-8 runs). The
//! report checks one point against `dynamic_yield`.

use crate::paper::{Paper, PrintedTables};
use crate::present::plot::{line_plot, series_csv, Scale, Series, Verdict};
use crate::present::table::{sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use analytic::{contact_stiffness, yield_velocity, DruckerPrager, Sphere};
pub use coupled::plan::log_root;
use coupled::plan::{self, impact_of, ModelKind, YieldRow, YieldValues};
use coupled::scene::even_points;
use coupled::transient::{TransientCase, TransientSettings};
use coupled::{Analysis, BeamModel, ModelError, PlateModel, Points, SupportSet};
use output::Artifacts;
use scene::Scene;
use std::collections::HashMap;
use std::time::Instant;
use studies::progress::Progress;

/// The report's prose: every number in it is a placeholder filled from the run.
const TEMPLATE: &str = include_str!("templates/yield_models.md");
/// The main report's section and finding of the paper's study.
const PAPER_SECTION: &str = include_str!("templates/yield/paper-section.md");
const PAPER_FINDING: &str = include_str!("templates/yield/paper-finding.md");
/// The study on a scene of one's own: its page, the main report's section, a finding per body.
const SCENE_PAGE: &str = include_str!("templates/yield/scene.md");
const SCENE_SECTION: &str = include_str!("templates/yield/scene-section.md");
const SCENE_FINDING: &str = include_str!("templates/yield/scene-finding.md");

/// The quasi-static plate model's ladder: 20 elements along the length, then 40.
pub const PLATE_BASE_MESH: usize = 20;
/// Meshes on the ladder (the finest two give the Richardson value and its error).
pub const PLATE_LEVELS: u32 = 2;
/// Relative width of the bracket that closes each transient root: hi/lo - 1.
pub const ROOT_TOLERANCE: f64 = coupled::plan::YIELD_ROOT_TOLERANCE;
/// The finer transient discretisation that estimates the default one's error.
pub const FINE: TransientSettings = TransientSettings {
    elements: 40,
    steps_per_contact: 400.0,
    window_contacts: coupled::transient::case::WINDOW_HERTZ_TIMES,
};
/// Points of the beam and plate curves (L in 100 parts, as section IV-A).
const SWEEP: usize = 101;
/// Points of the transient curves (each a root of ~7 time integrations).
const TRANSIENT_SWEEP: usize = 13;
/// The quasi-static plate's search grid for Table 5: x and z points, edges included.
const GRID: (usize, usize) = (11, 5);

/// A v_y and where: (v, x, z).
type Located = (f64, f64, f64);

/// A transient yield velocity and how it was found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransientYield {
    /// v_y, m/s: the geometric middle of the final bracket.
    pub velocity: f64,
    /// Width of the final bracket hi - lo, m/s: f(lo) < 0 ≤ f(hi).
    pub width: f64,
    /// Transient runs it took.
    pub runs: usize,
    /// δ_my of eq. 51, m.
    pub yield_compression: f64,
}

/// The transient yield velocity of `body` at (x, z) on the plate held by `set`, with the
/// scene's contact law: the v at which the transient δ_max reaches δ_my of eq. 51, to a relative width [`ROOT_TOLERANCE`].
pub fn transient_yield(
    scene: &Scene,
    case: &TransientCase,
    set: &SupportSet,
    body: &Sphere,
    x: f64,
    z: f64,
) -> Result<TransientYield, ModelError> {
    let k = contact_stiffness(body, scene.plate.material());
    let d_my = DruckerPrager::of(body).yield_compression(body.radius(), k);
    let v_rigid = yield_velocity(body, &impact_of(scene, body, 1.0), 0.0, d_my);
    let mut runs = 0;
    let (lo, hi) = {
        let mut f = |lv: f64| -> Result<f64, ModelError> {
            runs += 1;
            let s = coupled::plan::scene_striker(scene, body, lv.exp());
            // δ_max is the first contact's: the run need not follow the later ones.
            let steps = case.settings().steps_per_contact;
            Ok((case.first_contact(set, &s, x, z, steps)?.compression_max / d_my).ln())
        };
        log_root(&mut f, v_rigid.ln(), ROOT_TOLERANCE)?
    };
    Ok(TransientYield { velocity: (0.5 * (lo + hi)).exp(), width: hi.exp() - lo.exp(), runs, yield_compression: d_my })
}

/// The quasi-static yield velocity (eqs. 51-54) of rigid contact, C = 0 (eq. 14 with C = 0).
pub fn rigid_yield(scene: &Scene, body: &Sphere) -> f64 {
    let k = contact_stiffness(body, scene.plate.material());
    let d_my = DruckerPrager::of(body).yield_compression(body.radius(), k);
    yield_velocity(body, &impact_of(scene, body, 1.0), 0.0, d_my)
}

fn key(v: f64) -> i64 {
    (v * 1e9).round() as i64
}

/// The quasi-static v_y rows of one model, looked up by (body, condition, x, z).
struct QuasiStatic(HashMap<(String, String, i64, i64), YieldValues>);

impl QuasiStatic {
    fn new(rows: Vec<YieldRow>) -> Self {
        Self(
            rows.into_iter()
                .filter_map(|r| {
                    let v = r.values()?.clone();
                    Some(((r.body, r.condition, key(r.x), key(r.z)), v))
                })
                .collect(),
        )
    }
    fn get(&self, body: &str, cond: &str, x: f64, z: f64) -> Result<&YieldValues, Failure> {
        self.0
            .get(&(body.to_string(), cond.to_string(), key(x), key(z)))
            .ok_or_else(|| format!("no quasi-static v_y for {body} on {cond} at ({x}, {z}) m").into())
    }
    fn v(&self, body: &str, cond: &str, x: f64, z: f64) -> Result<f64, Failure> {
        Ok(self.get(body, cond, x, z)?.yield_velocity)
    }
}

/// Transient roots, each computed once.
struct Transients<'a> {
    scene: &'a Scene,
    case: TransientCase,
    cells: HashMap<(String, String, i64, i64), TransientYield>,
}

impl<'a> Transients<'a> {
    fn get(&mut self, body: &Sphere, set: &SupportSet, x: f64, z: f64) -> Result<TransientYield, Failure> {
        let k = (body.name.clone(), set.name.clone(), key(x), key(z));
        if let Some(t) = self.cells.get(&k) {
            return Ok(*t);
        }
        let t = transient_yield(self.scene, &self.case, set, body, x, z)?;
        self.cells.insert(k, t);
        Ok(t)
    }
    fn runs(&self) -> usize {
        self.cells.values().map(|t| t.runs).sum()
    }
}

fn verdict(v: Verdict) -> Cell {
    v.word().into()
}

/// Position as a fraction of a length, 2 decimals.
fn frac(v: f64, of: f64) -> String {
    format!("{:.2}", v / of)
}

/// The extremes (x_min, v_min, x_max, v_max) of a curve.
fn extremes(points: &[(f64, f64)]) -> (f64, f64, f64, f64) {
    let mut e = (f64::NAN, f64::INFINITY, f64::NAN, f64::NEG_INFINITY);
    for &(x, v) in points {
        if v < e.1 {
            (e.0, e.1) = (x, v);
        }
        if v > e.3 {
            (e.2, e.3) = (x, v);
        }
    }
    e
}

/// One row of the statements table: the statement, the verdict of each model and the
/// numbers it rests on.
struct Statement {
    text: String,
    holds: [Verdict; 3],
    evidence: [String; 3],
}

/// What the main report shows of a three-model yield study: its section (links relative to
/// the main report's page) and its line among the findings.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct YieldSummary {
    /// The Markdown section: the table, the figures and the link to the study's page.
    pub section: String,
    /// One Markdown bullet line for the findings.
    pub finding: String,
}

/// The folder the main report nests the study in, for the links of [`YieldSummary`].
pub const FOLDER: &str = "yield-three-models";

/// The study: the paper's own scene, whatever `scene` is.
pub fn report(scene: &Scene) -> Result<Artifacts, Failure> {
    Ok(study(scene)?.0)
}

/// [`report`], and what the main report shows of it.
pub fn study(_scene: &Scene) -> Result<(Artifacts, YieldSummary), Failure> {
    let t_start = Instant::now();
    let paper = Paper::new();
    let printed = PrintedTables::embedded()?;
    let mut sc = paper.scene.clone();
    let (l, b) = (sc.plate.length(), sc.plate.width());
    let zc = b / 2.0;
    let studied: [&Sphere; 2] = [&paper.coal, &paper.gangue1];
    let body_of = |name: &str| *paper.bodies().iter().find(|s| s.name == name).unwrap_or(&&paper.coal);
    let all_bodies = paper.bodies();
    let conds: Vec<SupportSet> = sc.conditions.clone();
    let cond_named = |n: usize| -> Result<&SupportSet, Failure> {
        conds.get(n - 1).ok_or_else(|| format!("the paper's scene has no Con {n}").into())
    };

    // ---------------------------------------------------------------- the quasi-static models
    let t2x: Vec<f64> = printed.table2.x.iter().map(|p| p.printed.value).collect();
    let sweep = even_points(l, SWEEP);
    let tsweep = even_points(l, TRANSIENT_SWEEP);
    let grid: Vec<(f64, f64)> = even_points(l, GRID.0)
        .into_iter()
        .flat_map(|x| even_points(b, GRID.1).into_iter().map(move |z| (x, z)))
        .collect();
    let candidates = [(0.0, 0.0), (l, 0.0), (0.0, zc), (l, zc), (l / 2.0, 0.0), (l / 2.0, zc)];
    let mut points: Vec<(f64, f64)> = Vec::new();
    for p in t2x.iter().map(|&x| (x, zc)).chain(sweep.iter().map(|&x| (x, zc))).chain(grid.iter().copied()) {
        if !points.iter().any(|q| key(q.0) == key(p.0) && key(q.1) == key(p.1)) {
            points.push(p);
        }
    }
    sc.points = Points::Pairs { pairs: points.clone() };
    sc.analyses = vec![Analysis::YieldVelocity];
    sc.bodies = all_bodies.iter().map(|s| (*s).clone()).collect();
    let t0 = Instant::now();
    let periods = plan::fundamental_periods(&sc)?;
    let beam_rows = plan::run(&sc, &BeamModel { plate: &sc.plate }, ModelKind::Beam, &periods)?;
    let plate_model = PlateModel::compute(&sc.plate, &sc.conditions, &points, PLATE_BASE_MESH, PLATE_LEVELS)?;
    let plate_rows = plan::run(&sc, &plate_model, ModelKind::Plate, &periods)?;
    let beam = QuasiStatic::new(beam_rows.yields);
    let plate = QuasiStatic::new(plate_rows.yields);
    let secs_quasi = t0.elapsed().as_secs_f64();
    let mut tr = Transients {
        scene: &sc,
        case: TransientCase::new(&sc.plate, TransientSettings::default())?,
        cells: HashMap::new(),
    };
    let settings = tr.case.settings();

    // ---------------------------------------------------------------- Table 2
    let t0 = Instant::now();
    struct T2 {
        body: String,
        cond: usize,
        area: usize,
        x: f64,
        printed: f64,
        beam: f64,
        plate: f64,
        plate_err: f64,
        tr: TransientYield,
    }
    let mut t2 = Vec::new();
    for row in &printed.table2.rows {
        let body = *all_bodies.iter().find(|s| s.name == row.body).ok_or_else(|| format!("no body {}", row.body))?;
        let set = cond_named(row.condition)?;
        for (i, (&x, p)) in t2x.iter().zip(&row.values).enumerate() {
            let pv = plate.get(&body.name, &set.name, x, zc)?;
            t2.push(T2 {
                body: body.name.clone(),
                cond: row.condition,
                area: i + 1,
                x,
                printed: p.printed.value,
                beam: beam.v(&body.name, &set.name, x, zc)?,
                plate: pv.yield_velocity,
                plate_err: pv.yield_velocity_error.unwrap_or(f64::NAN),
                tr: tr.get(body, set, x, zc)?,
            });
        }
    }
    let secs_t2 = t0.elapsed().as_secs_f64();

    // The transient discretisation error: three cells again with 40 elements and 400 steps
    // per contact time.
    let t0 = Instant::now();
    let fine_case = TransientCase::new(&sc.plate, FINE)?;
    let checks = [(&paper.coal, 1, l / 2.0), (&paper.gangue1, 1, l / 2.0), (&paper.gangue1, 2, t2x[0])];
    let mut disc = Table::new(
        "",
        &[
            "body",
            "condition",
            "x (mm)",
            &format!("v_y, {} el., {} steps (m/s)", settings.elements, settings.steps_per_contact),
            &format!("v_y, {} el., {} steps (m/s)", FINE.elements, FINE.steps_per_contact),
            "relative change",
            "runs (fine)",
        ],
    );
    let mut disc_rel: f64 = 0.0;
    for (body, n, x) in checks {
        let set = cond_named(n)?;
        let coarse = tr.get(body, set, x, zc)?;
        let fine = transient_yield(&sc, &fine_case, set, body, x, zc)?;
        let rel = fine.velocity / coarse.velocity - 1.0;
        disc_rel = disc_rel.max(rel.abs());
        disc.push(vec![
            body.name.clone().into(),
            set.name.clone().into(),
            (x * 1e3).into(),
            coarse.velocity.into(),
            fine.velocity.into(),
            rel.into(),
            fine.runs.into(),
        ]);
    }
    let secs_disc = t0.elapsed().as_secs_f64();

    // The same root by coupled::plan::dynamic_yield (doubling and bisection) at one cell.
    let t0 = Instant::now();
    let dy_set = cond_named(1)?;
    let dy = plan::dynamic_yield(&sc, &tr.case, dy_set, &paper.coal, l / 2.0, zc)?;
    let ours = tr.get(&paper.coal, dy_set, l / 2.0, zc)?;
    let secs_dy = t0.elapsed().as_secs_f64();

    let mut t2t = Table::new(
        "",
        &[
            "body",
            "condition",
            "area",
            "x (mm)",
            "printed (m/s)",
            "beam (m/s)",
            "plate (m/s)",
            "plate ± (m/s)",
            "transient (m/s)",
            "transient ± disc. (m/s)",
            "transient bracket (m/s)",
            "plate/beam - 1",
            "transient/beam - 1",
            "beam/printed - 1",
        ],
    );
    for r in &t2 {
        t2t.push(vec![
            r.body.clone().into(),
            format!("Con {}", r.cond).into(),
            r.area.into(),
            (r.x * 1e3).into(),
            r.printed.into(),
            r.beam.into(),
            r.plate.into(),
            r.plate_err.into(),
            r.tr.velocity.into(),
            (disc_rel * r.tr.velocity).into(),
            r.tr.width.into(),
            (r.plate / r.beam - 1.0).into(),
            (r.tr.velocity / r.beam - 1.0).into(),
            (r.beam / r.printed - 1.0).into(),
        ]);
    }

    // ---------------------------------------------------------------- Table 5
    let t0 = Instant::now();
    let mut t5 = Table::new(
        "",
        &[
            "body",
            "condition",
            "beam min (m/s)",
            "beam at x/L",
            "plate min (m/s)",
            "plate at (x/L, z/B)",
            "transient min (m/s)",
            "transient at (x/L, z/B)",
        ],
    );
    // Per model: (v, body, condition, x, z) of the overall minimum.
    let mut overall: [(f64, String, String, f64, f64); 3] =
        std::array::from_fn(|_| (f64::INFINITY, String::new(), String::new(), 0.0, 0.0));
    let mut minima_of: HashMap<(String, usize), [Located; 3]> = HashMap::new();
    for body in all_bodies {
        for set in &conds {
            let mut mins: [(f64, f64, f64); 3] = [(f64::INFINITY, 0.0, 0.0); 3];
            for &x in &sweep {
                let v = beam.v(&body.name, &set.name, x, zc)?;
                if v < mins[0].0 {
                    mins[0] = (v, x, zc);
                }
            }
            for &(x, z) in &grid {
                let v = plate.v(&body.name, &set.name, x, z)?;
                if v < mins[1].0 {
                    mins[1] = (v, x, z);
                }
            }
            for &(x, z) in &candidates {
                let v = tr.get(body, set, x, z)?.velocity;
                if v < mins[2].0 {
                    mins[2] = (v, x, z);
                }
            }
            for (m, &(v, x, z)) in mins.iter().enumerate() {
                if v < overall[m].0 {
                    overall[m] = (v, body.name.clone(), set.name.clone(), x, z);
                }
            }
            let ci = conds.iter().position(|c| c.name == set.name).unwrap_or(0);
            minima_of.insert((body.name.clone(), ci), mins);
            t5.push(vec![
                body.name.clone().into(),
                set.name.clone().into(),
                mins[0].0.into(),
                frac(mins[0].1, l).into(),
                mins[1].0.into(),
                Cell::Pair { x: mins[1].1 / l, z: mins[1].2 / b, scale: 1.0, decimals: 2 },
                mins[2].0.into(),
                Cell::Pair { x: mins[2].1 / l, z: mins[2].2 / b, scale: 1.0, decimals: 2 },
            ]);
        }
    }
    let secs_t5 = t0.elapsed().as_secs_f64();
    let quoted = &printed.section4d;
    let mut t5o = Table::new("", &["model", "lowest v_y (m/s)", "body", "condition", "at (x/L, z/B)", "/ quoted - 1"]);
    for (m, name) in ["beam", "plate", "transient"].iter().enumerate() {
        let (v, body, cond, x, z) = &overall[m];
        t5o.push(vec![
            (*name).into(),
            (*v).into(),
            body.clone().into(),
            cond.clone().into(),
            format!("({}, {})", frac(*x, l), frac(*z, b)).into(),
            (v / quoted.min_yield_velocity.printed.value - 1.0).into(),
        ]);
    }

    // ---------------------------------------------------------------- Figs. 8-9
    let t0 = Instant::now();
    let mut a = Artifacts::new();
    let mut figures = String::new();
    let mut figure_links = String::new();
    // Centreline curves per model, body, condition: (x, v).
    let mut curves: HashMap<(usize, String, usize), Vec<(f64, f64)>> = HashMap::new();
    for (fig, body) in [(8, studied[0]), (9, studied[1])] {
        let mut series = Vec::new();
        for (ci, set) in conds.iter().enumerate() {
            let bc: Vec<(f64, f64)> = sweep
                .iter()
                .map(|&x| Ok((x, beam.v(&body.name, &set.name, x, zc)?)))
                .collect::<Result<_, Failure>>()?;
            let pc: Vec<(f64, f64)> = sweep
                .iter()
                .map(|&x| Ok((x, plate.v(&body.name, &set.name, x, zc)?)))
                .collect::<Result<_, Failure>>()?;
            let mut tc = Vec::new();
            for &x in &tsweep {
                tc.push((x, tr.get(body, set, x, zc)?.velocity));
            }
            let mm = |c: &[(f64, f64)]| c.iter().map(|&(x, v)| (x * 1e3, v)).collect::<Vec<_>>();
            series.push(Series::new(format!("beam, {}", set.name), mm(&bc)));
            series.push(Series::new(format!("plate, {}", set.name), mm(&pc)));
            series.push(Series::new(format!("transient, {}", set.name), mm(&tc)));
            curves.insert((0, body.name.clone(), ci), bc);
            curves.insert((1, body.name.clone(), ci), pc);
            curves.insert((2, body.name.clone(), ci), tc);
        }
        let stem = format!("fig{fig:02}-yield-{}-three-models", crate::present::rows::slug(&body.name));
        let title = format!("Fig. {fig} redone: {} yield velocity on the centreline, three models", body.name);
        a.add(format!("{stem}.svg"), line_plot(&title, "x (mm)", "v_y (m/s)", &series, Scale::Linear));
        a.add(format!("{stem}.csv"), series_csv(&series, "x (mm)", "v_y (m/s)"));
        figures.push_str(&format!("![{title}]({stem}.svg)\n\n"));
        figure_links.push_str(&format!("![{title}]({FOLDER}/{stem}.svg)\n\n"));
    }
    let secs_figs = t0.elapsed().as_secs_f64();

    // ---------------------------------------------------------------- the statements
    let curve = |m: usize, body: &str, ci: usize| -> Result<&Vec<(f64, f64)>, Failure> {
        curves.get(&(m, body.to_string(), ci)).ok_or_else(|| format!("no curve {m} {body} {ci}").into())
    };
    // Table 2's values per model: v and its relative resolution (plate: the compliance
    // error carried to v_y; transient: the root's bracket and the discretisation error
    // estimate; beam: exact).
    let cell = |m: usize, r: &T2| -> (f64, f64) {
        match m {
            0 => (r.beam, 0.0),
            1 => (r.plate, r.plate_err / r.plate),
            _ => (r.tr.velocity, r.tr.width / r.tr.velocity + disc_rel),
        }
    };
    // The largest relative resolution of a model over Table 2's cells, for the statements on
    // the minima.
    let worst_resolution = |m: usize| t2.iter().map(|r| cell(m, r).1).fold(0.0, f64::max);
    let find =
        |body: &str, cond: usize, area: usize| t2.iter().find(|r| r.body == body && r.cond == cond && r.area == area);
    let mut statements = Vec::new();
    {
        let mut holds = [Verdict::Holds; 3];
        let mut evidence: [String; 3] = Default::default();
        for m in 0..3 {
            let mut parts = Vec::new();
            for body in studied {
                let e = extremes(curve(m, &body.name, 0)?);
                let here = !(0.05..=0.95).contains(&(e.0 / l)) && (0.4..=0.6).contains(&(e.2 / l));
                holds[m] = Verdict::all([holds[m], here.into()]);
                parts.push(format!("{}: min at x = {} L, max at x = {} L", body.name, frac(e.0, l), frac(e.2, l)));
            }
            evidence[m] = parts.join("; ");
        }
        statements.push(Statement {
            text: "Con 1, centreline: v_y is lowest at the ends and highest at the midpoint (coal and gangue 1)".into(),
            holds,
            evidence,
        });
    }
    {
        let mut holds = [Verdict::Holds; 3];
        let mut evidence: [String; 3] = Default::default();
        for m in 0..3 {
            let (mut rise, mut res) = (f64::INFINITY, 0.0f64);
            let mut cells = Vec::new();
            for r1 in t2.iter().filter(|r| r.cond == 1) {
                let r2 = find(&r1.body, 2, r1.area).ok_or("Table 2 lacks a Con 2 cell")?;
                let ((v1, e1), (v2, e2)) = (cell(m, r1), cell(m, r2));
                let up = v2 / v1 - 1.0;
                cells.push(Verdict::compare(up, 0.0, e1 + e2, true));
                rise = rise.min(up);
                res = res.max(e1 + e2);
            }
            holds[m] = Verdict::all(cells);
            evidence[m] = format!("smallest rise {}; resolution {}", sig(rise, 3), sig(res, 2));
        }
        statements.push(Statement {
            text: "Elastic supports raise v_y: v_y(Con 2) > v_y(Con 1) at Areas 1-7".into(),
            holds,
            evidence,
        });
    }
    {
        let mut holds = [Verdict::Holds; 3];
        let mut evidence: [String; 3] = Default::default();
        for m in 0..3 {
            let (mut n, mut open, mut total) = (0, 0, 0);
            let mut cells = Vec::new();
            for r1 in t2.iter().filter(|r| r.cond == 1) {
                let r2 = find(&r1.body, 2, r1.area).ok_or("Table 2 lacks a Con 2 cell")?;
                let r3 = find(&r1.body, 3, r1.area).ok_or("Table 2 lacks a Con 3 cell")?;
                let ((v1, e1), (v2, e2), (v3, e3)) = (cell(m, r1), cell(m, r2), cell(m, r3));
                // Each order on the relative scale of Con 1's value, to the two cells' resolution.
                let here = Verdict::all([
                    Verdict::compare(v2 / v1, v3 / v1, e2 + e3, false),
                    Verdict::compare(v3 / v1, 1.0, e3 + e1, false),
                ]);
                total += 1;
                match here {
                    Verdict::Holds => n += 1,
                    Verdict::NotResolved => open += 1,
                    _ => {}
                }
                cells.push(here);
            }
            holds[m] = Verdict::all(cells);
            evidence[m] = format!("holds in {n} of {total} cells, not resolved in {open}");
        }
        statements.push(Statement {
            text: "v_y(Con 2) ≥ v_y(Con 3) ≥ v_y(Con 1) at Areas 1-7 (coal and gangue 1)".into(),
            holds,
            evidence,
        });
    }
    {
        let mut holds = [Verdict::Holds; 3];
        let mut evidence: [String; 3] = Default::default();
        for m in 0..3 {
            let mut worst: f64 = 0.0;
            let mut cells = Vec::new();
            for rc in t2.iter().filter(|r| r.body == paper.coal.name) {
                let rg = find(&paper.gangue1.name, rc.cond, rc.area).ok_or("Table 2 lacks a gangue 1 cell")?;
                let ((vg, eg), (vc, ec)) = (cell(m, rg), cell(m, rc));
                cells.push(Verdict::compare(1.0, vg / vc, eg + ec, true));
                worst = worst.max(vg / vc);
            }
            holds[m] = Verdict::all(cells);
            evidence[m] = format!("largest v_y(gangue 1)/v_y(coal) {}", sig(worst, 3));
        }
        statements.push(Statement {
            text: "Gangue 1 yields at lower velocities than coal (every cell of Table 2)".into(),
            holds,
            evidence,
        });
    }
    {
        let mut holds = [Verdict::Holds; 3];
        let mut evidence: [String; 3] = Default::default();
        for m in 0..3 {
            let mut parts = Vec::new();
            for (body, order) in [(&paper.coal, -2.0), (&paper.gangue1, -3.0)] {
                let vs: Vec<f64> = t2.iter().filter(|r| r.body == body.name).map(|r| cell(m, r).0).collect();
                let (lo, hi) = vs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
                let here = vs.iter().all(|v| (v.log10() - order).abs() <= 0.5);
                holds[m] = Verdict::all([holds[m], here.into()]);
                parts.push(format!("{} {} to {}", body.name, sig(lo, 3), sig(hi, 3)));
            }
            evidence[m] = parts.join("; ");
        }
        statements.push(Statement {
            text: "v_y is of order 1e-2 m/s for coal and 1e-3 m/s for gangue 1 (within a factor √10, every cell of Table 2)".into(),
            holds,
            evidence,
        });
    }
    {
        let mut holds = [Verdict::Holds; 3];
        let mut evidence: [String; 3] = Default::default();
        for m in 0..3 {
            let (v, body, cond, x, z) = &overall[m];
            // Con 1 attains the overall minimum (ties with Con 3's fixed end count) at an end,
            // and the body is a gangue.
            let con1 = [&paper.gangue1, &paper.gangue2]
                .iter()
                .filter_map(|g| minima_of.get(&(g.name.clone(), 0)).map(|v| v[m]))
                .find(|&(w, _, _)| w <= *v * (1.0 + 1e-12));
            holds[m] = (body.starts_with("gangue") && con1.is_some_and(|(_, x1, _)| x1 == 0.0 || x1 == l)).into();
            evidence[m] = format!("{body}, {cond}, at (x/L, z/B) = ({}, {})", frac(*x, l), frac(*z, b));
        }
        statements.push(Statement {
            text: "Table 5: the lowest v_y of the three spheres is a gangue's, at an end (x = 0 or L), under Con 1"
                .into(),
            holds,
            evidence,
        });
    }
    {
        let coal_exceeds = quoted.coal_min_exceeds.printed.value;
        let ratio_exceeds = quoted.coal_over_gangue_exceeds.printed.value;
        let mut holds = [Verdict::Holds; 3];
        let mut evidence: [String; 3] = Default::default();
        for m in 0..3 {
            let res = worst_resolution(m);
            let min_of = |name: &str| {
                (0..conds.len())
                    .filter_map(|ci| minima_of.get(&(name.to_string(), ci)).map(|v| v[m].0))
                    .fold(f64::INFINITY, f64::min)
            };
            let coal = min_of(&paper.coal.name);
            let gangue = min_of(&paper.gangue1.name).min(min_of(&paper.gangue2.name));
            holds[m] = Verdict::all([
                Verdict::compare(coal / coal_exceeds, 1.0, res, true),
                Verdict::compare(coal / gangue / ratio_exceeds, 1.0, 2.0 * res, true),
            ]);
            evidence[m] = format!("coal's minimum {}; over the gangues' {}", sig(coal, 4), sig(coal / gangue, 4));
        }
        statements.push(Statement {
            text: format!(
                "Section IV-D: coal's minimum v_y exceeds {} m/s and is more than {} times the gangues'",
                quoted.coal_min_exceeds.text, quoted.coal_over_gangue_exceeds.text
            ),
            holds,
            evidence,
        });
    }
    let mut st =
        Table::new("", &["statement", "beam", "plate", "transient", "beam: data", "plate: data", "transient: data"]);
    for s in &statements {
        let mut row: Vec<Cell> = vec![s.text.clone().into()];
        row.extend(s.holds.iter().map(|&h| verdict(h)));
        row.extend(s.evidence.iter().map(|e| e.clone().into()));
        st.push(row);
    }
    let held = |m: usize| statements.iter().filter(|s| s.holds[m] == Verdict::Holds).count();
    let unresolved = |m: usize| statements.iter().filter(|s| s.holds[m] == Verdict::NotResolved).count();
    let matrix = crate::present::plot::Matrix {
        title: "The paper's yield statements under three models".into(),
        columns: vec!["beam".into(), "plate".into(), "transient".into()],
        rows: statements.iter().map(|s| s.text.clone()).collect(),
        cells: statements.iter().map(|s| s.holds.to_vec()).collect(),
    };
    a.add("statements.svg", matrix.svg());

    // ---------------------------------------------------------------- the prose
    let mid =
        |body: &str| find(body, 1, 4).ok_or_else(|| -> Failure { format!("Table 2 lacks {body} Con 1 Area 4").into() });
    let cm = mid(&paper.coal.name)?;
    let gm = mid(&paper.gangue1.name)?;
    let rel_range = |f: &dyn Fn(&T2) -> f64| {
        t2.iter().map(f).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)))
    };
    let (pb_lo, pb_hi) = rel_range(&|r| r.plate / r.beam - 1.0);
    let (tb_lo, tb_hi) = rel_range(&|r| r.tr.velocity / r.beam - 1.0);
    let (tp_lo, tp_hi) = rel_range(&|r| r.tr.velocity / r.plate - 1.0);
    let (w_lo, w_hi) = rel_range(&|r| r.tr.width / r.tr.velocity);
    let (pe_lo, pe_hi) = rel_range(&|r| r.plate_err / r.plate);
    let runs_t2: usize = t2.iter().map(|r| r.tr.runs).sum();
    let between =
        t2.iter().filter(|r| r.tr.velocity > rigid_yield(&sc, body_of(&r.body)) && r.tr.velocity < r.plate).count();
    let mut above_beam: Vec<usize> = t2.iter().filter(|r| r.tr.velocity > r.beam).map(|r| r.area).collect();
    above_beam.sort_unstable();
    above_beam.dedup();
    let above_beam_cells = t2.iter().filter(|r| r.tr.velocity > r.beam).count();
    // The transient v_y between conditions at one point, against its discretisation error.
    let mut cond_spread: f64 = 0.0;
    for r in &t2 {
        if let Some(r1) = find(&r.body, 1, r.area) {
            cond_spread = cond_spread.max((r.tr.velocity / r1.tr.velocity - 1.0).abs());
        }
    }
    // A difference between two cells is resolved beyond both cells' brackets and both cells'
    // discretisation error estimates.
    let pair_resolution = 2.0 * (w_hi + disc_rel);
    let pct = |v: f64| sig(100.0 * v, 3);
    let models_held = |m: usize| held(m).to_string();
    let values: Vec<(&str, String)> = vec![
        ("points_beam", SWEEP.to_string()),
        ("points_transient", TRANSIENT_SWEEP.to_string()),
        ("plate_base", PLATE_BASE_MESH.to_string()),
        ("plate_finest", (PLATE_BASE_MESH << (PLATE_LEVELS - 1)).to_string()),
        ("transient_elements", settings.elements.to_string()),
        ("transient_steps", settings.steps_per_contact.to_string()),
        ("fine_elements", FINE.elements.to_string()),
        ("fine_steps", FINE.steps_per_contact.to_string()),
        ("root_tolerance", format!("{ROOT_TOLERANCE:e}")),
        ("coal_mid_beam", sig(cm.beam, 6)),
        ("coal_mid_plate", sig(cm.plate, 6)),
        ("coal_mid_transient", sig(cm.tr.velocity, 6)),
        ("coal_mid_printed", sig(cm.printed, 7)),
        ("coal_mid_pb", pct(cm.plate / cm.beam - 1.0)),
        ("coal_mid_tb", pct(cm.tr.velocity / cm.beam - 1.0)),
        ("gangue_mid_beam", sig(gm.beam, 6)),
        ("gangue_mid_plate", sig(gm.plate, 6)),
        ("gangue_mid_transient", sig(gm.tr.velocity, 6)),
        ("gangue_mid_pb", pct(gm.plate / gm.beam - 1.0)),
        ("gangue_mid_tb", pct(gm.tr.velocity / gm.beam - 1.0)),
        ("pb_lo", pct(pb_lo)),
        ("pb_hi", pct(pb_hi)),
        ("tb_lo", pct(tb_lo)),
        ("tb_hi", pct(tb_hi)),
        ("tp_lo", pct(tp_lo)),
        ("tp_hi", pct(tp_hi)),
        ("width_lo", sig(w_lo, 2)),
        ("width_hi", sig(w_hi, 2)),
        ("plate_err_lo", sig(pe_lo, 2)),
        ("plate_err_hi", sig(pe_hi, 2)),
        ("disc_rel", sig(disc_rel, 2)),
        ("cells_t2", t2.len().to_string()),
        ("runs_t2", runs_t2.to_string()),
        ("between", between.to_string()),
        ("above_beam_cells", above_beam_cells.to_string()),
        (
            "above_beam_areas",
            if above_beam.is_empty() {
                "none".into()
            } else {
                above_beam.iter().map(|a| a.to_string()).collect::<Vec<_>>().join(", ")
            },
        ),
        ("cond_spread", sig(cond_spread, 2)),
        ("pair_resolution", sig(pair_resolution, 2)),
        ("spread_vs_disc", (if cond_spread <= pair_resolution { "within" } else { "beyond" }).to_string()),
        ("resolves", (if cond_spread <= pair_resolution { "does not resolve" } else { "resolves" }).to_string()),
        ("runs_per_cell", format!("{:.1}", runs_t2 as f64 / t2.len() as f64)),
        ("table2", t2t.to_markdown()),
        ("discretisation", disc.to_markdown()),
        ("dy_ours", sig(ours.velocity, 8)),
        ("dy_theirs", sig(dy.yield_velocity, 8)),
        ("dy_diff", sig(dy.yield_velocity / ours.velocity - 1.0, 2)),
        ("dy_width", sig(dy.yield_velocity_error.unwrap_or(f64::NAN) / dy.yield_velocity, 2)),
        ("dy_runs", ours.runs.to_string()),
        ("grid_x", GRID.0.to_string()),
        ("grid_z", GRID.1.to_string()),
        ("candidates", candidates.len().to_string()),
        ("table5", t5.to_markdown()),
        ("table5_overall", t5o.to_markdown()),
        ("quoted_min", quoted.min_yield_velocity.text.clone()),
        ("rigid_gangue", sig(rigid_yield(&sc, &paper.gangue1), 6)),
        ("rigid_gangue2", sig(rigid_yield(&sc, &paper.gangue2), 6)),
        ("figures", figures),
        ("statements", st.to_markdown()),
        ("statements_count", statements.len().to_string()),
        ("held_beam", models_held(0)),
        ("held_plate", models_held(1)),
        ("held_transient", models_held(2)),
        ("unresolved_beam", unresolved(0).to_string()),
        ("unresolved_plate", unresolved(1).to_string()),
        ("unresolved_transient", unresolved(2).to_string()),
        ("transient_cells", tr.cells.len().to_string()),
        ("transient_runs", tr.runs().to_string()),
    ];
    // The main report's section and finding: the statements' verdicts without their data.
    let mut verdicts = Table::new("", &["statement", "beam", "plate", "transient"]);
    for s in &statements {
        let mut row: Vec<Cell> = vec![s.text.clone().into()];
        row.extend(s.holds.iter().map(|&h| verdict(h)));
        verdicts.push(row);
    }
    let pick = |names: &[&str]| -> Vec<(&str, String)> {
        values.iter().filter(|(n, _)| names.contains(n)).map(|(n, v)| (*n, v.clone())).collect()
    };
    let mut section_values = pick(&[
        "coal_mid_beam",
        "coal_mid_plate",
        "coal_mid_transient",
        "coal_mid_pb",
        "coal_mid_tb",
        "tp_lo",
        "tp_hi",
        "table5",
        "held_beam",
        "held_plate",
        "held_transient",
        "unresolved_plate",
        "unresolved_transient",
        "statements_count",
    ]);
    section_values.push(("verdicts", verdicts.to_markdown()));
    section_values.push(("figures", figure_links));
    section_values.push(("folder", FOLDER.to_string()));
    let summary = YieldSummary {
        section: render("yield/paper-section.md", PAPER_SECTION, &section_values)?,
        finding: render(
            "yield/paper-finding.md",
            PAPER_FINDING,
            &[
                pick(&[
                    "coal_mid_beam",
                    "coal_mid_plate",
                    "coal_mid_transient",
                    "coal_mid_pb",
                    "coal_mid_tb",
                    "tp_lo",
                    "tp_hi",
                    "held_transient",
                    "unresolved_transient",
                    "statements_count",
                ]),
                vec![("folder", FOLDER.to_string())],
            ]
            .concat(),
        )?,
    };
    let md = render("yield_models.md", TEMPLATE, &values)?;
    a.add("index.md", md);
    a.add("table2-three-models.csv", t2t.to_csv());
    let t5 = t5
        .csv_name("plate at (x/L, z/B)", &["plate_at_x_per_L", "plate_at_z_per_B"])
        .csv_name("transient at (x/L, z/B)", &["transient_at_x_per_L", "transient_at_z_per_B"]);
    a.add("table5-three-models.csv", t5.to_csv());
    let st = st
        .csv_name("beam", &["beam_verdict"])
        .csv_name("plate", &["plate_verdict"])
        .csv_name("transient", &["transient_verdict"])
        .csv_name("beam: data", &["beam_evidence"])
        .csv_name("plate: data", &["plate_evidence"])
        .csv_name("transient: data", &["transient_evidence"]);
    a.add("statements.csv", st.to_csv());
    a.add("transient-discretisation.csv", disc.to_csv());
    let total = t_start.elapsed().as_secs_f64();
    let timing = format!(
        "# Run time of the three-model yield study\n\nWall-clock on this machine; the only page of the study that changes between runs.\n\n| part | s |\n|---|---|\n| quasi-static beam and plate (every point) | {secs_quasi:.1} |\n| Table 2, transient roots | {secs_t2:.1} |\n| discretisation check ({} cells at {} elements, {} steps) | {secs_disc:.1} |\n| `dynamic_yield` cross-check (one cell) | {secs_dy:.1} |\n| Table 5, transient candidates | {secs_t5:.1} |\n| Figs. 8-9, transient curves | {secs_figs:.1} |\n| **total** | **{total:.1}** |\n\n{} transient roots, {} transient runs at the default discretisation.\n",
        checks.len(),
        FINE.elements,
        FINE.steps_per_contact,
        tr.cells.len(),
        tr.runs()
    );
    a.add("timing.md", timing);
    Ok((a, summary))
}

/// The three-model yield study on a scene of one's own: the yield velocity of every body
/// under every support set at the scene's transient points, by the beam (Con 1-3 only), the
/// quasi-static plate and the transient plate, each with its error estimate, and whether the
/// transient v_y lies below the quasi-static plate's by more than both errors.
pub fn scene_study(scene: &Scene, progress: &dyn Progress) -> Result<(Artifacts, YieldSummary), Failure> {
    let mut sc = scene.clone();
    sc.points = Points::Pairs { pairs: scene.transient_points.clone() };
    sc.analyses = vec![Analysis::YieldVelocity];
    studies::run::check_budget(&sc, &[ModelKind::Transient])?;
    let points = sc.point_pairs();
    let periods = plan::fundamental_periods(&sc)?;
    let beam = plan::run(&sc, &BeamModel { plate: &sc.plate }, ModelKind::Beam, &periods)?.yields;
    let plate_model = PlateModel::compute(&sc.plate, &sc.conditions, &points, PLATE_BASE_MESH, PLATE_LEVELS)?;
    let plate = plan::run(&sc, &plate_model, ModelKind::Plate, &periods)?.yields;
    progress.start(plan::transient_case_count(&sc), "transient yield velocities");
    let transient = plan::run_transient_observed(&sc, &mut || progress.advance(1))?.yields;
    progress.finish();
    let same = |rows: &[YieldRow], r: &YieldRow| -> Option<YieldValues> {
        rows.iter()
            .find(|o| o.body == r.body && o.condition == r.condition && o.x == r.x && o.z == r.z)
            .and_then(|o| o.values().cloned())
    };
    let mut t = Table::new(
        "",
        &[
            "body",
            "condition",
            "x (mm)",
            "z (mm)",
            "beam (m/s)",
            "plate (m/s)",
            "plate ± (m/s)",
            "transient (m/s)",
            "transient ± (m/s)",
            "plate/beam - 1",
            "transient/plate - 1",
            "transient below plate",
            "plate validity",
        ],
    );
    let mut findings = String::new();
    for body in &sc.bodies {
        let (mut lo, mut hi, mut below, mut open, mut total) = (f64::INFINITY, f64::NEG_INFINITY, 0, 0, 0);
        let (mut v_lo, mut v_hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for tr in transient.iter().filter(|r| r.body == body.name) {
            let (Some(tv), Some(pv)) = (tr.values(), same(&plate, tr)) else { continue };
            let bv = same(&beam, tr);
            let (t_err, p_err) = (tv.yield_velocity_error.unwrap_or(0.0), pv.yield_velocity_error.unwrap_or(0.0));
            let rel = tv.yield_velocity / pv.yield_velocity - 1.0;
            let lower = Verdict::compare(pv.yield_velocity, tv.yield_velocity, t_err + p_err, true);
            (lo, hi) = (lo.min(rel), hi.max(rel));
            (v_lo, v_hi) = (v_lo.min(tv.yield_velocity), v_hi.max(tv.yield_velocity));
            total += 1;
            match lower {
                Verdict::Holds => below += 1,
                Verdict::NotResolved => open += 1,
                _ => {}
            }
            t.push(vec![
                tr.body.clone().into(),
                tr.condition.clone().into(),
                (tr.x * 1e3).into(),
                (tr.z * 1e3).into(),
                bv.as_ref().map_or(Cell::Empty, |b| b.yield_velocity.into()),
                pv.yield_velocity.into(),
                p_err.into(),
                tv.yield_velocity.into(),
                t_err.into(),
                bv.as_ref().map_or(Cell::Empty, |b| (pv.yield_velocity / b.yield_velocity - 1.0).into()),
                rel.into(),
                verdict(lower),
                crate::present::rows::validity_text(&pv.validity).into(),
            ]);
        }
        if total > 0 {
            findings.push_str(&render(
                "yield/scene-finding.md",
                SCENE_FINDING,
                &[
                    ("body", body.name.clone()),
                    ("v_lo", sig(v_lo, 3)),
                    ("v_hi", sig(v_hi, 3)),
                    ("rel_lo", sig(100.0 * lo, 3)),
                    ("rel_hi", sig(100.0 * hi, 3)),
                    ("below", below.to_string()),
                    ("open", open.to_string()),
                    ("cells", total.to_string()),
                    ("folder", FOLDER.to_string()),
                ],
            )?);
        }
    }
    let values = [
        ("scene", scene.name.clone()),
        ("plate_base", PLATE_BASE_MESH.to_string()),
        ("plate_finest", (PLATE_BASE_MESH << (PLATE_LEVELS - 1)).to_string()),
        ("root_tolerance", format!("{ROOT_TOLERANCE:e}")),
        ("table", t.to_markdown()),
    ];
    let mut a = Artifacts::new();
    a.add(
        "index.md",
        render("yield/scene.md", SCENE_PAGE, &[values.to_vec(), vec![("findings", findings.clone())]].concat())?,
    );
    a.add(
        "yield-three-models.csv",
        t.clone().csv_name("transient below plate", &["transient_below_plate_verdict"]).to_csv(),
    );
    let section = render(
        "yield/scene-section.md",
        SCENE_SECTION,
        &[("findings", findings.clone()), ("table", t.to_markdown()), ("folder", FOLDER.to_string())],
    )?;
    Ok((a, YieldSummary { section, finding: findings }))
}
