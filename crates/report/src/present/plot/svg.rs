//! What every figure shares: the palette, text metrics, the data-to-pixel map, axes with
//! their ticks and labels, markers, and the test of two curves coinciding.

use super::ticks::Ticks;
use super::{Axis, Scale, Series, Style};
use std::fmt::Write as _;

// Okabe-Ito's colour-blind-safe eight, then Tableau's remaining distinct hues; beyond these a
// series repeats a colour with another dash pattern and marker.
pub(super) const PALETTE: [&str; 10] =
    ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#8C564B", "#7F7F7F", "#BCBD22"];
pub(super) const DASHES: [&str; 3] = ["", "6 3", "2 2"];
pub(super) const FONT: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";
/// Average advance of a character of the label font, in font sizes (DejaVu Sans is wide).
pub(super) const CHAR_EM: f64 = 0.6;

pub(super) fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

pub(super) fn text_width(s: &str, size: f64) -> f64 {
    s.chars().count() as f64 * size * CHAR_EM
}

/// Distance, as a fraction of the axis span, under which two curves count as coinciding:
/// 0.5 % is 1.5 px on the 300 px axes, less than the 2 px line width, so the eye cannot
/// separate them.
pub(super) const COINCIDE: f64 = 5e-3;

/// Maps data to pixels along one axis.
#[derive(Debug, Clone, Copy)]
pub(super) struct Map {
    pub(super) lo: f64,
    pub(super) hi: f64,
    pub(super) p0: f64,
    pub(super) p1: f64,
    pub(super) log: bool,
}

impl Map {
    pub(super) fn at(&self, v: f64) -> f64 {
        let (a, b, v) = if self.log { (self.lo.log10(), self.hi.log10(), v.log10()) } else { (self.lo, self.hi, v) };
        self.p0 + (v - a) / (b - a) * (self.p1 - self.p0)
    }
}

/// The data range of an axis: padded by 4 % (linear) or a tenth of a decade (log); a single
/// value gets a range around it.
pub(super) fn range(values: impl Iterator<Item = f64>, scale: Scale) -> (f64, f64) {
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

pub(super) fn usable(scale: Scale, v: f64) -> bool {
    v.is_finite() && (scale == Scale::Linear || v > 0.0)
}

pub(super) fn marker(out: &mut String, shape: usize, x: f64, y: f64, colour: &str) {
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
pub(super) fn value_at(o: &[(f64, f64)], x: f64) -> Option<f64> {
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
pub(super) fn coincides_with(series: &[Series], i: usize, x: &Map, y: &Map) -> Option<usize> {
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

/// The major ticks of `xt` on the x axis `x` below the baseline `b`, with their labels.
pub(super) fn x_tick_marks(out: &mut String, x: &Map, xt: &Ticks, b: f64) {
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
}

/// Draws the axes frame, ticks, labels and grid of a plot area.
pub(super) fn axes(out: &mut String, x: &Map, y: &Map, xt: &Ticks, yt: &Ticks) {
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
    x_tick_marks(out, x, xt, b);
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
pub(super) fn axis_label(a: &Axis, t: &Ticks) -> String {
    let Some(f) = &t.factor else { return a.label.clone() };
    let power = f.trim_start_matches('×');
    match (a.label.rfind('('), a.label.ends_with(')')) {
        (Some(i), true) if !matches!(&a.label[i..], "(log)" | "(rel.)") => {
            format!("{}({power} {}", &a.label[..i], &a.label[i + 1..])
        }
        _ => format!("{} ({f})", a.label),
    }
}

pub(super) fn svg_open(out: &mut String, w: f64, h: f64) {
    let _ = write!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.2} {h:.2}" font-family="{FONT}"><rect width="100%" height="100%" fill="white"/>"#
    );
}

/// `text` broken at spaces into lines of at most `width` characters.
pub(super) fn wrap(text: &str, width: usize) -> Vec<String> {
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
