//! The tail-beam page: the structure's compliances, the impacts' three forces, and the paper's
//! plate beside it ([`studies::tail_beam`]).

use crate::present::table::{percent, sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use coupled::regimes::OlssonRegime;
use output::Artifacts;
use scene::Scene;
use studies::tail_beam::{TailBeamData, TailBeamRow};

const INDEX: &str = include_str!("templates/tail_beam/index.md");
const FINDING: &str = include_str!("templates/tail_beam/finding.md");

/// The rigid box's jack compliance at x (m): (x/a)²/Σk where every jack shares one x and
/// angle (a = y_pin cos θ + x_jack sin θ, the jacks' arm about the pins); None otherwise.
fn rigid_jacks(d: &TailBeamData, x: f64) -> Option<f64> {
    let b = &d.scene.beam;
    let first = b.jacks.first()?;
    if b.jacks.iter().any(|j| j.x != first.x || j.angle != first.angle) {
        return None;
    }
    let arm = b.pin_height * first.angle.cos() + first.x * first.angle.sin();
    let k: f64 = b.jacks.iter().map(|j| j.stiffness).sum();
    Some((x / arm).powi(2) / k)
}

/// The first row at each point (the compliance does not depend on the body or velocity).
fn per_point(d: &TailBeamData) -> Vec<&TailBeamRow> {
    d.scene.points.iter().filter_map(|&(x, z)| d.rows.iter().find(|r| (r.x, r.z) == (x, z))).collect()
}

/// The structure's table: compliance, its split, and the jacks against the rigid box.
fn structure(d: &TailBeamData) -> Table {
    let mut t = Table::new(
        "",
        &[
            "x (mm)",
            "z (mm)",
            "C (m/N)",
            "membrane share",
            "bending share",
            "shear share",
            "jacks share",
            "jacks, rigid box (m/N)",
            "jacks/rigid box - 1",
        ],
    );
    for r in per_point(d) {
        let rigid = rigid_jacks(d, r.x);
        let jacks = r.shares[3] * r.compliance;
        t.push(vec![
            Cell::Given(r.x * 1e3),
            Cell::Given(r.z * 1e3),
            Cell::Measured { value: r.compliance, error: r.compliance_error },
            Cell::Sig(r.shares[0], 3),
            Cell::Sig(r.shares[1], 3),
            Cell::Sig(r.shares[2], 3),
            Cell::Sig(r.shares[3], 3),
            rigid.map_or(Cell::Empty, |c| Cell::Sig(c, 4)),
            rigid.map_or(Cell::Empty, |c| Cell::Rel(jacks / c - 1.0)),
        ]);
    }
    t
}

/// Every impact's three forces and validity.
fn impacts(d: &TailBeamData) -> Table {
    let mut t = Table::new(
        "",
        &[
            "body",
            "v (m/s)",
            "x (mm)",
            "z (mm)",
            "P_max wave-controlled (N)",
            "P_max quasi-static (N)",
            "P_max rigid target (N)",
            "wave/rigid - 1",
            "quasi-static/wave - 1",
            "jacks' force (N)",
            "t_c/T_1",
            "M_i/M_p",
            "lambda",
            "zeta",
            "regime",
            "delta_max/delta_my",
            "v_y (m/s)",
        ],
    );
    for r in &d.rows {
        t.push(vec![
            Cell::Text(r.body.clone()),
            Cell::Given(r.velocity),
            Cell::Given(r.x * 1e3),
            Cell::Given(r.z * 1e3),
            Cell::Sig(r.p_wave, 5),
            Cell::Sig(r.p_quasi_static, 5),
            Cell::Sig(r.p_rigid, 5),
            Cell::Rel(r.p_wave / r.p_rigid - 1.0),
            Cell::Rel(r.p_quasi_static / r.p_wave - 1.0),
            Cell::Sig(r.jack_force, 4),
            Cell::Sig(r.quasi_static.value, 3),
            Cell::Sig(r.mass_ratio, 3),
            Cell::Sig(r.lambda, 3),
            Cell::Sig(r.zeta, 3),
            Cell::Text(if r.over_wall { format!("{}, over a wall", r.regime.key()) } else { r.regime.key().into() }),
            Cell::Sig(r.elastic.value, 3),
            Cell::Sig(r.yield_velocity, 4),
        ]);
    }
    t
}

/// The paper's beam and plate beside the tail beam at its first point.
fn paper(d: &TailBeamData) -> Table {
    let mut t = Table::new(
        "",
        &[
            "body",
            "v (m/s)",
            "condition",
            "P_max beam (N)",
            "P_max Kirchhoff plate (N)",
            "P_max tail beam (N)",
            "tail beam/plate",
        ],
    );
    let first = d.scene.points.first().copied();
    for p in &d.paper {
        let tail = d.rows.iter().find(|r| r.body == p.body && r.velocity == p.velocity && Some((r.x, r.z)) == first);
        t.push(vec![
            Cell::Text(p.body.clone()),
            Cell::Given(p.velocity),
            Cell::Text(p.condition.clone()),
            Cell::Sig(p.beam, 5),
            Cell::Sig(p.plate, 5),
            tail.map_or(Cell::Empty, |r| Cell::Sig(r.p_wave, 5)),
            tail.map_or(Cell::Empty, |r| Cell::Sig(r.p_wave / p.plate, 3)),
        ]);
    }
    t
}

/// The transient model on the top panel beside the wave-controlled force.
fn panel_table(d: &TailBeamData) -> Table {
    let mut t = Table::new(
        "",
        &[
            "body",
            "v (m/s)",
            "P_max transient, clamped (N)",
            "P_max transient, simply supported (N)",
            "clamped/simply supported - 1",
            "P_max wave-controlled (N)",
            "transient/wave - 1",
        ],
    );
    let measured = |(v, e): (f64, Option<f64>)| match e {
        Some(e) => Cell::Measured { value: v, error: e },
        None => Cell::Sig(v, 5),
    };
    for c in &d.panel_checks {
        t.push(vec![
            Cell::Text(c.body.clone()),
            Cell::Given(c.velocity),
            measured(c.clamped),
            measured(c.simple),
            Cell::Rel(c.clamped.0 / c.simple.0 - 1.0),
            c.wave.map_or(Cell::Empty, |w| Cell::Sig(w, 5)),
            c.wave.map_or(Cell::Empty, |w| Cell::Rel(c.clamped.0 / w - 1.0)),
        ]);
    }
    t
}

/// The impacts on the box's own modes in time, beside the wave-controlled and quasi-static
/// answers and the rigid box's.
fn in_time_beside(d: &TailBeamData) -> crate::in_time::Beside<'static> {
    crate::in_time::Beside {
        point: d.rows.iter().map(|q| vec![Cell::Given(q.x * 1e3), Cell::Given(q.z * 1e3)]).collect(),
        point_headers: &["x (mm)", "z (mm)"],
        p_wave: d.rows.iter().map(|q| q.p_wave).collect(),
        springs_quasi_static: d.rows.iter().map(|q| q.jack_force).collect(),
        rigid_box: Some(d.jacks_rigid_box.clone()),
        springs: "jacks'",
    }
}

