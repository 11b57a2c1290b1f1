//! The numeric factorization of one support set: solves with iterative refinement, and
//! point probes by reciprocity, C(p) = N(p)ᵀ K⁻¹ N(p), with the energy each support stores.

use super::cholesky::Cholesky;
use super::Model;
use super::{SelectedInverse, SELECTED_AGREEMENT};
use crate::element::Vec16;
use crate::supports::{Corner, CornerSupport, EdgeSupport, Supports};
use crate::FemError;
use faer::sparse::SparseColMat;
use faer::Mat;
use serde::Serialize;

/// y = A x for a symmetric matrix stored as its upper triangle.
///
/// # Panics
///
/// If `x` is shorter than the matrix has columns.
pub fn symmetric_upper_apply(a: &SparseColMat<usize, f64>, x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; x.len()];
    symmetric_upper_apply_into(a, x, &mut y);
    y
}

/// y = A x into `y` (overwritten) for a symmetric matrix stored as its upper triangle: the
/// product of [`symmetric_upper_apply`] without allocating, for time-stepping loops.
///
/// # Panics
///
/// If `x` or `y` is shorter than the matrix has columns.
pub fn symmetric_upper_apply_into(a: &SparseColMat<usize, f64>, x: &[f64], y: &mut [f64]) {
    let a = a.as_ref();
    let (cp, ri, v) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
    y.iter_mut().for_each(|yi| *yi = 0.0);
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
}

/// The quadratic form xᵀA x of a symmetric matrix stored as its upper triangle, in one pass
/// and without forming A x: Σⱼ xⱼ (Aⱼⱼ xⱼ + 2 Σ_{i<j} Aᵢⱼ xᵢ). An energy ½xᵀAx costs a
/// third of [`symmetric_upper_apply`] followed by a dot product, which scatters into y.
///
/// # Panics
///
/// If `x` is shorter than the matrix has columns.
pub fn symmetric_upper_quadratic(a: &SparseColMat<usize, f64>, x: &[f64]) -> f64 {
    let a = a.as_ref();
    let (cp, ri, v) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
    let mut total = 0.0;
    for (j, &xj) in x.iter().enumerate().take(a.ncols()) {
        let (mut off, mut diag) = (0.0, 0.0);
        for p in cp[j]..cp[j + 1] {
            let i = ri[p];
            if i == j {
                diag += v[p] * xj;
            } else {
                off += v[p] * x[i];
            }
        }
        total += xj * (diag + 2.0 * off);
    }
    total
}

