//! The selected inverse: every entry of Z = K⁻¹ on the pattern of the Cholesky factor L,
//! from L alone, by Takahashi's equations.
//!
//! With K = LLᵀ, Z = L⁻ᵀL⁻¹ gives LᵀZ = L⁻¹, an upper-triangular system whose right side is
//! lower triangular. Take one supernode: its columns S, the rows R of its off-diagonal block
//! (all later than S), and L's blocks L_SS (lower triangular) and L_RS. Row block S of Lᵀ is
//! [L_SSᵀ  L_RSᵀ], so for the columns j ∈ R, where (L⁻¹)_Sj = 0, and for j ∈ S:
//!
//! ```text
//! Z_RS = -Z_RR U,      Z_SS = L_SS⁻ᵀ L_SS⁻¹ - Uᵀ Z_RS,      U = L_RS L_SS⁻¹
//! ```
//!
//! (Takahashi, Fagan & Chen, *Formation of a sparse bus impedance matrix and its application
//! to short circuit study*, PICA 1973; Erisman & Tinney, *On computing certain elements of
//! the inverse of a sparse matrix*, CACM 18 (1975) 177; the supernodal form as in Lin, Yang,
//! Meza, Lu, Ying & E, *SelInv*, ACM TOMS 37 (2011) 40). R is a clique of the filled graph,
//! so Z_RR lies on L's pattern and was found at a later supernode: sweeping the supernodes
//! last to first needs nothing outside the pattern. The cost is a small multiple of the
//! factorization's (dense triangular solves and products on the same blocks), against one
//! pair of triangular solves per column for the inverse by columns.
//!
//! The pattern holds every pair of DOFs an element couples, so each element's 16 x 16 block
//! of K⁻¹ is here: a point compliance N(p)ᵀK⁻¹N(p) is a quadratic form on one block.

use super::cholesky::{Cholesky, Symbolic};
use crate::element::Vec16;
use crate::FemError;
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::{solve_lower_triangular_in_place, solve_upper_triangular_in_place};
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
use faer::{Accum, Mat, MatMut, MatRef, Par};

/// Largest relative gap between a compliance from the selected inverse and from a refined
/// solve: both carry the factor's conditioning (relative residuals ≤ ~1e-10 on the meshes in
/// use) and nothing else, so they agree far inside it; an error in the inverse is O(1).
pub const SELECTED_AGREEMENT: f64 = 1e-8;

/// The entries of K⁻¹ on the pattern of K's supernodal Cholesky factor.
#[derive(Debug, Clone)]
pub struct SelectedInverse {
    /// The factor's symbolic analysis (its supernodes and ordering), shared with it.
    symbolic: Symbolic,
    /// Z in L's supernodal layout: per supernode, its (|S| + |R|) x |S| block, column-major,
    /// with the diagonal block stored whole.
    values: Vec<f64>,
    /// The supernode of each (permuted) column.
    supernode_of: Vec<usize>,
    /// The permuted index of each DOF (the fill-reducing ordering's inverse).
    permuted: Vec<usize>,
    /// The DOFs the supports hold: they read as zero, as a solve leaves them.
    held: Vec<bool>,
}

impl SelectedInverse {
    /// Sweeps Takahashi's equations over the supernodes of `cholesky`, last to first; the
    /// DOFs `held` read as zero.
    pub(crate) fn new(cholesky: &Cholesky, held: &[usize]) -> Result<Self, FemError> {
        let symbolic = cholesky.symbolic().faer();
        let SymbolicCholeskyRaw::Supernodal(s) = symbolic.raw() else {
            return Err(defect("the factor is not supernodal"));
        };
        let n = s.nrows();
        let permuted = match symbolic.perm() {
            Some(p) => p.arrays().1.to_vec(),
            None => (0..n).collect(),
        };
        let mut supernode_of = vec![0; n];
        for k in 0..s.n_supernodes() {
            supernode_of[s.supernode_begin()[k]..s.supernode_end()[k]].fill(k);
        }
        for k in 0..s.n_supernodes() {
            if !s.supernode(k).pattern().windows(2).all(|w| w[0] < w[1]) {
                return Err(defect("a supernode's row pattern is not sorted"));
            }
        }
        let mut is_held = vec![false; n];
        for &d in held {
            if let Some(h) = is_held.get_mut(d) {
                *h = true;
            }
        }
        let mut this = Self {
            symbolic: cholesky.symbolic().clone(),
            values: vec![0.0; s.len_val()],
            supernode_of,
            permuted,
            held: is_held,
        };
        for k in (0..s.n_supernodes()).rev() {
            this.sweep(s, cholesky.values(), k)?;
        }
        Ok(this)
    }

