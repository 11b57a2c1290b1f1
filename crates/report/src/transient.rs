//! `impact dynamic` and the transient section of the main report.

use crate::present::plot::{line_plot, Axis, Plot, Scale, Series};
use crate::present::table::{sig, Cell, Table};
use analytic::{respond, Condition, DruckerPrager, Method};
use coupled::discretisation::{mesh_for, plate_properties};
use coupled::plan::impact_of;
use coupled::regimes::{mass_ratio, OlssonRegime, RuleInputs};
use coupled::transient::{
    law::Flores, simulate, zener, ContactLaw, Discretisation, Estimated, Ladder, LawKind, Outcome, Sample, Striker,
    TransientSettings, HERTZ_TIME,
};
use coupled::PlateModel;
use coupled::{BeamModel, ComplianceModel, Validity};
use output::Artifacts;
use plate_fem::dynamics::{fundamental_frequency, Newmark};
use plate_fem::{Mesh, Model, PlateProperties, Supports};
use scene::{Analysis, Scene, SceneSource, SupportSet};
use std::time::Instant;

use crate::template::{and_list, count_words, render};
use crate::Failure;
use studies::progress::Progress;

// The report's prose, one template per section (verification and the size map are written
// only when the scene asks for them; the summary repeats a line per body).
const HEAD: &str = include_str!("templates/transient/head.md");
const VERIFICATION: &str = include_str!("templates/transient/verification.md");
const NOT_VERIFIED: &str = include_str!("templates/transient/not-verified.md");
const COMPARISON: &str = include_str!("templates/transient/comparison.md");
const HISTORY: &str = include_str!("templates/transient/history.md");
const SUMMARY: &str = include_str!("templates/transient/summary.md");
const SUMMARY_BODY: &str = include_str!("templates/transient/summary-body.md");
const SIZE_MAP: &str = include_str!("templates/transient/size-map.md");
const CONTACTS: &str = include_str!("templates/transient/contacts.md");
const DISCRETISATION: &str = include_str!("templates/transient/discretisation.md");
const DISC_FIXED: &str = include_str!("templates/transient/discretisation-fixed.md");
const DISC_TOLERANCE: &str = include_str!("templates/transient/discretisation-tolerance.md");
const REGIMES: &str = include_str!("templates/transient/regimes.md");
const LAWS: &str = include_str!("templates/transient/laws.md");
const LAWS_NOT_ASKED: &str = include_str!("templates/transient/laws-not-asked.md");
const LAWS_END_LEFT: &str = include_str!("templates/transient/laws-end-left.md");
const LAWS_END_OPEN: &str = include_str!("templates/transient/laws-end-open.md");
const FINDING_CONTACTS: &str = include_str!("templates/transient/finding-contacts.md");
const FINDING_SINGLE: &str = include_str!("templates/transient/finding-single.md");
const FINDING_UNFINISHED: &str = include_str!("templates/transient/finding-unfinished.md");
const FINDING_ELASTIC: &str = include_str!("templates/transient/finding-elastic.md");
const FINDING_ERRORS: &str = include_str!("templates/transient/finding-errors.md");
const FINDING_ERRORS_UNMET: &str = include_str!("templates/transient/finding-errors-unmet.md");
const FINDING_REGIMES: &str = include_str!("templates/transient/finding-regimes.md");

/// Impact velocity of the verification runs, m/s.
const VERIFICATION_VELOCITY: f64 = 0.008;
/// The Hertz time constant as some texts round it (design.md among them).
const ROUNDED_HERTZ_TIME: f64 = 3.2145;
/// The restitutions from which on the Flores deviation is summarised as a multiple of 1 - e.
const FLORES_NEAR_ONE: f64 = 0.8;

/// Steps per Hertz contact time (force error ~4e-5, energy error ~5e-5: see the report).
pub const STEPS_PER_CONTACT: f64 = 200.0;
/// Elements along the longer side for the transient runs (the convergence table shows the
/// mesh error of P_max there).
pub const DYNAMIC_MESH: usize = 20;
const METHOD: Method = Method::Bracketed { tolerance: 1e-13, max_iterations: 200 };

pub use coupled::plan::scene_striker as striker;

/// An optional number as a cell: empty where there is none (no separation in the window).
fn opt(v: Option<f64>) -> Cell {
    v.map_or(Cell::Empty, Cell::Num)
}

/// One transient run on `model`.
pub fn transient(
    model: &Model,
    supports: Supports,
    s: &Striker,
    x: f64,
    z: f64,
    steps: f64,
) -> Result<Outcome, Failure> {
    let dt = s.hertz_time() / steps;
    let mut nm = Newmark::new(model, supports, dt, x, z)?;
    Ok(simulate(s, Some(&mut nm), dt, 20.0 * s.hertz_time()))
}

/// One case of the transient comparison: a condition, body, point and velocity.
#[derive(Debug, Clone, PartialEq)]
pub struct TransientCase {
    pub condition: String,
    pub body: String,
    /// The impact point, m.
    pub x: f64,
    pub z: f64,
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// The fundamental period T₁ of the supported plate, s.
    pub period: f64,
    /// The law's force at maximum compression of the transient run, at the instant δ̇ = 0 on
    /// the integrator's interpolant (the paper's P_max), N.
    pub force_at_max_compression: f64,
    /// P_max of the quasi-static balance with the plate's compliance, N.
    pub quasi_static_plate_force: f64,
    /// δ_max of that balance, m.
    pub quasi_static_plate_compression: f64,
    /// The plate's static compliance there (springs included), m/N.
    pub quasi_static_plate_compliance: f64,
    /// P_max of the quasi-static balance with the beam's compliance, N; `None` for a
    /// support set the beam does not describe.
    pub quasi_static_beam_force: Option<f64>,
    /// Plate energy (kinetic and strain) at maximum compression, over E₀.
    pub plate_energy: f64,
    /// The plate energy of the quasi-static plate balance, over E₀.
    pub quasi_static_plate_energy: f64,
    /// Sphere kinetic energy left at maximum compression, over E₀.
    pub sphere_energy_left: f64,
    /// δ_max over the Drucker-Prager yield compression δ_my of eq. 51.
    pub yield_ratio: f64,
    /// The closed-form regime rule's inputs, with the plate's compliance.
    pub rule: RuleInputs,
    /// M_i/M_p.
    pub mass_ratio: f64,
    /// The sphere's mass, kg.
    pub sphere_mass: f64,
    /// The Hertz contact time on a rigid target, s.
    pub hertz_time: f64,
    /// The values at their instants, their error estimates and the whole run (every contact).
    pub estimate: Estimated,
    /// Wall-clock time of the case (its discretisation's choice and estimate), s.
    pub seconds: f64,
    /// The case's validity status, as `impact solve --model transient` gives it for the same
    /// case (elastic range, re-contact, impact finished in its window, discretisation).
    pub validity: Validity,
}

impl TransientCase {
    /// The whole run.
    pub fn outcome(&self) -> &Outcome {
        &self.estimate.outcome
    }

    /// The first contact's duration on the interpolant, s.
    pub fn contact_time(&self) -> Option<f64> {
        self.outcome().contacts.first().map(|c| c.duration)
    }

    /// t_c/T₁; `None` if the sphere had not separated at the end of the run.
    pub fn contact_ratio(&self) -> Option<f64> {
        self.contact_time().map(|t| t / self.period)
    }

    /// The error of the quasi-static plate's P_max: the transient force at maximum
    /// compression / QS - 1.
    pub fn force_error(&self) -> f64 {
        self.force_at_max_compression / self.quasi_static_plate_force - 1.0
    }
}

