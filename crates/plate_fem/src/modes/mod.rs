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
//! every element (K⁻¹'s from the factor's selected inverse, less the modes' parts), so R at
//! any point is one element evaluation; [`Modes::residual_field`]
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

pub(crate) mod krylov;
mod residual;

pub use residual::ResidualFlexibility;

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

/// The generalized problem Kφ = ω²Mφ as the eigensolvers use it: products with K and M
/// (held rows and columns zero) and which DOFs are held.
pub(crate) trait Pencil {
    /// Whether each DOF is held (its mode components are zero).
    fn held(&self) -> &[bool];
    /// M x.
    fn mass(&self, x: &[f64]) -> Vec<f64>;
    /// K x.
    fn stiffness(&self, x: &[f64]) -> Vec<f64>;
    /// A random vector as the search takes it in: unchanged where M is positive definite;
    /// where some DOFs carry no mass, K⁻¹M r, which has no part along the modes of infinite
    /// frequency (directions the M inner product cannot see).
    fn start(&self, r: Vec<f64>) -> Vec<f64> {
        r
    }
}

/// Eigenpairs found: ωᵢ, M-normalised shapes (DOFs x modes), relative residuals and
/// max |ΦᵀMΦ - I|.
pub(crate) struct Finished {
    pub omega: Vec<f64>,
    pub shapes: Mat<f64>,
    pub residuals: Vec<f64>,
    pub orthogonality: f64,
}

/// The plate's matrices of the generalized problem on one support set.
struct SparsePencil {
    /// K with springs, held rows and columns zero (for products; not factorizable).
    k: faer::sparse::SparseColMat<usize, f64>,
    /// M with held rows and columns zero.
    m: faer::sparse::SparseColMat<usize, f64>,
    held: Vec<bool>,
}

impl SparsePencil {
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

impl Pencil for SparsePencil {
    fn held(&self) -> &[bool] {
        &self.held
    }
    fn mass(&self, x: &[f64]) -> Vec<f64> {
        symmetric_upper_apply(&self.m, x)
    }
    fn stiffness(&self, x: &[f64]) -> Vec<f64> {
        symmetric_upper_apply(&self.k, x)
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn col(m: &Mat<f64>, j: usize) -> Vec<f64> {
    m.col(j).iter().copied().collect()
}

impl Modes {
    /// The lowest `count` modes of `model` on `supports`: dense on tiny meshes (at most
    /// [`DENSE_LIMIT`] free DOFs), shift-invert block Krylov otherwise.
    pub fn lowest(model: &Model, supports: &Supports, count: usize) -> Result<Self, FemError> {
        let free = SparsePencil::new(model, supports)?.free();
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

    /// The lowest `count` modes by a dense generalized symmetric eigensolver on the free
    /// DOFs (M = LLᵀ, L⁻¹KL⁻ᵀ y = ω² y, φ = L⁻ᵀy); refused above [`DENSE_LIMIT`] free DOFs.
    pub fn dense(model: &Model, supports: &Supports, count: usize) -> Result<Self, FemError> {
        supports.validate(model.props().length, model.props().width)?;
        let pencil = SparsePencil::new(model, supports)?;
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
        let Finished { omega, shapes, residuals, orthogonality } = finish(shapes, &pencil)?;
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
fn finish(mut shapes: Mat<f64>, pencil: &impl Pencil) -> Result<Finished, FemError> {
    let (n, count) = (shapes.nrows(), shapes.ncols());
    let mut omega = Vec::with_capacity(count);
    let mut residuals = Vec::with_capacity(count);
    let mut mshapes = Mat::<f64>::zeros(n, count);
    for m in 0..count {
        let mut v = col(&shapes, m);
        let mv = pencil.mass(&v);
        let kv = pencil.stiffness(&v);
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
    Ok(Finished { omega, shapes, residuals, orthogonality: orth })
}
