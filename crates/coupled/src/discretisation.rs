//! The plate in `plate_fem` terms, and the meshes every plate result is computed on.
//!
//! One conversion from the paper's plate ([`analytic::Plate`]) to the finite-element
//! properties, and one rule for meshes: near-square elements, even counts (so the centre
//! lines are node lines), and ladders that halve h exactly (so Richardson extrapolation of
//! the point compliance, which converges at O(h²), applies).

use analytic::Plate;
use plate_fem::{FemError, Mesh, PlateProperties};

/// The plate's properties for `plate_fem`.
pub fn plate_properties(plate: &Plate) -> PlateProperties {
    PlateProperties {
        length: plate.length(),
        width: plate.width(),
        thickness: plate.thickness(),
        youngs_modulus: plate.material().youngs_modulus(),
        poisson_ratio: plate.material().poisson_ratio(),
        density: plate.density(),
    }
}

/// A uniform mesh with `n` elements along the longer side and near-square elements; both
/// counts are even, so the centre lines are node lines and halving h keeps every node.
pub fn mesh_for(props: &PlateProperties, n: usize) -> Result<Mesh, FemError> {
    let (nx, nz) = divisions(props.length, props.width, n);
    Mesh::uniform(props.length, props.width, nx, nz)
}

/// The element counts (along the length, across the width) of [`mesh_for`] on a plate of
/// sides `l` x `b` (any one unit) with `n` elements along the longer side.
pub fn divisions(l: f64, b: f64, n: usize) -> (usize, usize) {
    let even = |v: f64| (2.0 * (v / 2.0).round()).max(2.0) as usize;
    if l >= b {
        (even(n as f64), even(n as f64 * b / l))
    } else {
        (even(n as f64 * l / b), even(n as f64))
    }
}

/// Meshes `base`, 2·`base`, 4·`base`, ... (`levels` of them): each halves h exactly.
pub fn ladder_meshes(props: &PlateProperties, base: usize, levels: u32) -> Result<Vec<Mesh>, FemError> {
    let coarse = mesh_for(props, base)?;
    (0..levels).map(|k| Mesh::uniform(props.length, props.width, coarse.nx() << k, coarse.nz() << k)).collect()
}
