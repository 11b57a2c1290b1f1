//! General support sets through the library pipeline (scene -> plate model -> balance),
//! against independent references: scikit-fem Argyris runs of the same supports
//! (reference/data, written by reference/python/plate_reference.py) and Lévy's series.

use analytic::{Elastic, Plate};
use coupled::{BeamModel, ComplianceModel, PlateModel, SupportSet};
use impact::report::skfem;
use impact::scene::{Scene, SceneSource, DEFAULT_SCENE};
use plate_fem::classical::{levy_converged, LevyPlate, YEdge};
use plate_fem::convergence::richardson;

fn plate_of(case: &skfem::Case) -> Plate {
    let p = case.props;
    Plate::new(p.length, p.width, p.thickness, p.density, Elastic::new(p.youngs_modulus, p.poisson_ratio).unwrap())
        .unwrap()
}

/// The left edge clamped and the two right corners on 1e6 N/m springs. The plate model
/// (20 x 16 and 40 x 32, Richardson) against Argyris (to 160 x 128, Richardson): the two
/// extrapolations may differ by their two error estimates, plus 2e-6 of C for the
/// conditioning of scikit-fem's element basis the reference run measured at 40 x 32.
/// The spring stores (the energy split) are checked against the reference's own split.
#[test]
fn clamped_edge_and_two_springs_meet_argyris() {
    let case = skfem::load("clamped-edge-two-springs").unwrap();
    let plate = plate_of(&case);
    let set = SupportSet::new("clamped + springs", case.supports);
    let model = PlateModel::compute(&plate, std::slice::from_ref(&set), &case.points, 20, 2).unwrap();
    let argyris = skfem::extrapolate(&case.argyris);
    let raw: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(skfem::data_dir().join("clamped-edge-two-springs.json")).unwrap(),
    )
    .unwrap();
    let runs = raw["results"]["argyris"].as_array().unwrap();
    for (i, &(x, z)) in case.points.iter().enumerate() {
        let est = model.compliance(&set, x, z).unwrap();
        let c = est.compliance.total();
        let a = &argyris[i];
        let tol = est.error_estimate + a.error_estimate + 2e-6 * a.extrapolated;
        assert!((c - a.extrapolated).abs() <= tol, "({x}, {z}): {c:e} vs {:e}, tolerance {tol:e}", a.extrapolated);
        // Spring share of the compliance: the reference's two finest meshes, extrapolated.
        let share = |k: usize, j: usize| runs[k]["spring_energy_share"][i][j].as_f64().unwrap();
        let n = runs.len();
        for (j, corner) in ["(L, 0)", "(L, B)"].iter().enumerate() {
            let reference = richardson(&[share(n - 2, j), share(n - 1, j)]).unwrap();
            let ours =
                est.compliance.stores().iter().find(|s| s.name.ends_with(corner)).map(|s| s.compliance / c).unwrap();
            // Shares are ratios of compliances: their errors are those of C, relative.
            let tol = 10.0 * (est.relative_error() + a.error_estimate / a.extrapolated) + 1e-6;
            assert!(
                (ours - reference.extrapolated).abs() <= tol,
                "({x}, {z}) spring {corner}: share {ours} vs {}, tolerance {tol:e}",
                reference.extrapolated
            );
        }
    }
    // The beam does not describe this set, and says so.
    assert!(BeamModel { plate: &plate }.compliance(&set, 0.2, 0.1).is_err());
}

/// Lévy's plate (x = 0, L simply supported, z = 0, B free) in a scene file: the plate model
/// against Lévy's single series, within the FE error estimate and the series' truncation.
#[test]
fn levy_plate_from_a_scene_meets_the_series() {
    let text = DEFAULT_SCENE.replacen(
        "[[conditions]]\nname = \"Con 1\"\nsupports = \"both-fixed\"",
        "[[conditions]]\nname = \"Levy\"\n[conditions.edges]\nleft = \"simply-supported\"\nright = \"simply-supported\"",
        1,
    );
    let scene = Scene::parse(&text, "levy").unwrap();
    let set = scene.conditions.iter().find(|c| c.name == "Levy").unwrap().clone();
    assert_eq!(set.beam_condition(), None);
    let p = &scene.plate;
    let points = [(p.length() / 2.0, p.width() / 2.0), (p.length() / 4.0, 0.0), (p.length() / 2.0, 0.0)];
    let model = PlateModel::compute(p, std::slice::from_ref(&set), &points, 20, 2).unwrap();
    let levy = LevyPlate {
        a: p.length(),
        b: p.width(),
        d: p.flexural_rigidity(),
        nu: p.material().poisson_ratio(),
        y_edges: YEdge::Free,
    };
    for &(x, z) in &points {
        let est = model.compliance(&set, x, z).unwrap();
        // The series measures y from the centreline.
        let at = (x, z - p.width() / 2.0);
        let series = levy_converged(levy, at, at, 1e-10);
        let tol = 3.0 * est.error_estimate + 1e-9 * series;
        assert!(
            (est.compliance.total() - series).abs() <= tol,
            "({x}, {z}): {:e} vs {series:e}",
            est.compliance.total()
        );
    }
}
