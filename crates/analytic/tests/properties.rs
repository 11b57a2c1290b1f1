//! Property tests of the energy balance and the beam compliance over random valid inputs.

use analytic::*;
use proptest::prelude::*;

/// Random plate over extreme proportions: h/L from 1e-3 to 0.2, B/L 0.05 to 20.
fn plate() -> impl Strategy<Value = Plate> {
    (0.05f64..5.0, -3.0f64..(0.2f64).log10(), (0.05f64).log10()..(20f64).log10(), 1e9f64..1e12, 0.05f64..0.49).prop_map(
        |(l, lh, lb, e, nu)| {
            Plate::new(l, l * 10f64.powf(lb), l * 10f64.powf(lh), 7850.0, Elastic::new(e, nu).unwrap()).unwrap()
        },
    )
}

fn sphere() -> impl Strategy<Value = Sphere> {
    (500.0f64..5000.0, 1e-3f64..0.2, 1e8f64..1e12, 0.05f64..0.49, 1e5f64..1e8, 5.0f64..60.0).prop_map(
        |(rho, r, e, nu, c, phi)| {
            Sphere::new("s", rho, r, Elastic::new(e, nu).unwrap(), RockStrength::new(c, phi).unwrap()).unwrap()
        },
    )
}

fn condition() -> impl Strategy<Value = Condition> {
    prop_oneof![
        Just(Condition::BothFixed),
        (0.0f64..15.0).prop_map(|lk| Condition::both_springs(10f64.powf(lk)).unwrap()),
        (0.0f64..15.0).prop_map(|lk| Condition::fixed_and_springs(10f64.powf(lk)).unwrap()),
    ]
}

fn impact(s: &Sphere, p: &Plate, e: f64, v: f64) -> Impact {
    Impact { contact_stiffness: contact_stiffness(s, p.material()), mass: s.mass(), restitution: e, velocity: v }
}

/// A value drawn log-uniformly between 10^lo and 10^hi, or one of the two ends: the
/// overflows live in the corners of the box, which uniform draws alone rarely reach.
fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => (lo..=hi).prop_map(|l| 10f64.powf(l)),
        1 => Just(10f64.powf(lo)),
        1 => Just(10f64.powf(hi)),
    ]
}

