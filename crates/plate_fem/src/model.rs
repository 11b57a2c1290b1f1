//! Assembly, factorization and point probes.
//!
//! The sparsity pattern depends only on the mesh, so a [`Model`] does the symbolic
//! Cholesky analysis once. A support set changes values, not the pattern: a held DOF keeps
//! its row and column in the pattern with zero couplings and its own diagonal, and a
//! spring adds to the diagonal of its corner's w DOF. Each support set then costs one
//! numeric factorization ([`Factorization`]), and each impact point one solve: by
//! reciprocity C(p) = N(p)ᵀ K⁻¹ N(p), where N(p) are the shape functions at p.

use crate::element::{self, Mat16, Vec16};
use crate::mesh::Mesh;
use crate::supports::{Corner, CornerSupport, Supports};
use crate::FemError;
use faer::linalg::solvers::SolveCore;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};
use faer::{Conj, Mat, Side};
use serde::Serialize;
use std::collections::HashMap;

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
    symbolic: SymbolicLlt<usize>,
}

fn size_key(a: f64, b: f64) -> (u64, u64) {
    (a.to_bits(), b.to_bits())
}

impl Model {
    /// Assembles the plate on `mesh` and analyses the sparsity pattern.
    pub fn new(props: PlateProperties, mesh: Mesh) -> Result<Self, FemError> {
        props.validate()?;
        let tol = 1e-9 * props.length.max(props.width);
        if (mesh.length() - props.length).abs() > tol || (mesh.width() - props.width).abs() > tol {
            return Err(FemError::Mesh(format!(
                "mesh spans {} x {} m but the plate is {} x {} m",
                mesh.length(),
                mesh.width(),
                props.length,
                props.width
            )));
        }
        let n = mesh.dofs();
        let d = props.rigidity();
        let mut cache: HashMap<(u64, u64), Mat16> = HashMap::new();
        let mut mass_cache: HashMap<(u64, u64), Mat16> = HashMap::new();
        let rho_h = props.density * props.thickness;
        let per = 136;
        let mut entries = Vec::with_capacity(mesh.elements() * per + n);
        let mut element_values = Vec::with_capacity(mesh.elements() * per);
        let mut mass_values = Vec::with_capacity(mesh.elements() * per);
        let mut diagonal = vec![0.0; n];
        for ez in 0..mesh.nz() {
            for ex in 0..mesh.nx() {
                let (a, b) = mesh.element_size(ex, ez);
                let ke =
                    cache.entry(size_key(a, b)).or_insert_with(|| element::stiffness(a, b, d, props.poisson_ratio));
                let me = mass_cache.entry(size_key(a, b)).or_insert_with(|| element::mass(a, b, rho_h));
                let dofs = mesh.element_dofs(ex, ez);
                for p in 0..16 {
                    diagonal[dofs[p]] += ke[(p, p)];
                    for q in 0..16 {
                        let (r, c) = (dofs[p], dofs[q]);
                        if r <= c && (r < c || p == q) {
                            entries.push((r, c));
                            element_values.push(ke[(p, q)]);
                            mass_values.push(me[(p, q)]);
                        }
                    }
                }
            }
        }
        entries.extend((0..n).map(|i| (i, i)));
        let pairs: Vec<Pair<usize, usize>> = entries.iter().map(|&(r, c)| Pair::new(r, c)).collect();
        let (pattern, argsort) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|e| FemError::sparse("sparsity pattern", n, e))?;
        let symbolic = SymbolicLlt::try_new(pattern.as_ref(), Side::Upper)
            .map_err(|e| FemError::sparse("symbolic Cholesky analysis", n, e))?;
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

    /// α K + β M with `supports` applied (springs scaled by α), upper triangle. A held DOF
    /// keeps a positive diagonal when `hold_diagonal`, so the matrix stays factorizable.
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
        let llt = Llt::try_new_with_symbolic(self.symbolic.clone(), k.as_ref(), Side::Upper)
            .map_err(|e| FemError::sparse("numeric Cholesky factorization", self.dofs(), e))?;
        let held = supports.constrained_dofs(&self.mesh);
        Ok(Factorization { model: self, supports: *supports, llt, held, stiffness: k, refinement: 1 })
    }

    /// Shape functions at (x, z): the element's 16 DOFs and their values.
    pub fn load(&self, x: f64, z: f64) -> Result<([usize; 16], Vec16), FemError> {
        let loc = self.mesh.locate(x, z)?;
        let (a, b) = self.mesh.element_size(loc.ex, loc.ez);
        Ok((self.mesh.element_dofs(loc.ex, loc.ez), element::shape(a, b, loc.xi, loc.eta)))
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

    /// The element stiffness of element (ex, ez).
    fn element_stiffness(&self, ex: usize, ez: usize) -> Mat16 {
        let (a, b) = self.mesh.element_size(ex, ez);
        element::stiffness(a, b, self.props.rigidity(), self.props.poisson_ratio)
    }
}

