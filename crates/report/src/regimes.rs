//! The regime maps: where the paper's quasi-static balance holds, measured with the transient
//! model over plate size, thickness, sphere mass and corner-spring stiffness for Con 1-3, and
//! set beside Olsson's mass criterion, Christoforou and Yigit's characterisation, the t_c/T₁
//! criterion of the validity status and the closed-form rule of `coupled::regimes`.
//!
//! Every case is a transient run on a coarse mesh against the quasi-static plate model (the
//! Richardson-extrapolated compliance of `impact compare`) on the same plate; a sample of the
//! cases is rerun with h and Δt halved, and the largest change of the measured error is the
//! map's own error estimate.

use crate::present::plot::{line_plot, Scale, Series};
use crate::present::table::{sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use analytic::{respond, Condition, Plate, Sphere};
use coupled::plan::impact_of;
use coupled::regimes::{
    mass_ratio, measure, period_estimate, ContactSpeed, Measured, OlssonRegime, RuleInputs, FAST_CONTACT,
    OLSSON_QUASI_STATIC, OLSSON_WAVE_CONTROLLED, RESONANCE_FACTOR, RULE_LIMIT, SLOW_CONTACT, SLOW_FACTOR,
};
use coupled::transient::{case::striker, Striker, TransientCase, TransientSettings};
use coupled::validity::QUASI_STATIC_MIN_RATIO;
use coupled::{ComplianceModel, PlateModel};
use output::Artifacts;
use scene::{Scene, SupportSet};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

const TEMPLATE: &str = include_str!("templates/regimes.md");
/// The main report's line on the study.
const FINDING: &str = include_str!("templates/regimes-finding.md");

/// Plate sizes of the map: L and B times these.
pub const SCALES: [f64; 3] = [0.5, 1.0, 2.0];
/// Thicknesses of the map: the scene's h times these (2-32 mm for the paper's 8 mm plate).
pub const THICKNESS_FACTORS: [f64; 5] = [0.25, 0.5, 1.0, 2.0, 4.0];
/// Spheres of the map: the scene's first body with its radius times these (masses 1/8 to 64
/// times its own).
pub const RADIUS_FACTORS: [f64; 4] = [0.5, 1.0, 2.0, 4.0];
/// Corner-spring stiffnesses of Con 2 and Con 3, N/m: five decades.
pub const SPRINGS: [f64; 6] = [1e6, 1e7, 1e8, 1e9, 1e10, 1e11];
/// Elements along the longer side of the map's transient runs: the sample rerun on twice as
/// many (and twice the steps) moves the measured error by < 1e-3 (the report states it).
pub const MAP_MESH: usize = 16;
/// Steps per quasi-static contact time of the map's runs.
pub const MAP_STEPS: f64 = 200.0;
/// Every this many centre cases one is rerun with h and Δt halved.
const CHECK_EVERY: usize = 26;

/// Which part of the map a case belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slice {
    /// The plate centre, every size, thickness, sphere and support family.
    Centre,
    /// The scene's own support sets at its transient points, the scene's plate size.
    Points,
}

/// One case of the map.
#[derive(Debug, Clone)]
pub struct MapRow {
    /// Which part of the map.
    pub slice: Slice,
    /// The support set's name.
    pub condition: String,
    /// The family the set belongs to: "Con 1", "Con 2", "Con 3" or the scene's name for it.
    pub family: String,
    /// Its corner spring stiffness, N/m (Con 2 and Con 3).
    pub spring: Option<f64>,
    /// L and B over the scene's.
    pub scale: f64,
    /// Plate thickness, m.
    pub thickness: f64,
    /// Sphere radius, m.
    pub radius: f64,
    /// The impact point, m.
    pub point: (f64, f64),
    /// M_i/M_p (Olsson).
    pub mass_ratio: f64,
    /// The fundamental period T₁ from the plate FE, s.
    pub period: f64,
    /// The closed-form estimate T₁,est, s.
    pub period_estimate: Option<f64>,
    /// The Hertz contact time on a rigid target, s.
    pub hertz_time: f64,
    /// The quasi-static compliance at the point, m/N.
    pub compliance: f64,
    /// The closed-form rule's inputs.
    pub rule: RuleInputs,
    /// What the transient and quasi-static runs gave.
    pub measured: Measured,
}

impl MapRow {
    /// The quasi-static balance's force error: the larger of the first contact's and the
    /// whole impact's |transient/QS - 1|.
    pub fn error(&self) -> f64 {
        self.measured.force_error().abs().max(self.measured.impact_force_error().abs())
    }

    /// The signed force error of the two with the larger magnitude.
    pub fn signed_error(&self) -> f64 {
        let (a, b) = (self.measured.force_error(), self.measured.impact_force_error());
        if a.abs() >= b.abs() {
            a
        } else {
            b
        }
    }

    /// The contact-time error, the larger of the first contact's and the whole impact's.
    pub fn time_error(&self) -> Option<f64> {
        Some(self.measured.time_error()?.abs().max(self.measured.impact_time_error()?.abs()))
    }

