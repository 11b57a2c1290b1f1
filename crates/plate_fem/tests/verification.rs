//! Verification of the plate elements against classical plate theory.
//!
//! Tolerances: the point compliance of the conforming BFS element converges at O(h²)
//! (measured: 2.000 on Navier's plate). Richardson extrapolation of meshes n and 2n then
//! removes the h² term; what remains is the next term, which on the meshes used here is
//! below 1e-6 relative (measured 1e-7 for n = 16, 32). Tests allow 1e-5 for extrapolated
//! values and state the expected raw error for the finest mesh.

use approx::assert_relative_eq;
use plate_fem::classical::{levy_converged, LevyPlate, YEdge};
use plate_fem::convergence::richardson;
use plate_fem::*;

fn plate(l: f64, b: f64) -> PlateProperties {
    PlateProperties { length: l, width: b, thickness: 0.01, youngs_modulus: 1e9, poisson_ratio: 0.3, density: 7850.0 }
}

/// FE compliance at (x, z) on meshes n x m and 2n x 2m, and their extrapolation.
fn fe_pair(p: PlateProperties, supports: Supports, n: usize, m: usize, x: f64, z: f64) -> (f64, f64, f64) {
    let c = |k: usize| {
        let model = Model::new(p, Mesh::uniform(p.length, p.width, n * k, m * k).unwrap()).unwrap();
        model.factorize(&supports).unwrap().respond(x, z).unwrap().compliance
    };
    let (c1, c2) = (c(1), c(2));
    (c1, c2, richardson(&[c1, c2]).unwrap().extrapolated)
}

/// Navier: square plate, four simply supported edges, centre load: w = 0.01160 P a²/D
/// (Timoshenko Table 23) and the series to convergence. The FE approaches from below
/// (conforming), at rate 2.
#[test]
fn navier_square_centre() {
    let p = plate(1.0, 1.0);
    let series = levy_converged(
        LevyPlate { a: 1.0, b: 1.0, d: p.rigidity(), nu: 0.3, y_edges: YEdge::Simple },
        (0.5, 0.0),
        (0.5, 0.0),
        1e-12,
    );
    assert_relative_eq!(series * p.rigidity(), 0.01160, max_relative = 1e-4);
    let (c16, c32, ext) = fe_pair(p, Supports::all_edges_simple(), 16, 16, 0.5, 0.5);
    let c8 = fe_pair(p, Supports::all_edges_simple(), 8, 8, 0.5, 0.5).0;
    assert!(c8 < c16 && c16 < c32 && c32 < series, "monotone from below");
    let rate = plate_fem::convergence::observed_rate(c8, c16, c32).unwrap();
    assert!((rate - 2.0).abs() < 0.02, "observed rate {rate}");
    // Raw error at n = 32 is 1.7e-4; extrapolated, 1e-7.
    assert_relative_eq!(c32, series, max_relative = 2e-4);
    assert_relative_eq!(ext, series, max_relative = 1e-6);
}

/// Navier off-centre: a 1 x 0.7 plate, load at (0.3, 0.2), compliance there and the
/// deflection at another point (0.6, 0.45).
#[test]
fn navier_rectangle_off_centre() {
    let p = plate(1.0, 0.7);
    let d = p.rigidity();
    let series = levy_converged(
        LevyPlate { a: 1.0, b: 0.7, d, nu: 0.3, y_edges: YEdge::Simple },
        (0.3, 0.2 - 0.35),
        (0.3, 0.2 - 0.35),
        1e-11,
    );
    // 10 x 7 and 20 x 14 elements put the load on a node line.
    let (_, _, ext) = fe_pair(p, Supports::all_edges_simple(), 10, 7, 0.3, 0.2);
    assert_relative_eq!(ext, series, max_relative = 1e-5);
    // Transfer deflection: smooth away from the load, so already accurate on one mesh.
    let model = Model::new(p, Mesh::uniform(1.0, 0.7, 40, 28).unwrap()).unwrap();
    let f = model.factorize(&Supports::all_edges_simple()).unwrap();
    let w = f.deflection_field(0.3, 0.2).unwrap();
    let fe = model.evaluate(&w, 0.6, 0.45).unwrap();
    let exact = levy_converged(
        LevyPlate { a: 1.0, b: 0.7, d, nu: 0.3, y_edges: YEdge::Simple },
        (0.3, 0.2 - 0.35),
        (0.6, 0.45 - 0.35),
        1e-11,
    );
    assert_relative_eq!(fe, exact, max_relative = 1e-4);
}