/// y = A x for a symmetric matrix stored as its upper triangle.
///
/// # Panics
///
/// If `x` is shorter than the matrix has columns.
pub fn symmetric_upper_apply(a: &SparseColMat<usize, f64>, x: &[f64]) -> Vec<f64> {
    let a = a.as_ref();
    let (cp, ri, v) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
    let mut y = vec![0.0; x.len()];
    for j in 0..a.ncols() {
        let xj = x[j];
        let mut acc = 0.0;
        for p in cp[j]..cp[j + 1] {
            let i = ri[p];
            acc += v[p] * x[i];
            if i != j {
                y[i] += v[p] * xj;
            }
        }
        y[j] += acc;
    }
    y
}

/// What one corner does under a unit load at the impact point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CornerResponse {
    /// Force the support exerts against the load, per unit load (N/N).
    pub reaction: f64,
    /// The corner spring's energy store: it holds ½ `spring_compliance` P² (m/N); 0 for a
    /// fixed or free corner.
    pub spring_compliance: f64,
}

/// The compliance at one impact point and where its energy goes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PointResponse {
    /// Impact point x (m).
    pub x: f64,
    /// Impact point z (m).
    pub z: f64,
    /// C = N ᵀ K⁻¹ N (m/N): deflection of the impact point per unit load, springs included.
    pub compliance: f64,
    /// The plate's strain-energy store (m/N): C minus the spring stores.
    pub plate_compliance: f64,
    /// Corners in the order of [`Corner::ALL`].
    pub corners: [CornerResponse; 4],
    /// Relative residual ‖Kw - N‖/‖N‖ of the solve behind this response.
    pub residual: f64,
}

impl PointResponse {
    /// Σ reactions: 1 when only corners carry the load.
    pub fn total_reaction(&self) -> f64 {
        self.corners.iter().map(|c| c.reaction).sum()
    }
}

/// A numeric factorization for one support set.
pub struct Factorization<'m> {
    model: &'m Model,
    supports: Supports,
    llt: Llt<usize, f64>,
    held: Vec<usize>,
    /// The supported stiffness (upper triangle), for residuals and refinement.
    stiffness: SparseColMat<usize, f64>,
    /// Steps of iterative refinement after each solve.
    refinement: usize,
}