    /// t_H/T₁ with T₁ from the plate FE.
    pub fn period_ratio(&self) -> f64 {
        self.hertz_time / self.period
    }

    /// Whether the measured force error is within the rule's limit.
    pub fn quasi_static(&self) -> bool {
        self.error() <= RULE_LIMIT
    }
}

/// A support family of the map.
struct Family {
    family: String,
    set: SupportSet,
    spring: Option<f64>,
}

/// Con 1, and Con 2 and Con 3 at every stiffness of [`SPRINGS`], plus the scene's sets that
/// are not the paper's (each at its own supports).
fn families(scene: &Scene) -> Vec<Family> {
    let mut out =
        vec![Family { family: "Con 1".into(), set: SupportSet::preset("Con 1", Condition::BothFixed), spring: None }];
    for k_t in SPRINGS {
        for (family, condition) in
            [("Con 2", Condition::BothSprings { k_t }), ("Con 3", Condition::FixedAndSprings { k_t })]
        {
            out.push(Family {
                family: family.into(),
                set: SupportSet::preset(format!("{family}, k_T = {}", sig(k_t, 2)), condition),
                spring: Some(k_t),
            });
        }
    }
    for set in scene.conditions.iter().filter(|c| c.beam_condition().is_none()) {
        out.push(Family { family: set.name.clone(), set: set.clone(), spring: None });
    }
    out
}

/// One job of the map: a plate and what to run on it.
struct Job {
    slice: Slice,
    scale: f64,
    thickness_factor: f64,
}

/// The scene's plate scaled in size and thickness.
fn scaled_plate(scene: &Scene, scale: f64, thickness_factor: f64) -> Result<Plate, Failure> {
    let p = &scene.plate;
    Ok(Plate::new(p.length() * scale, p.width() * scale, p.thickness() * thickness_factor, p.density(), p.material())?)
}

/// The scene's first body with its radius times `factor`.
fn scaled_body(body: &Sphere, factor: f64) -> Result<Sphere, Failure> {
    Ok(Sphere::new(
        format!("{} x{factor}", body.name),
        body.density(),
        body.radius() * factor,
        body.material(),
        body.strength(),
    )?)
}

/// The support sets of a job (family, set, corner spring) and its impact points.
type JobCases = (Vec<(String, SupportSet, Option<f64>)>, Vec<(f64, f64)>);
/// Each job's rows, or its failure as text, in job order (None until it has run).
type JobSlots = Mutex<Vec<Option<Result<Vec<MapRow>, String>>>>;
/// A published criterion as a test of one case.
type CaseTest = Box<dyn Fn(&MapRow) -> bool>;

/// Every case of one plate.
fn run_job(scene: &Scene, job: &Job, families: &[Family]) -> Result<Vec<MapRow>, Failure> {
    let plate = scaled_plate(scene, job.scale, job.thickness_factor)?;
    let (sets, points): JobCases = match job.slice {
        Slice::Centre => (
            families.iter().map(|f| (f.family.clone(), f.set.clone(), f.spring)).collect(),
            vec![(plate.length() / 2.0, plate.width() / 2.0)],
        ),
        Slice::Points => (
            scene.conditions.iter().map(|c| (c.name.clone(), c.clone(), c.spring_stiffnesses().next())).collect(),
            scene.transient_points.clone(),
        ),
    };
    let set_list: Vec<SupportSet> = sets.iter().map(|s| s.1.clone()).collect();
    let case = TransientCase::new(&plate, TransientSettings { elements: MAP_MESH, ..Default::default() })?;
    let qs = PlateModel::compute(&plate, &set_list, &points, studies::settings::BASE_MESH, studies::settings::LEVELS)?;
    let body = scene.bodies.first().ok_or("the scene has no body")?;
    let v = scene.velocities.first().copied().ok_or("the scene has no velocity")?;
    let on_plate = Scene { plate, ..scene.clone() };
    let mut rows = Vec::new();
    for (family, set, spring) in &sets {
        let period = case.fundamental_period(&set.supports)?;
        for &(x, z) in &points {
            let facts = case.facts(&set.supports, x, z);
            let c = qs.compliance(set, x, z)?;
            for factor in RADIUS_FACTORS {
                let sphere = scaled_body(body, factor)?;
                let s: Striker = striker(&plate, &sphere, scene.restitution, v);
                let imp = impact_of(&on_plate, &sphere, v);
                let qs_force = respond(&imp, &c.compliance, studies::settings::METHOD)?.contact_force;
                let total = c.compliance.total();
                let measured = measure(&case, set, facts, &s, (x, z), total, qs_force, MAP_STEPS)?;
                rows.push(MapRow {
                    slice: job.slice,
                    condition: set.name.clone(),
                    family: family.clone(),
                    spring: *spring,
                    scale: job.scale,
                    thickness: plate.thickness(),
                    radius: sphere.radius(),
                    point: (x, z),
                    mass_ratio: mass_ratio(s.mass, &plate),
                    period,
                    period_estimate: period_estimate(&plate, set),
                    hertz_time: s.hertz_time(),
                    compliance: total,
                    rule: RuleInputs::of(&s, &plate, set, total),
                    measured,
                });
            }
        }
    }
    Ok(rows)
}

