use plate_fem::classical::*;
fn main() {
    let (l, h, e, nu) = (1.0f64, 0.01f64, 1e9f64, 0.3f64);
    let d = e * h.powi(3) / (12.0 * (1.0 - nu * nu));
    for bl in [4.0, 2.0, 1.0, 0.5, 0.2, 0.1, 0.05, 0.02] {
        let b = bl * l;
        let c_beam = l.powi(3) / (48.0 * e * b * h.powi(3) / 12.0);
        let w_c = levy_converged(LevyPlate { a: l, b, d, nu, y_edges: YEdge::Free }, (0.5, 0.0), (0.5, 0.0), 1e-10);
        let w_q = levy_converged(LevyPlate { a: l, b, d, nu, y_edges: YEdge::Free }, (0.25, 0.0), (0.25, 0.0), 1e-10);
        let c_beam_q = (0.25f64 * 0.75).powi(2) / (3.0 * e * b * h.powi(3) / 12.0 * l);
        // load at the free edge
        let w_e =
            levy_converged(LevyPlate { a: l, b, d, nu, y_edges: YEdge::Free }, (0.5, b / 2.0), (0.5, b / 2.0), 1e-10);
        println!(
            "B/L {bl}: centre ratio {:.6} quarter ratio {:.6} edge ratio {:.6}  (ratio-1)/(B/L)^2 {:.4}",
            w_c / c_beam,
            w_q / c_beam_q,
            w_e / c_beam,
            (w_c / c_beam - 1.0) / (bl * bl)
        );
    }
}
