//! The transient study's tables: the comparison, the contacts, the discretisation, the
//! regimes, the contact laws, the size map and the first case's history, each for Markdown
//! and CSV alike.

use crate::present::table::{sig, Cell, Table};
use coupled::regimes::OlssonRegime;
use coupled::transient::sequence_estimate::ContactValues;
use coupled::Validity;
use studies::transient::size_map::SizeRow;
use studies::transient::{contact_count, end_state, peak_over_contacts, LawCase, TransientCase};

/// An optional number as a cell: empty where there is none (no separation in the window).
pub(super) fn opt(v: Option<f64>) -> Cell {
    v.map_or(Cell::Empty, Cell::Num)
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
        let peaks = contact_errors(c);
        let each: Vec<String> = o
            .contacts
            .iter()
            .chain(&o.unfinished_contact)
            .enumerate()
            .map(|(i, k)| {
                let peak = peaks.get(i).filter(|_| i < o.contacts.len()).map_or(k.peak_force, |p| p.0);
                format!("{:.4} / {:.4} / {}", k.start * 1e3, k.duration * 1e3, sig(peak, 4))
            })
            .collect();
        let momentum = c.sphere_mass * c.velocity;
        t.push(vec![
            c.condition.clone().into(),
            c.body.clone().into(),
            point(c),
            c.velocity.into(),
            Cell::Int(contact_count(o) as u64),
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
            "start error (s)",
            "duration (s)",
            "duration error (s)",
            "peak force (N)",
            "peak force error (N)",
            "impulse (N·s)",
            "impulse error (N·s)",
            "velocity after (m/s)",
            "finished",
        ],
    );
    for c in cases {
        let errors = contact_errors(c);
        let o = c.outcome();
        let all = o.contacts.iter().map(|k| (k, true)).chain(o.unfinished_contact.iter().map(|k| (k, false)));
        for (i, (k, done)) in all.enumerate() {
            let (peak, error) = match errors.get(i) {
                Some(&(peak, error)) if done => (peak, error),
                _ => (k.peak_force, None),
            };
            let cell = |e: Option<f64>| e.map_or(Cell::Text("not estimated".into()), Cell::from);
            t.push(vec![
                c.condition.clone().into(),
                c.body.clone().into(),
                c.x.into(),
                c.z.into(),
                c.velocity.into(),
                Cell::Int(i as u64 + 1),
                k.start.into(),
                cell(error.map(|e| e.start)),
                k.duration.into(),
                cell(error.map(|e| e.duration)),
                peak.into(),
                cell(error.map(|e| e.peak_force)),
                k.impulse.into(),
                cell(error.map(|e| e.impulse)),
                k.rebound_velocity.into(),
                done.into(),
            ]);
        }
    }
    t
}

/// Per completed contact of `c`: its peak force (interpolated) and its estimated errors. One
/// contact that ended has the first contact's estimate (its start, the touch, is exact; its
/// impulse m(v₀ + v_r) carries m v₀ times the restitution's error); an impact struck more than
/// once has the estimate of the whole sequence (None for a contact whose count changes
/// between the estimate's levels).
fn contact_errors(c: &TransientCase) -> Vec<(f64, Option<ContactValues>)> {
    let e = &c.estimate;
    match &e.sequence {
        Some(q) => q.contacts.iter().map(|k| (k.values.peak_force, k.error)).collect(),
        None => {
            let first = e.outcome.contacts.first();
            let error = ContactValues {
                start: 0.0,
                duration: e.error.contact_time,
                peak_force: e.error.peak_force,
                impulse: c.sphere_mass * c.velocity * e.error.restitution,
            };
            first.map(|_| (e.outcome.force_max_interpolated, Some(error))).into_iter().collect()
        }
    }
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
        let contacts = contact_count(c.outcome());
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
            Cell::Int(contact_count(o) as u64),
            end_state(o).into(),
        ]);
        t.push(row);
    }
    t
}

/// The size map: each plate's T₁, t_c and transient P_max against the quasi-static plate's.
pub fn size_map_table(rows: &[SizeRow]) -> Table {
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
    for r in rows {
        t.push(vec![
            r.scale.into(),
            (r.thickness * 1e3).into(),
            (r.period * 1e3).into(),
            opt(r.contact_time.map(|t| t * 1e3)),
            opt(r.contact_time.map(|t| t / r.period)),
            r.force_at_max_compression.into(),
            r.quasi_static_force.into(),
            r.error.into(),
        ]);
    }
    t
}

/// Every sample of a case's run (every contact), in SI units.
pub fn history_table(c: &TransientCase) -> Table {
    let o = c.outcome();
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
    h
}
