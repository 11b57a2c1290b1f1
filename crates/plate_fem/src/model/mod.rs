//! Assembly, factorization and point probes.
//!
//! The element matrices are the bending and inertia forms of [`crate::assembly`]. The
//! sparsity pattern depends only on the mesh, so a [`Model`] does the symbolic Cholesky
//! analysis once. A support set changes values, not the pattern: a held DOF keeps its row
//! and column in the pattern with zero couplings and its own diagonal, a corner spring adds
//! to the diagonal of its corner's w DOF, and an elastic edge adds its Winkler form to the
//! entries of the elements along it (which couple only DOFs an element already couples).
//! Each support set then costs one
//! numeric factorization ([`Factorization`]), and each impact point one solve: by
//! reciprocity C(p) = N(p)ᵀ K⁻¹ N(p), where N(p) are the shape functions at p. Many points
//! are cheaper from the [`SelectedInverse`]: K⁻¹ on the factor's pattern, which holds every
//! element's 16 x 16 block, for a small multiple of one factorization; C(p) is then a
//! quadratic form on one block.

use crate::assembly;
use crate::element::{self, Mat16, Vec16};
use crate::mesh::Mesh;
use crate::supports::{Edge, Supports};
use crate::FemError;
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};
use serde::Serialize;
use std::collections::HashMap;

pub(crate) mod cholesky;
mod factorization;
mod selected_inverse;

pub use factorization::{
    mass_stiffness_pass, symmetric_upper_apply, symmetric_upper_apply_into, symmetric_upper_quadratic, CornerResponse,
    Factorization, PointResponse,
};
pub use selected_inverse::{SelectedInverse, SELECTED_AGREEMENT};

/// The plate: geometry and an isotropic material (SI units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlateProperties {
    /// Length L along x (m).
    pub length: f64,
    /// Width B along z (m).
    pub width: f64,
    /// Thickness h (m).
    pub thickness: f64,
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio ν, in (-1, 0.5).
    pub poisson_ratio: f64,
    /// Density ρ (kg/m³), for the consistent mass ρh.
    pub density: f64,
}

impl PlateProperties {
    /// Checks that sizes, modulus and density are positive and finite and ν ∈ (-1, 0.5).
    pub fn validate(&self) -> Result<(), FemError> {
        for (name, value) in [
            ("length", self.length),
            ("width", self.width),
            ("thickness", self.thickness),
            ("youngs_modulus", self.youngs_modulus),
            ("density", self.density),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(FemError::Property { name, value, allowed: "(0, inf)" });
            }
        }
        let nu = self.poisson_ratio;
        if !(nu.is_finite() && nu > -1.0 && nu < 0.5) {
            return Err(FemError::Property { name: "poisson_ratio", value: nu, allowed: "(-1, 0.5)" });
        }
        Ok(())
    }
    /// Kirchhoff flexural rigidity D = E h³ / 12(1 - ν²) (N·m).
    pub fn rigidity(&self) -> f64 {
        self.youngs_modulus * self.thickness.powi(3) / (12.0 * (1.0 - self.poisson_ratio * self.poisson_ratio))
    }
}

/// A meshed plate with its assembled (unsupported) stiffness and symbolic factorization.
pub struct Model {
    props: PlateProperties,
    mesh: Mesh,
    /// Upper-triangle entries in assembly order: 136 per element, then one diagonal
    /// "support slot" per DOF (where held DOFs and springs put their values).
    entries: Vec<(usize, usize)>,
    /// Element stiffness values in the order of `entries` (support slots excluded).
    element_values: Vec<f64>,
    /// Consistent element mass values in the same order.
    mass_values: Vec<f64>,
    /// The assembled diagonal, the scale given to a held DOF.
    diagonal: Vec<f64>,
    pattern: SymbolicSparseColMat<usize>,
    argsort: Argsort<usize>,
    symbolic: cholesky::Symbolic,
}

fn size_key(a: f64, b: f64) -> (u64, u64) {
    (a.to_bits(), b.to_bits())
}

/// Entries one element puts in the upper triangle: 16 · 17 / 2.
const SLOTS: usize = 136;

/// The element's upper-triangle entries in assembly order: local (p, q), p major, with
/// global dofs[p] ≤ dofs[q] (an element's DOFs are distinct, so equality is the diagonal).
fn upper_slots(dofs: &[usize; 16]) -> impl Iterator<Item = (usize, usize)> + '_ {
    (0..16).flat_map(move |p| (0..16).filter(move |&q| dofs[p] <= dofs[q]).map(move |q| (p, q)))
}