/// One pass over the common pattern of two symmetric matrices M and K stored as their upper
/// triangles: `my` = M y (overwritten, with the operations of [`symmetric_upper_apply_into`]
/// in its order, so bit for bit its result) and the quadratic forms vᵀMv and wᵀKw. A
/// Newmark step needs exactly these three (the next right-hand side and the two energies),
/// and reading the pattern once instead of three times is most of their cost.
///
/// # Panics
///
/// If a vector is shorter than the matrices have columns. The patterns must be equal
/// (checked in debug builds; [`crate::dynamics::Newmark`] checks once and falls back).
pub fn mass_stiffness_pass(
    (mass, stiffness): (&SparseColMat<usize, f64>, &SparseColMat<usize, f64>),
    (y, v, w): (&[f64], &[f64], &[f64]),
    my: &mut [f64],
) -> (f64, f64) {
    let (m, k) = (mass.as_ref(), stiffness.as_ref());
    let (cp, ri) = (m.symbolic().col_ptr(), m.symbolic().row_idx());
    debug_assert!(cp == k.symbolic().col_ptr() && ri == k.symbolic().row_idx(), "M and K must share their pattern");
    let (mv, kv) = (m.val(), &k.val()[..m.val().len()]);
    my.iter_mut().for_each(|x| *x = 0.0);
    let (mut kinetic, mut strain) = (0.0, 0.0);
    for j in 0..m.ncols() {
        let (yj, vj, wj) = (y[j], v[j], w[j]);
        // Row indices ascend within a column, so an upper triangle's diagonal entry, where
        // there is one, is its column's last: the off-diagonal loop needs no test.
        let (start, end) = (cp[j], cp[j + 1]);
        let diagonal = end > start && ri[end - 1] == j;
        let off_end = if diagonal { end - 1 } else { end };
        let (mut acc, mut v_off, mut w_off) = (0.0, 0.0, 0.0);
        for p in start..off_end {
            let i = ri[p];
            acc += mv[p] * y[i];
            my[i] += mv[p] * yj;
            v_off += mv[p] * v[i];
            w_off += kv[p] * w[i];
        }
        let (mut v_diag, mut w_diag) = (0.0, 0.0);
        if diagonal {
            acc += mv[off_end] * yj;
            v_diag = mv[off_end] * vj;
            w_diag = kv[off_end] * wj;
        }
        my[j] += acc;
        kinetic += vj * (v_diag + 2.0 * v_off);
        strain += wj * (w_diag + 2.0 * w_off);
    }
    (kinetic, strain)
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
    /// The plate's strain-energy store (m/N): C minus the corner and edge spring stores.
    pub plate_compliance: f64,
    /// Corners in the order of [`Corner::ALL`].
    pub corners: [CornerResponse; 4],
    /// The elastic edges' energy store (m/N): they hold ½ `edge_spring_compliance` P²;
    /// 0 without elastic edges.
    pub edge_spring_compliance: f64,
    /// Relative residual ‖Kw - N‖/‖N‖ of the solve behind this response.
    pub residual: f64,
}

impl PointResponse {
    /// Σ corner reactions: 1 when only corners carry the load.
    pub fn total_reaction(&self) -> f64 {
        self.corners.iter().map(|c| c.reaction).sum()
    }
}

/// A numeric factorization for one support set.
pub struct Factorization<'m> {
    model: &'m Model,
    supports: Supports,
    llt: Cholesky,
    held: Vec<usize>,
    /// The supported stiffness (upper triangle), for residuals and refinement.
    stiffness: SparseColMat<usize, f64>,
    /// Steps of iterative refinement after each solve.
    refinement: usize,
}