/// The in-time section's CSV and text.
fn in_time_part(d: &TailBeamData) -> Result<(String, String), Failure> {
    let beside = in_time_beside(d);
    let prose = crate::in_time::Prose {
        mesh: "the ladder's second mesh",
        contact: format!("{} mm patch", scene::mm_label(d.scene.beam.top)),
        coarser: "the ladder's first mesh",
        rigid: " Beside it, the rigid box turning on the jacks under the contact's impulse J at x, Σk_j a_j·J x/(I ω_r): the first mode's answer alone.",
        checked: " Here its P_max is checked against the transient Kirchhoff panel above (`crates/studies/tests/tail_beam.rs`: 0.1-1.7 %, growing as the contact shortens; the shell's contact is the patch, the plate's a point).",
    };
    crate::in_time::part(&d.in_time, &beside, &prose)
}

/// (min, max) of `v`.
pub(crate) fn range(v: impl Iterator<Item = f64>) -> (f64, f64) {
    v.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| (lo.min(x), hi.max(x)))
}

/// The page's files and the finding for the comparison's list.
pub fn report(scene: &Scene, d: &TailBeamData) -> Result<(Artifacts, String), Failure> {
    let (st, im, pa, pn) = (structure(d), impacts(d), paper(d), panel_table(d));
    let (in_time_csv, in_time) = in_time_part(d)?;

    let mut a = Artifacts::new();
    a.add("impacts-in-time.csv", in_time_csv);
    a.add("panel-transient.csv", pn.to_csv());
    a.add("structure.csv", st.to_csv());
    a.add("impacts.csv", im.to_csv());
    a.add("paper-plate.csv", pa.to_csv());
    let b = &d.scene.beam;
    let mm = scene::mm_label;
    let diaphragms = b
        .diaphragms
        .as_ref()
        .map_or_else(String::new, |d| format!(", {} diaphragm(s) of {} mm", d.x.len(), mm(d.thickness)));
    let box_text = format!(
        "{} x {} x {} mm (length, width, depth), top plate {} mm, bottom {} mm, webs {} mm, end plates {} mm, {} rib(s) of {} mm{diaphragms}, pins at {} mm height over {} span(s), {} jack(s)",
        mm(b.length), mm(b.width), mm(b.height), mm(b.top), mm(b.bottom), mm(b.webs), mm(b.ends),
        b.ribs.len(), mm(b.rib), mm(b.pin_height), b.pins.len(), b.jacks.len()
    );
    let finding = finding(scene, d)?;
    let first = d.scene.points.first().map_or_else(String::new, |&(x, z)| format!("{}, {}", mm(x), mm(z)));
    let levels: Vec<String> = d.levels.iter().map(|l| format!("{} x {} ({}, {:.1} s)", l.0, l.1, l.2, l.3)).collect();
    let description = scene.description.trim().trim_end_matches('.');
    let page = render(
        "tail_beam/index.md",
        INDEX,
        &[
            ("scene", scene.name.clone()),
            ("description", if description.is_empty() { String::new() } else { format!("{description}.") }),
            ("box", box_text),
            ("top_mm", mm(b.top)),
            ("levels", levels.join(", ")),
            ("finest_mm", sig(d.finest_element * 1e3, 3)),
            ("resolution", if d.resolution.valid { "within" } else { "**larger than**" }.into()),
            ("thickness", sig(d.thickness_range.value, 3)),
            ("thickness_ok", if d.thickness_range.valid { "inside" } else { "**beyond**" }.into()),
            ("mass", sig(d.mass, 4)),
            ("frequency", sig(d.frequency.0, 4)),
            ("frequency_change", percent(d.frequency.1)),
            (
                "iteration",
                if d.frequency.2 < 1e-10 {
                    "converged".into()
                } else {
                    format!("**not converged**: last change {}", sig(d.frequency.2, 2))
                },
            ),
            ("rigid_frequency", sig(d.rigid_frequency, 4)),
            ("seconds", format!("{:.1}", d.seconds)),
            ("structure", st.to_markdown()),
            ("findings", finding.clone()),
            ("impacts", im.to_markdown()),
            ("plate", plate_text(scene)),
            ("condition", d.paper.first().map_or_else(|| "no support set".into(), |p| p.condition.clone())),
            ("first_point", first),
            ("paper", pa.to_markdown()),
            ("panel", panel_text(d, &pn)),
            ("in_time", in_time),
        ],
    )?;
    a.add("index.md", page);
    Ok((a, finding))
}

