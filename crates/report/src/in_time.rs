//! The section of a structure's page on its impacts in time ([`studies::in_time`]), shared by
//! the tail beam's and a mesh file's pages.

use crate::present::table::{sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use studies::in_time::InTime;

const SECTION: &str = include_str!("templates/in_time/section.md");

/// What a page puts beside the rows in time, one entry per row (in the rows' order).
pub struct Beside<'a> {
    /// The struck point's cells (its coordinates, mm).
    pub point: Vec<Vec<Cell>>,
    /// The point's coordinate headers.
    pub point_headers: &'a [&'a str],
    /// The wave-controlled P_max, N.
    pub p_wave: Vec<f64>,
    /// The quasi-static balance's summed spring force, N.
    pub springs_quasi_static: Vec<f64>,
    /// The rigid box's answer for the springs, N, where the page has one.
    pub rigid_box: Option<Vec<f64>>,
    /// What the springs are ("jacks'", "springs'").
    pub springs: &'a str,
}

/// The table of the impacts in time.
pub fn table(t: &InTime, b: &Beside<'_>) -> Table {
    let springs = b.springs;
    let mut headers: Vec<String> = vec!["body".into(), "v (m/s)".into()];
    headers.extend(b.point_headers.iter().map(|h| h.to_string()));
    headers.extend(
        [
            "P_max in time (N)",
            "truncation (rel)",
            "mesh (rel)",
            "P_max wave-controlled (N)",
            "in time/wave - 1",
            "t_c in time (ms)",
            "contacts in time",
        ]
        .map(String::from),
    );
    headers.push(format!("{springs} force in time (N)"));
    if b.rigid_box.is_some() {
        headers.push(format!("{springs} force, rigid box (N)"));
    }
    headers.push(format!("{springs} force quasi-static (N)"));
    headers.push("in time/quasi-static".into());
    let refs: Vec<&str> = headers.iter().map(String::as_str).collect();
    let mut out = Table::new("", &refs);
    for (i, r) in t.rows.iter().enumerate() {
        let mut row = vec![Cell::Text(r.body.clone()), Cell::Given(r.velocity)];
        row.extend(b.point[i].iter().cloned());
        row.extend([
            Cell::Measured { value: r.p_max, error: r.p_max_error },
            Cell::Sig(r.truncation, 2),
            Cell::Sig(r.mesh, 2),
            Cell::Sig(b.p_wave[i], 5),
            Cell::Rel(r.p_max / b.p_wave[i] - 1.0),
            r.contact_time.map_or(Cell::Empty, |t| Cell::Sig(t * 1e3, 4)),
            Cell::Int(r.contacts as u64),
            Cell::Measured { value: r.spring_force, error: r.spring_force_error },
        ]);
        if let Some(rigid) = &b.rigid_box {
            row.push(Cell::Sig(rigid[i], 3));
        }
        let qs = b.springs_quasi_static[i];
        row.push(Cell::Sig(qs, 4));
        row.push(if qs > 0.0 { Cell::Sig(r.spring_force / qs, 3) } else { Cell::Empty });
        out.push(row);
    }
    out
}

/// The section's prose and table: `mesh` names the mesh, `contact` the load, `coarser` the
/// mesh of the mesh error, `rigid` and `checked` add the page's own sentences.
pub struct Prose<'a> {
    /// "mesh 1 of the ladder".
    pub mesh: &'a str,
    /// "30 mm patch".
    pub contact: String,
    /// "the coarser mesh".
    pub coarser: &'a str,
    /// A sentence on the rigid box's answer, or empty.
    pub rigid: &'a str,
    /// A sentence on the page's own independent check, or empty.
    pub checked: &'a str,
}

/// The modes' damping in words, with where it comes from.
fn damping_words(d: coupled::reduced::ModalDamping) -> String {
    let percent = |z: f64| {
        let text = format!("{:.4}", 100.0 * z);
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    };
    match d {
        coupled::reduced::ModalDamping::Ratio(z) => format!(
            "ζ = {} % (the scene's `[signals] damping_ratio`, {} % unless given)",
            percent(z),
            percent(coupled::reduced::ReducedSettings::DEFAULT_DAMPING_RATIO)
        ),
        coupled::reduced::ModalDamping::Rayleigh(r) => format!(
            "Rayleigh's ζᵢ = α/(2ωᵢ) + βωᵢ/2 with α = {} 1/s and β = {} s (the scene's `[plate_damping]`)",
            sig(r.alpha, 3),
            sig(r.beta, 3)
        ),
    }
}

/// The section's text with `table`.
pub fn section(t: &InTime, b: &Beside<'_>, p: &Prose<'_>, table: &Table) -> Result<String, Failure> {
    Ok(render(
        "in_time/section.md",
        SECTION,
        &[
            ("mesh", p.mesh.into()),
            ("unknowns", t.unknowns.to_string()),
            ("modes", t.modes.to_string()),
            ("damping", damping_words(t.damping)),
            ("half", (t.modes / 2).to_string()),
            ("f1", sig(t.frequencies.0, 4)),
            ("fn", sig(t.frequencies.1, 4)),
            ("contact", p.contact.clone()),
            ("springs", b.springs.into()),
            ("window", sig(t.window * 1e3, 3)),
            ("rigid", p.rigid.into()),
            ("coarser", p.coarser.into()),
            ("checked", p.checked.into()),
            ("seconds", format!("{:.1}", t.seconds)),
            ("table", table.to_markdown()),
        ],
    )?)
}

/// The section's CSV and text: [`table`] and [`section`] together.
pub fn part(t: &InTime, b: &Beside<'_>, p: &Prose<'_>) -> Result<(String, String), Failure> {
    let table = table(t, b);
    Ok((table.to_csv(), section(t, b, p, &table)?))
}

#[cfg(test)]
mod tests {
    use super::damping_words;
    use coupled::reduced::ModalDamping;
    use plate_fem::dynamics::Rayleigh;

    #[test]
    fn the_damping_is_named_with_its_source() {
        assert_eq!(
            damping_words(ModalDamping::Ratio(0.007)),
            "ζ = 0.7 % (the scene's `[signals] damping_ratio`, 0.5 % unless given)"
        );
        let r = damping_words(ModalDamping::Rayleigh(Rayleigh { alpha: 12.5, beta: 2e-7 }));
        assert!(r.contains("α = 12.5 1/s") && r.contains("β = 2.00e-7 s") && r.contains("[plate_damping]"), "{r}");
    }
}
