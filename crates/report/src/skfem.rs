//! The scikit-fem reference data (reference/data/*.json, written by
//! reference/python/plate_reference.py) read from the source tree, and the matching Rust runs
//! ([`studies::fem_verification::reference`], which the verification computes with).

use std::path::{Path, PathBuf};
pub use studies::fem_verification::reference::{extrapolate, rust_runs, Case, Run};

/// The cases the reference script writes for the verification.
pub const CASES: [&str; 5] = ["paper-con1", "paper-con2", "paper-con3", "paper-simple-all", "paper-simple-free"];

/// reference/data in the source tree.
pub fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../reference/data")
}

/// Reads one case (any file of reference/data, by its stem).
pub fn load(name: &str) -> Result<Case, String> {
    let path = data_dir().join(format!("{name}.json"));
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    studies::fem_verification::reference::parse(name, &text, &path.display().to_string())
}
