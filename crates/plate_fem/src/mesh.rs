//! Structured rectangular meshes: a tensor grid of node lines x_i, z_j over [0, L] x [0, B].
//!
//! Nodes are numbered row by row (i fastest); each carries the four Bogner-Fox-Schmit
//! degrees of freedom (w, w_x, w_z, w_xz), so node n owns DOFs 4n..4n+3.

use crate::FemError;
use serde::Serialize;

/// Degrees of freedom per node.
pub const DOFS_PER_NODE: usize = 4;

/// A tensor-product grid over the plate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Mesh {
    xs: Vec<f64>,
    zs: Vec<f64>,
}

/// Where a point falls: the element and its local coordinates in [0, 1]².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Location {
    /// Element column (along x).
    pub ex: usize,
    /// Element row (along z).
    pub ez: usize,
    /// Local coordinate ξ = (x - x_ex)/a in [0, 1].
    pub xi: f64,
    /// Local coordinate η = (z - z_ez)/b in [0, 1].
    pub eta: f64,
}

impl Mesh {
    /// `nx` x `nz` equal elements over [0, length] x [0, width].
    pub fn uniform(length: f64, width: f64, nx: usize, nz: usize) -> Result<Self, FemError> {
        if nx == 0 || nz == 0 {
            return Err(FemError::Mesh(format!("element counts nx = {nx}, nz = {nz} must both be at least 1")));
        }
        Self::from_lines(
            (0..=nx).map(|i| length * i as f64 / nx as f64).collect(),
            (0..=nz).map(|j| width * j as f64 / nz as f64).collect(),
        )
    }

    /// A grid with the given node lines (strictly increasing, at least two each).
    pub fn from_lines(mut xs: Vec<f64>, mut zs: Vec<f64>) -> Result<Self, FemError> {
        for (name, v) in [("x", &xs), ("z", &zs)] {
            if v.len() < 2 || v.iter().any(|x| !x.is_finite()) || v.windows(2).any(|w| w[1] <= w[0]) {
                return Err(FemError::Mesh(format!(
                    "{name} node lines must be finite and strictly increasing, at least two"
                )));
            }
        }
        // Pin the ends exactly so that points on the boundary locate without rounding.
        let (x0, z0) = (xs[0], zs[0]);
        xs.iter_mut().for_each(|x| *x -= x0);
        zs.iter_mut().for_each(|z| *z -= z0);
        Ok(Self { xs, zs })
    }

    /// The node lines x_i (m), from 0.
    pub fn xs(&self) -> &[f64] {
        &self.xs
    }
    /// The node lines z_j (m), from 0.
    pub fn zs(&self) -> &[f64] {
        &self.zs
    }
    /// Plate length L, the last x line (m).
    pub fn length(&self) -> f64 {
        // The constructors keep at least two lines, so the last one exists.
        self.xs.last().copied().unwrap_or(0.0)
    }
    /// Plate width B, the last z line (m).
    pub fn width(&self) -> f64 {
        self.zs.last().copied().unwrap_or(0.0)
    }
    /// Elements along x.
    pub fn nx(&self) -> usize {
        self.xs.len() - 1
    }
    /// Checks that the mesh spans a plate of `length` x `width` (m), to 1e-9 of its size.
    pub fn check_spans(&self, length: f64, width: f64) -> Result<(), FemError> {
        let tol = 1e-9 * length.max(width);
        if (self.length() - length).abs() > tol || (self.width() - width).abs() > tol {
            return Err(FemError::Mesh(format!(
                "mesh spans {} x {} m but the plate is {} x {} m",
                self.length(),
                self.width(),
                length,
                width
            )));
        }
        Ok(())
    }

