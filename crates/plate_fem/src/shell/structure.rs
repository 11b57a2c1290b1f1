//! Assembly of flat shell rectangles in space, restraints, one factorization, patch responses.

use super::element::{self, Mat24, Parts, Vec24, DOFS_PER_NODE};
use crate::mindlin::SHEAR_CORRECTION;
use crate::model::cholesky::{Cholesky, Symbolic};
use crate::patch::Patch;
use crate::{FemError, Mesh};
use faer::sparse::{SparseColMat, Triplet};
use faer::Mat;
use nalgebra::{Matrix3, Vector3};
use serde::Serialize;
use std::collections::HashMap;

pub use super::restraints::{Restraints, Spring};

/// A rectangular wall meshed as a tensor grid: its corner `origin`, two orthogonal unit axes,
/// the grid lines along each (m, from the origin, increasing from 0) and its thickness. Its
/// normal is e₁ x e₂; a patch on it is placed by (x, z) = (along e₁, along e₂).
#[derive(Debug, Clone, PartialEq)]
pub struct Face {
    origin: Vector3<f64>,
    axes: Matrix3<f64>,
    mesh: Mesh,
    thickness: f64,
}

impl Face {
    /// A wall from its corner, axes (unit and orthogonal, to 1e-9), lines and thickness (m).
    pub fn new(
        origin: [f64; 3],
        e1: [f64; 3],
        e2: [f64; 3],
        lines1: Vec<f64>,
        lines2: Vec<f64>,
        thickness: f64,
    ) -> Result<Self, FemError> {
        let (e1, e2) = (Vector3::from(e1), Vector3::from(e2));
        let unit = |v: &Vector3<f64>| (v.norm() - 1.0).abs() < 1e-9;
        if !(unit(&e1) && unit(&e2) && e1.dot(&e2).abs() < 1e-9) {
            return Err(FemError::Mesh(format!(
                "a face's axes must be orthogonal unit vectors, not {e1:?} and {e2:?}"
            )));
        }
        check_thickness(thickness)?;
        let mesh = Mesh::from_lines(lines1, lines2)?;
        let e3 = e1.cross(&e2);
        Ok(Self {
            origin: Vector3::from(origin),
            axes: Matrix3::from_rows(&[e1.transpose(), e2.transpose(), e3.transpose()]),
            mesh,
            thickness,
        })
    }

    /// The point (m) at face coordinates (x, z).
    pub fn point(&self, x: f64, z: f64) -> Vector3<f64> {
        self.origin + self.axes.row(0).transpose() * x + self.axes.row(1).transpose() * z
    }

    /// The unit normal e₁ x e₂.
    pub fn normal(&self) -> Vector3<f64> {
        self.axes.row(2).transpose()
    }

    /// The face's grid.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// Thickness (m).
    pub fn thickness(&self) -> f64 {
        self.thickness
    }
}

/// A wall's thickness: positive and finite (m).
fn check_thickness(thickness: f64) -> Result<(), FemError> {
    if thickness.is_finite() && thickness > 0.0 {
        Ok(())
    } else {
        Err(FemError::Property { name: "shell thickness", value: thickness, allowed: "(0, inf) m" })
    }
}

/// A face of a [`Structure`]: its index in the order added.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FaceId(usize);

/// One flat element: nodes in the order (0,0), (1,0), (0,1), (1,1) of its parameters (for a
/// rectangle, of its sides a along e₁ and b along e₂).
#[derive(Debug, Clone)]
pub(super) struct Element {
    pub(super) nodes: [usize; 4],
    /// Rows e₁, e₂, e₃.
    pub(super) axes: Matrix3<f64>,
    /// Its parts' index in [`Structure::parts`].
    pub(super) parts: usize,
    pub(super) shape: Shape,
    pub(super) thickness: f64,
    /// A warped element's corner heights above its mean plane (m, element node order), tied
    /// to its flat projection by rigid links ([`super::warp`]); None when flat.
    pub(super) heights: Option<[f64; 4]>,
}

/// What a uniform load and a lumped mass need of an element's shape.
#[derive(Debug, Clone, Copy)]
pub(super) enum Shape {
    /// An a x b rectangle: a quarter of ab at each node.
    Rectangle { a: f64, b: f64 },
    /// A general quadrilateral: ∫ N_k dA at node k.
    Quad { nodal_areas: [f64; 4] },
}

