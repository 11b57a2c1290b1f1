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

use std::fmt::Write as _;
/// A statement's verdict under one model: data of the studies, drawn here by [`Matrix`].
pub use studies::verdict::Verdict;

/// Series with at most this many points get markers: few points joined by lines would read
/// as a measured curve.
pub const MARKER_LIMIT: usize = 30;

/// Distance, as a fraction of the axis span, under which two curves count as coinciding:
/// 0.5 % is 1.5 px on the 300 px axes, less than the 2 px line width, so the eye cannot
/// separate them.
const COINCIDE: f64 = 5e-3;
/// Dash patterns of the curves drawn over a curve they coincide with, so two or three of
/// them on one curve still show apart.
const OVER_DASHES: [&str; 3] = ["8 6", "3 4", "1 3"];

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

// Okabe-Ito's colour-blind-safe eight, then Tableau's remaining distinct hues; beyond these a
// series repeats a colour with another dash pattern and marker.
const PALETTE: [&str; 10] =
    ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#8C564B", "#7F7F7F", "#BCBD22"];
const DASHES: [&str; 3] = ["", "6 3", "2 2"];
const FONT: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";
/// Average advance of a character of the label font, in font sizes (DejaVu Sans is wide).
const CHAR_EM: f64 = 0.6;

fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

fn text_width(s: &str, size: f64) -> f64 {
    s.chars().count() as f64 * size * CHAR_EM
}

/// `n` as Unicode superscript digits (10⁻⁴).
pub fn superscript(n: i32) -> String {
    n.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            '9' => '⁹',
            c => c,
        })
        .collect()
}

/// Ticks of an axis: positions (data values) and labels, all in one format, and the factor
/// moved into the axis label (`×10⁻⁷`), if any.
#[derive(Debug, Clone, PartialEq)]
pub struct Ticks {
    pub major: Vec<(f64, String)>,
    pub minor: Vec<f64>,
    pub factor: Option<String>,
}

/// Round steps 1, 2, 2.5, 5 × 10^k with about `target` intervals over [lo, hi].
fn nice_step(lo: f64, hi: f64, target: f64) -> f64 {
    let raw = (hi - lo) / target;
    let p = 10f64.powf(raw.log10().floor());
    let m = raw / p;
    let m = if m <= 1.0 {
        1.0
    } else if m <= 2.0 {
        2.0
    } else if m <= 2.5 {
        2.5
    } else if m <= 5.0 {
        5.0
    } else {
        10.0
    };
    m * p
}

/// One format for all `values`: a common power of ten when they are very large or small, and
/// the fewest decimals that print every value to 1e-9 of the largest.
pub fn common_format(values: &[f64]) -> (Vec<String>, Option<String>) {
    let big = values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let exp = if big > 0.0 && !(1e-2..1e4).contains(&big) { big.log10().floor() as i32 } else { 0 };
    let scale = 10f64.powi(-exp);
    let scaled: Vec<f64> = values.iter().map(|v| v * scale).collect();
    let top = big * scale;
    let decimals = (0..=8)
        .find(|&d| {
            scaled.iter().all(|v| {
                let s: f64 = format!("{v:.d$}").parse().unwrap_or(f64::NAN);
                (s - v).abs() <= 1e-9 * top.max(f64::MIN_POSITIVE)
            })
        })
        .unwrap_or(8);
    let labels = scaled
        .iter()
        .map(|v| {
            let s = format!("{v:.decimals$}");
            // A tick at zero printed as "-0.0" would read as a negative value.
            if s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
                s.trim_start_matches('-').to_string()
            } else {
                s.replace('-', "−")
            }
        })
        .collect();
    (labels, (exp != 0).then(|| format!("×10{}", superscript(exp))))
}

/// Linear ticks over [lo, hi].
pub fn linear_ticks(lo: f64, hi: f64) -> Ticks {
    let step = nice_step(lo, hi, 5.0);
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    let values: Vec<f64> = (first..=last).map(|k| k as f64 * step).collect();
    let (labels, factor) = common_format(&values);
    Ticks { major: values.into_iter().zip(labels).collect(), minor: vec![], factor }
}

