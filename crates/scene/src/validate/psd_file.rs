//! `noise_psd_file`: a measured background PSD read from a file beside the scene, in place of
//! the points written inline (`noise_psd_<unit>_per_hz`), in the same unit.
//!
//! The file is plain text, as a spreadsheet or `numpy.savetxt` writes it: one point a line,
//! frequency (Hz) then density, separated by a comma, a semicolon, tabs or spaces; empty
//! lines and lines starting with `#` are skipped, and so is one header line before the first
//! point. A relative path is taken from the scene file's folder (from the working folder for
//! a scene given as text). The points become the scene's own: the provenance hash covers
//! them, not the file's name.

use super::{other, Invalid};
use std::path::Path;

/// Largest PSD file, bytes (a PSD of the most points allowed is far smaller).
pub(crate) const MAX_PSD_FILE_BYTES: u64 = 1 << 20;

/// The points of the PSD file `path` (relative to `base`), named `field` in errors.
pub(crate) fn read(field: &str, path: &str, base: Option<&Path>) -> Result<Vec<Vec<f64>>, Invalid> {
    let full = match base {
        Some(dir) if Path::new(path).is_relative() => dir.join(path),
        _ => Path::new(path).to_path_buf(),
    };
    let shown = full.display();
    let meta = std::fs::metadata(&full).map_err(|e| other(field, format!("'{shown}' cannot be read: {e}")))?;
    if !meta.is_file() || meta.len() > MAX_PSD_FILE_BYTES {
        return Err(other(field, format!("'{shown}' is not a regular file of at most {MAX_PSD_FILE_BYTES} bytes")));
    }
    let text = std::fs::read_to_string(&full).map_err(|e| other(field, format!("'{shown}' cannot be read: {e}")))?;
    points(&text).map_err(|(line, message)| other(field, format!("'{shown}' line {line}: {message}")))
}

/// The points of a PSD file's text, or the line (from 1) and what is wrong with it.
fn points(text: &str) -> Result<Vec<Vec<f64>>, (usize, String)> {
    let mut out = Vec::new();
    let mut header_allowed = true;
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> =
            line.split(|c: char| c == ',' || c == ';' || c.is_whitespace()).filter(|s| !s.is_empty()).collect();
        let numbers: Result<Vec<f64>, _> = fields.iter().map(|s| s.parse::<f64>()).collect();
        match numbers {
            Ok(v) if v.len() == 2 => out.push(v),
            Ok(v) => return Err((i + 1, format!("has {} numbers; give two, frequency (Hz) and density", v.len()))),
            Err(_) if header_allowed && out.is_empty() => {}
            Err(_) => return Err((i + 1, format!("'{line}' is not two numbers"))),
        }
        header_allowed = false;
    }
    if out.is_empty() {
        return Err((0, "has no points".into()));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::points;

    #[test]
    fn a_psd_file_is_read_as_spreadsheets_write_it() {
        let text = "# measured on the tail beam\nfrequency_hz,psd\n0,1e-6\n\n2000; 1e-6\n5000\t1e-8\n";
        assert_eq!(points(text).unwrap(), vec![vec![0.0, 1e-6], vec![2000.0, 1e-6], vec![5000.0, 1e-8]]);
        assert_eq!(
            points("0,1\n1,2,3\n").unwrap_err(),
            (2, "has 3 numbers; give two, frequency (Hz) and density".into())
        );
        assert_eq!(points("0,1\nx,y\n").unwrap_err().0, 2);
        assert_eq!(points("# nothing\n").unwrap_err().1, "has no points");
    }
}
