//! The verdict matrix's SVG: statements against models, each cell a verdict in words and
//! colour-blind-safe colours.

use super::svg::{esc, svg_open, text_width, wrap};
use super::Verdict;
use std::fmt::Write as _;

/// A yes/no matrix: rows (statements) against columns (models), each cell a verdict.
#[derive(Debug, Clone)]
pub struct Matrix {
    pub title: String,
    pub columns: Vec<String>,
    pub rows: Vec<String>,
    /// cells[row][column]: the statement's verdict under the column's model.
    pub cells: Vec<Vec<Verdict>>,
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