/// Log ticks over [lo, hi] (both > 0): decades when the range spans two or more, else the
/// 1-2-5 (or 1-9) multiples inside it, labelled in one common format.
pub fn log_ticks(lo: f64, hi: f64) -> Ticks {
    let (k0, k1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let inside = |v: f64| v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9);
    let decades: Vec<i32> = (k0..=k1).filter(|&k| inside(10f64.powi(k))).collect();
    let multiples = |ms: &[f64]| -> Vec<f64> {
        (k0..=k1).flat_map(|k| ms.iter().map(move |m| m * 10f64.powi(k))).filter(|&v| inside(v)).collect()
    };
    let minor: Vec<f64> = multiples(&[2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
    if decades.len() >= 2 {
        let every = decades.len().div_ceil(7).max(1) as i32;
        let major = decades
            .iter()
            .filter(|&&k| (k - decades[0]) % every == 0)
            .map(|&k| (10f64.powi(k), format!("10{}", superscript(k))))
            .collect();
        let minor = if (k1 - k0) > 12 { vec![] } else { minor };
        return Ticks { major, minor, factor: None };
    }
    let mut values = multiples(&[1.0, 2.0, 5.0]);
    if values.len() < 4 {
        values = multiples(&[1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 7.0]);
    }
    if values.len() < 4 {
        values = multiples(&[1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
    }
    if values.len() < 3 {
        // Less than a factor of two: linear steps read best, placed on the log axis.
        let t = linear_ticks(lo, hi);
        return Ticks { major: t.major, minor: vec![], factor: t.factor };
    }
    let (labels, factor) = common_format(&values);
    let minor = minor.into_iter().filter(|m| !values.iter().any(|v| (v - m).abs() <= 1e-9 * v)).collect();
    Ticks { major: values.into_iter().zip(labels).collect(), minor, factor }
}

/// Maps data to pixels along one axis.
#[derive(Debug, Clone, Copy)]
struct Map {
    lo: f64,
    hi: f64,
    p0: f64,
    p1: f64,
    log: bool,
}

impl Map {
    fn at(&self, v: f64) -> f64 {
        let (a, b, v) = if self.log { (self.lo.log10(), self.hi.log10(), v.log10()) } else { (self.lo, self.hi, v) };
        self.p0 + (v - a) / (b - a) * (self.p1 - self.p0)
    }
}

/// The data range of an axis: padded by 4 % (linear) or a tenth of a decade (log); a single
/// value gets a range around it.
fn range(values: impl Iterator<Item = f64>, scale: Scale) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    match scale {
        Scale::Linear => {
            if !lo.is_finite() {
                return (0.0, 1.0);
            }
            if hi > lo {
                let d = 0.04 * (hi - lo);
                (lo - d, hi + d)
            } else {
                let d = if lo == 0.0 { 1.0 } else { 0.05 * lo.abs() };
                (lo - d, hi + d)
            }
        }
        Scale::Log => {
            if !lo.is_finite() {
                return (0.1, 10.0);
            }
            if hi > lo {
                let d = 0.04 * (hi / lo).log10().max(0.25);
                (lo / 10f64.powf(d), hi * 10f64.powf(d))
            } else {
                (lo / 2.0, hi * 2.0)
            }
        }
    }
}

fn usable(scale: Scale, v: f64) -> bool {
    v.is_finite() && (scale == Scale::Linear || v > 0.0)
}

fn marker(out: &mut String, shape: usize, x: f64, y: f64, colour: &str) {
    let r = 3.2;
    match shape % 5 {
        0 => {
            let _ = write!(out, r#"<circle cx="{x:.2}" cy="{y:.2}" r="{r}" fill="{colour}"/>"#);
        }
        1 => {
            let _ = write!(
                out,
                r#"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="{colour}"/>"#,
                x - r * 0.9,
                y - r * 0.9,
                1.8 * r,
                1.8 * r
            );
        }
        2 => {
            let _ = write!(
                out,
                r#"<path d="M{:.2},{:.2}L{:.2},{:.2}L{:.2},{:.2}Z" fill="{colour}"/>"#,
                x,
                y - 1.2 * r,
                x + 1.1 * r,
                y + 0.8 * r,
                x - 1.1 * r,
                y + 0.8 * r
            );
        }
        3 => {
            let _ = write!(
                out,
                r#"<path d="M{:.2},{:.2}L{:.2},{:.2}L{:.2},{:.2}L{:.2},{:.2}Z" fill="{colour}"/>"#,
                x,
                y - 1.3 * r,
                x + 1.3 * r,
                y,
                x,
                y + 1.3 * r,
                x - 1.3 * r,
                y
            );
        }
        _ => {
            let _ = write!(
                out,
                r#"<circle cx="{x:.2}" cy="{y:.2}" r="{r}" fill="white" stroke="{colour}" stroke-width="1.5"/>"#
            );
        }
    }
}

/// `o`'s value at `x` by linear interpolation between its points (which must rise in x);
/// `None` outside its range.
fn value_at(o: &[(f64, f64)], x: f64) -> Option<f64> {
    let k = o.partition_point(|p| p.0 < x);
    match (k.checked_sub(1).and_then(|i| o.get(i)), o.get(k)) {
        (_, Some(b)) if b.0 == x => Some(b.1),
        (Some(a), Some(b)) if b.0 > a.0 => Some(a.1 + (x - a.0) / (b.0 - a.0) * (b.1 - a.1)),
        _ => None,
    }
}

/// Index of an earlier drawn series that `s` coincides with, on the plot's scales: every
/// point of `s` within [`COINCIDE`] of the axis span of the other curve (interpolated, so the
/// two need not share their x values) and the two spanning the same x range.
fn coincides_with(series: &[Series], i: usize, x: &Map, y: &Map) -> Option<usize> {
    let fin = |s: &Series| -> Vec<(f64, f64)> {
        s.points.iter().copied().filter(|p| p.0.is_finite() && p.1.is_finite()).collect()
    };
    let rising = |p: &[(f64, f64)]| p.windows(2).all(|w| w[1].0 > w[0].0);
    let s = fin(&series[i]);
    if s.len() < 2 || !rising(&s) {
        return None;
    }
    let span = |m: &Map| (m.p1 - m.p0).abs();
    (0..i).find(|&j| {
        let o = &series[j];
        let op = fin(o);
        if !matches!(o.style, Style::Line | Style::Points) || op.len() < 2 || !rising(&op) {
            return false;
        }
        let ends = |a: f64, b: f64| (x.at(a) - x.at(b)).abs() <= COINCIDE * span(x);
        ends(s[0].0, op[0].0)
            && ends(s[s.len() - 1].0, op[op.len() - 1].0)
            && s.iter().all(|p| {
                let v = value_at(&op, p.0.clamp(op[0].0, op[op.len() - 1].0));
                v.is_some_and(|v| (y.at(p.1) - y.at(v)).abs() <= COINCIDE * span(y))
            })
    })
}

/// Draws the axes frame, ticks, labels and grid of a plot area.
fn axes(out: &mut String, x: &Map, y: &Map, xt: &Ticks, yt: &Ticks) {
    let (l, r, t, b) = (x.p0, x.p1, y.p1, y.p0);
    // Light grid at the major ticks, under everything else.
    for (v, _) in &xt.major {
        let px = x.at(*v);
        let _ = write!(out, r##"<line x1="{px:.2}" y1="{t:.2}" x2="{px:.2}" y2="{b:.2}" stroke="#e6e6e6"/>"##);
    }
    for (v, _) in &yt.major {
        let py = y.at(*v);
        let _ = write!(out, r##"<line x1="{l:.2}" y1="{py:.2}" x2="{r:.2}" y2="{py:.2}" stroke="#e6e6e6"/>"##);
    }
    let _ = write!(
        out,
        r#"<rect x="{l:.2}" y="{t:.2}" width="{:.2}" height="{:.2}" fill="none" stroke="black" stroke-width="1"/>"#,
        r - l,
        b - t
    );
    for (v, label) in &xt.major {
        let px = x.at(*v);
        let _ = write!(
            out,
            r#"<line x1="{px:.2}" y1="{b:.2}" x2="{px:.2}" y2="{:.2}" stroke="black"/><text x="{px:.2}" y="{:.2}" text-anchor="middle" font-size="12">{}</text>"#,
            b + 5.0,
            b + 19.0,
            esc(label)
        );
    }
    for v in &xt.minor {
        let px = x.at(*v);
        let _ = write!(out, r#"<line x1="{px:.2}" y1="{b:.2}" x2="{px:.2}" y2="{:.2}" stroke="black"/>"#, b + 3.0);
    }
    for (v, label) in &yt.major {
        let py = y.at(*v);
        let _ = write!(
            out,
            r#"<line x1="{:.2}" y1="{py:.2}" x2="{l:.2}" y2="{py:.2}" stroke="black"/><text x="{:.2}" y="{:.2}" text-anchor="end" font-size="12">{}</text>"#,
            l - 5.0,
            l - 8.0,
            py + 4.0,
            esc(label)
        );
    }
    for v in &yt.minor {
        let py = y.at(*v);
        let _ = write!(out, r#"<line x1="{:.2}" y1="{py:.2}" x2="{l:.2}" y2="{py:.2}" stroke="black"/>"#, l - 3.0);
    }
}

/// The axis label with the ticks' common factor: into the unit, "C (10⁻⁶ m/N)", or after
/// the label of a dimensionless quantity, "ratio (×10⁻³)".
fn axis_label(a: &Axis, t: &Ticks) -> String {
    let Some(f) = &t.factor else { return a.label.clone() };
    let power = f.trim_start_matches('×');
    match (a.label.rfind('('), a.label.ends_with(')')) {
        (Some(i), true) if !matches!(&a.label[i..], "(log)" | "(rel.)") => {
            format!("{}({power} {}", &a.label[..i], &a.label[i + 1..])
        }
        _ => format!("{} ({f})", a.label),
    }
}

fn svg_open(out: &mut String, w: f64, h: f64) {
    let _ = write!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.2} {h:.2}" font-family="{FONT}"><rect width="100%" height="100%" fill="white"/>"#
    );
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

    /// The SVG document.
    pub fn svg(&self) -> String {
        let (xs, ys) = (self.x.scale, self.y.scale);
        let ok = |&(x, y): &(f64, f64)| usable(xs, x) && usable(ys, y);
        let (xlo, xhi) = range(self.series.iter().flat_map(|s| s.points.iter().filter(|p| ok(p)).map(|p| p.0)), xs);
        let (ylo, yhi) = range(self.series.iter().flat_map(|s| s.points.iter().filter(|p| ok(p)).map(|p| p.1)), ys);
        let ticks = |lo, hi, s| if s == Scale::Log { log_ticks(lo, hi) } else { linear_ticks(lo, hi) };
        let (xt, yt) = (ticks(xlo, xhi, xs), ticks(ylo, yhi, ys));

        // Legend labels, with what a reader must know about each series.
        let (pw, ph) = (480.0, 300.0);
        let ylab_w = yt.major.iter().map(|(_, l)| text_width(l, 12.0)).fold(0.0, f64::max);
        let left = 30.0 + ylab_w + 12.0;
        let top = if self.title.is_empty() { 16.0 } else { 38.0 };
        let x = Map { lo: xlo, hi: xhi, p0: left, p1: left + pw, log: xs == Scale::Log };
        let y = Map { lo: ylo, hi: yhi, p0: top + ph, p1: top, log: ys == Scale::Log };
        let mut notes = self.notes.clone();
        let mut labels = Vec::new();
        let mut coincide = vec![None; self.series.len()];
        for (i, s) in self.series.iter().enumerate() {
            let mut label = s.name.clone();
            if matches!(s.style, Style::Line | Style::Points) {
                coincide[i] = coincides_with(&self.series, i, &x, &y);
            }
            if let Some(j) = coincide[i] {
                label.push_str(&format!(" (dashed: on {})", self.series[j].name));
            }
            let hidden = s.points.iter().filter(|p| p.0.is_finite() && p.1.is_finite() && !ok(p)).count();
            if hidden > 0 {
                label.push_str(&format!(" ({hidden} ≤ 0 not shown)"));
                notes.push(format!(
                    "{}: {hidden} point{} at or below zero cannot be shown on the log axis.",
                    s.name,
                    if hidden == 1 { "" } else { "s" }
                ));
            }
            labels.push(label);
        }
        if coincide.iter().any(Option::is_some) {
            notes.push(format!(
                "A dashed curve lies on the curve it names, within {} % of the axis span; the CSV has the values.",
                COINCIDE * 100.0
            ));
        }
        let named: Vec<usize> = (0..self.series.len()).filter(|&i| !self.series[i].name.is_empty()).collect();
        let widest = named.iter().map(|&i| text_width(&labels[i], 12.0)).fold(0.0, f64::max);
        let legend_right = widest <= 260.0;
        let legend_w = if named.is_empty() { 0.0 } else { widest + 46.0 };
        let width = if legend_right {
            left + pw + legend_w.max(16.0) + 8.0
        } else {
            (left + pw + 24.0).max(left + legend_w + 12.0)
        };
        let xlab_y = top + ph + 40.0;
        let mut cursor = xlab_y + 10.0;
        let legend_top = if legend_right { top } else { cursor + 6.0 };
        if !legend_right {
            cursor += 10.0 + 18.0 * named.len() as f64;
        }
        let note_top = cursor + 6.0;
        let per_line = ((width - 24.0) / (11.0 * CHAR_EM)) as usize;
        let notes: Vec<String> = notes.iter().flat_map(|n| wrap(n, per_line)).collect();
        let height = note_top + 16.0 * notes.len() as f64 + 6.0;

        let mut out = String::new();
        svg_open(&mut out, width, height);
        if !self.title.is_empty() {
            let _ = write!(
                out,
                r#"<text x="{:.2}" y="24" text-anchor="middle" font-size="15">{}</text>"#,
                left + pw / 2.0,
                esc(&self.title)
            );
        }
        axes(&mut out, &x, &y, &xt, &yt);
        let _ = write!(
            out,
            r#"<text x="{:.2}" y="{xlab_y:.2}" text-anchor="middle" font-size="13">{}</text>"#,
            left + pw / 2.0,
            esc(&axis_label(&self.x, &xt))
        );
        let _ = write!(
            out,
            r#"<text transform="translate(14,{:.2}) rotate(-90)" text-anchor="middle" font-size="13">{}</text>"#,
            top + ph / 2.0,
            esc(&axis_label(&self.y, &yt))
        );
        let _ = write!(
            out,
            r#"<clipPath id="area"><rect x="{left:.2}" y="{top:.2}" width="{pw:.2}" height="{ph:.2}"/></clipPath><g clip-path="url(#area)">"#
        );
        let mut colour_of = Vec::new();
        let mut k: usize = 0;
        let mut over = 0;
        for (i, s) in self.series.iter().enumerate() {
            let (colour, dash, width_px, shape) = match s.style {
                Style::Guide => ("#555555", "5 4".to_string(), 1.2, 0),
                Style::Level => (PALETTE[k.saturating_sub(1) % PALETTE.len()], "6 4".to_string(), 1.4, 0),
                _ => {
                    let c = PALETTE[k % PALETTE.len()];
                    let d = DASHES[(k / PALETTE.len()) % DASHES.len()].to_string();
                    k += 1;
                    if coincide[i].is_some() {
                        over += 1;
                        (c, OVER_DASHES[(over - 1) % OVER_DASHES.len()].to_string(), 1.8, k - 1)
                    } else {
                        // Earlier curves a little wider, so a later curve drawn on top of one
                        // it nearly follows leaves a visible rim of it.
                        let lines = self.series.iter().filter(|s| s.style == Style::Line).count();
                        let rank = (k - 1) as f64 / (lines.max(2) - 1) as f64;
                        (c, d, 3.2 - 1.6 * rank.min(1.0), k - 1)
                    }
                }
            };
            colour_of.push((colour, dash.clone(), width_px, shape));
            let pts: Vec<(f64, f64)> = s.points.iter().copied().filter(ok).map(|(a, b)| (x.at(a), y.at(b))).collect();
            let markers = s.style == Style::Points || (s.style == Style::Line && pts.len() <= MARKER_LIMIT);
            if s.style != Style::Points && pts.len() >= 2 {
                // A gap (a value the axis cannot show) breaks the line rather than bridging it.
                let mut d = String::new();
                let mut pen = false;
                for p in &s.points {
                    if ok(p) {
                        let _ = write!(d, "{}{:.2},{:.2}", if pen { "L" } else { "M" }, x.at(p.0), y.at(p.1));
                        pen = true;
                    } else {
                        pen = false;
                    }
                }
                let dash_attr = if dash.is_empty() { String::new() } else { format!(r#" stroke-dasharray="{dash}""#) };
                let _ = write!(
                    out,
                    r#"<path d="{d}" fill="none" stroke="{colour}" stroke-width="{width_px}" stroke-linejoin="round"{dash_attr}/>"#
                );
            }
            if markers {
                for &(px, py) in &pts {
                    marker(&mut out, shape, px, py, colour);
                }
            }
        }
        out.push_str("</g>");

        // The legend, outside the axes.
        let (lx0, mut ly) = if legend_right { (left + pw + 14.0, legend_top + 6.0) } else { (left, legend_top) };
        for &i in &named {
            let s = &self.series[i];
            let (colour, dash, width_px, shape) = &colour_of[i];
            let cy = ly + 8.0;
            if s.style != Style::Points {
                let dash_attr = if dash.is_empty() { String::new() } else { format!(r#" stroke-dasharray="{dash}""#) };
                let _ = write!(
                    out,
                    r#"<line x1="{lx0:.2}" y1="{cy:.2}" x2="{:.2}" y2="{cy:.2}" stroke="{colour}" stroke-width="{width_px}"{dash_attr}/>"#,
                    lx0 + 28.0
                );
            }
            let few = s.points.iter().filter(|p| ok(p)).count() <= MARKER_LIMIT;
            if s.style == Style::Points || (s.style == Style::Line && few) {
                marker(&mut out, *shape, lx0 + 14.0, cy, colour);
            }
            let _ = write!(
                out,
                r#"<text x="{:.2}" y="{:.2}" font-size="12">{}</text>"#,
                lx0 + 34.0,
                cy + 4.0,
                esc(&labels[i])
            );
            ly += 18.0;
        }
        for (n, note) in notes.iter().enumerate() {
            let _ = write!(
                out,
                r##"<text x="{:.2}" y="{:.2}" font-size="11" fill="#444444">{}</text>"##,
                12.0,
                note_top + 12.0 + 16.0 * n as f64,
                esc(note)
            );
        }
        out.push_str("</svg>\n");
        out
    }
}

/// Viridis (matplotlib's perceptually uniform sequential map) at 11 even stops; colours in
/// between interpolate linearly in sRGB, which stays within a few units of the full table.
const VIRIDIS: [[u8; 3]; 11] = [
    [68, 1, 84],
    [72, 36, 117],
    [65, 68, 135],
    [53, 95, 141],
    [42, 120, 142],
    [33, 145, 140],
    [34, 168, 132],
    [68, 191, 112],
    [122, 209, 81],
    [189, 223, 38],
    [253, 231, 37],
];

/// The viridis colour at `t` in [0, 1] (clamped).
pub fn viridis(t: f64) -> [u8; 3] {
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    let f = t * (VIRIDIS.len() - 1) as f64;
    let i = (f.floor() as usize).min(VIRIDIS.len() - 2);
    let u = f - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    [0, 1, 2].map(|k| (a[k] as f64 + u * (b[k] as f64 - a[k] as f64)).round() as u8)
}

/// The colour bar's bands, and the colours a map's cells take.
const BANDS: usize = 100;

/// A pixel coordinate to 0.01 px, without trailing zeros ("63.3", "-0.3", "480").
fn px_num(v: f64) -> String {
    let t = format!("{:.2}", v);
    let t = t.trim_end_matches('0').trim_end_matches('.');
    if t == "-0" {
        "0".into()
    } else {
        t.to_string()
    }
}

fn hex(c: [u8; 3]) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// A mark on a colour map (the impact point, a support).
#[derive(Debug, Clone)]
pub struct Mark {
    pub x: f64,
    pub y: f64,
    pub label: String,
}

/// A colour map of a field over a rectangle, drawn at its true aspect ratio.
#[derive(Debug, Clone)]
pub struct ColourMap {
    pub title: String,
    pub x: Axis,
    pub y: Axis,
    /// Cell centres along x and y (the cells reach halfway to the neighbours, and to the
    /// first and last centre at the border); with `edges`, the cells' edges instead (one
    /// more than the values).
    pub xs: Vec<f64>,
    pub ys: Vec<f64>,
    pub edges: bool,
    /// `values[i][j]` at (`xs[i]`, `ys[j]`); NaN where nothing is shown (drawn grey).
    pub values: Vec<Vec<f64>>,
    /// The colour bar's label (the quantity with its unit) and scale.
    pub bar: Axis,
    /// What the grey cells are, if there are any.
    pub missing: Option<String>,
    pub marks: Vec<Mark>,
    pub notes: Vec<String>,
}

impl ColourMap {
    /// The SVG document.
    pub fn svg(&self) -> String {
        let log = self.bar.scale == Scale::Log;
        let ok = |v: f64| usable(self.bar.scale, v);
        let vals = self.values.iter().flatten().copied().filter(|&v| ok(v));
        let (mut lo, mut hi) = vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
        if !lo.is_finite() {
            (lo, hi) = if log { (1.0, 10.0) } else { (0.0, 1.0) };
        }
        if hi <= lo {
            (lo, hi) =
                if log { (lo / 1.1, hi * 1.1) } else { (lo - 0.5 * lo.abs().max(1.0), hi + 0.5 * hi.abs().max(1.0)) };
        }
        let t_of = |v: f64| if log { (v / lo).ln() / (hi / lo).ln() } else { (v - lo) / (hi - lo) };
        let by_edges = self.edges;
        let edges = |c: &[f64], i: usize| {
            if by_edges {
                return (c[i], c[i + 1]);
            }
            let a = if i == 0 { c[0] } else { 0.5 * (c[i - 1] + c[i]) };
            let b = if i + 1 == c.len() { c[i] } else { 0.5 * (c[i] + c[i + 1]) };
            (a, b)
        };
        let (x0, x1) = (self.xs[0], self.xs[self.xs.len() - 1]);
        let (y0, y1) = (self.ys[0], self.ys[self.ys.len() - 1]);
        // True aspect: one data unit is as long on both axes; the longer side gets 480 px.
        let (sx, sy) = ((x1 - x0).max(f64::MIN_POSITIVE), (y1 - y0).max(f64::MIN_POSITIVE));
        let k = 480.0 / sx.max(sy);
        let (pw, ph) = (sx * k, sy * k);
        let xt = linear_ticks(x0, x1);
        let yt = linear_ticks(y0, y1);
        let ylab_w = yt.major.iter().map(|(_, l)| text_width(l, 12.0)).fold(0.0, f64::max);
        let left = 30.0 + ylab_w + 12.0;
        let top = if self.title.is_empty() { 16.0 } else { 38.0 };
        let x = Map { lo: x0, hi: x1, p0: left, p1: left + pw, log: false };
        let y = Map { lo: y0, hi: y1, p0: top + ph, p1: top, log: false };
        let bt = if log { log_ticks(lo, hi) } else { linear_ticks(lo, hi) };
        let bar_x = left + pw + 24.0;
        let bar_w = 18.0;
        let bar_lab_w = bt.major.iter().map(|(_, l)| text_width(l, 12.0)).fold(0.0, f64::max);
        let bar_title = axis_label(&self.bar, &bt);
        let bar_title_w = text_width(&bar_title, 13.0);
        let width = (bar_x + bar_w + 8.0 + bar_lab_w + 30.0).max(left + pw + 24.0 + 16.0);
        let xlab_y = top + ph + 40.0;
        let mut lines: Vec<String> =
            self.marks.iter().filter(|m| !m.label.is_empty()).map(|m| format!("◇ {}", m.label)).collect();
        if let Some(m) = &self.missing {
            lines.push(format!("grey: {m}"));
        }
        lines.extend(self.notes.iter().cloned());
        let note_top = xlab_y + 10.0;
        let per_line = ((width - 24.0) / (11.0 * CHAR_EM)) as usize;
        let lines: Vec<String> = lines.iter().flat_map(|n| wrap(n, per_line)).collect();
        let height = (note_top + 16.0 * lines.len() as f64 + 8.0).max(top + ph + 30.0);
        // The bar's title runs along the bar, so it needs the bar's height, not width.
        let _ = bar_title_w;

        let mut out = String::new();
        svg_open(&mut out, width, height);
        if !self.title.is_empty() {
            let _ = write!(
                out,
                r#"<text x="{:.2}" y="24" text-anchor="middle" font-size="15">{}</text>"#,
                (left + width - 10.0) / 2.0,
                esc(&self.title)
            );
        }
        let _ = write!(
            out,
            r#"<clipPath id="field"><rect x="{left:.2}" y="{top:.2}" width="{pw:.2}" height="{ph:.2}"/></clipPath><g clip-path="url(#field)">"#
        );
        // Each cell takes the colour of the colour bar's band its value falls in (the bar is
        // the legend of these colours, so the map shows no more than the bar can read back).
        // Runs of one band down a column are one rectangle, equal runs in neighbouring
        // columns widen it, and the rectangles of one colour are one path: a smooth field
        // draws in a few thousand path commands, not one element per cell.
        let (nx, ny) = (self.values.len(), self.values.first().map_or(0, Vec::len));
        let colour_of = |v: f64| -> String {
            if ok(v) {
                let band = (t_of(v).clamp(0.0, 1.0) * BANDS as f64).floor().min(BANDS as f64 - 1.0);
                hex(viridis((band + 0.5) / BANDS as f64))
            } else {
                "#c8c8c8".into()
            }
        };
        // Rectangles still open for widening: (first row, last row, colour, first column).
        let mut open: Vec<(usize, usize, String, usize)> = Vec::new();
        let mut paths: Vec<(String, String)> = Vec::new();
        let mut emit = |(j0, j1, colour, i0): (usize, usize, String, usize), i1: usize| {
            let (a, _) = edges(&self.xs, i0);
            let (_, b) = edges(&self.xs, i1);
            let (c, _) = edges(&self.ys, j0);
            let (_, d) = edges(&self.ys, j1);
            // Each a little oversized so anti-aliasing leaves no hairline seams.
            let (px, py) = (x.at(a) - 0.3, y.at(d) - 0.3);
            let (w, h) = (x.at(b) - x.at(a) + 0.6, y.at(c) - y.at(d) + 0.6);
            let d = format!("M{},{}h{}v{}h{}z", px_num(px), px_num(py), px_num(w), px_num(h), px_num(-w));
            match paths.iter_mut().find(|(f, _)| *f == colour) {
                Some((_, path)) => path.push_str(&d),
                None => paths.push((colour, d)),
            }
        };
        for i in 0..=nx {
            let mut runs: Vec<(usize, usize, String)> = Vec::new();
            if i < nx {
                let mut j = 0;
                while j < ny {
                    let colour = colour_of(self.values[i][j]);
                    let mut k = j + 1;
                    while k < ny && colour_of(self.values[i][k]) == colour {
                        k += 1;
                    }
                    runs.push((j, k - 1, colour));
                    j = k;
                }
            }
            let mut still = Vec::with_capacity(runs.len());
            for r in open.drain(..) {
                match runs.iter().position(|(j0, j1, c)| (*j0, *j1, c) == (r.0, r.1, &r.2)) {
                    Some(p) => {
                        runs.remove(p);
                        still.push(r);
                    }
                    None => emit(r, i - 1),
                }
            }
            still.extend(runs.into_iter().map(|(j0, j1, c)| (j0, j1, c, i)));
            open = still;
        }
        for (fill, d) in &paths {
            let _ = write!(out, r#"<path fill="{fill}" d="{d}"/>"#);
        }
        out.push_str("</g>");
        let _ = write!(
            out,
            r#"<rect x="{left:.2}" y="{top:.2}" width="{pw:.2}" height="{ph:.2}" fill="none" stroke="black"/>"#
        );
        for (v, label) in &xt.major {
            let px = x.at(*v);
            let b = top + ph;
            let _ = write!(
                out,
                r#"<line x1="{px:.2}" y1="{b:.2}" x2="{px:.2}" y2="{:.2}" stroke="black"/><text x="{px:.2}" y="{:.2}" text-anchor="middle" font-size="12">{}</text>"#,
                b + 5.0,
                b + 19.0,
                esc(label)
            );
        }
        for (v, label) in &yt.major {
            let py = y.at(*v);
            let _ = write!(
                out,
                r#"<line x1="{:.2}" y1="{py:.2}" x2="{left:.2}" y2="{py:.2}" stroke="black"/><text x="{:.2}" y="{:.2}" text-anchor="end" font-size="12">{}</text>"#,
                left - 5.0,
                left - 8.0,
                py + 4.0,
                esc(label)
            );
        }
        let _ = write!(
            out,
            r#"<text x="{:.2}" y="{xlab_y:.2}" text-anchor="middle" font-size="13">{}</text>"#,
            left + pw / 2.0,
            esc(&axis_label(&self.x, &xt))
        );
        let _ = write!(
            out,
            r#"<text transform="translate(14,{:.2}) rotate(-90)" text-anchor="middle" font-size="13">{}</text>"#,
            top + ph / 2.0,
            esc(&axis_label(&self.y, &yt))
        );
        for m in &self.marks {
            let (px, py) = (x.at(m.x), y.at(m.y));
            let r = 5.0;
            let _ = write!(
                out,
                r#"<path d="M{:.2},{:.2}L{:.2},{:.2}L{:.2},{:.2}L{:.2},{:.2}Z" fill="none" stroke="white" stroke-width="3"/><path d="M{:.2},{:.2}L{:.2},{:.2}L{:.2},{:.2}L{:.2},{:.2}Z" fill="none" stroke="black" stroke-width="1.5"/>"#,
                px,
                py - r,
                px + r,
                py,
                px,
                py + r,
                px - r,
                py,
                px,
                py - r,
                px + r,
                py,
                px,
                py + r,
                px - r,
                py
            );
        }
        // The colour bar: its bands, ticks in the quantity itself.
        let bmap = Map { lo, hi, p0: top + ph, p1: top, log };
        let bands = BANDS;
        for n in 0..bands {
            let (ta, tb) = (n as f64 / bands as f64, (n + 1) as f64 / bands as f64);
            let (ya, yb) = (top + ph - ta * ph, top + ph - tb * ph);
            let _ = write!(
                out,
                r#"<rect x="{bar_x:.2}" y="{:.2}" width="{bar_w}" height="{:.2}" fill="{}"/>"#,
                yb - 0.3,
                ya - yb + 0.6,
                hex(viridis(0.5 * (ta + tb)))
            );
        }
        let _ = write!(
            out,
            r#"<rect x="{bar_x:.2}" y="{top:.2}" width="{bar_w}" height="{ph:.2}" fill="none" stroke="black"/>"#
        );
        for (v, label) in &bt.major {
            let py = bmap.at(*v);
            let _ = write!(
                out,
                r#"<line x1="{:.2}" y1="{py:.2}" x2="{:.2}" y2="{py:.2}" stroke="black"/><text x="{:.2}" y="{:.2}" font-size="12">{}</text>"#,
                bar_x + bar_w,
                bar_x + bar_w + 5.0,
                bar_x + bar_w + 8.0,
                py + 4.0,
                esc(label)
            );
        }
        for v in &bt.minor {
            let py = bmap.at(*v);
            let _ = write!(
                out,
                r#"<line x1="{:.2}" y1="{py:.2}" x2="{:.2}" y2="{py:.2}" stroke="black"/>"#,
                bar_x + bar_w,
                bar_x + bar_w + 3.0
            );
        }
        let _ = write!(
            out,
            r#"<text transform="translate({:.2},{:.2}) rotate(-90)" text-anchor="middle" font-size="13">{}</text>"#,
            bar_x + bar_w + 8.0 + bar_lab_w + 18.0,
            top + ph / 2.0,
            esc(&bar_title)
        );
        for (n, line) in lines.iter().enumerate() {
            let _ = write!(
                out,
                r##"<text x="12" y="{:.2}" font-size="11" fill="#444444">{}</text>"##,
                note_top + 12.0 + 16.0 * n as f64,
                esc(line)
            );
        }
        out.push_str("</svg>\n");
        out
    }
}

/// A yes/no matrix: rows (statements) against columns (models), each cell a verdict.
#[derive(Debug, Clone)]
pub struct Matrix {
    pub title: String,
    pub columns: Vec<String>,
    pub rows: Vec<String>,
    /// cells[row][column]: the statement's verdict under the column's model.
    pub cells: Vec<Vec<Verdict>>,
}

/// `text` broken at spaces into lines of at most `width` characters.
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines: Vec<String> = vec![];
    let mut line = String::new();
    for word in text.split(' ') {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > width {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    lines.push(line);
    lines
}

impl Matrix {
    /// The SVG document: green "yes", orange "no", sky blue "not resolved" (colour-blind-safe
    /// colours, and the words say it too); long statements wrap.
    pub fn svg(&self) -> String {
        const WRAP: usize = 70;
        let rows: Vec<Vec<String>> = self.rows.iter().map(|r| wrap(r, WRAP)).collect();
        let row_w = rows.iter().flatten().map(|r| text_width(r, 12.0)).fold(0.0, f64::max) + 16.0;
        let col_w = self.columns.iter().map(|c| text_width(c, 12.0)).fold(56.0, f64::max) + 16.0;
        let top = if self.title.is_empty() { 30.0 } else { 52.0 };
        let heights: Vec<f64> = rows.iter().map(|r| 15.0 * r.len() as f64 + 8.0).collect();
        let width = row_w + col_w * self.columns.len() as f64 + 12.0;
        let height = top + heights.iter().sum::<f64>() + 12.0;
        let mut out = String::new();
        svg_open(&mut out, width, height);
        if !self.title.is_empty() {
            let _ = write!(out, r#"<text x="12" y="22" font-size="15">{}</text>"#, esc(&self.title));
        }
        for (c, name) in self.columns.iter().enumerate() {
            let _ = write!(
                out,
                r#"<text x="{:.2}" y="{:.2}" text-anchor="middle" font-size="12" font-weight="bold">{}</text>"#,
                row_w + col_w * (c as f64 + 0.5),
                top - 8.0,
                esc(name)
            );
        }
        let mut y = top;
        for (r, lines) in rows.iter().enumerate() {
            let h = heights[r];
            if r % 2 == 1 {
                let _ = write!(out, r##"<rect x="0" y="{y:.2}" width="{row_w:.2}" height="{h:.2}" fill="#f4f4f4"/>"##);
            }
            for (k, line) in lines.iter().enumerate() {
                let _ = write!(
                    out,
                    r#"<text x="8" y="{:.2}" font-size="12">{}</text>"#,
                    y + 4.0 + 12.0 + 15.0 * k as f64,
                    esc(line)
                );
            }
            for (c, v) in self.cells[r].iter().enumerate() {
                let word = v.word();
                let (fill, ink) = match v {
                    Verdict::Holds => ("#009E73", "white"),
                    Verdict::Fails => ("#E69F00", "black"),
                    Verdict::NotResolved => ("#56B4E9", "black"),
                    Verdict::NotTested => ("#eeeeee", "#555555"),
                };
                let x = row_w + col_w * c as f64;
                let _ = write!(
                    out,
                    r#"<rect x="{x:.2}" y="{y:.2}" width="{col_w:.2}" height="{h:.2}" fill="{fill}" stroke="white" stroke-width="2"/><text x="{:.2}" y="{:.2}" text-anchor="middle" font-size="12" font-weight="bold" fill="{ink}">{word}</text>"#,
                    x + col_w / 2.0,
                    y + h / 2.0 + 4.0
                );
            }
            y += h;
        }
        out.push_str("</svg>\n");
        out
    }
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
