//! The regime maps: where the paper's quasi-static balance holds, measured with the transient
//! model over plate size, thickness, sphere mass and corner-spring stiffness for Con 1-3, and
//! set beside Olsson's mass criterion, Christoforou and Yigit's characterisation, the t_c/T₁
//! criterion of the validity status and the closed-form rule of `coupled::regimes`.
//!
//! Every case is a transient run on a coarse mesh against the quasi-static plate model (the
//! Richardson-extrapolated compliance of `impact compare`) on the same plate; a sample of the
//! cases is rerun with h and Δt halved, and the largest change of the measured error is the
//! map's own error estimate.
//!
//! The maps measure the paper's balance, so every case strikes with the paper's contact law
//! (Flores, [`coupled::transient::case::striker`]) whatever law the scene names: the
//! criteria they test are statements about that balance, and a scene's other law would move
//! the measured errors, not the criteria.

mod run;
mod score;

pub use score::{CriterionScore, OlssonRow, PointScore, Score};

use crate::columns::sig;
use crate::progress::Progress;
use crate::settings::Settings;
use crate::Failure;
use analytic::Condition;
use coupled::regimes::{ContactSpeed, Measured, RuleInputs, OLSSON_QUASI_STATIC, OLSSON_WAVE_CONTROLLED, RULE_LIMIT};
use coupled::validity::QUASI_STATIC_MIN_RATIO;
use scene::{Scene, SupportSet};
use serde::Serialize;
use std::time::Instant;

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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Slice {
    /// The plate centre, every size, thickness, sphere and support family.
    Centre,
    /// The scene's own support sets at its transient points, the scene's plate size.
    Points,
}

impl Slice {
    /// Its name in tables.
    pub fn key(self) -> &'static str {
        match self {
            Slice::Centre => "centre",
            Slice::Points => "points",
        }
    }
}

/// One case of the map.
#[derive(Debug, Clone, PartialEq, Serialize)]
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

/// The map's own error, from a sample of centre cases rerun with h and Δt halved.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Check {
    /// Cases rerun.
    pub cases: usize,
    /// Largest relative change of a transient force (first contact or whole impact).
    pub force: f64,
    /// Largest change of the force error among cases within 10 % of quasi-static, where the
    /// rule's 3 % is decided.
    pub near: f64,
    /// Largest change of the contact-time error.
    pub time: f64,
    /// Cases whose number of contacts changed.
    pub recount: usize,
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

/// The numbers the study's prose quotes, all from this run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Centre cases.
    pub centre_cases: usize,
    /// Cases at the scene's points.
    pub points_cases: usize,
    /// The closed-form rule on the centre cases.
    pub rule: Score,
    /// The rule at the scene's points.
    pub rule_points: Score,
    /// t_H/T₁ ≥ 0.2 on the centre cases.
    pub ratio: Score,
    /// Olsson's large mass on the centre cases.
    pub large: Score,
    /// Centre cases of small mass (wave controlled by Olsson).
    pub small_cases: usize,
    /// Of them within the rule's limit.
    pub small_fine: usize,
    /// Their largest relative stiffness λ.
    pub small_fine_lambda: f64,
    /// Centre cases with repeated contacts.
    pub repeated: usize,
    /// Their smallest loss factor ζ.
    pub repeated_min_zeta: f64,
    /// Centre cases the rule calls fast.
    pub fast_cases: usize,
    /// Of them within Christoforou and Yigit's bound.
    pub fast_bound_holds: usize,
    /// The lowest signed error over λ/(1 + λ) among resonant cases.
    pub band_low: f64,
    /// The highest error over λ/(1 + λ) among slow cases.
    pub slow_high: f64,
    /// The largest contact-time error among the cases the rule trusts.
    pub trusted_time: f64,
    /// The range of T₁,est/T₁.
    pub period_ratio_range: (f64, f64),
}

/// What the regime maps computed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RegimeData {
    /// The scene's first body, the map's sphere at its own radius.
    pub body: String,
    /// Its radius times [`RADIUS_FACTORS`], m.
    pub radii: Vec<f64>,
    /// The scene's first velocity, m/s.
    pub velocity: f64,
    /// Support families at the centre.
    pub families: usize,
    /// Elements along the longer side of the transient runs.
    pub mesh: usize,
    /// Steps per contact time.
    pub steps: f64,
    /// Threads the map ran on.
    pub threads: usize,
    /// Every case.
    pub rows: Vec<MapRow>,
    /// The map's own error.
    pub check: Check,
    /// Each criterion on the centre cases and at the scene's points.
    pub criteria: Vec<CriterionScore>,
    /// Olsson's three regimes against the measured error (centre cases).
    pub olsson: Vec<OlssonRow>,
    /// The rule point by point (the scene's points).
    pub points: Vec<PointScore>,
    /// The numbers the prose quotes.
    pub summary: Summary,
    /// Seconds the map took.
    pub map_secs: f64,
    /// Seconds the check took.
    pub check_secs: f64,
}

