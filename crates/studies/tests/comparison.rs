//! The beam-against-plate comparison on one impact (Table 1's coal at the plate's centre under
//! Con 1, 0.008 m/s) against closed forms: the simply supported beam's L³/(48EI), Hertz's
//! contact stiffness and the energy balance at maximum compression solved here by bisection,
//! and for the plate the independent scikit-fem Argyris value of the committed reference.

mod common;

use common::{beam_compliance, contact_force, COAL, PLATE};
use scene::{Scene, SceneSource};
use studies::progress::Silent;
use studies::settings::Settings;
use studies::study::{Comparison, Study};
use test_scenes::ONE_IMPACT;

/// The plate's centre compliance under Con 1 (four fixed corners) by scikit-fem's Argyris
/// triangles, Richardson-extrapolated (`reference/data/paper-con1.json`), m/N.
const ARGYRIS_CENTRE: f64 = 7.4702346e-7;

#[test]
fn one_impact_meets_the_closed_forms() {
    let scene = Scene::parse(ONE_IMPACT, "one-impact.toml").unwrap();
    let d = Comparison::compute(&scene, &Settings::default(), &Silent).unwrap();
    let (l, b) = (PLATE.0, PLATE.1);
    let (beam, plate) = (d.beam.responses[0].values().unwrap(), d.plate.responses[0].values().unwrap());

    // The beam at mid-span: x²(L - x)²/(3EIL) = L³/(48EI), to round-off.
    let c_beam = beam_compliance(l / 2.0);
    assert!((beam.compliance.unwrap() / c_beam - 1.0).abs() < 1e-12, "{:?} vs {c_beam}", beam.compliance);
    // P_max = K δ^{3/2} with δ the root of ½mv² = (2K/5e)δ^{5/2} + ½CK²δ³: the study solves
    // the balance to a relative residual of 1e-13, δ to ~4e-14, P to ~6e-14.
    for (values, c) in [(beam, c_beam), (plate, plate.compliance.unwrap())] {
        let p = contact_force(COAL, c, 0.008);
        assert!((values.contact_force / p - 1.0).abs() < 1e-9, "{} vs {p}", values.contact_force);
    }

    // The plate against scikit-fem's Argyris triangles (an independent code): the study's
    // Richardson value of 20 x 16 and 40 x 32 is within 5e-6 of it (its own error estimate,
    // reports/fem).
    let c_plate = plate.compliance.unwrap();
    assert!((c_plate / ARGYRIS_CENTRE - 1.0).abs() < 5e-6, "{c_plate} vs {ARGYRIS_CENTRE}");

    // The finding at the scene's points is that one ratio, and the plate's FE error is the
    // one its row reports.
    let f = &d.points[0];
    let ratio = c_plate / c_beam - 1.0;
    let (lo, hi) = f.compliance.unwrap();
    assert!((lo - ratio).abs() < 1e-9 && (hi - ratio).abs() < 1e-9, "{lo}, {hi} vs {ratio}");
    assert_eq!((f.points, f.ends, f.force_cases), (1, 0, 1));
    assert!(f.yield_velocity.is_none(), "no yield velocities asked for");
    // The plate at P_max is the one impact at (L/2, B/2).
    let peak = d.peak.as_ref().unwrap();
    assert_eq!(peak.point, (l / 2.0, b / 2.0));
    assert_eq!(peak.p_max, plate.contact_force);
    // Studies the scene does not name are not computed.
    assert!(d.maps.is_none() && d.width.is_none() && d.extremes.is_none() && d.error_vs_time.is_none());
}