/// Transient against quasi-static at the given points, for every condition, body and
/// velocity of the scene, each case on the discretisation the scene asks for
/// ([`Scene::transient_discretisation`]) with its error estimate.
pub fn comparison(
    scene: &Scene,
    points: &[(f64, f64)],
    progress: &dyn Progress,
) -> Result<Vec<TransientCase>, Failure> {
    let disc = scene.transient_discretisation;
    let mut ladder = Ladder::new(&scene.plate, disc.start())?;
    let qs = PlateModel::compute(
        &scene.plate,
        &scene.conditions,
        points,
        studies::settings::BASE_MESH,
        studies::settings::LEVELS,
    )?;
    let beam = BeamModel { plate: &scene.plate };
    let mut cases = Vec::new();
    let total = scene.conditions.len() * scene.bodies.len() * scene.velocities.len() * points.len();
    progress.start(total, "transient cases");
    for cond in &scene.conditions {
        let t1 = ladder.levels(0)?.0.fundamental_period(&cond.supports)?;
        for body in &scene.bodies {
            let d_my =
                DruckerPrager::of(body).yield_compression(body.radius(), impact_of(scene, body, 1.0).contact_stiffness);
            for &v in &scene.velocities {
                let s = striker(scene, body, v);
                let imp = impact_of(scene, body, v);
                for &(x, z) in points {
                    let t0 = Instant::now();
                    let e = disc.estimate(&mut ladder, cond, &s, (x, z))?;
                    let seconds = t0.elapsed().as_secs_f64();
                    let c = qs.compliance(cond, x, z)?;
                    let rp = respond(&imp, &c.compliance, METHOD)?;
                    // The beam describes only the paper's Con 1-3; for any other set it has
                    // no value to show.
                    let rb = match beam.compliance(cond, x, z) {
                        Ok(c) => Some(respond(&imp, &c.compliance, METHOD)?.contact_force),
                        Err(coupled::ModelError::NotApplicable { .. }) => None,
                        Err(e) => return Err(e.into()),
                    };
                    let e0 = 0.5 * s.mass * v * v;
                    let m = e.outcome.at_max_compression_interpolated;
                    let dt = s.hertz_time() / e.steps_per_contact;
                    let validity =
                        coupled::plan::transient_values(scene, cond, body, &e.outcome, &s, dt, (x, z), Some(&e))
                            .validity;
                    cases.push(TransientCase {
                        condition: cond.name.clone(),
                        body: body.name.clone(),
                        x,
                        z,
                        velocity: v,
                        period: t1,
                        force_at_max_compression: e.values.force_at_max_compression,
                        quasi_static_plate_force: rp.contact_force,
                        quasi_static_plate_compression: rp.compression,
                        quasi_static_plate_compliance: c.compliance.total(),
                        quasi_static_beam_force: rb,
                        plate_energy: (m.plate_kinetic + m.plate_strain) / e0,
                        quasi_static_plate_energy: rp.plate_ratio,
                        sphere_energy_left: m.sphere_kinetic / e0,
                        yield_ratio: e.values.compression / d_my,
                        rule: RuleInputs::of(&s, &scene.plate, cond, c.compliance.total()),
                        mass_ratio: mass_ratio(s.mass, &scene.plate),
                        sphere_mass: s.mass,
                        hertz_time: s.hertz_time(),
                        estimate: e,
                        seconds,
                        validity,
                    });
                    progress.advance(1);
                }
            }
        }
    }
    progress.finish();
    Ok(cases)
}

/// "valid", or the flags of the criteria a case fails, joined by "; ".
fn flags(v: &Validity) -> String {
    let f = v.flags();
    if f.is_empty() {
        "valid".into()
    } else {
        f.join("; ")
    }
}

/// The median of `values` (the mean of the two middle ones for an even count); None for none.
pub fn median(values: &[f64]) -> Option<f64> {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| !x.is_nan()).collect();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(v[n / 2]),
        _ => Some(0.5 * (v[n / 2 - 1] + v[n / 2])),
    }
}

/// The largest force of every contact of a run: the first contact's peak on the interpolant,
/// the later ones' sampled at the steps.
pub fn peak_over_contacts(o: &Outcome) -> f64 {
    o.contacts
        .iter()
        .chain(&o.unfinished_contact)
        .skip(1)
        .map(|c| c.peak_force)
        .fold(o.force_max_interpolated, f64::max)
}

/// A value and its estimated error as two cells (empty where there is none).
fn with_error(v: f64, e: f64) -> [Cell; 2] {
    let cell = |x: f64| if x.is_finite() { Cell::Num(x) } else { Cell::Empty };
    [cell(v), if v.is_finite() { cell(e) } else { Cell::Empty }]
}

/// The impact point, shown in mm; in the CSV as x_m and z_m.
fn point(c: &TransientCase) -> Cell {
    Cell::Pair { x: c.x, z: c.z, scale: 1e3, decimals: 1 }
}

/// The CSV names of the columns every case table shares.
fn case_columns(t: Table) -> Table {
    t.csv_name(POINT, &["x_m", "z_m"])
}

const POINT: &str = "point (x, z) in mm";

/// The transient comparison as the report prints it: every value at its instant, with its
/// error estimate.
pub fn comparison_table(cases: &[TransientCase]) -> Table {
    let mut t = Table::new(
        "",
        &[
            "condition",
            "body",
            "x (mm)",
            "z (mm)",
            "v (m/s)",
            "t_c (ms)",
            "t_c error (ms)",
            "t_c/T₁",
            "peak force, transient (N)",
            "peak force error (N)",
            "P_max at δ_max, transient (N)",
            "P_max error (N)",
            "P_max quasi-static plate (N)",
            "P_max quasi-static beam (N)",
            "P_max transient/QS plate - 1",
            "δ_max transient/QS plate - 1",
            "apparent e",
            "apparent e error",
            "plate energy at δ_max (transient)",
            "plate energy (QS plate)",
            "sphere KE left at δ_max",
            "validity",
        ],
    );
    for c in cases {
        let (q, err) = (&c.estimate.values, &c.estimate.error);
        let mut row: Vec<Cell> =
            vec![c.condition.clone().into(), c.body.clone().into(), (c.x * 1e3).into(), (c.z * 1e3).into()];
        row.push(c.velocity.into());
        row.extend(with_error(q.contact_time * 1e3, err.contact_time * 1e3));
        row.push(opt(c.contact_ratio()));
        row.extend(with_error(q.peak_force, err.peak_force));
        row.extend(with_error(q.force_at_max_compression, err.force_at_max_compression));
        row.push(c.quasi_static_plate_force.into());
        row.push(c.quasi_static_beam_force.map_or(Cell::Empty, Cell::Num));
        row.push(c.force_error().into());
        row.push((q.compression / c.quasi_static_plate_compression - 1.0).into());
        row.extend(with_error(q.restitution, err.restitution));
        row.extend([c.plate_energy.into(), c.quasi_static_plate_energy.into(), c.sphere_energy_left.into()]);
        row.push(flags(&c.validity).into());
        t.push(row);
    }
    t
}

/// The whole impact of each case: every contact, the total impulse and the final rebound.
pub fn contacts_table(cases: &[TransientCase]) -> Table {
    let mut t = Table::new(
        "",
        &[
            "condition",
            "body",
            POINT,
            "v (m/s)",
            "contacts",
            "each contact: start (ms), duration (ms), peak force (N)",
            "total impulse (N·s)",
            "impulse / m v₀",
            "final velocity (m/s)",
            "final rebound / v₀",
            "left for good at (ms)",
        ],
    );
    for c in cases {
        let o = c.outcome();
        let each: Vec<String> = o
            .contacts
            .iter()
            .chain(&o.unfinished_contact)
            .map(|k| format!("{:.4} / {:.4} / {}", k.start * 1e3, k.duration * 1e3, sig(k.peak_force, 4)))
            .collect();
        let momentum = c.sphere_mass * c.velocity;
        t.push(vec![
            c.condition.clone().into(),
            c.body.clone().into(),
            point(c),
            c.velocity.into(),
            Cell::Int((o.contacts.len() + usize::from(o.unfinished_contact.is_some())) as u64),
            each.join("; ").into(),
            o.total_impulse.into(),
            (o.total_impulse / momentum).into(),
            o.final_velocity.into(),
            (-o.final_velocity / c.velocity).into(),
            o.left_at.map_or(Cell::Text("window ended".into()), |t| Cell::Num(t * 1e3)),
        ]);
    }
    t
}
/// Every contact of every case, one row each (the CSV beside the contacts table).
pub fn contact_rows(cases: &[TransientCase]) -> Table {
    let mut t = Table::new(
        "",
        &[
            "condition",
            "body",
            "x (m)",
            "z (m)",
            "v (m/s)",
            "contact",
            "start (s)",
            "duration (s)",
            "peak force (N)",
            "impulse (N·s)",
            "velocity after (m/s)",
            "finished",
        ],
    );
    for c in cases {
        let o = c.outcome();
        let all = o.contacts.iter().map(|k| (k, true)).chain(o.unfinished_contact.iter().map(|k| (k, false)));
        for (i, (k, done)) in all.enumerate() {
            t.push(vec![
                c.condition.clone().into(),
                c.body.clone().into(),
                c.x.into(),
                c.z.into(),
                c.velocity.into(),
                Cell::Int(i as u64 + 1),
                k.start.into(),
                k.duration.into(),
                k.peak_force.into(),
                k.impulse.into(),
                k.rebound_velocity.into(),
                done.into(),
            ]);
        }
    }
    t
}