/// Any beam condition with k_T anywhere in [1e-300, 1e300] N/m.
fn extreme_condition() -> impl Strategy<Value = Condition> {
    prop_oneof![
        Just(Condition::BothFixed),
        log_uniform(-300.0, 300.0).prop_map(|k| Condition::both_springs(k).unwrap()),
        log_uniform(-300.0, 300.0).prop_map(|k| Condition::fixed_and_springs(k).unwrap()),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Over extreme but finite inputs (each size 1e-6 to 1e5 m on its own, E 1e3 to 1e13
    /// Pa, k_T 1e-300 to 1e300 N/m), every parameter passes its range check, so
    /// beam_compliance must answer without panicking; what it returns as Ok is a physical
    /// compliance: finite and non-negative in total and in every store, with a finite
    /// deflection and finite spring forces.
    #[test]
    fn beam_compliance_never_panics_and_ok_is_physical(
        l in log_uniform(-6.0, 5.0), b in log_uniform(-6.0, 5.0), h in log_uniform(-6.0, 5.0),
        e in log_uniform(3.0, 13.0), nu in 0.01f64..0.49, c in extreme_condition(), xf in 0.0f64..=1.0,
    ) {
        let p = Plate::new(l, b, h, 7850.0, Elastic::new(e, nu).unwrap()).unwrap();
        if let Ok(comp) = beam_compliance(&p, c, (xf * l).min(l)) {
            prop_assert!(comp.total().is_finite() && comp.total() >= 0.0, "C = {}", comp.total());
            for s in comp.stores() {
                prop_assert!(s.compliance.is_finite() && s.compliance >= 0.0, "{} = {}", s.name, s.compliance);
            }
            prop_assert!(comp.deflection_per_unit_load().is_finite());
            prop_assert!(comp.springs().iter().all(|s| s.per_unit_load.is_finite()));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// The solution satisfies ½mv² = (2K/5e)δ^{5/2} + ½CK²δ³ to 1e-12, recomputed here
    /// from the reported responses rather than from the solver's own residual.
    #[test]
    fn energy_identity(p in plate(), s in sphere(), c in condition(), xf in 0.0f64..=1.0,
                       e in 0.01f64..=1.0, lv in -6.0f64..1.0) {
        let imp = impact(&s, &p, e, 10f64.powf(lv));
        let comp = beam_compliance(&p, c, xf * p.length()).unwrap();
        // Each solver stops at its own residual (1e-14 bracketed, ğ = 1e-12 recursion); the
        // recomputed sum may differ from the solver's residual by a few ulps of rounding.
        for (method, tol) in [(Method::default(), 1e-14), (Method::paper(), 1e-12)] {
            let r = respond(&imp, &comp, method).unwrap();
            let sum = r.rock_total_ratio + r.plate_ratio + r.spring_ratio;
            prop_assert!((sum - 1.0).abs() <= tol + 1e-14, "energy ratios sum to {sum}");
            // Rock stored is e times rock total (eq. 7).
            prop_assert!((r.rock_stored_ratio - e * r.rock_total_ratio).abs() < 1e-13);
        }
    }

    /// Both solvers agree to 1e-12 relative in δ.
    #[test]
    fn solvers_agree(p in plate(), s in sphere(), c in condition(), xf in 0.0f64..=1.0, lv in -6.0f64..1.0) {
        let imp = impact(&s, &p, 0.65, 10f64.powf(lv));
        let comp = beam_compliance(&p, c, xf * p.length()).unwrap();
        let bal = imp.balance(comp.total());
        let a = bal.solve(Method::paper()).unwrap().delta;
        let b = bal.solve(Method::default()).unwrap().delta;
        prop_assert!(((a - b) / b).abs() < 1e-12);
    }

    /// P_max rises with v.
    #[test]
    fn force_rises_with_velocity(p in plate(), s in sphere(), c in condition(), xf in 0.0f64..=1.0,
                                 lv in -6.0f64..1.0, factor in 1.001f64..10.0) {
        let comp = beam_compliance(&p, c, xf * p.length()).unwrap();
        let v = 10f64.powf(lv);
        let p1 = respond(&impact(&s, &p, 0.65, v), &comp, Method::default()).unwrap().contact_force;
        let p2 = respond(&impact(&s, &p, 0.65, v * factor), &comp, Method::default()).unwrap().contact_force;
        prop_assert!(p2 > p1);
    }

    /// A stiffer support never lowers P_max: raising k_T, and fixing the springs.
    #[test]
    fn stiffer_support_never_lowers_force(p in plate(), s in sphere(), xf in 0.0f64..=1.0,
                                          lk in 0.0f64..14.0, factor in 1.0f64..100.0, spring_both in any::<bool>()) {
        let x = xf * p.length();
        let make = |k: f64| if spring_both { Condition::both_springs(k).unwrap() } else { Condition::fixed_and_springs(k).unwrap() };
        let imp = impact(&s, &p, 0.65, 0.01);
        let force = |c: Condition| respond(&imp, &beam_compliance(&p, c, x).unwrap(), Method::default()).unwrap().contact_force;
        let k = 10f64.powf(lk);
        let (soft, stiff, fixed) = (force(make(k)), force(make(k * factor)), force(Condition::BothFixed));
        // Equal up to rounding where the springs carry nothing (x at the fixed end).
        prop_assert!(stiff >= soft * (1.0 - 1e-14));
        prop_assert!(fixed >= stiff * (1.0 - 1e-14));
    }

    /// Con 2 and Con 3 tend to Con 1 as k_T → ∞: the relative gap in δ falls like 1/k_T.
    #[test]
    fn springs_tend_to_fixed(p in plate(), s in sphere(), xf in 0.0f64..=1.0) {
        let x = xf * p.length();
        let imp = impact(&s, &p, 0.65, 0.01);
        let delta = |c: Condition| respond(&imp, &beam_compliance(&p, c, x).unwrap(), Method::default()).unwrap().compression;
        let d1 = delta(Condition::BothFixed);
        let gap = |k: f64| ((delta(Condition::both_springs(k).unwrap()) - d1) / d1).abs()
            .max(((delta(Condition::fixed_and_springs(k).unwrap()) - d1) / d1).abs());
        let (g1, g2) = (gap(1e10), gap(1e14));
        prop_assert!(g2 <= g1 * 1e-3 + 1e-14, "gap {g1} at 1e10, {g2} at 1e14");
        prop_assert!(g2 < 1e-6);
    }
}