/// The elements with a side on `edge`, (ex, ez).
fn edge_elements(mesh: &Mesh, edge: Edge) -> Vec<(usize, usize)> {
    let (nx, nz) = (mesh.nx(), mesh.nz());
    match edge {
        Edge::Left => (0..nz).map(|ez| (0, ez)).collect(),
        Edge::Right => (0..nz).map(|ez| (nx - 1, ez)).collect(),
        Edge::Near => (0..nx).map(|ex| (ex, 0)).collect(),
        Edge::Far => (0..nx).map(|ex| (ex, nz - 1)).collect(),
    }
}

impl Model {
    /// Assembles the plate on `mesh` and analyses the sparsity pattern.
    pub fn new(props: PlateProperties, mesh: Mesh) -> Result<Self, FemError> {
        props.validate()?;
        mesh.check_spans(props.length, props.width)?;
        let n = mesh.dofs();
        let bending = assembly::bending(props.rigidity(), props.poisson_ratio);
        let inertia = assembly::inertia(props.density * props.thickness);
        // Graded meshes repeat a few element sizes: each is integrated once.
        let mut cache: HashMap<(u64, u64), (Mat16, Mat16)> = HashMap::new();
        let mut entries = Vec::with_capacity(mesh.elements() * SLOTS + n);
        let mut element_values = Vec::with_capacity(mesh.elements() * SLOTS);
        let mut mass_values = Vec::with_capacity(mesh.elements() * SLOTS);
        let mut diagonal = vec![0.0; n];
        for ez in 0..mesh.nz() {
            for ex in 0..mesh.nx() {
                let (a, b) = mesh.element_size(ex, ez);
                let (ke, me) =
                    cache.entry(size_key(a, b)).or_insert_with(|| (bending.element(a, b), inertia.element(a, b)));
                let dofs = mesh.element_dofs(ex, ez);
                for p in 0..16 {
                    diagonal[dofs[p]] += ke[(p, p)];
                }
                for (p, q) in upper_slots(&dofs) {
                    entries.push((dofs[p], dofs[q]));
                    element_values.push(ke[(p, q)]);
                    mass_values.push(me[(p, q)]);
                }
            }
        }
        entries.extend((0..n).map(|i| (i, i)));
        let pairs: Vec<Pair<usize, usize>> = entries.iter().map(|&(r, c)| Pair::new(r, c)).collect();
        let (pattern, argsort) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|e| FemError::sparse("sparsity pattern", n, e))?;
        let symbolic = cholesky::Symbolic::new(pattern.as_ref(), n)?;
        Ok(Self { props, mesh, entries, element_values, mass_values, diagonal, pattern, argsort, symbolic })
    }

    /// The plate.
    pub fn props(&self) -> &PlateProperties {
        &self.props
    }
    /// The mesh.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }
    /// Number of degrees of freedom, four per node.
    pub fn dofs(&self) -> usize {
        self.mesh.dofs()
    }
    /// Stored entries of the upper triangle of K.
    pub fn nonzeros(&self) -> usize {
        self.pattern.compute_nnz()
    }

    /// The stiffness with `supports` applied, upper triangle, in the model's pattern.
    pub fn supported_stiffness(&self, supports: &Supports) -> Result<SparseColMat<usize, f64>, FemError> {
        self.supported_matrix(supports, 1.0, 0.0, true)
    }

    /// The consistent mass with the held DOFs of `supports` removed (their rows and columns
    /// zero, unit diagonal kept out: a held DOF has no inertia).
    pub fn supported_mass(&self, supports: &Supports) -> Result<SparseColMat<usize, f64>, FemError> {
        self.supported_matrix(supports, 0.0, 1.0, false)
    }

    /// α K + β M with `supports` applied (corner and edge springs scaled by α), upper
    /// triangle. A held DOF keeps a positive diagonal when `hold_diagonal`, so the matrix
    /// stays factorizable.
    pub fn supported_matrix(
        &self,
        supports: &Supports,
        alpha: f64,
        beta: f64,
        hold_diagonal: bool,
    ) -> Result<SparseColMat<usize, f64>, FemError> {
        supports.validate(self.props.length, self.props.width)?;
        let n = self.dofs();
        let mut held = vec![false; n];
        for d in supports.constrained_dofs(&self.mesh) {
            held[d] = true;
        }
        let m = self.element_values.len();
        let mut values = Vec::with_capacity(self.entries.len());
        for (k, &(r, c)) in self.entries[..m].iter().enumerate() {
            values.push(if held[r] || held[c] {
                0.0
            } else {
                alpha * self.element_values[k] + beta * self.mass_values[k]
            });
        }
        for (ex, ez, spring) in self.edge_spring_matrices(supports) {
            let dofs = self.mesh.element_dofs(ex, ez);
            let start = (ez * self.mesh.nx() + ex) * SLOTS;
            for (slot, (p, q)) in upper_slots(&dofs).enumerate() {
                if !(held[dofs[p]] || held[dofs[q]]) {
                    values[start + slot] += alpha * spring[(p, q)];
                }
            }
        }
        let mut slots: Vec<f64> = (0..n)
            .map(|i| if held[i] && hold_diagonal { self.diagonal[i].max(f64::MIN_POSITIVE) } else { 0.0 })
            .collect();
        for (dof, k) in supports.springs(&self.mesh) {
            slots[dof] += alpha * k;
        }
        values.extend(slots);
        SparseColMat::new_from_argsort(self.pattern.clone(), &self.argsort, &values)
            .map_err(|e| FemError::sparse("filling the matrix values", n, e))
    }

    /// One numeric Cholesky factorization for `supports` (checked for rigid-body motion
    /// first).
    pub fn factorize(&self, supports: &Supports) -> Result<Factorization<'_>, FemError> {
        self.factorize_matrix(supports, self.supported_stiffness(supports)?)
    }

    /// Factorizes K + `shift`·M for `supports` (the effective matrix of implicit time
    /// stepping); same symbolic analysis.
    pub fn factorize_shifted(&self, supports: &Supports, shift: f64) -> Result<Factorization<'_>, FemError> {
        self.factorize_matrix(supports, self.supported_matrix(supports, 1.0, shift, true)?)
    }

    fn factorize_matrix(
        &self,
        supports: &Supports,
        k: SparseColMat<usize, f64>,
    ) -> Result<Factorization<'_>, FemError> {
        let llt = cholesky::Cholesky::new(&self.symbolic, k.as_ref())?;
        let held = supports.constrained_dofs(&self.mesh);
        Ok(Factorization::new(self, *supports, llt, held, k))
    }

    /// Shape functions at (x, z): the element's 16 DOFs and their values.
    pub fn load(&self, x: f64, z: f64) -> Result<([usize; 16], Vec16), FemError> {
        let loc = self.mesh.locate(x, z)?;
        let (a, b) = self.mesh.element_size(loc.ex, loc.ez);
        Ok((self.mesh.element_dofs(loc.ex, loc.ez), element::shape(a, b, loc.xi, loc.eta)))
    }

    /// The consistent load of a unit force spread uniformly over `patch`: ∫ p N dA over each
    /// part of an element it covers, exact by 4 x 4 Gauss points (N is bicubic).
    pub fn patch_load(&self, patch: &crate::Patch) -> Result<Vec<f64>, FemError> {
        let mut f = vec![0.0; self.dofs()];
        let p = patch.pressure();
        for part in patch.parts(&self.mesh)? {
            let ((a, b), [x0, x1, z0, z1]) = (part.size, part.local);
            let dofs = self.mesh.element_dofs(part.ex, part.ez);
            for &(s, ws) in &assembly::GAUSS {
                for &(t, wt) in &assembly::GAUSS {
                    let (x, z) = (x0 + s * (x1 - x0), z0 + t * (z1 - z0));
                    let n = element::shape(a, b, x / a, z / b);
                    let weight = p * ws * wt * (x1 - x0) * (z1 - z0);
                    for (d, v) in dofs.iter().zip(n.iter()) {
                        f[*d] += v * weight;
                    }
                }
            }
        }
        Ok(f)
    }

    /// The bending strain along x at (x, z) on the face away from the load, as a functional
    /// of the element's DOFs: ε_x = -(h/2) ∂²w/∂x² (Kirchhoff: the strain varies linearly
    /// through the thickness and vanishes on the mid-plane; w positive along the load, so the
    /// far face stretches where the plate sags). What a strain gauge bonded along x on the
    /// unstruck face reads. On an element edge x = const, w_xx of the element located
    /// ([`crate::mesh::Mesh::locate`]) is taken: the C¹ element's curvature may jump there.
    pub fn bending_strain(&self, x: f64, z: f64) -> Result<([usize; 16], Vec16), FemError> {
        let loc = self.mesh.locate(x, z)?;
        let (a, b) = self.mesh.element_size(loc.ex, loc.ez);
        let w_xx = element::curvature(a, b, loc.xi, loc.eta).row(0).transpose();
        Ok((self.mesh.element_dofs(loc.ex, loc.ez), w_xx * (-0.5 * self.props.thickness)))
    }

    /// Deflection of a field `w` at (x, z).
    ///
    /// # Panics
    ///
    /// If `w` has fewer than [`dofs`](Self::dofs) entries.
    pub fn evaluate(&self, w: &[f64], x: f64, z: f64) -> Result<f64, FemError> {
        let (dofs, n) = self.load(x, z)?;
        Ok(dofs.iter().zip(n.iter()).map(|(&d, &v)| w[d] * v).sum())
    }

    /// Bending moments (M_x, M_z, M_xz) = -D κ per unit width at every element centre, for
    /// the field `w`; elements in row order (ex fastest).
    ///
    /// # Panics
    ///
    /// If `w` has fewer than [`dofs`](Self::dofs) entries.
    pub fn centre_moments(&self, w: &[f64]) -> Vec<[f64; 3]> {
        let dm = element::bending_matrix(self.props.rigidity(), self.props.poisson_ratio);
        let mut out = Vec::with_capacity(self.mesh.elements());
        for ez in 0..self.mesh.nz() {
            for ex in 0..self.mesh.nx() {
                let (a, b) = self.mesh.element_size(ex, ez);
                let dofs = self.mesh.element_dofs(ex, ez);
                let we = Vec16::from_fn(|k, _| w[dofs[k]]);
                // With κ = (w_xx, w_zz, 2w_xz), the third row of D κ is D(1-ν) w_xz, so
                // -Dκ is (M_x, M_z, M_xz) in Timoshenko's convention.
                let m = -(dm * (element::curvature(a, b, 0.5, 0.5) * we));
                out.push([m[0], m[1], m[2]]);
            }
        }
        out
    }

    /// The Winkler form of every elastic edge of `supports` on the element sides along it,
    /// (ex, ez, matrix), edges in [`Edge::ALL`] order.
    fn edge_spring_matrices(&self, supports: &Supports) -> Vec<(usize, usize, Mat16)> {
        let mut out = Vec::new();
        for (edge, k) in supports.elastic_edges() {
            let form = assembly::winkler(k);
            for (ex, ez) in edge_elements(&self.mesh, edge) {
                let (a, b) = self.mesh.element_size(ex, ez);
                out.push((ex, ez, form.side(a, b, edge)));
            }
        }
        out
    }

    /// wᵀ S w for the field `w`, S the elastic edges' Winkler form: twice the energy the edge
    /// springs of `supports` hold (0 without elastic edges).
    ///
    /// # Panics
    ///
    /// If `w` has fewer than [`dofs`](Self::dofs) entries.
    pub fn edge_spring_store(&self, supports: &Supports, w: &[f64]) -> f64 {
        self.edge_spring_matrices(supports)
            .iter()
            .map(|(ex, ez, spring)| {
                let dofs = self.mesh.element_dofs(*ex, *ez);
                let we = Vec16::from_fn(|k, _| w[dofs[k]]);
                we.dot(&(spring * we))
            })
            .sum()
    }

    /// The stiffness of element (ex, ez) with the Winkler forms of the elastic edges of
    /// `supports` on its sides: its part of the supported K before any DOF is held (what a
    /// held DOF's reaction is computed from). Without elastic edges, the bending form alone.
    pub fn element_stiffness(&self, ex: usize, ez: usize, supports: &Supports) -> Mat16 {
        let (a, b) = self.mesh.element_size(ex, ez);
        let mut k = element::stiffness(a, b, self.props.rigidity(), self.props.poisson_ratio);
        let (nx, nz) = (self.mesh.nx(), self.mesh.nz());
        for (edge, spring) in supports.elastic_edges() {
            let on = match edge {
                Edge::Left => ex == 0,
                Edge::Right => ex + 1 == nx,
                Edge::Near => ez == 0,
                Edge::Far => ez + 1 == nz,
            };
            if on {
                k += assembly::winkler(spring).side(a, b, edge);
            }
        }
        k
    }
}
