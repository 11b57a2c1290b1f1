//! Errors of the coupled models, each keeping its source.

use analytic::NotConverged;
use plate_fem::FemError;

/// A failure while computing a scene's results.
#[derive(Debug, thiserror::Error)]
pub enum ModelError {
    /// The model does not describe this support set (the beam and anything but Con 1-3).
    #[error("the {model} model is not applicable to support set '{set}': {reason}")]
    NotApplicable {
        /// Model name.
        model: String,
        /// Support set name.
        set: String,
        /// Why.
        reason: String,
    },
    /// The impact point is outside the beam.
    #[error(transparent)]
    Outside(#[from] analytic::OutsideBeam),
    /// The energy balance did not converge.
    #[error("{context}: {source}")]
    NotConverged {
        /// Which case.
        context: String,
        /// The solver's evidence.
        source: NotConverged,
    },
    /// The finite-element model failed.
    #[error(transparent)]
    Fem(#[from] FemError),
    /// A value the model needs was not computed (a plan error, not a user error).
    #[error("{0}")]
    Missing(String),
    /// A model produced a compliance that cannot be physical.
    #[error(transparent)]
    InvalidCompliance(#[from] analytic::compliance::InvalidCompliance),
    /// A parameter is outside its range.
    #[error(transparent)]
    Parameter(#[from] analytic::InvalidParameter),
    /// The measurement chain cannot run on the model's samples.
    #[error(transparent)]
    Chain(#[from] identify::measurement::ChainError),
}

impl From<analytic::BeamError> for ModelError {
    /// The beam's two failures map onto the variants that already name them.
    fn from(e: analytic::BeamError) -> Self {
        match e {
            analytic::BeamError::Outside(e) => Self::Outside(e),
            analytic::BeamError::Compliance(e) => Self::InvalidCompliance(e),
        }
    }
}
