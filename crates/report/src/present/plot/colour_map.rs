//! The colour map's SVG: a field over a rectangle at its true aspect ratio, its cells in the
//! colour bar's bands (runs of one band merged into few paths), marks, and the colour bar
//! labelled in the quantity itself.

use super::svg::{axis_label, esc, svg_open, text_width, usable, wrap, x_tick_marks, Map, CHAR_EM};
use super::ticks::{linear_ticks, log_ticks, Ticks};
use super::{Axis, Scale};
use std::fmt::Write as _;

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

/// Where everything of a colour map goes.
struct Layout {
    x: Map,
    y: Map,
    xt: Ticks,
    yt: Ticks,
    /// The colour bar's range, scale and ticks.
    bar: Map,
    bt: Ticks,
    left: f64,
    top: f64,
    pw: f64,
    ph: f64,
    width: f64,
    height: f64,
    xlab_y: f64,
    bar_x: f64,
    bar_lab_w: f64,
    note_top: f64,
    /// The lines under the map (marks, grey cells, notes), wrapped.
    lines: Vec<String>,
}

/// The colour bar's width, px.
const BAR_W: f64 = 18.0;

impl ColourMap {
    /// The SVG document.
    pub fn svg(&self) -> String {
        let l = self.layout();
        let mut out = String::new();
        svg_open(&mut out, l.width, l.height);
        if !self.title.is_empty() {
            let _ = write!(
                out,
                r#"<text x="{:.2}" y="24" text-anchor="middle" font-size="15">{}</text>"#,
                (l.left + l.width - 10.0) / 2.0,
                esc(&self.title)
            );
        }
        let (left, top, pw, ph) = (l.left, l.top, l.pw, l.ph);
        let _ = write!(
            out,
            r#"<clipPath id="field"><rect x="{left:.2}" y="{top:.2}" width="{pw:.2}" height="{ph:.2}"/></clipPath><g clip-path="url(#field)">"#
        );
        self.cells(&mut out, &l);
        out.push_str("</g>");
        self.frame(&mut out, &l);
        self.marks(&mut out, &l);
        colour_bar(&mut out, &l, &axis_label(&self.bar, &l.bt));
        for (n, line) in l.lines.iter().enumerate() {
            let _ = write!(
                out,
                r##"<text x="12" y="{:.2}" font-size="11" fill="#444444">{}</text>"##,
                l.note_top + 12.0 + 16.0 * n as f64,
                esc(line)
            );
        }
        out.push_str("</svg>\n");
        out
    }

    /// The colour bar's range: the shown values' extent, a decade (log) or the unit interval
    /// when nothing can be shown, widened around a single value.
    fn bar_range(&self) -> (f64, f64) {
        let log = self.bar.scale == Scale::Log;
        let vals = self.values.iter().flatten().copied().filter(|&v| usable(self.bar.scale, v));
        let (mut lo, mut hi) = vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
        if !lo.is_finite() {
            (lo, hi) = if log { (1.0, 10.0) } else { (0.0, 1.0) };
        }
        if hi <= lo {
            (lo, hi) =
                if log { (lo / 1.1, hi * 1.1) } else { (lo - 0.5 * lo.abs().max(1.0), hi + 0.5 * hi.abs().max(1.0)) };
        }
        (lo, hi)
    }

    /// The cell `i` of `c` (centres, or edges with `self.edges`) as its two edges: a centre's
    /// cell reaches halfway to its neighbours, and to the first and last centre at the border.
    fn edges(&self, c: &[f64], i: usize) -> (f64, f64) {
        if self.edges {
            return (c[i], c[i + 1]);
        }
        let a = if i == 0 { c[0] } else { 0.5 * (c[i - 1] + c[i]) };
        let b = if i + 1 == c.len() { c[i] } else { 0.5 * (c[i] + c[i + 1]) };
        (a, b)
    }