    /// Z_RS and Z_SS of supernode `k`, from its L blocks (in `l_values`) and the Z_RR found
    /// before.
    fn sweep(&mut self, s: &SymbolicSupernodalCholesky<usize>, l_values: &[f64], k: usize) -> Result<(), FemError> {
        let l = block(s, l_values, k);
        let ns = l.ncols();
        let pattern = s.supernode(k).pattern();
        let nr = pattern.len();
        let (l_ss, l_rs) = l.split_at_row(ns);
        // Uᵀ = L_SS⁻ᵀ L_RSᵀ.
        let mut ut = l_rs.transpose().to_owned();
        solve_upper_triangular_in_place(l_ss.transpose(), ut.as_mut(), Par::Seq);
        let z_rr = self.gather(s, pattern)?;
        let mut z_rs = Mat::<f64>::zeros(nr, ns);
        matmul(z_rs.as_mut(), Accum::Replace, z_rr.as_ref(), ut.transpose(), -1.0, Par::Seq);
        let mut l_inv = Mat::<f64>::identity(ns, ns);
        solve_lower_triangular_in_place(l_ss, l_inv.as_mut(), Par::Seq);
        let mut z_ss = Mat::<f64>::zeros(ns, ns);
        matmul(z_ss.as_mut(), Accum::Replace, l_inv.transpose(), l_inv.as_ref(), 1.0, Par::Seq);
        matmul(z_ss.as_mut(), Accum::Add, ut.as_ref(), z_rs.as_ref(), -1.0, Par::Seq);
        let mut z = block_mut(s, &mut self.values, k);
        for j in 0..ns {
            for i in 0..ns {
                // Symmetric in exact arithmetic; the mean removes the rounding asymmetry.
                z[(i, j)] = 0.5 * (z_ss[(i, j)] + z_ss[(j, i)]);
            }
            for i in 0..nr {
                z[(ns + i, j)] = z_rs[(i, j)];
            }
        }
        Ok(())
    }

    /// Z_RR for the sorted rows `rows`, whole, from the supernodes already swept.
    fn gather(&self, s: &SymbolicSupernodalCholesky<usize>, rows: &[usize]) -> Result<Mat<f64>, FemError> {
        let nr = rows.len();
        let mut z = Mat::<f64>::zeros(nr, nr);
        for b in 0..nr {
            let c = rows[b];
            let t = self.supernode_of[c];
            let zt = block(s, &self.values, t);
            let (start, end) = (s.supernode_begin()[t], s.supernode_end()[t]);
            let below = s.supernode(t).pattern();
            let mut cursor = 0;
            for a in b..nr {
                let r = rows[a];
                let local = if r < end {
                    r - start
                } else {
                    // Both lists are sorted: one merge pass per column.
                    while cursor < below.len() && below[cursor] < r {
                        cursor += 1;
                    }
                    if below.get(cursor) != Some(&r) {
                        return Err(defect("a row of a supernode's clique is outside a later supernode's pattern"));
                    }
                    (end - start) + cursor
                };
                let v = zt[(local, c - start)];
                z[(a, b)] = v;
                z[(b, a)] = v;
            }
        }
        Ok(z)
    }

