//! Corner stiffnesses over the whole range (0, ∞) from one base factorization: exact limits,
//! invariants, the a-posteriori check, and bit-for-bit agreement with the rank-4 update
//! where it is well conditioned.
//!
//! The plate is the paper's (L = 0.4584 m, B = 0.36 m, h = 8 mm, steel). Its base springs
//! are k_b = 1e4 D/(L B) ≈ 5.97e8 N/m and its twist stiffness s = 2(1 - ν) D/(L B) (the
//! pure twist w = xz is exact in the element), so k_b/4s ≈ 1786 for any mesh.

use nalgebra::{DMatrix, DVector};
use plate_fem::corners::{BasePoint, Formulation, UPDATE_ERROR_BOUND};
use plate_fem::*;
use CornerSupport::*;

const L: f64 = 0.4584;
const B: f64 = 0.36;

fn paper() -> PlateProperties {
    PlateProperties {
        length: L,
        width: B,
        thickness: 0.008,
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
        density: 7850.0,
    }
}

fn model(p: PlateProperties, nx: usize, nz: usize) -> Model {
    Model::new(p, Mesh::uniform(p.length, p.width, nx, nz).unwrap()).unwrap()
}

fn family(m: &Model) -> CornerFamily<'_> {
    CornerFamily::new(m, [EdgeSupport::Free; 4], CornerFamily::default_base_stiffness(m)).unwrap()
}

/// 1e-12 .. 1e60 N/m in steps of 10^(1/4), and the paper's k_T.
fn sweep() -> Vec<f64> {
    let mut ks: Vec<f64> = (-48..=240).map(|e| 10f64.powf(e as f64 / 4.0)).collect();
    ks.push(5.11545e8);
    ks.sort_by(f64::total_cmp);
    ks
}

const POINTS: [(f64, f64); 6] = [(0.2292, 0.18), (0.1146, 0.0), (0.4584, 0.18), (0.35, 0.3), (0.05, 0.02), (0.0, 0.0)];

fn con2(k: f64) -> [CornerSupport; 4] {
    [Spring(k); 4]
}
fn con3(k: f64) -> [CornerSupport; 4] {
    [Fixed, Spring(k), Fixed, Spring(k)]
}

/// Con 2 at the centre: by double symmetry each spring carries exactly 1/4 and the plate
/// deforms as on fixed corners plus a rigid drop, so C = C_Con1 + 1/(4 k_T) exactly.
///
/// Tolerances: where condensation is used every term of C is non-negative (module docs), so
/// C carries a few ε; the centre's f is exactly 1/4 each in the rigid directions, so its
/// only other error is the round-off of C_fix = C_b - uᵀf (a few ε of C_b ≈ C_fix here).
/// We allow 1e-13. Where the update is used, its error is bounded by the criterion's
/// UPDATE_ERROR_BOUND = 1e-8 (measured worst 1.2e-9, at k_T = 5e4).
#[test]
fn con2_centre_is_fixed_corners_plus_rigid_drop() {
    let m = model(paper(), 24, 20);
    let fam = family(&m);
    let bp = fam.probe_many(&[(L / 2.0, B / 2.0)]).unwrap()[0];
    let c1 = fam.respond(&bp, [Fixed; 4]).unwrap().compliance;
    for k in sweep() {
        let exact = c1 + 0.25 / k;
        let r = fam.respond(&bp, con2(k)).unwrap();
        let err = (r.compliance - exact).abs() / exact;
        let tol = match fam.formulation(&con2(k)) {
            Formulation::Condensed => 1e-13,
            Formulation::Update => UPDATE_ERROR_BOUND,
        };
        assert!(err <= tol, "k_T = {k:e}: C = {:e}, exact {exact:e}, error {err:e}", r.compliance);
        // Each spring carries 1/4 (the base solve's symmetry holds to ~1e-11).
        for c in r.corners {
            assert!((c.reaction - 0.25).abs() < 1e-9, "k_T = {k:e}: reaction {}", c.reaction);
        }
        // The plate store is the fixed-corner one; the rest is the springs'.
        assert!((r.plate_compliance - c1).abs() <= 1e-8 * c1 + 1e-8 * 0.25 / k, "k_T = {k:e}");
    }
}

