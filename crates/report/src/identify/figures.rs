//! A support set's figures: the placement maps (separability over the candidate grid) and the
//! histograms of coal's and gangue's values of the best feature and of P_max.

use crate::present::plot::{line_plot, Axis, ColourMap, Scale, Series};
use output::Artifacts;
use studies::identify::{ClassValues, ConditionDetail, PlacementMap};

/// Histogram bins.
const BINS: usize = 30;

/// The histogram of coal and gangue values of one column as two curves of the fraction of
/// each class per bin; a scale on a log10 axis when all its values are positive.
fn histogram(title: &str, v: &ClassValues) -> String {
    let (coal, gangue) = (&v.coal, &v.gangue);
    let log = v.scale && coal.iter().chain(gangue).all(|v| *v > 0.0);
    let t = |v: f64| if log { v.log10() } else { v };
    let (lo, hi) =
        coal.iter().chain(gangue).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(t(v)), b.max(t(v))));
    let (lo, hi) = if lo.is_finite() && hi > lo { (lo, hi) } else { (lo.min(0.0), lo.max(0.0) + 1.0) };
    let width = (hi - lo) / BINS as f64;
    let curve = |vals: &[f64]| -> Vec<(f64, f64)> {
        let mut counts = vec![0.0; BINS];
        for &v in vals {
            let k = (((t(v) - lo) / width) as usize).min(BINS - 1);
            counts[k] += 1.0;
        }
        let n = vals.len().max(1) as f64;
        counts.iter().enumerate().map(|(k, c)| (lo + (k as f64 + 0.5) * width, c / n)).collect()
    };
    let x_label = if log { format!("log10 {}", v.label) } else { v.label.clone() };
    line_plot(
        title,
        &x_label,
        "fraction of the class per bin",
        &[Series::new("coal", curve(coal)), Series::new("gangue", curve(gangue))],
        Scale::Linear,
    )
}

/// One placement map of support set `set`.
fn map_svg(set: &str, m: &PlacementMap) -> String {
    ColourMap {
        title: format!("{set}: separability of {} {}", m.quantity, m.feature.name()),
        x: Axis::linear("x (mm)"),
        y: Axis::linear("z (mm)"),
        xs: m.x_mm.clone(),
        ys: m.z_mm.clone(),
        edges: false,
        values: m.separability.clone(),
        bar: Axis::linear("max(AUC, 1 - AUC)"),
        missing: None,
        marks: vec![],
        notes: vec![],
    }
    .svg()
}

/// The figures of support set `set` (file names start with `stem`) into `artifacts`; returns
/// the Markdown of its maps and of its histograms.
pub(super) fn figures(set: &str, stem: &str, d: &ConditionDetail, artifacts: &mut Artifacts) -> (String, String) {
    let mut maps = String::new();
    for m in &d.maps {
        let file = format!("{stem}-map-{}.svg", m.quantity);
        maps.push_str(&format!("![{} map]({file})\n\n", m.quantity));
        artifacts.add(file, map_svg(set, m));
    }
    let mut hists = String::new();
    if let Some(best) = &d.best {
        let file = format!("{stem}-hist-best.svg");
        artifacts.add(&file, histogram(&format!("{set}: best feature"), best));
        hists.push_str(&format!("![best feature]({file})\n\n"));
    }
    let file = format!("{stem}-hist-force.svg");
    artifacts.add(&file, histogram(&format!("{set}: contact force"), &d.force_max));
    hists.push_str(&format!("![contact force]({file})\n\n"));
    (maps, hists)
}
