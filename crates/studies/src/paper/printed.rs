//! The paper's printed numbers, as printed.

use super::*;

// ------------------------------------------------------------------ printed values

/// The paper's printed numbers, as printed. Embedded, so that neither the binary nor the
/// tests depend on the working directory.
pub const PRINTED_TABLES: &str = include_str!("data/paper_printed.toml");

/// A quantity the paper prints, with the unit of its column.
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    ContactForce,
    Compression,
    Deflection,
    RockTotal,
    RockStored,
    PlateRatio,
    SpringRatio,
    /// Force of the spring at index i of the response's spring list.
    SpringForce(usize),
}

impl Quantity {
    pub fn of(&self, r: &Response) -> f64 {
        match *self {
            Self::ContactForce => r.contact_force,
            Self::Compression => r.compression,
            Self::Deflection => r.deflection,
            Self::RockTotal => r.rock_total_ratio,
            Self::RockStored => r.rock_stored_ratio,
            Self::PlateRatio => r.plate_ratio,
            Self::SpringRatio => r.spring_ratio,
            Self::SpringForce(i) => r.spring_forces[i].force,
        }
    }
}

/// Why the printed tables could not be read.
#[derive(Debug, thiserror::Error)]
pub enum PrintedError {
    #[error("the paper's printed tables: {0}")]
    Toml(#[from] toml::de::Error),
    #[error("the paper's printed tables, {table}: {what}")]
    Shape { table: String, what: String },
    #[error("the paper's printed tables name {0:?}, which is not a sphere of the default scene")]
    UnknownBody(String),
}

/// A printed number: its value and half a unit of its last printed digit.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Printed {
    pub value: f64,
    pub half_ulp: f64,
}

impl Printed {
    /// Reads a number as the paper prints it: an optional minus sign, digits and at most
    /// one decimal point. Exponents, `inf` and `NaN` (which `f64` parsing accepts) are
    /// refused, because the count of decimals is the number's resolution.
    pub fn parse(text: &str) -> Result<Self, String> {
        let digits = text.strip_prefix('-').unwrap_or(text);
        let (int, frac) = digits.split_once('.').unwrap_or((digits, ""));
        let plain = |s: &str| s.bytes().all(|b| b.is_ascii_digit());
        if int.is_empty() || !plain(int) || !plain(frac) || (digits.contains('.') && frac.is_empty()) {
            return Err(format!("{text:?} is not a number as printed (digits, an optional sign and decimal point)"));
        }
        let value: f64 = text.parse().map_err(|e| format!("{text:?}: {e}"))?;
        Ok(Self { value, half_ulp: 0.5 * 10f64.powi(-(frac.len() as i32)) })
    }

    /// Significant digits of the printed text.
    pub fn significant_digits(text: &str) -> usize {
        text.bytes().filter(u8::is_ascii_digit).skip_while(|&b| b == b'0').count()
    }
}

/// A printed cell: its text exactly as printed, and the number it reads as.
#[derive(Debug, Clone, PartialEq)]
pub struct PrintedText {
    pub text: String,
    pub printed: Printed,
}

impl<'de> serde::Deserialize<'de> for PrintedText {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let text = String::deserialize(d)?;
        let printed = Printed::parse(&text).map_err(serde::de::Error::custom)?;
        Ok(Self { text, printed })
    }
}

/// All printed numbers of section IV (the layout is described in the data file).
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PrintedTables {
    pub table2: Table2,
    pub table3: Table3,
    pub table4: Table4,
    pub tables6_8: Vec<ResponseTable>,
    pub tables9_10: Vec<DifferenceTable>,
    pub table11: Table11,
    pub table12: Table12,
    pub section4d: Section4d,
}

/// Table 2: v_y of Areas 1-7 (at printed x, m) for rows of body x condition.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Table2 {
    pub unit: String,
    pub x: Vec<PrintedText>,
    pub rows: Vec<Table2Row>,
}

#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Table2Row {
    pub body: String,
    pub condition: usize,
    pub values: Vec<PrintedText>,
}

/// An impact point given as a fraction of the plate length.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Point {
    pub label: String,
    pub x_over_length: f64,
}

#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConditionColumn {
    pub label: String,
    pub condition: usize,
}

/// A printed quantity in its printed unit (`scale` in SI).
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuantityColumn {
    pub label: String,
    pub quantity: Quantity,
    pub scale: f64,
}

/// Table 3: one block per quantity, rows = points, columns = conditions.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Table3 {
    pub body: String,
    pub rows: Vec<Point>,
    pub columns: Vec<ConditionColumn>,
    pub blocks: Vec<Table3Block>,
}

#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Table3Block {
    pub label: String,
    pub quantity: Quantity,
    pub scale: f64,
    pub values: Vec<Vec<PrintedText>>,
}

