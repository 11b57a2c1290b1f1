//! SVG line plots (plotters), one panel per file.

use plotters::prelude::*;

/// A named series of (x, y) points.
#[derive(Debug, Clone)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
}

impl Series {
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { name: name.into(), points }
    }
}

/// The curves of a plot as long-format CSV: series, x_mm, value.
pub fn series_csv(series: &[Series]) -> String {
    let mut t = crate::present::table::Table::new("", &["series", "x_mm", "value"]);
    for s in series {
        for &(x, y) in &s.points {
            t.push(vec![s.name.clone().into(), x.into(), y.into()]);
        }
    }
    t.to_csv()
}

/// Axis scaling.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    Linear,
    Log,
}

/// A line plot of `series` as an SVG document.
pub fn line_plot(title: &str, x_label: &str, y_label: &str, series: &[Series], y_scale: Scale) -> String {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (720, 440)).into_drawing_area();
        root.fill(&WHITE).expect("drawing to memory");
        let all = || series.iter().flat_map(|s| s.points.iter()).filter(|(x, y)| x.is_finite() && y.is_finite());
        let (mut x0, mut x1) = all().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &(x, _)| (a.min(x), b.max(x)));
        let positive = |y: f64| y_scale == Scale::Linear || y > 0.0;
        let (mut y0, mut y1) = all()
            .filter(|(_, y)| positive(*y))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &(_, y)| (a.min(y), b.max(y)));
        if !x0.is_finite() {
            (x0, x1) = (0.0, 1.0);
        }
        if !y0.is_finite() {
            (y0, y1) = (if y_scale == Scale::Log { 1e-12 } else { 0.0 }, 1.0);
        }
        if x1 <= x0 {
            x1 = x0 + 1.0;
        }
        let pad = |lo: f64, hi: f64| {
            if hi > lo {
                let d = (hi - lo) * 0.05;
                (lo - d, hi + d)
            } else {
                let d = if lo == 0.0 { 1.0 } else { lo.abs() * 0.05 };
                (lo - d, hi + d)
            }
        };
        // Twelve distinguishable colours (Tableau 10 plus two), enough for 4 lengths x 3 conditions.
        let palette = [
            RGBColor(31, 119, 180),
            RGBColor(255, 127, 14),
            RGBColor(44, 160, 44),
            RGBColor(214, 39, 40),
            RGBColor(148, 103, 189),
            RGBColor(140, 86, 75),
            RGBColor(227, 119, 194),
            RGBColor(127, 127, 127),
            RGBColor(188, 189, 34),
            RGBColor(23, 190, 207),
            RGBColor(0, 0, 0),
            RGBColor(0, 0, 128),
        ];
        let mut chart_builder = ChartBuilder::on(&root);
        chart_builder.caption(title, ("sans-serif", 18)).margin(12).x_label_area_size(40).y_label_area_size(80);
        macro_rules! draw {
            ($chart:expr) => {{
                let mut chart = $chart;
                chart
                    .configure_mesh()
                    .x_desc(x_label)
                    .y_desc(y_label)
                    .y_label_formatter(&|v| crate::present::table::sig(*v, 3))
                    .x_label_formatter(&|v| crate::present::table::sig(*v, 3))
                    .draw()
                    .expect("drawing to memory");
                for (i, s) in series.iter().enumerate() {
                    let color = palette[i % palette.len()];
                    let pts: Vec<(f64, f64)> = s
                        .points
                        .iter()
                        .copied()
                        .filter(|(x, y)| x.is_finite() && y.is_finite() && positive(*y))
                        .collect();
                    chart
                        .draw_series(LineSeries::new(pts, color.stroke_width(2)))
                        .expect("drawing to memory")
                        .label(s.name.clone())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
                }
                chart
                    .configure_series_labels()
                    .background_style(WHITE.mix(0.85))
                    .border_style(BLACK)
                    .draw()
                    .expect("drawing to memory");
            }};
        }
        let (xa, xb) = pad(x0, x1);
        match y_scale {
            Scale::Linear => {
                let (ya, yb) = pad(y0, y1);
                draw!(chart_builder.build_cartesian_2d(xa..xb, ya..yb).expect("valid ranges"))
            }
            Scale::Log => {
                let (ya, yb) = if y1 > y0 { (y0 / 1.5, y1 * 1.5) } else { (y0 / 10.0, y0 * 10.0) };
                draw!(chart_builder.build_cartesian_2d(xa..xb, (ya..yb).log_scale()).expect("valid ranges"))
            }
        }
        root.present().expect("drawing to memory");
    }
    svg
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plot_is_svg_with_legend() {
        let s = vec![
            Series::new("Con 1", vec![(0.0, 1.0), (1.0, 2.0)]),
            Series::new("Con 2", vec![(0.0, 2.0), (1.0, 1.0)]),
        ];
        let svg = line_plot("t", "x", "y", &s, Scale::Linear);
        assert!(svg.starts_with("<svg"));
        assert!(svg.contains("Con 2"));
    }

    #[test]
    fn degenerate_data_does_not_panic() {
        let s = vec![Series::new("flat", vec![(0.0, 0.0), (0.0, 0.0)]), Series::new("nan", vec![(f64::NAN, 1.0)])];
        line_plot("t", "x", "y", &s, Scale::Linear);
        line_plot("t", "x", "y", &s, Scale::Log);
        line_plot("t", "x", "y", &[], Scale::Linear);
    }
}
