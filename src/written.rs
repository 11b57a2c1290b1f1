//! Numbers given on the command line, kept as written, and the one check of a flag's range.

use analytic::params::Range;
use impact::report::Failure;

/// A number given on the command line, with the text it was written as: an error names the
/// value as the user wrote it (`1e308`, not its 309 digits).
#[derive(Clone, Debug)]
pub struct Written {
    text: String,
    value: f64,
}

impl std::str::FromStr for Written {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let value = s.trim().parse::<f64>().map_err(|_| format!("'{s}' is not a number"))?;
        Ok(Written { text: s.to_string(), value })
    }
}

/// A default, written as `--help` shows it.
impl From<f64> for Written {
    fn from(value: f64) -> Self {
        Written { text: value.to_string(), value }
    }
}

impl std::fmt::Display for Written {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

impl Written {
    /// The value if it lies in `allowed`, else an error naming `flag`, the value as written
    /// and the range.
    pub fn within(&self, flag: &str, allowed: Range, unit: &str) -> Result<f64, Failure> {
        in_range(flag, &self.text, self.value, allowed, unit)
    }
}

/// `value` (written as `text`) if it lies in `allowed`, else an error naming `flag`, the
/// value and the range: one wording for every range the command line checks.
pub fn in_range(flag: &str, text: &str, value: f64, allowed: Range, unit: &str) -> Result<f64, Failure> {
    if allowed.contains(value) {
        return Ok(value);
    }
    let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
    Err(format!("{flag} {text} is outside the allowed range {allowed}{unit}").into())
}
