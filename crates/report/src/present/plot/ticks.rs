//! Tick positions and labels: 1-2-5 steps on a linear axis, decades or 1-2-5 values on a
//! log axis, every label of an axis in one format with a common power of ten.

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
pub(super) fn nice_step(lo: f64, hi: f64, target: f64) -> f64 {
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
