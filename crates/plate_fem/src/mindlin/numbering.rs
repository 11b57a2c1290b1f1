//! The supports as a linear map from the unknowns x to the plate's DOFs, u = T x.
//!
//! A held DOF has no unknown (its row of T is zero) and a free DOF has its own. A corner
//! support acts on its pad through the pad's mean deflection w̄ = Σ gᵢ wᵢ, with gᵢ the
//! consistent nodal weights of a unit pressure over the pad (Σ gᵢ = 1): the reaction is a
//! uniform pressure over the pad, and the plate may rotate on it as on a pin. The constraint
//! w̄ = w_s (w_s = 0 for a fixed corner, the spring's own unknown for a spring) is met by
//! making the corner node's w dependent:
//!
//! ```text
//! w₀ = (w_s - Σ_{i ≠ 0} gᵢ wᵢ) / g₀
//! ```
//!
//! The stiffness is then Tᵀ K T, the load Tᵀ f, and the displacement T x.

use super::element::DOFS_PER_NODE;
use super::Plate;
use crate::supports::{Corner, CornerSupport};
use crate::{FemError, Patch, Supports};

/// T in rows: each DOF's terms (unknown, coefficient).
#[derive(Debug, Clone)]
pub(crate) struct Numbering {
    start: Vec<usize>,
    terms: Vec<(usize, f64)>,
    /// Number of unknowns.
    pub(crate) unknowns: usize,
    /// Each corner's spring unknown and stiffness, where the corner is a spring.
    pub(crate) springs: [Option<(usize, f64)>; 4],
    /// Each supported corner's pad: its w DOFs (empty where the corner is free or an edge
    /// holds its node).
    pub(crate) pads: [Vec<usize>; 4],
}

impl Numbering {
    /// DOF `dof`'s terms.
    pub(crate) fn terms(&self, dof: usize) -> &[(usize, f64)] {
        &self.terms[self.start[dof]..self.start[dof + 1]]
    }

    /// T for `supports` on `plate`, whose edges hold the DOFs marked in `held`.
    pub(crate) fn new(plate: &Plate, supports: &Supports, held: &[bool]) -> Result<Self, FemError> {
        let dofs = held.len();
        // The pads of the supported corners whose node no edge holds: (corner, weights).
        let mut pads = Vec::new();
        for (c, s) in Corner::ALL.iter().zip(&supports.corners) {
            let corner_w = DOFS_PER_NODE * plate.corner_node(*c);
            if *s == CornerSupport::Free || held[corner_w] {
                continue;
            }
            pads.push((*c, *s, corner_w, pad_weights(plate, *c)?));
        }
        // Pads that share a node would share a constraint row: refused, before any assembly.
        let mut owner: Vec<Option<Corner>> = vec![None; dofs];
        for (c, _, _, weights) in &pads {
            for &(d, _) in weights {
                if let Some(other) = owner[d] {
                    return Err(FemError::Support(format!(
                        "the corner pads of side {:?} m at {} and {} share nodes on this mesh; use a smaller pad",
                        plate.pad(),
                        other.name(),
                        c.name()
                    )));
                }
                owner[d] = Some(*c);
            }
        }
        let mut dependent = vec![false; dofs];
        pads.iter().for_each(|p| dependent[p.2] = true);
        let mut index = vec![usize::MAX; dofs];
        let mut unknowns = 0;
        for dof in 0..dofs {
            if !held[dof] && !dependent[dof] {
                index[dof] = unknowns;
                unknowns += 1;
            }
        }
        let mut springs = [None; 4];
        let mut pad_dofs: [Vec<usize>; 4] = Default::default();
        let mut expressions: Vec<(usize, Vec<(usize, f64)>)> = Vec::new();
        for (c, s, corner_w, weights) in pads {
            pad_dofs[c.index()] = weights.iter().map(|w| w.0).collect();
            let g0 = weights.iter().find(|(d, _)| *d == corner_w).map_or(0.0, |w| w.1);
            if g0 <= 0.0 {
                return Err(FemError::Support(format!("the pad of {} carries no weight at its corner node", c.name())));
            }
            let mut terms: Vec<(usize, f64)> = weights
                .iter()
                .filter(|(d, _)| *d != corner_w && index[*d] != usize::MAX)
                .map(|&(d, g)| (index[d], -g / g0))
                .collect();
            if let CornerSupport::Spring(k) = s {
                springs[c.index()] = Some((unknowns, k));
                terms.push((unknowns, 1.0 / g0));
                unknowns += 1;
            }
            expressions.push((corner_w, terms));
        }
        let mut start = Vec::with_capacity(dofs + 1);
        let mut terms = Vec::with_capacity(dofs + 64);
        for (dof, &unknown) in index.iter().enumerate() {
            start.push(terms.len());
            if let Some((_, e)) = expressions.iter().find(|(d, _)| *d == dof) {
                terms.extend_from_slice(e);
            } else if unknown != usize::MAX {
                terms.push((unknown, 1.0));
            }
        }
        start.push(terms.len());
        Ok(Self { start, terms, unknowns, springs, pads: pad_dofs })
    }
}

/// The consistent w weights (DOF, gᵢ) of a unit pressure over corner `c`'s pad, Σ gᵢ = 1.
/// Without a pad, the corner node alone.
fn pad_weights(plate: &Plate, c: Corner) -> Result<Vec<(usize, f64)>, FemError> {
    let corner_w = DOFS_PER_NODE * plate.corner_node(c);
    let Some(side) = plate.pad() else { return Ok(vec![(corner_w, 1.0)]) };
    let mesh = plate.mesh();
    let (l, b) = (mesh.length(), mesh.width());
    let (cx, cz) = c.position(l, b);
    let inward = |at: f64, end: f64| if at == 0.0 { side / 2.0 } else { end - side / 2.0 };
    let pad = Patch { x: inward(cx, l), z: inward(cz, b), side_x: side, side_z: side };
    let mut weights: Vec<(usize, f64)> = Vec::new();
    for part in pad.parts(mesh)? {
        let fe = super::element::pressure_load(part.size.0, part.size.1, part.local, pad.pressure());
        for (k, dof) in plate.element_dofs(part.ex, part.ez).into_iter().enumerate().filter(|(k, _)| k % 3 == 0) {
            match weights.iter_mut().find(|(d, _)| *d == dof) {
                Some(w) => w.1 += fe[k],
                None => weights.push((dof, fe[k])),
            }
        }
    }
    Ok(weights)
}
