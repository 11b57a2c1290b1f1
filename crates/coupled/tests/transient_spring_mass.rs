//! The transient model's contact sequence against an independent reference: the sphere
//! striking a rigid mass on a spring, integrated as an ODE.

mod common;

use common::strike;
use coupled::transient::{law::Flores, simulate_with, Contact, ContactLaw, Outcome, PlateFacts, SpringMass, Striker};

// ---------------------------------------------------------------------------------------
// An independent reference: the sphere striking a rigid mass M on a spring k, with the same
// Flores law written out here, its damping scaled by each contact's own approach velocity
// δ̇⁻ (the relative velocity at the located onset, as Flores et al. define it). In contact the four-state ODE is integrated by an adaptive
// Dormand-Prince 5(4) pair; in free flight the sphere moves uniformly and the mass-spring
// harmonically, both in closed form, so a later contact is the first root of
// δ(t) = u(t) - w(t), found by scanning and bisection. Gravity g pulls the sphere toward the
// mass: ü = g - P/m, a parabola in free flight.

struct Sdof {
    m: f64,
    k_contact: f64,
    e: f64,
    v0: f64,
    big_m: f64,
    k: f64,
    /// δ̇⁻ of the contact being integrated.
    approach: std::cell::Cell<f64>,
    /// Gravity on the sphere toward the mass, m/s².
    g: f64,
}