/// Runs `jobs` on up to `threads` threads, in order of the jobs.
fn run_jobs(scene: &Scene, jobs: &[Job], families: &[Family], threads: usize) -> Result<Vec<MapRow>, Failure> {
    let next = AtomicUsize::new(0);
    let results: JobSlots = Mutex::new(jobs.iter().map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..threads.max(1) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(job) = jobs.get(i) else { break };
                let r = run_job(scene, job, families).map_err(|e| e.to_string());
                if let Ok(mut all) = results.lock() {
                    all[i] = Some(r);
                }
            });
        }
    });
    let mut rows = Vec::new();
    for r in results.into_inner().map_err(|_| "a map thread panicked")? {
        rows.extend(r.ok_or("a map job did not run")??);
    }
    Ok(rows)
}

/// The map's own error, from a sample of centre cases rerun with h and Δt halved.
#[derive(Debug, Clone, Copy, Default)]
struct Check {
    /// Cases rerun.
    cases: usize,
    /// Largest relative change of a transient force (first contact or whole impact).
    force: f64,
    /// Largest change of the force error among cases within 10 % of quasi-static, where the
    /// rule's 3 % is decided.
    near: f64,
    /// Largest change of the contact-time error.
    time: f64,
    /// Cases whose number of contacts changed.
    recount: usize,
}

fn discretisation_check(scene: &Scene, rows: &[MapRow], families: &[Family]) -> Result<Check, Failure> {
    let body = scene.bodies.first().ok_or("the scene has no body")?;
    let v = scene.velocities.first().copied().ok_or("the scene has no velocity")?;
    let mut c = Check::default();
    for r in rows.iter().filter(|r| r.slice == Slice::Centre).step_by(CHECK_EVERY) {
        let set = &families.iter().find(|f| f.set.name == r.condition).ok_or("lost a support family")?.set;
        let plate = Plate::new(
            scene.plate.length() * r.scale,
            scene.plate.width() * r.scale,
            r.thickness,
            scene.plate.density(),
            scene.plate.material(),
        )?;
        let case = TransientCase::new(&plate, TransientSettings { elements: 2 * MAP_MESH, ..Default::default() })?;
        let sphere = scaled_body(body, r.radius / body.radius())?;
        let s = striker(&plate, &sphere, scene.restitution, v);
        let facts = case.facts(&set.supports, r.point.0, r.point.1);
        let m = measure(&case, set, facts, &s, r.point, r.compliance, r.measured.quasi_static_force, 2.0 * MAP_STEPS)?;
        let old = &r.measured;
        c.force = c
            .force
            .max((m.transient_force / old.transient_force - 1.0).abs())
            .max((m.impact_force / old.impact_force - 1.0).abs());
        if r.error() < 0.1 {
            c.near = c
                .near
                .max((m.force_error() - old.force_error()).abs())
                .max((m.impact_force_error() - old.impact_force_error()).abs());
        }
        if let (Some(a), Some(b)) = (m.time_error(), old.time_error()) {
            c.time = c.time.max((a - b).abs());
        }
        c.recount += usize::from(m.contacts != old.contacts);
        c.cases += 1;
    }
    Ok(c)
}

/// How one criterion fares on a set of cases: it trusts the balance or flags it, and the
/// measured error says whether it was right (force within the rule's 3 %).
#[derive(Debug, Clone, Copy, Default)]
struct Score {
    trusted: usize,
    trusted_wrong: usize,
    worst_trusted: f64,
    flagged: usize,
    flagged_fine: usize,
}

fn score<'a>(rows: impl Iterator<Item = &'a MapRow>, trusts: impl Fn(&MapRow) -> bool) -> Score {
    let mut s = Score::default();
    for r in rows {
        if trusts(r) {
            s.trusted += 1;
            s.worst_trusted = s.worst_trusted.max(r.error());
            s.trusted_wrong += usize::from(!r.quasi_static());
        } else {
            s.flagged += 1;
            s.flagged_fine += usize::from(r.quasi_static());
        }
    }
    s
}

/// The criteria set beside the measured error, each as a test of one case.
fn criteria() -> Vec<(&'static str, CaseTest)> {
    vec![
        ("Olsson: large mass, M_i/M_p > 2", Box::new(|r: &MapRow| r.mass_ratio > OLSSON_QUASI_STATIC)),
        ("Olsson: not small mass, M_i/M_p ≥ 0.23", Box::new(|r: &MapRow| r.mass_ratio >= OLSSON_WAVE_CONTROLLED)),
        (
            "t_H/T₁ ≥ 0.2 (T₁ from the plate FE; the validity status)",
            Box::new(|r: &MapRow| r.period_ratio() >= QUASI_STATIC_MIN_RATIO),
        ),
        (
            "Christoforou and Yigit: B ≤ 3 % (ζ < 1)",
            Box::new(|r: &MapRow| r.rule.parameters.error_bound() <= RULE_LIMIT && r.rule.parameters.loss_factor < 1.0),
        ),
        ("the closed-form rule", Box::new(|r: &MapRow| r.rule.trusts())),
        (
            "the validity status: t_H/T₁ ≥ 0.2 and the rule",
            Box::new(|r: &MapRow| r.period_ratio() >= QUASI_STATIC_MIN_RATIO && r.rule.trusts()),
        ),
    ]
}

