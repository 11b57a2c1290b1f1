//! What holds a structure: DOFs held at zero and translational springs to ground.

use super::element::DOFS_PER_NODE;
use crate::FemError;
use nalgebra::Vector3;
use serde::Serialize;

/// A translational spring from a node to ground: a jack, a pad, a foundation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Spring {
    /// The node.
    pub node: usize,
    /// The line of action (any length; normalised).
    pub direction: [f64; 3],
    /// Stiffness along it (N/m).
    pub stiffness: f64,
}

impl Spring {
    /// The spring's force (N), positive in compression along `direction`'s stretch sign,
    /// under the displacements `u` (all DOFs).
    pub fn force(&self, u: &[f64]) -> f64 {
        let d = Vector3::from(self.direction).normalize();
        let n = DOFS_PER_NODE * self.node;
        self.stiffness * d.dot(&Vector3::new(u[n], u[n + 1], u[n + 2]))
    }

    /// The spring's force as a functional of the displacements: (DOF, coefficient) for its
    /// node's three translations, so that the force is Σ c u (equal to [`Self::force`] up to
    /// rounding).
    pub fn coefficients(&self) -> [(usize, f64); 3] {
        let d = Vector3::from(self.direction).normalize();
        let n = DOFS_PER_NODE * self.node;
        [(n, self.stiffness * d.x), (n + 1, self.stiffness * d.y), (n + 2, self.stiffness * d.z)]
    }

    /// Refused unless its node exists among `nodes`, its direction is finite and not zero, and
    /// 0 < k < inf.
    pub fn check(&self, nodes: usize) -> Result<(), FemError> {
        let norm = Vector3::from(self.direction).norm();
        if self.node >= nodes
            || !(norm.is_finite() && norm > 0.0)
            || !(self.stiffness.is_finite() && self.stiffness > 0.0)
        {
            return Err(FemError::Support(format!(
                "spring on node {} along {:?} with k = {} N/m: needs an existing node, a direction and 0 < k < inf",
                self.node, self.direction, self.stiffness
            )));
        }
        Ok(())
    }
}

/// What holds a structure: DOFs held at zero and springs to ground.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Restraints {
    /// (node, DOF) pairs held at zero; DOFs 0-2 translations, 3-5 rotations, global axes.
    pub held: Vec<(usize, usize)>,
    /// Springs to ground.
    pub springs: Vec<Spring>,
}

impl Restraints {
    /// Holds the given DOFs of `node`.
    pub fn hold(&mut self, node: usize, dofs: &[usize]) {
        self.held.extend(dofs.iter().map(|&d| (node, d)));
    }
}
