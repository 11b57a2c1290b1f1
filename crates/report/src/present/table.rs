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
    /// A number shown with the given significant digits (CSV: in full).
    Sig(f64, usize),
    /// A relative difference (a fraction), shown in percent to 3 significant figures;
    /// below 1e-12 it is round-off and shown as 0 (never "-0 %").
    Rel(f64),
    /// An input as given (a position, a velocity): shortest form, to 9 significant digits,
    /// so a unit conversion's round-off does not show (13.752, not 13.75199999).
    Given(f64),
    /// A value with its error estimate, shown to the digit the error supports (the error's
    /// leading two digits); a value not resolved from zero is shown as 0 ([`measured`]).
    Measured {
        value: f64,
        error: f64,
    },
    /// A yes/no answer, shown as `shown` ("yes", "no", or an emphasised "**no**"), written to
    /// CSV as 1 or 0.
    Flag {
        yes: bool,
        shown: &'static str,
    },
    /// A number with a remark after it in parentheses, "2.27 (beyond elastic range)", the
    /// number with `digits` significant digits. CSV: the number in full, and the remark in a
    /// column of its own (`<name>_note`).
    Noted {
        value: f64,
        digits: usize,
        note: String,
    },
    /// A point (x, z), stored in SI and shown as "(x, z)" scaled by `scale` to `decimals`
    /// decimals. CSV: two columns (`<name>_x`, `<name>_z`), in SI.
    Pair {
        x: f64,
        z: f64,
        scale: f64,
        decimals: usize,
    },
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
impl From<bool> for Cell {
    /// "yes" or "no".
    fn from(yes: bool) -> Self {
        Cell::Flag { yes, shown: if yes { "yes" } else { "no" } }
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

pub use studies::columns::sig;

/// The SI unit key and the factor to SI of a display unit ("mm" -> ("m", 1e-3)); a leading
/// scale ("1e-7 m") multiplies in. Units this table does not know are kept as written, in key
/// form, with factor 1.
fn si_unit(unit: &str) -> (String, f64) {
    let unit = unit.trim();
    if let Some((scale, rest)) = unit.split_once(' ') {
        if let Ok(k) = scale.parse::<f64>() {
            let (u, f) = si_unit(rest);
            return (u, k * f);
        }
    }
    let (u, f) = match unit {
        "mm" => ("m", 1e-3),
        "µm" | "μm" | "um" => ("m", 1e-6),
        "ms" => ("s", 1e-3),
        "µs" | "μs" => ("s", 1e-6),
        "GPa" => ("Pa", 1e9),
        "MPa" => ("Pa", 1e6),
        "kN" => ("N", 1e3),
        "m/s^2" | "m/s²" => ("m_per_s2", 1.0),
        "%" => ("", 0.01),
        "rel." | "log" | "-" | "" => ("", 1.0),
        other => return (key_part(other), 1.0),
    };
    (u.to_string(), f)
}

/// A name in key form: symbols kept in their case (P_max, C), Greek letters and sub- and
/// superscripts spelt out, operators as words, everything else an underscore.
fn key_part(name: &str) -> String {
    let mut s = String::new();
    let spaced = name.replace(" - ", " minus ").replace(" + ", " plus ");
    for c in spaced.chars() {
        let word = match c {
            'δ' => "delta",
            'Δ' => "Delta",
            'σ' => "sigma",
            'ν' => "nu",
            'ρ' => "rho",
            'τ' => "tau",
            'ω' => "omega",
            'θ' | 'Θ' => "theta",
            'ζ' => "zeta",
            'φ' => "phi",
            'μ' | 'µ' => "mu",
            '±' => "error",
            '/' => "_per_",
            '₀' | '⁰' => "0",
            '₁' | '¹' => "1",
            '₂' | '²' => "2",
            '³' => "3",
            c if c.is_ascii_alphanumeric() => {
                s.push(c);
                continue;
            }
            _ => "_",
        };
        s.push_str(word);
    }
    let mut out = String::new();
    for part in s.split('_').filter(|p| !p.is_empty()) {
        if !out.is_empty() {
            out.push('_');
        }
        out.push_str(part);
    }
    out
}

/// The CSV column name of a display header, and the factor that takes its values to SI:
/// `"x (mm)"` -> `("x_m", 1e-3)`, `"P_max (N)"` -> `("P_max_N", 1.0)`,
/// `"C (m/N)"` -> `("C_m_per_N", 1.0)`. One style for every CSV the program writes: the
/// quantity in key form, then its SI unit; a dimensionless column has no unit part.
pub fn csv_key(header: &str) -> (String, f64) {
    let (name, u) = csv_name_and_unit(header);
    let (_, f) = si_unit(unit_of(header.trim()).1);
    (if u.is_empty() { name } else { format!("{name}_{u}") }, f)
}

/// The key form of an SI unit as written for display ("m/s^2" -> "m_per_s2", "N" -> "N"),
/// for a column that names a row's unit.
pub fn unit_key(unit: &str) -> String {
    si_unit(unit).0
}

/// A display header split into its name and its parenthesised unit.
fn unit_of(h: &str) -> (&str, &str) {
    match (h.rfind('('), h.ends_with(')')) {
        (Some(i), true) => (&h[..i], &h[i + 1..h.len() - 1]),
        _ => (h, ""),
    }
}

/// The name (key form) and the SI unit key of a display header.
fn csv_name_and_unit(header: &str) -> (String, String) {
    let (name, unit) = unit_of(header.trim());
    (key_part(name), si_unit(unit).0)
}

/// A relative difference in percent, 3 significant figures, with its sign; round-off
/// (|v| < 1e-12) is 0.
pub fn percent(v: f64) -> String {
    if !v.is_finite() {
        return "-".into();
    }
    if v.abs() < 1e-12 {
        return "0 %".into();
    }
    let p = 100.0 * v;
    let mag = p.abs().log10().floor() as i32;
    // Three significant figures also above 1000 %: 18559 % is 18600 %.
    let s = if mag >= 3 {
        let unit = 10f64.powi(mag - 2);
        format!("{:.0}", (p.abs() / unit).round() * unit)
    } else {
        sig(p.abs(), 3)
    };
    format!("{}{s} %", if p < 0.0 { "−" } else { "+" })
}

/// `value` rounded to what `error` supports: the decimal place of the error's second
/// significant digit (at most 7 significant digits). A value not resolved from zero (at most
/// twice its error, as round-off at a held point is) is shown as 0.
pub fn measured(value: f64, error: f64) -> String {
    if !value.is_finite() {
        return "-".into();
    }
    if !(error.is_finite() && error > 0.0) {
        return sig(value, 7);
    }
    if value.abs() <= 2.0 * error {
        return "0".into();
    }
    let digits = (value.abs().log10().floor() - error.log10().floor() + 2.0).clamp(1.0, 7.0) as usize;
    sig(value, digits)
}

impl Cell {
    pub fn show(&self) -> String {
        match self {
            // A note without its number (there is none) stands alone.
            Cell::Noted { value, note, .. } if !value.is_finite() => note.clone(),
            Cell::Sig(v, _) | Cell::Rel(v) | Cell::Measured { value: v, .. } if !v.is_finite() => "-".into(),
            Cell::Sig(v, d) => sig(*v, *d),
            Cell::Given(v) if !v.is_finite() => "-".into(),
            Cell::Given(v) => {
                let r: f64 = format!("{v:.8e}").parse().unwrap_or(*v);
                format!("{r}")
            }
            Cell::Rel(v) => percent(*v),
            Cell::Measured { value, error } => measured(*value, *error),
            Cell::Text(s) => s.clone(),
            // No value (a ratio to zero, a contact that never ended) is shown as none, never
            // as NaN or inf.
            Cell::Num(v) if !v.is_finite() => "-".into(),
            Cell::Num(v) => sig(*v, 7),
            Cell::Int(i) => i.to_string(),
            Cell::Flag { shown, .. } => shown.to_string(),
            Cell::Noted { value, digits, note } => format!("{} ({note})", sig(*value, *digits)),
            Cell::Pair { x, z, scale, decimals } => format!("({:.*}, {:.*})", decimals, x * scale, decimals, z * scale),
            Cell::Empty => "-".into(),
        }
    }
    fn csv(&self, factor: f64) -> String {
        match self {
            Cell::Text(s) => s.clone(),
            Cell::Num(v) if !v.is_finite() => String::new(),
            Cell::Num(v) | Cell::Sig(v, _) | Cell::Rel(v) | Cell::Given(v) | Cell::Measured { value: v, .. }
                if !v.is_finite() =>
            {
                String::new()
            }
            Cell::Num(v) | Cell::Sig(v, _) | Cell::Rel(v) | Cell::Given(v) | Cell::Measured { value: v, .. }
                if factor == 1.0 =>
            {
                format!("{v:e}")
            }
            Cell::Num(v) | Cell::Sig(v, _) | Cell::Rel(v) | Cell::Given(v) | Cell::Measured { value: v, .. } => {
                format!("{:e}", v * factor)
            }
            Cell::Int(i) => i.to_string(),
            Cell::Flag { yes, .. } => (if *yes { "1" } else { "0" }).into(),
            Cell::Noted { value, .. } => Cell::Num(*value).csv(factor),
            Cell::Pair { .. } => unreachable!("a pair is written as two columns"),
            Cell::Empty => String::new(),
        }
    }

    /// The cells of a column of `shape` this cell writes, in SI (`factor` from the header).
    fn csv_cells(&self, shape: Shape, factor: f64) -> Vec<String> {
        match (shape, self) {
            (Shape::Plain, c) => vec![c.csv(factor)],
            (Shape::Noted, Cell::Noted { note, .. }) => vec![self.csv(factor), note.clone()],
            (Shape::Noted, c) => vec![c.csv(factor), String::new()],
            (Shape::Pair, Cell::Pair { x, z, .. }) => vec![Cell::Num(*x).csv(factor), Cell::Num(*z).csv(factor)],
            (Shape::Pair, c) => vec![c.csv(factor), String::new()],
        }
    }
}

/// How a column is written to CSV: one column, a number and its note, or a point's two
/// coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Shape {
    Plain,
    Noted,
    Pair,
}

/// A titled table.
#[derive(Debug, Clone, Default)]
pub struct Table {
    pub title: String,
    pub headers: Vec<String>,
    pub rows: Vec<Vec<Cell>>,
    /// CSV column names given explicitly (by column index), where the name made from the
    /// display header ([`csv_key`]) would not say what the column holds; one name per CSV
    /// column the column writes (two for a noted number or a point).
    pub csv_names: Vec<(usize, Vec<String>)>,
}

impl Table {
    pub fn new(title: impl Into<String>, headers: &[&str]) -> Self {
        Self {
            title: title.into(),
            headers: headers.iter().map(|s| s.to_string()).collect(),
            rows: vec![],
            csv_names: vec![],
        }
    }