/// Con 3 for k_T → 0. Statics gives three equations for the four reactions (one
/// redundancy): the moment about the left edge fixes only the springs' sum,
/// L (r_RN + r_RF) = x. The split follows from compatibility: the complementary energy is
/// the plate's (bounded) plus (r_RN² + r_RF²)/k_T, which dominates as k_T → 0, so the split
/// tends to the one minimizing r_RN² + r_RF²: equal halves, x/2L each (the plate turns
/// rigidly about the left edge and both right corners drop alike). Then
/// C k_T → a = Σ r_i² = x²/(2L²), and the fixed corners carry, from the other two
/// equations, r_LF = z/B - x/2L and r_LN = 1 - x/2L - z/B.
///
/// Tolerances: C = a/k_T + C_0 + O(k_T) with C_0 below 1e-4 m/N (the plate's own
/// compliance is ~1e-6 m/N), so |C k_T - a| ≤ k_T·1e-4 plus round-off, which with every
/// term non-negative is a few ε of a: 1e-12 a.
#[test]
fn con3_soft_springs_turn_the_plate_about_its_left_edge() {
    let m = model(paper(), 24, 20);
    let fam = family(&m);
    let pts: Vec<(f64, f64)> = POINTS.iter().copied().filter(|p| p.0 > 0.0).collect();
    let base = fam.probe_many(&pts).unwrap();
    for k in [1e-12, 1e-10, 1e-8, 1e-6, 1e-4] {
        for bp in &base {
            let r = fam.respond(bp, con3(k)).unwrap();
            let xi = bp.x / L;
            let a = xi * xi / 2.0;
            assert!(
                (r.compliance * k - a).abs() <= 1e-12 * a + k * 1e-4,
                "k_T = {k:e} at ({}, {}): C k = {:e}, a = {a:e}",
                bp.x,
                bp.z,
                r.compliance * k
            );
            // Reactions: the springs' are statically exact in the limit, their split
            // converges like k_T·(plate compliance) ≲ k_T·1e-4.
            let expect = [1.0 - xi / 2.0 - bp.z / B, xi / 2.0, bp.z / B - xi / 2.0, xi / 2.0];
            for (c, e) in r.corners.iter().zip(expect) {
                assert!((c.reaction - e).abs() <= 1e-12 + k * 1e4, "k_T = {k:e}: {} vs {e}", c.reaction);
            }
        }
    }
}

/// Con 3 and Con 2 for k_T → ∞ reach Con 1. The spring part of C is
/// fᵀc ≤ Σ φ_i f_i² = Σ f_i²/k_T (the twist only relieves the springs), so
/// 0 ≤ C - C_Con1 ≤ Σ f_i²/k_T with f the fixed-corner reactions, up to round-off (a few ε
/// of C, allowed as 1e-14 C). The reactions differ from the fixed ones by the twist force,
/// r - f = -t β with |β| ≤ s Σ φ_i |f_i| ≤ 4 s max|f|/k_T, plus the update's error bound
/// where it is used.
#[test]
fn stiff_springs_tend_to_fixed_corners() {
    let m = model(paper(), 24, 20);
    let fam = family(&m);
    let base = fam.probe_many(&POINTS).unwrap();
    for bp in &base {
        let fixed = fam.respond(bp, [Fixed; 4]).unwrap();
        let f2: Vec<f64> = fixed.corners.iter().map(|c| c.reaction * c.reaction).collect();
        for k in [1e12, 1e16, 1e20, 1e30, 1e50, 1e60] {
            for (corners, sum) in [(con2(k), f2.iter().sum::<f64>()), (con3(k), f2[1] + f2[3])] {
                let r = fam.respond(bp, corners).unwrap();
                let gap = r.compliance - fixed.compliance;
                let slack = 1e-14 * fixed.compliance.abs() + 1e-30;
                assert!(gap >= -slack && gap <= sum / k + slack, "k = {k:e} at ({}, {}): gap {gap:e}", bp.x, bp.z);
                let fmax = fixed.corners.iter().map(|c| c.reaction.abs()).fold(0.0, f64::max);
                let s = fam.twist_stiffness_value().unwrap();
                for (a, b) in r.corners.iter().zip(&fixed.corners) {
                    assert!(
                        (a.reaction - b.reaction).abs() <= 4.0 * s * fmax / k + UPDATE_ERROR_BOUND,
                        "k = {k:e}: {} vs {}",
                        a.reaction,
                        b.reaction
                    );
                }
            }
        }
    }
}

