//! # Kirchhoff plate finite elements with corner point supports and springs
//!
//! The compliance C(x, z) of a thin rectangular plate at any point, under any combination
//! of corner supports (fixed or springs) and edge supports (simple, clamped or elastic line
//! springs), with its split into the plate's strain energy and each spring's energy, and
//! the support reactions. The crate knows nothing about rocks or spheres.
//!
//! It reads top-down:
//! - [`mesh`]: tensor grids over [0, L] x [0, B];
//! - [`element`]: the Bogner-Fox-Schmit rectangle (conforming C¹, bicubic Hermite);
//! - [`assembly`]: the weak form as code: bending, inertia and edge-spring forms, each a
//!   small integrand, integrated over elements and element sides by one Gauss assembler;
//! - [`supports`]: corners, edges (free, simple, clamped or elastic), and the rigid-body
//!   check;
//! - [`model`]: assembly with one symbolic Cholesky analysis per mesh, one numeric
//!   factorization per support set (faer), and point probes by reciprocity;
//! - [`corners`]: any corner stiffness set from one factorization, by a rank-4 update
//!   or, where that is ill conditioned, by condensation onto the corners;
//! - [`dynamics`]: Newmark time stepping of the supported plate;
//! - [`modes`]: its lowest eigenpairs (shift-invert block Krylov) and the residual
//!   flexibility of the modes left out;
//! - [`classical`]: Navier and Lévy series, the references of the tests;
//! - [`convergence`]: Richardson extrapolation and observed rates.
//!
//! The plate is Kirchhoff's: flexural rigidity D = E h³ / 12(1 - ν²), transverse shear
//! neglected. Lengths are in m, forces in N, compliances in m/N.
//!
//! # Example: a plate probe
//!
//! A simply supported square plate (Navier's plate) under a centre load deflects
//! w = 0.01160 P a²/D at the load (Timoshenko & Woinowsky-Krieger, Table 23). On a 16 x 16
//! mesh of BFS elements the compliance at the centre is within 1e-3 of that, and below it,
//! as it must be for a conforming element.
//!
//! ```
//! use plate_fem::{Mesh, Model, PlateProperties, Supports};
//!
//! let a = 1.0;
//! let plate = PlateProperties {
//!     length: a,
//!     width: a,
//!     thickness: 0.01,
//!     youngs_modulus: 210e9,
//!     poisson_ratio: 0.3,
//!     density: 7850.0,
//! };
//! let model = Model::new(plate, Mesh::uniform(a, a, 16, 16)?)?;
//! let supported = model.factorize(&Supports::all_edges_simple())?;
//! let probe = supported.respond(a / 2.0, a / 2.0)?;
//! let navier = 0.01160 * a * a / plate.rigidity();
//! assert!((probe.compliance / navier - 1.0).abs() < 1e-3, "C = {:e} m/N", probe.compliance);
//! assert!(probe.compliance < navier); // conforming: the FE plate is too stiff
//! assert!(probe.residual < 1e-12);
//! # Ok::<(), plate_fem::FemError>(())
//! ```

#![warn(missing_docs)]

pub mod assembly;
pub mod classical;
pub mod convergence;
pub mod corners;
pub mod dynamics;
pub mod element;
pub mod mesh;
pub mod mindlin;
pub mod model;
pub mod modes;
pub mod patch;
pub mod shell;
pub mod supports;

/// faer, re-exported: [`Factorization::solve_in_place`] takes a `faer::Mat<f64>`,
/// [`Model::supported_stiffness`] returns a `faer::sparse::SparseColMat`, and
/// [`FemError::Factorization`] carries faer's own errors; using these names guarantees the
/// same version of faer as this crate's.
pub use faer;
/// nalgebra, re-exported: element matrices ([`element::Mat16`]), the corner flexibility of
/// [`CornerFamily`] and [`corners::BasePoint::u`] are nalgebra types; using these names
/// guarantees the same version of nalgebra as this crate's.
pub use nalgebra;

pub use corners::CornerFamily;
pub use mesh::Mesh;
pub use model::{Factorization, Model, PlateProperties, PointResponse};
pub use modes::{Modes, ResidualFlexibility};
pub use patch::Patch;
pub use supports::{Corner, CornerSupport, Edge, EdgeSupport, Supports};

