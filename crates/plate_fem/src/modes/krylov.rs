//! The shift-invert block Krylov iteration (module docs of [`super`]): an M-orthonormal
//! basis grown by K⁻¹M, Rayleigh-Ritz on it (Parlett, *The Symmetric Eigenvalue Problem*,
//! 1998, ch. 11 and 13).

use super::{col, dot, finish, EigenMethod, Finished, Modes, Pencil, SparsePencil, BLOCK, RESIDUAL_TOLERANCE};
use crate::model::Factorization;
use crate::FemError;
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par};
use nalgebra::DMatrix;

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

    /// The same basis with room for `capacity` vectors.
    fn grown(self, capacity: usize) -> Self {
        let mut bigger = Basis::new(self.q.nrows(), capacity);
        for c in 0..self.len {
            for i in 0..self.q.nrows() {
                bigger.q[(i, c)] = self.q[(i, c)];
                bigger.mq[(i, c)] = self.mq[(i, c)];
                bigger.kq[(i, c)] = self.kq[(i, c)];
            }
        }
        bigger.len = self.len;
        bigger
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
    fn append(&mut self, pencil: &impl Pencil, mut w: Mat<f64>, seed: &mut u64) -> std::ops::Range<usize> {
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
                let norm0 = dot(&v, &pencil.mass(&v)).max(0.0).sqrt();
                // Two passes against the block's earlier columns (or everything).
                for _ in 0..2 {
                    for c in from..self.len {
                        let a: f64 = (0..n).map(|i| self.mq[(i, c)] * v[i]).sum();
                        for (i, vi) in v.iter_mut().enumerate() {
                            *vi -= a * self.q[(i, c)];
                        }
                    }
                }
                let mv = pencil.mass(&v);
                let norm = dot(&v, &mv).max(0.0).sqrt();
                if norm > 1e-10 * norm0 && norm > 0.0 {
                    let kv = pencil.stiffness(&v);
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
                v = pencil.start(random_vector(seed, pencil.held()));
                from = 0;
            }
        }
        start..self.len
    }
}

/// The error of a search that reached its basis limit with a residual `worst` left.
fn not_converged(count: usize, limit: usize, worst: f64) -> FemError {
    FemError::Modes(format!(
        "the lowest {count} modes did not converge within a Krylov basis of {limit} vectors (residual {worst:e} above {RESIDUAL_TOLERANCE:e}): the supports leave modes of nearly zero frequency (springs far softer than the structure?), which the shift-invert search cannot separate; stiffen the supports or ask for fewer modes"
    ))
}

/// Basis vectors between two Rayleigh-Ritz steps once the basis holds `len`. A search that
/// converges does so with a basis of about 2·count + 30 vectors (188 for 80 modes, 412 for 200
/// on the paper's plate), checked every count/4 vectors as before. Past 4·count + 64 the search
/// is one that may not converge (rigid-body modes on soft springs, whose relative residual
/// rounding keeps above the tolerance): its steps then grow with the basis by a quarter, so
/// that the Rayleigh-Ritz steps, each O(len³), cost a few times the last one in all instead of
/// one every count/4 vectors up to the whole space (80 modes on 1e3 N/m corner springs of the
/// paper's plate: 126 s to the error before, 20 s now, both on this 2-core machine under the
/// same load). A search that converges takes exactly the steps it took before.
fn check_step(len: usize, count: usize) -> usize {
    let step = (count / 4).max(2 * BLOCK);
    if len > 4 * count + 64 {
        step.max(len / 4)
    } else {
        step
    }
}

impl Modes {
    /// The lowest `count` modes by shift-invert block Krylov on the factorization `fact`
    /// of K (see the module).
    pub fn krylov(fact: &Factorization<'_>, count: usize) -> Result<Self, FemError> {
        let model = fact.model();
        let supports = *fact.supports();
        let pencil = SparsePencil::new(model, &supports)?;
        Self::check_count(count, pencil.free())?;
        let (found, basis) = search(&pencil, |x| fact.solve_unchecked(x), count)?;
        Ok(Self {
            mesh: model.mesh().clone(),
            supports,
            omega: found.omega,
            shapes: found.shapes,
            residuals: found.residuals,
            orthogonality: found.orthogonality,
            method: EigenMethod::Krylov { basis },
        })
    }
}

