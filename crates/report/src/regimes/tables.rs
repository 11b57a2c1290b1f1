//! The regime maps' tables: every case for the CSV, the criteria's scores, Olsson's regimes,
//! the Con 1 grid, the springs and the scene's points.

use crate::present::table::{sig, Cell, Table};
use coupled::regimes::ContactSpeed;
use studies::regimes::{MapRow, RegimeData, Score, Slice};

/// The criteria against the measured error on one slice.
pub(super) fn score_table(d: &RegimeData, slice: Slice) -> Table {
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
    for c in &d.criteria {
        let s: &Score = c.on(slice);
        t.push(vec![
            c.criterion.as_str().into(),
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
pub(super) fn olsson_table(d: &RegimeData) -> Table {
    let mut t = Table::new(
        "",
        &["Olsson's regime", "cases", "within 3 %", "largest error", "smallest error", "with repeated contacts"],
    );
    for o in &d.olsson {
        t.push(vec![
            o.regime.key().into(),
            Cell::Int(o.cases as u64),
            Cell::Int(o.within as u64),
            o.largest.map_or(Cell::Empty, Cell::Num),
            o.smallest.map_or(Cell::Empty, Cell::Num),
            Cell::Int(o.repeated as u64),
        ]);
    }
    t
}

/// Every case, for the CSV.
pub(super) fn full_table(rows: &[MapRow]) -> Table {
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
        t.push(full_row(r));
    }
    t
}

fn full_row(r: &MapRow) -> Vec<Cell> {
    let m = &r.measured;
    let p = &r.rule.parameters;
    let ms = |v: Option<f64>| v.map_or(Cell::Empty, |v| Cell::Num(v * 1e3));
    vec![
        r.slice.key().into(),
        r.condition.clone().into(),
        r.spring.map_or(Cell::Empty, Cell::Num),
        r.scale.into(),
        (r.thickness * 1e3).into(),
        (r.radius * 1e3).into(),
        (r.point.0 * 1e3).into(),
        (r.point.1 * 1e3).into(),
        r.mass_ratio.into(),
        coupled::regimes::OlssonRegime::of(r.mass_ratio).key().into(),
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
    ]
}

fn speed_key(s: ContactSpeed) -> &'static str {
    match s {
        ContactSpeed::Fast => "fast",
        ContactSpeed::Resonant => "resonant",
        ContactSpeed::Slow => "slow",
    }
}

/// One grid cell: the signed force error in percent, the contacts if more than one, and a
/// mark where the rule trusts the balance.
fn grid_cell(r: &MapRow) -> Cell {
    Cell::Text(format!(
        "{:+.1}{}{}",
        100.0 * r.signed_error(),
        if r.measured.contacts > 1 { format!(" ({} contacts)", r.measured.contacts) } else { String::new() },
        if r.rule.trusts() { ", trusted" } else { "" }
    ))
}

/// Signed force errors in percent, rows (size, h), columns the spheres, for one family at
/// one spring stiffness; a mark where the rule trusts the balance.
pub(super) fn grid_table(rows: &[MapRow], condition: &str, radii: &[f64]) -> Table {
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
            let here = of.iter().find(|r| r.scale == scale && r.thickness == h && r.radius == radius);
            row.push(here.map_or(Cell::Empty, |r| grid_cell(r)));
        }
        t.push(row);
    }
    t
}

/// Force error against the spring stiffness at the scene's size and thickness.
pub(super) fn spring_table(rows: &[MapRow], radii: &[f64]) -> Table {
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
pub(super) fn mid_thickness(rows: &[MapRow]) -> f64 {
    let mut hs: Vec<f64> = rows.iter().map(|r| r.thickness).collect();
    hs.sort_by(f64::total_cmp);
    hs.dedup();
    hs.get(hs.len() / 2).copied().unwrap_or(f64::NAN)
}

/// The points slice, point by point: how the rule fares there.
pub(super) fn points_table(d: &RegimeData) -> Table {
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
    for p in &d.points {
        let s = &p.rule;
        t.push(vec![
            format!("({}, {})", sig(p.point.0 * 1e3, 4), sig(p.point.1 * 1e3, 4)).into(),
            Cell::Int(p.cases as u64),
            Cell::Int(p.within as u64),
            Cell::Int(s.trusted as u64),
            Cell::Int(s.trusted_wrong as u64),
            if s.trusted > 0 { Cell::Num(s.worst_trusted) } else { Cell::Empty },
            Cell::Int(p.repeated as u64),
        ]);
    }
    t
}