fn score_table(rows: &[MapRow], slice: Slice) -> Table {
    let mut t = Table::new(
        "",
        &[
            "criterion",
            "cases it trusts",
            "of them off by more than 3 %",
            "worst error it trusts",
            "cases it flags",
            "of them within 3 %",
        ],
    );
    for (name, trusts) in criteria() {
        let s = score(rows.iter().filter(|r| r.slice == slice), trusts);
        t.push(vec![
            name.into(),
            Cell::Int(s.trusted as u64),
            Cell::Int(s.trusted_wrong as u64),
            if s.trusted > 0 { Cell::Num(s.worst_trusted) } else { Cell::Empty },
            Cell::Int(s.flagged as u64),
            Cell::Int(s.flagged_fine as u64),
        ]);
    }
    t
}

/// Olsson's three regimes against the measured error.
fn olsson_table(rows: &[MapRow]) -> Table {
    let mut t = Table::new(
        "",
        &["Olsson's regime", "cases", "within 3 %", "largest error", "smallest error", "with repeated contacts"],
    );
    for regime in [OlssonRegime::WaveControlled, OlssonRegime::Mixed, OlssonRegime::QuasiStatic] {
        let of: Vec<&MapRow> =
            rows.iter().filter(|r| r.slice == Slice::Centre && OlssonRegime::of(r.mass_ratio) == regime).collect();
        let errors = of.iter().map(|r| r.error());
        t.push(vec![
            regime.key().into(),
            Cell::Int(of.len() as u64),
            Cell::Int(of.iter().filter(|r| r.quasi_static()).count() as u64),
            if of.is_empty() { Cell::Empty } else { Cell::Num(errors.clone().fold(0.0, f64::max)) },
            if of.is_empty() { Cell::Empty } else { Cell::Num(errors.fold(f64::INFINITY, f64::min)) },
            Cell::Int(of.iter().filter(|r| r.measured.contacts > 1).count() as u64),
        ]);
    }
    t
}

/// Every case, for the CSV.
fn full_table(rows: &[MapRow]) -> Table {
    full_rows(rows).csv_name("Olsson", &["Olsson_regime"])
}

fn full_rows(rows: &[MapRow]) -> Table {
    let mut t = Table::new(
        "",
        &[
            "slice",
            "condition",
            "k_T (N/m)",
            "size (x L, B)",
            "h (mm)",
            "R (mm)",
            "x (mm)",
            "z (mm)",
            "M_i/M_p",
            "Olsson",
            "T₁ FE (ms)",
            "T₁ est (ms)",
            "t_H (ms)",
            "t_H/T₁",
            "t_H/T₁ est",
            "lambda",
            "zeta",
            "C&Y bound B",
            "rule regime",
            "rule bound",
            "rule trusts",
            "P transient first contact (N)",
            "P transient whole impact (N)",
            "P quasi-static (N)",
            "force error first contact",
            "force error whole impact",
            "contacts",
            "t_c transient (ms)",
            "t_c quasi-static (ms)",
            "contact-time error first contact",
            "duration error whole impact",
            "time step (s)",
        ],
    );
    for r in rows {
        let m = &r.measured;
        let p = &r.rule.parameters;
        let ms = |v: Option<f64>| v.map_or(Cell::Empty, |v| Cell::Num(v * 1e3));
        t.push(vec![
            match r.slice {
                Slice::Centre => "centre",
                Slice::Points => "points",
            }
            .into(),
            r.condition.clone().into(),
            r.spring.map_or(Cell::Empty, Cell::Num),
            r.scale.into(),
            (r.thickness * 1e3).into(),
            (r.radius * 1e3).into(),
            (r.point.0 * 1e3).into(),
            (r.point.1 * 1e3).into(),
            r.mass_ratio.into(),
            OlssonRegime::of(r.mass_ratio).key().into(),
            (r.period * 1e3).into(),
            ms(r.period_estimate),
            (r.hertz_time * 1e3).into(),
            r.period_ratio().into(),
            r.rule.period_ratio.map_or(Cell::Empty, Cell::Num),
            p.relative_stiffness.into(),
            p.loss_factor.into(),
            p.error_bound().into(),
            speed_key(r.rule.speed()).into(),
            r.rule.error_bound().into(),
            r.rule.trusts().into(),
            m.transient_force.into(),
            m.impact_force.into(),
            m.quasi_static_force.into(),
            m.force_error().into(),
            m.impact_force_error().into(),
            Cell::Int(m.contacts as u64),
            ms(m.transient_time),
            ms(m.quasi_static_time),
            m.time_error().map_or(Cell::Empty, Cell::Num),
            m.impact_time_error().map_or(Cell::Empty, Cell::Num),
            m.time_step.into(),
        ]);
    }
    t
}