impl Shape {
    /// The share of the element's area at each node (m²).
    pub(super) fn nodal_areas(&self) -> [f64; 4] {
        match *self {
            Shape::Rectangle { a, b } => [a * b / 4.0; 4],
            Shape::Quad { nodal_areas } => nodal_areas,
        }
    }
}

/// Flat shell rectangles in space with their shared nodes.
#[derive(Debug, Clone)]
pub struct Structure {
    youngs_modulus: f64,
    poisson_ratio: f64,
    drilling: f64,
    pub(super) nodes: Vec<Vector3<f64>>,
    index: HashMap<[i64; 3], usize>,
    pub(super) elements: Vec<Element>,
    /// Element matrices: one per rectangle size (a, b, h), since a structure of walls repeats
    /// a few sizes, and one per general quadrilateral.
    pub(super) parts: Vec<Parts>,
    rectangles: HashMap<(u64, u64, u64), usize>,
    /// The parts of general quadrilaterals by shape (local corners in picometres) and
    /// thickness.
    quads: HashMap<([[i64; 2]; 4], u64), usize>,
    /// Each face with its elements, row-major over its grid (ez, ex).
    faces: Vec<(Face, Vec<usize>)>,
}

/// Positions closer than this (m) are one node.
const MERGE: f64 = 1e-9;

/// A position's node key: its coordinates in units of [`MERGE`].
fn position_key(p: &Vector3<f64>) -> [i64; 3] {
    [p.x, p.y, p.z].map(|v| (v / MERGE).round() as i64)
}

/// The most a quadrilateral's corners may leave its mean plane, as a fraction of its longer
/// diagonal: the flat element is built on the corners' projections and tied to its nodes by
/// rigid links ([`super::warp`]), an error of the order of this ratio in the element's
/// geometry (MacNeal and Harder's twisted beam on 12 x 2 elements is warped by 1.6 %).
pub const WARP_LIMIT: f64 = 0.05;

impl Structure {
    /// An empty structure of one isotropic material.
    pub fn new(youngs_modulus: f64, poisson_ratio: f64) -> Result<Self, FemError> {
        if !(youngs_modulus.is_finite() && youngs_modulus > 0.0) {
            return Err(FemError::Property { name: "Young's modulus", value: youngs_modulus, allowed: "(0, inf) Pa" });
        }
        if !(poisson_ratio.is_finite() && (0.0..0.5).contains(&poisson_ratio)) {
            return Err(FemError::Property { name: "Poisson ratio", value: poisson_ratio, allowed: "[0, 0.5)" });
        }
        Ok(Self {
            youngs_modulus,
            poisson_ratio,
            drilling: element::DRILLING_FACTOR,
            nodes: Vec::new(),
            index: HashMap::new(),
            elements: Vec::new(),
            parts: Vec::new(),
            rectangles: HashMap::new(),
            quads: HashMap::new(),
            faces: Vec::new(),
        })
    }

    /// The same empty structure with the drilling penalty's factor α instead of
    /// [`element::DRILLING_FACTOR`]: for the test that the results do not depend on it.
    pub fn with_drilling_factor(mut self, alpha: f64) -> Result<Self, FemError> {
        if !(alpha.is_finite() && alpha > 0.0 && self.elements.is_empty()) {
            return Err(FemError::Property {
                name: "drilling factor",
                value: alpha,
                allowed: "(0, inf), before any element",
            });
        }
        self.drilling = alpha;
        Ok(self)
    }

    fn node(&mut self, p: Vector3<f64>) -> usize {
        let key = position_key(&p);
        let next = self.nodes.len();
        *self.index.entry(key).or_insert_with(|| {
            self.nodes.push(p);
            next
        })
    }

    /// Adds the rectangle with corner `origin`, unit axes `axes` (rows e₁, e₂, e₃), sides a x b
    /// and thickness h; returns its element index.
    fn add_rectangle(&mut self, origin: Vector3<f64>, axes: Matrix3<f64>, a: f64, b: f64, h: f64) -> usize {
        let (e1, e2) = (axes.row(0).transpose(), axes.row(1).transpose());
        let nodes = [origin, origin + e1 * a, origin + e2 * b, origin + e1 * a + e2 * b].map(|p| self.node(p));
        let key = (a.to_bits(), b.to_bits(), h.to_bits());
        let (e, nu, alpha) = (self.youngs_modulus, self.poisson_ratio, self.drilling);
        let parts = *self.rectangles.entry(key).or_insert_with(|| {
            self.parts.push(Parts::new(a, b, e, nu, h, SHEAR_CORRECTION, alpha));
            self.parts.len() - 1
        });
        self.elements.push(Element {
            nodes,
            axes,
            parts,
            shape: Shape::Rectangle { a, b },
            thickness: h,
            heights: None,
        });
        self.elements.len() - 1
    }