/// The numbers the prose quotes.
fn summary(rows: &[MapRow]) -> Summary {
    use score::score;
    let centre: Vec<&MapRow> = rows.iter().filter(|r| r.slice == Slice::Centre).collect();
    let small: Vec<&&MapRow> = centre.iter().filter(|r| r.mass_ratio < OLSSON_WAVE_CONTROLLED).collect();
    let repeated: Vec<&&MapRow> = centre.iter().filter(|r| r.measured.contacts > 1).collect();
    // Christoforou and Yigit's bound where ζ < 1 and the contact is fast: how often it holds.
    let fast: Vec<&&MapRow> = centre.iter().filter(|r| r.rule.speed() == ContactSpeed::Fast).collect();
    let share = |r: &MapRow| r.rule.parameters.relative_stiffness / (1.0 + r.rule.parameters.relative_stiffness);
    Summary {
        centre_cases: centre.len(),
        points_cases: rows.len() - centre.len(),
        rule: score(centre.iter().copied(), |r| r.rule.trusts()),
        rule_points: score(rows.iter().filter(|r| r.slice == Slice::Points), |r| r.rule.trusts()),
        ratio: score(centre.iter().copied(), |r| r.period_ratio() >= QUASI_STATIC_MIN_RATIO),
        large: score(centre.iter().copied(), |r| r.mass_ratio > OLSSON_QUASI_STATIC),
        small_cases: small.len(),
        small_fine: small.iter().filter(|r| r.quasi_static()).count(),
        small_fine_lambda: small
            .iter()
            .filter(|r| r.quasi_static())
            .map(|r| r.rule.parameters.relative_stiffness)
            .fold(0.0f64, f64::max),
        repeated: repeated.len(),
        repeated_min_zeta: repeated.iter().map(|r| r.rule.parameters.loss_factor).fold(f64::INFINITY, f64::min),
        fast_cases: fast.len(),
        fast_bound_holds: fast.iter().filter(|r| r.error() <= r.rule.parameters.error_bound() + 1e-12).count(),
        band_low: centre
            .iter()
            .filter(|r| r.rule.speed() == ContactSpeed::Resonant && r.rule.period_ratio.is_some())
            .map(|r| r.signed_error() / share(r))
            .fold(0.0f64, f64::min),
        slow_high: centre
            .iter()
            .filter(|r| r.rule.speed() == ContactSpeed::Slow)
            .map(|r| r.error() / share(r))
            .fold(0.0f64, f64::max),
        trusted_time: rows.iter().filter(|r| r.rule.trusts()).filter_map(|r| r.time_error()).fold(0.0f64, f64::max),
        period_ratio_range: rows
            .iter()
            .filter_map(|r| r.period_estimate.map(|t| t / r.period))
            .fold((f64::INFINITY, 0.0f64), |(a, b), q| (a.min(q), b.max(q))),
    }
}

/// The maps of `scene`: every centre case and every case at the scene's points, the
/// discretisation check, and the criteria scored on them.
pub fn compute(scene: &Scene, settings: &Settings, progress: &dyn Progress) -> Result<RegimeData, Failure> {
    let t0 = Instant::now();
    let families = families(scene);
    let mut jobs: Vec<run::Job> = Vec::new();
    for scale in SCALES {
        for f in THICKNESS_FACTORS {
            jobs.push(run::Job { slice: Slice::Centre, scale, thickness_factor: f });
        }
    }
    for f in THICKNESS_FACTORS {
        jobs.push(run::Job { slice: Slice::Points, scale: 1.0, thickness_factor: f });
    }
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).min(4);
    progress.start(jobs.len(), "regime-map plates");
    let rows = run::run_jobs(scene, settings, &jobs, &families, threads, progress)?;
    progress.finish();
    let map_secs = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let check = run::discretisation_check(scene, &rows, &families)?;
    let check_secs = t1.elapsed().as_secs_f64();
    let body = scene.bodies.first().ok_or("the scene has no body")?;
    Ok(RegimeData {
        body: body.name.clone(),
        radii: RADIUS_FACTORS.iter().map(|f| body.radius() * f).collect(),
        velocity: scene.velocities.first().copied().unwrap_or(f64::NAN),
        families: families.len(),
        mesh: MAP_MESH,
        steps: MAP_STEPS,
        threads,
        criteria: score::criteria_scores(&rows),
        olsson: score::olsson_rows(&rows),
        points: score::point_scores(&rows),
        summary: summary(&rows),
        rows,
        check,
        map_secs,
        check_secs,
    })
}