fn speed_key(s: ContactSpeed) -> &'static str {
    match s {
        ContactSpeed::Fast => "fast",
        ContactSpeed::Resonant => "resonant",
        ContactSpeed::Slow => "slow",
    }
}

/// Signed force errors in percent, rows (size, h), columns the spheres, for one family at
/// one spring stiffness; a mark where the rule trusts the balance.
fn grid_table(rows: &[MapRow], condition: &str, radii: &[f64]) -> Table {
    let mut headers = vec!["size (x L, B)".to_string(), "h (mm)".to_string()];
    headers.extend(radii.iter().map(|r| format!("R = {} mm: error (%), rule", sig(r * 1e3, 3))));
    let refs: Vec<&str> = headers.iter().map(String::as_str).collect();
    let mut t = Table::new("", &refs);
    let of: Vec<&MapRow> = rows.iter().filter(|r| r.slice == Slice::Centre && r.condition == condition).collect();
    let mut keys: Vec<(f64, f64)> = Vec::new();
    for r in &of {
        if !keys.iter().any(|k| k.0 == r.scale && k.1 == r.thickness) {
            keys.push((r.scale, r.thickness));
        }
    }
    for (scale, h) in keys {
        let mut row: Vec<Cell> = vec![scale.into(), (h * 1e3).into()];
        for &radius in radii {
            row.push(of.iter().find(|r| r.scale == scale && r.thickness == h && r.radius == radius).map_or(
                Cell::Empty,
                |r| {
                    Cell::Text(format!(
                        "{:+.1}{}{}",
                        100.0 * r.signed_error(),
                        if r.measured.contacts > 1 {
                            format!(" ({} contacts)", r.measured.contacts)
                        } else {
                            String::new()
                        },
                        if r.rule.trusts() { ", trusted" } else { "" }
                    ))
                },
            ));
        }
        t.push(row);
    }
    t
}

/// Force error against the spring stiffness at the scene's size and thickness.
fn spring_table(rows: &[MapRow], radii: &[f64]) -> Table {
    let mut headers =
        vec!["family".to_string(), "k_T (N/m)".to_string(), "T₁ FE (ms)".to_string(), "T₁ est/FE".to_string()];
    headers.extend(radii.iter().map(|r| format!("R = {} mm: error (%)", sig(r * 1e3, 3))));
    let refs: Vec<&str> = headers.iter().map(String::as_str).collect();
    let mut t = Table::new("", &refs);
    let h = mid_thickness(rows);
    let paper_h: Vec<&MapRow> = rows
        .iter()
        .filter(|r| r.slice == Slice::Centre && r.scale == 1.0 && r.spring.is_some() && r.thickness == h)
        .collect();
    let mut done: Vec<String> = Vec::new();
    for r in &paper_h {
        if done.contains(&r.condition) {
            continue;
        }
        done.push(r.condition.clone());
        let mut row: Vec<Cell> = vec![
            r.family.clone().into(),
            r.spring.map_or(Cell::Empty, |k| Cell::Text(sig(k, 2))),
            (r.period * 1e3).into(),
            r.period_estimate.map_or(Cell::Empty, |t| Cell::Num(t / r.period)),
        ];
        for &radius in radii {
            row.push(
                paper_h
                    .iter()
                    .find(|q| q.condition == r.condition && q.radius == radius)
                    .map_or(Cell::Empty, |q| Cell::Text(format!("{:+.1}", 100.0 * q.signed_error()))),
            );
        }
        t.push(row);
    }
    t
}

/// The scene's own thickness (the middle factor of the map).
fn mid_thickness(rows: &[MapRow]) -> f64 {
    let mut hs: Vec<f64> = rows.iter().map(|r| r.thickness).collect();
    hs.sort_by(f64::total_cmp);
    hs.dedup();
    hs.get(hs.len() / 2).copied().unwrap_or(f64::NAN)
}

/// The points slice, point by point: how the rule fares there.
fn points_table(rows: &[MapRow]) -> Table {
    let mut t = Table::new(
        "",
        &[
            "point (x, z) in mm",
            "cases",
            "within 3 %",
            "the rule trusts",
            "of them off by more than 3 %",
            "worst error it trusts",
            "with repeated contacts",
        ],
    );
    let of: Vec<&MapRow> = rows.iter().filter(|r| r.slice == Slice::Points).collect();
    let mut points: Vec<(f64, f64)> = Vec::new();
    for r in &of {
        if !points.contains(&r.point) {
            points.push(r.point);
        }
    }
    for p in points {
        let here: Vec<&&MapRow> = of.iter().filter(|r| r.point == p).collect();
        let s = score(here.iter().map(|r| **r), |r| r.rule.trusts());
        t.push(vec![
            format!("({}, {})", sig(p.0 * 1e3, 4), sig(p.1 * 1e3, 4)).into(),
            Cell::Int(here.len() as u64),
            Cell::Int(here.iter().filter(|r| r.quasi_static()).count() as u64),
            Cell::Int(s.trusted as u64),
            Cell::Int(s.trusted_wrong as u64),
            if s.trusted > 0 { Cell::Num(s.worst_trusted) } else { Cell::Empty },
            Cell::Int(here.iter().filter(|r| r.measured.contacts > 1).count() as u64),
        ]);
    }
    t
}