/// Lévy: x-edges simply supported, z-edges free, loads on the centreline and off it.
#[test]
fn levy_simple_free() {
    let p = plate(1.0, 0.6);
    let d = p.rigidity();
    for (x, z) in [(0.5, 0.3), (0.25, 0.3), (0.5, 0.15), (0.5, 0.6)] {
        let series = levy_converged(
            LevyPlate { a: 1.0, b: 0.6, d, nu: 0.3, y_edges: YEdge::Free },
            (x, z - 0.3),
            (x, z - 0.3),
            1e-11,
        );
        let (_, c2, ext) = fe_pair(p, Supports::simple_free(), 12, 8, x, z);
        assert!(c2 < series, "conforming: from below at ({x}, {z})");
        assert_relative_eq!(ext, series, max_relative = 1e-5);
    }
}

/// K is symmetric and the free plate has exactly three zero-energy modes (w = a + bx + cz).
#[test]
fn free_plate_has_three_rigid_modes() {
    use nalgebra::DMatrix;
    let p = plate(1.0, 0.5);
    let mesh = Mesh::uniform(1.0, 0.5, 3, 2).unwrap();
    let n = mesh.dofs();
    let mut k = DMatrix::<f64>::zeros(n, n);
    for ez in 0..mesh.nz() {
        for ex in 0..mesh.nx() {
            let (a, b) = mesh.element_size(ex, ez);
            let ke = element::stiffness(a, b, p.rigidity(), 0.3);
            let dofs = mesh.element_dofs(ex, ez);
            for i in 0..16 {
                for j in 0..16 {
                    k[(dofs[i], dofs[j])] += ke[(i, j)];
                }
            }
        }
    }
    assert!((&k - k.transpose()).abs().max() <= 1e-12 * k.abs().max());
    let mut ev: Vec<f64> = k.symmetric_eigenvalues().iter().copied().collect();
    ev.sort_by(f64::total_cmp);
    let top = ev[n - 1];
    assert!(ev[..3].iter().all(|v| v.abs() < 1e-10 * top), "{:?}", &ev[..4]);
    assert!(ev[3] > 1e-8 * top, "a fourth mode would be a mechanism: {}", ev[3] / top);
}

/// Maxwell-Betti reciprocity: the deflection at q under a load at p equals that at p
/// under a load at q, for corner springs and points off the nodes.
#[test]
fn reciprocity() {
    let p = plate(0.4584, 0.36);
    let model = Model::new(p, Mesh::uniform(0.4584, 0.36, 12, 9).unwrap()).unwrap();
    let f = model.factorize(&Supports::con3(1e6)).unwrap();
    let (a, b) = ((0.1234, 0.0567), (0.3456, 0.2987));
    let wa = f.deflection_field(a.0, a.1).unwrap();
    let wb = f.deflection_field(b.0, b.1).unwrap();
    let ab = model.evaluate(&wa, b.0, b.1).unwrap();
    let ba = model.evaluate(&wb, a.0, a.1).unwrap();
    assert_relative_eq!(ab, ba, max_relative = 1e-12);
}

/// The field and the response from one solve are those of the two separate paths (the same
/// right-hand side through the same factor, so equal to the last bit), and the field read at
/// the load point is the compliance C = Nᵀw (to round-off of the interpolation, 1e-12).
#[test]
fn one_solve_gives_the_field_and_the_response() {
    let p = plate(0.4584, 0.36);
    let model = Model::new(p, Mesh::uniform(0.4584, 0.36, 12, 9).unwrap()).unwrap();
    for sup in [Supports::con1(), Supports::con3(1e6)] {
        let f = model.factorize(&sup).unwrap();
        for (x, z) in [(0.2292, 0.18), (0.1234, 0.0567), (0.0, 0.18)] {
            let (r, w) = f.respond_with_field(x, z).unwrap();
            assert_eq!(w, f.deflection_field(x, z).unwrap());
            assert_eq!(r, f.respond(x, z).unwrap());
            assert_relative_eq!(model.evaluate(&w, x, z).unwrap(), r.compliance, max_relative = 1e-12);
        }
    }
}