impl Sdof {
    fn force(&self, d: f64, r: f64) -> f64 {
        if d <= 0.0 {
            return 0.0;
        }
        (self.k_contact * d.powf(1.5) * (1.0 + 8.0 * (1.0 - self.e) / (5.0 * self.e) * r / self.approach.get()))
            .max(0.0)
    }
    fn rhs(&self, y: [f64; 4]) -> [f64; 4] {
        let p = self.force(y[0] - y[2], y[1] - y[3]);
        [y[1], self.g - p / self.m, y[3], (p - self.k * y[2]) / self.big_m]
    }
    /// One Dormand-Prince step: the fifth-order solution and the error estimate.
    fn dopri(&self, y: [f64; 4], h: f64) -> ([f64; 4], f64) {
        const A: [[f64; 6]; 6] = [
            [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
            [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
            [19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0, 0.0, 0.0],
            [9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0, 0.0],
            [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0],
        ];
        const E: [f64; 7] =
            [71.0 / 57600.0, 0.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0];
        let mut k = [[0.0; 4]; 7];
        k[0] = self.rhs(y);
        for s in 0..6 {
            let mut ys = y;
            for (i, yi) in ys.iter_mut().enumerate() {
                *yi += h * (0..=s).map(|j| A[s][j] * k[j][i]).sum::<f64>();
            }
            k[s + 1] = self.rhs(ys);
        }
        let mut y5 = y;
        for (i, yi) in y5.iter_mut().enumerate() {
            *yi += h * (0..6).map(|j| A[5][j] * k[j][i]).sum::<f64>();
        }
        // Error relative to the scales of displacement (δ-sized) and velocity (v₀-sized).
        let scale = [1e-5, self.v0, 1e-5, self.v0];
        let err =
            (0..4).map(|i| (h * (0..7).map(|j| E[j] * k[j][i]).sum::<f64>() / scale[i]).abs()).fold(0.0, f64::max);
        (y5, err)
    }
    /// Free flight from `y` at t0 for τ: the sphere on its parabola, the mass harmonic.
    fn free(&self, y: [f64; 4], tau: f64) -> [f64; 4] {
        let om = (self.k / self.big_m).sqrt();
        let (c, s) = ((om * tau).cos(), (om * tau).sin());
        [
            y[0] + y[1] * tau + 0.5 * self.g * tau * tau,
            y[1] + self.g * tau,
            y[2] * c + y[3] / om * s,
            -y[2] * om * s + y[3] * c,
        ]
    }
    /// The contact sequence within `window` s: (start, duration, peak force, impulse, v after).
    fn sequence(&self, window: f64, tol: f64, h_max: f64) -> Vec<(f64, f64, f64, f64, f64)> {
        let mut out = Vec::new();
        let (mut t, mut y) = (0.0, [0.0, self.v0, 0.0, 0.0]);
        let period = 2.0 * std::f64::consts::PI * (self.big_m / self.k).sqrt();
        while t < window {
            // In contact from (t, y), δ = 0 rising.
            let (start, v_in) = (t, y[1]);
            self.approach.set(y[1] - y[3]);
            let mut h = h_max * 1e-3;
            let mut peak: f64 = 0.0;
            loop {
                let (yn, err) = self.dopri(y, h);
                if err > tol {
                    h *= (0.9 * (tol / err).powf(0.2)).max(0.2);
                    continue;
                }
                if yn[0] - yn[2] <= 0.0 {
                    // The end lies inside this step: bisect on the step length.
                    let (mut lo, mut hi) = (0.0, h);
                    for _ in 0..100 {
                        let mid = 0.5 * (lo + hi);
                        let ym = self.dopri(y, mid).0;
                        if ym[0] - ym[2] > 0.0 {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    y = self.dopri(y, hi).0;
                    t += hi;
                    break;
                }
                y = yn;
                t += h;
                if t >= window {
                    // A contact the window cuts is not one of the sequence's (nor the model's).
                    return out;
                }
                peak = peak.max(self.force(y[0] - y[2], y[1] - y[3]));
                h = (h * (0.9 * (tol / err.max(1e-300)).powf(0.2)).min(5.0)).min(h_max);
            }
            // ∫P dt = m(v_in - v_out) + m g (t - start): gravity pushed on during the contact.
            out.push((start, t - start, peak, self.m * (v_in - y[1] + self.g * (t - start)), y[1]));
            // Free flight: the next root of δ, scanning in steps of period/400.
            let (t0, y0) = (t, y);
            let dtau = period / 400.0;
            let delta = |tau: f64| {
                let z = self.free(y0, tau);
                z[0] - z[2]
            };
            let mut tau = 1e-3 * dtau;
            let mut found = None;
            while t0 + tau < window {
                if delta(tau + dtau) > 0.0 {
                    let (mut lo, mut hi) = (tau, tau + dtau);
                    for _ in 0..200 {
                        let mid = 0.5 * (lo + hi);
                        if delta(mid) > 0.0 {
                            hi = mid;
                        } else {
                            lo = mid;
                        }
                    }
                    found = Some(hi);
                    break;
                }
                tau += dtau;
            }
            match found {
                Some(tau) => {
                    t = t0 + tau;
                    y = self.free(y0, tau);
                    // Start exactly on the surface.
                    y[0] = y[2];
                }
                None => break,
            }
        }
        out
    }
}

/// The transient loop on the spring-mass target.
fn on_spring_mass(sd: &Sdof, steps: f64, window: f64) -> (Outcome, f64) {
    let s = Striker {
        k: sd.k_contact,
        restitution: sd.e,
        mass: sd.m,
        velocity: sd.v0,
        law: ContactLaw::Flores(Flores),
        gravity: sd.g,
    };
    let dt = s.hertz_time() / steps;
    let mut target = SpringMass::new(sd.big_m, sd.k, dt);
    let facts = PlateFacts { static_compliance: Some(target.static_compliance()), ..Default::default() };
    (simulate_with(&s, Some(&mut target), facts, dt, window), s.hertz_time())
}

fn coal_sdof(mass_ratio: f64, period_ratio: f64) -> Sdof {
    let s = strike("coal");
    let big_m = mass_ratio * s.mass;
    let period = period_ratio * s.hertz_time();
    let k = big_m * (2.0 * std::f64::consts::PI / period).powi(2);
    Sdof {
        m: s.mass,
        k_contact: s.k,
        e: 0.65,
        v0: s.velocity,
        big_m,
        k,
        approach: std::cell::Cell::new(s.velocity),
        g: 0.0,
    }
}

/// Largest relative deviation of the model's contacts from the reference's, per field
/// (start and duration relative to t_c; peak force, impulse and velocity to their own scale).
fn deviation(o: &Outcome, r: &[(f64, f64, f64, f64, f64)], tc: f64, sd: &Sdof) -> [f64; 5] {
    assert_eq!(o.contacts.len(), r.len(), "contact counts: model {:?}, reference {r:?}", o.contacts);
    let mut dev = [0.0f64; 5];
    let p_scale = r.iter().map(|c| c.2).fold(0.0, f64::max);
    for (c, q) in o.contacts.iter().zip(r) {
        let Contact { start, duration, peak_force, impulse, rebound_velocity, .. } = *c;
        dev[0] = dev[0].max((start - q.0).abs() / tc);
        dev[1] = dev[1].max((duration - q.1).abs() / tc);
        dev[2] = dev[2].max((peak_force - q.2).abs() / p_scale);
        dev[3] = dev[3].max((impulse - q.3).abs() / (sd.m * sd.v0));
        dev[4] = dev[4].max((rebound_velocity - q.4).abs() / sd.v0);
    }
    dev
}

#[test]
fn double_impacts_on_a_spring_mass_match_an_ode_solution() {
    // Both cases strike more than once in the reference (2 and 3 contacts, each later one
    // damped on its own approach velocity), so every later contact is compared.
    for (mr, pr, n) in [(1.0, 4.0, 2), (0.5, 8.0, 3)] {
        let sd = coal_sdof(mr, pr);
        let tc = strike("coal").hertz_time();
        let window = 40.0 * tc;
        let r = sd.sequence(window, 1e-11, tc / 2000.0);
        assert_eq!(r.len(), n, "reference contacts {r:?}");
        let mut last: Option<[f64; 5]> = None;
        for steps in [400.0, 800.0] {
            let (o, _) = on_spring_mass(&sd, steps, window);
            let d = deviation(&o, &r, tc, &sd);
            println!("M/m {mr}, T/t_c {pr}, {steps} steps per t_c: deviations {d:?}");
            // Every contact's timing, peak force, impulse and rebound to 3e-4 (the phase of the
            // later contacts carries the period error of the free vibration, O(Δt²) per cycle).
            assert!(d.iter().all(|&x| x < 3e-4), "{d:?}");
            // The sphere has provably left, after the last reference contact and before the window end.
            let left = o.left_at.expect("the sphere leaves");
            let (s_last, d_last, ..) = r[r.len() - 1];
            assert!(left > s_last + d_last && left < window);
            // Impulses add up to the sphere's change of momentum.
            assert!((o.total_impulse - sd.m * (sd.v0 - o.final_velocity)).abs() < 1e-12 * sd.m * sd.v0);
            // Second order: halving Δt quarters the deviation (within a factor of 2).
            if let Some(prev) = last {
                let rate = [0usize, 1, 3, 4].map(|i| f64::log2(prev[i] / d[i]));
                println!("   observed orders {rate:.2?}");
                assert!(rate.iter().all(|&p| p > 1.5), "{rate:?}");
            }
            last = Some(d);
        }
    }
}

/// A sphere falling back under gravity: coal at 0.008 m/s on the spring-mass (M = m, period
/// 4 t_c), with g = 2 m/s² so that it comes back within 12 contact times (a rebound of
/// 3.6 mm/s returns after 2v/g = 3.6 ms): four contacts where without gravity there are two. The reference integrates ü = g - P/m in contact and the parabola in flight; the
/// model the same through Newmark's rule with g in the prediction. Every contact (the later
/// ones approached at the velocity gravity gave back) to 3e-4 as above, impulses summing to
/// the change of momentum less gravity's impulse over the run, and the run stopping only
/// when the sphere cannot be back within the window (it says when it can).
#[test]
fn bounces_under_gravity_match_an_ode_solution() {
    let sd = Sdof { g: 2.0, ..coal_sdof(1.0, 4.0) };
    let tc = strike("coal").hertz_time();
    let window = 12.0 * tc;
    let r = sd.sequence(window, 1e-11, tc / 2000.0);
    println!("t_c {tc:e}, reference {r:?}");
    assert_eq!(r.len(), 4, "the sphere comes back twice more than without gravity: {r:?}");
    let mut last: Option<[f64; 5]> = None;
    for steps in [800.0, 1600.0] {
        let (o, _) = on_spring_mass(&sd, steps, window);
        let d = deviation(&o, &r, tc, &sd);
        println!("{steps} steps per t_c: deviations {d:?}");
        // Every contact to 3e-5 (measured 9e-6 at 800 steps, the later starts ten contact
        // times on), and second order: the O(Δt) errors a missing half step of gravity or a
        // rebound taken at the step's end would leave show up as order 1.
        assert!(d.iter().all(|&x| x < 3e-5), "{d:?}");
        if let Some(prev) = last {
            let rate = [0usize, 1, 3, 4].map(|i| f64::log2(prev[i] / d[i]));
            println!("   observed orders {rate:.2?}");
            assert!(rate.iter().all(|&p| p > 1.5), "{rate:?}");
        }
        last = Some(d);
        // The last bounce rises 0.4 µm, less than the mass's reach: nothing proves it gone.
        assert!(o.left_at.is_none(), "{:?}", o.left_at);
        let end = o.steps_total as f64 * tc / steps;
        let gravity_impulse = sd.m * sd.g * end;
        let balance = o.total_impulse - sd.m * (sd.v0 - o.final_velocity) - gravity_impulse;
        assert!(balance.abs() < 1e-9 * sd.m * sd.v0, "{balance:e}");
    }
    // A window that ends while the sphere flies high after the second contact (apex 3 µm,
    // back at 8.0 ms by the reference): the run stops there and says when it can be back, no
    // later than the reference's third touch and beyond the window.
    let short = 6.0 * tc;
    let (o, _) = on_spring_mass(&sd, 800.0, short);
    assert_eq!(o.contacts.len(), 2);
    let (left, back) = (o.left_at.expect("the sphere cannot be back within the window"), o.returns_at.unwrap());
    println!("left at {left:e} s, back no sooner than {back:e} s; reference back at {:e} s", r[2].0);
    assert!(left < short && back >= short && back <= r[2].0, "left {left}, back {back}");
    // Without gravity the same impact is struck fewer times: gravity is what the test sees.
    let (plain, _) = on_spring_mass(&coal_sdof(1.0, 4.0), 800.0, window);
    assert!(plain.contacts.len() < r.len(), "{} vs {}", plain.contacts.len(), r.len());
}