/// The discretisation each case got, its error estimate and its cost.
pub fn discretisation_table(cases: &[TransientCase]) -> Table {
    let mut t = Table::new(
        "",
        &[
            "condition",
            "body",
            POINT,
            "v (m/s)",
            "elements",
            "steps per t_H",
            "estimate on P_max and t_c (relative)",
            "time part",
            "mesh part",
            "peak-force estimate (relative)",
            "tolerance met",
            "wall time (s)",
        ],
    );
    for c in cases {
        let e = &c.estimate;
        t.push(vec![
            c.condition.clone().into(),
            c.body.clone().into(),
            point(c),
            c.velocity.into(),
            Cell::Int(e.elements as u64),
            e.steps_per_contact.into(),
            e.relative_error().into(),
            e.time_error.relative_to(&e.values).into(),
            e.mesh_error.relative_to(&e.values).into(),
            e.error.relative_peak(&e.values).into(),
            match e.tolerance {
                Some(tol) if e.met_tolerance => format!("yes (≤ {})", sig(tol, 2)),
                Some(tol) => format!("no (> {}; budget reached)", sig(tol, 2)),
                None => "fixed settings".into(),
            }
            .into(),
            Cell::Sig(c.seconds, 3),
        ]);
    }
    case_columns(t).csv_name("tolerance met", &["tolerance_verdict"])
}

/// Each case's regime: the closed-form criteria, the validity status, and the measured
/// quasi-static error beside them.
pub fn regimes_table(cases: &[TransientCase]) -> Table {
    let mut t = Table::new(
        "",
        &[
            "condition",
            "body",
            POINT,
            "v (m/s)",
            "M_i/M_p (Olsson)",
            "lambda",
            "zeta",
            "C&Y bound B",
            "t_H/T₁ est",
            "rule: bound, verdict",
            "t_H/T₁ (FE) ≥ 0.2",
            "contacts",
            "δ_max/δ_my",
            "measured QS force error",
            "rule right",
        ],
    );
    for c in cases {
        let r = &c.rule;
        let trusted = r.trusts();
        let within = c.force_error().abs() <= coupled::regimes::RULE_LIMIT;
        let contacts = c.outcome().contacts.len() + usize::from(c.outcome().unfinished_contact.is_some());
        t.push(vec![
            c.condition.clone().into(),
            c.body.clone().into(),
            point(c),
            c.velocity.into(),
            Cell::Noted { value: c.mass_ratio, digits: 3, note: OlssonRegime::of(c.mass_ratio).key().into() },
            r.parameters.relative_stiffness.into(),
            r.parameters.loss_factor.into(),
            r.parameters.error_bound().into(),
            r.period_ratio.map_or(Cell::Empty, Cell::Num),
            Cell::Noted {
                value: r.error_bound(),
                digits: 3,
                note: (if trusted { "trusted" } else { "not quasi-static" }).into(),
            },
            (c.hertz_time / c.period >= coupled::validity::QUASI_STATIC_MIN_RATIO).into(),
            Cell::Int(contacts as u64),
            if c.yield_ratio > 1.0 {
                Cell::Noted { value: c.yield_ratio, digits: 3, note: "beyond elastic range".into() }
            } else {
                Cell::Sig(c.yield_ratio, 3)
            },
            c.force_error().into(),
            match (trusted, within) {
                (true, true) | (false, false) => "yes",
                (false, true) => "conservative",
                (true, false) => "NO",
            }
            .into(),
        ]);
    }
    case_columns(t)
        .csv_name("M_i/M_p (Olsson)", &["M_i_per_M_p", "Olsson_regime"])
        .csv_name("rule: bound, verdict", &["rule_bound", "rule_verdict"])
        .csv_name("rule right", &["rule_right_verdict"])
}

/// Multiples of the rigid-target yield velocity at which the contact laws are compared: one
/// below yield, and 10, 100 and 200 times above (2 m/s for the paper's coal).
pub const LAW_RATIOS: [f64; 4] = [0.5, 10.0, 100.0, 200.0];

/// One contact law at one velocity.
#[derive(Debug, Clone)]
pub struct LawCase {
    pub law: LawKind,
    /// v over the rigid-target yield velocity.
    pub ratio: f64,
    pub velocity: f64,
    /// δ_my of eq. 51, m.
    pub yield_compression: f64,
    /// The sphere's E₀, J.
    pub energy: f64,
    /// Values, errors and the whole run.
    pub estimate: Estimated,
    /// Thornton's permanent compression after the impact, m (zero for the elastic laws).
    pub permanent_set: f64,
}

/// Every law of the registry ([`LawKind::ALL`]: Hertz, Flores and Thornton) side by side on
/// the scene's plate: the first body at the centre under the first condition, at
/// [`LAW_RATIOS`] times its rigid-target yield velocity.
pub fn laws(scene: &Scene, progress: &dyn Progress) -> Result<Vec<LawCase>, Failure> {
    let body = scene.bodies.first().ok_or("no body")?;
    let cond = scene.conditions.first().ok_or("no condition")?;
    let (x, z) = (scene.plate.length() / 2.0, scene.plate.width() / 2.0);
    let k = impact_of(scene, body, 1.0).contact_stiffness;
    let d_my = DruckerPrager::of(body).yield_compression(body.radius(), k);
    let v_y = analytic::yield_velocity(body, &impact_of(scene, body, 1.0), 0.0, d_my);
    let disc = scene.transient_discretisation;
    let mut ladder = Ladder::new(&scene.plate, disc.start())?;
    let mut out = Vec::new();
    progress.start(LawKind::ALL.len() * LAW_RATIOS.len(), "contact-law runs");
    for &law in LawKind::ALL {
        for ratio in LAW_RATIOS {
            let v = ratio * v_y;
            let s = Striker { law: law.law_for(body), ..striker(scene, body, v) };
            let e = disc.estimate(&mut ladder, cond, &s, (x, z))?;
            let deepest =
                e.outcome.history.iter().chain(&e.outcome.later_history).map(|h| h.compression).fold(0.0, f64::max);
            out.push(LawCase {
                law,
                ratio,
                velocity: v,
                yield_compression: d_my,
                energy: 0.5 * s.mass * v * v,
                permanent_set: s.permanent_set(deepest),
                estimate: e,
            });
            progress.advance(1);
        }
    }
    progress.finish();
    Ok(out)
}

/// How a run ended: the sphere provably gone, or the window ended with the sphere still
/// approaching the plate, in contact, or moving away but within the plate's reach.
pub fn end_state(o: &Outcome) -> &'static str {
    match (o.left_at, o.unfinished_contact, o.final_velocity > 0.0) {
        (Some(_), _, _) => "sphere left",
        (None, Some(_), _) => "window ended in contact",
        (None, None, true) => "window ended, sphere still approaching",
        (None, None, false) => "window ended, sphere within the plate's reach",
    }
}

