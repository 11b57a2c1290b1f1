//! The Rust plate elements against scikit-fem, from the committed data in
//! reference/data/*.json (written by reference/python/plate_reference.py; no Python needed).
//!
//! Tolerance: each code's value is Richardson-extrapolated from its two finest meshes, with
//! an error estimate (|finest - extrapolated| in the asymptotic range, |finest - previous|
//! otherwise). Two estimates of the same exact value must differ by no more than the sum of
//! their error estimates; we allow twice that sum, plus 1e-9 relative for the floating-point
//! noise of the solves. Where both ladders are asymptotic the two must also agree to 1e-4
//! relative, the agreement the FE verification report states.

use impact::report::skfem::{extrapolate, load, rust_runs, CASES};
use plate_fem::classical::{LevyPlate, YEdge};

fn check_case(case: &str) {
    let v = load(case).unwrap();
    let argyris = extrapolate(&v.argyris);
    let bfs = rust_runs(&v, 4).unwrap();
    let ours = extrapolate(&bfs);
    let finest_bfs = &bfs.last().unwrap().compliance;
    let morley_finest = &v.morley.last().unwrap().compliance;
    for (i, (a, r)) in argyris.iter().zip(&ours).enumerate() {
        let (ax, rx) = (a.extrapolated, r.extrapolated);
        if ax.abs() < 1e-20 {
            // A point on a supported edge: C = 0 in both codes up to rounding.
            assert!(rx.abs() < 1e-20, "{case} point {i}: {rx:e} on a supported edge");
            continue;
        }
        let tol = 2.0 * (a.error_estimate + r.error_estimate) + 1e-9 * ax.abs();
        assert!(
            (ax - rx).abs() <= tol,
            "{case} point {i}: Argyris {ax:e} ± {:e}, BFS {rx:e} ± {:e}",
            a.error_estimate,
            r.error_estimate
        );
        // The 1e-4 aim holds where both ladders are in their asymptotic range; near a
        // corner (point 4) they are not, and the estimates above govern.
        if a.asymptotic && r.asymptotic {
            let rel = (ax - rx).abs() / ax.abs();
            assert!(rel < 1e-4, "{case} point {i}: {rel:e} relative");
        }
        // Bracketing: the conforming BFS approaches from below, the nonconforming Morley
        // from above, so the finest of each encloses the extrapolated value.
        assert!(finest_bfs[i] <= rx * (1.0 + 1e-9), "{case} point {i}: BFS from below");
        assert!(
            morley_finest[i] >= rx * (1.0 - 1e-9),
            "{case} point {i}: Morley from above: {} vs {rx}",
            morley_finest[i]
        );
    }
}

#[test]
fn paper_con1_against_argyris() {
    check_case("paper-con1");
}

#[test]
fn paper_con2_against_argyris() {
    check_case("paper-con2");
}

#[test]
fn paper_con3_against_argyris() {
    check_case("paper-con3");
}

#[test]
fn simply_supported_against_argyris() {
    check_case("paper-simple-all");
}

#[test]
fn simple_free_against_argyris() {
    check_case("paper-simple-free");
}

/// The Python setup itself against Navier: the simply supported paper plate at its centre.
#[test]
fn argyris_data_meets_navier() {
    let v = load("paper-simple-all").unwrap();
    let p = v.props;
    let e = &extrapolate(&v.argyris)[0];
    let (a, ea) = (e.extrapolated, e.error_estimate);
    let series = LevyPlate { a: p.length, b: p.width, d: p.rigidity(), nu: p.poisson_ratio, y_edges: YEdge::Simple }
        .converged((p.length / 2.0, 0.0), (p.length / 2.0, 0.0), 1e-12);
    assert!((a - series).abs() <= 2.0 * ea + 1e-9 * series, "Argyris {a:e} ± {ea:e} vs Navier {series:e}");
}

/// The data records what produced it.
#[test]
fn data_carries_provenance() {
    for case in CASES {
        let v = load(case).unwrap();
        for key in ["scikit-fem", "meshio", "numpy", "scipy", "python"] {
            assert!(v.versions.iter().any(|(k, v)| k == key && !v.is_empty()), "{case}: version of {key}");
        }
        for r in v.argyris.iter().chain(&v.morley) {
            assert!(r.dofs > 0 && r.seconds > 0.0 && r.nx > 0 && r.nz > 0);
            assert_eq!(r.compliance.len(), v.points.len());
        }
    }
}