/// The transient check's paragraph and table, or why there is none.
fn panel_text(d: &TailBeamData, t: &Table) -> String {
    match d.panel {
        Some(p) => format!(
            "The transient model (Kirchhoff plate, Newmark, the scene's contact law, to a relative tolerance of {}) on the top plate's panel that holds the first point, {} x {} mm between its walls, struck at ({}, {}) mm, once with its edges clamped and once simply supported:\n\n{}",
            studies::tail_beam::PANEL_TOLERANCE,
            scene::mm_label(p.length),
            scene::mm_label(p.width),
            scene::mm_label(p.at.0),
            scene::mm_label(p.at.1),
            t.to_markdown()
        ),
        None => "No transient check: the first point lies on a wall's line, or its panel is not a plate the transient model takes (an aspect ratio beyond 100).\n".into(),
    }
}

/// "458.4 x 360 x 8 mm".
fn plate_text(scene: &Scene) -> String {
    let p = &scene.plate;
    format!("{} x {} x {} mm", scene::mm_label(p.length()), scene::mm_label(p.width()), scene::mm_label(p.thickness()))
}

/// The finding line: the regimes, the three forces' spread, and the paper's plate beside.
fn finding(scene: &Scene, d: &TailBeamData) -> Result<String, Failure> {
    let wave_rows = d.rows.iter().filter(|r| r.regime == OlssonRegime::WaveControlled).count();
    let regime = if wave_rows == d.rows.len() {
        "every impact is wave controlled".to_string()
    } else {
        format!("{wave_rows} of {} impacts are wave controlled", d.rows.len())
    };
    let (_, mass_ratio) = range(d.rows.iter().map(|r| r.mass_ratio));
    let (_, t_ratio) = range(d.rows.iter().map(|r| r.quasi_static.value));
    let (wave_low, wave_high) = range(d.rows.iter().filter(|r| !r.over_wall).map(|r| r.p_wave / r.p_rigid));
    let (qs_low, qs_high) = range(d.rows.iter().map(|r| r.p_quasi_static / r.p_wave - 1.0));
    let (jack_low, jack_high) = range(d.rows.iter().map(|r| r.shares[3]));
    let first = d.scene.points.first().copied();
    let (paper_low, paper_high) = range(d.paper.iter().filter_map(|p| {
        d.rows
            .iter()
            .find(|r| r.body == p.body && r.velocity == p.velocity && Some((r.x, r.z)) == first)
            .map(|r| r.p_wave / p.plate)
    }));
    let share = |v: f64| format!("{} %", sig(100.0 * v, 3));
    let (panel_low, panel_high) = range(d.panel_checks.iter().filter_map(|c| c.wave.map(|w| c.clamped.0 / w - 1.0)));
    let (_, edge_high) = range(d.panel_checks.iter().map(|c| (c.clamped.0 / c.simple.0 - 1.0).abs()));
    let panel = if d.panel_checks.is_empty() {
        String::new()
    } else {
        format!(
            " The transient plate model on the top panel differs from the wave-controlled force by {} to {}, and its clamped and simply supported edges differ by at most {}: the edges do not matter, as in a wave-controlled impact.",
            percent(panel_low),
            percent(panel_high),
            sig(100.0 * edge_high, 2) + " %"
        )
    };
    let in_time = in_time_sentence(d);
    render(
        "tail_beam/finding.md",
        FINDING,
        &[
            ("scene", scene.name.clone()),
            ("regime", regime),
            ("mass_ratio", sig(mass_ratio, 2)),
            ("t_ratio", sig(t_ratio, 2)),
            ("wave_low", share(wave_low)),
            ("wave_high", share(wave_high)),
            ("qs_low", percent(qs_low)),
            ("qs_high", percent(qs_high)),
            ("jack_low", share(jack_low)),
            ("jack_high", share(jack_high)),
            ("plate", plate_text(scene)),
            ("paper_low", sig(paper_low, 3)),
            ("paper_high", sig(paper_high, 3)),
            ("panel", panel),
            ("in_time", in_time),
        ],
    )
    .map_err(Into::into)
}

