//! The line plot's SVG: the layout first (axes, legend beside or below, notes), then the
//! frame, the curves, the legend and the notes, each a function of the layout.

use super::svg::{
    axes, axis_label, coincides_with, esc, marker, range, svg_open, text_width, usable, wrap, Map, CHAR_EM, COINCIDE,
    DASHES, PALETTE,
};
use super::ticks::{linear_ticks, log_ticks, Ticks};
use super::{Plot, Scale, Style, MARKER_LIMIT};
use std::fmt::Write as _;

/// Dash patterns of the curves drawn over a curve they coincide with, so two or three of
/// them on one curve still show apart.
const OVER_DASHES: [&str; 3] = ["8 6", "3 4", "1 3"];
/// The plotting area's width, px.
const PW: f64 = 480.0;
/// The plotting area's height, px.
const PH: f64 = 300.0;

/// Where everything of a line plot goes.
struct Layout {
    x: Map,
    y: Map,
    xt: Ticks,
    yt: Ticks,
    left: f64,
    top: f64,
    width: f64,
    height: f64,
    xlab_y: f64,
    legend_right: bool,
    legend_top: f64,
    note_top: f64,
    /// Each series' legend label, with what a reader must know about it.
    labels: Vec<String>,
    /// The series each one coincides with, if any (drawn dashed over it).
    coincide: Vec<Option<usize>>,
    /// The series with a name, in the legend.
    named: Vec<usize>,
    /// The notes under the figure, wrapped.
    notes: Vec<String>,
}

