//! The reproduction of the paper's section IV against closed forms computed here: the
//! solver study's rigid cases (C = 0, where the balance has the root δ = (5 e m v²/(4K))^{2/5}),
//! the compliance it scales (L³/(48EI)), and Fig. 10's beam curve at mid-span (the balance
//! with that compliance, solved by bisection).

mod common;

use common::{beam_compliance, contact_force, COAL, PLATE, RESTITUTION};
use scene::SceneSource;
use studies::paper::{Drawn, RESPONSE_PANELS};
use studies::progress::Silent;
use studies::settings::Settings;
use studies::study::{Reproduction, Study};

#[test]
fn reproduction_meets_the_closed_forms() {
    let d = Reproduction::compute(&scene::Scene::default_scene(), &Settings::default(), &Silent).unwrap();
    assert!(d.counts.iter().sum::<usize>() == d.rows.len() && d.counts[3] == 0, "{:?}", d.counts);

    // The compliance the solver study scales: the simply supported beam's at mid-span.
    let c_paper = beam_compliance(PLATE.0 / 2.0);
    assert!((d.c_paper / c_paper - 1.0).abs() < 1e-12, "{} vs {c_paper}", d.c_paper);

    // With no plate compliance the balance reduces to ½mv² = (2K/5e)δ^{5/2}. The bracketed
    // solver stops at a relative energy residual of 1e-13 (δ to 4e-14: 1e-12 leaves room for
    // the closed form's round-off); the paper's recursion at ğ = 1e-6 (δ to 4e-7 of it).
    let (rho, _, nu, r) = COAL;
    let m = rho * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let rigid: Vec<_> = d.solvers.iter().filter(|s| s.compliance_factor == 0.0).collect();
    assert_eq!(rigid.len(), 16, "four velocities by four moduli");
    for s in rigid {
        let k = common::hertz_stiffness((rho, s.modulus_ratio * PLATE.3, nu, r), (PLATE.3, PLATE.4));
        let delta = (5.0 * RESTITUTION * m * s.velocity.powi(2) / (4.0 * k)).powf(0.4);
        assert!((s.bracketed.delta / delta - 1.0).abs() < 1e-12, "{s:?} vs {delta}");
        assert!((s.recursion.delta / delta - 1.0).abs() < 1e-6, "{s:?} vs {delta}");
    }

    // Fig. 10(1): the coal's P_max at 0.008 m/s along the plate; under Con 1 at mid-span (the
    // 51st of 101 points) the balance's with L³/(48EI).
    let contact = RESPONSE_PANELS.iter().position(|p| p.0 == "contact-force").unwrap();
    let panel = d
        .panels
        .iter()
        .find(|p| p.figure == "10" && p.drawn == Drawn::Response { quantity: contact, panel: 1 })
        .unwrap();
    let con1 = panel.curves.iter().find(|c| c.name == "Con 1").unwrap();
    let (x, p) = con1.points[50];
    assert!((x - PLATE.0 / 2.0 * 1e3).abs() < 1e-9, "{x} mm");
    let expected = contact_force(COAL, c_paper, 0.008);
    assert!((p / expected - 1.0).abs() < 1e-9, "{p} vs {expected}");
}
