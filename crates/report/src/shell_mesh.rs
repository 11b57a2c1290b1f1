//! The page of a structure read from a mesh file: its compliances on the ladder and the
//! impacts' three forces ([`studies::shell_mesh`]).

use crate::present::table::{percent, sig, Cell, Table};
use crate::tail_beam::range;
use crate::template::render;
use crate::Failure;
use coupled::compliance::shell_mesh::{CONFIRMED, RATES};
use output::Artifacts;
use scene::Scene;
use studies::shell_mesh::{ShellMeshData, ShellMeshRow};

const INDEX: &str = include_str!("templates/shell_mesh/index.md");
const FINDING: &str = include_str!("templates/shell_mesh/finding.md");

/// The first row at each point (the compliance does not depend on the body or velocity).
fn per_point(d: &ShellMeshData) -> Vec<(usize, &ShellMeshRow)> {
    let points = d.scene.points.iter().enumerate();
    points.filter_map(|(i, p)| d.rows.iter().find(|r| r.at == *p).map(|r| (i, r))).collect()
}

/// The structure's table: compliance with its estimate and rate, and its split.
fn structure(d: &ShellMeshData) -> Table {
    let mut t = Table::new(
        "",
        &[
            "x (mm)",
            "y (mm)",
            "z (mm)",
            "C (m/N)",
            "observed rate",
            "asymptotic",
            "membrane share",
            "bending share",
            "shear share",
            "springs share",
        ],
    );
    for (i, r) in per_point(d) {
        t.push(vec![
            Cell::Given(r.at[0] * 1e3),
            Cell::Given(r.at[1] * 1e3),
            Cell::Given(r.at[2] * 1e3),
            Cell::Measured { value: r.compliance, error: r.compliance_error },
            d.rates[i].map_or(Cell::Empty, |p| Cell::Sig(p, 3)),
            Cell::Flag { yes: r.asymptotic, shown: if r.asymptotic { "yes" } else { "**no**" } },
            Cell::Sig(r.shares[0], 3),
            Cell::Sig(r.shares[1], 3),
            Cell::Sig(r.shares[2], 3),
            Cell::Sig(r.shares[3], 3),
        ]);
    }
    t
}

/// Every impact's three forces and validity.
fn impacts(d: &ShellMeshData) -> Table {
    let mut t = Table::new(
        "",
        &[
            "body",
            "v (m/s)",
            "x (mm)",
            "y (mm)",
            "z (mm)",
            "P_max quasi-static (N)",
            "springs' force (N)",
            "P_max wave-controlled (N)",
            "P_max rigid target (N)",
            "quasi-static/wave - 1",
            "lambda",
            "zeta",
            "t_c/T_1",
            "delta_max/delta_my",
            "v_y (m/s)",
        ],
    );
    for r in &d.rows {
        t.push(vec![
            Cell::Text(r.body.clone()),
            Cell::Given(r.velocity),
            Cell::Given(r.at[0] * 1e3),
            Cell::Given(r.at[1] * 1e3),
            Cell::Given(r.at[2] * 1e3),
            Cell::Sig(r.p_quasi_static, 5),
            Cell::Sig(r.spring_force, 4),
            Cell::Sig(r.p_wave, 5),
            Cell::Sig(r.p_rigid, 5),
            Cell::Rel(r.p_quasi_static / r.p_wave - 1.0),
            Cell::Sig(r.lambda, 3),
            Cell::Sig(r.zeta, 3),
            Cell::Sig(r.quasi_static.value, 3),
            Cell::Sig(r.elastic.value, 3),
            Cell::Sig(r.yield_velocity, 4),
        ]);
    }
    t
}