/// |error| against a closed-form abscissa, one curve per sphere at the scene's size over the
/// thicknesses, for one condition.
fn curves(rows: &[MapRow], condition: &str, scale: f64, x: impl Fn(&MapRow) -> f64, radii: &[f64]) -> Vec<Series> {
    radii
        .iter()
        .map(|&radius| {
            let mut pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| {
                    r.slice == Slice::Centre && r.condition == condition && r.scale == scale && r.radius == radius
                })
                .map(|r| (x(r), r.error()))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            Series::new(format!("R = {} mm, h over the map", sig(radius * 1e3, 3)), pts)
        })
        .collect()
}

/// A vertical line at `x` across the y range of `series`.
fn vertical(name: &str, x: f64, series: &[Series]) -> Series {
    let ys = series.iter().flat_map(|s| s.points.iter().map(|p| p.1)).filter(|y| *y > 0.0 && y.is_finite());
    let (lo, hi) = ys.fold((f64::INFINITY, 0.0f64), |(a, b), y| (a.min(y), b.max(y)));
    Series::new(name, if lo.is_finite() { vec![(x, lo), (x, hi)] } else { vec![] })
}

/// A horizontal line at `y` across the x range of `series`.
fn horizontal(name: &str, y: f64, series: &[Series]) -> Series {
    let xs = series.iter().flat_map(|s| s.points.iter().map(|p| p.0)).filter(|x| x.is_finite());
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    Series::new(name, if lo.is_finite() { vec![(lo, y), (hi, y)] } else { vec![] })
}

/// The main report's line on the study: how the closed-form rule and t_c/T₁ ≥ 0.2 fare on the
/// `cases` centre cases, and the rule on the `points_cases` cases at the scene's points.
fn main_finding(
    cases: usize,
    rule: &Score,
    ratio: &Score,
    points_cases: usize,
    points: &Score,
) -> Result<String, Failure> {
    Ok(render(
        "regimes-finding.md",
        FINDING,
        &[
            ("cases", cases.to_string()),
            ("rule_trusted", rule.trusted.to_string()),
            ("rule_wrong", rule.trusted_wrong.to_string()),
            ("rule_worst", format!("{:.1}", 100.0 * rule.worst_trusted)),
            ("ratio_trusted", ratio.trusted.to_string()),
            ("ratio_wrong", ratio.trusted_wrong.to_string()),
            ("ratio_worst", format!("{:.0}", 100.0 * ratio.worst_trusted)),
            ("points_cases", points_cases.to_string()),
            ("points_trusted", points.trusted.to_string()),
            ("points_wrong", points.trusted_wrong.to_string()),
            ("limit", format!("{}", 100.0 * RULE_LIMIT)),
            ("qs_ratio", QUASI_STATIC_MIN_RATIO.to_string()),
        ],
    )?)
}

/// The regime-maps report.
pub fn report(scene: &Scene) -> Result<Artifacts, Failure> {
    Ok(study(scene)?.0)
}

