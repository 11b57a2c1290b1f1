//! Free vibration of a restrained shell structure: the lowest eigenpairs of Kφ = ω²Mφ with
//! a lumped mass, and what a point load asks of them.
//!
//! **Mass.** [`ShellMass`]: each element's ρhA is shared by its nodes' translations as
//! ∫N_k dA, and its rotary inertia ρh³/12 ∫N_k dA (Mindlin's) by the rotations about its two
//! in-plane axes, a 3 x 3 block (ρh³/12 ∫N_k dA)(I - nnᵀ) per node in the global frame. The
//! rotation about the normal (drilling) gets none: it is not a motion of the shell's fibres,
//! and the drilling penalty's stiffness against an inertia of the fibres' size would make a
//! cluster of spurious modes (one per node, near √(12 α G/ρh²)) among the structure's
//! lowest, which no search can resolve.
//!
//! **Eigenpairs.** The plate's search ([`crate::modes`]): shift-invert block Krylov on the
//! structure's own sparse Cholesky factorization of K, M-orthonormal by two passes of block
//! Gram-Schmidt, Rayleigh-Ritz pairs accepted once each of the lowest N has the relative
//! residual ‖Kφ - ω²Mφ‖/‖Kφ‖ ≤ [`crate::modes::RESIDUAL_TOLERANCE`] (Parlett, *The Symmetric
//! Eigenvalue Problem*, 1998, ch. 11 and 13). It runs on the unknowns (the held DOFs taken
//! out), where the lumped M is block diagonal (a node's translations, and a 3 x 3 block of its
//! rotations) and singular: the drilling rotations carry no mass, so a structure has fewer
//! modes of finite frequency than unknowns, and random restarts enter through K⁻¹M.
//!
//! **A load's modal view.** For a load vector f of unit resultant (a disc of pressure,
//! [`Structure::disc_load`](super::Structure::disc_load)) the work-conjugate displacement of mode i is φᵢ(p) = φᵢᵀf, and
//! the static compliance fᵀK⁻¹f is Σ φᵢ(p)²/ωᵢ² over the modes of finite frequency plus the
//! static part of the massless DOFs. Keeping N modes leaves the residual flexibility C_res(p) = fᵀK⁻¹f - Σ_{i≤N} φᵢ(p)²/ωᵢ² ≥ 0 (Craig & Kurdila,
//! *Fundamentals of Structural Dynamics*, 2nd ed., 2006: the static correction), and between
//! the load and a second load g the residual term is gᵀK⁻¹f - Σ φᵢᵀg φᵢᵀf/ωᵢ².

use super::element::DOFS_PER_NODE;
use super::structure::Factorized;
use super::structure::{Restraints, Shape, Structure};
use crate::model::cholesky::Cholesky;
use crate::model::symmetric_upper_apply;
use crate::modes::krylov::search;
use crate::modes::{Finished, Pencil};
use crate::FemError;
use faer::sparse::SparseColMat;
use faer::{Mat, MatRef};
use nalgebra::{Matrix3, Vector3};

/// The lumped mass of a structure (see the module): per node, the translational mass (kg)
/// and the 3 x 3 rotary inertia (kg m²) in the global frame.
#[derive(Debug, Clone)]
pub struct ShellMass {
    translational: Vec<f64>,
    rotary: Vec<Matrix3<f64>>,
}

impl Structure {
    /// The lumped (diagonal) mass of steel of density `rho` (kg/m³) over all DOFs: each
    /// element's ρhA shared by its nodes' translations as ∫ N_k dA (equally on a rectangle),
    /// and its rotary inertia ρh³A/12 alike by their rotations (the drilling one too, so that
    /// no DOF is massless): the inverse iteration's mass for the fundamental frequency. The
    /// modes take [`super::ShellMass`], which leaves the drilling rotation massless.
    pub fn lumped_mass(&self, rho: f64) -> Vec<f64> {
        let mut m = vec![0.0; self.dofs()];
        for e in &self.elements {
            let h = e.thickness;
            let shares = match e.shape {
                Shape::Rectangle { a, b } => [(rho * h * a * b / 4.0, rho * h.powi(3) / 12.0 * a * b / 4.0); 4],
                Shape::Quad { nodal_areas } => nodal_areas.map(|s| (rho * h * s, rho * h.powi(3) / 12.0 * s)),
            };
            for (&n, (translation, rotation)) in e.nodes.iter().zip(shares) {
                for i in 0..3 {
                    m[DOFS_PER_NODE * n + i] += translation;
                    m[DOFS_PER_NODE * n + 3 + i] += rotation;
                }
            }
        }
        m
    }
}