/// Over the whole sweep, for Con 2, Con 3 and mixed sets, at every point: `respond` is Ok
/// (the check accepts correct results), C ≥ 0 and the plate store ≥ 0 up to round-off of
/// the base (1e-24 m/N at a fixed corner point, where C is 0 in exact arithmetic),
/// the stores add up to C (to 1e-12 of C: a few ε each), and the reactions sum to the unit
/// load: to 1e-12 by condensation (its fixed-corner reactions are exact in the rigid
/// directions, and Σt = 0), to the update's error bound by the update (it forms spring
/// reactions as k w, and inherits the base solve's ~1e-11).
#[test]
fn invariants_over_the_whole_range() {
    let m = model(paper(), 24, 20);
    let fam = family(&m);
    let base = fam.probe_many(&POINTS).unwrap();
    for k in sweep() {
        let sets = [
            con2(k),
            con3(k),
            [Spring(k), Spring(1e-10), Spring(1e50), Spring(1.0)],
            [Fixed, Spring(k), Spring(1e-10), Spring(5.11545e8)],
            [Free, Spring(k), Spring(k), Spring(k)],
            [Spring(k), Free, Fixed, Spring(1e-8)],
        ];
        for corners in sets {
            for bp in &base {
                let r = fam.respond(bp, corners).unwrap_or_else(|e| panic!("{corners:?} at ({}, {}): {e}", bp.x, bp.z));
                let springs: f64 = r.corners.iter().map(|c| c.spring_compliance).sum();
                assert!(r.compliance >= -1e-24, "{corners:?}: C = {:e}", r.compliance);
                assert!(r.plate_compliance >= -1e-24, "{corners:?}: plate {:e}", r.plate_compliance);
                assert!(r.corners.iter().all(|c| c.spring_compliance >= 0.0));
                assert!((r.plate_compliance + springs - r.compliance).abs() <= 1e-12 * r.compliance.abs() + 1e-24);
                let tol = match fam.formulation(&corners) {
                    Formulation::Condensed => 1e-12,
                    Formulation::Update => UPDATE_ERROR_BOUND,
                };
                assert!((r.total_reaction() - 1.0).abs() < tol, "{corners:?}: Σr = {}", r.total_reaction());
            }
        }
    }
}

/// C is continuous and non-increasing in k_T (stiffer springs, smaller compliance) over
/// 1e-12 .. 1e60, across both switches of formulation. Steps of 10^(1/4) change C by a
/// finite ratio, so a decrease within round-off is allowed: 1e-12 relative where both
/// neighbours are condensed, the update's bound where either is an update.
#[test]
fn monotone_and_continuous_in_k() {
    let m = model(paper(), 24, 20);
    let fam = family(&m);
    let base = fam.probe_many(&POINTS).unwrap();
    let ks = sweep();
    for make in [con2 as fn(f64) -> [CornerSupport; 4], con3] {
        for bp in &base {
            let c: Vec<f64> = ks.iter().map(|&k| fam.respond(bp, make(k)).unwrap().compliance).collect();
            for i in 1..ks.len() {
                let both = [fam.formulation(&make(ks[i - 1])), fam.formulation(&make(ks[i]))];
                let tol = if both == [Formulation::Condensed; 2] { 1e-12 } else { UPDATE_ERROR_BOUND };
                assert!(
                    c[i] <= c[i - 1] * (1.0 + tol) + 1e-24,
                    "{:?} at ({}, {}): C({:e}) = {:e} > C({:e}) = {:e}",
                    make(1.0),
                    bp.x,
                    bp.z,
                    ks[i],
                    c[i],
                    ks[i - 1],
                    c[i - 1]
                );
            }
        }
    }
    // Continuity across the switch: in the update's window both formulations answer, and
    // agree to its error bound.
    for &k in &ks {
        for make in [con2 as fn(f64) -> [CornerSupport; 4], con3] {
            if fam.formulation(&make(k)) != Formulation::Update {
                continue;
            }
            for bp in &base {
                let u = fam.respond_by(bp, make(k), Formulation::Update).unwrap();
                let n = fam.respond_by(bp, make(k), Formulation::Condensed).unwrap();
                let scale = n.compliance.abs();
                // 1e-24 m/N: the round-off of C_b (~ε/k_b) where C vanishes, at a fixed corner.
                assert!(
                    (u.compliance - n.compliance).abs() <= UPDATE_ERROR_BOUND * scale + 1e-24,
                    "k = {k:e} at ({}, {}): {:e} vs {:e}",
                    bp.x,
                    bp.z,
                    u.compliance,
                    n.compliance
                );
            }
        }
    }
}

