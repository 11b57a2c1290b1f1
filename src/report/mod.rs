//! The studies a scene can ask for, each written up as a set of files ([`Artifacts`]).
//!
//! Every report has the same signature, `fn(&Scene) -> Result<Artifacts, Failure>`, and
//! writes only its own files; a report that includes another nests the other's files
//! under a subdirectory.

pub mod comparison;
pub mod conclusions;
pub mod fem_bench;
pub mod fem_verification;
pub mod field;
pub mod paper;
pub mod skfem;
pub mod studies;
pub mod transient;

use crate::output::Artifacts;
use coupled::Scene;

/// Any failure of a study, with its source.
pub type Failure = Box<dyn std::error::Error>;

/// The signature every report has.
pub type Report = fn(&Scene) -> Result<Artifacts, Failure>;