/// The laws' forces and energy split: at maximum compression, and at the end of the run
/// (after the impact where the sphere has provably left, else at the end of the window).
pub fn laws_table(cases: &[LawCase]) -> Table {
    let mut t = Table::new(
        "",
        &[
            "law",
            "v/v_y",
            "v (m/s)",
            "peak force, first contact (N)",
            "peak force error (N)",
            "peak force, every contact (N)",
            "P_max at δ_max (N)",
            "P_max error (N)",
            "δ_max/δ_my",
            "permanent set δ_p/δ_max",
            "apparent e",
            "apparent e error",
            "at δ_max: rock elastic",
            "at δ_max: dissipated",
            "at δ_max: plate",
            "at δ_max: springs",
            "at δ_max: sphere KE",
            "at the end: sphere KE",
            "at the end: dissipated",
            "at the end: in the plate",
            "contacts",
            "the end",
        ],
    );
    for c in cases {
        let (q, err) = (&c.estimate.values, &c.estimate.error);
        let o = &c.estimate.outcome;
        let m = o.at_max_compression_interpolated;
        let end = o.later_history.last().or(o.history.last()).copied().unwrap_or(m);
        let e0 = c.energy;
        let mut row: Vec<Cell> = vec![c.law.key().into(), c.ratio.into(), c.velocity.into()];
        row.extend(with_error(q.peak_force, err.peak_force));
        row.push(peak_over_contacts(o).into());
        row.extend(with_error(q.force_at_max_compression, err.force_at_max_compression));
        row.extend([(q.compression / c.yield_compression).into(), (c.permanent_set / q.compression).into()]);
        row.extend(with_error(q.restitution, err.restitution));
        row.extend([
            (m.contact / e0).into(),
            (m.dissipated / e0).into(),
            ((m.plate_kinetic + m.plate_strain) / e0).into(),
            (m.springs / e0).into(),
            (m.sphere_kinetic / e0).into(),
            (end.sphere_kinetic / e0).into(),
            (end.dissipated / e0).into(),
            ((end.plate_kinetic + end.plate_strain + end.springs) / e0).into(),
            Cell::Int((o.contacts.len() + usize::from(o.unfinished_contact.is_some())) as u64),
            end_state(o).into(),
        ]);
        t.push(row);
    }
    t
}

/// Quasi-static error over plate size and thickness (Con 1, centre, first body, first
/// velocity): t_c/T₁ and transient P_max against the quasi-static plate.
pub fn size_map(scene: &Scene) -> Result<(Table, Vec<Series>), Failure> {
    let body = scene.bodies.first().ok_or("no body")?;
    let v = scene.velocities.first().copied().unwrap_or(0.008);
    let s = striker(scene, body, v);
    let imp = impact_of(scene, body, v);
    let base = plate_properties(&scene.plate);
    let mut t = Table::new(
        "",
        &[
            "size (x L, B)",
            "h (mm)",
            "T₁ (ms)",
            "t_c (ms)",
            "t_c/T₁",
            "P_max at δ_max, transient (N)",
            "P_max QS plate (N)",
            "transient/QS - 1",
        ],
    );
    let mut series = Vec::new();
    for scale in [0.5, 1.0, 2.0] {
        let mut pts = Vec::new();
        for h in [2e-3, 4e-3, 8e-3, 16e-3, 32e-3] {
            let props =
                PlateProperties { length: base.length * scale, width: base.width * scale, thickness: h, ..base };
            let plate = analytic::Plate::new(props.length, props.width, h, props.density, scene.plate.material())?;
            let sc = Scene { plate, ..scene.clone() };
            let model = Model::new(props, mesh_for(&props, DYNAMIC_MESH)?)?;
            let (w1, _) = fundamental_frequency(&model, &Supports::con1(), 200)?;
            let t1 = 2.0 * std::f64::consts::PI / w1;
            let (x, z) = (props.length / 2.0, props.width / 2.0);
            let o = transient(&model, Supports::con1(), &s, x, z, STEPS_PER_CONTACT)?;
            let cond = SupportSet::preset("Con 1", Condition::BothFixed);
            let qs = PlateModel::compute(
                &sc.plate,
                std::slice::from_ref(&cond),
                &[(x, z)],
                studies::settings::BASE_MESH,
                studies::settings::LEVELS,
            )?;
            let rp = respond(&imp, &qs.compliance(&cond, x, z)?.compliance, METHOD)?;
            let p_at_max = s.force_at_max_compression(o.compression_max_interpolated);
            let err = p_at_max / rp.contact_force - 1.0;
            let contact_time = o.contacts.first().map(|c| c.duration);
            t.push(vec![
                scale.into(),
                (h * 1e3).into(),
                (t1 * 1e3).into(),
                opt(contact_time.map(|t| t * 1e3)),
                opt(contact_time.map(|t| t / t1)),
                p_at_max.into(),
                rp.contact_force.into(),
                err.into(),
            ]);
            if let Some(ct) = contact_time {
                pts.push((ct / t1, 1.0 + err));
            }
        }
        series.push(Series::new(format!("{scale} x the paper's L and B"), pts));
    }
    Ok((t, series))
}

/// The contact force histories of the first support set, body and velocity at every
/// transient point, each with its quasi-static plate P_max (dashed, same colour), beside the
/// Hertz history of the same sphere on a rigid target (the stiff limit).
fn history_figure(scene: &Scene, cases: &[TransientCase]) -> Plot {
    let mut plot =
        Plot::new("Contact force: transient against quasi-static", Axis::linear("t (ms)"), Axis::linear("P (N)"));
    let Some(first) = cases.first() else { return plot };
    let same =
        |c: &&TransientCase| c.condition == first.condition && c.body == first.body && c.velocity == first.velocity;
    let mut t_end: f64 = 0.0;
    for c in cases.iter().filter(same) {
        let h = &c.outcome().history;
        t_end = t_end.max(h.last().map_or(0.0, |s| s.t));
        plot = plot.with(Series::new(
            format!("transient at ({:.0}, {:.0}) mm", c.x * 1e3, c.z * 1e3),
            h.iter().map(|s| (s.t * 1e3, s.force)).collect(),
        ));
        let t_max = c.outcome().time_of_max_compression * 1e3;
        plot = plot.with(Series::level(
            "its quasi-static plate P_max",
            vec![(0.0, c.quasi_static_plate_force), (t_max, c.quasi_static_plate_force)],
        ));
    }
    if let Some(body) = scene.bodies.iter().find(|b| b.name == first.body) {
        let s = striker(scene, body, first.velocity);
        let hertz = Striker { restitution: 1.0, law: ContactLaw::Flores(Flores), ..s };
        let tc = hertz.hertz_time();
        let o = simulate(&hertz, None, tc / STEPS_PER_CONTACT, 1.5 * tc);
        plot =
            plot.with(Series::guide("Hertz, rigid target", o.history.iter().map(|s| (s.t * 1e3, s.force)).collect()));
    }
    plot.note(format!(
        "{}, {} at {} m/s. Dashed: the quasi-static plate's P_max of the curve above it, drawn up to the transient maximum compression.",
        first.condition, first.body, first.velocity
    ))
}

/// Transient against quasi-static P_max (Kδ_max^{3/2}) over t_c/T₁: the size map's plates
/// (lines, one per plate size, thickness varying along each) and the scene's own cases
/// (points), with the quasi-static criterion t_c/T₁ = 0.2 and the ratio 1 as guides.
fn ratio_figure(size_map: &[Series], cases: &[TransientCase]) -> Plot {
    let mut plot = Plot::new(
        "Transient over quasi-static force against t_c/T₁",
        Axis::log("t_c / T₁"),
        Axis::log("P_max transient / quasi-static plate"),
    );
    let mut all: Vec<(f64, f64)> = Vec::new();
    for s in size_map {
        all.extend(s.points.iter().copied());
        plot = plot.with(Series::new(format!("size map: {} (h = 2 to 32 mm)", s.name), s.points.clone()));
    }
    let mut bodies: Vec<&str> = Vec::new();
    for c in cases {
        if !bodies.contains(&c.body.as_str()) {
            bodies.push(&c.body);
        }
    }
    for b in bodies {
        let pts: Vec<(f64, f64)> = cases
            .iter()
            .filter(|c| c.body == b)
            .filter_map(|c| c.contact_ratio().map(|r| (r, 1.0 + c.force_error())))
            .collect();
        all.extend(pts.iter().copied());
        plot = plot.with(Series::points(format!("this scene: {b}"), pts));
    }
    let (xlo, xhi) = all.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let (ylo, yhi) = all.iter().fold((1.0f64, 1.0f64), |(a, b), p| (a.min(p.1), b.max(p.1)));
    let limit = coupled::validity::QUASI_STATIC_MIN_RATIO;
    if xlo.is_finite() {
        plot = plot
            .with(Series::guide("ratio 1 (quasi-static exact)", vec![(xlo.min(limit), 1.0), (xhi.max(limit), 1.0)]));
        plot = plot.with(Series::guide(
            format!("t_c/T₁ = {limit} (quasi-static criterion)"),
            vec![(limit, ylo), (limit, yhi)],
        ));
    }
    plot.note("Thickness varies along each size-map line; a thick plate is nearly rigid for the sphere, so its ratio returns to 1 whatever t_c/T₁.")
}

