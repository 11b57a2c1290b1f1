//! Figures 8-19 of the paper: the beam model's responses (eqs. 14, 25, 46 solved to
//! convergence) and yield velocities (eqs. 51-54) along the plate, one panel per quantity.

use super::*;
use scene::even_points;
use serde::Serialize;

/// The quantities of the response panels of Figs. 10 and 13 (and, a selection, of Figs. 14
/// and 17): the panel's file-stem part, the quantity, and the unit it is drawn in.
pub const RESPONSE_PANELS: [(&str, Quantity, f64); 8] = [
    ("contact-force", Quantity::ContactForce, 1.0),
    ("compression", Quantity::Compression, 1e-6),
    ("deflection", Quantity::Deflection, 1e-6),
    ("spring-force", Quantity::SpringForce(0), 1.0),
    ("rock-total", Quantity::RockTotal, 1.0),
    ("rock-stored", Quantity::RockStored, 1.0),
    ("plate-energy", Quantity::PlateRatio, 1.0),
    ("spring-energy", Quantity::SpringRatio, 1.0),
];

/// What a panel draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Drawn {
    /// The yield velocity.
    Yield,
    /// Entry `quantity` of [`RESPONSE_PANELS`], as panel `panel` (from 1) of its figure.
    Response {
        /// Index into [`RESPONSE_PANELS`].
        quantity: usize,
        /// The panel's number within its figure.
        panel: usize,
    },
}

/// One curve of a panel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PanelCurve {
    /// Its name in the legend.
    pub name: String,
    /// (x in mm, value).
    pub points: Vec<(f64, f64)>,
}

/// A figure panel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Panel {
    /// The file stem, `figNN-...`.
    pub stem: String,
    /// The figure's number as the paper prints it ("10").
    pub figure: String,
    /// What it draws.
    pub drawn: Drawn,
    /// Its curves.
    pub curves: Vec<PanelCurve>,
    /// Whether the values span decades (drawn on a log axis).
    pub log: bool,
}

/// A curve setting: plate, body, condition, velocity, label.
struct Curve<'a> {
    plate: Plate,
    body: &'a Sphere,
    cond: Condition,
    v: f64,
    label: String,
}

fn sweep_responses(paper: &Paper, c: &Curve) -> Vec<(f64, Response)> {
    even_points(c.plate.length(), SWEEP)
        .into_iter()
        .map(|x| (x * 1e3, paper.respond(&c.plate, c.body, c.cond, x, c.v, Solve::Converged)))
        .collect()
}

/// Panels of the response quantities `which` for a family of curves; spring panels list every
/// spring of every curve that has springs, and are left out when none has.
fn response_panels(paper: &Paper, fig: &str, curves: &[Curve], which: &[usize]) -> Vec<Panel> {
    let data: Vec<Vec<(f64, Response)>> = curves.iter().map(|c| sweep_responses(paper, c)).collect();
    let mut panels = Vec::new();
    for (k, &i) in which.iter().enumerate() {
        let (stem, q, scale) = RESPONSE_PANELS[i];
        let mut series = Vec::new();
        for (c, d) in curves.iter().zip(&data) {
            match q {
                Quantity::SpringForce(_) => {
                    for (si, s) in d[0].1.spring_forces.iter().enumerate() {
                        let points = d.iter().map(|(x, r)| (*x, r.spring_forces[si].force)).collect();
                        series.push(PanelCurve { name: format!("{} {}", c.label, s.name), points });
                    }
                }
                Quantity::SpringRatio if c.cond.spring_stiffness().is_none() => {}
                _ => series.push(PanelCurve {
                    name: c.label.clone(),
                    points: d.iter().map(|(x, r)| (*x, q.of(r) / scale)).collect(),
                }),
            }
        }
        if series.is_empty() {
            continue;
        }
        panels.push(Panel {
            stem: format!("fig{fig}-{}-{stem}", k + 1),
            figure: fig.into(),
            drawn: Drawn::Response { quantity: i, panel: k + 1 },
            curves: series,
            log: false,
        });
    }
    panels
}

fn yield_panel(paper: &Paper, stem: &str, fig: &str, curves: &[Curve]) -> Panel {
    let series = curves
        .iter()
        .map(|c| {
            let points = even_points(c.plate.length(), SWEEP)
                .into_iter()
                .map(|x| (x * 1e3, paper.yield_velocity_scaled(&c.plate, c.body, c.cond, x, 1.0)))
                .collect();
            PanelCurve { name: c.label.clone(), points }
        })
        .collect();
    Panel { stem: stem.into(), figure: fig.into(), drawn: Drawn::Yield, curves: series, log: false }
}

