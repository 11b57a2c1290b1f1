//! Supports: corner points (fixed or on springs) and edges (simply supported, clamped or on
//! an elastic line support), in any combination, with the rigid-body check that must pass
//! before factorization.
//!
//! A held DOF (a fixed corner, a simple or clamped edge) is a constraint; a spring is
//! energy: a corner spring ½ k w² at one DOF, an elastic edge ½ k ∮ w² ds along the edge,
//! the Winkler form of [`crate::assembly::winkler`] on the element sides that lie on it.

use crate::mesh::{Mesh, DOFS_PER_NODE};
use crate::FemError;
use nalgebra::{DMatrix, SVD};
use serde::Serialize;

/// The four corners, in the order used everywhere in this crate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Corner {
    /// x = 0, z = 0.
    LeftNear,
    /// x = L, z = 0.
    RightNear,
    /// x = 0, z = B.
    LeftFar,
    /// x = L, z = B.
    RightFar,
}

impl Corner {
    /// The four corners in this crate's order.
    pub const ALL: [Corner; 4] = [Corner::LeftNear, Corner::RightNear, Corner::LeftFar, Corner::RightFar];
    /// Position in [`Corner::ALL`], 0 to 3.
    pub fn index(self) -> usize {
        self as usize
    }
    /// The corner's name in messages and reports, "corner (L, 0)" etc.
    pub fn name(self) -> &'static str {
        ["corner (0, 0)", "corner (L, 0)", "corner (0, B)", "corner (L, B)"][self.index()]
    }
    /// Position on a plate of length `l`, width `b`.
    pub fn position(self, l: f64, b: f64) -> (f64, f64) {
        [(0.0, 0.0), (l, 0.0), (0.0, b), (l, b)][self.index()]
    }
}

/// What holds a corner.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum CornerSupport {
    /// Nothing holds the corner.
    Free,
    /// w = 0, rotations free.
    Fixed,
    /// A vertical spring of stiffness k (N/m), k > 0 and finite.
    Spring(f64),
}

/// What holds an edge.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum EdgeSupport {
    /// Nothing holds the edge.
    Free,
    /// w = 0 along the edge (so its tangential slope vanishes), normal slope free.
    Simple,
    /// w = 0 and normal slope = 0 along the edge.
    Clamped,
    /// An elastic line support: a Winkler spring of stiffness k per length (N/m², k > 0
    /// and finite) under the whole edge, pressing back with k w per length; slopes free.
    /// The limit k → 0 is the free edge, k → ∞ the simply supported one.
    ///
    /// Scenes do not offer it yet (the scene format and the command line name free,
    /// simply supported and clamped edges only); it is used through this library.
    ///
    /// ```
    /// use plate_fem::{EdgeSupport, Mesh, Model, PlateProperties, Supports};
    /// let plate = PlateProperties {
    ///     length: 1.0,
    ///     width: 0.6,
    ///     thickness: 0.01,
    ///     youngs_modulus: 210e9,
    ///     poisson_ratio: 0.3,
    ///     density: 7850.0,
    /// };
    /// let model = Model::new(plate, Mesh::uniform(1.0, 0.6, 10, 6)?)?;
    /// let centre = (0.5, 0.3);
    /// let on = |edge| {
    ///     let s = Supports { edges: [EdgeSupport::Simple, EdgeSupport::Simple, edge, edge], ..Supports::FREE };
    ///     model.factorize(&s)?.respond(centre.0, centre.1)
    /// };
    /// // Between the free and the simply supported edges, and the springs hold energy.
    /// let (free, simple) = (on(EdgeSupport::Free)?, on(EdgeSupport::Simple)?);
    /// let elastic = on(EdgeSupport::Elastic(1e6))?;
    /// assert!(simple.compliance < elastic.compliance && elastic.compliance < free.compliance);
    /// assert!(elastic.edge_spring_compliance > 0.0);
    /// # Ok::<(), plate_fem::FemError>(())
    /// ```
    Elastic(f64),
}

impl EdgeSupport {
    /// Whether the edge is held (w = 0 on it): simply supported or clamped.
    pub fn holds(self) -> bool {
        matches!(self, EdgeSupport::Simple | EdgeSupport::Clamped)
    }
}

/// Edges in the order x = 0, x = L, z = 0, z = B.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Edge {
    /// x = 0.
    Left,
    /// x = L.
    Right,
    /// z = 0.
    Near,
    /// z = B.
    Far,
}

impl Edge {
    /// The four edges in this crate's order.
    pub const ALL: [Edge; 4] = [Edge::Left, Edge::Right, Edge::Near, Edge::Far];
    /// The edge's name in messages, "edge x = 0" etc.
    pub fn name(self) -> &'static str {
        match self {
            Edge::Left => "edge x = 0",
            Edge::Right => "edge x = L",
            Edge::Near => "edge z = 0",
            Edge::Far => "edge z = B",
        }
    }
}

