//! The residual flexibility of the modes a [`Modes`] leaves out, element by element.

use super::Modes;
use crate::element::{self, Vec16};
use crate::mesh::Mesh;
use crate::model::{symmetric_upper_apply, Factorization};
use crate::FemError;
use faer::Mat;

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
    /// Per element, RMR's block, where it was asked for ([`Self::with_inertia`]).
    mass_blocks: Option<Vec<[f64; 256]>>,
}

impl ResidualFlexibility {
    /// R's element blocks: K⁻¹'s from the selected inverse of the factor, less the modes'
    /// parts. The cost is a small multiple of the factorization, with no solve.
    pub fn new(fact: &Factorization<'_>, modes: &Modes) -> Result<Self, FemError> {
        check_same_plate(fact, modes)?;
        let inverse = fact.selected_inverse()?;
        // R = K⁻¹ - Σφφᵀ/ω² cancels most of K⁻¹, so its blocks carry K⁻¹'s error magnified:
        // a support set conditioned badly enough to spoil them is named here.
        let (l, b) = (fact.model().props().length, fact.model().props().width);
        fact.check_selected_inverse(&inverse, (0.5 * l, 0.5 * b), 0.0)?;
        let mesh = fact.model().mesh().clone();
        let mut blocks = Vec::with_capacity(mesh.elements());
        for ez in 0..mesh.nz() {
            for ex in 0..mesh.nx() {
                let dofs = mesh.element_dofs(ex, ez);
                let mut b = inverse.block(&dofs).ok_or_else(|| {
                    FemError::Modes("selected inversion: an element's DOF pair is outside the factor's pattern; this is a defect of this crate".into())
                })?;
                subtract_modes(&mut b, &dofs, modes, 2);
                blocks.push(b);
            }
        }
        Ok(Self { mesh, blocks, mass_blocks: None })
    }

    /// R's blocks and RMR's, the residual shape's mass. K⁻¹MK⁻¹ is not on any factor's
    /// pattern: its element blocks come from solves with unit loads on every free DOF (in
    /// blocks of 64 columns), K⁻¹ then K⁻¹M of each.
    pub fn with_inertia(fact: &Factorization<'_>, modes: &Modes) -> Result<Self, FemError> {
        let mut this = Self::new(fact, modes)?;
        let mut mass_blocks = inverse_mass_inverse_blocks(fact)?;
        let mesh = &this.mesh;
        for ez in 0..mesh.nz() {
            for ex in 0..mesh.nx() {
                let dofs = mesh.element_dofs(ex, ez);
                let b = &mut mass_blocks[ez * mesh.nx() + ex];
                subtract_modes(b, &dofs, modes, 4);
                symmetrize(b);
            }
        }
        this.mass_blocks = Some(mass_blocks);
        Ok(this)
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
        element::quadratic(&self.blocks[e], n)
    }

    /// Nᵀ (RMR) N on element `e` for shape values `n`: the mass m_ψ of the residual shape
    /// ψ = RN, kg·(m/N)²; `None` unless built [`with_inertia`](Self::with_inertia).
    pub fn mass_quadratic(&self, e: usize, n: &Vec16) -> Option<f64> {
        self.mass_blocks.as_ref().map(|m| element::quadratic(&m[e], n))
    }

    /// The mesh.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }
}

fn check_same_plate(fact: &Factorization<'_>, modes: &Modes) -> Result<(), FemError> {
    if modes.mesh != *fact.model().mesh() || modes.supports != *fact.supports() {
        return Err(FemError::Modes("the modes belong to another mesh or support set than the factorization".into()));
    }
    Ok(())
}

/// b -= Σᵢ φᵢφᵢᵀ/ωᵢ^power on the element's DOFs: the kept modes' part of K⁻¹ (power 2) or of
/// K⁻¹MK⁻¹ (power 4).
fn subtract_modes(b: &mut [f64; 256], dofs: &[usize; 16], modes: &Modes, power: i32) {
    let shapes = modes.shapes();
    for k in 0..16 {
        for l in 0..16 {
            let modal: f64 = (0..modes.count())
                .map(|m| shapes[(dofs[k], m)] * shapes[(dofs[l], m)] / modes.omega[m].powi(power))
                .sum();
            b[k * 16 + l] -= modal;
        }
    }
}

fn symmetrize(b: &mut [f64; 256]) {
    for k in 0..16 {
        for l in 0..k {
            let s = 0.5 * (b[k * 16 + l] + b[l * 16 + k]);
            b[k * 16 + l] = s;
            b[l * 16 + k] = s;
        }
    }
}

/// The element blocks of K⁻¹MK⁻¹, by solves: column d of K⁻¹ for every free DOF d, then
/// K⁻¹M of it, harvested onto the elements around d.
fn inverse_mass_inverse_blocks(fact: &Factorization<'_>) -> Result<Vec<[f64; 256]>, FemError> {
    const CHUNK: usize = 64;
    let model = fact.model();
    let mesh = model.mesh();
    let mass = model.supported_mass(fact.supports())?;
    let n = model.dofs();
    let (nx, nz) = (mesh.nx(), mesh.nz());
    let mut blocks = vec![[0.0f64; 256]; mesh.elements()];
    let held: std::collections::HashSet<usize> = fact.held().iter().copied().collect();
    let cols: Vec<usize> = (0..n).filter(|d| !held.contains(d)).collect();
    let nodes_x = nx + 1;
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
            let (node, q) = (d / 4, d % 4);
            let (i, jn) = (node % nodes_x, node / nodes_x);
            for ez in jn.saturating_sub(1)..=jn.min(nz - 1) {
                for ex in i.saturating_sub(1)..=i.min(nx - 1) {
                    // The node's place among the element's four, so the column within its block.
                    let local_node = (jn - ez) * 2 + (i - ex);
                    let l = 4 * local_node + q;
                    let dofs = mesh.element_dofs(ex, ez);
                    let b = &mut blocks[ez * nx + ex];
                    for k in 0..16 {
                        b[k * 16 + l] = y[(dofs[k], j)];
                    }
                }
            }
        }
    }
    Ok(blocks)
}