    /// The table with the CSV column(s) of the column headed `header` named `names` (the
    /// values are still converted to SI by the header's unit). Panics if there is no such
    /// column: a programming error, caught by the report's tests.
    pub fn csv_name(mut self, header: &str, names: &[&str]) -> Self {
        let i = self.headers.iter().position(|h| h == header).unwrap_or_else(|| panic!("no column '{header}'"));
        self.csv_names.retain(|(j, _)| *j != i);
        self.csv_names.push((i, names.iter().map(|s| s.to_string()).collect()));
        self
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

    /// How column `i` is written: a point if any cell is one, a noted number if any is.
    fn shape(&self, i: usize) -> Shape {
        let cells = || self.rows.iter().filter_map(|r| r.get(i));
        if cells().any(|c| matches!(c, Cell::Pair { .. })) {
            Shape::Pair
        } else if cells().any(|c| matches!(c, Cell::Noted { .. })) {
            Shape::Noted
        } else {
            Shape::Plain
        }
    }

    /// The CSV column names of each column ([`csv_key`], or as given by
    /// [`Table::csv_name`]) with its factor to SI and its shape, made unique: a repeated
    /// name gets `_2`, `_3`.
    fn csv_layout(&self) -> Vec<(Vec<String>, f64, Shape)> {
        let mut seen: Vec<String> = Vec::new();
        let mut unique = |key: String| {
            let mut k = key.clone();
            let mut n = 1;
            while seen.contains(&k) {
                n += 1;
                k = format!("{key}_{n}");
            }
            seen.push(k.clone());
            k
        };
        let mut out = Vec::with_capacity(self.headers.len());
        for (i, h) in self.headers.iter().enumerate() {
            let (key, f) = csv_key(h);
            let shape = self.shape(i);
            let given = self.csv_names.iter().find(|(j, _)| *j == i).map(|(_, n)| n.clone());
            let names = match (given, shape) {
                (Some(n), _) => n,
                (None, Shape::Plain) => vec![key],
                (None, Shape::Noted) => {
                    let (name, _) = csv_name_and_unit(h);
                    vec![key, format!("{name}_note")]
                }
                (None, Shape::Pair) => {
                    let (name, unit) = csv_name_and_unit(h);
                    let with = |axis: &str| {
                        [name.as_str(), axis, unit.as_str()]
                            .iter()
                            .filter(|s| !s.is_empty())
                            .copied()
                            .collect::<Vec<_>>()
                            .join("_")
                    };
                    vec![with("x"), with("z")]
                }
            };
            // A table without rows shows no cell to tell a pair from a plain column: its
            // given names say how many columns it has.
            let shape = match (self.rows.is_empty(), names.len()) {
                (true, 2) if shape == Shape::Plain => Shape::Pair,
                _ => shape,
            };
            let width = if shape == Shape::Plain { 1 } else { 2 };
            assert_eq!(names.len(), width, "column '{h}' writes {width} CSV column(s), named {names:?}");
            out.push((names.into_iter().map(&mut unique).collect(), f, shape));
        }
        out
    }

    /// The CSV column names, made unique: a repeated name gets `_2`, `_3`.
    pub fn csv_headers(&self) -> Vec<String> {
        self.csv_layout().into_iter().flat_map(|(names, _, _)| names).collect()
    }

    /// CSV with full-precision numbers in SI units, under [`csv_key`] column names.
    pub fn to_csv(&self) -> String {
        let layout = self.csv_layout();
        let mut w = csv::Writer::from_writer(vec![]);
        w.write_record(layout.iter().flat_map(|(n, _, _)| n)).expect("writing to memory cannot fail");
        for r in &self.rows {
            let cells = r.iter().zip(&layout).flat_map(|(c, (_, f, shape))| c.csv_cells(*shape, *f));
            w.write_record(cells.collect::<Vec<_>>()).expect("writing to memory cannot fail");
        }
        String::from_utf8(w.into_inner().expect("flush to memory")).expect("csv of UTF-8 cells is UTF-8")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_without_rows_writes_its_header() {
        // Once a panic: no cell told the pair named by two CSV names from a plain column.
        let t = Table::new("empty", &["point", "force"]).csv_name("point", &["x_m", "z_m"]);
        assert_eq!(t.to_csv().lines().count(), 1);
        assert!(t.to_csv().starts_with("x_m,z_m,"), "{}", t.to_csv());
        let _ = t.to_markdown();
    }

    #[test]
    fn significant_digits() {
        assert_eq!(sig(1.934765173, 7), "1.934765");
        assert_eq!(sig(0.00876323, 7), "0.008763230");
        assert_eq!(sig(2.4275e-6, 4), "2.428e-6");
        assert_eq!(sig(0.0, 7), "0");
    }

    #[test]
    fn round_off_is_not_data() {
        assert_eq!(percent(-0.2068189), "−20.7 %");
        assert_eq!(percent(1.12), "+112 %");
        assert_eq!(percent(185.59), "+18600 %");
        assert_eq!(percent(-4.985435e-20), "0 %");
        assert_eq!(percent(0.0), "0 %");
        // C = 6.221534e-7 with an error of 3.3e-11: digits to the 1e-12 place.
        assert_eq!(measured(6.221534e-7, 3.3e-11), "6.22153e-7");
        assert_eq!(measured(2.237948e-31, 1.4e-31), "0");
        assert_eq!(measured(1.712807, 1.7e-3), "1.7128");
    }

    #[test]
    fn csv_keys_are_si_in_one_style() {
        assert_eq!(csv_key("x (mm)"), ("x_m".into(), 1e-3));
        assert_eq!(csv_key("P_max (N)"), ("P_max_N".into(), 1.0));
        assert_eq!(csv_key("C (m/N)"), ("C_m_per_N".into(), 1.0));
        assert_eq!(csv_key("v (m/s)"), ("v_m_per_s".into(), 1.0));
        assert_eq!(csv_key("δ_max (1e-7 m)"), ("delta_max_m".into(), 1e-7));
        assert_eq!(csv_key("FE ± (m/N)"), ("FE_error_m_per_N".into(), 1.0));
        assert_eq!(csv_key("C plate/beam - 1"), ("C_plate_per_beam_minus_1".into(), 1.0));
        assert_eq!(csv_key("t_c / T₁"), ("t_c_per_T1".into(), 1.0));
        let mut t = Table::new("", &["a (mm)", "a (mm)", "b"]);
        t.push(vec![Cell::Num(2.0), Cell::Num(3.0), Cell::Empty]);
        assert_eq!(t.to_csv(), "a_m,a_m_2,b\n2e-3,3e-3,\n");
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
