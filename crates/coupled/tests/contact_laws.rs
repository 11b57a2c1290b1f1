//! The contact laws of the transient model: Thornton's elastic-perfectly-plastic law
//! against its closed-form restitution on a rigid target, equal to Hertz below yield, its
//! yield onset at the paper's δ_my, and the three laws on the paper's plate.

use analytic::{DruckerPrager, Elastic, Plate, RockStrength, Sphere};
use coupled::supports::SupportSet;
use coupled::transient::case::striker;
use coupled::transient::law::{Flores, Hertz, Thornton};
use coupled::transient::{
    simulate, thornton_restitution, ContactLaw, Law, Outcome, Striker, TransientCase, TransientSettings,
};
use plate_fem::Supports;

fn plate() -> Plate {
    Plate::new(0.4584, 0.360, 0.008, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap()
}

fn coal() -> Sphere {
    Sphere::new("coal", 1380.0, 0.025, Elastic::new(2.26e9, 0.28).unwrap(), RockStrength::new(10e6, 30.0).unwrap())
        .unwrap()
}

fn thornton(v: f64) -> Striker {
    Striker { law: Thornton::for_body(&coal()).into(), ..striker(&plate(), &coal(), 1.0, v) }
}

/// Thornton's law of a striker made by [`thornton`].
fn law_of(s: &Striker) -> Thornton {
    let ContactLaw::Thornton(t) = s.law else { panic!("not Thornton's law: {:?}", s.law) };
    t
}

/// v_y on a rigid target: ½mv_y² = (2/5)Kδ_y^{5/2}.
fn rigid_yield_velocity() -> f64 {
    let s = thornton(1.0);
    let dy = law_of(&s).yield_compression(s.k);
    (2.0 * 0.4 * s.k * dy.powf(2.5) / s.mass).sqrt()
}

fn rigid_restitution(s: &Striker, steps: f64) -> f64 {
    let tc = s.hertz_time();
    let o = simulate(s, None, tc / steps, 20.0 * tc);
    assert!(o.left_at.is_some());
    -o.final_velocity / s.velocity
}

#[test]
fn yield_onset_is_the_papers_delta_my() {
    let (b, s) = (coal(), thornton(1.0));
    let dp = DruckerPrager::of(&b);
    let d_my = dp.yield_compression(b.radius(), s.k);
    let dy = law_of(&s).yield_compression(s.k);
    assert!((dy / d_my - 1.0).abs() < 1e-12, "δ_y {dy}, δ_my {d_my}");
    // At δ_my the Hertz centre pressure 3P/(2πa²), a = √(Rδ), is p_y.
    let Thornton { yield_pressure, radius } = law_of(&s);
    let p0 = 1.5 * s.k * d_my.powf(1.5) / (std::f64::consts::PI * radius * d_my);
    assert!((p0 / yield_pressure - 1.0).abs() < 1e-12);
}

#[test]
fn below_yield_thornton_is_hertz_exactly() {
    let vy = rigid_yield_velocity();
    for ratio in [0.1, 0.5, 0.999] {
        let t = thornton(ratio * vy);
        let h = Striker { law: Hertz.into(), ..t };
        let dt = t.hertz_time() / 200.0;
        let mut a: Outcome = simulate(&t, None, dt, 5.0 * t.hertz_time());
        let b = simulate(&h, None, dt, 5.0 * t.hertz_time());
        // Only the energy-error fields differ: they are kept for conservative laws only.
        assert_eq!(a.max_energy_error, 0.0);
        (a.max_energy_error, a.max_energy_error_total) = (b.max_energy_error, b.max_energy_error_total);
        assert!(a == b, "v/v_y = {ratio}: Thornton differs from Hertz below yield");
        assert!((a.apparent_restitution.unwrap() - 1.0).abs() < 1e-4);
    }
}

#[test]
fn thornton_restitution_on_a_rigid_target_is_the_closed_form() {
    let vy = rigid_yield_velocity();
    eprintln!("v_y = {vy:.6e} m/s");
    eprintln!("{:>8} {:>12} {:>12} {:>12} {:>12} {:>8}", "v/v_y", "e closed", "err 200", "err 400", "err 800", "order");
    for ratio in [1.0, 1.5, 2.0, 5.0, 10.0, 30.0, 100.0, 300.0, 1000.0] {
        let s = thornton(ratio * vy);
        let exact = thornton_restitution(ratio);
        let e: Vec<f64> = [200.0, 400.0, 800.0].iter().map(|&n| rigid_restitution(&s, n)).collect();
        let err: Vec<f64> = e.iter().map(|x| x - exact).collect();
        let order = ((e[0] - e[1]) / (e[1] - e[2])).abs().log2();
        eprintln!("{ratio:>8} {exact:>12.8} {:>12.3e} {:>12.3e} {:>12.3e} {order:>8.3}", err[0], err[1], err[2]);
        // The measured order lies between 1 and 3.5 (the turn from loading to unloading is
        // taken at a step end), so the error is bounded by twice the change from halving Δt.
        assert!(err[2].abs() <= 2.0 * (e[1] - e[2]).abs() + 1e-12, "v/v_y = {ratio}");
        assert!(err[2].abs() < 3e-6, "v/v_y = {ratio}");
    }
}

#[test]
fn on_the_papers_plate_plastic_flow_caps_the_force_and_dissipates() {
    // Con 1, the centre, coal: Hertz, Flores (e = 0.65) and Thornton at 0.008 to 2 m/s.
    let p = plate();
    let case = TransientCase::new(&p, TransientSettings::default()).unwrap();
    let set = SupportSet::new("Con 1", Supports::con1());
    let (x, z) = (p.length() / 2.0, p.width() / 2.0);
    let run = |law: ContactLaw, e: f64, v: f64| {
        let s = Striker { law, ..striker(&p, &coal(), e, v) };
        let o = case.run(&set, &s, x, z).unwrap();
        let e0 = 0.5 * s.mass * v * v;
        let last = o.later_history.last().or(o.history.last()).copied().unwrap();
        let plate = (last.plate_kinetic + last.plate_strain + last.springs) / e0;
        (o.force_max_interpolated, (o.final_velocity / v).powi(2), plate, last.dissipated / e0, -o.final_velocity / v)
    };
    let thornton = Thornton::for_body(&coal()).into();
    eprintln!("v_y (rigid) = {:.4e} m/s", rigid_yield_velocity());
    eprintln!(
        "{:>6} {:>9} | {:>10} {:>10} {:>10} | {:>8} {:>8} {:>8} {:>8}",
        "v", "law", "P_max N", "Hertz P", "ratio", "rebound", "plate", "dissip", "e_app"
    );
    let mut prev: Option<(f64, f64)> = None;
    for v in [0.008, 0.1, 1.0, 2.0] {
        let h = run(Hertz.into(), 1.0, v);
        let f = run(Flores.into(), 0.65, v);
        let t = run(thornton, 1.0, v);
        for (name, r) in [("hertz", h), ("flores", f), ("thornton", t)] {
            eprintln!(
                "{v:>6} {name:>9} | {:>10.4} {:>10.4} {:>10.4} | {:>8.4} {:>8.4} {:>8.4} {:>8.4}",
                r.0,
                h.0,
                r.0 / h.0,
                r.1,
                r.2,
                r.3,
                r.4
            );
        }
        // A capped pressure can only lower the force for the same energy.
        assert!(t.0 <= h.0 * (1.0 + 1e-9), "v = {v}");
        // Hertz's numerical loss bounds what the integrator alone can show as dissipation.
        let noise = h.3.abs() + 1e-9;
        assert!(t.3 >= -noise, "v = {v}: dissipated {}", t.3);
        if let Some((d, e)) = prev {
            assert!(t.3 >= d - noise, "dissipation not increasing at v = {v}");
            assert!(t.4 <= e + 1e-6, "restitution not decreasing at v = {v}");
        }
        prev = Some((t.3, t.4));
    }
}

/// A yielded lump's contact opens again only at its permanent set δ_p, so the stopping rule
/// measures the sphere's reach from δ_p: the run on the paper's plate (Con 1, the centre,
/// coal under Thornton's law at 2 m/s, about 200 times its yield velocity) stops once the
/// sphere is beyond the free plate's reach W of δ_p. The proof is checked against the same
/// impact followed with no stopping rule for 30 Hertz times: the same contacts, to the bit,
/// and none after. The rebounding sphere flies back far less than δ_p before the stop: a rule
/// measuring from δ = 0 would wait until it had flown back δ_p + W.
#[test]
fn a_yielded_lump_has_left_once_beyond_the_plates_reach_of_its_permanent_set() {
    use coupled::transient::{simulate_with, PlateFacts};
    let p = plate();
    let case = TransientCase::new(&p, TransientSettings::default()).unwrap();
    let set = SupportSet::new("Con 1", Supports::con1());
    let (x, z) = (p.length() / 2.0, p.width() / 2.0);
    let s = thornton(2.0);
    let stopped = case.run(&set, &s, x, z).unwrap();
    let left = stopped.left_at.expect("the rule stops the run");
    let last = *stopped.contacts.last().unwrap();
    let set_p = s.permanent_set(stopped.compression_max);
    let flown = -stopped.final_velocity * (left - (last.start + last.duration));
    assert!(set_p > 0.0 && flown < 0.5 * set_p, "flew back {flown:e} m before the stop, δ_p = {set_p:e} m");
    let dt = s.hertz_time() / case.settings().steps_per_contact;
    let mut nm = plate_fem::dynamics::Newmark::damped(case.model(), set.supports, dt, (x, z), None).unwrap();
    let facts = PlateFacts { follow_unbounded: true, ..PlateFacts::default() };
    let followed = simulate_with(&s, Some(&mut nm), facts, dt, 30.0 * s.hertz_time());
    assert!(followed.left_at.is_none() && followed.steps_total > stopped.steps_total);
    assert_eq!(followed.contacts, stopped.contacts);
    assert!(followed.unfinished_contact.is_none());
}