    /// (K⁻¹)_ij for DOFs `i`, `j` (0 if either is held), or `None` where the pair is outside
    /// L's pattern.
    pub fn get(&self, i: usize, j: usize) -> Option<f64> {
        if *self.held.get(i)? || *self.held.get(j)? {
            return Some(0.0);
        }
        let s = self.supernodal();
        let (pi, pj) = (*self.permuted.get(i)?, *self.permuted.get(j)?);
        let (r, c) = if pi >= pj { (pi, pj) } else { (pj, pi) };
        let t = self.supernode_of[c];
        let (start, end) = (s.supernode_begin()[t], s.supernode_end()[t]);
        let local =
            if r < end { r - start } else { (end - start) + s.supernode(t).pattern().binary_search(&r).ok()? };
        Some(block(s, &self.values, t)[(local, c - start)])
    }

    /// The block of K⁻¹ on `dofs` (an element's, say), row-major; `None` if a pair is
    /// outside L's pattern.
    pub fn block(&self, dofs: &[usize; 16]) -> Option<[f64; 256]> {
        let mut b = [0.0; 256];
        for k in 0..16 {
            for l in k..16 {
                let v = self.get(dofs[k], dofs[l])?;
                b[k * 16 + l] = v;
                b[l * 16 + k] = v;
            }
        }
        Some(b)
    }

    /// N ᵀ K⁻¹ N for the values `n` on `dofs` (a point's shape functions: its compliance), or
    /// `None` if a pair is outside L's pattern.
    pub fn quadratic(&self, dofs: &[usize; 16], n: &Vec16) -> Option<f64> {
        Some(crate::element::quadratic(&self.block(dofs)?, n))
    }

    fn supernodal(&self) -> &SymbolicSupernodalCholesky<usize> {
        match self.symbolic.faer().raw() {
            SymbolicCholeskyRaw::Supernodal(s) => s,
            // `new` refuses any other factor.
            SymbolicCholeskyRaw::Simplicial(_) => unreachable!("a selected inverse is built on a supernodal factor"),
        }
    }
}

/// Floating-point operations of one sweep and of one pair of triangular solves with one
/// right side (unrefined, as the corner family's base solves), from the supernode sizes: the
/// sweep's triangular solve and inverse and its three products, against 2 flops per stored
/// entry of L and way. Their ratio is the number
/// of points beyond which the selected inverse is the cheaper way to their compliances.
pub(crate) fn flops(cholesky: &Cholesky) -> Option<(f64, f64)> {
    let SymbolicCholeskyRaw::Supernodal(s) = cholesky.symbolic().faer().raw() else { return None };
    let mut sweep = 0.0;
    for k in 0..s.n_supernodes() {
        let ns = (s.supernode_end()[k] - s.supernode_begin()[k]) as f64;
        let nr = s.supernode(k).pattern().len() as f64;
        // Uᵀ (ns² nr), Z_RS (2 nr² ns), L_SS⁻¹ by solves on the identity (ns³), L⁻ᵀL⁻¹
        // (2 ns³), UᵀZ_RS (2 ns² nr).
        sweep += 3.0 * ns * ns * nr + 2.0 * nr * nr * ns + 3.0 * ns * ns * ns;
    }
    Some((sweep, 4.0 * s.len_val() as f64))
}

fn defect(what: &str) -> FemError {
    FemError::Modes(format!("selected inversion: {what}; this is a defect of this crate"))
}

/// Supernode `k`'s (|S| + |R|) x |S| block of `values` (L's or Z's layout).
fn block<'a>(s: &SymbolicSupernodalCholesky<usize>, values: &'a [f64], k: usize) -> MatRef<'a, f64> {
    let (ns, nr) = (s.supernode_end()[k] - s.supernode_begin()[k], s.supernode(k).pattern().len());
    let range = s.col_ptr_for_val()[k]..s.col_ptr_for_val()[k + 1];
    MatRef::from_column_major_slice(&values[range], ns + nr, ns)
}

fn block_mut<'a>(s: &SymbolicSupernodalCholesky<usize>, values: &'a mut [f64], k: usize) -> MatMut<'a, f64> {
    let (ns, nr) = (s.supernode_end()[k] - s.supernode_begin()[k], s.supernode(k).pattern().len());
    let range = s.col_ptr_for_val()[k]..s.col_ptr_for_val()[k + 1];
    MatMut::from_column_major_slice_mut(&mut values[range], ns + nr, ns)
}
