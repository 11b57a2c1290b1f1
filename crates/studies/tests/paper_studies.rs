//! The paper's studies under both models against closed forms computed here: Hertz's contact
//! on a rigid support at the beam's supported ends, the balance with the simply supported
//! beam's L³/(48EI) at mid-span, and for the plate the independent scikit-fem Argyris
//! compliance.

mod common;

use common::{
    beam_compliance, contact_force, delta_max, hertz_stiffness, mass, COAL, GANGUE_1, GANGUE_2, PLATE, RESTITUTION,
};
use studies::paper::Paper;
use studies::paper_studies::{checks::checks, midpoint, Along, Evidence, Statement};

/// The plate's centre compliance under Con 1 by scikit-fem's Argyris triangles,
/// Richardson-extrapolated (`reference/data/paper-con1.json`), m/N.
const ARGYRIS_CENTRE: f64 = 7.4702346e-7;

/// Tables 6-8 at the midpoint under Con 1, 0.0025 m/s: the beam's P_max and δ_max are the
/// balance's with C = L³/(48EI) (to the balance's 1e-13 residual: 1e-9 leaves room for the
/// closed form's own round-off); the plate's C (its deflection over P_max: Con 1's corners
/// do not move) is Argyris's to the FE error estimate 5e-6, and its P_max the balance's with
/// that C; every row's energies sum to E₀.
#[test]
fn midpoint_tables_meet_the_balance() {
    let rows = midpoint(&Paper::new()).unwrap();
    assert_eq!(rows.len(), 9, "three support sets, three spheres");
    let c_beam = beam_compliance(PLATE.0 / 2.0);
    for (r, sphere) in rows.iter().filter(|r| r.condition == "Con 1").zip([COAL, GANGUE_1, GANGUE_2]) {
        let k = hertz_stiffness(sphere, (PLATE.3, PLATE.4));
        let delta = delta_max(k, c_beam, mass(sphere), RESTITUTION, 0.0025);
        assert!((r.beam.compression / delta - 1.0).abs() < 1e-9, "{}: {} vs {delta}", r.body, r.beam.compression);
        let p = contact_force(sphere, c_beam, 0.0025);
        assert!((r.beam.contact_force / p - 1.0).abs() < 1e-9, "{}: {} vs {p}", r.body, r.beam.contact_force);
        let c_plate = r.plate.deflection / r.plate.contact_force;
        assert!((c_plate / ARGYRIS_CENTRE - 1.0).abs() < 5e-6, "{}: {c_plate}", r.body);
        let p = contact_force(sphere, c_plate, 0.0025);
        assert!((r.plate.contact_force / p - 1.0).abs() < 1e-9, "{}: {} vs {p}", r.body, r.plate.contact_force);
    }
    for r in &rows {
        for m in [&r.beam, &r.plate] {
            let sum = m.rock_total_ratio + m.plate_ratio + m.spring_ratio;
            assert!((sum - 1.0).abs() < 1e-12, "{} {}: energies sum to {sum}", r.condition, r.body);
        }
    }
}

/// Item 1's P_max along the centreline under Con 1: by the beam least at mid-span, where it is
/// the balance's with L³/(48EI), and greatest at the supported ends, where the beam's C is 0
/// and P_max is Hertz's on a rigid support, K ((5 e m v²)/(4K))^{3/5}.
#[test]
fn item_one_meets_hertz_at_the_ends() {
    let checks = checks(&Paper::new(), 101).unwrap();
    assert_eq!(checks.len(), 19, "9 statements on each line and item 4");
    assert!(checks.windows(2).all(|w| w[0].item <= w[1].item), "sorted by item");
    let force =
        checks.iter().find(|c| c.statement == Statement::ForceShape && c.along == Some(Along::Centreline)).unwrap();
    let k = hertz_stiffness(COAL, (PLATE.3, PLATE.4));
    let (m, v, e) = (mass(COAL), 0.008, RESTITUTION);
    let rigid = k * (5.0 * e * m * v * v / (4.0 * k)).powf(0.6);
    let mid = contact_force(COAL, beam_compliance(PLATE.0 / 2.0), v);
    let Evidence::Extremes { min_at, min, max_at, max } = force.beam else { panic!("{:?}", force.beam) };
    assert!((min_at - 0.5).abs() < 1e-12, "{min_at}");
    assert!((min / mid - 1.0).abs() < 1e-9, "{min} vs {mid}");
    assert!(max_at == 0.0 || max_at == 1.0, "{max_at}");
    assert!((max / rigid - 1.0).abs() < 1e-9, "{max} vs {rigid}");
    assert!(force.beam_holds);
}
