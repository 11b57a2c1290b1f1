//! The findings of the reproduction that the report states as numbers: the unit slip of
//! Table 3, the cells close to print, and the δ_my inversion of Table 2.

use super::*;

/// Table 3's cell at x = L under Con 3: its deflection is printed in the wrong unit and its
/// plate energy ratio as 0.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct UnitSlip {
    /// The deflection as printed.
    pub printed: String,
    /// The power of ten of the column's unit.
    pub column_exponent: i32,
    /// The power of ten between the printed value in the column's unit and the equations'.
    pub slip_exponent: i32,
    /// The equations' deflection (the paper's recursion), m.
    pub deflection: f64,
    /// The plate energy ratio as printed.
    pub zero_printed: String,
    /// The equations' plate energy ratio.
    pub plate_ratio: f64,
}

impl UnitSlip {
    /// The factor between print and the equations, 10^|slip exponent|.
    pub fn factor(&self) -> i64 {
        10i64.pow(self.slip_exponent.unsigned_abs())
    }
}

/// [`UnitSlip`] of the paper's print.
pub fn unit_slip(paper: &Paper, printed: &PrintedTables) -> Result<UnitSlip, PrintedError> {
    let plate = paper.scene.plate;
    let l = plate.length();
    let coal = body(paper, "coal")?;
    let shape = |what: &str| PrintedError::Shape { table: "Table 3".into(), what: what.into() };
    let t3 = &printed.table3;
    let row_l = t3.rows.iter().position(|p| p.x_over_length == 1.0).ok_or_else(|| shape("no row at x = L"))?;
    let col_3 = t3.columns.iter().position(|c| c.condition == 3).ok_or_else(|| shape("no Con 3 column"))?;
    let block =
        |q: Quantity| t3.blocks.iter().find(|b| b.quantity == q).ok_or_else(|| shape(&format!("no {q:?} block")));
    let (defl_block, plate_block) = (block(Quantity::Deflection)?, block(Quantity::PlateRatio)?);
    let con3_at_l = paper.respond(&plate, coal, Paper::condition(3, paper.k_t), l, V_TABLE3, Solve::PaperRecursion);
    let slip = &defl_block.values[row_l][col_3];
    Ok(UnitSlip {
        printed: slip.text.clone(),
        column_exponent: defl_block.scale.log10().round() as i32,
        slip_exponent: (slip.printed.value * defl_block.scale / con3_at_l.deflection).log10().round() as i32,
        deflection: con3_at_l.deflection,
        zero_printed: plate_block.values[row_l][col_3].text.clone(),
        plate_ratio: con3_at_l.plate_ratio,
    })
}

/// Cells of Tables 3-4 that the recursion leaves beyond print rounding but within the
/// threshold (the bare 0 is noted on its own).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct CloseCells {
    /// How many.
    pub count: usize,
    /// How many of them the converged root also leaves beyond print rounding.
    pub converged: usize,
    /// Their smallest relative deviation.
    pub min: f64,
    /// Their largest.
    pub max: f64,
    /// The significant-digit counts at least a quarter of the non-zero cells print ("4-5").
    pub digits: String,
}

/// [`CloseCells`] of the comparisons `rows`, with the explanations of `explainer`.
pub fn close_cells(rows: &[Comparison], explainer: &impl Fn(&Comparison) -> Option<String>) -> CloseCells {
    let t34: Vec<&Comparison> = rows.iter().filter(|r| r.table == "Table 3" || r.table == "Table 4").collect();
    let beyond_print = |r: &Comparison, ours: f64| {
        (ours - r.printed.value).abs() > r.printed.half_ulp * (1.0 + 1e-9) + 1e-12 * r.printed.value.abs()
    };
    let close: Vec<&&Comparison> =
        t34.iter().filter(|r| r.printed.value != 0.0 && r.verdict(explainer) == Verdict::Close).collect();
    let converged = close.iter().filter(|r| beyond_print(r, r.equations)).count();
    let (min, max) = close
        .iter()
        .map(|r| r.deviation(r.best()))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| (lo.min(d), hi.max(d)));
    let mut digits: Vec<usize> = Vec::new();
    let nonzero: Vec<&&Comparison> = t34.iter().filter(|r| r.printed.value != 0.0).collect();
    for r in &nonzero {
        let d = Printed::significant_digits(&r.printed_text);
        if 4 * nonzero.iter().filter(|s| Printed::significant_digits(&s.printed_text) == d).count() >= nonzero.len() {
            digits.push(d);
        }
    }
    let (dmin, dmax) = (digits.iter().min().copied().unwrap_or(0), digits.iter().max().copied().unwrap_or(0));
    let digits = if dmin == dmax { format!("{dmin}") } else { format!("{dmin}-{dmax}") };
    CloseCells { count: close.len(), converged, min, max, digits }
}

/// What Table 2 and its δ_my inversion show.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct InversionFindings {
    /// Mean relative deviation of the equations from print, coal.
    pub t2_deviation_coal: f64,
    /// The same, gangue 1.
    pub t2_deviation_gangue: f64,
    /// Cells per body in the inversion (the fewest).
    pub cells: usize,
    /// Largest distance of a cell's ratio from its body's mean.
    pub spread: f64,
    /// Mean δ_my ratio, coal.
    pub d_my_coal: f64,
    /// Mean δ_my ratio, gangue 1.
    pub d_my_gangue: f64,
}

/// [`InversionFindings`] of the comparisons `rows` and the inversion of [`yield_inversion`].
pub fn inversion_findings(
    rows: &[Comparison],
    inversion: &[(String, Vec<f64>)],
) -> Result<InversionFindings, PrintedError> {
    let t2_deviation = |name: &str| {
        let d: Vec<f64> = rows
            .iter()
            .filter(|r| r.table == "Table 2" && r.case.starts_with(name))
            .map(|r| r.deviation(r.equations))
            .collect();
        mean(&d)
    };
    let inversion_mean = |name: &str| {
        inversion
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, r)| mean(r))
            .ok_or_else(|| PrintedError::Shape { table: "Table 2".into(), what: format!("no rows for {name}") })
    };
    Ok(InversionFindings {
        t2_deviation_coal: t2_deviation("coal"),
        t2_deviation_gangue: t2_deviation("gangue 1"),
        cells: inversion.iter().map(|(_, r)| r.len()).min().unwrap_or(0),
        spread: inversion
            .iter()
            .flat_map(|(_, r)| {
                let m = mean(r);
                r.iter().map(move |x| (x - m).abs())
            })
            .fold(0.0, f64::max),
        d_my_coal: inversion_mean("coal")?,
        d_my_gangue: inversion_mean("gangue 1")?,
    })
}
