//! The regime criteria and the closed-form rule against hand calculations and independent
//! solutions, and the measured quasi-static error in its two limits.

use analytic::{contact_stiffness, respond, Elastic, Impact, Method, Plate, RockStrength, Sphere};
use coupled::regimes::{
    mass_ratio, measure, period_estimate, quasi_static_run, ChristoforouYigit, ContactSpeed, OlssonRegime, RuleInputs,
    SLOW_FACTOR,
};
use coupled::supports::SupportSet;
use coupled::transient::case::striker;
use coupled::transient::{law::Hertz, ContactLaw, Striker, TransientCase, TransientSettings};
use coupled::{ComplianceModel, PlateModel};
use plate_fem::Supports;

fn steel_plate(scale: f64, h: f64) -> Plate {
    Plate::new(0.4584 * scale, 0.360 * scale, h, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap()
}

fn coal(radius: f64) -> Sphere {
    Sphere::new("coal", 1380.0, radius, Elastic::new(2.26e9, 0.28).unwrap(), RockStrength::new(8.39e6, 25.0).unwrap())
        .unwrap()
}

#[test]
fn mass_ratio_is_the_hand_calculation() {
    // The coal sphere: 1380 kg/m³ x (4/3)π(0.025 m)³ = 0.0903208 kg; the paper's plate:
    // 7850 x 0.4584 x 0.360 x 0.008 = 10.36350 kg; ratio 0.00871527.
    let m = 1380.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.025f64.powi(3);
    assert!((m - 0.0903208).abs() < 1e-7);
    let r = mass_ratio(m, &steel_plate(1.0, 0.008));
    assert!((r - 0.0903208 / 10.36350).abs() < 1e-8, "{r}");
    assert_eq!(OlssonRegime::of(r), OlssonRegime::WaveControlled);
    assert_eq!(OlssonRegime::of(1.0), OlssonRegime::Mixed);
    assert_eq!(OlssonRegime::of(2.5), OlssonRegime::QuasiStatic);
}

/// The infinite-plate asymptote in closed form against an RK4 solution of the mass on the
/// contact spring against the dashpot: ü + 2ζω u̇ + ω²u = 0, u(0) = 0, u̇(0) = v, whose peak
/// ωu_max/v is F̄_∞. 20,000 steps per 1/ω put the RK4 error near 1e-14; 1e-9 allows for the
/// sampled maximum (the peak is flat, so a step's miss costs O(h²) ~ 1e-9 at most).
#[test]
fn infinite_plate_force_is_the_damped_oscillator_peak() {
    for zeta in [0.02, 0.3, 0.8, 1.0, 1.7, 5.0] {
        let p = ChristoforouYigit { contact_stiffness: 1.0, relative_stiffness: 0.0, loss_factor: zeta };
        let (w, v) = (1.0, 1.0);
        let h = 1.0 / 20000.0;
        let f = |u: f64, du: f64| (du, -2.0 * zeta * w * du - w * w * u);
        let (mut u, mut du, mut peak): (f64, f64, f64) = (0.0, v, 0.0);
        while du > 0.0 {
            let (a1, b1) = f(u, du);
            let (a2, b2) = f(u + 0.5 * h * a1, du + 0.5 * h * b1);
            let (a3, b3) = f(u + 0.5 * h * a2, du + 0.5 * h * b2);
            let (a4, b4) = f(u + h * a3, du + h * b3);
            u += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
            du += h / 6.0 * (b1 + 2.0 * b2 + 2.0 * b3 + b4);
            peak = peak.max(u);
        }
        let closed = p.infinite_plate_force();
        assert!((closed - w * peak / v).abs() < 1e-9, "ζ {zeta}: closed {closed}, RK4 {}", w * peak / v);
    }
    // λ only enters the quasi-static asymptote: 1/√(1 + λ).
    let p = ChristoforouYigit { contact_stiffness: 1.0, relative_stiffness: 3.0, loss_factor: 0.0 };
    assert_eq!(p.quasi_static_force(), 0.5);
    assert!((p.error_bound() - 1.0).abs() < 1e-15, "ζ = 0 is the half-space: B = √(1 + λ) - 1");
}

/// The quasi-static model in time (the sphere on a massless spring of compliance C) against
/// the energy integral: with Hertz's law, u = δ + CKδ^{3/2} and
/// ½mu̇² + (2/5)Kδ^{5/2} + ½CK²δ³ = ½mv², so t_c = 2∫(1 + (3/2)CKδ^{1/2}) dδ/√(v² - 2U(δ)/m),
/// integrated here with δ = δ_max(1 - s²), which removes the square-root end point, by the
/// midpoint rule on 200,000 points (error ~1e-10). 2000 steps per contact put the
/// integrator's second-order error near 1e-7; the bound is 1e-6.
#[test]
fn quasi_static_contact_time_is_the_energy_integral() {
    let plate = steel_plate(1.0, 0.008);
    let s = Striker { law: ContactLaw::Hertz(Hertz), ..striker(&plate, &coal(0.025), 1.0, 0.008) };
    for c in [0.0, 6.2e-7, 1e-5] {
        let u = |d: f64| 0.4 * s.k * d.powf(2.5) + 0.5 * c * s.k * s.k * d.powi(3);
        let e0 = 0.5 * s.mass * s.velocity * s.velocity;
        // δ_max: the balance's root, by bisection.
        let (mut lo, mut hi) = (0.0, 1e-3);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if u(mid) < e0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let dm = 0.5 * (lo + hi);
        let n = 200_000;
        let mut half = 0.0;
        for i in 0..n {
            let sv = (i as f64 + 0.5) / n as f64;
            let d = dm * (1.0 - sv * sv);
            let rate = (s.velocity * s.velocity - 2.0 * u(d) / s.mass).max(0.0).sqrt();
            half += (1.0 + 1.5 * c * s.k * d.sqrt()) * 2.0 * dm * sv / rate / n as f64;
        }
        let reference = 2.0 * half;
        let o = quasi_static_run(&s, c.max(1e-300), reference / 2000.0, 3.0 * reference);
        let t = o.contacts[0].duration;
        assert!((t / reference - 1.0).abs() < 1e-6, "C {c}: {t} against {reference}");
        // The force at the largest compression of the steps is the balance's P_max =
        // Kδ_max^{3/2} (the interpolant's instant is not used: a massless spring's velocity
        // from the trapezoidal rule carries an alternating error, see quasi_static_run); the
        // step misses the peak by O(Δt²), about 1e-6 at 2000 steps.
        let p = s.k * o.compression_max.powf(1.5);
        assert!((p / (s.k * dm.powf(1.5)) - 1.0).abs() < 2e-6, "C {c}: {}", p / (s.k * dm.powf(1.5)) - 1.0);
    }
}

/// The closed-form period: Con 1 is the paper's beam, T = 2π/((π/L)²√(Eh²/12ρ)) (11.2 ms for
/// the paper's plate, by hand: (π/0.4584)² = 46.97 1/m², √(210e9 x 6.4e-5/(12 x 7850)) =
/// 11.94 m/s, ω = 560.9 rad/s); soft springs tend to the bounce on them, 2π√(M_p/4k_T) (Con 2)
/// and 2π√(M_p/6k_T) (Con 3); against the plate FE's T₁ it is within the range the regime
/// map measured (0.90 to 1.01 of it).
#[test]
fn period_estimate_is_the_beam_with_dunkerley() {
    let plate = steel_plate(1.0, 0.008);
    let t_beam = period_estimate(&plate, &SupportSet::new("Con 1", Supports::con1())).unwrap();
    assert!((t_beam - 2.0 * std::f64::consts::PI / 560.9).abs() < 2e-5, "{t_beam}");
    let m_p = 7850.0 * 0.4584 * 0.360 * 0.008;
    // At 10 N/m the bounce (ω_s² ≈ 4 s⁻²) is 1e5 times softer than the bending (ω_b² ≈
    // 3.1e5 s⁻²): Dunkerley's sum differs from the bounce alone by ω_s²/2ω_b² < 1e-5.
    let k = 10.0;
    let t2 = period_estimate(&plate, &SupportSet::new("Con 2", Supports::con2(k))).unwrap();
    let t3 = period_estimate(&plate, &SupportSet::new("Con 3", Supports::con3(k))).unwrap();
    let bounce = |n: f64| 2.0 * std::f64::consts::PI * (m_p / (n * k)).sqrt();
    assert!((t2 / bounce(4.0) - 1.0).abs() < 1e-5 && (t3 / bounce(6.0) - 1.0).abs() < 1e-5);
    let general =
        SupportSet::new("clamped", Supports { edges: [plate_fem::EdgeSupport::Clamped; 4], ..Supports::con1() });
    assert!(period_estimate(&plate, &general).is_none());
    let case = TransientCase::new(&plate, TransientSettings { elements: 16, ..Default::default() }).unwrap();
    for (set, k) in [(Supports::con1(), None), (Supports::con2(1e6), Some(1e6)), (Supports::con3(1e6), Some(1e6))] {
        let fe = case.fundamental_period(&set).unwrap();
        let est = period_estimate(&plate, &SupportSet::new("c", set)).unwrap();
        assert!((0.85..1.05).contains(&(est / fe)), "{k:?}: {est} against the FE's {fe}");
    }
}

/// The measured error in its two limits, each against an independent reference. A sphere 5.8
/// kg (R = 100 mm) on the half-size 32 mm plate is a slow contact (t_H/T₁ ≈ 5): the
/// transient force agrees with the quasi-static balance within the rule's slow bound
/// 0.35λ/(1 + λ) (0.4 % here). The paper's coal sphere on the paper's plate is a fast contact
/// (t_H/T₁ ≈ 0.09): the transient force lies above the balance and below Christoforou and
/// Yigit's infinite-plate bound B.
#[test]
fn the_measured_error_meets_its_limits() {
    let v = 0.008;
    for (scale, h, radius, slow) in [(0.5, 0.032, 0.1, true), (1.0, 0.008, 0.025, false)] {
        let plate = steel_plate(scale, h);
        let body = coal(radius);
        let set = SupportSet::new("Con 1", Supports::con1());
        let pt = (plate.length() / 2.0, plate.width() / 2.0);
        let qs = PlateModel::compute(&plate, std::slice::from_ref(&set), &[pt], 20, 2).unwrap();
        let c = qs.compliance(&set, pt.0, pt.1).unwrap();
        let imp = Impact {
            contact_stiffness: contact_stiffness(&body, plate.material()),
            mass: body.mass(),
            restitution: 0.65,
            velocity: v,
        };
        let p_qs = respond(&imp, &c.compliance, Method::default()).unwrap().contact_force;
        let s = striker(&plate, &body, 0.65, v);
        let case = TransientCase::new(&plate, TransientSettings { elements: 16, ..Default::default() }).unwrap();
        let facts = case.facts(&set.supports, pt.0, pt.1);
        let m = measure(&case, &set, facts, &s, pt, c.compliance.total(), p_qs, 200.0).unwrap();
        let rule = RuleInputs::of(&s, &plate, &set, c.compliance.total());
        let lambda = rule.parameters.relative_stiffness;
        println!(
            "slow {slow}: t_H/T1,est {:?}, λ {lambda:.4}, error {:+.5}, B {:.4}",
            rule.period_ratio,
            m.force_error(),
            rule.parameters.error_bound()
        );
        assert_eq!(m.contacts, 1);
        if slow {
            assert_eq!(rule.speed(), ContactSpeed::Slow);
            assert!(m.force_error().abs() <= SLOW_FACTOR * lambda / (1.0 + lambda));
            assert!(rule.trusts());
        } else {
            assert_eq!(rule.speed(), ContactSpeed::Fast);
            assert!(m.force_error() > 0.0 && m.force_error() <= rule.parameters.error_bound());
            assert!(!rule.trusts());
        }
    }
}