    /// Elements along z.
    pub fn nz(&self) -> usize {
        self.zs.len() - 1
    }
    /// Number of nodes.
    pub fn nodes(&self) -> usize {
        self.xs.len() * self.zs.len()
    }
    /// Number of degrees of freedom, four per node.
    pub fn dofs(&self) -> usize {
        DOFS_PER_NODE * self.nodes()
    }
    /// Number of elements.
    pub fn elements(&self) -> usize {
        self.nx() * self.nz()
    }
    /// Node number of grid node (i, j).
    pub fn node(&self, i: usize, j: usize) -> usize {
        j * self.xs.len() + i
    }
    /// Every node's (x, z), in node-number order (x fastest).
    pub fn node_points(&self) -> Vec<[f64; 2]> {
        self.zs.iter().flat_map(|&z| self.xs.iter().map(move |&x| [x, z])).collect()
    }
    /// Every element's four nodes, counter-clockwise from its (x, z)-lowest corner, in
    /// element order (x fastest): the quadrilaterals of a VTK or meshio grid.
    pub fn quads(&self) -> Vec<[usize; 4]> {
        let (nx, nz) = (self.nx(), self.nz());
        (0..nz)
            .flat_map(|ez| (0..nx).map(move |ex| (ex, ez)))
            .map(|(ex, ez)| {
                [self.node(ex, ez), self.node(ex + 1, ez), self.node(ex + 1, ez + 1), self.node(ex, ez + 1)]
            })
            .collect()
    }
    /// Largest element side.
    pub fn h_max(&self) -> f64 {
        let m = |v: &[f64]| v.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
        m(&self.xs).max(m(&self.zs))
    }
    /// The 16 global DOFs of element (ex, ez), in the local order of [`crate::element`]:
    /// local nodes (0,0), (1,0), (0,1), (1,1), each (w, w_x, w_z, w_xz).
    pub fn element_dofs(&self, ex: usize, ez: usize) -> [usize; 16] {
        let mut d = [0; 16];
        for (k, (di, dj)) in [(0, 0), (1, 0), (0, 1), (1, 1)].into_iter().enumerate() {
            let n = self.node(ex + di, ez + dj);
            for q in 0..DOFS_PER_NODE {
                d[4 * k + q] = DOFS_PER_NODE * n + q;
            }
        }
        d
    }
    /// Element sizes (a along x, b along z).
    pub fn element_size(&self, ex: usize, ez: usize) -> (f64, f64) {
        (self.xs[ex + 1] - self.xs[ex], self.zs[ez + 1] - self.zs[ez])
    }

    /// The element holding (x, z); a point on a shared line goes to the element after it
    /// (the last element at the far edge). Outside the plate is an error.
    pub fn locate(&self, x: f64, z: f64) -> Result<Location, FemError> {
        let (l, b) = (self.length(), self.width());
        if !(x.is_finite() && z.is_finite() && (0.0..=l).contains(&x) && (0.0..=b).contains(&z)) {
            return Err(FemError::OutsidePlate { x, z, length: l, width: b });
        }
        let find = |v: &[f64], p: f64| {
            let k = v.partition_point(|&t| t <= p);
            k.clamp(1, v.len() - 1) - 1
        };
        let (ex, ez) = (find(&self.xs, x), find(&self.zs, z));
        let (a, bb) = self.element_size(ex, ez);
        Ok(Location {
            ex,
            ez,
            xi: ((x - self.xs[ex]) / a).clamp(0.0, 1.0),
            eta: ((z - self.zs[ez]) / bb).clamp(0.0, 1.0),
        })
    }

    /// The w DOF of the corner node at (x = 0 or L, z = 0 or B), corners in the order
    /// of [`crate::supports::Corner`].
    pub fn corner_w_dof(&self, corner: usize) -> usize {
        let (i, j) = match corner {
            0 => (0, 0),
            1 => (self.nx(), 0),
            2 => (0, self.nz()),
            _ => (self.nx(), self.nz()),
        };
        DOFS_PER_NODE * self.node(i, j)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locate_interior_edges_and_corners() {
        let m = Mesh::uniform(2.0, 1.0, 4, 2).unwrap();
        let l = m.locate(0.6, 0.25).unwrap();
        assert_eq!((l.ex, l.ez), (1, 0));
        assert!((l.xi - 0.2).abs() < 1e-12 && (l.eta - 0.5).abs() < 1e-12);
        let far = m.locate(2.0, 1.0).unwrap();
        assert_eq!((far.ex, far.ez, far.xi, far.eta), (3, 1, 1.0, 1.0));
        let origin = m.locate(0.0, 0.0).unwrap();
        assert_eq!((origin.ex, origin.ez, origin.xi, origin.eta), (0, 0, 0.0, 0.0));
        assert!(m.locate(2.0000001, 0.5).is_err());
        assert!(m.locate(f64::NAN, 0.5).is_err());
    }

    #[test]
    fn bad_meshes_are_rejected() {
        assert!(Mesh::uniform(1.0, 1.0, 0, 3).is_err());
        assert!(Mesh::from_lines(vec![0.0, 1.0, 1.0], vec![0.0, 1.0]).is_err());
    }

    #[test]
    fn element_dofs_are_node_blocks() {
        let m = Mesh::uniform(1.0, 1.0, 2, 2).unwrap();
        let d = m.element_dofs(1, 1);
        assert_eq!(&d[..4], &[16, 17, 18, 19]); // node (1,1) = 4
        assert_eq!(&d[12..], &[32, 33, 34, 35]); // node (2,2) = 8
    }
}
