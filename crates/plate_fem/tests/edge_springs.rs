//! Elastic edges (Winkler line springs of k per length) against classical plate theory.
//!
//! The reference is Lévy's series with the spring in the edge shear (`classical`,
//! `YEdge::Elastic`): x-edges simply supported, z-edges on springs, for the finite k in
//! between the two limits; Navier's series for k → ∞ on all four edges; Lévy's free-edge
//! series for k → 0. The FE edge spring is the Winkler form integrated exactly on the
//! element sides, so the discretisation stays conforming: the compliance approaches from
//! below at O(h²) (the energy error), and Richardson extrapolation of meshes n and 2n
//! removes the h² term as it does for the rigid edges (`verification.rs`).

use plate_fem::assembly::winkler;
use plate_fem::classical::{levy_converged, LevyPlate, YEdge};
use plate_fem::convergence::{observed_rate, richardson};
use plate_fem::element::Vec16;
use plate_fem::*;

fn plate(l: f64, b: f64) -> PlateProperties {
    PlateProperties { length: l, width: b, thickness: 0.01, youngs_modulus: 1e9, poisson_ratio: 0.3, density: 7850.0 }
}

/// x-edges simply supported, z-edges on springs of `k` N/m² (Lévy's elastic plate).
fn simple_elastic(k: f64) -> Supports {
    use EdgeSupport::*;
    Supports { edges: [Simple, Simple, Elastic(k), Elastic(k)], ..Supports::FREE }
}

/// FE compliance at (x, z) on meshes (n, m) times 1, 2 and 4.
fn fe_ladder(p: PlateProperties, supports: Supports, (n, m): (usize, usize), (x, z): (f64, f64)) -> [f64; 3] {
    [1, 2, 4].map(|f| {
        let model = Model::new(p, Mesh::uniform(p.length, p.width, n * f, m * f).unwrap()).unwrap();
        model.factorize(&supports).unwrap().respond(x, z).unwrap().compliance
    })
}

/// Finite k: the FE plate with z-edges on springs against Lévy's series with the spring in
/// the edge shear, for soft, moderate and stiff springs (k b³/D = 1, 10, 100) and loads at
/// the centre, off the centreline and on the elastic edge itself. Conforming: every mesh
/// is below the series and the sequence increases. Rate: the observed order of meshes
/// 12 x 8, 24 x 16, 48 x 32 is 2 (measured 1.98-2.04; allowed 2 ± 0.1). Raw error on
/// 48 x 32: 2.6e-5 to 3.1e-4 (largest for the stiff springs with the load on the elastic
/// edge). Extrapolated (Richardson, h²), the next term is left: measured at most 2.6e-6
/// relative, allowed 1e-5 as for the rigid edges.
#[test]
fn elastic_edges_match_levy_series() {
    let p = plate(1.0, 0.6);
    let d = p.rigidity();
    for ratio in [1.0, 10.0, 100.0] {
        let k = ratio * d / p.width.powi(3);
        let series = LevyPlate { a: 1.0, b: 0.6, d, nu: 0.3, y_edges: YEdge::Elastic(k) };
        for (x, z) in [(0.5, 0.3), (0.25, 0.15), (0.5, 0.6)] {
            let exact = levy_converged(series, (x, z - 0.3), (x, z - 0.3), 1e-11);
            let c = fe_ladder(p, simple_elastic(k), (12, 8), (x, z));
            assert!(
                c[0] < c[1] && c[1] < c[2] && c[2] < exact,
                "from below at ({x}, {z}), kb³/D = {ratio}: {c:?} {exact}"
            );
            let rate = observed_rate(c[0], c[1], c[2]).unwrap();
            let ext = richardson(&c[1..]).unwrap().extrapolated;
            let (raw, extrapolated) = ((c[2] / exact - 1.0).abs(), (ext / exact - 1.0).abs());
            println!(
                "kb³/D = {ratio:>5}, ({x}, {z}): rate {rate:.3}, raw error {raw:.2e}, extrapolated {extrapolated:.2e}"
            );
            assert!((rate - 2.0).abs() < 0.1, "rate {rate} at ({x}, {z}), kb³/D = {ratio}");
            assert!(extrapolated < 1e-5, "extrapolated error {extrapolated:e} at ({x}, {z}), kb³/D = {ratio}");
        }
    }
}

