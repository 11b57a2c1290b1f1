//! The transient study's figures: the force histories against the quasi-static P_max, the
//! energy split over time, the contact laws' forces, and the quasi-static error over t_c/T₁.

use crate::present::plot::{line_plot, Axis, Plot, Scale, Series};
use coupled::transient::{Outcome, Sample};
use studies::transient::size_map::{SizeRow, SCALES};
use studies::transient::{LawCase, TransientCase};

/// The contact force histories of the first support set, body and velocity at every
/// transient point, each with its quasi-static plate P_max (dashed, same colour), beside the
/// Hertz history of the same sphere on a rigid target (the stiff limit), `rigid`.
pub fn history_figure(cases: &[TransientCase], rigid: &[Sample]) -> Plot {
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
    if !rigid.is_empty() {
        plot = plot.with(Series::guide("Hertz, rigid target", rigid.iter().map(|s| (s.t * 1e3, s.force)).collect()));
    }
    plot.note(format!(
        "{}, {} at {} m/s. Dashed: the quasi-static plate's P_max of the curve above it, drawn up to the transient maximum compression.",
        first.condition, first.body, first.velocity
    ))
}

/// Transient against quasi-static P_max (Kδ_max^{3/2}) over t_c/T₁: the size map's plates
/// (lines, one per plate size, thickness varying along each) and the scene's own cases
/// (points), with the quasi-static criterion t_c/T₁ = 0.2 and the ratio 1 as guides.
pub fn ratio_figure(size_map: &[Series], cases: &[TransientCase]) -> Plot {
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

/// The size map's plates as one line per plate size, thickness varying along each.
pub fn size_series(rows: &[SizeRow]) -> Vec<Series> {
    SCALES
        .iter()
        .map(|&scale| {
            let pts = rows.iter().filter(|r| r.scale == scale).filter_map(SizeRow::point).collect();
            Series::new(format!("{scale} x the paper's L and B"), pts)
        })
        .collect()
}

/// The energy split of a case's whole run, each part over E₀, against t in ms.
pub fn energy_figure(c: &TransientCase) -> String {
    let o = c.outcome();
    let ms = |t: f64| t * 1e3;
    let e0 = 0.5 * c.sphere_mass * c.velocity * c.velocity;
    let energies = vec![
        whole_run(o, "sphere kinetic", ms, |s| s.sphere_kinetic / e0),
        whole_run(o, "contact (elastic)", ms, |s| s.contact / e0),
        whole_run(o, "plate kinetic", ms, |s| s.plate_kinetic / e0),
        whole_run(o, "plate strain", ms, |s| s.plate_strain / e0),
        whole_run(o, "springs", ms, |s| s.springs / e0),
        whole_run(o, "dissipated", ms, |s| s.dissipated / e0),
    ];
    line_plot("Energy split over time (first case of the table), / E₀", "t (ms)", "E / E₀", &energies, Scale::Linear)
}

/// The contact force of each of `runs` against t over its own Hertz time, at `top` x v_y.
pub fn laws_figure(runs: &[&LawCase], top: f64) -> String {
    let series: Vec<Series> =
        runs.iter().map(|c| whole_run(&c.estimate.outcome, c.law.key(), |t| t / c.hertz_time, |s| s.force)).collect();
    line_plot(
        &format!("Contact force at {top} x v_y, the three laws"),
        "t / t_H (Hertz time)",
        "P (N)",
        &series,
        Scale::Linear,
    )
}

/// A series over the whole run (every contact) of one sampled quantity.
fn whole_run(o: &Outcome, name: &str, x: impl Fn(f64) -> f64, f: impl Fn(&Sample) -> f64) -> Series {
    Series::new(name, o.history.iter().chain(&o.later_history).map(|s| (x(s.t), f(s))).collect())
}