/// The size map's findings in numbers from this run: the largest error where the contact is
/// slow against the plate (t_c/T₁ ≥ 0.2) and the error at the fastest contact.
fn size_map_findings(series: &[Series]) -> String {
    let pts: Vec<(f64, f64)> = series.iter().flat_map(|s| s.points.iter().copied()).collect();
    let slow = pts
        .iter()
        .filter(|p| p.0 >= coupled::validity::QUASI_STATIC_MIN_RATIO)
        .map(|p| (p.1 - 1.0).abs())
        .fold(None, |m: Option<f64>, e| Some(m.map_or(e, |m| m.max(e))));
    let fastest = pts.iter().copied().min_by(|a, b| a.0.total_cmp(&b.0));
    let mut out = String::from("Measured in this run:");
    match slow {
        Some(e) => out.push_str(&format!(
            " where t_c/T₁ ≥ {} the quasi-static force is within {:.1} %;",
            coupled::validity::QUASI_STATIC_MIN_RATIO,
            100.0 * e
        )),
        None => out
            .push_str(&format!(" no plate of the map reaches t_c/T₁ ≥ {};", coupled::validity::QUASI_STATIC_MIN_RATIO)),
    }
    if let Some((r, ratio)) = fastest {
        out.push_str(&format!(
            " at the fastest contact, t_c/T₁ = {r:.3}, it is off by {:.0} %.",
            100.0 * (ratio - 1.0).abs()
        ));
    }
    out
}

/// The verification tables: Hertz, Flores restitution, energy, Zener, convergence.
fn verification(scene: &Scene) -> Result<String, Failure> {
    let coal = scene.bodies.first().ok_or("no body")?;
    let imp = impact_of(scene, coal, VERIFICATION_VELOCITY);
    let elastic = Striker {
        k: imp.contact_stiffness,
        restitution: 1.0,
        mass: imp.mass,
        velocity: VERIFICATION_VELOCITY,
        law: ContactLaw::Flores(Flores),
    };
    let tc = elastic.hertz_time();
    let mut h =
        Table::new("", &["steps per t_c", "P_max/Hertz - 1", "t_c/Hertz - 1", "apparent e - 1", "max energy error"]);
    let mut force_errors = Vec::new();
    for n in [50.0, 100.0, 200.0, 400.0] {
        let o = simulate(&elastic, None, tc / n, 3.0 * tc);
        force_errors.push(o.force_max / elastic.hertz_force() - 1.0);
        h.push(vec![
            n.into(),
            (o.force_max / elastic.hertz_force() - 1.0).into(),
            opt(o.contact_time.map(|t| t / tc - 1.0)),
            opt(o.apparent_restitution.map(|e| e - 1.0)),
            o.max_energy_error.into(),
        ]);
    }
    let mut f = Table::new(
        "",
        &["e", "apparent restitution", "relative deviation", "δ_max / eq. 14 (C = 0) - 1", "peak force / Kδ_max^{3/2}"],
    );
    // The paper's e is the restitution of its scene, the default one.
    let paper_e = Scene::default_scene().restitution;
    let mut flores_slopes = Vec::new();
    let mut flores_paper = f64::NAN;
    for e in [0.99, 0.95, 0.9, 0.8, paper_e, 0.5] {
        let s = Striker { restitution: e, ..elastic };
        let o = simulate(&s, None, tc / 800.0, 3.0 * tc);
        let qs = (5.0 * e * s.mass * s.velocity.powi(2) / (4.0 * s.k)).powf(0.4);
        if let Some(a) = o.apparent_restitution {
            if e >= FLORES_NEAR_ONE {
                flores_slopes.push(-(a / e - 1.0) / (1.0 - e));
            }
            if e == paper_e {
                flores_paper = -(a / e - 1.0);
            }
        }
        f.push(vec![
            e.into(),
            opt(o.apparent_restitution),
            opt(o.apparent_restitution.map(|a| a / e - 1.0)),
            (o.compression_max / qs - 1.0).into(),
            (o.force_max / (s.k * o.compression_max.powf(1.5))).into(),
        ]);
    }

    let props = plate_properties(&scene.plate);
    let mut en =
        Table::new("", &["steps per t_c", "max abs(E - E₀)/E₀, e = 1, Con 2, centre", "P_max (N)", "run time (s)"]);
    let model = Model::new(props, mesh_for(&props, DYNAMIC_MESH)?)?;
    let mut p_ref = Vec::new();
    for n in [50.0, 100.0, 200.0, 400.0] {
        let t0 = Instant::now();
        let o = transient(&model, Supports::con2(5.11545e8), &elastic, props.length / 2.0, props.width / 2.0, n)?;
        en.push(vec![n.into(), o.max_energy_error.into(), o.force_max.into(), t0.elapsed().as_secs_f64().into()]);
        p_ref.push(o.force_max);
    }

    let mut mc =
        Table::new("", &["mesh", "DOFs", "P_max (N)", "rel. change to next finer", "t_c (ms)", "run time (s)"]);
    let mut rows = Vec::new();
    for n in [10, 20, 40, 80] {
        let t0 = Instant::now();
        let m = Model::new(props, mesh_for(&props, n)?)?;
        let o = transient(
            &m,
            Supports::con1(),
            &Striker { restitution: scene.restitution, ..elastic },
            props.length / 2.0,
            props.width / 2.0,
            STEPS_PER_CONTACT,
        )?;
        rows.push((
            format!("{} x {}", m.mesh().nx(), m.mesh().nz()),
            m.dofs(),
            o.force_max,
            o.contact_time,
            t0.elapsed().as_secs_f64(),
        ));
    }
    for (i, r) in rows.iter().enumerate() {
        let next = rows.get(i + 1).map_or(Cell::Empty, |n| Cell::Num((r.2 - n.2).abs() / n.2));
        mc.push(vec![r.0.clone().into(), r.1.into(), r.2.into(), next, opt(r.3.map(|t| t * 1e3)), r.4.into()]);
    }

    let thin = PlateProperties { length: 1.0, width: 1.0, thickness: 0.004, ..props };
    let fast = Striker { velocity: 1.0, ..elastic };
    let fast = Striker { k: impact_of(scene, coal, 1.0).contact_stiffness, ..fast };
    let zimp = 8.0 * (thin.rigidity() * thin.density * thin.thickness).sqrt();
    let (fz, tz) = zener(&fast, zimp, 20000);
    let tz = tz.ok_or("Zener's reference impact did not end within 100 Hertz times")?;
    let mut z = Table::new("", &["mesh", "P_max (N)", "P_max/Zener - 1", "t_c (ms)", "t_c/Zener - 1", "apparent e"]);
    for n in [16, 24, 32] {
        let m = Model::new(thin, Mesh::uniform(1.0, 1.0, n, n)?)?;
        let dt = tz / STEPS_PER_CONTACT;
        let mut nm = Newmark::new(&m, Supports::all_edges_simple(), dt, 0.5, 0.5)?;
        let o = simulate(&fast, Some(&mut nm), dt, 5.0 * tz);
        z.push(vec![
            format!("{n} x {n}").into(),
            o.force_max.into(),
            (o.force_max / fz - 1.0).into(),
            opt(o.contact_time.map(|t| t * 1e3)),
            opt(o.contact_time.map(|t| t / tz - 1.0)),
            opt(o.apparent_restitution),
        ]);
    }
    let halvings: Vec<String> = force_errors.windows(2).map(|w| format!("{:.1}x", w[0] / w[1])).collect();
    let (last, rest) = halvings.split_last().ok_or("no step ladder")?;
    let slope = flores_slopes.iter().sum::<f64>() / flores_slopes.len() as f64;
    Ok(render(
        "transient/verification.md",
        VERIFICATION,
        &[
            ("body", coal.name.clone()),
            ("e_elastic", elastic.restitution.to_string()),
            ("hertz_time", format!("{HERTZ_TIME:.5}")),
            ("hertz_time_4", format!("{HERTZ_TIME:.4}")),
            ("rounded_hertz_time", ROUNDED_HERTZ_TIME.to_string()),
            ("rounded_low", format!("{:.2}", 100.0 * (1.0 - ROUNDED_HERTZ_TIME / HERTZ_TIME))),
            ("halving_ratios", format!("{} and {last}", rest.join(", "))),
            ("hertz_table", h.to_markdown()),
            ("flores_slope", format!("{slope:.2}")),
            ("flores_paper", format!("{:.0}", 100.0 * flores_paper)),
            ("paper_e", paper_e.to_string()),
            ("flores_table", f.to_markdown()),
            ("steps", STEPS_PER_CONTACT.to_string()),
            ("energy_table", en.to_markdown()),
            ("velocity", elastic.velocity.to_string()),
            ("e_scene", scene.restitution.to_string()),
            ("mesh_table", mc.to_markdown()),
            ("zener_length", thin.length.to_string()),
            ("zener_width", thin.width.to_string()),
            ("zener_thickness", (thin.thickness * 1e3).to_string()),
            ("zener_velocity", fast.velocity.to_string()),
            ("impedance", sig(zimp, 5)),
            ("zener_force", sig(fz, 6)),
            ("hertz_force", sig(fast.hertz_force(), 6)),
            ("zener_time", sig(tz * 1e3, 5)),
            ("zener_table", z.to_markdown()),
        ],
    )?)
}