    /// True aspect (one data unit is as long on both axes; the longer side gets 480 px), the
    /// colour bar right of the map, the lines under it.
    fn layout(&self) -> Layout {
        let (lo, hi) = self.bar_range();
        let log = self.bar.scale == Scale::Log;
        let (x0, x1) = (self.xs[0], self.xs[self.xs.len() - 1]);
        let (y0, y1) = (self.ys[0], self.ys[self.ys.len() - 1]);
        let (sx, sy) = ((x1 - x0).max(f64::MIN_POSITIVE), (y1 - y0).max(f64::MIN_POSITIVE));
        let k = 480.0 / sx.max(sy);
        let (pw, ph) = (sx * k, sy * k);
        let (xt, yt) = (linear_ticks(x0, x1), linear_ticks(y0, y1));
        let ylab_w = yt.major.iter().map(|(_, l)| text_width(l, 12.0)).fold(0.0, f64::max);
        let left = 30.0 + ylab_w + 12.0;
        let top = if self.title.is_empty() { 16.0 } else { 38.0 };
        let x = Map { lo: x0, hi: x1, p0: left, p1: left + pw, log: false };
        let y = Map { lo: y0, hi: y1, p0: top + ph, p1: top, log: false };
        let bt = if log { log_ticks(lo, hi) } else { linear_ticks(lo, hi) };
        let bar_x = left + pw + 24.0;
        let bar_lab_w = bt.major.iter().map(|(_, l)| text_width(l, 12.0)).fold(0.0, f64::max);
        let width = (bar_x + BAR_W + 8.0 + bar_lab_w + 30.0).max(left + pw + 24.0 + 16.0);
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
        let bar = Map { lo, hi, p0: top + ph, p1: top, log };
        Layout { x, y, xt, yt, bar, bt, left, top, pw, ph, width, height, xlab_y, bar_x, bar_lab_w, note_top, lines }
    }

    /// The colour of value `v`: that of the colour bar's band it falls in (the bar is the
    /// legend of these colours, so the map shows no more than the bar can read back); grey
    /// where nothing is shown.
    fn colour_of(&self, bar: &Map, v: f64) -> String {
        if !usable(self.bar.scale, v) {
            return "#c8c8c8".into();
        }
        let (lo, hi) = (bar.lo, bar.hi);
        let t = if bar.log { (v / lo).ln() / (hi / lo).ln() } else { (v - lo) / (hi - lo) };
        let band = (t.clamp(0.0, 1.0) * BANDS as f64).floor().min(BANDS as f64 - 1.0);
        hex(viridis((band + 0.5) / BANDS as f64))
    }

    /// The runs of one colour down column `i`: (first row, last row, colour).
    fn runs(&self, bar: &Map, i: usize) -> Vec<(usize, usize, String)> {
        let column = &self.values[i];
        let mut runs = Vec::new();
        let mut j = 0;
        while j < column.len() {
            let colour = self.colour_of(bar, column[j]);
            let mut k = j + 1;
            while k < column.len() && self.colour_of(bar, column[k]) == colour {
                k += 1;
            }
            runs.push((j, k - 1, colour));
            j = k;
        }
        runs
    }

