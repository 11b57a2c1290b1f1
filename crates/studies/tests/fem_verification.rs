//! The plate FE verification's classical checks against Navier's double series, summed here
//! independently of `plate_fem::classical` (whose Lévy series the study uses as its exact
//! value).

mod common;

use common::{navier, rigidity};
use studies::fem_verification::classical::{navier_square, off_centre, OFF_CENTRE, OFF_CENTRE_POINT};
use studies::fem_verification::Convergence;

/// Navier's series summed to `terms` and to 2·`terms` in each direction, Richardson-extrapolated:
/// the truncated tail falls as 1/N², so the extrapolation leaves O(1/N⁴), far below the
/// tolerances below.
fn navier_converged(a: f64, b: f64, d: f64, p: (f64, f64)) -> f64 {
    let (w1, w2) = (navier(a, b, d, p, 600), navier(a, b, d, p, 1200));
    (4.0 * w2 - w1) / 3.0
}

/// Every row of a ladder against the independent series `exact`: the BFS element is conforming,
/// so each mesh is stiffer than the plate (C_FE < C); each row's relative error is the one the
/// study reports; the error falls by about four per halving of h (O(h²), the r² ln r
/// singularity of the point load); and the Richardson value of the two finest meshes meets the
/// series far closer than the finest mesh does.
fn check_ladder(c: &Convergence, exact: f64, richardson_tolerance: f64) {
    // The study's own series value (Lévy's) against Navier's, summed independently: both
    // converge to the same plate, to 1e-8 by the tail estimate of each.
    assert!((c.exact / exact - 1.0).abs() < 1e-8, "series {} vs Navier {exact}", c.exact);
    for r in &c.rows {
        assert!(r.compliance < exact, "{} x {}: {} not below {exact}", r.nx, r.nz, r.compliance);
        let e = (r.compliance - exact).abs() / exact;
        // The two series agree to 1e-8, so the errors against them do, absolutely.
        assert!((r.rel_error - e).abs() <= 1e-8, "{} x {}: {} vs {e}", r.nx, r.nz, r.rel_error);
    }
    for w in c.rows.windows(2) {
        let ratio = w[0].rel_error / w[1].rel_error;
        // Rate 2 within ±0.3 between successive meshes: 2^1.7 to 2^2.3.
        assert!(
            (3.2..=5.0).contains(&ratio),
            "{} x {} -> {} x {}: error ratio {ratio}",
            w[0].nx,
            w[0].nz,
            w[1].nx,
            w[1].nz
        );
    }
    let last = c.rows.last().expect("a ladder");
    let richardson = last.richardson.expect("two meshes or more");
    assert!(
        (richardson / exact - 1.0).abs() < richardson_tolerance,
        "Richardson {richardson} vs Navier {exact} (finest mesh's own error {})",
        last.rel_error
    );
    let rate = c.finest_rate.expect("two meshes or more");
    assert!((rate - 2.0).abs() < 0.3, "finest rate {rate}");
}

/// The simply supported square (1 m, 10 mm steel) under a centre load, 4 x 4 to 128 x 128:
/// the centre coefficient w D/(P a²) is Navier's 0.0116 (Timoshenko & Woinowsky-Krieger,
/// Table 23, prints 0.01160), and the FE ladder converges to it. The Richardson value of the
/// finest pair is within 1e-7: the finest mesh's error is ~1e-5 (h = 1/128) and the
/// extrapolation removes its h² part, leaving remainders of order h⁴ (~1e-9 here), above the
/// two series' 1e-8 agreement by an order.
#[test]
fn navier_square_meets_the_double_series() {
    let (c, coefficient, whole_ladder) = navier_square().unwrap();
    let d = rigidity(210e9, 0.3, 0.01);
    let exact = navier_converged(1.0, 1.0, d, (0.5, 0.5));
    assert!((coefficient / (exact * d) - 1.0).abs() < 1e-8, "{coefficient} vs {}", exact * d);
    assert!((coefficient - 0.01160).abs() < 5e-6, "{coefficient}: Table 23 prints 0.01160");
    assert_eq!(c.rows.len(), 6);
    check_ladder(&c, exact, 1e-7);
    assert!(whole_ladder < 1e-7, "the whole ladder's Richardson error {whole_ladder}");
}

/// The 1 x 0.7 m rectangle loaded off-centre at (0.3, 0.2) m, 10 x 7 to 80 x 56: the same
/// checks against the series at that point; the finest mesh (h = L/80) leaves ~7e-5, the
/// Richardson value of the finest pair within 1e-7 (as for the square).
#[test]
fn off_centre_plate_meets_the_double_series() {
    let c = off_centre().unwrap();
    let (a, b) = OFF_CENTRE;
    let exact = navier_converged(a, b, rigidity(210e9, 0.3, 0.01), OFF_CENTRE_POINT);
    assert_eq!(c.rows.len(), 4);
    check_ladder(&c, exact, 1e-7);
}
