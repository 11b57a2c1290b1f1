//! # Kirchhoff plate finite elements with corner point supports and springs
//!
//! The compliance C(x, z) of a thin rectangular plate at any point, under any combination
//! of corner supports (fixed or springs) and edge supports (simple or clamped), with its
//! split into the plate's strain energy and each spring's energy, and the support
//! reactions. The crate knows nothing about rocks or spheres.
//!
//! It reads top-down:
//! - [`mesh`]: tensor grids over [0, L] x [0, B];
//! - [`element`]: the Bogner-Fox-Schmit rectangle (conforming C¹, bicubic Hermite);
//! - [`supports`]: corners, edges, and the rigid-body check;
//! - [`model`]: assembly with one symbolic Cholesky analysis per mesh, one numeric
//!   factorization per support set (faer), and point probes by reciprocity;
//! - [`corners`]: any corner stiffness set from one factorization, by a rank-4 update
//!   or, where that is ill conditioned, by condensation onto the corners;
//! - [`classical`]: Navier and Lévy series, the references of the tests;
//! - [`convergence`]: Richardson extrapolation and observed rates.

pub mod classical;
pub mod convergence;
pub mod corners;
pub mod dynamics;
pub mod element;
pub mod mesh;
pub mod model;
pub mod supports;

pub use corners::CornerFamily;
pub use mesh::Mesh;
pub use model::{Factorization, Model, PlateProperties, PointResponse};
pub use supports::{Corner, CornerSupport, Edge, EdgeSupport, Supports};

/// Everything that can go wrong, each with what to change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FemError {
    #[error("mesh: {0}")]
    Mesh(String),
    #[error("point (x = {x} m, z = {z} m) is outside the plate [0, {length}] x [0, {width}] m")]
    OutsidePlate { x: f64, z: f64, length: f64, width: f64 },
    #[error("supports: {0}")]
    Support(String),
    #[error("singular support set: {0}")]
    Singular(String),
    #[error("plate property {name} = {value} is outside the allowed range {allowed}")]
    Property { name: &'static str, value: f64, allowed: &'static str },
    #[error("factorization failed: {0}")]
    Factorization(String),
    /// A corner-update result that failed its a-posteriori check (see [`corners`]): the
    /// corner set with its stiffnesses, the base spring stiffness, and what failed.
    #[error("corner update to {corners} (base springs {k_base:e} N/m) failed its accuracy check: {what}")]
    CornerUpdate { corners: String, k_base: f64, what: String },
}