/// The formulations' limits agree with independent routes: a spring of 1e60 N/m is a
/// fixed corner, and with three fixed corners a spring of 1e-12 N/m is a free corner
/// (it carries ~k_T of the load), each computed by the update for Fixed/Free. Relative
/// 1e-10: the base solve's error (relative residual ~1e-11) enters the update's
/// fixed-corner reactions in every direction but condensation's in the twist only, and
/// the update's Free loses log10(k_b/4s) ≈ 3 more digits of ε (module docs).
#[test]
fn extreme_springs_match_fixed_and_free_corners() {
    let m = model(paper(), 24, 20);
    let fam = family(&m);
    for bp in fam.probe_many(&POINTS).unwrap() {
        let pairs = [
            ([Spring(1e60), Spring(1e60), Fixed, Free], [Fixed, Fixed, Fixed, Free]),
            ([Fixed, Fixed, Fixed, Spring(1e-12)], [Fixed, Fixed, Fixed, Free]),
            ([Spring(1e-12), Fixed, Fixed, Fixed], [Free, Fixed, Fixed, Fixed]),
        ];
        for (a, b) in pairs {
            let (ra, rb) = (fam.respond(&bp, a).unwrap(), fam.respond(&bp, b).unwrap());
            assert!(
                (ra.compliance - rb.compliance).abs() <= 1e-10 * rb.compliance + 1e-24,
                "{a:?} vs {b:?} at ({}, {}): {:e} vs {:e}",
                bp.x,
                bp.z,
                ra.compliance,
                rb.compliance
            );
        }
    }
}

/// The check rejects what the update returns where it is ill conditioned, with an error
/// that names the stiffness and what failed; `respond` then uses condensation.
#[test]
fn the_check_rejects_an_ill_conditioned_update() {
    let m = model(paper(), 24, 20);
    let fam = family(&m);
    let bp = fam.probe_many(&[(L / 2.0, B / 2.0)]).unwrap()[0];
    for k in [1e-10, 1e50] {
        let e = fam.respond_by(&bp, con2(k), Formulation::Update).unwrap_err();
        assert!(matches!(e, FemError::CornerUpdate { .. }), "{e}");
        let msg = e.to_string();
        assert!(msg.contains(&format!("k = {k:e} N/m")) && msg.contains("check"), "{msg}");
        assert!(fam.respond(&bp, con2(k)).is_ok());
    }
}

/// The rank-4 update as it was before condensation existed, re-implemented here operation
/// for operation.
fn old_update(fam: &CornerFamily, p: &BasePoint, corners: [CornerSupport; 4]) -> PointResponse {
    let (g, kb) = (fam.corner_flexibility(), fam.k_base());
    let s: Vec<usize> = (0..4).filter(|&i| corners[i] != Spring(kb)).collect();
    let inv_delta = |i: usize| match corners[i] {
        Fixed => 0.0,
        Free => -1.0 / kb,
        Spring(k) => 1.0 / (k - kb),
    };
    let m = s.len();
    let lambda = if m == 0 {
        DVector::zeros(0)
    } else {
        let mat = DMatrix::from_fn(m, m, |a, b| g[(s[a], s[b])] + if a == b { inv_delta(s[a]) } else { 0.0 });
        let rhs = DVector::from_fn(m, |a, _| p.u[s[a]]);
        mat.lu().solve(&rhs).unwrap()
    };
    let mut compliance = p.compliance;
    let mut w = p.u;
    for (a, &i) in s.iter().enumerate() {
        compliance -= p.u[i] * lambda[a];
        for r in 0..4 {
            w[r] -= g[(r, i)] * lambda[a];
        }
    }
    let mut out = [model_corner(0.0, 0.0); 4];
    for i in 0..4 {
        let extra = s.iter().position(|&j| j == i).map_or(0.0, |a| lambda[a]);
        out[i] = match corners[i] {
            Free => model_corner(0.0, 0.0),
            Fixed => model_corner(kb * w[i] + extra, 0.0),
            Spring(k) => model_corner(k * w[i], k * w[i] * w[i]),
        };
    }
    let springs: f64 = out.iter().map(|c| c.spring_compliance).sum();
    PointResponse {
        x: p.x,
        z: p.z,
        compliance,
        plate_compliance: compliance - springs,
        corners: out,
        edge_spring_compliance: 0.0,
        residual: p.residual,
    }
}

