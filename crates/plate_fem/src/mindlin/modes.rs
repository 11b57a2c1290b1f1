//! The fundamental mode of the supported Mindlin plate, by inverse iteration.
//!
//! With the stiffness factorized, y = K⁻¹ M x converges to the lowest mode at the rate
//! ω₁²/ω₂² per step, and the Rayleigh quotient ω² = yᵀ M x / yᵀ M y of each iterate bounds ω₁²
//! from above. The mass is the consistent one of [`super::element::mass`], with the rotary
//! inertia ρh³/12 of Mindlin's theory, assembled only when the mode is asked for.

use super::{element, Supported};
use crate::model::symmetric_upper_apply;
use crate::FemError;
use faer::sparse::SparseColMat;
use faer::Mat;
use serde::Serialize;

/// Relative change of ω² between iterates at which the iteration stops.
pub const TOLERANCE: f64 = 1e-12;
/// Most iterations: enough for ω₁/ω₂ up to 0.93.
pub const MAX_ITERATIONS: usize = 500;

/// The lowest natural frequency.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Fundamental {
    /// Angular frequency ω₁ (rad/s).
    pub omega: f64,
    /// Period T₁ = 2π/ω₁ (s).
    pub period: f64,
    /// Inverse iterations taken.
    pub iterations: usize,
}

impl Supported<'_> {
    /// The lowest natural frequency of the supported plate.
    pub fn fundamental(&self) -> Result<Fundamental, FemError> {
        let plate = self.plate;
        let props = plate.props();
        let (rho_h, rho_i) = (props.density * props.thickness, props.density * props.thickness.powi(3) / 12.0);
        let n = self.numbering.unknowns;
        let triplets = plate.reduced(&self.numbering, |ex, ez| {
            let (a, b) = plate.mesh().element_size(ex, ez);
            element::mass(a, b, rho_h, rho_i)
        });
        let mass = SparseColMat::try_new_from_triplets(n, n, &triplets)
            .map_err(|e| FemError::sparse("mass sparsity pattern", n, e))?;
        let mut x = vec![1.0; n];
        let mut previous = f64::INFINITY;
        for iterations in 1..=MAX_ITERATIONS {
            let mx = symmetric_upper_apply(&mass, &x);
            let mut y = Mat::<f64>::from_fn(n, 1, |i, _| mx[i]);
            self.factor.solve_in_place(y.as_mut());
            let y: Vec<f64> = (0..n).map(|i| y[(i, 0)]).collect();
            let my = symmetric_upper_apply(&mass, &y);
            let (ymx, ymy) = (dot(&y, &mx), dot(&y, &my));
            let omega2 = ymx / ymy;
            if !(omega2.is_finite() && omega2 > 0.0) {
                return Err(FemError::Modes(format!("inverse iteration reached ω² = {omega2} at step {iterations}")));
            }
            if (previous - omega2).abs() <= TOLERANCE * omega2 {
                let omega = omega2.sqrt();
                return Ok(Fundamental { omega, period: 2.0 * std::f64::consts::PI / omega, iterations });
            }
            previous = omega2;
            let norm = ymy.sqrt();
            x = y.iter().map(|v| v / norm).collect();
        }
        Err(FemError::Modes(format!(
            "inverse iteration did not settle to {TOLERANCE:e} in {MAX_ITERATIONS} steps (the two lowest modes are too close)"
        )))
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