/// A complete support set.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Supports {
    /// Corners in [`Corner::ALL`] order.
    pub corners: [CornerSupport; 4],
    /// Edges in [`Edge::ALL`] order.
    pub edges: [EdgeSupport; 4],
}

impl Supports {
    /// Nothing holds the plate.
    pub const FREE: Supports = Supports { corners: [CornerSupport::Free; 4], edges: [EdgeSupport::Free; 4] };

    /// The four corners as given, edges free.
    pub fn corners(corners: [CornerSupport; 4]) -> Self {
        Self { corners, ..Self::FREE }
    }

    /// The paper's Con 1: four fixed corners.
    pub fn con1() -> Self {
        Self::corners([CornerSupport::Fixed; 4])
    }
    /// The paper's Con 2: four corner springs of stiffness k_t.
    pub fn con2(k_t: f64) -> Self {
        Self::corners([CornerSupport::Spring(k_t); 4])
    }
    /// The paper's Con 3: fixed corners at x = 0, springs at x = L.
    pub fn con3(k_t: f64) -> Self {
        use CornerSupport::*;
        Self::corners([Fixed, Spring(k_t), Fixed, Spring(k_t)])
    }
    /// All four edges simply supported (Navier's plate).
    pub fn all_edges_simple() -> Self {
        Self { edges: [EdgeSupport::Simple; 4], ..Self::FREE }
    }
    /// Edges x = 0 and x = L simply supported, z = 0 and z = B free (Lévy's plate).
    pub fn simple_free() -> Self {
        use EdgeSupport::*;
        Self { edges: [Simple, Simple, Free, Free], ..Self::FREE }
    }

    /// Checks the values and that no rigid-body motion (w = c₀ + c₁x + c₂z) stays free.
    ///
    /// A rigid motion is suppressed when the support conditions it must satisfy have rank
    /// three: each fixed corner or positive spring gives [1, x, z]; a supported or elastic
    /// edge gives its two end points (a rigid motion without energy in the edge springs
    /// vanishes on the whole edge); a clamped edge also fixes the normal slope.
    pub fn validate(&self, length: f64, width: f64) -> Result<(), FemError> {
        for (c, s) in Corner::ALL.iter().zip(&self.corners) {
            if let CornerSupport::Spring(k) = *s {
                if !(k.is_finite() && k > 0.0) {
                    return Err(FemError::Support(format!(
                        "{} spring stiffness {k} N/m is outside the allowed range (0, inf) N/m (use Free for no spring, Fixed for a rigid one)",
                        c.name()
                    )));
                }
            }
        }
        for (e, k) in self.elastic_edges() {
            if !(k.is_finite() && k > 0.0) {
                return Err(FemError::Support(format!(
                    "{} edge spring stiffness {k} N/m² is outside the allowed range (0, inf) N/m² (use Free for no support, Simple for a rigid one)",
                    e.name()
                )));
            }
        }
        // Rows scaled by the plate size so the rank test is dimensionless.
        let s = length.max(width);
        let mut rows: Vec<[f64; 3]> = Vec::new();
        for (c, sup) in Corner::ALL.iter().zip(&self.corners) {
            if *sup != CornerSupport::Free {
                let (x, z) = c.position(length, width);
                rows.push([1.0, x / s, z / s]);
            }
        }
        let ends = |e: Edge| match e {
            Edge::Left => [(0.0, 0.0), (0.0, width)],
            Edge::Right => [(length, 0.0), (length, width)],
            Edge::Near => [(0.0, 0.0), (length, 0.0)],
            Edge::Far => [(0.0, width), (length, width)],
        };
        for (e, sup) in Edge::ALL.iter().zip(&self.edges) {
            if *sup != EdgeSupport::Free {
                for (x, z) in ends(*e) {
                    rows.push([1.0, x / s, z / s]);
                }
            }
            if *sup == EdgeSupport::Clamped {
                rows.push(match e {
                    Edge::Left | Edge::Right => [0.0, 1.0, 0.0],
                    _ => [0.0, 0.0, 1.0],
                });
            }
        }
        let rank = if rows.is_empty() {
            0
        } else {
            let m = DMatrix::from_fn(rows.len(), 3, |i, j| rows[i][j]);
            SVD::new(m, false, false).singular_values.iter().filter(|&&v| v > 1e-9).count()
        };
        if rank < 3 {
            return Err(FemError::Singular(format!(
                "the supports leave {} rigid-body motion{} of the plate free (supported points and edges must not all lie on one line); corners: {:?}, edges (x=0, x=L, z=0, z=B): {:?}",
                3 - rank,
                if rank == 2 { "" } else { "s" },
                self.corners,
                self.edges
            )));
        }
        Ok(())
    }