fn model_corner(reaction: f64, spring_compliance: f64) -> plate_fem::model::CornerResponse {
    plate_fem::model::CornerResponse { reaction, spring_compliance }
}

fn bits(r: &PointResponse) -> Vec<u64> {
    let mut v = vec![r.compliance.to_bits(), r.plate_compliance.to_bits(), r.residual.to_bits()];
    for c in r.corners {
        v.push(c.reaction.to_bits());
        v.push(c.spring_compliance.to_bits());
    }
    v
}

/// Where the update is well conditioned its results are unchanged bit for bit: the paper's
/// k_T, the stiffnesses of the project's tests and reports (5e4 .. 1e15 N/m on the paper's
/// plate, 5e4 .. 1e12 on the verification plate), Con 1, and a free corner.
#[test]
fn well_conditioned_results_are_bit_identical() {
    let verification = PlateProperties {
        length: L,
        width: B,
        thickness: 0.01,
        youngs_modulus: 1e9,
        poisson_ratio: 0.3,
        density: 7850.0,
    };
    for (p, nx, nz, ks) in [
        (paper(), 24, 20, vec![5.11545e8, 5e4, 1e6, 2.50025e8, 5e8, 1e10, 1e12, 1e15]),
        (paper(), 10, 8, vec![5.11545e8, 5e4, 1e12]),
        (verification, 10, 8, vec![5e4, 5.11545e8, 1e12]),
    ] {
        let m = model(p, nx, nz);
        let fam = family(&m);
        let base = fam.probe_many(&POINTS).unwrap();
        let mut sets = vec![[Fixed; 4], [Fixed, Free, Fixed, Fixed]];
        for &k in &ks {
            sets.extend([con2(k), con3(k)]);
        }
        for corners in sets {
            assert_eq!(fam.formulation(&corners), Formulation::Update, "{corners:?}");
            for bp in &base {
                let new = fam.respond(bp, corners).unwrap();
                let old = old_update(&fam, bp, corners);
                assert_eq!(bits(&new), bits(&old), "{corners:?} at ({}, {}): {new:?} vs {old:?}", bp.x, bp.z);
            }
        }
    }
}

/// Past the break-even point the base is probed through its selected inverse; each point
/// then agrees with its own solve (`Factorization::respond`, corner reactions k_b u) to
/// 1e-10 of the largest C in C (a point on a supported edge has none) and of the largest |u|
/// in every corner deflection. Both carry the
/// base's conditioning only (relative residuals ~1e-12 here); an error in the inverse or
/// in the reciprocity read of u is O(1).
#[test]
fn probes_from_the_selected_inverse_equal_solves() {
    for edges in
        [[EdgeSupport::Free; 4], [EdgeSupport::Simple, EdgeSupport::Simple, EdgeSupport::Free, EdgeSupport::Free]]
    {
        let m = model(paper(), 12, 10);
        let fam = CornerFamily::new(&m, edges, CornerFamily::default_base_stiffness(&m)).unwrap();
        let points: Vec<(f64, f64)> =
            (0..15).flat_map(|i| (0..12).map(move |j| (L * i as f64 / 14.0, B * j as f64 / 11.0))).collect();
        assert!(fam.base().selected_inverse_pays(points.len()) && !fam.base().selected_inverse_pays(1));
        let many = fam.probe_many(&points).unwrap();
        let largest = many.iter().fold(0.0f64, |a, p| a.max(p.compliance));
        for (p, bp) in points.iter().zip(&many) {
            let one = fam.base().respond(p.0, p.1).unwrap();
            let gap = (bp.compliance - one.compliance).abs();
            assert!(gap < 1e-10 * largest, "{p:?}: {} against {}", bp.compliance, one.compliance);
            let u: Vec<f64> = one.corners.iter().map(|c| c.reaction / fam.k_base()).collect();
            let scale = u.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            for (c, want) in u.iter().enumerate() {
                assert!((bp.u[c] - want).abs() <= 1e-10 * scale, "{p:?} corner {c}: {} against {want}", bp.u[c]);
            }
        }
    }
}