/// Everything that can go wrong, each with what to change.
#[derive(Debug, Clone, thiserror::Error)]
pub enum FemError {
    /// The mesh (or a time step) is not usable: too few lines, lines not increasing, or
    /// not spanning the plate.
    #[error("mesh: {0}")]
    Mesh(String),
    /// A probe point lies outside the plate.
    #[error("point (x = {x} m, z = {z} m) is outside the plate [0, {length}] x [0, {width}] m")]
    OutsidePlate {
        /// Requested x (m).
        x: f64,
        /// Requested z (m).
        z: f64,
        /// Plate length L (m).
        length: f64,
        /// Plate width B (m).
        width: f64,
    },
    /// A support value is out of range (a spring stiffness not positive and finite).
    #[error("supports: {0}")]
    Support(String),
    /// The supports leave a rigid-body motion w = c₀ + c₁x + c₂z free, or a small corner
    /// system is singular.
    #[error("singular support set: {0}")]
    Singular(String),
    /// A plate property is out of range.
    #[error("plate property {name} = {value} is outside the allowed range {allowed}")]
    Property {
        /// Which property.
        name: &'static str,
        /// The refused value (SI).
        value: f64,
        /// The allowed range, as text.
        allowed: &'static str,
    },
    /// A sparse step of faer failed: the sparsity pattern, its symbolic analysis, the
    /// matrix values or the numeric Cholesky factorization.
    #[error("{stage} failed: {advice}")]
    Factorization {
        /// Which step.
        stage: &'static str,
        /// What the failure means for the plate model and what to change.
        advice: String,
        /// faer's error, kept whole.
        #[source]
        source: SparseError,
    },
    /// A mesh file that cannot be read: its origin, the line (1-based; 0 where the fault is
    /// the file's as a whole) and what is wrong there.
    #[error("{origin}, line {line}: {message}")]
    MeshFile {
        /// The file's name as given.
        origin: String,
        /// The line, from 1 (0: the whole file).
        line: usize,
        /// What is wrong, with the value as written and what is allowed.
        message: String,
    },
    /// An eigenvalue request that cannot be met: more modes than degrees of freedom, or a
    /// subspace iteration that did not reach its residual tolerance.
    #[error("modes: {0}")]
    Modes(String),
    /// A corner-update result that failed its a-posteriori check (see [`corners`]): the
    /// corner set with its stiffnesses, the base spring stiffness, and what failed.
    #[error("corner update to {corners} (base springs {k_base:e} N/m) failed its accuracy check: {what}")]
    CornerUpdate {
        /// The corner set, each corner with its support and stiffness.
        corners: String,
        /// Stiffness k_b of the base springs (N/m).
        k_base: f64,
        /// Which check failed, with the values.
        what: String,
    },
}

/// The error faer reported from one of its sparse routines.
#[derive(Debug, Clone, Copy, thiserror::Error)]
pub enum SparseError {
    /// From building the sparsity pattern from the assembled indices.
    #[error(transparent)]
    Creation(#[from] faer::sparse::CreationError),
    /// An allocation or index overflow in the symbolic analysis or the value fill.
    #[error(transparent)]
    Generic(#[from] faer::sparse::FaerError),
    /// From the numeric Cholesky factorization: a non-positive pivot, or a generic error.
    #[error(transparent)]
    Llt(#[from] faer::sparse::linalg::LltError),
}

impl FemError {
    /// The error of a failed faer step on a system of `dofs` unknowns, with advice that
    /// follows from what faer reports.
    pub(crate) fn sparse(stage: &'static str, dofs: usize, source: impl Into<SparseError>) -> Self {
        use faer::linalg::cholesky::llt::factor::LltError as Pivot;
        use faer::sparse::{linalg::LltError, CreationError, FaerError};
        let source = source.into();
        let generic = |e: FaerError| match e {
            FaerError::IndexOverflow => {
                format!("{dofs} degrees of freedom overflow faer's sparse indices; use a coarser mesh")
            }
            FaerError::OutOfMemory => {
                format!("not enough memory for the sparse matrix of {dofs} degrees of freedom; use a coarser mesh")
            }
            // FaerError is non-exhaustive.
            other => format!("faer reported {other:?} for {dofs} degrees of freedom; use a coarser mesh"),
        };
        let advice = match source {
            SparseError::Creation(CreationError::Generic(e)) | SparseError::Generic(e) | SparseError::Llt(LltError::Generic(e)) => {
                generic(e)
            }
            SparseError::Creation(CreationError::OutOfBounds { row, col }) => format!(
                "assembled entry ({row}, {col}) lies outside the {dofs} x {dofs} stiffness; the mesh numbering is inconsistent, which is a defect of this crate"
            ),
            SparseError::Llt(LltError::Numeric(Pivot::NonPositivePivot { index })) => format!(
                "the supported stiffness is not positive definite in double precision (pivot {index} of {dofs}): the ratio between the stiffest and softest parts (springs against the plate's D/L², or element size against plate size) is too extreme; bring the spring stiffnesses closer to the plate's or use a coarser mesh"
            ),
        };
        Self::Factorization { stage, advice, source }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::error::Error;

    /// K - 1e20 M is indefinite, so the numeric Cholesky meets a non-positive pivot: the
    /// error names the step, says what to change, and keeps faer's error as its source.
    #[test]
    fn failed_factorization_keeps_faer_error() {
        let props = PlateProperties {
            length: 1.0,
            width: 1.0,
            thickness: 0.01,
            youngs_modulus: 210e9,
            poisson_ratio: 0.3,
            density: 7850.0,
        };
        let model = Model::new(props, Mesh::uniform(1.0, 1.0, 4, 4).unwrap()).unwrap();
        let e = match model.factorize_shifted(&Supports::con1(), -1e20) {
            Err(e) => e,
            Ok(_) => panic!("an indefinite matrix factorized"),
        };
        assert!(matches!(e, FemError::Factorization { stage: "numeric Cholesky factorization", .. }), "{e}");
        assert!(e.to_string().contains("not positive definite"), "{e}");
        let source = e.source().and_then(|s| s.downcast_ref::<SparseError>());
        assert!(
            matches!(
                source,
                Some(SparseError::Llt(faer::sparse::linalg::LltError::Numeric(
                    faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { .. }
                )))
            ),
            "{source:?}"
        );
    }
}