    /// Adds a wall, merging its nodes with those already at the same positions.
    pub fn add_face(&mut self, face: &Face) -> Result<FaceId, FemError> {
        let (xs, zs) = (face.mesh.xs().to_vec(), face.mesh.zs().to_vec());
        let mut ids = Vec::with_capacity(face.mesh.elements());
        for (ez, &z) in zs.iter().take(face.mesh.nz()).enumerate() {
            for (ex, &x) in xs.iter().take(face.mesh.nx()).enumerate() {
                let (a, b) = face.mesh.element_size(ex, ez);
                ids.push(self.add_rectangle(face.point(x, z), face.axes, a, b, face.thickness));
            }
        }
        self.faces.push((face.clone(), ids));
        Ok(FaceId(self.faces.len() - 1))
    }

    /// Adds a single rectangle from its four corners in the order (0,0), (1,0), (0,1), (1,1)
    /// (a facet of a curved shell), which must form a rectangle to 1e-9 of its size.
    pub fn add_facet(&mut self, corners: [[f64; 3]; 4], thickness: f64) -> Result<usize, FemError> {
        let [p0, p1, p2, p3] = corners.map(Vector3::from);
        let (s1, s2) = (p1 - p0, p2 - p0);
        let (a, b) = (s1.norm(), s2.norm());
        let size = a.max(b);
        if !(a > 0.0 && b > 0.0 && s1.dot(&s2).abs() < 1e-9 * size * size && (p3 - p1 - s2).norm() < 1e-9 * size) {
            return Err(FemError::Mesh(format!("facet {corners:?} is not a rectangle")));
        }
        check_thickness(thickness)?;
        let (e1, e2) = (s1 / a, s2 / b);
        let axes = Matrix3::from_rows(&[e1.transpose(), e2.transpose(), e1.cross(&e2).transpose()]);
        Ok(self.add_rectangle(p0, axes, a, b, thickness))
    }

    /// Adds a quadrilateral ([`super::quad`]) from its four corners in order around its
    /// boundary (counter-clockwise seen from the side its normal points to, as meshers write
    /// them), merging its nodes with those already at the same positions; returns its element
    /// index. Its frame: e₃ the unit normal (p₂ - p₀) x (p₃ - p₁), e₁ along its first side,
    /// e₂ = e₃ x e₁. Refused if the corners are not finite, the quadrilateral is concave or
    /// degenerate, or its corners leave its mean plane by more than [`WARP_LIMIT`] of its
    /// diagonal. A warped quadrilateral (its corners off its mean plane by more than
    /// rounding) is formed on their projections and linked to its nodes ([`super::warp`]).
    pub fn add_quad(&mut self, corners: [[f64; 3]; 4], thickness: f64) -> Result<usize, FemError> {
        check_thickness(thickness)?;
        let p = corners.map(Vector3::from);
        let keys = p.map(|q| position_key(&q));
        if (0..4).any(|i| (i + 1..4).any(|j| keys[i] == keys[j])) {
            return Err(FemError::Mesh(format!("quadrilateral {corners:?} has two corners at one node")));
        }
        let normal = (p[2] - p[0]).cross(&(p[3] - p[1]));
        let size = (p[2] - p[0]).norm().max((p[3] - p[1]).norm());
        if !(normal.norm() > 1e-9 * size * size && size.is_finite()) {
            return Err(FemError::Mesh(format!("quadrilateral {corners:?} is degenerate or not finite")));
        }
        let e3 = normal.normalize();
        let centre = (p[0] + p[1] + p[2] + p[3]) / 4.0;
        let warp = p.iter().map(|q| (q - centre).dot(&e3).abs()).fold(0.0, f64::max) / size;
        if warp > WARP_LIMIT {
            return Err(FemError::Mesh(format!(
                "quadrilateral {corners:?} is warped: its corners leave its mean plane by {warp:.2e} of its diagonal, above {WARP_LIMIT:e}; split it or refine the mesh"
            )));
        }
        let side = p[1] - p[0];
        let e1 = (side - e3 * side.dot(&e3)).normalize();
        let e2 = e3.cross(&e1);
        // Boundary order 0, 1, 2, 3 is the parameter order 0, 1, 3, 2.
        let tensor = [p[0], p[1], p[3], p[2]];
        let xy = tensor.map(|q| [(q - centre).dot(&e1), (q - centre).dot(&e2)]);
        let quad = super::quad::Quad::new(xy)?;
        // Congruent elements (a refined mesh repeats a few shapes) share their matrices: the
        // shape to a picometre and the thickness.
        let shape_key = (xy.map(|c| c.map(|v| (v / 1e-12).round() as i64)), thickness.to_bits());
        let (e, nu, alpha) = (self.youngs_modulus, self.poisson_ratio, self.drilling);
        let parts = *self.quads.entry(shape_key).or_insert_with(|| {
            self.parts.push(quad.parts(e, nu, thickness, SHEAR_CORRECTION, alpha));
            self.parts.len() - 1
        });
        let nodes = tensor.map(|q| self.node(q));
        let axes = Matrix3::from_rows(&[e1.transpose(), e2.transpose(), e3.transpose()]);
        let shape = Shape::Quad { nodal_areas: quad.nodal_areas() };
        let heights = (warp > super::warp::FLAT).then(|| tensor.map(|q| (q - centre).dot(&e3)));
        self.elements.push(Element { nodes, axes, parts, shape, thickness, heights });
        Ok(self.elements.len() - 1)
    }