/// The discretisation of the comparison in words (from the templates).
fn discretisation_prose(scene: &Scene) -> Result<String, Failure> {
    Ok(match scene.transient_discretisation {
        Discretisation::Fixed { settings } => render(
            "transient/discretisation-fixed.md",
            DISC_FIXED,
            &[("elements", settings.elements.to_string()), ("steps", settings.steps_per_contact.to_string())],
        )?,
        Discretisation::Tolerance { tolerance, budget } => {
            let start = TransientSettings::default();
            render(
                "transient/discretisation-tolerance.md",
                DISC_TOLERANCE,
                &[
                    ("tolerance", sig(tolerance, 2)),
                    ("elements", start.elements.to_string()),
                    ("steps", start.steps_per_contact.to_string()),
                    ("max_elements", budget.max_elements.to_string()),
                    ("max_steps", budget.max_steps_per_contact.to_string()),
                ],
            )?
        }
    })
}

/// A series over the whole run (every contact) of one sampled quantity.
fn whole_run(o: &Outcome, name: &str, x: impl Fn(f64) -> f64, f: impl Fn(&Sample) -> f64) -> Series {
    Series::new(name, o.history.iter().chain(&o.later_history).map(|s| (x(s.t), f(s))).collect())
}

/// What the study found, each finding a Markdown bullet line rendered from the templates: the
/// study's page opens with them, and the main report's transient section repeats them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TransientSummary {
    /// Per body: t_c/T₁, the quasi-static error and the plate's share of E₀.
    pub bodies: String,
    /// The whole impact: re-contact, and impacts the window cut.
    pub contacts: String,
    /// Cases beyond the elastic range under an elastic law (empty where there are none).
    pub elastic: String,
    /// The discretisation errors against the tolerance, and the cost of a case.
    pub errors: String,
    /// The regime criteria on the scene's cases.
    pub regimes: String,
    /// The counts behind the lines, for `findings.json`.
    pub numbers: serde_json::Value,
}

impl TransientSummary {
    /// Every finding, in the order the pages list them.
    pub fn lines(&self) -> String {
        [&self.bodies, &self.contacts, &self.elastic, &self.errors, &self.regimes].iter().map(|s| s.as_str()).collect()
    }
}

/// The number of contacts of a run, an unfinished one included.
fn contact_count(o: &Outcome) -> usize {
    o.contacts.len() + usize::from(o.unfinished_contact.is_some())
}

/// A case as the findings name it.
fn case_label(c: &TransientCase) -> String {
    format!("{}, {} at ({:.1}, {:.1}) mm, {} m/s", c.body, c.condition, c.x * 1e3, c.z * 1e3, sig(c.velocity, 3))
}

/// The findings on the whole impact, the elastic range, the errors and the regimes of `cases`.
fn findings(scene: &Scene, cases: &[TransientCase]) -> Result<TransientSummary, Failure> {
    let n = cases.len().to_string();
    let repeated: Vec<&TransientCase> = cases.iter().filter(|c| contact_count(c.outcome()) > 1).collect();
    let unfinished = cases.iter().filter(|c| c.outcome().left_at.is_none()).count();
    let mut contacts = if let Some(most) = repeated.iter().map(|c| contact_count(c.outcome())).max() {
        // The later contact that strikes hardest against its own first contact.
        let later = |c: &TransientCase| {
            let o = c.outcome();
            let first = o.force_max_interpolated;
            let peak = o.contacts.iter().chain(&o.unfinished_contact).skip(1).map(|k| k.peak_force).fold(0.0, f64::max);
            (peak, first)
        };
        let worst = repeated
            .iter()
            .copied()
            .max_by(|a, b| {
                let (pa, fa) = later(a);
                let (pb, fb) = later(b);
                (pa / fa).total_cmp(&(pb / fb))
            })
            .ok_or("no repeated case")?;
        let (peak, first) = later(worst);
        render(
            "transient/finding-contacts.md",
            FINDING_CONTACTS,
            &[
                ("repeated", repeated.len().to_string()),
                ("cases", n.clone()),
                ("most", most.to_string()),
                ("later_peak", sig(peak, 3)),
                ("first_peak", sig(first, 3)),
                ("later_ratio", sig(peak / first, 3)),
                ("later_case", case_label(worst)),
            ],
        )?
    } else {
        render("transient/finding-single.md", FINDING_SINGLE, &[("cases", n.clone())])?
    };
    if unfinished > 0 {
        contacts.push_str(&render(
            "transient/finding-unfinished.md",
            FINDING_UNFINISHED,
            &[
                ("unfinished", unfinished.to_string()),
                ("cases", n.clone()),
                ("window", sig(scene.transient_discretisation.start().window_contacts, 3)),
            ],
        )?);
    }
    let beyond: Vec<f64> =
        cases.iter().filter_map(|c| c.validity.elastic.filter(|e| !e.valid).map(|e| e.value)).collect();
    let elastic = if beyond.is_empty() {
        String::new()
    } else {
        render(
            "transient/finding-elastic.md",
            FINDING_ELASTIC,
            &[
                ("beyond", beyond.len().to_string()),
                ("cases", n.clone()),
                ("worst", sig(beyond.iter().copied().fold(0.0, f64::max), 3)),
                ("law", scene.contact_law.key().to_string()),
            ],
        )?
    };
    let worst = cases.iter().map(|c| c.estimate.relative_error()).fold(0.0, f64::max);
    let secs: Vec<f64> = cases.iter().map(|c| c.seconds).collect();
    let above = cases.iter().filter(|c| c.validity.discretisation.is_some_and(|d| !d.valid)).count();
    let median_secs = sig(median(&secs).unwrap_or(0.0), 3);
    let slowest = sig(secs.iter().copied().fold(0.0, f64::max), 3);
    let tolerance = match scene.transient_discretisation {
        Discretisation::Tolerance { tolerance, .. } => Some(tolerance),
        Discretisation::Fixed { .. } => None,
    };
    let errors = if above > 0 {
        render(
            "transient/finding-errors-unmet.md",
            FINDING_ERRORS_UNMET,
            &[
                ("above", above.to_string()),
                ("cases", n.clone()),
                ("tolerance", sig(tolerance.unwrap_or(f64::NAN), 2)),
                ("worst", sig(worst, 2)),
                ("median", median_secs.clone()),
                ("slowest", slowest.clone()),
            ],
        )?
    } else {
        render(
            "transient/finding-errors.md",
            FINDING_ERRORS,
            &[
                (
                    "within",
                    tolerance.map_or_else(|| format!("{} (fixed discretisation)", sig(worst, 2)), |t| sig(t, 2)),
                ),
                ("worst", sig(worst, 2)),
                ("median", median_secs.clone()),
                ("slowest", slowest.clone()),
            ],
        )?
    };
    let trusted = cases.iter().filter(|c| c.rule.trusts()).count();
    let wrong =
        cases.iter().filter(|c| c.rule.trusts() && c.force_error().abs() > coupled::regimes::RULE_LIMIT).count();
    let conservative =
        cases.iter().filter(|c| !c.rule.trusts() && c.force_error().abs() <= coupled::regimes::RULE_LIMIT).count();
    let wave = cases.iter().filter(|c| OlssonRegime::of(c.mass_ratio) == OlssonRegime::WaveControlled).count();
    let regimes = render(
        "transient/finding-regimes.md",
        FINDING_REGIMES,
        &[
            ("cases", n.clone()),
            ("trusted", trusted.to_string()),
            ("wrong", wrong.to_string()),
            ("conservative", conservative.to_string()),
            ("wave", wave.to_string()),
        ],
    )?;
    let force_errors = cases
        .iter()
        .map(|c| c.force_error())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), e| (a.min(e), b.max(e)));
    let numbers = serde_json::json!({
        "cases": cases.len(),
        "quasi_static_force_error": [force_errors.0, force_errors.1],
        "struck_more_than_once": repeated.len(),
        "most_contacts": repeated.iter().map(|c| contact_count(c.outcome())).max().unwrap_or(1),
        "unfinished_in_window": unfinished,
        "beyond_elastic_with_elastic_law": beyond.len(),
        "largest_relative_error_estimate": worst,
        "tolerance": tolerance,
        "above_tolerance": above,
        "median_seconds_per_case": median(&secs),
        "rule_trusts": trusted,
        "rule_trusts_wrongly": wrong,
        "rule_flags_needlessly": conservative,
        "olsson_wave_controlled": wave,
    });
    Ok(TransientSummary { bodies: String::new(), contacts, elastic, errors, regimes, numbers })
}

