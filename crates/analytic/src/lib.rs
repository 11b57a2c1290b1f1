//! # The paper's model of a rock sphere impacting a supported metal plate
//!
//! A coal or gangue sphere of mass m strikes a steel plate at velocity v. The plate is a
//! beam on two fixed ends (Con 1), on springs at both ends (Con 2), or fixed at the left
//! and on springs at the right (Con 3). At maximum compression the sphere has stopped,
//! the Flores damping vanishes, and energy conservation gives one scalar equation in δ:
//!
//! ```text
//! ½ m v² = (2K/5e) δ^{5/2} + ½ C K² δ³            (eqs. 14, 25, 46)
//! ```
//!
//! The crate reads top-down in the order of the paper:
//! - [`params`]: allowed ranges, checked in one place;
//! - [`material`]: the plate and the spheres of Table 1;
//! - [`contact`]: contact stiffness K and the rock's energy (eqs. 1-7);
//! - [`compliance`]: C at the impact point and its energy stores, the input type that any
//!   plate model fills;
//! - [`beam`]: the paper's beam compliances for Con 1-3 (eqs. 8-12, 21-23, 31-44);
//! - [`balance`]: the balance and its two solvers (eqs. 15-19 and a bracketed Newton);
//! - [`response`]: P_max, δ_max, deflection, spring forces and energy ratios;
//! - [`strength`]: Drucker-Prager δ_my and the yield velocity (eqs. 51-54).
//!
//! Everything is SI. No function here does I/O or knows which plate model produced C.

#![warn(missing_docs)]

pub mod balance;
pub mod beam;
pub mod compliance;
pub mod contact;
pub mod material;
pub mod params;
pub mod response;
pub mod strength;

pub use balance::{EnergyBalance, Method, NotConverged, Solution};
pub use beam::{beam_compliance, BeamError, Condition, OutsideBeam};
pub use compliance::{InvalidCompliance, PointCompliance, SpringReaction, Store, StoreKind};
pub use contact::contact_stiffness;
pub use material::{Elastic, Plate, RockStrength, Sphere};
pub use params::{check, InvalidParameter, Range};
pub use response::{evaluate, respond, Impact, Response, SpringForce};
pub use strength::{yield_velocity, DruckerPrager};
