//! Figures 8-19 of the paper: the beam model's responses and yield velocities along the
//! plate, one panel per quantity.

use super::*;

// ------------------------------------------------------------------ figures

/// A figure panel: its file stem, title, axis label, series and scale.
pub(super) struct Panel {
    pub(super) stem: String,
    pub(super) title: String,
    pub(super) y_label: String,
    pub(super) series: Vec<Series>,
    pub(super) scale: Scale,
}

fn panel(stem: &str, title: &str, y_label: &str, series: Vec<Series>) -> Panel {
    Panel { stem: stem.into(), title: title.into(), y_label: y_label.into(), series, scale: Scale::Linear }
}

/// The 8 response panels of Figs. 10 and 13, and the 6 of Figs. 14 and 17.
const RESPONSE_PANELS: [(&str, &str, Quantity, f64); 8] = [
    ("contact-force", "Maximum contact force (N)", Quantity::ContactForce, 1.0),
    ("compression", "Maximum rock compression (µm)", Quantity::Compression, 1e-6),
    ("deflection", "Impact-point deflection (µm)", Quantity::Deflection, 1e-6),
    ("spring-force", "Spring force (N)", Quantity::SpringForce(0), 1.0),
    ("rock-total", "Rock total energy ratio", Quantity::RockTotal, 1.0),
    ("rock-stored", "Rock absorbed energy ratio", Quantity::RockStored, 1.0),
    ("plate-energy", "Plate energy ratio", Quantity::PlateRatio, 1.0),
    ("spring-energy", "Spring energy ratio", Quantity::SpringRatio, 1.0),
];

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

/// Panels of the response quantities for a family of curves; spring panels list every
/// spring of every curve that has springs, and are left out when none has.
fn response_panels(paper: &Paper, fig: &str, what: &str, curves: &[Curve], which: &[usize]) -> Vec<Panel> {
    let data: Vec<Vec<(f64, Response)>> = curves.iter().map(|c| sweep_responses(paper, c)).collect();
    let mut panels = Vec::new();
    for (k, &i) in which.iter().enumerate() {
        let (stem, label, q, scale) = RESPONSE_PANELS[i];
        let mut series = Vec::new();
        for (c, d) in curves.iter().zip(&data) {
            match q {
                Quantity::SpringForce(_) => {
                    for (si, s) in d[0].1.spring_forces.iter().enumerate() {
                        let pts = d.iter().map(|(x, r)| (*x, r.spring_forces[si].force)).collect();
                        series.push(Series::new(format!("{} {}", c.label, s.name), pts));
                    }
                }
                Quantity::SpringRatio if c.cond.spring_stiffness().is_none() => {}
                _ => series.push(Series::new(c.label.clone(), d.iter().map(|(x, r)| (*x, q.of(r) / scale)).collect())),
            }
        }
        if series.is_empty() {
            continue;
        }
        let title = format!("Fig. {fig}({}) {what}", k + 1);
        panels.push(panel(&format!("fig{fig}-{}-{stem}", k + 1), &title, label, series));
    }
    panels
}

fn yield_panel(paper: &Paper, stem: &str, title: &str, curves: &[Curve]) -> Panel {
    let series = curves
        .iter()
        .map(|c| {
            let pts = even_points(c.plate.length(), SWEEP)
                .into_iter()
                .map(|x| (x * 1e3, paper.yield_velocity_scaled(&c.plate, c.body, c.cond, x, 1.0)))
                .collect();
            Series::new(c.label.clone(), pts)
        })
        .collect();
    panel(stem, title, "Yield velocity (m/s)", series)
}

pub(super) fn figures(paper: &Paper) -> Vec<Panel> {
    let plate = paper.scene.plate;
    fn cons<'a>(body: &'a Sphere, v: f64, k_t: f64, plate: Plate, prefix: &str) -> Vec<Curve<'a>> {
        (1..=3)
            .map(|n| Curve { plate, body, cond: Paper::condition(n, k_t), v, label: format!("{prefix}Con {n}") })
            .collect()
    }
    let mut out = Vec::new();
    let coal = &paper.coal;
    out.push(yield_panel(
        paper,
        "fig08-yield-coal",
        "Fig. 8 Yield velocity of the coal sphere",
        &cons(coal, 1.0, paper.k_t, plate, ""),
    ));
    out.push(yield_panel(
        paper,
        "fig09-yield-gangue1",
        "Fig. 9 Yield velocity of gangue sphere 1",
        &cons(&paper.gangue1, 1.0, paper.k_t, plate, ""),
    ));
    let all8: Vec<usize> = (0..8).collect();
    out.extend(response_panels(paper, "10", "coal, v = 0.008 m/s", &cons(coal, V_TABLE3, paper.k_t, plate, ""), &all8));

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
    out.push(yield_panel(
        paper,
        "fig11-yield-con2-stiffness",
        "Fig. 11 Yield velocity, Con 2, three k_T",
        &k_curves(2),
    ));
    out.push(yield_panel(
        paper,
        "fig12-yield-con3-stiffness",
        "Fig. 12 Yield velocity, Con 3, three k_T",
        &k_curves(3),
    ));
    let mut k13 = Vec::new();
    for n in [2, 3] {
        for c in k_curves(n) {
            k13.push(Curve { label: format!("Con {n} {}", c.label), ..c });
        }
    }
    out.extend(response_panels(paper, "13", "coal, v = 0.008 m/s, three k_T", &k13, &all8));

    let mut lengths = Vec::new();
    for f in LENGTH_FACTORS {
        let p = plate.with_length(plate.length() * f).expect("positive length");
        lengths.extend(cons(coal, V_TABLE3, K_LENGTH_STUDY, p, &format!("L = {:.1} mm ", p.length() * 1e3)));
    }
    out.extend(response_panels(
        paper,
        "14",
        "coal, v = 0.008 m/s, k_T = 5e6 N/m, four lengths",
        &lengths,
        &[0, 1, 2, 4, 5, 6],
    ));
    let springs: Vec<Curve> = lengths.into_iter().filter(|c| c.cond.spring_stiffness().is_some()).collect();
    for (fig, i) in [("15", 3), ("16", 7)] {
        let mut p = response_panels(paper, fig, "coal, v = 0.008 m/s, k_T = 5e6 N/m, four lengths", &springs, &[i]);
        for q in &mut p {
            q.stem = q.stem.replacen(&format!("fig{fig}-1-"), &format!("fig{fig}-"), 1);
        }
        out.extend(p);
    }

    let mut bodies = Vec::new();
    for b in paper.bodies() {
        bodies.extend(cons(b, V_TABLE6, paper.k_t, plate, &format!("{} ", b.name)));
    }
    out.extend(response_panels(paper, "17", "three spheres, v = 0.0025 m/s", &bodies, &[1, 0, 2, 4, 5, 6]));
    let springs: Vec<Curve> = bodies.into_iter().filter(|c| c.cond.spring_stiffness().is_some()).collect();
    for (fig, i) in [("18", 3), ("19", 7)] {
        let mut p = response_panels(paper, fig, "three spheres, v = 0.0025 m/s", &springs, &[i]);
        for q in &mut p {
            q.stem = q.stem.replacen(&format!("fig{fig}-1-"), &format!("fig{fig}-"), 1);
        }
        out.extend(p);
    }
    // Spring forces and energies span decades when k_T changes (Fig. 13) or soft springs
    // take most of the energy; a log axis keeps every curve visible.
    for p in &mut out {
        if p.stem.starts_with("fig13") && (p.stem.ends_with("spring-energy") || p.stem.ends_with("deflection")) {
            p.scale = Scale::Log;
        }
    }
    out
}