impl ShellMass {
    /// The lumped mass of `structure` of density `rho` (kg/m³).
    pub fn lumped(structure: &Structure, rho: f64) -> Self {
        let nodes = structure.nodes.len();
        let (mut translational, mut rotary) = (vec![0.0; nodes], vec![Matrix3::zeros(); nodes]);
        for e in &structure.elements {
            let h = e.thickness;
            let n: Vector3<f64> = e.axes.row(2).transpose();
            let in_plane = Matrix3::identity() - n * n.transpose();
            for (&node, area) in e.nodes.iter().zip(e.shape.nodal_areas()) {
                translational[node] += rho * h * area;
                rotary[node] += in_plane * (rho * h.powi(3) / 12.0 * area);
            }
        }
        Self { translational, rotary }
    }

    /// The DOFs `restraints` leave free, and how many of them carry mass: the second bounds
    /// the modes of finite frequency ([`Factorized::modes`] finds at most that many).
    pub fn free_dofs(&self, restraints: &Restraints) -> (usize, usize) {
        let dofs = DOFS_PER_NODE * self.translational.len();
        let mut held = vec![false; dofs];
        for &(node, dof) in &restraints.held {
            if let Some(h) = held.get_mut(DOFS_PER_NODE * node + dof) {
                *h = true;
            }
        }
        let free = held.iter().filter(|h| !**h).count();
        let massive = (0..dofs).filter(|&d| !held[d] && self.diagonal(d) > 0.0).count();
        (free, massive)
    }

    /// M's diagonal entry of DOF `d` (all DOFs numbered as the structure's).
    fn diagonal(&self, d: usize) -> f64 {
        let (n, i) = (d / DOFS_PER_NODE, d % DOFS_PER_NODE);
        if i < 3 {
            self.translational[n]
        } else {
            self.rotary[n][(i - 3, i - 3)]
        }
    }

    /// The total translational mass, kg.
    pub fn total(&self) -> f64 {
        self.translational.iter().sum()
    }

    /// M x over all DOFs.
    pub fn apply(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; x.len()];
        for (n, (&m, j)) in self.translational.iter().zip(&self.rotary).enumerate() {
            let base = DOFS_PER_NODE * n;
            for i in 0..3 {
                y[base + i] = m * x[base + i];
            }
            let r = j * Vector3::new(x[base + 3], x[base + 4], x[base + 5]);
            y[base + 3..base + 6].copy_from_slice(r.as_slice());
        }
        y
    }
}

/// The lowest modes of a restrained structure, M-orthonormal (φᵢᵀMφⱼ = δᵢⱼ) with the lumped
/// mass, zero on held DOFs.
#[derive(Debug, Clone)]
pub struct ShellModes {
    omega: Vec<f64>,
    /// All DOFs x modes.
    shapes: Mat<f64>,
    residuals: Vec<f64>,
    orthogonality: f64,
    basis: usize,
}

/// K and M on the unknowns.
struct Unknowns<'a> {
    stiffness: &'a SparseColMat<usize, f64>,
    factor: &'a Cholesky,
    mass: &'a ShellMass,
    /// Each DOF's unknown, usize::MAX where held.
    free: &'a [usize],
    held: Vec<bool>,
}

impl Pencil for Unknowns<'_> {
    fn held(&self) -> &[bool] {
        &self.held
    }
    fn mass(&self, x: &[f64]) -> Vec<f64> {
        let all: Vec<f64> = self.free.iter().map(|&s| if s == usize::MAX { 0.0 } else { x[s] }).collect();
        let mut y = vec![0.0; x.len()];
        for (&s, m) in self.free.iter().zip(self.mass.apply(&all)) {
            if s != usize::MAX {
                y[s] = m;
            }
        }
        y
    }
    fn stiffness(&self, x: &[f64]) -> Vec<f64> {
        symmetric_upper_apply(self.stiffness, x)
    }
    fn start(&self, r: Vec<f64>) -> Vec<f64> {
        let m = self.mass(&r);
        let mut x = Mat::from_fn(m.len(), 1, |i, _| m[i]);
        self.factor.solve_in_place(x.as_mut());
        x.col(0).iter().copied().collect()
    }
}