    /// Node positions (m).
    pub fn nodes(&self) -> &[Vector3<f64>] {
        &self.nodes
    }

    /// The nodes whose position satisfies `keep`.
    pub fn nodes_where(&self, keep: impl Fn([f64; 3]) -> bool) -> Vec<usize> {
        (0..self.nodes.len()).filter(|&n| keep(self.nodes[n].into())).collect()
    }

    /// The node nearest to `p` and its distance (m).
    pub fn nearest_node(&self, p: [f64; 3]) -> Option<(usize, f64)> {
        let p = Vector3::from(p);
        (0..self.nodes.len()).map(|n| (n, (self.nodes[n] - p).norm())).min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// The nodes of element `e` (as [`Self::add_quad`] or [`Self::add_facet`] numbered it),
    /// in its parameter order (0,0), (1,0), (0,1), (1,1).
    pub fn element_nodes(&self, e: usize) -> [usize; 4] {
        self.elements[e].nodes
    }

    /// Number of elements.
    pub fn elements(&self) -> usize {
        self.elements.len()
    }

    /// Every face added by [`Self::add_face`], in that order, with its elements (row-major
    /// over its grid).
    pub fn faces(&self) -> impl Iterator<Item = (FaceId, &[usize])> {
        self.faces.iter().enumerate().map(|(i, (_, ids))| (FaceId(i), ids.as_slice()))
    }

    /// A face added by [`Self::add_face`].
    pub fn face(&self, id: FaceId) -> &Face {
        &self.faces[id.0].0
    }

    /// DOFs before restraints: six per node.
    pub fn dofs(&self) -> usize {
        DOFS_PER_NODE * self.nodes.len()
    }

    fn element_dofs(&self, e: &Element) -> [usize; 24] {
        std::array::from_fn(|k| DOFS_PER_NODE * e.nodes[k / 6] + k % 6)
    }

    /// An element matrix in the global frame: Tᵀ K T, T = diag(Λ) over the eight 3-blocks.
    pub(super) fn global(e: &Element, local: &Mat24) -> Mat24 {
        let mut t = Mat24::zeros();
        for block in 0..8 {
            t.fixed_view_mut::<3, 3>(3 * block, 3 * block).copy_from(&e.axes);
        }
        t.transpose() * local * t
    }

    /// The consistent load of a uniform traction `q` (Pa, a global vector) on every element:
    /// the structure's own weight as a load, or the benchmarks' gravity load.
    pub fn area_load(&self, q: [f64; 3]) -> Vec<f64> {
        let mut f = vec![0.0; self.dofs()];
        for e in &self.elements {
            for (&n, share) in e.nodes.iter().zip(e.shape.nodal_areas()) {
                for (i, qi) in q.iter().enumerate() {
                    // ∫ N_k dA (A/4 for a rectangle).
                    f[DOFS_PER_NODE * n + i] += qi * share;
                }
            }
        }
        f
    }

    /// The consistent load of a unit force spread over `patch` on face `id`, pressing along
    /// -normal (into a closed box whose face normals point outward).
    pub fn patch_load(&self, id: FaceId, patch: &Patch) -> Result<Vec<f64>, FemError> {
        let (face, ids) = &self.faces[id.0];
        let mut f = vec![0.0; self.dofs()];
        for part in patch.parts(&face.mesh)? {
            let e = &self.elements[ids[part.ez * face.mesh.nx() + part.ex]];
            let local: Vec24 = -element::pressure_load(part.size.0, part.size.1, part.local, patch.pressure());
            let dofs = self.element_dofs(e);
            for node in 0..4 {
                let global = e.axes.transpose() * local.fixed_rows::<3>(6 * node);
                for i in 0..3 {
                    f[dofs[6 * node + i]] += global[i];
                }
            }
        }
        Ok(f)
    }

    /// Restrains the structure and factorizes its stiffness.
    pub fn factorize(&self, restraints: &Restraints) -> Result<Factorized<'_>, FemError> {
        let n_dofs = self.dofs();
        let mut free = vec![0usize; n_dofs];
        let mut held = vec![false; n_dofs];
        for &(node, dof) in &restraints.held {
            if node >= self.nodes.len() || dof >= DOFS_PER_NODE {
                return Err(FemError::Support(format!("restraint on node {node}, DOF {dof}: no such DOF")));
            }
            held[DOFS_PER_NODE * node + dof] = true;
        }
        let mut unknowns = 0;
        for (d, slot) in free.iter_mut().enumerate() {
            *slot = if held[d] { usize::MAX } else { unknowns };
            unknowns += usize::from(!held[d]);
        }
        let upper = self.restrained_stiffness(restraints, &free, unknowns)?;
        let symbolic = Symbolic::new(upper.symbolic(), unknowns)?;
        let factor = Cholesky::new(&symbolic, upper.as_ref()).map_err(|_| {
            FemError::Singular("the restraints leave the structure a rigid-body motion (or a mechanism)".into())
        })?;
        Ok(Factorized { structure: self, restraints: restraints.clone(), free, unknowns, factor })
    }