/// Con 1-3 of `body` at `v` on `plate` with springs `k_t`, labelled `prefix` Con n.
fn cons<'a>(body: &'a Sphere, v: f64, k_t: f64, plate: Plate, prefix: &str) -> Vec<Curve<'a>> {
    (1..=3)
        .map(|n| Curve { plate, body, cond: Paper::condition(n, k_t), v, label: format!("{prefix}Con {n}") })
        .collect()
}

/// The panels of `fig` for the single quantity `i`, its stem without the panel number.
fn single(paper: &Paper, fig: &str, curves: &[Curve], i: usize) -> Vec<Panel> {
    let mut p = response_panels(paper, fig, curves, &[i]);
    for q in &mut p {
        q.stem = q.stem.replacen(&format!("fig{fig}-1-"), &format!("fig{fig}-"), 1);
    }
    p
}

/// Figs. 8-13: the yield velocities and the coal's responses, Con 1-3 and three k_T.
fn support_panels(paper: &Paper) -> Vec<Panel> {
    let plate = paper.scene.plate;
    let coal = &paper.coal;
    let mut out = vec![
        yield_panel(paper, "fig08-yield-coal", "8", &cons(coal, 1.0, paper.k_t, plate, "")),
        yield_panel(paper, "fig09-yield-gangue1", "9", &cons(&paper.gangue1, 1.0, paper.k_t, plate, "")),
    ];
    let all8: Vec<usize> = (0..8).collect();
    out.extend(response_panels(paper, "10", &cons(coal, V_TABLE3, paper.k_t, plate, ""), &all8));
    let k_curves = |n: usize| -> Vec<Curve> {
        K_STUDY
            .iter()
            .map(|&k| Curve {
                plate,
                body: coal,
                cond: Paper::condition(n, k),
                v: V_TABLE3,
                label: format!("k_T = {k:e}"),
            })
            .collect()
    };
    out.push(yield_panel(paper, "fig11-yield-con2-stiffness", "11", &k_curves(2)));
    out.push(yield_panel(paper, "fig12-yield-con3-stiffness", "12", &k_curves(3)));
    let mut k13 = Vec::new();
    for n in [2, 3] {
        for c in k_curves(n) {
            k13.push(Curve { label: format!("Con {n} {}", c.label), ..c });
        }
    }
    out.extend(response_panels(paper, "13", &k13, &all8));
    out
}

/// Every panel of Figs. 8-19.
pub fn panels(paper: &Paper) -> Vec<Panel> {
    let plate = paper.scene.plate;
    let mut out = support_panels(paper);
    let mut lengths = Vec::new();
    for f in LENGTH_FACTORS {
        let p = plate.with_length(plate.length() * f).expect("positive length");
        lengths.extend(cons(&paper.coal, V_TABLE3, K_LENGTH_STUDY, p, &format!("L = {:.1} mm ", p.length() * 1e3)));
    }
    out.extend(response_panels(paper, "14", &lengths, &[0, 1, 2, 4, 5, 6]));
    let springs: Vec<Curve> = lengths.into_iter().filter(|c| c.cond.spring_stiffness().is_some()).collect();
    for (fig, i) in [("15", 3), ("16", 7)] {
        out.extend(single(paper, fig, &springs, i));
    }
    let mut bodies = Vec::new();
    for b in paper.bodies() {
        bodies.extend(cons(b, V_TABLE6, paper.k_t, plate, &format!("{} ", b.name)));
    }
    out.extend(response_panels(paper, "17", &bodies, &[1, 0, 2, 4, 5, 6]));
    let springs: Vec<Curve> = bodies.into_iter().filter(|c| c.cond.spring_stiffness().is_some()).collect();
    for (fig, i) in [("18", 3), ("19", 7)] {
        out.extend(single(paper, fig, &springs, i));
    }
    // Spring forces and energies span decades when k_T changes (Fig. 13) or soft springs
    // take most of the energy; a log axis keeps every curve visible.
    for p in &mut out {
        if p.stem.starts_with("fig13") && (p.stem.ends_with("spring-energy") || p.stem.ends_with("deflection")) {
            p.log = true;
        }
    }
    out
}
