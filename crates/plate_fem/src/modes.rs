//! Free vibration of the supported plate: the lowest eigenpairs of K φ = ω² M φ, and the
//! residual flexibility of the modes left out.
//!
//! **Eigenpairs.** Shift-invert about zero with the support set's own sparse Cholesky
//! factorization: the operator K⁻¹M is self-adjoint in the M inner product, and its largest
//! eigenvalues 1/ω² belong to the plate's lowest modes. A block Krylov basis
//! span{X, K⁻¹MX, (K⁻¹M)²X, ...} of block size [`BLOCK`] (so that a mode of multiplicity up
//! to four, such as the equal pairs of a square plate, is found whole) is kept M-orthonormal
//! by two passes of block Gram-Schmidt (full reorthogonalisation), and the Rayleigh-Ritz
//! pairs of (K, M) on it are accepted once each of the lowest N has the relative residual
//! ‖Kφ - ω²Mφ‖/‖Kφ‖ ≤ [`RESIDUAL_TOLERANCE`] (Parlett, *The Symmetric Eigenvalue Problem*,
//! 1998, ch. 11 and 13: Rayleigh-Ritz on a Krylov subspace, and the shift-invert spectral
//! transformation for the end of the spectrum). On tiny meshes (at most [`DENSE_LIMIT`]
//! free DOFs) a dense solve is used instead; it is also the reference of the tests.
//!
//! **Residual flexibility.** With M-orthonormal modes, K⁻¹ = Σ φᵢφᵢᵀ/ωᵢ² over all modes.
//! Keeping N of them leaves R = K⁻¹ - Σ_{i≤N} φᵢφᵢᵀ/ωᵢ², positive semi-definite: the static
//! flexibility of the truncated modes, which a reduced model adds to the modal response as
//! their quasi-static answer to the load (the static correction, or mode-acceleration
//! method: Craig & Kurdila, *Fundamentals of Structural Dynamics*, 2nd ed., 2006). Between
//! two points p, s it is N(p)ᵀ R N(s). [`ResidualFlexibility`] keeps R's 16 x 16 block on
//! every element, so R at any point is one element evaluation; [`Modes::residual_field`]
//! gives R f for any load vector f with one solve.

use crate::element::{self, Vec16};
use crate::mesh::Mesh;
use crate::model::{symmetric_upper_apply, Factorization, Model};
use crate::supports::Supports;
use crate::FemError;
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatRef, Par};
use nalgebra::DMatrix;
use serde::Serialize;

/// Largest accepted relative residual ‖Kφ - ω²Mφ‖/‖Kφ‖ of a returned mode. The Krylov
/// iteration reaches 1e-12 and below on the plates of the tests; 1e-8 is the point beyond
/// which a frequency (whose error is about the residual squared) or a modal force would no
/// longer be good to 1e-8 relative.
pub const RESIDUAL_TOLERANCE: f64 = 1e-8;

/// Block size of the Krylov basis: the largest multiplicity of a frequency found whole.
pub const BLOCK: usize = 4;

/// Most free DOFs for which [`Modes::lowest`] solves densely (O(n³), a tenth of a second
/// here); above it the sparse Krylov iteration is used.
pub const DENSE_LIMIT: usize = 600;

/// How the modes were found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum EigenMethod {
    /// Shift-invert block Krylov with Rayleigh-Ritz; `basis` is the final basis size.
    Krylov {
        /// Basis vectors used.
        basis: usize,
    },
    /// Dense generalized symmetric eigensolver on the free DOFs.
    Dense,
}

/// The lowest modes of a supported plate, M-orthonormal (φᵢᵀMφⱼ = δᵢⱼ), zero on held DOFs.
#[derive(Debug, Clone)]
pub struct Modes {
    mesh: Mesh,
    supports: Supports,
    omega: Vec<f64>,
    /// DOFs x modes.
    shapes: Mat<f64>,
    residuals: Vec<f64>,
    orthogonality: f64,
    method: EigenMethod,
}

/// The matrices of the generalized problem on one support set.
struct Pencil {
    /// K with springs, held rows and columns zero (for products; not factorizable).
    k: faer::sparse::SparseColMat<usize, f64>,
    /// M with held rows and columns zero.
    m: faer::sparse::SparseColMat<usize, f64>,
    held: Vec<bool>,
}