    /// The restrained stiffness's upper triangle on the `unknowns` (`free[d]` each DOF's, or
    /// usize::MAX where held), springs included.
    pub(super) fn restrained_stiffness(
        &self,
        restraints: &Restraints,
        free: &[usize],
        unknowns: usize,
    ) -> Result<SparseColMat<usize, f64>, FemError> {
        let mut triplets = Vec::with_capacity(self.elements.len() * 300);
        for e in &self.elements {
            let k = Self::global(e, &super::warp::on_nodes(e.heights.as_ref(), self.parts[e.parts].total()));
            let dofs = self.element_dofs(e);
            for p in 0..24 {
                for q in 0..24 {
                    let (a, b) = (free[dofs[p]], free[dofs[q]]);
                    if a != usize::MAX && b != usize::MAX && a <= b {
                        triplets.push(Triplet::new(a, b, k[(p, q)]));
                    }
                }
            }
        }
        for s in &restraints.springs {
            s.check(self.nodes.len())?;
            let d = Vector3::from(s.direction).normalize();
            for i in 0..3 {
                for j in 0..3 {
                    let (a, b) = (free[DOFS_PER_NODE * s.node + i], free[DOFS_PER_NODE * s.node + j]);
                    if a != usize::MAX && b != usize::MAX && a <= b {
                        triplets.push(Triplet::new(a, b, s.stiffness * d[i] * d[j]));
                    }
                }
            }
        }
        SparseColMat::try_new_from_triplets(unknowns, unknowns, &triplets)
            .map_err(|e| FemError::sparse("sparsity pattern", unknowns, e))
    }
}

/// A patch's response per unit force, with the energy split.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ShellResponse {
    /// Work-conjugate compliance: the pressure-weighted mean displacement along the load
    /// per unit force (m/N).
    pub compliance: f64,
    /// Membrane strain energy x 2/P² (m/N).
    pub membrane: f64,
    /// Bending strain energy x 2/P² (m/N).
    pub bending: f64,
    /// Transverse shear strain energy x 2/P² (m/N).
    pub shear: f64,
    /// Drilling penalty energy x 2/P² (m/N): a measure of the penalty's intrusion.
    pub drilling: f64,
    /// The springs' energy x 2/P² (m/N).
    pub springs: f64,
}

/// A restrained structure with its factorized stiffness.
pub struct Factorized<'s> {
    pub(super) structure: &'s Structure,
    pub(super) restraints: Restraints,
    /// Each DOF's unknown, usize::MAX where held.
    pub(super) free: Vec<usize>,
    pub(super) unknowns: usize,
    pub(super) factor: Cholesky,
}

