//! The compliance seam: every plate model turns (support set, x, z) into the compliance of
//! the supported plate at the impact point, split into its energy stores, with an error
//! estimate. The energy balance, the responses and the yield model (crate `analytic`)
//! see only that, so they cannot tell which model produced it.

pub mod mindlin;
pub mod plate;
pub mod shell_mesh;
pub mod table;
pub mod tail_beam;

use crate::error::ModelError;
use crate::supports::SupportSet;
use analytic::{beam_compliance, PointCompliance};
use serde::Serialize;

pub use mindlin::MindlinModel;
pub use plate::PlateModel;
pub use tail_beam::TailBeamModel;

/// A compliance with the estimate of its discretisation error.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Estimate {
    /// The compliance and its stores.
    pub compliance: PointCompliance,
    /// Estimated absolute error of the total compliance, m/N: 0 for a closed form, the
    /// Richardson estimate for finite elements.
    pub error_estimate: f64,
    /// Whether the error estimate comes from a mesh sequence in its asymptotic range (a
    /// closed form always is).
    pub asymptotic: bool,
}

impl Estimate {
    /// A closed-form value: no discretisation error.
    pub fn exact(compliance: PointCompliance) -> Self {
        Self { compliance, error_estimate: 0.0, asymptotic: true }
    }

    /// The estimated relative error of the total compliance (0 where C = 0).
    pub fn relative_error(&self) -> f64 {
        let c = self.compliance.total();
        if c > 0.0 {
            self.error_estimate / c
        } else {
            0.0
        }
    }
}

/// A source of plate compliance at impact points.
pub trait ComplianceModel {
    /// Short name for tables ("beam", "plate FE (extrapolated from 40 x 32)").
    fn name(&self) -> &str;
    /// Whether the model resolves the width coordinate z (the beam does not: its value is
    /// the same at every z).
    fn resolves_width(&self) -> bool;
    /// The compliance under `set` at (x, z), m/N; [`ModelError::NotApplicable`] where the
    /// model does not describe the support set.
    fn compliance(&self, set: &SupportSet, x: f64, z: f64) -> Result<Estimate, ModelError>;
}

/// The paper's beam model (section II): the plate as a beam of width B along its length.
///
/// ```
/// use analytic::{Elastic, Plate, Condition};
/// use coupled::{BeamModel, ComplianceModel, SupportSet};
/// let plate = Plate::new(0.4584, 0.36, 0.008, 7850.0, Elastic::new(210e9, 0.3)?)?;
/// let beam = BeamModel { plate: &plate };
/// let con1 = SupportSet::preset("Con 1", Condition::BothFixed);
/// // x²y²/(3EIL) at midspan: L³/(48EI) (eq. 12).
/// let c = beam.compliance(&con1, 0.2292, 0.18)?.compliance.total();
/// let ei = plate.beam_bending_stiffness();
/// assert!((c / (0.4584f64.powi(3) / (48.0 * ei)) - 1.0).abs() < 1e-14);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct BeamModel<'a> {
    /// The plate the beam stands for.
    pub plate: &'a analytic::Plate,
}

impl ComplianceModel for BeamModel<'_> {
    fn name(&self) -> &str {
        "beam"
    }
    fn resolves_width(&self) -> bool {
        false
    }
    fn compliance(&self, set: &SupportSet, x: f64, _z: f64) -> Result<Estimate, ModelError> {
        let condition = set.beam_condition().ok_or_else(|| ModelError::NotApplicable {
            model: "beam".into(),
            set: set.name.clone(),
            reason: "the beam model describes only the paper's Con 1-3 (corner pairs fixed or on one spring stiffness, edges free)".into(),
        })?;
        Ok(Estimate::exact(beam_compliance(self.plate, condition, x)?))
    }
}