impl Factorized<'_> {
    /// The restrained stiffness's upper triangle on the unknowns.
    fn stiffness(&self) -> Result<SparseColMat<usize, f64>, FemError> {
        self.structure.restrained_stiffness(&self.restraints, &self.free, self.unknowns)
    }

    /// The structure's DOFs, held ones included.
    pub fn dofs(&self) -> usize {
        self.free.len()
    }

    /// K u over all DOFs (held DOFs' rows and columns taken out, their entries 0): the
    /// restrained stiffness as a product, for models built beside this one.
    ///
    /// # Panics
    ///
    /// If `u` is shorter than the structure has DOFs.
    pub fn stiffness_times(&self, u: &[f64]) -> Result<Vec<f64>, FemError> {
        let mut x = vec![0.0; self.unknowns];
        for (d, &slot) in self.free.iter().enumerate() {
            if slot != usize::MAX {
                x[slot] = u[d];
            }
        }
        let y = symmetric_upper_apply(&self.stiffness()?, &x);
        Ok(self.free.iter().map(|&slot| if slot == usize::MAX { 0.0 } else { y[slot] }).collect())
    }

    /// The lowest `count` modes with the mass `mass` of this structure ([`ShellMass::lumped`]):
    /// see the module. Refused when `mass` is another structure's or a free translation has
    /// no positive finite mass, when `count` is not in [1, unknowns], and when the structure
    /// has fewer modes of finite frequency than `count` ([`ShellMass::free_dofs`] bounds them).
    pub fn modes(&self, mass: &ShellMass, count: usize) -> Result<ShellModes, FemError> {
        let dofs = self.structure.dofs();
        if mass.translational.len() * DOFS_PER_NODE != dofs {
            return Err(FemError::Modes(format!(
                "a mass of {} nodes given for a structure of {} nodes",
                mass.translational.len(),
                dofs / DOFS_PER_NODE
            )));
        }
        if count == 0 || count > self.unknowns {
            return Err(FemError::Modes(format!(
                "{count} modes asked for; the restrained structure has {} unknowns, so the allowed range is [1, {}]",
                self.unknowns, self.unknowns
            )));
        }
        let (_, massive) = mass.free_dofs(&self.restraints);
        if count > massive {
            return Err(FemError::Modes(format!(
                "{count} modes asked for; the restrained structure has at most {massive} of finite frequency (its other {} unknowns carry no mass)",
                self.unknowns - massive
            )));
        }
        for (d, &slot) in self.free.iter().enumerate() {
            let m = mass.translational[d / DOFS_PER_NODE];
            if slot != usize::MAX && d % DOFS_PER_NODE < 3 && !(m.is_finite() && m > 0.0) {
                return Err(FemError::Modes(format!(
                    "node {} is free to move and has mass {m:e} kg: it must be positive",
                    d / DOFS_PER_NODE
                )));
            }
        }
        // K for the search's products, assembled again here rather than kept by every
        // factorization.
        let stiffness = self.stiffness()?;
        let pencil = Unknowns {
            stiffness: &stiffness,
            factor: &self.factor,
            mass,
            free: &self.free,
            held: vec![false; self.unknowns],
        };
        let (found, basis) = search(&pencil, |x| self.factor.solve_in_place(x.as_mut()), count)?;
        let Finished { omega, shapes, residuals, orthogonality } = found;
        let all =
            Mat::from_fn(dofs, count, |d, m| if self.free[d] == usize::MAX { 0.0 } else { shapes[(self.free[d], m)] });
        Ok(ShellModes { omega, shapes: all, residuals, orthogonality, basis })
    }
}

impl ShellModes {
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
    /// Mode shapes, all DOFs x modes.
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
    /// The Krylov basis the search ended with.
    pub fn basis(&self) -> usize {
        self.basis
    }

    /// φᵢᵀf for every mode: the modal force of the load `f` (all DOFs), which for a load of
    /// unit resultant is also each mode's work-conjugate displacement there.
    pub fn modal(&self, f: &[f64]) -> Vec<f64> {
        (0..self.count()).map(|m| self.shapes.col(m).iter().zip(f).map(|(a, b)| a * b).sum()).collect()
    }

    /// The residual flexibility between the loads `g` and `f` (all DOFs): gᵀK⁻¹f - Σ φᵢᵀg
    /// φᵢᵀf/ωᵢ², with K⁻¹f given as `static_field` (one solve on the same factorization).
    pub fn residual_between(&self, g: &[f64], f: &[f64], static_field: &[f64]) -> f64 {
        let full: f64 = g.iter().zip(static_field).map(|(a, b)| a * b).sum();
        self.residual_of(full, &self.modal(g), &self.modal(f))
    }

    /// The residual flexibility gᵀK⁻¹f - Σ φᵢᵀg φᵢᵀf/ωᵢ² from its parts: `full` = gᵀK⁻¹f and
    /// the modal projections `mg` = Φᵀg, `mf` = Φᵀf.
    pub fn residual_of(&self, full: f64, mg: &[f64], mf: &[f64]) -> f64 {
        full - mg.iter().zip(mf).zip(&self.omega).map(|((a, b), w)| a * b / (w * w)).sum::<f64>()
    }