impl Pencil {
    fn new(model: &Model, supports: &Supports) -> Result<Self, FemError> {
        let k = model.supported_matrix(supports, 1.0, 0.0, false)?;
        let m = model.supported_mass(supports)?;
        let mut held = vec![false; model.dofs()];
        for d in supports.constrained_dofs(model.mesh()) {
            held[d] = true;
        }
        Ok(Self { k, m, held })
    }
    fn free(&self) -> usize {
        self.held.iter().filter(|h| !**h).count()
    }
}

/// A deterministic pseudo-random vector (xorshift64*), zero on held DOFs: a start block with
/// a component along every mode, whatever the plate's symmetry.
fn random_vector(state: &mut u64, held: &[bool]) -> Vec<f64> {
    held.iter()
        .map(|&h| {
            *state ^= *state >> 12;
            *state ^= *state << 25;
            *state ^= *state >> 27;
            let r = state.wrapping_mul(0x2545_f491_4f6c_dd1d);
            if h {
                0.0
            } else {
                (r >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            }
        })
        .collect()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn col(m: &Mat<f64>, j: usize) -> Vec<f64> {
    m.col(j).iter().copied().collect()
}

/// An M-orthonormal basis with its images under M and K, grown block by block.
struct Basis {
    q: Mat<f64>,
    mq: Mat<f64>,
    kq: Mat<f64>,
    len: usize,
}

impl Basis {
    fn new(n: usize, capacity: usize) -> Self {
        Self { q: Mat::zeros(n, capacity), mq: Mat::zeros(n, capacity), kq: Mat::zeros(n, capacity), len: 0 }
    }

    /// Removes the components along the basis from `w` (M inner product), twice.
    fn orthogonalize(&self, w: &mut Mat<f64>) {
        if self.len == 0 {
            return;
        }
        let q = self.q.as_ref().subcols(0, self.len);
        let mq = self.mq.as_ref().subcols(0, self.len);
        for _ in 0..2 {
            let mut c = Mat::<f64>::zeros(self.len, w.ncols());
            matmul(c.as_mut(), Accum::Replace, mq.transpose(), w.as_ref(), 1.0, Par::Seq);
            matmul(w.as_mut(), Accum::Add, q, c.as_ref(), -1.0, Par::Seq);
        }
    }

    /// Appends the columns of `w` that are independent of the basis, M-normalized; a column
    /// that has (numerically) no new direction is replaced by a random one. Returns the
    /// indices of the appended columns.
    fn append(&mut self, pencil: &Pencil, mut w: Mat<f64>, seed: &mut u64) -> std::ops::Range<usize> {
        let n = w.nrows();
        self.orthogonalize(&mut w);
        let start = self.len;
        for j in 0..w.ncols() {
            if self.len == self.q.ncols() {
                break;
            }
            let mut v = col(&w, j);
            let mut tries = 0;
            // The block is already orthogonal to the basis before it; a random replacement
            // is not.
            let mut from = start;
            loop {
                let norm0 = dot(&v, &symmetric_upper_apply(&pencil.m, &v)).max(0.0).sqrt();
                // Two passes against the block's earlier columns (or everything).
                for _ in 0..2 {
                    for c in from..self.len {
                        let a: f64 = (0..n).map(|i| self.mq[(i, c)] * v[i]).sum();
                        for (i, vi) in v.iter_mut().enumerate() {
                            *vi -= a * self.q[(i, c)];
                        }
                    }
                }
                let mv = symmetric_upper_apply(&pencil.m, &v);
                let norm = dot(&v, &mv).max(0.0).sqrt();
                if norm > 1e-10 * norm0 && norm > 0.0 {
                    let kv = symmetric_upper_apply(&pencil.k, &v);
                    for i in 0..n {
                        self.q[(i, self.len)] = v[i] / norm;
                        self.mq[(i, self.len)] = mv[i] / norm;
                        self.kq[(i, self.len)] = kv[i] / norm;
                    }
                    self.len += 1;
                    break;
                }
                tries += 1;
                if tries > 3 {
                    break;
                }
                v = random_vector(seed, &pencil.held);
                from = 0;
            }
        }
        start..self.len
    }
}

impl Modes {
    /// The lowest `count` modes of `model` on `supports`: dense on tiny meshes (at most
    /// [`DENSE_LIMIT`] free DOFs), shift-invert block Krylov otherwise.
    pub fn lowest(model: &Model, supports: &Supports, count: usize) -> Result<Self, FemError> {
        let free = Pencil::new(model, supports)?.free();
        if free <= DENSE_LIMIT {
            Self::dense(model, supports, count)
        } else {
            Self::krylov(&model.factorize(supports)?, count)
        }
    }

    fn check_count(count: usize, free: usize) -> Result<(), FemError> {
        if count == 0 || count > free {
            return Err(FemError::Modes(format!(
                "{count} modes asked for; the supported plate has {free} free degrees of freedom, so the allowed range is [1, {free}]"
            )));
        }
        Ok(())
    }

    /// The lowest `count` modes by shift-invert block Krylov on the factorization `fact`
    /// of K (see the module).
    pub fn krylov(fact: &Factorization<'_>, count: usize) -> Result<Self, FemError> {
        let model = fact.model();
        let supports = *fact.supports();
        let pencil = Pencil::new(model, &supports)?;
        let n = model.dofs();
        let free = pencil.free();
        Self::check_count(count, free)?;
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let capacity = free.min((3 * count + 8 * BLOCK).max(count + 16 * BLOCK));
        let mut basis = Basis::new(n, capacity);
        // Start: K⁻¹M applied once to a random block, which damps the highest modes.
        let b = BLOCK.min(free);
        let mut x = Mat::<f64>::zeros(n, b);
        for j in 0..b {
            let r = random_vector(&mut seed, &pencil.held);
            let mr = symmetric_upper_apply(&pencil.m, &r);
            for i in 0..n {
                x[(i, j)] = mr[i];
            }
        }
        fact.solve_unchecked(&mut x);
        let mut block = basis.append(&pencil, x, &mut seed);
        let mut next_check = (3 * count / 2 + 2 * BLOCK).min(free);
        loop {
            if basis.len >= next_check || basis.len == capacity {
                if let Some(modes) = rayleigh_ritz(&basis, count, &pencil)? {
                    let (omega, shapes, residuals, orthogonality) = modes;
                    let worst = residuals.iter().copied().fold(0.0, f64::max);
                    if worst <= RESIDUAL_TOLERANCE || basis.len == free {
                        if worst > RESIDUAL_TOLERANCE {
                            return Err(FemError::Modes(format!(
                                "the complete basis of {free} vectors left a residual {worst:e} above {RESIDUAL_TOLERANCE:e}: the stiffness or mass is too ill conditioned"
                            )));
                        }
                        return Ok(Self {
                            mesh: model.mesh().clone(),
                            supports,
                            omega,
                            shapes,
                            residuals,
                            orthogonality,
                            method: EigenMethod::Krylov { basis: basis.len },
                        });
                    }
                    if basis.len == capacity {
                        // Grow the basis: keep what was built.
                        let grown = free.min(capacity + count.max(8 * BLOCK));
                        let mut bigger = Basis::new(n, grown);
                        for c in 0..basis.len {
                            for i in 0..n {
                                bigger.q[(i, c)] = basis.q[(i, c)];
                                bigger.mq[(i, c)] = basis.mq[(i, c)];
                                bigger.kq[(i, c)] = basis.kq[(i, c)];
                            }
                        }
                        bigger.len = basis.len;
                        basis = bigger;
                    }
                }
                next_check = (basis.len + (count / 4).max(2 * BLOCK)).min(free);
            }
            if block.is_empty() {
                // The Krylov space is invariant: continue from a random block.
                let r = random_vector(&mut seed, &pencil.held);
                let w = Mat::from_fn(n, 1, |i, _| r[i]);
                block = basis.append(&pencil, w, &mut seed);
                continue;
            }
            // Next block: K⁻¹ M X for the last block X (M X is stored).
            let mut w = Mat::<f64>::zeros(n, block.len());
            for (j, c) in block.clone().enumerate() {
                for i in 0..n {
                    w[(i, j)] = basis.mq[(i, c)];
                }
            }
            fact.solve_unchecked(&mut w);
            block = basis.append(&pencil, w, &mut seed);
        }
    }

    /// The lowest `count` modes by a dense generalized symmetric eigensolver on the free
    /// DOFs (M = LLᵀ, L⁻¹KL⁻ᵀ y = ω² y, φ = L⁻ᵀy); refused above [`DENSE_LIMIT`] free DOFs.
    pub fn dense(model: &Model, supports: &Supports, count: usize) -> Result<Self, FemError> {
        supports.validate(model.props().length, model.props().width)?;
        let pencil = Pencil::new(model, supports)?;
        let free_dofs: Vec<usize> = (0..model.dofs()).filter(|&d| !pencil.held[d]).collect();
        let nf = free_dofs.len();
        Self::check_count(count, nf)?;
        if nf > DENSE_LIMIT {
            return Err(FemError::Modes(format!(
                "a dense eigensolution of {nf} free DOFs is refused (at most {DENSE_LIMIT}); use the Krylov solver"
            )));
        }
        let n = model.dofs();
        let dense = |a: &faer::sparse::SparseColMat<usize, f64>| {
            let mut out = DMatrix::<f64>::zeros(nf, nf);
            for (j, &dj) in free_dofs.iter().enumerate() {
                let mut e = vec![0.0; n];
                e[dj] = 1.0;
                let c = symmetric_upper_apply(a, &e);
                for (i, &di) in free_dofs.iter().enumerate() {
                    out[(i, j)] = c[di];
                }
            }
            out
        };
        let (kd, md) = (dense(&pencil.k), dense(&pencil.m));
        let l = nalgebra::Cholesky::new(md.clone())
            .ok_or_else(|| FemError::Modes("the consistent mass on the free DOFs is not positive definite".into()))?
            .l();
        let li = l.clone().try_inverse().ok_or_else(|| FemError::Modes("the mass factor is singular".into()))?;
        let a = &li * &kd * li.transpose();
        let a = 0.5 * (&a + a.transpose());
        let eig = a.symmetric_eigen();
        let mut order: Vec<usize> = (0..nf).collect();
        order.sort_by(|&x, &y| eig.eigenvalues[x].total_cmp(&eig.eigenvalues[y]));
        let mut shapes = Mat::<f64>::zeros(n, count);
        for (m, &j) in order.iter().take(count).enumerate() {
            let y = eig.eigenvectors.column(j).into_owned();
            let phi = li.transpose() * y;
            for (i, &di) in free_dofs.iter().enumerate() {
                shapes[(di, m)] = phi[i];
            }
        }
        let (omega, shapes, residuals, orthogonality) = finish(shapes, &pencil)?;
        Ok(Self {
            mesh: model.mesh().clone(),
            supports: *supports,
            omega,
            shapes,
            residuals,
            orthogonality,
            method: EigenMethod::Dense,
        })
    }

    /// Number of modes.
    pub fn count(&self) -> usize {
        self.omega.len()
    }
    /// Angular frequencies ωᵢ, rad/s, ascending.
    pub fn omegas(&self) -> &[f64] {
        &self.omega
    }
    /// Frequencies ωᵢ/2π, Hz.
    pub fn frequencies_hz(&self) -> Vec<f64> {
        self.omega.iter().map(|w| w / (2.0 * std::f64::consts::PI)).collect()
    }
    /// Mode shapes, DOFs x modes.
    pub fn shapes(&self) -> MatRef<'_, f64> {
        self.shapes.as_ref()
    }
    /// Relative residuals ‖Kφ - ω²Mφ‖/‖Kφ‖.
    pub fn residuals(&self) -> &[f64] {
        &self.residuals
    }
    /// max |ΦᵀMΦ - I|.
    pub fn orthogonality(&self) -> f64 {
        self.orthogonality
    }
    /// How they were found.
    pub fn method(&self) -> EigenMethod {
        self.method
    }
    /// The support set.
    pub fn supports(&self) -> &Supports {
        &self.supports
    }
    /// The mesh they live on.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// Every mode's deflection at (x, z): φᵢ(p) = N(p)ᵀφᵢ.
    pub fn at(&self, x: f64, z: f64) -> Result<Vec<f64>, FemError> {
        let (dofs, n) = shape_at(&self.mesh, x, z)?;
        Ok((0..self.count()).map(|m| (0..16).map(|k| n[k] * self.shapes[(dofs[k], m)]).sum()).collect())
    }

    /// R f = K⁻¹f - Σᵢ φᵢ(φᵢᵀf)/ωᵢ² for a load vector `f` (held entries ignored): the static
    /// response of the truncated modes, by one solve on `fact` (the factorization of K on
    /// the same support set).
    pub fn residual_field(&self, fact: &Factorization<'_>, f: &[f64]) -> Vec<f64> {
        let n = f.len();
        let mut x = Mat::from_fn(n, 1, |i, _| f[i]);
        for &h in fact.held() {
            x[(h, 0)] = 0.0;
        }
        let fz: Vec<f64> = col(&x, 0);
        fact.solve_in_place(&mut x);
        let mut r = col(&x, 0);
        for m in 0..self.count() {
            let c = (0..n).map(|i| self.shapes[(i, m)] * fz[i]).sum::<f64>() / (self.omega[m] * self.omega[m]);
            for (i, ri) in r.iter_mut().enumerate() {
                *ri -= c * self.shapes[(i, m)];
            }
        }
        r
    }
}

/// The 16 DOFs and shape-function values at (x, z).
pub fn shape_at(mesh: &Mesh, x: f64, z: f64) -> Result<([usize; 16], Vec16), FemError> {
    let loc = mesh.locate(x, z)?;
    let (a, b) = mesh.element_size(loc.ex, loc.ez);
    Ok((mesh.element_dofs(loc.ex, loc.ez), element::shape(a, b, loc.xi, loc.eta)))
}

/// Frequencies, sign-fixed shapes, residuals and the orthogonality error of candidate
/// shapes (columns of `shapes`, any normalisation).
#[allow(clippy::type_complexity)]
fn finish(mut shapes: Mat<f64>, pencil: &Pencil) -> Result<(Vec<f64>, Mat<f64>, Vec<f64>, f64), FemError> {
    let (n, count) = (shapes.nrows(), shapes.ncols());
    let mut omega = Vec::with_capacity(count);
    let mut residuals = Vec::with_capacity(count);
    let mut mshapes = Mat::<f64>::zeros(n, count);
    for m in 0..count {
        let mut v = col(&shapes, m);
        let mv = symmetric_upper_apply(&pencil.m, &v);
        let kv = symmetric_upper_apply(&pencil.k, &v);
        let mass = dot(&v, &mv);
        let lambda = dot(&v, &kv) / mass;
        if !(lambda.is_finite() && lambda > 0.0 && mass > 0.0) {
            return Err(FemError::Modes(format!("mode {} has ω² = {lambda:e}, not positive", m + 1)));
        }
        // Sign: the largest component positive.
        let big = v.iter().copied().fold(0.0f64, |a, b| if b.abs() > a.abs() { b } else { a });
        let s = big.signum() / mass.sqrt();
        v.iter_mut().for_each(|x| *x *= s);
        let r: f64 = (0..n).map(|i| (kv[i] - lambda * mv[i]).powi(2)).sum::<f64>().sqrt();
        residuals.push(r / dot(&kv, &kv).sqrt());
        omega.push(lambda.sqrt());
        for i in 0..n {
            shapes[(i, m)] = v[i];
            mshapes[(i, m)] = mv[i] * s;
        }
    }
    let mut g = Mat::<f64>::zeros(count, count);
    matmul(g.as_mut(), Accum::Replace, shapes.as_ref().transpose(), mshapes.as_ref(), 1.0, Par::Seq);
    let mut orth: f64 = 0.0;
    for i in 0..count {
        for j in 0..count {
            orth = orth.max((g[(i, j)] - if i == j { 1.0 } else { 0.0 }).abs());
        }
    }
    Ok((omega, shapes, residuals, orth))
}

/// Rayleigh-Ritz of (K, M) on the basis; the lowest `count` pairs, or None if the basis is
/// still smaller than `count`.
#[allow(clippy::type_complexity)]
fn rayleigh_ritz(
    basis: &Basis,
    count: usize,
    pencil: &Pencil,
) -> Result<Option<(Vec<f64>, Mat<f64>, Vec<f64>, f64)>, FemError> {
    let d = basis.len;
    if d < count {
        return Ok(None);
    }
    let q = basis.q.as_ref().subcols(0, d);
    let kq = basis.kq.as_ref().subcols(0, d);
    let mut kp = Mat::<f64>::zeros(d, d);
    matmul(kp.as_mut(), Accum::Replace, q.transpose(), kq, 1.0, Par::Seq);
    let a = DMatrix::from_fn(d, d, |i, j| 0.5 * (kp[(i, j)] + kp[(j, i)]));
    let eig = a.symmetric_eigen();
    let mut order: Vec<usize> = (0..d).collect();
    order.sort_by(|&x, &y| eig.eigenvalues[x].total_cmp(&eig.eigenvalues[y]));
    let s = Mat::<f64>::from_fn(d, count, |i, j| eig.eigenvectors[(i, order[j])]);
    let mut shapes = Mat::<f64>::zeros(q.nrows(), count);
    matmul(shapes.as_mut(), Accum::Replace, q, s.as_ref(), 1.0, Par::Seq);
    finish(shapes, pencil).map(Some)
}

/// R = K⁻¹ - Σ_{i≤N} φᵢφᵢᵀ/ωᵢ² on every element: the residual flexibility of the modes a
/// [`Modes`] leaves out, at any point by one element evaluation; and RMR, the mass of the
/// residual static shape.
///
/// With the load vector N(p) of a unit force at p, ψ(p) = R N(p) is the static deflection
/// of the truncated modes alone. It is M-orthogonal to the kept modes (ΦᵀMK⁻¹ = Ω⁻²Φᵀ),
/// its stiffness ψᵀKψ and its load participation ψᵀN both equal C_res(p) = N(p)ᵀRN(p) (RKR =
/// R), and its mass is m_ψ(p) = ψᵀMψ = N(p)ᵀ(RMR)N(p) with RMR = K⁻¹MK⁻¹ - Σᵢφᵢφᵢᵀ/ωᵢ⁴. As
/// one more Ritz vector beside the modes it is a "residual mode" of frequency
/// ω_ψ² = C_res/m_ψ, which keeps the static correction's compliance and adds the truncated
/// modes' inertia (the residual-vector augmentation of a modal basis: Dickens, Nakagawa &
/// Wittbrodt, *A critique of mode acceleration and modal truncation augmentation methods for
/// modal response analysis*, Computers & Structures 62 (1997) 985).
#[derive(Debug, Clone)]
pub struct ResidualFlexibility {
    mesh: Mesh,
    /// Per element (row order, ex fastest), R's 16 x 16 block, row-major.
    blocks: Vec<[f64; 256]>,
    /// Per element, RMR's block.
    mass_blocks: Vec<[f64; 256]>,
}

impl ResidualFlexibility {
    /// Assembles the element blocks of K⁻¹ and K⁻¹MK⁻¹ from solves with unit loads on every
    /// free DOF (in blocks of 64 columns) and subtracts the modes' parts.
    pub fn new(fact: &Factorization<'_>, modes: &Modes) -> Result<Self, FemError> {
        let model = fact.model();
        let mesh = model.mesh().clone();
        if modes.mesh != mesh || modes.supports != *fact.supports() {
            return Err(FemError::Modes(
                "the modes belong to another mesh or support set than the factorization".into(),
            ));
        }
        let mass = model.supported_mass(fact.supports())?;
        let n = model.dofs();
        let (nx, nz) = (mesh.nx(), mesh.nz());
        let mut blocks = vec![[0.0f64; 256]; mesh.elements()];
        let mut mass_blocks = vec![[0.0f64; 256]; mesh.elements()];
        let held: std::collections::HashSet<usize> = fact.held().iter().copied().collect();
        const CHUNK: usize = 64;
        let cols: Vec<usize> = (0..n).filter(|d| !held.contains(d)).collect();
        let nodes_x = nx + 1;
        let harvest = |blocks: &mut [[f64; 256]], x: &Mat<f64>, j: usize, d: usize| {
            let node = d / 4;
            let q = d % 4;
            let (i, jn) = (node % nodes_x, node / nodes_x);
            for ez in jn.saturating_sub(1)..=jn.min(nz - 1) {
                for ex in i.saturating_sub(1)..=i.min(nx - 1) {
                    let local_node = [(0, 0), (1, 0), (0, 1), (1, 1)]
                        .iter()
                        .position(|&(di, dj)| ex + di == i && ez + dj == jn)
                        .unwrap_or(0);
                    let l = 4 * local_node + q;
                    let dofs = mesh.element_dofs(ex, ez);
                    let b = &mut blocks[ez * nx + ex];
                    for k in 0..16 {
                        b[k * 16 + l] = x[(dofs[k], j)];
                    }
                }
            }
        };
        for chunk in cols.chunks(CHUNK) {
            let mut x = Mat::<f64>::zeros(n, chunk.len());
            for (j, &d) in chunk.iter().enumerate() {
                x[(d, j)] = 1.0;
            }
            fact.solve_in_place(&mut x);
            let mut y = Mat::<f64>::zeros(n, chunk.len());
            for j in 0..chunk.len() {
                let mx = symmetric_upper_apply(&mass, x.col_as_slice(j));
                y.col_as_slice_mut(j).copy_from_slice(&mx);
            }
            fact.solve_in_place(&mut y);
            for (j, &d) in chunk.iter().enumerate() {
                harvest(&mut blocks, &x, j, d);
                harvest(&mut mass_blocks, &y, j, d);
            }
        }
        let shapes = modes.shapes();
        let count = modes.count();
        for ez in 0..nz {
            for ex in 0..nx {
                let dofs = mesh.element_dofs(ex, ez);
                let e = ez * nx + ex;
                for (b, power) in [(&mut blocks[e], 2), (&mut mass_blocks[e], 4)] {
                    for k in 0..16 {
                        for l in 0..16 {
                            let modal: f64 = (0..count)
                                .map(|m| shapes[(dofs[k], m)] * shapes[(dofs[l], m)] / modes.omega[m].powi(power))
                                .sum();
                            b[k * 16 + l] -= modal;
                        }
                    }
                    for k in 0..16 {
                        for l in 0..k {
                            let s = 0.5 * (b[k * 16 + l] + b[l * 16 + k]);
                            b[k * 16 + l] = s;
                            b[l * 16 + k] = s;
                        }
                    }
                }
            }
        }
        Ok(Self { mesh, blocks, mass_blocks })
    }

    /// N(p)ᵀ R N(p) at p = (x, z), m/N: the static compliance of the truncated modes.
    pub fn at(&self, x: f64, z: f64) -> Result<f64, FemError> {
        let loc = self.mesh.locate(x, z)?;
        let (a, b) = self.mesh.element_size(loc.ex, loc.ez);
        let n = element::shape(a, b, loc.xi, loc.eta);
        Ok(self.quadratic(loc.ez * self.mesh.nx() + loc.ex, &n))
    }

    /// Nᵀ R N on element `e` for shape values `n` (m/N).
    pub fn quadratic(&self, e: usize, n: &Vec16) -> f64 {
        quadratic(&self.blocks[e], n)
    }

    /// Nᵀ (RMR) N on element `e` for shape values `n`: the mass m_ψ of the residual shape
    /// ψ = RN, kg·(m/N)².
    pub fn mass_quadratic(&self, e: usize, n: &Vec16) -> f64 {
        quadratic(&self.mass_blocks[e], n)
    }

    /// The mesh.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }
}

fn quadratic(b: &[f64; 256], n: &Vec16) -> f64 {
    (0..16).map(|k| n[k] * (0..16).map(|l| b[k * 16 + l] * n[l]).sum::<f64>()).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::PlateProperties;

    fn plate(l: f64, b: f64) -> PlateProperties {
        PlateProperties {
            length: l,
            width: b,
            thickness: 0.008,
            youngs_modulus: 210e9,
            poisson_ratio: 0.3,
            density: 7850.0,
        }
    }

    /// On a mesh small enough for both, the Krylov modes are the dense modes: frequencies to
    /// 1e-10 (both are exact eigenpairs of the same pencil, to their residuals), shapes to
    /// 1e-6 (a shape's error is its residual over the gap to the next frequency).
    #[test]
    fn krylov_matches_dense_on_a_small_mesh() {
        let model = Model::new(plate(0.4584, 0.36), Mesh::uniform(0.4584, 0.36, 8, 6).unwrap()).unwrap();
        for s in [Supports::con1(), Supports::con3(5e8), Supports::all_edges_simple()] {
            let dense = Modes::dense(&model, &s, 30).unwrap();
            let fact = model.factorize(&s).unwrap();
            let kry = Modes::krylov(&fact, 30).unwrap();
            for (a, b) in dense.omegas().iter().zip(kry.omegas()) {
                assert!((a / b - 1.0).abs() < 1e-10, "{a} {b}");
            }
            assert!(kry.residuals().iter().all(|&r| r < RESIDUAL_TOLERANCE), "{:?}", kry.residuals());
            assert!(kry.orthogonality() < 1e-10 && dense.orthogonality() < 1e-10);
        }
    }
}