/// Energy bookkeeping and statics: the stores sum to C, the reactions to the load.
#[test]
fn stores_and_reactions_balance() {
    let p = plate(0.4584, 0.36);
    let model = Model::new(p, Mesh::uniform(0.4584, 0.36, 10, 8).unwrap()).unwrap();
    for sup in [Supports::con1(), Supports::con2(5.11545e8), Supports::con3(5e4)] {
        let f = model.factorize(&sup).unwrap();
        for (x, z) in [(0.2292, 0.18), (0.05, 0.33), (0.4584, 0.0), (0.0, 0.18)] {
            let r = f.respond(x, z).unwrap();
            assert_relative_eq!(r.total_reaction(), 1.0, max_relative = 1e-10);
            let springs: f64 = r.corners.iter().map(|c| c.spring_compliance).sum();
            assert_relative_eq!(r.plate_compliance + springs, r.compliance, max_relative = 1e-14);
            assert!(r.plate_compliance >= -1e-12 * r.compliance);
            assert!(r.residual < 1e-12, "residual {}", r.residual);
        }
    }
}

/// k_T → ∞ reproduces fixed corners: the spring part falls like 1/k_T.
#[test]
fn stiff_springs_reach_fixed_corners() {
    let p = plate(0.4584, 0.36);
    let model = Model::new(p, Mesh::uniform(0.4584, 0.36, 10, 8).unwrap()).unwrap();
    let fixed = model.factorize(&Supports::con1()).unwrap().respond(0.1, 0.1).unwrap().compliance;
    for k in [1e10, 1e12, 1e14] {
        let c = model.factorize(&Supports::con2(k)).unwrap().respond(0.1, 0.1).unwrap().compliance;
        // Four springs in parallel-ish: the extra compliance is at most 1/k.
        assert!(c >= fixed && c - fixed <= 1.0 / k, "k = {k}: {c} vs {fixed}");
    }
}

/// The rank-4 corner update agrees with a fresh factorization to 1e-10 relative at
/// interior and edge points, for k_T from 5e4 to 1e12 N/m and fixed corners; at a point on
/// a fixed corner C is 0 and the update gives 0 to 1e-25 m/N.
#[test]
fn corner_update_matches_fresh_factorization() {
    let p = plate(0.4584, 0.36);
    let model = Model::new(p, Mesh::uniform(0.4584, 0.36, 10, 8).unwrap()).unwrap();
    let family =
        CornerFamily::new(&model, [EdgeSupport::Free; 4], CornerFamily::default_base_stiffness(&model)).unwrap();
    let points = [(0.2292, 0.18), (0.1, 0.0), (0.4584, 0.18), (0.03, 0.35), (0.0, 0.0), (0.4584, 0.36)];
    let base = family.probe_many(&points).unwrap();
    for k in [5e4, 5.11545e8, 1e12] {
        for sup in [Supports::con1(), Supports::con2(k), Supports::con3(k)] {
            let fresh = model.factorize(&sup).unwrap().with_refinement(2).respond_many(&points).unwrap();
            for (bp, fr) in base.iter().zip(&fresh) {
                let up = family.respond(bp, sup.corners).unwrap();
                if fr.compliance == 0.0 {
                    assert!(up.compliance.abs() < 1e-25);
                    continue;
                }
                let tol = if k >= 1e12 && (bp.x, bp.z) == (0.4584, 0.36) { 1e-9 } else { 1e-10 };
                assert_relative_eq!(up.compliance, fr.compliance, max_relative = tol);
                for c in 0..4 {
                    assert!((up.corners[c].reaction - fr.corners[c].reaction).abs() < 1e-9, "reaction {c}");
                }
            }
        }
    }
}

/// Bad inputs are errors, not panics.
#[test]
fn errors() {
    let p = plate(1.0, 1.0);
    let model = Model::new(p, Mesh::uniform(1.0, 1.0, 4, 4).unwrap()).unwrap();
    assert!(matches!(model.factorize(&Supports::FREE), Err(FemError::Singular(_))));
    let f = model.factorize(&Supports::con1()).unwrap();
    assert!(matches!(f.respond(1.5, 0.5), Err(FemError::OutsidePlate { .. })));
    assert!(Model::new(PlateProperties { thickness: -1.0, ..p }, Mesh::uniform(1.0, 1.0, 2, 2).unwrap()).is_err());
    assert!(Model::new(p, Mesh::uniform(2.0, 1.0, 2, 2).unwrap()).is_err(), "mesh must span the plate");
}