/// Everything `impact dynamic` writes for `scene` at its transient points.
pub fn report(scene: &Scene, progress: &dyn Progress) -> Result<Artifacts, Failure> {
    Ok(study(scene, progress)?.0)
}

/// [`report`], and its findings for the main report.
pub fn study(scene: &Scene, progress: &dyn Progress) -> Result<(Artifacts, TransientSummary), Failure> {
    let points = &scene.transient_points;
    let mut a = Artifacts::new();
    // The page: findings first (computed below), the figures, the tables, the laws, and the
    // verification last; each section is rendered into its own string and assembled at the end.
    let head = render(
        "transient/head.md",
        HEAD,
        &[("scene", scene.name.clone()), ("discretisation", discretisation_prose(scene)?)],
    )?;
    let verification_md = if scene.wants(Analysis::Verification) {
        verification(scene)?
    } else {
        render("transient/not-verified.md", NOT_VERIFIED, &[])?
    };
    let mut md = String::new();
    let mut figures = String::new();

    let t0 = Instant::now();
    let cases = comparison(scene, points, progress)?;
    let comparison_secs = t0.elapsed().as_secs_f64();
    let t = comparison_table(&cases);
    a.add("transient-vs-quasistatic.csv", t.to_csv());
    md.push_str(&render("transient/comparison.md", COMPARISON, &[("table", t.to_markdown())])?);

    // The whole impact.
    let ct = contacts_table(&cases);
    a.add("contacts.csv", contact_rows(&cases).to_csv());
    let repeated = cases.iter().filter(|c| contact_count(c.outcome()) > 1).count();
    let unproven = cases.iter().filter(|c| c.outcome().left_at.is_none()).count();
    md.push_str(&render(
        "transient/contacts.md",
        CONTACTS,
        &[
            ("cases", cases.len().to_string()),
            ("repeated", repeated.to_string()),
            ("unproven", unproven.to_string()),
            ("window", sig(scene.transient_discretisation.start().window_contacts, 3)),
            ("table", ct.to_markdown()),
        ],
    )?);

    // Discretisation, error estimates and cost.
    let dt = discretisation_table(&cases);
    a.add("discretisation.csv", dt.to_csv());
    let secs: Vec<f64> = cases.iter().map(|c| c.seconds).collect();
    let worst_estimate = cases.iter().map(|c| c.estimate.relative_error()).fold(0.0, f64::max);
    let unmet = cases.iter().filter(|c| !c.estimate.met_tolerance).count();
    let finest = cases.iter().map(|c| c.estimate.elements).max().unwrap_or(0);
    md.push_str(&render(
        "transient/discretisation.md",
        DISCRETISATION,
        &[
            ("cases", cases.len().to_string()),
            ("seconds", sig(comparison_secs, 3)),
            ("median", sig(median(&secs).unwrap_or(0.0), 3)),
            ("slowest", sig(secs.iter().copied().fold(0.0, f64::max), 3)),
            ("worst_estimate", sig(worst_estimate, 2)),
            ("unmet", unmet.to_string()),
            ("finest", finest.to_string()),
            ("table", dt.to_markdown()),
        ],
    )?);

    // Regimes.
    let rt = regimes_table(&cases);
    a.add("regimes.csv", rt.to_csv());
    let trusted = cases.iter().filter(|c| c.rule.trusts()).count();
    let wrong =
        cases.iter().filter(|c| c.rule.trusts() && c.force_error().abs() > coupled::regimes::RULE_LIMIT).count();
    let conservative =
        cases.iter().filter(|c| !c.rule.trusts() && c.force_error().abs() <= coupled::regimes::RULE_LIMIT).count();
    let wave = cases.iter().filter(|c| OlssonRegime::of(c.mass_ratio) == OlssonRegime::WaveControlled).count();
    let beyond = cases.iter().filter(|c| c.yield_ratio > 1.0).count();
    md.push_str(&render(
        "transient/regimes.md",
        REGIMES,
        &[
            ("cases", cases.len().to_string()),
            ("trusted", trusted.to_string()),
            ("wrong", wrong.to_string()),
            ("conservative", conservative.to_string()),
            ("wave", wave.to_string()),
            ("repeated", repeated.to_string()),
            ("beyond", beyond.to_string()),
            ("table", rt.to_markdown()),
        ],
    )?);

    if let Some(c) = cases.first() {
        let o = c.outcome();
        let ms = |t: f64| t * 1e3;
        a.add("history-force.svg", history_figure(scene, &cases).svg());
        let e0 = 0.5 * c.sphere_mass * c.velocity * c.velocity;
        let energies = vec![
            whole_run(o, "sphere kinetic", ms, |s| s.sphere_kinetic / e0),
            whole_run(o, "contact (elastic)", ms, |s| s.contact / e0),
            whole_run(o, "plate kinetic", ms, |s| s.plate_kinetic / e0),
            whole_run(o, "plate strain", ms, |s| s.plate_strain / e0),
            whole_run(o, "springs", ms, |s| s.springs / e0),
            whole_run(o, "dissipated", ms, |s| s.dissipated / e0),
        ];
        a.add(
            "history-energy.svg",
            line_plot(
                "Energy split over time (first case of the table), / E₀",
                "t (ms)",
                "E / E₀",
                &energies,
                Scale::Linear,
            ),
        );
        let mut h = Table::new(
            "",
            &[
                "t (s)",
                "force (N)",
                "compression (m)",
                "sphere velocity (m/s)",
                "plate displacement (m)",
                "sphere kinetic (J)",
                "contact (J)",
                "plate kinetic (J)",
                "plate strain (J)",
                "springs (J)",
                "dissipated (J)",
            ],
        );
        for s in o.history.iter().chain(&o.later_history) {
            h.push(vec![
                s.t.into(),
                s.force.into(),
                s.compression.into(),
                s.sphere_velocity.into(),
                s.plate_displacement.into(),
                s.sphere_kinetic.into(),
                s.contact.into(),
                s.plate_kinetic.into(),
                s.plate_strain.into(),
                s.springs.into(),
                s.dissipated.into(),
            ]);
        }
        a.add("history.csv", h.to_csv());
        figures.push_str(&render("transient/history.md", HISTORY, &[])?);
    }

    // The contact laws side by side above the yield velocity, when the scene asks for them.
    let laws_md = if scene.wants(Analysis::ContactLaws) {
        laws_section(scene, &mut a, progress)?
    } else {
        let laws: Vec<&str> = LawKind::ALL.iter().map(|l| l.name()).collect();
        let runs = count_words(LawKind::ALL.len() * LAW_RATIOS.len());
        render("transient/laws-not-asked.md", LAWS_NOT_ASKED, &[("laws", and_list(&laws)), ("runs", runs)])?
    };
    md.push_str(&laws_md);

    // Per body: the range of the quasi-static error and of t_c/T₁ over the cases.
    let mut summary = String::new();
    for body in &scene.bodies {
        let of_body: Vec<&TransientCase> = cases.iter().filter(|c| c.body == body.name).collect();
        if of_body.is_empty() {
            // A range over no cases is no range: say nothing rather than "inf to -inf".
            continue;
        }
        // A t_c/T₁ of a contact that did not end is NaN, which min and max pass over.
        let range = |f: &dyn Fn(&TransientCase) -> f64| {
            of_body.iter().map(|c| f(c)).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)))
        };
        let e = range(&|c| c.force_error());
        let tc = range(&|c| c.contact_ratio().unwrap_or(f64::NAN));
        let pe = range(&|c| c.plate_energy);
        let pq = range(&|c| c.quasi_static_plate_energy);
        summary.push_str(&render(
            "transient/summary-body.md",
            SUMMARY_BODY,
            &[
                ("body", body.name.clone()),
                ("ratio_from", format!("{:.3}", tc.0)),
                ("ratio_to", format!("{:.3}", tc.1)),
                ("error_from", format!("{:+.0}", 100.0 * e.0)),
                ("error_to", format!("{:+.0}", 100.0 * e.1)),
                ("plate_from", format!("{:.0}", 100.0 * pe.0)),
                ("plate_to", format!("{:.0}", 100.0 * pe.1)),
                ("qs_from", format!("{:.0}", 100.0 * pq.0)),
                ("qs_to", format!("{:.0}", 100.0 * pq.1)),
            ],
        )?);
    }
    let mut found = findings(scene, &cases)?;
    found.bodies = summary;
    let mut summary_md = render("transient/summary.md", SUMMARY, &[("findings", found.lines())])?;

    let mut size_md = String::new();
    if scene.wants(Analysis::SizeMap) {
        let (st, series) = size_map(scene)?;
        a.add("size-map.csv", st.to_csv());
        a.add("size-map.svg", ratio_figure(&series, &cases).svg());
        let findings = size_map_findings(&series);
        let said = findings.trim_start_matches("Measured in this run:").trim();
        summary_md = format!("{}\n", summary_md.trim_end());
        summary_md.push_str(&format!("- Over plate size and thickness (Con 1, centre): {said}\n"));
        size_md = render("transient/size-map.md", SIZE_MAP, &[("findings", findings), ("table", st.to_markdown())])?;
    }
    let all: Vec<String> = summary_md
        .lines()
        .filter(|l| l.starts_with("- "))
        .map(|l| l.trim_start_matches("- ").replace("**", ""))
        .collect();
    a.add(
        "findings.json",
        serde_json::to_string_pretty(&serde_json::json!({
            "report": "transient against quasi-static",
            "findings": all,
            "numbers": found.numbers,
        }))?,
    );
    a.add("index.md", [head, summary_md, figures, size_md, md, verification_md].concat());
    Ok((a, found))
}

