//! A uniform pressure over a rectangle: the load a contact spreads, and the one a
//! Reissner-Mindlin plate needs (its point compliance is infinite, see [`crate::mindlin`]).
//!
//! The compliance of a patch is work-conjugate: C = (1/P²) ∫ p w dA, the pressure-weighted
//! mean deflection per unit force. Its element loads are ∫ p N dA over the part of each element
//! the patch covers ([`Patch::parts`]).

use crate::{FemError, Mesh};
use serde::Serialize;

/// A uniform pressure over the rectangle of sides `side_x` x `side_z` centred at (x, z), all
/// in m; its total force is the unit of the responses.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Patch {
    /// Centre x (m).
    pub x: f64,
    /// Centre z (m).
    pub z: f64,
    /// Side along x (m).
    pub side_x: f64,
    /// Side along z (m).
    pub side_z: f64,
}

/// The part of one element a patch covers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Part {
    /// Element column.
    pub ex: usize,
    /// Element row.
    pub ez: usize,
    /// The element's sides (a, b), m.
    pub size: (f64, f64),
    /// The covered rectangle [x0, x1, z0, z1] in the element's local coordinates (m, from
    /// its lower corner).
    pub local: [f64; 4],
}

impl Patch {
    /// The patch's extent [x0, x1, z0, z1] (m).
    pub fn bounds(&self) -> [f64; 4] {
        let (hx, hz) = (self.side_x / 2.0, self.side_z / 2.0);
        [self.x - hx, self.x + hx, self.z - hz, self.z + hz]
    }

    /// A square of side `side` centred at (x, z), clipped to the plate [0, length] x [0, width]
    /// (its centre moves inward with the clipping): the contact patch of the shear-deformable
    /// models.
    pub fn clipped_square(x: f64, z: f64, side: f64, length: f64, width: f64) -> Self {
        let (x0, x1) = ((x - side / 2.0).max(0.0), (x + side / 2.0).min(length));
        let (z0, z1) = ((z - side / 2.0).max(0.0), (z + side / 2.0).min(width));
        Patch { x: 0.5 * (x0 + x1), z: 0.5 * (z0 + z1), side_x: x1 - x0, side_z: z1 - z0 }
    }

    /// The uniform pressure of a unit force over the patch (Pa/N).
    pub fn pressure(&self) -> f64 {
        1.0 / (self.side_x * self.side_z)
    }

    /// Checks that the sides are positive and the patch lies on the plate.
    pub fn validate(&self, length: f64, width: f64) -> Result<(), FemError> {
        for (name, value) in [("patch side_x", self.side_x), ("patch side_z", self.side_z)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(FemError::Property { name, value, allowed: "(0, inf) m, on the plate" });
            }
        }
        let [x0, x1, z0, z1] = self.bounds();
        let tol = 1e-12 * length.max(width);
        for (x, z) in [(x0, z0), (x1, z1)] {
            if !(x >= -tol && x <= length + tol && z >= -tol && z <= width + tol) {
                return Err(FemError::OutsidePlate { x, z, length, width });
            }
        }
        Ok(())
    }

    /// The elements the patch covers, each with the part it covers, after [`Self::validate`].
    pub fn parts(&self, mesh: &Mesh) -> Result<Vec<Part>, FemError> {
        self.validate(mesh.length(), mesh.width())?;
        let [x0, x1, z0, z1] = self.bounds();
        let (xs, zs) = (mesh.xs(), mesh.zs());
        let mut out = Vec::new();
        for ez in 0..mesh.nz() {
            let (lo, hi) = (z0.max(zs[ez]), z1.min(zs[ez + 1]));
            if hi <= lo {
                continue;
            }
            for ex in 0..mesh.nx() {
                let (left, right) = (x0.max(xs[ex]), x1.min(xs[ex + 1]));
                if right > left {
                    out.push(Part {
                        ex,
                        ez,
                        size: mesh.element_size(ex, ez),
                        local: [left - xs[ex], right - xs[ex], lo - zs[ez], hi - zs[ez]],
                    });
                }
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The parts tile the patch: their areas sum to its area, on a graded grid, with a patch
    /// straddling element lines.
    #[test]
    fn parts_tile_the_patch() {
        let mesh = Mesh::from_lines(vec![0.0, 0.1, 0.25, 0.3, 0.5], vec![0.0, 0.2, 0.35, 0.4]).unwrap();
        let patch = Patch { x: 0.27, z: 0.2, side_x: 0.2, side_z: 0.3 };
        let area: f64 =
            patch.parts(&mesh).unwrap().iter().map(|p| (p.local[1] - p.local[0]) * (p.local[3] - p.local[2])).sum();
        assert!((area - 0.06).abs() < 1e-15);
        assert!(Patch { x: 0.45, ..patch }.parts(&mesh).is_err(), "over the edge x = L");
        assert!(Patch { side_z: 0.0, ..patch }.parts(&mesh).is_err());
    }
}