    /// DOFs held at zero, sorted and unique.
    pub fn constrained_dofs(&self, mesh: &Mesh) -> Vec<usize> {
        let mut out = Vec::new();
        for (c, sup) in Corner::ALL.iter().zip(&self.corners) {
            if *sup == CornerSupport::Fixed {
                out.push(mesh.corner_w_dof(c.index()));
            }
        }
        let (nx, nz) = (mesh.nx(), mesh.nz());
        for (e, sup) in Edge::ALL.iter().zip(&self.edges) {
            if !sup.holds() {
                continue;
            }
            // Along an x = const edge, w and w_z interpolate w; the normal slope is w_x,
            // whose tangential derivative is w_xz. Mirror for z = const edges.
            let (nodes, tangential, normal, cross): (Vec<usize>, usize, usize, usize) = match e {
                Edge::Left => ((0..=nz).map(|j| mesh.node(0, j)).collect(), 2, 1, 3),
                Edge::Right => ((0..=nz).map(|j| mesh.node(nx, j)).collect(), 2, 1, 3),
                Edge::Near => ((0..=nx).map(|i| mesh.node(i, 0)).collect(), 1, 2, 3),
                Edge::Far => ((0..=nx).map(|i| mesh.node(i, nz)).collect(), 1, 2, 3),
            };
            for n in nodes {
                out.push(DOFS_PER_NODE * n);
                out.push(DOFS_PER_NODE * n + tangential);
                if *sup == EdgeSupport::Clamped {
                    out.push(DOFS_PER_NODE * n + normal);
                    out.push(DOFS_PER_NODE * n + cross);
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// (edge, stiffness per length) of every elastic edge, in [`Edge::ALL`] order.
    pub fn elastic_edges(&self) -> Vec<(Edge, f64)> {
        Edge::ALL
            .iter()
            .zip(&self.edges)
            .filter_map(|(&e, s)| match *s {
                EdgeSupport::Elastic(k) => Some((e, k)),
                _ => None,
            })
            .collect()
    }

    /// (corner w DOF, stiffness) of every corner spring.
    pub fn springs(&self, mesh: &Mesh) -> Vec<(usize, f64)> {
        Corner::ALL
            .iter()
            .zip(&self.corners)
            .filter_map(|(c, s)| match *s {
                CornerSupport::Spring(k) => Some((mesh.corner_w_dof(c.index()), k)),
                _ => None,
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_conditions_hold_the_plate() {
        for s in [
            Supports::con1(),
            Supports::con2(1.0),
            Supports::con3(1e9),
            Supports::all_edges_simple(),
            Supports::simple_free(),
        ] {
            s.validate(0.4584, 0.36).unwrap();
        }
    }

    #[test]
    fn rigid_body_motion_is_rejected() {
        use CornerSupport::*;
        let bad = [
            Supports::FREE,
            Supports::corners([Fixed, Fixed, Free, Free]), // a line: rotation about it is free
            Supports::corners([Fixed, Free, Free, Fixed]), // a diagonal
            Supports {
                edges: [EdgeSupport::Simple, EdgeSupport::Free, EdgeSupport::Free, EdgeSupport::Free],
                ..Supports::FREE
            },
        ];
        for s in bad {
            let e = s.validate(1.0, 0.5).unwrap_err().to_string();
            assert!(e.contains("rigid-body"), "{e}");
        }
        // One clamped edge alone holds the plate (a cantilever plate).
        let cantilever = Supports {
            edges: [EdgeSupport::Clamped, EdgeSupport::Free, EdgeSupport::Free, EdgeSupport::Free],
            ..Supports::FREE
        };
        cantilever.validate(1.0, 0.5).unwrap();
    }

    /// An elastic edge holds the plate as a simple edge does (two of them, opposite, hold
    /// it), and its stiffness must be positive and finite.
    #[test]
    fn elastic_edges_hold_and_are_checked() {
        use EdgeSupport::*;
        let two = |k| Supports { edges: [Elastic(k), Elastic(k), Free, Free], ..Supports::FREE };
        two(1e6).validate(1.0, 0.5).unwrap();
        let one = Supports { edges: [Elastic(1e6), Free, Free, Free], ..Supports::FREE };
        assert!(one.validate(1.0, 0.5).unwrap_err().to_string().contains("rigid-body"));
        for k in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = two(k).validate(1.0, 0.5).unwrap_err().to_string();
            assert!(e.contains("edge x = 0 edge spring stiffness") && e.contains("N/m²"), "{e}");
        }
        assert!(two(1e6).constrained_dofs(&Mesh::uniform(1.0, 0.5, 2, 2).unwrap()).is_empty());
        assert_eq!(two(2.0).elastic_edges(), vec![(Edge::Left, 2.0), (Edge::Right, 2.0)]);
    }

    #[test]
    fn zero_negative_or_nan_spring_is_an_error() {
        for k in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = Supports::con2(k).validate(1.0, 1.0).unwrap_err().to_string();
            assert!(e.contains("spring stiffness") && e.contains("(0, inf)"), "{e}");
        }
    }
}