    /// The cells: runs of one band down a column are one rectangle, equal runs in
    /// neighbouring columns widen it, and the rectangles of one colour are one path, so a
    /// smooth field draws in a few thousand path commands, not one element per cell.
    fn cells(&self, out: &mut String, l: &Layout) {
        let nx = self.values.len();
        // Rectangles still open for widening: (first row, last row, colour, first column).
        let mut open: Vec<(usize, usize, String, usize)> = Vec::new();
        let mut paths: Vec<(String, String)> = Vec::new();
        let mut emit = |(j0, j1, colour, i0): (usize, usize, String, usize), i1: usize| {
            let (a, _) = self.edges(&self.xs, i0);
            let (_, b) = self.edges(&self.xs, i1);
            let (c, _) = self.edges(&self.ys, j0);
            let (_, d) = self.edges(&self.ys, j1);
            // Each a little oversized so anti-aliasing leaves no hairline seams.
            let (px, py) = (l.x.at(a) - 0.3, l.y.at(d) - 0.3);
            let (w, h) = (l.x.at(b) - l.x.at(a) + 0.6, l.y.at(c) - l.y.at(d) + 0.6);
            let d = format!("M{},{}h{}v{}h{}z", px_num(px), px_num(py), px_num(w), px_num(h), px_num(-w));
            match paths.iter_mut().find(|(f, _)| *f == colour) {
                Some((_, path)) => path.push_str(&d),
                None => paths.push((colour, d)),
            }
        };
        for i in 0..=nx {
            let mut runs = if i < nx { self.runs(&l.bar, i) } else { Vec::new() };
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
    }

    /// The map's border, its ticks and the axis labels.
    fn frame(&self, out: &mut String, l: &Layout) {
        let (left, top, pw, ph) = (l.left, l.top, l.pw, l.ph);
        let _ = write!(
            out,
            r#"<rect x="{left:.2}" y="{top:.2}" width="{pw:.2}" height="{ph:.2}" fill="none" stroke="black"/>"#
        );
        x_tick_marks(out, &l.x, &l.xt, top + ph);
        for (v, label) in &l.yt.major {
            let py = l.y.at(*v);
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
            r#"<text x="{:.2}" y="{:.2}" text-anchor="middle" font-size="13">{}</text>"#,
            left + pw / 2.0,
            l.xlab_y,
            esc(&axis_label(&self.x, &l.xt))
        );
        let _ = write!(
            out,
            r#"<text transform="translate(14,{:.2}) rotate(-90)" text-anchor="middle" font-size="13">{}</text>"#,
            top + ph / 2.0,
            esc(&axis_label(&self.y, &l.yt))
        );
    }

    /// Each mark as a diamond, black on a white halo so it reads on every colour.
    fn marks(&self, out: &mut String, l: &Layout) {
        const R: f64 = 5.0;
        for m in &self.marks {
            let (px, py) = (l.x.at(m.x), l.y.at(m.y));
            let diamond = format!(
                "M{:.2},{:.2}L{:.2},{:.2}L{:.2},{:.2}L{:.2},{:.2}Z",
                px,
                py - R,
                px + R,
                py,
                px,
                py + R,
                px - R,
                py
            );
            let _ = write!(
                out,
                r#"<path d="{diamond}" fill="none" stroke="white" stroke-width="3"/><path d="{diamond}" fill="none" stroke="black" stroke-width="1.5"/>"#
            );
        }
    }
}

/// The colour bar: its bands, ticks in the quantity itself, and its title along the bar.
fn colour_bar(out: &mut String, l: &Layout, title: &str) {
    let (top, ph, bar_x) = (l.top, l.ph, l.bar_x);
    for n in 0..BANDS {
        let (ta, tb) = (n as f64 / BANDS as f64, (n + 1) as f64 / BANDS as f64);
        let (ya, yb) = (top + ph - ta * ph, top + ph - tb * ph);
        let _ = write!(
            out,
            r#"<rect x="{bar_x:.2}" y="{:.2}" width="{BAR_W}" height="{:.2}" fill="{}"/>"#,
            yb - 0.3,
            ya - yb + 0.6,
            hex(viridis(0.5 * (ta + tb)))
        );
    }
    let _ = write!(
        out,
        r#"<rect x="{bar_x:.2}" y="{top:.2}" width="{BAR_W}" height="{ph:.2}" fill="none" stroke="black"/>"#
    );
    let tick_x = bar_x + BAR_W;
    for (v, label) in &l.bt.major {
        let py = l.bar.at(*v);
        let _ = write!(
            out,
            r#"<line x1="{:.2}" y1="{py:.2}" x2="{:.2}" y2="{py:.2}" stroke="black"/><text x="{:.2}" y="{:.2}" font-size="12">{}</text>"#,
            tick_x,
            tick_x + 5.0,
            tick_x + 8.0,
            py + 4.0,
            esc(label)
        );
    }
    for v in &l.bt.minor {
        let py = l.bar.at(*v);
        let _ = write!(
            out,
            r#"<line x1="{:.2}" y1="{py:.2}" x2="{:.2}" y2="{py:.2}" stroke="black"/>"#,
            tick_x,
            tick_x + 3.0
        );
    }
    let _ = write!(
        out,
        r#"<text transform="translate({:.2},{:.2}) rotate(-90)" text-anchor="middle" font-size="13">{}</text>"#,
        tick_x + 8.0 + l.bar_lab_w + 18.0,
        top + ph / 2.0,
        esc(title)
    );
}