/// Table 4: spring forces, rows = springs, columns = points.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Table4 {
    pub body: String,
    pub label: String,
    pub columns: Vec<Point>,
    pub rows: Vec<SpringRow>,
}

#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringRow {
    pub label: String,
    pub condition: usize,
    pub spring: usize,
    pub values: Vec<PrintedText>,
}

#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyRow {
    pub body: String,
    pub values: Vec<PrintedText>,
}

/// One of Tables 6-8: a condition, rows = bodies, columns = quantities.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ResponseTable {
    pub table: u32,
    pub condition: usize,
    pub columns: Vec<QuantityColumn>,
    pub rows: Vec<BodyRow>,
}

#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConditionRow {
    pub condition: usize,
    pub values: Vec<PrintedText>,
}

/// Table 9 or 10: minuend minus subtrahend, rows = conditions, columns = quantities.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DifferenceTable {
    pub table: u32,
    pub minuend: String,
    pub subtrahend: String,
    pub columns: Vec<QuantityColumn>,
    pub rows: Vec<ConditionRow>,
}

#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringColumn {
    pub label: String,
    pub condition: usize,
    pub quantity: Quantity,
}

/// Table 11: spring responses, rows = bodies.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Table11 {
    pub columns: Vec<SpringColumn>,
    pub rows: Vec<BodyRow>,
}

#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DifferenceRow {
    pub minuend: String,
    pub subtrahend: String,
    pub values: Vec<PrintedText>,
}

/// Table 12: differences of Table 11's columns named by label.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Table12 {
    pub columns: Vec<String>,
    pub rows: Vec<DifferenceRow>,
}

/// What section IV-D quotes of Table 5.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Section4d {
    pub min_yield_velocity: PrintedText,
    pub coal_min_exceeds: PrintedText,
    pub coal_over_gangue_exceeds: PrintedText,
}

impl PrintedTables {
    /// The embedded tables.
    pub fn embedded() -> Result<Self, PrintedError> {
        Self::parse(PRINTED_TABLES)
    }

    /// Reads and checks the layout: every row as long as its header, conditions 1-3, and
    /// Table 12's columns present in Table 11.
    pub fn parse(text: &str) -> Result<Self, PrintedError> {
        let t: Self = toml::from_str(text)?;
        let shape = |table: &str, what: String| PrintedError::Shape { table: table.into(), what };
        let width = |table: &str, row: &str, got: usize, want: usize| {
            if got == want {
                Ok(())
            } else {
                Err(shape(table, format!("row {row} has {got} values for {want} columns")))
            }
        };
        let cond = |table: &str, n: usize| {
            if (1..=3).contains(&n) {
                Ok(())
            } else {
                Err(shape(table, format!("condition {n} is not Con 1, 2 or 3")))
            }
        };
        for r in &t.table2.rows {
            cond("Table 2", r.condition)?;
            width("Table 2", &r.body, r.values.len(), t.table2.x.len())?;
        }
        for c in &t.table3.columns {
            cond("Table 3", c.condition)?;
        }
        for b in &t.table3.blocks {
            if b.values.len() != t.table3.rows.len() {
                return Err(shape(
                    "Table 3",
                    format!("{} has {} rows, not {}", b.label, b.values.len(), t.table3.rows.len()),
                ));
            }
            for (r, p) in b.values.iter().zip(&t.table3.rows) {
                width("Table 3", &format!("{} {}", b.label, p.label), r.len(), t.table3.columns.len())?;
            }
        }
        for r in &t.table4.rows {
            cond("Table 4", r.condition)?;
            width("Table 4", &r.label, r.values.len(), t.table4.columns.len())?;
        }
        for tab in &t.tables6_8 {
            let name = format!("Table {}", tab.table);
            cond(&name, tab.condition)?;
            for r in &tab.rows {
                width(&name, &r.body, r.values.len(), tab.columns.len())?;
            }
        }
        for tab in &t.tables9_10 {
            let name = format!("Table {}", tab.table);
            for r in &tab.rows {
                cond(&name, r.condition)?;
                width(&name, &format!("Con {}", r.condition), r.values.len(), tab.columns.len())?;
            }
        }
        for c in &t.table11.columns {
            cond("Table 11", c.condition)?;
        }
        for r in &t.table11.rows {
            width("Table 11", &r.body, r.values.len(), t.table11.columns.len())?;
        }
        for c in &t.table12.columns {
            t.table12_column(c).map_err(|what| shape("Table 12", what))?;
        }
        for r in &t.table12.rows {
            width("Table 12", &r.subtrahend, r.values.len(), t.table12.columns.len())?;
        }
        Ok(t)
    }

    /// The index in Table 11 of the column Table 12 names `label`.
    pub(crate) fn table12_column(&self, label: &str) -> Result<usize, String> {
        self.table11
            .columns
            .iter()
            .position(|c| c.label == label)
            .ok_or_else(|| format!("column {label:?} is not a column of Table 11"))
    }
}