/// The page's files and the finding for the comparison's list.
pub fn report(scene: &Scene, d: &ShellMeshData) -> Result<(Artifacts, String), Failure> {
    let (st, im) = (structure(d), impacts(d));
    let mut a = Artifacts::new();
    a.add("structure.csv", st.to_csv());
    a.add("impacts.csv", im.to_csv());
    let (csv, in_time) = in_time_part(d)?;
    a.add("impacts-in-time.csv", csv);
    let sm = &d.scene;
    let mesh = &sm.mesh;
    let groups: Vec<String> = mesh
        .groups
        .iter()
        .map(|g| {
            let kind = ["points", "curves", "surface"][usize::from(g.dim.min(2))];
            match sm.thickness.iter().find(|(n, _)| *n == g.name) {
                Some((_, t)) => format!("\"{}\" ({kind}, {} mm)", g.name, scene::mm_label(*t)),
                None => format!("\"{}\" ({kind})", g.name),
            }
        })
        .collect();
    let groups = format!(
        "{} nodes, {} quadrilaterals, and the groups {}",
        mesh.nodes.len(),
        mesh.quads.len(),
        groups.join(", ")
    );
    let dofs = ["u_x", "u_y", "u_z", "ω_x", "ω_y", "ω_z"];
    let mut restraints: Vec<String> = sm
        .holds
        .iter()
        .map(|(g, held)| {
            let names: Vec<&str> = held.iter().map(|&k| dofs[k]).collect();
            format!("\"{g}\" holds {}", names.join(", "))
        })
        .collect();
    restraints.extend(sm.springs.iter().map(|s| {
        format!(
            "\"{}\" carries a spring of {} N/m along ({}, {}, {})",
            s.group,
            sig(s.stiffness, 3),
            sig(s.direction[0], 3),
            sig(s.direction[1], 3),
            sig(s.direction[2], 3)
        )
    }));
    let restraints =
        if restraints.is_empty() { String::new() } else { format!("{}.", capitalise(&restraints.join("; "))) };
    let levels: Vec<String> =
        d.levels.iter().map(|l| format!("{} ({}, {:.1} s)", l.elements, l.dofs, l.seconds)).collect();
    let description = scene.description.trim().trim_end_matches('.');
    let finding = finding(scene, d)?;
    let page = render(
        "shell_mesh/index.md",
        INDEX,
        &[
            ("scene", scene.name.clone()),
            ("description", if description.is_empty() { String::new() } else { format!("{description}.") }),
            ("file", sm.file.clone()),
            ("sha", sm.sha256.chars().take(16).collect()),
            ("groups", groups),
            ("restraints", restraints),
            ("struck", sm.struck.clone()),
            ("struck_mm", scene::mm_label(d.struck_thickness)),
            ("levels", levels.join(", ")),
            ("rate_low", RATES.start().to_string()),
            ("rate_high", RATES.end().to_string()),
            ("confirmed", CONFIRMED.to_string()),
            ("mass", sig(d.mass, 4)),
            ("frequency", sig(d.frequency.0, 4)),
            ("frequency_change", percent(d.frequency.1)),
            ("seconds", format!("{:.1}", d.seconds)),
            ("structure", st.to_markdown()),
            ("findings", finding.clone()),
            ("impacts", im.to_markdown()),
            ("in_time", in_time),
        ],
    )?;
    a.add("index.md", page);
    Ok((a, finding))
}

/// The in-time section's CSV and text.
fn in_time_part(d: &ShellMeshData) -> Result<(String, String), Failure> {
    let beside = crate::in_time::Beside {
        point: d
            .rows
            .iter()
            .map(|r| vec![Cell::Given(r.at[0] * 1e3), Cell::Given(r.at[1] * 1e3), Cell::Given(r.at[2] * 1e3)])
            .collect(),
        point_headers: &["x (mm)", "y (mm)", "z (mm)"],
        p_wave: d.rows.iter().map(|r| r.p_wave).collect(),
        springs_quasi_static: d.rows.iter().map(|r| r.spring_force).collect(),
        rigid_box: None,
        springs: "springs'",
    };
    let prose = crate::in_time::Prose {
        mesh: "the file's mesh refined once",
        contact: format!("disc of diameter {} mm", scene::mm_label(d.struck_thickness)),
        coarser: "the file's own mesh",
        rigid: "",
        checked: "",
    };
    crate::in_time::part(&d.in_time, &beside, &prose)
}

fn capitalise(s: &str) -> String {
    let mut c = s.chars();
    c.next().map_or_else(String::new, |f| f.to_uppercase().chain(c).collect())
}

/// The finding line: the wave-controlled force against the rigid one, the quasi-static
/// balance against it, and the springs' share.
fn finding(scene: &Scene, d: &ShellMeshData) -> Result<String, Failure> {
    let (_, t_ratio) = range(d.rows.iter().map(|r| r.quasi_static.value));
    let (wave_low, wave_high) = range(d.rows.iter().map(|r| r.p_wave / r.p_rigid));
    let (qs_low, qs_high) = range(d.rows.iter().map(|r| r.p_quasi_static / r.p_wave - 1.0));
    let (spring_low, spring_high) = range(d.rows.iter().map(|r| r.shares[3]));
    let (_, error) = range(d.rows.iter().map(|r| r.compliance_error / r.compliance));
    let share = |v: f64| format!("{} %", sig(100.0 * v, 3));
    let (time_low, time_high) = range(d.in_time.rows.iter().zip(&d.rows).map(|(t, r)| t.p_max / r.p_wave - 1.0));
    render(
        "shell_mesh/finding.md",
        FINDING,
        &[
            ("scene", scene.name.clone()),
            ("file", d.scene.file.clone()),
            ("struck", d.scene.struck.clone()),
            ("t_ratio", sig(t_ratio, 2)),
            ("wave_low", share(wave_low)),
            ("wave_high", share(wave_high)),
            ("qs_low", percent(qs_low)),
            ("qs_high", percent(qs_high)),
            ("spring_low", share(spring_low)),
            ("spring_high", share(spring_high)),
            ("error", percent(error)),
            ("modes", d.in_time.modes.to_string()),
            ("time_low", percent(time_low)),
            ("time_high", percent(time_high)),
        ],
    )
    .map_err(Into::into)
}