impl<'m> Factorization<'m> {
    /// The model it factorizes.
    pub fn model(&self) -> &'m Model {
        self.model
    }
    /// The support set it was factorized for.
    pub fn supports(&self) -> &Supports {
        &self.supports
    }

    /// The DOFs the supports hold at zero, sorted.
    pub fn held(&self) -> &[usize] {
        &self.held
    }

    /// Solves K W = F in place without refinement or residuals (held DOFs zeroed first):
    /// for inner loops whose results are checked by their own residuals.
    ///
    /// # Panics
    ///
    /// If `rhs` does not have [`Model::dofs`] rows.
    pub fn solve_unchecked(&self, rhs: &mut Mat<f64>) {
        for &d in &self.held {
            for j in 0..rhs.ncols() {
                rhs[(d, j)] = 0.0;
            }
        }
        self.llt.solve_in_place_with_conj(Conj::No, rhs.as_mut());
    }

    /// Sets the number of iterative-refinement steps after each solve (default 1).
    ///
    /// The condition number of K grows like (L/h)⁴ and, with very soft springs, like the
    /// ratio of plate to spring stiffness; one step of refinement in working precision
    /// brings the residual back to rounding level in the cases of the extreme-case study.
    pub fn with_refinement(mut self, steps: usize) -> Self {
        self.refinement = steps;
        self
    }

    /// y = K x with the supported stiffness, column by column.
    ///
    /// # Panics
    ///
    /// If `x` does not have [`Model::dofs`] rows.
    pub fn apply(&self, x: faer::MatRef<'_, f64>) -> Mat<f64> {
        let mut y = Mat::<f64>::zeros(x.nrows(), x.ncols());
        for c in 0..x.ncols() {
            let xc: Vec<f64> = x.col(c).iter().copied().collect();
            for (i, v) in symmetric_upper_apply(&self.stiffness, &xc).into_iter().enumerate() {
                y[(i, c)] = v;
            }
        }
        y
    }

    /// Solves K W = F in place for the columns of `rhs` (held DOFs are zeroed first), with
    /// the configured refinement; returns the relative residual ‖KW - F‖/‖F‖ of each column.
    ///
    /// # Panics
    ///
    /// If `rhs` does not have [`Model::dofs`] rows.
    pub fn solve_in_place(&self, rhs: &mut Mat<f64>) -> Vec<f64> {
        for &d in &self.held {
            for j in 0..rhs.ncols() {
                rhs[(d, j)] = 0.0;
            }
        }
        let f = rhs.clone();
        self.llt.solve_in_place_with_conj(Conj::No, rhs.as_mut());
        let residual = |w: &Mat<f64>| {
            let mut r = self.apply(w.as_ref());
            for j in 0..r.ncols() {
                for i in 0..r.nrows() {
                    r[(i, j)] = f[(i, j)] - r[(i, j)];
                }
            }
            r
        };
        let mut r = residual(rhs);
        for _ in 0..self.refinement {
            let mut dw = r.clone();
            self.llt.solve_in_place_with_conj(Conj::No, dw.as_mut());
            *rhs += &dw;
            r = residual(rhs);
        }
        (0..f.ncols())
            .map(|j| {
                let n = |m: &Mat<f64>| (0..m.nrows()).map(|i| m[(i, j)] * m[(i, j)]).sum::<f64>().sqrt();
                n(&r) / n(&f).max(f64::MIN_POSITIVE)
            })
            .collect()
    }

    /// The load vector of a unit point load at (x, z).
    pub fn load_vector(&self, x: f64, z: f64) -> Result<Vec<f64>, FemError> {
        let (dofs, n) = self.model.load(x, z)?;
        let mut f = vec![0.0; self.model.dofs()];
        for (d, v) in dofs.iter().zip(n.iter()) {
            f[*d] += v;
        }
        for &d in &self.held {
            f[d] = 0.0;
        }
        Ok(f)
    }

    /// The deflection field under a unit load at (x, z).
    pub fn deflection_field(&self, x: f64, z: f64) -> Result<Vec<f64>, FemError> {
        let f = self.load_vector(x, z)?;
        let mut m = Mat::from_fn(f.len(), 1, |i, _| f[i]);
        self.solve_in_place(&mut m);
        Ok((0..f.len()).map(|i| m[(i, 0)]).collect())
    }

    /// Responses at many points, solved in blocks of columns.
    pub fn respond_many(&self, points: &[(f64, f64)]) -> Result<Vec<PointResponse>, FemError> {
        const BLOCK: usize = 64;
        let n = self.model.dofs();
        let mut out = Vec::with_capacity(points.len());
        for chunk in points.chunks(BLOCK) {
            let _ = n;
            let mut rhs = Mat::<f64>::zeros(n, chunk.len());
            let mut loads = Vec::with_capacity(chunk.len());
            for (j, &(x, z)) in chunk.iter().enumerate() {
                let (dofs, nv) = self.model.load(x, z)?;
                for (d, v) in dofs.iter().zip(nv.iter()) {
                    rhs[(*d, j)] += v;
                }
                loads.push((dofs, nv));
            }
            let residuals = self.solve_in_place(&mut rhs);
            for (j, &(x, z)) in chunk.iter().enumerate() {
                let w: Vec<f64> = rhs.col(j).iter().copied().collect();
                let mut r = self.response_from_field(x, z, &loads[j], &w);
                r.residual = residuals[j];
                out.push(r);
            }
        }
        Ok(out)
    }

    /// Response at one point.
    pub fn respond(&self, x: f64, z: f64) -> Result<PointResponse, FemError> {
        Ok(self.respond_many(&[(x, z)])?.remove(0))
    }

    fn response_from_field(&self, x: f64, z: f64, load: &([usize; 16], Vec16), w: &[f64]) -> PointResponse {
        let held: std::collections::HashSet<usize> = self.held.iter().copied().collect();
        let compliance: f64 =
            load.0.iter().zip(load.1.iter()).filter(|(d, _)| !held.contains(d)).map(|(&d, &v)| w[d] * v).sum();
        let mesh = self.model.mesh();
        let mut corners = [CornerResponse { reaction: 0.0, spring_compliance: 0.0 }; 4];
        for c in Corner::ALL {
            let dof = mesh.corner_w_dof(c.index());
            corners[c.index()] = match self.supports.corners[c.index()] {
                CornerSupport::Free => CornerResponse { reaction: 0.0, spring_compliance: 0.0 },
                CornerSupport::Spring(k) => {
                    CornerResponse { reaction: k * w[dof], spring_compliance: k * w[dof] * w[dof] }
                }
                CornerSupport::Fixed => {
                    // The corner node belongs to one element: R = N_c - (K_e w_e)_c.
                    let (ex, ez, local) = match c {
                        Corner::LeftNear => (0, 0, 0),
                        Corner::RightNear => (mesh.nx() - 1, 0, 4),
                        Corner::LeftFar => (0, mesh.nz() - 1, 8),
                        Corner::RightFar => (mesh.nx() - 1, mesh.nz() - 1, 12),
                    };
                    let dofs = mesh.element_dofs(ex, ez);
                    let ke = self.model.element_stiffness(ex, ez);
                    let kw: f64 = (0..16).map(|q| ke[(local, q)] * w[dofs[q]]).sum();
                    let applied: f64 =
                        load.0.iter().zip(load.1.iter()).filter(|(d, _)| **d == dof).map(|(_, v)| v).sum();
                    CornerResponse { reaction: applied - kw, spring_compliance: 0.0 }
                }
            };
        }
        let springs: f64 = corners.iter().map(|c| c.spring_compliance).sum();
        PointResponse { x, z, compliance, plate_compliance: compliance - springs, corners, residual: 0.0 }
    }
}
