//! The verification section of the transient page: the model against Hertz, the Flores law's
//! restitution, the energy balance, mesh convergence and Zener's infinite plate, as tables.

use super::tables::opt;
use crate::present::table::{sig, Table};
use crate::template::render;
use crate::Failure;
use coupled::transient::HERTZ_TIME;
use scene::Scene;
use studies::settings::STEPS_PER_CONTACT;
use studies::transient::verification::Verification;

const VERIFICATION: &str = include_str!("../templates/transient/verification.md");

/// The Hertz time constant as some texts round it (design.md among them).
const ROUNDED_HERTZ_TIME: f64 = 3.2145;

/// The verification tables of `v`: Hertz, Flores restitution, energy, convergence, Zener.
pub(super) fn section(scene: &Scene, v: &Verification) -> Result<String, Failure> {
    let force_errors: Vec<f64> = v.hertz.iter().map(|r| r.force_error).collect();
    let halvings: Vec<String> = force_errors.windows(2).map(|w| format!("{:.1}x", w[0] / w[1])).collect();
    let (last, rest) = halvings.split_last().ok_or("no step ladder")?;
    let (z, (length, width, thickness)) = (&v.zener, v.zener.plate);
    Ok(render(
        "transient/verification.md",
        VERIFICATION,
        &[
            ("body", v.body.clone()),
            ("e_elastic", v.elastic.restitution.to_string()),
            ("hertz_time", format!("{HERTZ_TIME:.5}")),
            ("hertz_time_4", format!("{HERTZ_TIME:.4}")),
            ("rounded_hertz_time", ROUNDED_HERTZ_TIME.to_string()),
            ("rounded_low", format!("{:.2}", 100.0 * (1.0 - ROUNDED_HERTZ_TIME / HERTZ_TIME))),
            ("halving_ratios", format!("{} and {last}", rest.join(", "))),
            ("hertz_table", hertz_table(v).to_markdown()),
            ("flores_slope", format!("{:.2}", v.flores_slope)),
            ("flores_paper", format!("{:.0}", 100.0 * v.flores_paper)),
            ("paper_e", v.paper_restitution.to_string()),
            ("flores_table", flores_table(v).to_markdown()),
            ("steps", STEPS_PER_CONTACT.to_string()),
            ("energy_table", energy_table(v).to_markdown()),
            ("velocity", v.elastic.velocity.to_string()),
            ("e_scene", scene.restitution.to_string()),
            ("mesh_table", mesh_table(v).to_markdown()),
            ("zener_length", length.to_string()),
            ("zener_width", width.to_string()),
            ("zener_thickness", (thickness * 1e3).to_string()),
            ("zener_velocity", z.velocity.to_string()),
            ("impedance", sig(z.impedance, 5)),
            ("zener_force", sig(z.force, 6)),
            ("hertz_force", sig(z.hertz_force, 6)),
            ("zener_time", sig(z.time * 1e3, 5)),
            ("zener_table", zener_table(v).to_markdown()),
        ],
    )?)
}

fn hertz_table(v: &Verification) -> Table {
    let mut h =
        Table::new("", &["steps per t_c", "P_max/Hertz - 1", "t_c/Hertz - 1", "apparent e - 1", "max energy error"]);
    for r in &v.hertz {
        h.push(vec![
            r.steps.into(),
            r.force_error.into(),
            opt(r.time_error),
            opt(r.restitution_error),
            r.energy_error.into(),
        ]);
    }
    h
}

fn flores_table(v: &Verification) -> Table {
    let mut f = Table::new(
        "",
        &["e", "apparent restitution", "relative deviation", "δ_max / eq. 14 (C = 0) - 1", "peak force / Kδ_max^{3/2}"],
    );
    for r in &v.flores {
        f.push(vec![
            r.restitution.into(),
            opt(r.apparent),
            opt(r.deviation),
            r.compression_error.into(),
            r.force_ratio.into(),
        ]);
    }
    f
}

fn energy_table(v: &Verification) -> Table {
    let mut en =
        Table::new("", &["steps per t_c", "max abs(E - E₀)/E₀, e = 1, Con 2, centre", "P_max (N)", "run time (s)"]);
    for r in &v.energy {
        en.push(vec![r.steps.into(), r.energy_error.into(), r.force_max.into(), r.seconds.into()]);
    }
    en
}

fn mesh_table(v: &Verification) -> Table {
    let mut mc =
        Table::new("", &["mesh", "DOFs", "P_max (N)", "rel. change to next finer", "t_c (ms)", "run time (s)"]);
    for r in &v.mesh {
        mc.push(vec![
            format!("{} x {}", r.elements.0, r.elements.1).into(),
            r.dofs.into(),
            r.force_max.into(),
            opt(r.change),
            opt(r.contact_time.map(|t| t * 1e3)),
            r.seconds.into(),
        ]);
    }
    mc
}

fn zener_table(v: &Verification) -> Table {
    let mut z = Table::new("", &["mesh", "P_max (N)", "P_max/Zener - 1", "t_c (ms)", "t_c/Zener - 1", "apparent e"]);
    for r in &v.zener.rows {
        z.push(vec![
            format!("{n} x {n}", n = r.elements).into(),
            r.force_max.into(),
            r.force_error.into(),
            opt(r.contact_time.map(|t| t * 1e3)),
            opt(r.time_error),
            opt(r.restitution),
        ]);
    }
    z
}