/// The finding's sentence on the impacts in time: P_max against the wave-controlled force away
/// from the walls, and the jacks against the quasi-static balance (each left out where its
/// range is empty).
fn in_time_sentence(d: &TailBeamData) -> String {
    let share = |v: f64| format!("{} %", sig(100.0 * v, 3));
    let (time_low, time_high) =
        range(d.in_time.rows.iter().zip(&d.rows).filter(|(_, q)| !q.over_wall).map(|(r, q)| r.p_max / q.p_wave - 1.0));
    let (jt_low, jt_high) = range(
        d.in_time
            .rows
            .iter()
            .zip(&d.rows)
            .filter(|(_, q)| q.jack_force > 0.0)
            .map(|(r, q)| r.spring_force / q.jack_force),
    );
    // An empty range (every point over a wall, or no jack loaded) says nothing.
    let forces = if time_low <= time_high {
        format!(
            ", P_max away from the walls is {} to {} off the wave-controlled force",
            percent(time_low),
            percent(time_high)
        )
    } else {
        String::new()
    };
    let jacks = if jt_low <= jt_high {
        format!(
            ", and the jacks feel {} to {} of the quasi-static balance's jack force: a contact this short reaches them as an impulse",
            share(jt_low),
            share(jt_high)
        )
    } else {
        String::new()
    };
    format!(" In time, on the box's own {} modes{forces}{jacks}.", d.in_time.modes)
}