/// [`report`], and its finding for the main report: one Markdown bullet line linking the
/// study (nested in the folder `regimes`).
pub fn study(scene: &Scene) -> Result<(Artifacts, String), Failure> {
    let t0 = Instant::now();
    let families = families(scene);
    let mut jobs: Vec<Job> = Vec::new();
    for scale in SCALES {
        for f in THICKNESS_FACTORS {
            jobs.push(Job { slice: Slice::Centre, scale, thickness_factor: f });
        }
    }
    for f in THICKNESS_FACTORS {
        jobs.push(Job { slice: Slice::Points, scale: 1.0, thickness_factor: f });
    }
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).min(4);
    let rows = run_jobs(scene, &jobs, &families, threads)?;
    let map_secs = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let check = discretisation_check(scene, &rows, &families)?;
    let check_secs = t1.elapsed().as_secs_f64();

    let body = scene.bodies.first().ok_or("the scene has no body")?;
    let radii: Vec<f64> = RADIUS_FACTORS.iter().map(|f| body.radius() * f).collect();
    let centre: Vec<&MapRow> = rows.iter().filter(|r| r.slice == Slice::Centre).collect();
    let points_n = rows.len() - centre.len();

    // The numbers the prose quotes, all from this run.
    let rule = score(centre.iter().copied(), |r| r.rule.trusts());
    let rule_points = score(rows.iter().filter(|r| r.slice == Slice::Points), |r| r.rule.trusts());
    let ratio = score(centre.iter().copied(), |r| r.period_ratio() >= QUASI_STATIC_MIN_RATIO);
    let large = score(centre.iter().copied(), |r| r.mass_ratio > OLSSON_QUASI_STATIC);
    let small: Vec<&&MapRow> = centre.iter().filter(|r| r.mass_ratio < OLSSON_WAVE_CONTROLLED).collect();
    let small_fine = small.iter().filter(|r| r.quasi_static()).count();
    let small_fine_lambda =
        small.iter().filter(|r| r.quasi_static()).map(|r| r.rule.parameters.relative_stiffness).fold(0.0f64, f64::max);
    let repeated: Vec<&&MapRow> = centre.iter().filter(|r| r.measured.contacts > 1).collect();
    let repeated_min_zeta = repeated.iter().map(|r| r.rule.parameters.loss_factor).fold(f64::INFINITY, f64::min);
    // Christoforou and Yigit's bound where ζ < 1 and the contact is fast: how often it holds.
    let fast: Vec<&&MapRow> = centre.iter().filter(|r| r.rule.speed() == ContactSpeed::Fast).collect();
    let fast_bound_holds = fast.iter().filter(|r| r.error() <= r.rule.parameters.error_bound() + 1e-12).count();
    let share = |r: &MapRow| r.rule.parameters.relative_stiffness / (1.0 + r.rule.parameters.relative_stiffness);
    let band_low = centre
        .iter()
        .filter(|r| r.rule.speed() == ContactSpeed::Resonant && r.rule.period_ratio.is_some())
        .map(|r| r.signed_error() / share(r))
        .fold(0.0f64, f64::min);
    let slow_high = centre
        .iter()
        .filter(|r| r.rule.speed() == ContactSpeed::Slow)
        .map(|r| r.error() / share(r))
        .fold(0.0f64, f64::max);
    let trusted_time = rows.iter().filter(|r| r.rule.trusts()).filter_map(|r| r.time_error()).fold(0.0f64, f64::max);
    let period_ratio_range = rows
        .iter()
        .filter_map(|r| r.period_estimate.map(|t| t / r.period))
        .fold((f64::INFINITY, 0.0f64), |(a, b), q| (a.min(q), b.max(q)));

    let mut a = Artifacts::new();
    a.add("map.csv", full_table(&rows).to_csv());

    let con1 = "Con 1";
    let olsson_curves = curves(&rows, con1, 1.0, |r| r.mass_ratio.log10(), &radii);
    let mut olsson_plot = olsson_curves.clone();
    olsson_plot.push(vertical("Olsson: wave controlled below 0.23", OLSSON_WAVE_CONTROLLED.log10(), &olsson_curves));
    olsson_plot.push(vertical("Olsson: quasi-static above 2", OLSSON_QUASI_STATIC.log10(), &olsson_curves));
    olsson_plot.push(horizontal("3 %", RULE_LIMIT, &olsson_curves));
    a.add(
        "olsson.svg",
        line_plot(
            "Con 1, centre, the scene's plate size: force error against Olsson's mass ratio",
            "log10(M_i/M_p)",
            "|P transient/quasi-static - 1|",
            &olsson_plot,
            Scale::Log,
        ),
    );
    let cy_curves = curves(&rows, con1, 1.0, |r| r.rule.parameters.error_bound().max(1e-6).log10(), &radii);
    let mut cy_plot = cy_curves.clone();
    let xs: Vec<f64> = cy_curves.iter().flat_map(|s| s.points.iter().map(|p| p.0)).collect();
    let (x_lo, x_hi) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    if x_lo.is_finite() {
        cy_plot.push(Series::new("measured = B", vec![(x_lo, 10f64.powf(x_lo)), (x_hi, 10f64.powf(x_hi))]));
    }
    a.add(
        "christoforou-yigit.svg",
        line_plot(
            "Con 1, centre: force error against Christoforou and Yigit's bound B",
            "log10 B",
            "|P transient/quasi-static - 1|",
            &cy_plot,
            Scale::Log,
        ),
    );
    // The smallest plates reach the slow regime.
    let small_scale = SCALES.iter().copied().fold(f64::INFINITY, f64::min);
    let period_curves = curves(&rows, con1, small_scale, |r| r.rule.period_ratio.unwrap_or(f64::NAN).log10(), &radii);
    let mut period_plot = period_curves.clone();
    period_plot.push(vertical("t_H/T₁ = 0.2 (fast below)", FAST_CONTACT.log10(), &period_curves));
    period_plot.push(vertical("t_H/T₁ = 2 (slow above)", SLOW_CONTACT.log10(), &period_curves));
    period_plot.push(horizontal("3 %", RULE_LIMIT, &period_curves));
    a.add(
        "period.svg",
        line_plot(
            "Con 1, centre, the smallest plates: force error against t_H/T₁,est",
            "log10(t_H/T₁,est)",
            "|P transient/quasi-static - 1|",
            &period_plot,
            Scale::Log,
        ),
    );
    let spring_series: Vec<Series> = ["Con 2", "Con 3"]
        .iter()
        .flat_map(|fam| radii.iter().take(2).map(move |&radius| (fam, radius)))
        .map(|(fam, radius)| {
            let h = mid_thickness(&rows);
            let mut pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| {
                    r.slice == Slice::Centre
                        && r.family == *fam
                        && r.scale == 1.0
                        && r.thickness == h
                        && r.radius == radius
                })
                .filter_map(|r| Some((r.spring?.log10(), r.error())))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            Series::new(format!("{fam}, R = {} mm", sig(radius * 1e3, 3)), pts)
        })
        .collect();
    a.add(
        "springs.svg",
        line_plot(
            "Centre, the scene's plate: force error against the corner-spring stiffness",
            "log10(k_T / (N/m))",
            "|P transient/quasi-static - 1|",
            &spring_series,
            Scale::Log,
        ),
    );

    let md = render(
        "regimes.md",
        TEMPLATE,
        &[
            ("scene", scene.name.clone()),
            ("body", body.name.clone()),
            ("velocity", sig(scene.velocities.first().copied().unwrap_or(f64::NAN), 3)),
            ("cases", centre.len().to_string()),
            ("points_cases", points_n.to_string()),
            ("families", families.len().to_string()),
            ("mesh", MAP_MESH.to_string()),
            ("steps", MAP_STEPS.to_string()),
            ("map_secs", format!("{map_secs:.0}")),
            ("threads", threads.to_string()),
            ("checked", check.cases.to_string()),
            ("check_force", sig(check.force, 2)),
            ("check_near", sig(check.near, 2)),
            ("check_time", sig(check.time, 2)),
            ("recount", check.recount.to_string()),
            ("check_secs", format!("{check_secs:.0}")),
            ("rule_trusted", rule.trusted.to_string()),
            ("rule_wrong", rule.trusted_wrong.to_string()),
            ("rule_worst", format!("{:.1}", 100.0 * rule.worst_trusted)),
            ("rule_flagged", rule.flagged.to_string()),
            ("rule_fine", rule.flagged_fine.to_string()),
            ("points_trusted", rule_points.trusted.to_string()),
            ("points_wrong", rule_points.trusted_wrong.to_string()),
            ("points_flagged_fine", rule_points.flagged_fine.to_string()),
            ("points_flagged", rule_points.flagged.to_string()),
            ("trusted_time", format!("{:.1}", 100.0 * trusted_time)),
            ("ratio_trusted", ratio.trusted.to_string()),
            ("ratio_wrong", ratio.trusted_wrong.to_string()),
            ("ratio_worst", format!("{:.0}", 100.0 * ratio.worst_trusted)),
            ("large_trusted", large.trusted.to_string()),
            ("large_wrong", large.trusted_wrong.to_string()),
            ("large_worst", format!("{:.0}", 100.0 * large.worst_trusted)),
            ("small_cases", small.len().to_string()),
            ("small_fine", small_fine.to_string()),
            ("small_fine_lambda", sig(small_fine_lambda, 2)),
            ("repeated", repeated.len().to_string()),
            ("repeated_min_zeta", sig(repeated_min_zeta, 2)),
            ("fast_cases", fast.len().to_string()),
            ("fast_bound_holds", fast_bound_holds.to_string()),
            ("band_low", format!("{band_low:.2}")),
            ("slow_high", format!("{slow_high:.2}")),
            ("period_ratio_lo", format!("{:.3}", period_ratio_range.0)),
            ("period_ratio_hi", format!("{:.3}", period_ratio_range.1)),
            ("olsson_wave", OLSSON_WAVE_CONTROLLED.to_string()),
            ("olsson_quasi", OLSSON_QUASI_STATIC.to_string()),
            ("fast_contact", FAST_CONTACT.to_string()),
            ("slow_contact", SLOW_CONTACT.to_string()),
            ("resonance_factor", RESONANCE_FACTOR.to_string()),
            ("slow_factor", SLOW_FACTOR.to_string()),
            ("limit", format!("{}", 100.0 * RULE_LIMIT)),
            ("qs_ratio", QUASI_STATIC_MIN_RATIO.to_string()),
            ("score_table", score_table(&rows, Slice::Centre).to_markdown()),
            ("points_score_table", score_table(&rows, Slice::Points).to_markdown()),
            ("olsson_table", olsson_table(&rows).to_markdown()),
            ("con1_table", grid_table(&rows, con1, &radii).to_markdown()),
            ("spring_table", spring_table(&rows, &radii).to_markdown()),
            ("points_table", points_table(&rows).to_markdown()),
        ],
    )?;
    a.add("index.md", md);
    let finding = main_finding(centre.len(), &rule, &ratio, points_n, &rule_points)?;
    Ok((a, finding))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The main report's line renders every number it is given (the study itself takes
    /// minutes and runs in `impact report`).
    #[test]
    fn the_main_report_line_renders() {
        let rule = Score { trusted: 101, trusted_wrong: 0, worst_trusted: 0.017, flagged: 679, flagged_fine: 126 };
        let ratio = Score { trusted: 251, trusted_wrong: 107, worst_trusted: 0.32, ..Score::default() };
        let points = Score { trusted: 30, ..Score::default() };
        let line = main_finding(780, &rule, &ratio, 240, &points).unwrap();
        for part in [
            "780 cases",
            "in 101, 0 of them",
            "worst 1.7 %",
            "trusts 251, 107 of them wrongly (worst 32 %)",
            "on 240 cases",
            "trusts 30, 0 wrongly",
            "](regimes/index.md)",
        ] {
            assert!(line.contains(part), "{part}: {line}");
        }
    }
}
