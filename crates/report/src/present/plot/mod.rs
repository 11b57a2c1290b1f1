//! Figures as SVG, written directly: line plots and colour maps.
//!
//! Why not plotters: its SVG backend snaps every coordinate to whole pixels (its backend
//! coordinate is `(i32, i32)`), which draws smooth curves as staircases; its legend is drawn
//! inside the plotting area, over the data; its tick labels have no per-axis format; it has
//! no colour bar. A figure here is a few hundred `<path>`/`<rect>`/`<text>` elements, so the
//! module writes them itself with coordinates to 0.01 px, and owns the rules a figure for a
//! paper needs:
//!
//! - the legend sits outside the data (right of the axes, or below when the labels are long);
//! - a series of few points (≤ [`MARKER_LIMIT`]) carries markers;
//! - every tick label of an axis has one format: the same number of decimals, and one
//!   common power of ten moved into the axis label when the numbers are very large or small;
//! - a log axis labels decades (10⁻⁴) or, inside one decade, 1-2-5 values, and a point at or
//!   below zero, which a log axis cannot show, is counted in a note under the figure;
//! - a curve that coincides with an earlier one (within 0.2 % of the axis span at every
//!   point) is drawn dashed over it and says so in the legend;
//! - colour maps use viridis (perceptually uniform, sequential, readable in grey), keep the
//!   true aspect ratio of the plate, and label their colour bar in the plotted quantity itself
//!   (a log colour scale still shows 1.2, 1.5, 2, not log10 values).

mod colour_map;
mod line;
mod matrix;
mod svg;
mod ticks;

pub use colour_map::{viridis, ColourMap, Mark};
pub use matrix::Matrix;
/// A statement's verdict under one model: data of the studies, drawn here by [`Matrix`].
pub use studies::verdict::Verdict;
pub use ticks::{common_format, linear_ticks, log_ticks, superscript, Ticks};

/// Series with at most this many points get markers: few points joined by lines would read
/// as a measured curve.
pub const MARKER_LIMIT: usize = 30;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// A line; markers too when the series has few points.
    Line,
    /// Markers only (measured or sampled points that a line would over-interpret).
    Points,
    /// A thin dashed grey reference (a slope guide, a closed form, a limit).
    Guide,
    /// A dashed line in the colour of the series before it: a value that belongs to that
    /// curve (its quasi-static counterpart, its limit).
    Level,
}

/// A named series of (x, y) points.
#[derive(Debug, Clone)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
}

impl Series {
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { name: name.into(), points, style: Style::Line }
    }
    /// Markers only.
    pub fn points(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { name: name.into(), points, style: Style::Points }
    }
    /// A dashed line in the previous series' colour.
    pub fn level(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { name: name.into(), points, style: Style::Level }
    }
    /// A dashed reference line.
    pub fn guide(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { name: name.into(), points, style: Style::Guide }
    }
}

/// The curves of a plot as long-format CSV: series, x, value (`x_name` names the x column
/// with its unit, e.g. `x_mm`).
pub fn series_csv(series: &[Series], x_name: &str, y_name: &str) -> String {
    let mut t = crate::present::table::Table::new("", &["series", x_name, y_name]);
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

/// An axis: its label (with the unit) and scale.
#[derive(Debug, Clone)]
pub struct Axis {
    pub label: String,
    pub scale: Scale,
}

impl Axis {
    pub fn linear(label: impl Into<String>) -> Self {
        Self { label: label.into(), scale: Scale::Linear }
    }
    pub fn log(label: impl Into<String>) -> Self {
        Self { label: label.into(), scale: Scale::Log }
    }
}

/// A line plot.
#[derive(Debug, Clone)]
pub struct Plot {
    pub title: String,
    pub x: Axis,
    pub y: Axis,
    pub series: Vec<Series>,
    /// Sentences printed under the figure (what a reader must know to read it).
    pub notes: Vec<String>,
}

impl Plot {
    pub fn new(title: impl Into<String>, x: Axis, y: Axis) -> Self {
        Self { title: title.into(), x, y, series: vec![], notes: vec![] }
    }

    pub fn with(mut self, s: Series) -> Self {
        self.series.push(s);
        self
    }

    pub fn note(mut self, n: impl Into<String>) -> Self {
        self.notes.push(n.into());
        self
    }
}

/// A line plot of `series` with a linear x axis, as an SVG document.
pub fn line_plot(title: &str, x_label: &str, y_label: &str, series: &[Series], y_scale: Scale) -> String {
    Plot {
        title: title.into(),
        x: Axis::linear(x_label),
        y: Axis { label: y_label.into(), scale: y_scale },
        series: series.to_vec(),
        notes: vec![],
    }
    .svg()
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
