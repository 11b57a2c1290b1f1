//! A support set's sensor design ([`studies::identify::SensorDesign`]) as a table of steps
//! and the first step's map.

use crate::present::table::{sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use studies::identify::{BackgroundDesign, SensorDesign};

const DESIGN: &str = include_str!("../templates/identify/design.md");
const BACKGROUNDS: &str = include_str!("../templates/identify/design-backgrounds.md");

/// The design's Markdown; `measured` says whether the features were read through the
/// scene's measurement chain.
pub(super) fn markdown(d: &SensorDesign, measured: bool) -> Result<String, Failure> {
    let noise = if measured {
        "The features are read through the scene's measurement chain, at its background level."
    } else {
        "The scene has no measurement chain: the features are the model's exact ones, so the design says where the signals differ most, not what survives a mine's noise."
    };
    let candidates = d.x_mm.len() * d.z_mm.len();
    Ok(render(
        "identify/design.md",
        DESIGN,
        &[
            ("count", d.steps.len().to_string()),
            ("quantity", d.quantity.to_string()),
            ("candidates", candidates.to_string()),
            ("noise", noise.to_string()),
            ("steps", steps(d).to_markdown()),
            ("first", first_map(d).to_markdown()),
        ],
    )?)
}

/// One row per step: where, the AUC so far and the gain.
fn steps(d: &SensorDesign) -> Table {
    let mut t = Table::new("", &["sensors", "added at (x, z) (mm)", "AUC (cross-validated)", "gain (paired error)"]);
    for (k, s) in d.steps.iter().enumerate() {
        t.push(vec![
            Cell::Int(k as u64 + 1),
            format!("({}, {})", sig(s.at_mm.0, 4), sig(s.at_mm.1, 4)).into(),
            format!("{} ± {}", sig(s.auc.auc, 3), sig(s.auc.standard_error, 2)).into(),
            format!("{:+.4} ± {}", s.gain, sig(s.gain_standard_error, 2)).into(),
        ]);
    }
    t
}

/// The first step's map: a row per z, a column per x, the chosen point marked.
fn first_map(d: &SensorDesign) -> Table {
    let first = d.steps.first().map(|s| (s.at_mm, s.map.as_slice()));
    chosen_map((&d.x_mm, &d.z_mm), first)
}

/// A design step as its map shows it: the point chosen, (x, z) mm, and the AUC had each grid
/// point been added, `[x][z]`.
pub(crate) type MapStep<'a> = ((f64, f64), &'a [Vec<Option<f64>>]);

/// A design step's map over the grid `x_mm` by `z_mm`: a row per z, a column per x, each
/// cell the AUC had that point been added (`-`: already chosen), the point chosen marked.
/// No step: the headers alone.
pub(crate) fn chosen_map((x_mm, z_mm): (&[f64], &[f64]), step: Option<MapStep<'_>>) -> Table {
    let mut headers = vec!["z \\ x (mm)".to_string()];
    headers.extend(x_mm.iter().map(|x| sig(*x, 4)));
    let refs: Vec<&str> = headers.iter().map(String::as_str).collect();
    let mut t = Table::new("", &refs);
    let Some((at_mm, map)) = step else { return t };
    for (j, z) in z_mm.iter().enumerate() {
        let mut row = vec![Cell::from(sig(*z, 4))];
        for (i, x) in x_mm.iter().enumerate() {
            let v = map[i][j].map_or("-".to_string(), |a| sig(a, 3));
            row.push(if at_mm == (*x, *z) { format!("**{v}** ●") } else { v }.into());
        }
        t.push(row);
    }
    t
}

/// The designs at the scene's other backgrounds: a row per level and step (empty: no text).
pub(super) fn at_backgrounds(designs: &[BackgroundDesign]) -> Result<String, Failure> {
    if designs.is_empty() {
        return Ok(String::new());
    }
    let mut t = Table::new(
        "",
        &[
            "background",
            "SNR (dB)",
            "quantity",
            "sensors",
            "added at (x, z) (mm)",
            "AUC (cross-validated)",
            "gain (paired error)",
        ],
    );
    for b in designs {
        let level = format!("× {}", sig(b.scale, 3));
        let snr = b.snr_db.map_or(Cell::Empty, |v| Cell::Sig(v, 3));
        let Some(d) = &b.design else {
            t.push(vec![
                level.into(),
                snr,
                "no placement map".into(),
                Cell::Empty,
                Cell::Empty,
                Cell::Empty,
                Cell::Empty,
            ]);
            continue;
        };
        for (k, s) in d.steps.iter().enumerate() {
            t.push(vec![
                level.as_str().into(),
                if k == 0 { snr.clone() } else { Cell::Empty },
                d.quantity.into(),
                Cell::Int(k as u64 + 1),
                format!("({}, {})", sig(s.at_mm.0, 4), sig(s.at_mm.1, 4)).into(),
                format!("{} ± {}", sig(s.auc.auc, 3), sig(s.auc.standard_error, 2)).into(),
                format!("{:+.4} ± {}", s.gain, sig(s.gain_standard_error, 2)).into(),
            ]);
        }
    }
    Ok(render("identify/design-backgrounds.md", BACKGROUNDS, &[("table", t.to_markdown())])?)
}