/// How one series is drawn: colour, dash pattern, line width, marker shape.
type Pen = (&'static str, String, f64, usize);

impl Plot {
    /// The SVG document.
    pub fn svg(&self) -> String {
        let l = self.layout();
        let mut out = String::new();
        svg_open(&mut out, l.width, l.height);
        self.frame(&mut out, &l);
        let pens = self.curves(&mut out, &l);
        self.legend(&mut out, &l, &pens);
        for (n, note) in l.notes.iter().enumerate() {
            let _ = write!(
                out,
                r##"<text x="{:.2}" y="{:.2}" font-size="11" fill="#444444">{}</text>"##,
                12.0,
                l.note_top + 12.0 + 16.0 * n as f64,
                esc(note)
            );
        }
        out.push_str("</svg>\n");
        out
    }

    /// Whether a point can be shown on both axes (a log axis cannot show x ≤ 0).
    fn shows(&self, &(x, y): &(f64, f64)) -> bool {
        usable(self.x.scale, x) && usable(self.y.scale, y)
    }

    /// The axes' ranges and ticks, the legend's place (right of the axes when its labels are
    /// short, else below) and the figure's size.
    fn layout(&self) -> Layout {
        let (xs, ys) = (self.x.scale, self.y.scale);
        let (xlo, xhi) =
            range(self.series.iter().flat_map(|s| s.points.iter().filter(|p| self.shows(p)).map(|p| p.0)), xs);
        let (ylo, yhi) =
            range(self.series.iter().flat_map(|s| s.points.iter().filter(|p| self.shows(p)).map(|p| p.1)), ys);
        let ticks = |lo, hi, s| if s == Scale::Log { log_ticks(lo, hi) } else { linear_ticks(lo, hi) };
        let (xt, yt) = (ticks(xlo, xhi, xs), ticks(ylo, yhi, ys));
        let ylab_w = yt.major.iter().map(|(_, l)| text_width(l, 12.0)).fold(0.0, f64::max);
        let left = 30.0 + ylab_w + 12.0;
        let top = if self.title.is_empty() { 16.0 } else { 38.0 };
        let x = Map { lo: xlo, hi: xhi, p0: left, p1: left + PW, log: xs == Scale::Log };
        let y = Map { lo: ylo, hi: yhi, p0: top + PH, p1: top, log: ys == Scale::Log };
        let (labels, coincide, notes) = self.labels(&x, &y);
        let named: Vec<usize> = (0..self.series.len()).filter(|&i| !self.series[i].name.is_empty()).collect();
        let widest = named.iter().map(|&i| text_width(&labels[i], 12.0)).fold(0.0, f64::max);
        let legend_right = widest <= 260.0;
        let legend_w = if named.is_empty() { 0.0 } else { widest + 46.0 };
        let width = if legend_right {
            left + PW + legend_w.max(16.0) + 8.0
        } else {
            (left + PW + 24.0).max(left + legend_w + 12.0)
        };
        let xlab_y = top + PH + 40.0;
        let mut cursor = xlab_y + 10.0;
        let legend_top = if legend_right { top } else { cursor + 6.0 };
        if !legend_right {
            cursor += 10.0 + 18.0 * named.len() as f64;
        }
        let note_top = cursor + 6.0;
        let per_line = ((width - 24.0) / (11.0 * CHAR_EM)) as usize;
        let notes: Vec<String> = notes.iter().flat_map(|n| wrap(n, per_line)).collect();
        let height = note_top + 16.0 * notes.len() as f64 + 6.0;
        Layout {
            x,
            y,
            xt,
            yt,
            left,
            top,
            width,
            height,
            xlab_y,
            legend_right,
            legend_top,
            note_top,
            labels,
            coincide,
            named,
            notes,
        }
    }

    /// The legend labels, which series coincide with which, and the notes: the plot's own,
    /// then one per series with points a log axis cannot show, then the dashed-curve rule.
    fn labels(&self, x: &Map, y: &Map) -> (Vec<String>, Vec<Option<usize>>, Vec<String>) {
        let mut notes = self.notes.clone();
        let mut labels = Vec::new();
        let mut coincide = vec![None; self.series.len()];
        for (i, s) in self.series.iter().enumerate() {
            let mut label = s.name.clone();
            if matches!(s.style, Style::Line | Style::Points) {
                coincide[i] = coincides_with(&self.series, i, x, y);
            }
            if let Some(j) = coincide[i] {
                label.push_str(&format!(" (dashed: on {})", self.series[j].name));
            }
            let hidden = s.points.iter().filter(|p| p.0.is_finite() && p.1.is_finite() && !self.shows(p)).count();
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
        (labels, coincide, notes)
    }

    /// The title, the axes with their ticks and labels, and the clip of the plotting area.
    fn frame(&self, out: &mut String, l: &Layout) {
        if !self.title.is_empty() {
            let _ = write!(
                out,
                r#"<text x="{:.2}" y="24" text-anchor="middle" font-size="15">{}</text>"#,
                l.left + PW / 2.0,
                esc(&self.title)
            );
        }
        axes(out, &l.x, &l.y, &l.xt, &l.yt);
        let _ = write!(
            out,
            r#"<text x="{:.2}" y="{:.2}" text-anchor="middle" font-size="13">{}</text>"#,
            l.left + PW / 2.0,
            l.xlab_y,
            esc(&axis_label(&self.x, &l.xt))
        );
        let _ = write!(
            out,
            r#"<text transform="translate(14,{:.2}) rotate(-90)" text-anchor="middle" font-size="13">{}</text>"#,
            l.top + PH / 2.0,
            esc(&axis_label(&self.y, &l.yt))
        );
        let (left, top) = (l.left, l.top);
        let _ = write!(
            out,
            r#"<clipPath id="area"><rect x="{left:.2}" y="{top:.2}" width="{PW:.2}" height="{PH:.2}"/></clipPath><g clip-path="url(#area)">"#
        );
    }

    /// The pens of the series in order: guides grey, levels in the colour of the curve
    /// before, curves through the palette (then its dash patterns); a curve on another is
    /// dashed over it, and earlier curves are a little wider, so a later curve drawn on top
    /// of one it nearly follows leaves a visible rim of it.
    fn pens(&self, coincide: &[Option<usize>]) -> Vec<Pen> {
        let lines = self.series.iter().filter(|s| s.style == Style::Line).count();
        let (mut k, mut over) = (0usize, 0usize);
        let mut pens = Vec::with_capacity(self.series.len());
        for (i, s) in self.series.iter().enumerate() {
            pens.push(match s.style {
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
                        let rank = (k - 1) as f64 / (lines.max(2) - 1) as f64;
                        (c, d, 3.2 - 1.6 * rank.min(1.0), k - 1)
                    }
                }
            });
        }
        pens
    }

    /// Every series inside the clip: a path broken at each value the axes cannot show (a
    /// gap, not a bridge), and markers on series of few points.
    fn curves(&self, out: &mut String, l: &Layout) -> Vec<Pen> {
        let pens = self.pens(&l.coincide);
        for (s, (colour, dash, width_px, shape)) in self.series.iter().zip(&pens) {
            let pts: Vec<(f64, f64)> =
                s.points.iter().copied().filter(|p| self.shows(p)).map(|(a, b)| (l.x.at(a), l.y.at(b))).collect();
            let markers = s.style == Style::Points || (s.style == Style::Line && pts.len() <= MARKER_LIMIT);
            if s.style != Style::Points && pts.len() >= 2 {
                let mut d = String::new();
                let mut pen = false;
                for p in &s.points {
                    if self.shows(p) {
                        let _ = write!(d, "{}{:.2},{:.2}", if pen { "L" } else { "M" }, l.x.at(p.0), l.y.at(p.1));
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
                    marker(out, *shape, px, py, colour);
                }
            }
        }
        out.push_str("</g>");
        pens
    }

    /// The legend, outside the axes: each named series' pen, marker and label.
    fn legend(&self, out: &mut String, l: &Layout, pens: &[Pen]) {
        let (lx0, mut ly) =
            if l.legend_right { (l.left + PW + 14.0, l.legend_top + 6.0) } else { (l.left, l.legend_top) };
        for &i in &l.named {
            let s = &self.series[i];
            let (colour, dash, width_px, shape) = &pens[i];
            let cy = ly + 8.0;
            if s.style != Style::Points {
                let dash_attr = if dash.is_empty() { String::new() } else { format!(r#" stroke-dasharray="{dash}""#) };
                let _ = write!(
                    out,
                    r#"<line x1="{lx0:.2}" y1="{cy:.2}" x2="{:.2}" y2="{cy:.2}" stroke="{colour}" stroke-width="{width_px}"{dash_attr}/>"#,
                    lx0 + 28.0
                );
            }
            let few = s.points.iter().filter(|p| self.shows(p)).count() <= MARKER_LIMIT;
            if s.style == Style::Points || (s.style == Style::Line && few) {
                marker(out, *shape, lx0 + 14.0, cy, colour);
            }
            let _ = write!(
                out,
                r#"<text x="{:.2}" y="{:.2}" font-size="12">{}</text>"#,
                lx0 + 34.0,
                cy + 4.0,
                esc(&l.labels[i])
            );
            ly += 18.0;
        }
    }
}