impl<'m> Factorization<'m> {
    /// The factorization `llt` of the supported stiffness `stiffness` of `model` on
    /// `supports`, holding `held`; one step of refinement per solve.
    pub(super) fn new(
        model: &'m Model,
        supports: Supports,
        llt: Cholesky,
        held: Vec<usize>,
        stiffness: SparseColMat<usize, f64>,
    ) -> Self {
        Self { model, supports, llt, held, stiffness, refinement: 1 }
    }

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
        self.llt.solve_in_place(rhs.as_mut());
    }

    /// Every entry of K⁻¹ on the factor's pattern (each element's 16 x 16 block among them),
    /// by Takahashi's equations on the factor: for a small multiple of one factorization,
    /// where the blocks by solves cost two triangular solves per DOF.
    pub fn selected_inverse(&self) -> Result<SelectedInverse, FemError> {
        SelectedInverse::new(&self.llt, &self.held)
    }

    /// The selected inverse's compliance at (x, z) against this factorization's solve there,
    /// to [`SELECTED_AGREEMENT`] of `scale` or of the solved compliance, whichever is larger
    /// (a point on a held edge has none); the solve's response.
    pub fn check_selected_inverse(
        &self,
        inverse: &SelectedInverse,
        (x, z): (f64, f64),
        scale: f64,
    ) -> Result<PointResponse, FemError> {
        let (dofs, n) = self.model.load(x, z)?;
        let selected = inverse.quadratic(&dofs, &n).ok_or_else(|| {
            FemError::Modes(
                "selected inversion: an element's DOF pair is outside the factor's pattern; this is a defect of this crate"
                    .into(),
            )
        })?;
        let solved = self.respond(x, z)?;
        let scale = scale.max(solved.compliance.abs());
        let gap = (selected - solved.compliance).abs() / if scale > 0.0 { scale } else { 1.0 };
        if gap.is_nan() || gap > SELECTED_AGREEMENT {
            return Err(FemError::Modes(format!(
                "selected inversion: the compliance at ({x}, {z}) m differs from a solve's by {gap:e} of the largest, above {SELECTED_AGREEMENT:e}; the support set is conditioned too badly for it"
            )));
        }
        Ok(solved)
    }

    /// Whether the compliances of `points` points cost less from the selected inverse than
    /// from one solve each (the flop counts of both on this factor's supernodes).
    pub fn selected_inverse_pays(&self, points: usize) -> bool {
        super::selected_inverse::flops(&self.llt).is_some_and(|(sweep, solve)| points as f64 * solve > sweep)
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
        self.llt.solve_in_place(rhs.as_mut());
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
            self.llt.solve_in_place(dw.as_mut());
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
        Ok(self.functional_vector(&dofs, &n))
    }

    /// The vector of the point functional `n` on the element `dofs` (a load vector, a
    /// strain gauge's [`Model::bending_strain`]), zero at the held DOFs.
    pub fn functional_vector(&self, dofs: &[usize; 16], n: &Vec16) -> Vec<f64> {
        let mut f = vec![0.0; self.model.dofs()];
        for (d, v) in dofs.iter().zip(n.iter()) {
            f[*d] += v;
        }
        for &d in &self.held {
            f[d] = 0.0;
        }
        f
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

    /// The response at (x, z) and the deflection field w = K⁻¹N behind it (4 values per
    /// node), from one solve: the field is that of [`Factorization::deflection_field`] and the
    /// response that of [`Factorization::respond`], residual included.
    pub fn respond_with_field(&self, x: f64, z: f64) -> Result<(PointResponse, Vec<f64>), FemError> {
        let load = self.model.load(x, z)?;
        let mut rhs = Mat::<f64>::zeros(self.model.dofs(), 1);
        for (d, v) in load.0.iter().zip(load.1.iter()) {
            rhs[(*d, 0)] += v;
        }
        let residuals = self.solve_in_place(&mut rhs);
        let w: Vec<f64> = rhs.col(0).iter().copied().collect();
        let mut r = self.response_from_field(x, z, &load, &w);
        r.residual = residuals[0];
        Ok((r, w))
    }

    /// The work-conjugate compliance (1/P²) ∫ p w dA of a unit force spread over `patch`
    /// (m/N): the Kirchhoff counterpart of [`crate::mindlin::Supported::respond`].
    pub fn respond_patch(&self, patch: &crate::Patch) -> Result<f64, FemError> {
        let mut load = self.model.patch_load(patch)?;
        for &d in &self.held {
            load[d] = 0.0;
        }
        let mut rhs = Mat::<f64>::from_fn(load.len(), 1, |i, _| load[i]);
        self.solve_in_place(&mut rhs);
        Ok(load.iter().enumerate().map(|(i, f)| f * rhs[(i, 0)]).sum())
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
                    let ke = self.model.element_stiffness(ex, ez, &self.supports);
                    let kw: f64 = (0..16).map(|q| ke[(local, q)] * w[dofs[q]]).sum();
                    let applied: f64 =
                        load.0.iter().zip(load.1.iter()).filter(|(d, _)| **d == dof).map(|(_, v)| v).sum();
                    CornerResponse { reaction: applied - kw, spring_compliance: 0.0 }
                }
            };
        }
        let mut springs: f64 = corners.iter().map(|c| c.spring_compliance).sum();
        let mut edge_spring_compliance = 0.0;
        if self.supports.edges.iter().any(|e| matches!(e, EdgeSupport::Elastic(_))) {
            edge_spring_compliance = self.model.edge_spring_store(&self.supports, w);
            springs += edge_spring_compliance;
        }
        PointResponse {
            x,
            z,
            compliance,
            plate_compliance: compliance - springs,
            corners,
            edge_spring_compliance,
            residual: 0.0,
        }
    }
}