/// k → ∞ on all four edges is Navier's plate. Navier's plate has concentrated corner
/// reactions (2M_xz, T&W-K §31), which a line spring can only carry over a boundary layer
/// of length ~(D/k)^{1/3}; so C_k falls towards the simply supported C as k grows, slower
/// than 1/k until that layer is shorter than an element, and like 1/k on a fixed mesh
/// beyond (16 x 16: (C_k - C_simple) k L³/D measured 0.0066, 0.027, 0.071, 0.0797, 0.0798
/// at k L³/D = 1e2, 1e5, 1e7, 1e9, 1e11). So: C_k decreases to C_simple; the 1/k regime holds
/// between 1e10 and 1e11 (product changes by 1.2e-4, allowed 1e-3); at 1e10 the two differ
/// by 6e-8 relative (allowed 1e-6); and the spring plate at 1e10 extrapolated from 16 x 16
/// and 32 x 32 matches Navier's series for the centre load to 1e-6 (measured 2.3e-7; the
/// rigid edges reach 1e-7 in `verification.rs`).
#[test]
fn stiff_springs_tend_to_navier() {
    let p = plate(1.0, 1.0);
    let d = p.rigidity();
    let model = Model::new(p, Mesh::uniform(1.0, 1.0, 16, 16).unwrap()).unwrap();
    let c = |s: &Supports| model.factorize(s).unwrap().respond(0.5, 0.5).unwrap().compliance;
    let simple = c(&Supports::all_edges_simple());
    let on_springs = |r: f64| Supports { edges: [EdgeSupport::Elastic(r * d); 4], ..Supports::FREE };
    let mut last = f64::INFINITY;
    for e in [2, 5, 7, 9, 10, 11] {
        let ck = c(&on_springs(10f64.powi(e)));
        assert!(ck > simple && ck < last, "k L³/D = 1e{e}: {ck:e} not in ({simple:e}, {last:e})");
        last = ck;
    }
    let gap = |r: f64| (c(&on_springs(r)) - simple) * r;
    let (g10, g11) = (gap(1e10), gap(1e11));
    println!("(C_k - C_simple) k L³/D: {g10:e} at 1e10, {g11:e} at 1e11");
    assert!((g11 / g10 - 1.0).abs() < 1e-3, "{g10:e} {g11:e}");
    let stiff = on_springs(1e10);
    let near = (c(&stiff) / simple - 1.0).abs();
    println!("k L³/D = 1e10: {near:.2e} from the simply supported plate");
    assert!(near < 1e-6);
    let fine = Model::new(p, Mesh::uniform(1.0, 1.0, 32, 32).unwrap()).unwrap();
    let c32 = fine.factorize(&stiff).unwrap().respond(0.5, 0.5).unwrap().compliance;
    let ext = richardson(&[c(&stiff), c32]).unwrap().extrapolated;
    let navier =
        levy_converged(LevyPlate { a: 1.0, b: 1.0, d, nu: 0.3, y_edges: YEdge::Simple }, (0.5, 0.0), (0.5, 0.0), 1e-12);
    println!("k L³/D = 1e10: extrapolated {:.2e} from Navier", (ext / navier - 1.0).abs());
    assert!((ext / navier - 1.0).abs() < 1e-6, "{ext:e} against Navier {navier:e}");
}

/// k → 0 on the z-edges, with the x-edges simply supported, is Lévy's plate with free
/// edges: on one mesh the FE compliance tends to the free-edge FE compliance linearly in k
/// (the difference over k changes by < 1e-3 between k b³/D = 1e-6 and 1e-7; measured
/// 1.2e-6), and at k b³/D = 1e-8 the two agree to 1e-8 (measured 1.6e-9) and, extrapolated
/// from 24 x 16 and 48 x 32, match Lévy's free-edge series to 1e-5 (measured 8e-9).
#[test]
fn soft_springs_tend_to_free_edges() {
    let p = plate(1.0, 0.6);
    let d = p.rigidity();
    let scale = d / p.width.powi(3);
    let model = Model::new(p, Mesh::uniform(1.0, 0.6, 12, 8).unwrap()).unwrap();
    let (x, z) = (0.5, 0.6);
    let c = |s: &Supports| model.factorize(s).unwrap().respond(x, z).unwrap().compliance;
    let free = c(&Supports::simple_free());
    let slope = |r: f64| (free - c(&simple_elastic(r * scale))) / r;
    let (s6, s7) = (slope(1e-6), slope(1e-7));
    println!("(C_free - C_k) D/(k b³): {s6:e} at 1e-6, {s7:e} at 1e-7");
    assert!(s6 > 0.0 && (s7 / s6 - 1.0).abs() < 1e-3, "{s6:e} {s7:e}");
    let soft = simple_elastic(1e-8 * scale);
    let near = (c(&soft) / free - 1.0).abs();
    let ladder = fe_ladder(p, soft, (12, 8), (x, z));
    let ext = richardson(&ladder[1..]).unwrap().extrapolated;
    let levy = levy_converged(
        LevyPlate { a: 1.0, b: 0.6, d, nu: 0.3, y_edges: YEdge::Free },
        (x, z - 0.3),
        (x, z - 0.3),
        1e-11,
    );
    println!("k b³/D = 1e-8: {near:.2e} from the free edges, extrapolated {:.2e} from Lévy", (ext / levy - 1.0).abs());
    assert!(near < 1e-8);
    assert!((ext / levy - 1.0).abs() < 1e-5, "{ext:e} against Lévy {levy:e}");
}