    /// Φᵀf of a load given by its nonzero entries (DOF, value) in increasing DOF order: the
    /// same sums as [`Self::modal`] (which adds the zeros too, exactly), at the cost of the
    /// entries rather than of every DOF.
    pub fn modal_sparse(&self, f: &[(usize, f64)]) -> Vec<f64> {
        (0..self.count()).map(|m| f.iter().map(|&(d, v)| self.shapes[(d, m)] * v).sum()).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Restraints, Structure};
    use nalgebra::DMatrix;

    /// A small welded angle (two walls of 4 x 3 elements at a right angle, clamped at one end):
    /// the Krylov modes are the dense generalized eigenpairs of the same K and lumped M to
    /// 1e-9 in frequency (both are exact pairs of one pencil to their residuals).
    #[test]
    fn krylov_modes_are_the_dense_modes_of_a_small_box() {
        let mut s = Structure::new(210e9, 0.3).unwrap();
        let (l, w, t) = (0.4, 0.3, 0.01);
        for e in 0..4 {
            for k in 0..3 {
                let (x0, x1) = (l * e as f64 / 4.0, l * (e + 1) as f64 / 4.0);
                let (z0, z1) = (w * k as f64 / 3.0, w * (k + 1) as f64 / 3.0);
                s.add_quad([[x0, 0.0, z0], [x1, 0.0, z0], [x1, 0.0, z1], [x0, 0.0, z1]], t).unwrap();
                s.add_quad([[x0, z0, 0.0], [x1, z0, 0.0], [x1, z1, 0.0], [x0, z1, 0.0]], t).unwrap();
            }
        }
        let mut r = Restraints::default();
        for n in s.nodes_where(|p| p[0] == 0.0) {
            r.hold(n, &[0, 1, 2, 3, 4, 5]);
        }
        let fact = s.factorize(&r).unwrap();
        let mass = super::ShellMass::lumped(&s, 7850.0);
        let modes = fact.modes(&mass, 12).unwrap();
        let n = fact.unknowns;
        let stiffness = fact.stiffness().unwrap();
        let pencil = super::Unknowns {
            stiffness: &stiffness,
            factor: &fact.factor,
            mass: &mass,
            free: &fact.free,
            held: vec![false; n],
        };
        let column = |f: &dyn Fn(&[f64]) -> Vec<f64>| {
            let mut a = DMatrix::<f64>::zeros(n, n);
            for j in 0..n {
                let mut e = vec![0.0; n];
                e[j] = 1.0;
                a.set_column(j, &nalgebra::DVector::from_vec(f(&e)));
            }
            a
        };
        let k = column(&|x| super::Pencil::stiffness(&pencil, x));
        let m = column(&|x| super::Pencil::mass(&pencil, x));
        // The drilling rotations are massless, so M is singular: the eigenvalues μ = 1/ω² of
        // L⁻¹ M L⁻ᵀ (K = LLᵀ), the largest first.
        let l = nalgebra::Cholesky::new(k).unwrap().l();
        let li = l.try_inverse().unwrap();
        let a = &li * m * li.transpose();
        let mut mu: Vec<f64> = (0.5 * (&a + a.transpose())).symmetric_eigen().eigenvalues.iter().copied().collect();
        mu.sort_by(|a, b| b.total_cmp(a));
        for (a, m) in modes.omegas().iter().zip(&mu) {
            let b = 1.0 / m.sqrt();
            assert!((a / b - 1.0).abs() < 1e-9, "{a} {b}");
        }
        assert!(modes.orthogonality() < 1e-10);
        assert!(modes.residuals().iter().all(|&r| r < crate::modes::RESIDUAL_TOLERANCE));
        assert!(fact.modes(&mass, 0).is_err() && fact.modes(&mass, n + 1).is_err());
        // At most as many modes as DOFs with mass: asking for all of them ends either with
        // them or with an error, never a hang; asking for more is refused.
        let (free, massive) = mass.free_dofs(&r);
        assert_eq!(free, n);
        assert!(massive < n);
        // The highest of them are beyond the shift-invert search's reach: an error, not a hang.
        if let Ok(all) = fact.modes(&mass, massive) {
            assert_eq!(all.count(), massive);
        }
        let more = fact.modes(&mass, massive + 1).unwrap_err().to_string();
        assert!(more.contains("finite frequency"), "{more}");
    }
}