/// The contact-laws section: Hertz, Flores and Thornton side by side at [`LAW_RATIOS`] times
/// the yield velocity, its table, figure and CSV added to `a`.
fn laws_section(scene: &Scene, a: &mut Artifacts, progress: &dyn Progress) -> Result<String, Failure> {
    let lc = laws(scene, progress)?;
    let lt = laws_table(&lc);
    a.add("contact-laws.csv", lt.clone().csv_name("the end", &["run_end_label"]).to_csv());
    let top = LAW_RATIOS.iter().copied().fold(0.0, f64::max);
    let at = |law: LawKind, ratio: f64| lc.iter().find(|c| c.law == law && c.ratio == ratio);
    let (hertz, flores, thornton) = (
        at(LawKind::Hertz, top).ok_or("no Hertz run")?,
        at(LawKind::Flores, top).ok_or("no Flores run")?,
        at(LawKind::Thornton, top).ok_or("no Thornton run")?,
    );
    let t_h = |c: &LawCase| striker(scene, &scene.bodies[0], c.velocity).hertz_time();
    // The figure has every law of the registry; the prose compares the three named here.
    let law_series = LawKind::ALL
        .iter()
        .map(|&law| {
            let c = at(law, top).ok_or("no run at the top velocity")?;
            let th = t_h(c);
            Ok(whole_run(&c.estimate.outcome, c.law.key(), |t| t / th, |s| s.force))
        })
        .collect::<Result<Vec<Series>, Failure>>()?;
    a.add(
        "contact-laws.svg",
        line_plot(
            &format!("Contact force at {top} x v_y, the {} laws", count_words(LawKind::ALL.len())),
            "t / t_H (Hertz time)",
            "P (N)",
            &law_series,
            Scale::Linear,
        ),
    );
    let end_dissipated = |c: &LawCase| {
        let o = &c.estimate.outcome;
        o.later_history.last().or(o.history.last()).map_or(f64::NAN, |s| s.dissipated / c.energy)
    };
    let below = at(LawKind::Thornton, LAW_RATIOS[0]).ok_or("no run below yield")?;
    let below_hertz = at(LawKind::Hertz, LAW_RATIOS[0]).ok_or("no run below yield")?;
    // "After the impact" only where every run at the top velocity has provably ended.
    let top_runs = [hertz, flores, thornton];
    let open: Vec<String> = top_runs
        .iter()
        .filter(|c| c.estimate.outcome.left_at.is_none())
        .map(|c| format!("{}: {}", c.law.key(), end_state(&c.estimate.outcome)))
        .collect();
    let end = if open.is_empty() {
        render("transient/laws-end-left.md", LAWS_END_LEFT, &[])?
    } else {
        render(
            "transient/laws-end-open.md",
            LAWS_END_OPEN,
            &[("open", open.len().to_string()), ("states", open.join("; "))],
        )?
    };
    let peaks = |f: &dyn Fn(&LawCase) -> f64| top_runs.iter().map(|c| sig(f(c), 3)).collect::<Vec<_>>().join(" / ");
    render(
        "transient/laws.md",
        LAWS,
        &[
            ("end", end.trim().to_string()),
            ("first_peaks", peaks(&|c| c.estimate.values.peak_force)),
            ("all_peaks", peaks(&|c| peak_over_contacts(&c.estimate.outcome))),
            (
                "contacts",
                top_runs.iter().map(|c| contact_count(&c.estimate.outcome).to_string()).collect::<Vec<_>>().join(" / "),
            ),
            ("body", scene.bodies[0].name.clone()),
            ("condition", scene.conditions[0].name.clone()),
            ("v_y", sig(hertz.velocity / hertz.ratio, 4)),
            ("ratios", LAW_RATIOS.iter().map(|r| r.to_string()).collect::<Vec<_>>().join(", ")),
            ("top", top.to_string()),
            ("v_top", sig(hertz.velocity, 3)),
            (
                "thornton_hertz",
                format!("{:.3}", thornton.estimate.values.peak_force / hertz.estimate.values.peak_force),
            ),
            ("flores_hertz", format!("{:.3}", flores.estimate.values.peak_force / hertz.estimate.values.peak_force)),
            ("thornton_e", format!("{:.3}", thornton.estimate.values.restitution)),
            ("flores_e", format!("{:.3}", flores.estimate.values.restitution)),
            ("thornton_dissipated", format!("{:.0}", 100.0 * end_dissipated(thornton))),
            ("flores_dissipated", format!("{:.0}", 100.0 * end_dissipated(flores))),
            ("below_ratio", LAW_RATIOS[0].to_string()),
            (
                "below_same",
                sig((below.estimate.values.peak_force / below_hertz.estimate.values.peak_force - 1.0).abs(), 2),
            ),
            ("table", lt.to_markdown()),
        ],
    )
    .map_err(Into::into)
}
