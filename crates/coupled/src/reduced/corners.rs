//! The plate's corners in the reduced model. A spring or free corner moves with the modes:
//! its deflection is φᵢ(c) on the modes plus R e_c of the truncated ones. A fixed corner
//! reacts, R_c = N_c(p)P - k_cᵀw - m_cᵀẅ with k_c and m_c its rows of the unsupported K and
//! M, on the modes and as residual fields.

use plate_fem::{element, Corner, CornerSupport, Factorization, Mesh, Model, Modes, Supports};

/// One corner's data: its support, its modal rows and its residual fields.
#[derive(Debug, Clone)]
pub(super) struct CornerData {
    pub(super) corner: Corner,
    pub(super) support: CornerSupport,
    /// The corner's w DOF.
    pub(super) dof: usize,
    /// Spring or free corner: φᵢ(c); fixed corner: (Kφᵢ)_c, its stiffness row on the mode.
    pub(super) row: Vec<f64>,
    /// Fixed corner: (Mφᵢ)_c, its mass row on the mode.
    pub(super) mass_row: Option<Vec<f64>>,
    /// Spring or free corner: R e_c; fixed corner: R k_c (k_c its stiffness row).
    pub(super) field: Vec<f64>,
    /// Fixed corner: R m_c (m_c its mass row).
    pub(super) mass_field: Option<Vec<f64>>,
}

/// Every corner a channel can follow, in [`Corner::ALL`] order: the fixed ones and those
/// that can move (a corner held by an edge has no channel and no deflection). `phi` is φ by
/// DOF, `phi[d * N + i]` mode i at DOF d.
pub(super) fn corner_data(
    model: &Model,
    fact: &Factorization<'_>,
    modes: &Modes,
    supports: &Supports,
    phi: &[f64],
) -> Vec<CornerData> {
    let mesh = model.mesh();
    let mut corners = Vec::new();
    for c in Corner::ALL {
        let support = supports.corners[c.index()];
        let dof = mesh.corner_w_dof(c.index());
        if fact.held().contains(&dof) && support != CornerSupport::Fixed {
            // Held by an edge: no channel, no deflection.
            continue;
        }
        corners.push(match support {
            CornerSupport::Fixed => fixed_corner(model, (fact, supports), modes, phi, c),
            CornerSupport::Spring(_) | CornerSupport::Free => {
                let n = modes.count();
                let mut e = vec![0.0; model.dofs()];
                e[dof] = 1.0;
                CornerData {
                    corner: c,
                    support,
                    dof,
                    row: phi[dof * n..(dof + 1) * n].to_vec(),
                    mass_row: None,
                    field: modes.residual_field(fact, &e),
                    mass_field: None,
                }
            }
        });
    }
    corners
}

/// A fixed corner: its stiffness and mass rows k_c, m_c of K and M before the corner is held
/// (the held DOF's own entry left out; K with the elastic edges of `supports`, which share
/// the load with the corner), on the modes and as residual fields R k_c, R m_c.
fn fixed_corner(
    model: &Model,
    (fact, supports): (&Factorization<'_>, &Supports),
    modes: &Modes,
    phi: &[f64],
    c: Corner,
) -> CornerData {
    let (mesh, props) = (model.mesh(), model.props());
    let (n, ndof) = (modes.count(), model.dofs());
    let dof = mesh.corner_w_dof(c.index());
    // The held DOF's rows of the unsupported K and M: the corner node belongs to one
    // element, whose matrices give them.
    let (ex, ez, local) = corner_element(mesh, c);
    let (a, b) = mesh.element_size(ex, ez);
    let ke = model.element_stiffness(ex, ez, supports);
    let me = element::mass(a, b, props.density * props.thickness);
    let dofs = mesh.element_dofs(ex, ez);
    let (mut kc, mut mc) = (vec![0.0; ndof], vec![0.0; ndof]);
    for k in 0..16 {
        if dofs[k] != dof {
            kc[dofs[k]] += ke[(local, k)];
            mc[dofs[k]] += me[(local, k)];
        }
    }
    let on_modes =
        |r: &[f64]| -> Vec<f64> { (0..n).map(|i| (0..16).map(|k| r[dofs[k]] * phi[dofs[k] * n + i]).sum()).collect() };
    CornerData {
        corner: c,
        support: CornerSupport::Fixed,
        dof,
        row: on_modes(&kc),
        mass_row: Some(on_modes(&mc)),
        field: modes.residual_field(fact, &kc),
        mass_field: Some(modes.residual_field(fact, &mc)),
    }
}

/// The element holding a corner node and the corner's local w DOF in it.
fn corner_element(mesh: &Mesh, c: Corner) -> (usize, usize, usize) {
    match c {
        Corner::LeftNear => (0, 0, 0),
        Corner::RightNear => (mesh.nx() - 1, 0, 4),
        Corner::LeftFar => (0, mesh.nz() - 1, 8),
        Corner::RightFar => (mesh.nx() - 1, mesh.nz() - 1, 12),
    }
}
