//! # The coupled impact of a rock sphere on a supported plate
//!
//! The paper's model (crate `analytic`) needs one thing from the plate: its compliance at
//! the impact point, split into energy stores. This crate supplies it from two models
//! behind one trait, runs the scene's plan through the same energy balance and yield model,
//! says of every result whether it is inside its model's assumptions, and integrates the
//! whole impact in time where the quasi-static assumption is in doubt.
//!
//! It reads top-down:
//! - [`supports`]: support sets (any corner fixed / spring / free, any edge free / simply
//!   supported / clamped) and the paper's Con 1-3 as presets;
//! - [`scene`]: a validated scene in SI units;
//! - [`discretisation`]: the plate in `plate_fem` terms and its meshes;
//! - [`compliance`]: the [`ComplianceModel`] seam, the beam ([`BeamModel`]) and the plate
//!   finite elements with Richardson error estimates ([`PlateModel`]);
//! - [`validity`]: elastic range, quasi-static validity, thin-plate range, re-contact;
//! - [`regimes`]: Olsson's and Christoforou and Yigit's impact regimes, the closed-form rule
//!   for the quasi-static balance, and one measured case of the regime map;
//! - [`transient`]: the sphere, the Flores contact and the plate dynamics in time;
//! - [`reduced`]: the same impact on the plate's lowest modes plus a static correction,
//!   fast enough for ensembles, with sensor signals;
//! - [`plan`]: every model filling one row schema for a scene;
//! - [`yield_root`]: the transient yield velocity, the v at which the transient δ_max
//!   reaches δ_my of eq. 51;
//! - [`identification`]: the random-impact ensemble of crate `identify` on the reduced model,
//!   one support set at a time, features only.
//!
//! No function here reads or writes files or knows of terminals.
//!
//! ```
//! use analytic::{Condition, Elastic, Plate};
//! use coupled::{BeamModel, ComplianceModel, PlateModel, SupportSet};
//! use plate_fem::{CornerSupport, EdgeSupport, Supports};
//! let plate = Plate::new(0.4584, 0.36, 0.008, 7850.0, Elastic::new(210e9, 0.3)?)?;
//! // A general support set: the left edge clamped, the right corners on springs.
//! let clamped = SupportSet::new("clamped + springs", Supports {
//!     corners: [CornerSupport::Free, CornerSupport::Spring(1e6), CornerSupport::Free, CornerSupport::Spring(1e6)],
//!     edges: [EdgeSupport::Clamped, EdgeSupport::Free, EdgeSupport::Free, EdgeSupport::Free],
//! });
//! let point = (0.2292, 0.18);
//! // The beam does not describe it; the plate does.
//! assert!(BeamModel { plate: &plate }.compliance(&clamped, point.0, point.1).is_err());
//! let fe = PlateModel::compute(&plate, &[clamped.clone()], &[point], 10, 2)?;
//! assert!(fe.compliance(&clamped, point.0, point.1)?.compliance.total() > 0.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(missing_docs)]

pub mod compliance;
pub mod discretisation;
pub mod error;
pub mod identification;
pub mod plan;
pub mod reduced;
pub mod regimes;
pub mod scene;
pub mod supports;
pub mod transient;
pub mod validity;
pub mod yield_root;

pub use compliance::{BeamModel, ComplianceModel, Estimate, PlateModel};
pub use error::ModelError;
pub use plan::{ModelKind, ResponseRow, Results, RowOutcome, YieldRow};
pub use scene::{Analysis, Points, Scene};
pub use supports::SupportSet;
pub use validity::Validity;