/// Where the load goes: on four elastic edges and four fixed corners, the edge springs'
/// forces k∮w ds (the Winkler form against w = 1) and the corner reactions carry the unit
/// load (to the solve's residual, 1e-10 allowed); and the stores add up, C = plate store +
/// edge store, every store positive.
#[test]
fn edge_springs_and_corners_carry_the_load() {
    let p = plate(0.4584, 0.36);
    let d = p.rigidity();
    let mesh = Mesh::uniform(p.length, p.width, 10, 8).unwrap();
    let model = Model::new(p, mesh.clone()).unwrap();
    let k = 30.0 * d / p.width.powi(3);
    for corners in [CornerSupport::Free, CornerSupport::Fixed] {
        let supports = Supports { corners: [corners; 4], edges: [EdgeSupport::Elastic(k); 4] };
        let fact = model.factorize(&supports).unwrap();
        for (x, z) in [(0.2292, 0.18), (0.05, 0.3), (0.4584, 0.1)] {
            let w = fact.deflection_field(x, z).unwrap();
            let one = Vec16::from_fn(|i, _| if i % 4 == 0 { 1.0 } else { 0.0 });
            let mut edge_force = 0.0;
            for edge in Edge::ALL {
                let elements: Vec<(usize, usize)> = match edge {
                    Edge::Left => (0..mesh.nz()).map(|ez| (0, ez)).collect(),
                    Edge::Right => (0..mesh.nz()).map(|ez| (mesh.nx() - 1, ez)).collect(),
                    Edge::Near => (0..mesh.nx()).map(|ex| (ex, 0)).collect(),
                    Edge::Far => (0..mesh.nx()).map(|ex| (ex, mesh.nz() - 1)).collect(),
                };
                for (ex, ez) in elements {
                    let (a, b) = mesh.element_size(ex, ez);
                    let dofs = mesh.element_dofs(ex, ez);
                    let we = Vec16::from_fn(|i, _| w[dofs[i]]);
                    edge_force += one.dot(&(winkler(k).side(a, b, edge) * we));
                }
            }
            let r = fact.respond(x, z).unwrap();
            let total = edge_force + r.total_reaction();
            assert!(
                (total - 1.0).abs() < 1e-10,
                "{corners:?} at ({x}, {z}): edges {edge_force}, corners {}",
                r.total_reaction()
            );
            assert!(r.edge_spring_compliance > 0.0 && r.plate_compliance > 0.0);
            assert!((r.plate_compliance + r.edge_spring_compliance - r.compliance).abs() <= 1e-12 * r.compliance);
            let store = model.edge_spring_store(&supports, &w);
            assert!((store - r.edge_spring_compliance).abs() <= 1e-12 * store);
        }
    }
}

/// The Newmark plate on elastic edges counts their energy with the springs: in free
/// vibration after a short push, kinetic + strain + springs stays constant (the rule
/// conserves the quadratic energy of a linear system), with the edge springs' share
/// positive.
#[test]
fn newmark_counts_edge_spring_energy() {
    let p = plate(0.4584, 0.36);
    let model = Model::new(p, Mesh::uniform(p.length, p.width, 8, 6).unwrap()).unwrap();
    let k = 10.0 * p.rigidity() / p.width.powi(3);
    let supports = Supports { edges: [EdgeSupport::Elastic(k); 4], ..Supports::FREE };
    let mut plate = dynamics::Newmark::new(&model, supports, 1e-5, 0.1, 0.1).unwrap();
    for _ in 0..5 {
        plate.predict();
        plate.commit(100.0);
    }
    // The step in which the force falls to zero still does work (the trapezoid of 100 and 0).
    plate.predict();
    plate.commit(0.0);
    let total = |e: dynamics::PlateEnergy| e.kinetic + e.strain + e.springs;
    let start = total(plate.energy());
    for _ in 0..200 {
        plate.predict();
        plate.commit(0.0);
        let e = plate.energy();
        assert!(e.springs > 0.0 && e.strain > 0.0);
        assert!((total(e) / start - 1.0).abs() < 1e-10, "{e:?}");
    }
}