impl Factorized<'_> {
    /// Unknowns after the restraints.
    pub fn unknowns(&self) -> usize {
        self.unknowns
    }

    /// The displacements (all DOFs, held ones 0) under the load `f` (all DOFs; loads on held
    /// DOFs go to the supports).
    pub fn solve(&self, f: &[f64]) -> Vec<f64> {
        let mut rhs = Mat::<f64>::zeros(self.unknowns, 1);
        for (d, &slot) in self.free.iter().enumerate() {
            if slot != usize::MAX {
                rhs[(slot, 0)] += f[d];
            }
        }
        self.factor.solve_in_place(rhs.as_mut());
        self.free.iter().map(|&slot| if slot == usize::MAX { 0.0 } else { rhs[(slot, 0)] }).collect()
    }

    /// The fundamental circular frequency ω₁ (rad/s) with the diagonal mass `mass` (all DOFs,
    /// [`Structure::lumped_mass`]), by inverse iteration y = K⁻¹M x from a uniform field,
    /// to a Rayleigh quotient steady to 1e-10 or 500 iterations. Returns ω₁ and the last
    /// relative change of ω₁² (the iteration's own error indicator).
    pub fn fundamental(&self, mass: &[f64]) -> (f64, f64) {
        let mut x: Vec<f64> = (0..mass.len()).map(|d| if d % DOFS_PER_NODE < 3 { 1.0 } else { 0.0 }).collect();
        let (mut lambda, mut change) = (f64::INFINITY, f64::INFINITY);
        for _ in 0..500 {
            let mx: Vec<f64> = x.iter().zip(mass).map(|(a, m)| a * m).collect();
            let y = self.solve(&mx);
            let (ymx, ymy) =
                y.iter().zip(&mx).zip(mass).fold((0.0, 0.0), |(p, q), ((yi, mxi), m)| (p + yi * mxi, q + yi * yi * m));
            // A zero or NaN norm: the field has left every mass (cannot happen for a
            // positive definite K and positive masses).
            if ymy.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                break;
            }
            let next = ymx / ymy;
            change = ((next - lambda) / next).abs();
            lambda = next;
            let norm = ymy.sqrt();
            x = y.into_iter().map(|v| v / norm).collect();
            if change < 1e-10 {
                break;
            }
        }
        (lambda.sqrt(), change)
    }

    /// The response to a unit force spread over `patch` on face `id`.
    pub fn respond(&self, id: FaceId, patch: &Patch) -> Result<ShellResponse, FemError> {
        self.respond_with_field(id, patch).map(|(r, _)| r)
    }

    /// [`Self::respond`] with the displacements (all DOFs) per unit force.
    pub fn respond_with_field(&self, id: FaceId, patch: &Patch) -> Result<(ShellResponse, Vec<f64>), FemError> {
        Ok(self.respond_to(&self.structure.patch_load(id, patch)?))
    }

    /// The response to the load `f` (all DOFs; of unit resultant for the parts to be
    /// compliances), with the displacements.
    pub fn respond_to(&self, f: &[f64]) -> (ShellResponse, Vec<f64>) {
        let u = self.solve(f);
        let compliance = f.iter().zip(&u).map(|(a, b)| a * b).sum();
        let (mut membrane, mut bending, mut shear, mut drilling) = (0.0, 0.0, 0.0, 0.0);
        for e in &self.structure.elements {
            let dofs = self.structure.element_dofs(e);
            // The element's displacements in its own frame, T u: each part's energy is then a
            // quadratic form of the local matrix, without forming Tᵀ K T.
            let ue = super::warp::at_projections(
                e.heights.as_ref(),
                Vec24::from_fn(|k, _| {
                    let (block, row) = (k / 3, k % 3);
                    (0..3).map(|c| e.axes[(row, c)] * u[dofs[3 * block + c]]).sum()
                }),
            );
            let parts = &self.structure.parts[e.parts];
            let energy = |k: &Mat24| ue.dot(&(k * ue));
            membrane += energy(&parts.membrane);
            bending += energy(&parts.bending);
            shear += energy(&parts.shear);
            drilling += energy(&parts.drilling);
        }
        let springs = self
            .restraints
            .springs
            .iter()
            .map(|s| {
                let force = s.force(&u);
                force * force / s.stiffness
            })
            .sum();
        (ShellResponse { compliance, membrane, bending, shear, drilling, springs }, u)
    }
}