/// The lowest `count` eigenpairs of `pencil` by shift-invert block Krylov, `solve` applying
/// K⁻¹ to every column in place (held rows zero), with the final basis size; `count` is at
/// most the free DOFs (checked by the caller).
pub(crate) fn search(
    pencil: &impl Pencil,
    solve: impl Fn(&mut Mat<f64>),
    count: usize,
) -> Result<(Finished, usize), FemError> {
    let held = pencil.held();
    let n = held.len();
    let free = held.iter().filter(|h| !**h).count();
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    // The basis never grows past `limit`: where the lowest modes need more (supports that
    // leave modes of nearly zero frequency), the search ends with an error, not after
    // the whole space.
    let limit = free.min((20 * count).max(400));
    let capacity = limit.min((3 * count + 8 * BLOCK).max(count + 16 * BLOCK));
    let mut basis = Basis::new(n, capacity);
    // Start: K⁻¹M applied once to a random block, which damps the highest modes.
    let b = BLOCK.min(free);
    let mut x = Mat::<f64>::zeros(n, b);
    for j in 0..b {
        let r = random_vector(&mut seed, held);
        let mr = pencil.mass(&r);
        for i in 0..n {
            x[(i, j)] = mr[i];
        }
    }
    solve(&mut x);
    let mut block = basis.append(pencil, x, &mut seed);
    let mut next_check = (3 * count / 2 + 2 * BLOCK).min(free);
    loop {
        if basis.len >= next_check || basis.len == basis.q.ncols() {
            if let Some(found) = rayleigh_ritz(&basis, count, pencil)? {
                let worst = found.residuals.iter().copied().fold(0.0, f64::max);
                if worst <= RESIDUAL_TOLERANCE || basis.len == free {
                    if worst > RESIDUAL_TOLERANCE {
                        return Err(FemError::Modes(format!(
                            "the complete basis of {free} vectors left a residual {worst:e} above {RESIDUAL_TOLERANCE:e}: the stiffness or mass is too ill conditioned"
                        )));
                    }
                    return Ok((found, basis.len));
                }
                if basis.len >= limit {
                    return Err(not_converged(count, limit, worst));
                }
            } else if basis.len >= limit {
                return Err(not_converged(count, limit, f64::INFINITY));
            }
            if basis.len == basis.q.ncols() {
                // Grow the basis: keep what was built. A full basis is also a Rayleigh-Ritz
                // step, so it grows as the steps do (see `check_step`).
                let capacity = basis.q.ncols();
                basis = basis.grown(limit.min(capacity + count.max(8 * BLOCK).max(check_step(capacity, count))));
            }
            next_check = (basis.len + check_step(basis.len, count)).min(free);
        }
        if block.is_empty() {
            // The Krylov space is invariant: continue from a random block.
            let r = pencil.start(random_vector(&mut seed, held));
            let w = Mat::from_fn(n, 1, |i, _| r[i]);
            block = basis.append(pencil, w, &mut seed);
            if block.is_empty() {
                // Nothing new even from random vectors: with a singular M (massless DOFs)
                // the basis spans every direction of finite frequency, and its pairs are
                // exact.
                return exhausted(&basis, count, pencil);
            }
            continue;
        }
        // Next block: K⁻¹ M X for the last block X (M X is stored).
        let mut w = Mat::<f64>::zeros(n, block.len());
        for (j, c) in block.clone().enumerate() {
            for i in 0..n {
                w[(i, j)] = basis.mq[(i, c)];
            }
        }
        solve(&mut w);
        block = basis.append(pencil, w, &mut seed);
    }
}

/// The pairs of a basis that spans every direction the mass reaches (fewer than the free
/// DOFs: some are massless), or the error that there are fewer than `count` of them.
fn exhausted(basis: &Basis, count: usize, pencil: &impl Pencil) -> Result<(Finished, usize), FemError> {
    let found = rayleigh_ritz(basis, count, pencil)?.ok_or_else(|| {
        FemError::Modes(format!(
            "{count} modes asked for; the structure has only {} of finite frequency (its other free DOFs carry no mass)",
            basis.len
        ))
    })?;
    let worst = found.residuals.iter().copied().fold(0.0, f64::max);
    if worst > RESIDUAL_TOLERANCE {
        return Err(FemError::Modes(format!(
            "the {count} modes asked for are nearly all the structure's {} modes of finite frequency, whose highest the shift-invert search cannot resolve (residual {worst:e} above {RESIDUAL_TOLERANCE:e}); ask for fewer",
            basis.len
        )));
    }
    Ok((found, basis.len))
}

/// Rayleigh-Ritz of (K, M) on the basis; the lowest `count` pairs, or None if the basis is
/// still smaller than `count`.
fn rayleigh_ritz(basis: &Basis, count: usize, pencil: &impl Pencil) -> Result<Option<Finished>, FemError> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;
    use crate::model::{Model, PlateProperties};
    use crate::supports::Supports;

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
