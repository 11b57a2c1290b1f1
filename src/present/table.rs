//! Tables of numbers, rendered for the terminal, Markdown and CSV from one description.

use std::fmt::Write as _;

/// A table cell.
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    Text(String),
    /// Shown with 7 significant digits; written to CSV in full (shortest round-trip).
    Num(f64),
    /// An integer count.
    Int(u64),
    /// Not applicable here.
    Empty,
}

impl From<&str> for Cell {
    fn from(s: &str) -> Self {
        Cell::Text(s.to_string())
    }
}
impl From<String> for Cell {
    fn from(s: String) -> Self {
        Cell::Text(s)
    }
}
impl From<f64> for Cell {
    fn from(v: f64) -> Self {
        Cell::Num(v)
    }
}
impl From<u32> for Cell {
    fn from(v: u32) -> Self {
        Cell::Int(v as u64)
    }
}
impl From<usize> for Cell {
    fn from(v: usize) -> Self {
        Cell::Int(v as u64)
    }
}

/// `v` with `sig` significant digits: plain for moderate magnitudes, else scientific.
pub fn sig(v: f64, sig: usize) -> String {
    if v == 0.0 {
        return "0".into();
    }
    if !v.is_finite() {
        return format!("{v}");
    }
    let mag = v.abs().log10().floor() as i32;
    if (-3..6).contains(&mag) {
        let decimals = (sig as i32 - 1 - mag).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{:.*e}", sig - 1, v)
    }
}

impl Cell {
    fn show(&self) -> String {
        match self {
            Cell::Text(s) => s.clone(),
            // No value (a ratio to zero, a contact that never ended) is shown as none, never
            // as NaN or inf.
            Cell::Num(v) if !v.is_finite() => "-".into(),
            Cell::Num(v) => sig(*v, 7),
            Cell::Int(i) => i.to_string(),
            Cell::Empty => "-".into(),
        }
    }
    fn csv(&self) -> String {
        match self {
            Cell::Text(s) => s.clone(),
            Cell::Num(v) if !v.is_finite() => String::new(),
            Cell::Num(v) => format!("{v:e}"),
            Cell::Int(i) => i.to_string(),
            Cell::Empty => String::new(),
        }
    }
}

/// A titled table.
#[derive(Debug, Clone, Default)]
pub struct Table {
    pub title: String,
    pub headers: Vec<String>,
    pub rows: Vec<Vec<Cell>>,
}

impl Table {
    pub fn new(title: impl Into<String>, headers: &[&str]) -> Self {
        Self { title: title.into(), headers: headers.iter().map(|s| s.to_string()).collect(), rows: vec![] }
    }

    pub fn push(&mut self, row: Vec<Cell>) {
        debug_assert_eq!(row.len(), self.headers.len(), "row width must match the headers");
        self.rows.push(row);
    }

    /// Aligned plain text for the terminal.
    pub fn to_text(&self) -> String {
        let shown: Vec<Vec<String>> = self.rows.iter().map(|r| r.iter().map(Cell::show).collect()).collect();
        let mut width: Vec<usize> = self.headers.iter().map(|h| h.chars().count()).collect();
        for r in &shown {
            for (w, c) in width.iter_mut().zip(r) {
                *w = (*w).max(c.chars().count());
            }
        }
        let mut out = String::new();
        if !self.title.is_empty() {
            let _ = writeln!(out, "{}", self.title);
        }
        let line = |cells: &[String]| {
            cells
                .iter()
                .zip(&width)
                // Padded by hand: a format width is limited to u16, and a cell may be longer.
                .map(|(c, w)| format!("{}{c}", " ".repeat(w.saturating_sub(c.chars().count()))))
                .collect::<Vec<_>>()
                .join("  ")
                .trim_end()
                .to_string()
        };
        let _ = writeln!(out, "{}", line(&self.headers));
        let _ = writeln!(out, "{}", width.iter().map(|w| "-".repeat(*w)).collect::<Vec<_>>().join("  "));
        for r in &shown {
            let _ = writeln!(out, "{}", line(r));
        }
        out
    }

    /// A GitHub-flavoured Markdown table (without the title).
    pub fn to_markdown(&self) -> String {
        let mut out = String::new();
        let headers: Vec<String> = self.headers.iter().map(|h| h.replace('|', "\\|")).collect();
        let _ = writeln!(out, "| {} |", headers.join(" | "));
        let _ = writeln!(out, "|{}|", self.headers.iter().map(|_| "---").collect::<Vec<_>>().join("|"));
        for r in &self.rows {
            let cells: Vec<String> = r.iter().map(|c| c.show().replace('|', "\\|")).collect();
            let _ = writeln!(out, "| {} |", cells.join(" | "));
        }
        out
    }

    /// CSV with full-precision numbers.
    pub fn to_csv(&self) -> String {
        let mut w = csv::Writer::from_writer(vec![]);
        w.write_record(&self.headers).expect("writing to memory cannot fail");
        for r in &self.rows {
            w.write_record(r.iter().map(Cell::csv)).expect("writing to memory cannot fail");
        }
        String::from_utf8(w.into_inner().expect("flush to memory")).expect("csv of UTF-8 cells is UTF-8")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn significant_digits() {
        assert_eq!(sig(1.934765173, 7), "1.934765");
        assert_eq!(sig(0.00876323, 7), "0.008763230");
        assert_eq!(sig(2.4275e-6, 4), "2.428e-6");
        assert_eq!(sig(0.0, 7), "0");
    }

    #[test]
    fn csv_keeps_full_precision() {
        let mut t = Table::new("", &["a", "b"]);
        t.push(vec![Cell::from("x, y"), Cell::Num(0.1 + 0.2)]);
        let csv = t.to_csv();
        assert!(csv.contains("\"x, y\""));
        let v: f64 = csv.lines().nth(1).unwrap().rsplit(',').next().unwrap().parse().unwrap();
        assert_eq!(v, 0.1 + 0.2);
    }
}
