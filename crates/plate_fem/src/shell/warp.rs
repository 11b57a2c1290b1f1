//! The warping correction of a flat element on warped corners (MacNeal, *A simple
//! quadrilateral shell element*, Comput. Struct. 8, 1978, 175-183; MacNeal & Harder, Finite
//! Elem. Anal. Des. 1, 1985, 3-20, where the twisted beam shows the need): the element is formed
//! on the corners' projections onto its mean plane, and each projection is tied to its node by a
//! rigid link along the normal. A node at height h above the plane moves its projection by
//! u' = u + θ x (-h e₃), in the element's frame ū'_x = ū_x - h θ̄_y, ū'_y = ū_y + h θ̄_x; the
//! element's matrix on the nodes is OᵀKO with O that map, and its strains read O ū. Loads and
//! masses stay at the nodes: a pressure along the normal has no moment about the link, and the
//! links' effect on an in-plane traction or the rotary inertia is of the order of the warp.

use super::element::{Mat24, Vec24};

/// Corner heights below this fraction of the diagonal are rounding: the element is flat, and
/// no link is formed (its matrices are then the flat element's, bit for bit).
pub(super) const FLAT: f64 = 1e-9;

/// O for the corner heights `h` (element node order, m): the identity but for the links.
fn links(h: &[f64; 4]) -> Mat24 {
    let mut o = Mat24::identity();
    for (n, &hn) in h.iter().enumerate() {
        // Node n: translations at 6n..6n+3, rotations at 6n+3..6n+6 (local frame).
        o[(6 * n, 6 * n + 4)] = -hn;
        o[(6 * n + 1, 6 * n + 3)] = hn;
    }
    o
}

/// The element matrix `k` (local frame, at the projections) on the nodes: OᵀKO, or `k` itself
/// for a flat element.
pub(super) fn on_nodes(h: Option<&[f64; 4]>, k: Mat24) -> Mat24 {
    match h {
        Some(h) => {
            let o = links(h);
            o.transpose() * k * o
        }
        None => k,
    }
}

/// The local displacements at the projections from the nodes' `u` (local frame).
pub(super) fn at_projections(h: Option<&[f64; 4]>, u: Vec24) -> Vec24 {
    match h {
        Some(h) => links(h) * u,
        None => u,
    }
}

#[cfg(test)]
mod tests {
    use super::super::Structure;
    use super::on_nodes;
    use nalgebra::Vector3;

    /// A warped quadrilateral (corners 4 % of its diagonal off its mean plane) keeps exactly the
    /// six rigid-body motions of its nodes as zero-energy modes with the links; without them
    /// the rotations about its in-plane axes strain it.
    #[test]
    fn a_warped_element_moves_rigidly_without_energy() {
        let mut s = Structure::new(210e9, 0.3).unwrap();
        let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.05], [1.1, 0.9, -0.01], [-0.05, 1.0, 0.06]];
        s.add_quad(corners, 0.02).unwrap();
        let e = &s.elements[0];
        assert!(e.heights.is_some());
        let local = s.parts[e.parts].total();
        let (with, without) =
            (Structure::global(e, &on_nodes(e.heights.as_ref(), local)), Structure::global(e, &local));
        let scale = with.abs().max();
        let rigid = |a: Vector3<f64>, theta: Vector3<f64>| {
            let mut r = nalgebra::SVector::<f64, 24>::zeros();
            for (k, &n) in e.nodes.iter().enumerate() {
                let u = a + theta.cross(&s.nodes[n]);
                for i in 0..3 {
                    r[6 * k + i] = u[i];
                    r[6 * k + 3 + i] = theta[i];
                }
            }
            r
        };
        let mut worst_without: f64 = 0.0;
        for i in 0..3 {
            let unit = Vector3::from_fn(|j, _| if i == j { 1.0 } else { 0.0 });
            for r in [rigid(unit, Vector3::zeros()), rigid(Vector3::zeros(), unit)] {
                let residual = (with * r).abs().max() / (scale * r.abs().max());
                assert!(residual < 1e-12, "{residual:e}");
                worst_without = worst_without.max((without * r).abs().max() / (scale * r.abs().max()));
            }
        }
        assert!(worst_without > 1e-4, "{worst_without:e}");
    }
}
