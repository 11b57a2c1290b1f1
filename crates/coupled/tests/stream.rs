//! The caving stream on the reduced plate against two references that share none of its
//! stepping code.
//!
//! 1. A stream of one lump is the single impact: [`ReducedModel::impact`] runs the
//!    transient loop on the modal target (its own prediction pass, its own contact
//!    sequence), the stream its own multi-lump step. Same rule, same Δt, same law: they
//!    agree to rounding (1e-9 of each channel's peak; the sums are ordered differently), and
//!    the stream is zero before the touch; also for a lump under gravity, which the stream
//!    lets go of by its own rule, and for a yielding lump (Thornton's law), whose contact
//!    opens at its permanent set, also one pressed back to strike its dent again (the free
//!    intervals between its contacts, taken in one exact step where no sphere can touch,
//!    must not step over the return: with the dent's allowance doubled this test fails).
//! 2. Two lumps in contact at the same time are one coupled system: the modes driven by both
//!    contact forces, each sphere by its own, Hertz's law on each compression with the static
//!    correction at its point. The reference integrates that system as one ODE, with
//!    classical Runge-Kutta at a step 1,000 times finer than the stream's (its own error is
//!    far below the stream's), solving each point's algebraic static correction by Newton.
//!    The stream (Newmark's rule, second order) must converge to it: quadrupling the steps
//!    per contact divides its error in the sensor's deflection after the contacts by 16 ± a
//!    factor 2, and the finer run lies within 1e-4 of the reference's peak forces.

use analytic::{Elastic, Plate, RockStrength, Sphere};
use coupled::reduced::stream::{Arrival, StreamResponse};
use coupled::reduced::{ChannelKind, Quantity, ReducedModel, ReducedSettings, SignalSpec};
use coupled::transient::case::striker;
use coupled::transient::{LawKind, Striker};
use coupled::SupportSet;
use plate_fem::Supports;

fn plate() -> Plate {
    Plate::new(0.4584, 0.360, 0.008, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap()
}

fn rock(name: &str, density: f64, e: f64) -> Sphere {
    Sphere::new(name, density, 0.025, Elastic::new(e, 0.28).unwrap(), RockStrength::new(20e6, 30.0).unwrap()).unwrap()
}

#[test]
fn a_stream_of_one_lump_is_the_single_impact() {
    let plate = plate();
    let set = SupportSet::new("Con 3", Supports::con3(5.11545e8));
    let settings = ReducedSettings { modes: 30, elements: 8, ..ReducedSettings::default() };
    let model = ReducedModel::new(&plate, &set, settings).unwrap();
    let spec = SignalSpec { window: 0.01, ..SignalSpec::new(vec![(0.1, 0.1), (0.35, 0.3)]) };
    let probes = model.probes(&spec).unwrap();
    let cases = [
        (rock("coal", 1380.0, 2.26e9), 0.65, 1.3, 0.0),
        (rock("gangue", 2400.0, 16e9), 0.5, 2.7, 0.0),
        (rock("coal", 1380.0, 2.26e9), 0.3, 0.6, 9.81),
        (rock("gangue", 2400.0, 16e9), 1.0, 3.0, 9.81),
        // Pressed back by a body force 400 g, the yielded lump returns within its window and
        // touches again at its dent: the free intervals between must not step over it.
        (rock("gangue", 2400.0, 16e9), 1.0, 3.0, 4000.0),
    ];
    for (k, (sphere, e, v, gravity)) in cases.into_iter().enumerate() {
        let mut s = Striker { gravity, ..striker(&plate, &sphere, e, v) };
        if k >= 3 {
            // Thornton's plastic law: the contact opens at its permanent set δ_p > 0, which
            // the stream's free intervals must respect as the single impact's steps do.
            s.law = LawKind::Thornton.law_for(&sphere);
        }
        let (x, z) = (0.13 + 0.07 * k as f64, 0.21);
        let single = model.impact(&s, x, z, &probes).unwrap();
        if k >= 3 {
            let set = s.permanent_set(single.outcome.compression_max);
            assert!(set > 1e-3 * single.outcome.compression_max, "the lump yields: δ_p = {set:e}");
        }
        if k == 4 {
            assert!(
                single.outcome.contacts.len() >= 2,
                "the lump comes back: {} contacts",
                single.outcome.contacts.len()
            );
        }
        let touch = 37;
        let arrival = Arrival { time: touch as f64 / spec.rate_hz + 1e-7, striker: s, x, z };
        let stream = model.stream(&[arrival], &probes, 0.02).unwrap();
        assert_eq!(stream.lumps.len(), 1);
        assert_eq!(stream.lumps[0].sample, touch);
        let o = &single.outcome;
        assert_eq!(stream.lumps[0].contacts, o.contacts.len() + usize::from(o.unfinished_contact.is_some()));
        assert!((stream.lumps[0].force_max / o.force_max - 1.0).abs() < 1e-9, "{:?} {}", stream.lumps[0], o.force_max);
        for (a, b) in single.signals.channels.iter().zip(&stream.signals.channels) {
            assert_eq!(a.kind, b.kind);
            let peak = a.samples.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert!(b.samples[..touch].iter().all(|&x| x == 0.0), "{:?} moves before the touch", b.kind);
            for (i, (x, y)) in a.samples.iter().zip(&b.samples[touch..]).enumerate() {
                assert!((x - y).abs() <= 1e-9 * peak, "{:?} sample {i}: {x} against {y} (peak {peak})", a.kind);
            }
        }
    }
}

/// The coupled system of the modes and two Hertz contacts, integrated as one ODE by RK4.
struct Reference<'a> {
    omega: &'a [f64],
    zeta: f64,
    /// φᵢ(pⱼ) and C_res(pⱼ) per lump.
    points: Vec<(Vec<f64>, f64)>,
    strikers: &'a [Striker],
    /// Arrival of each lump, in steps of the reference.
    arrive: Vec<usize>,
}

impl Reference<'_> {
    /// Hertz's force at lump j with the static correction: P = K(u - Σφq - C P)^{3/2},
    /// by Newton from P = 0 (the residual is concave and increasing in P, so the iterates
    /// rise monotonically to the root).
    fn force(&self, j: usize, q: &[f64], u: f64) -> f64 {
        let (phi, c) = &self.points[j];
        let a = u - phi.iter().zip(q).map(|(f, q)| f * q).sum::<f64>();
        if a <= 0.0 {
            return 0.0;
        }
        let k = self.strikers[j].k;
        let mut p = 0.0;
        for _ in 0..100 {
            let d = (a - c * p).max(0.0);
            let f = p - k * d.powf(1.5);
            let next = p - f / (1.0 + 1.5 * k * c * d.sqrt());
            if (next - p).abs() <= 1e-15 * next.abs() {
                return next;
            }
            p = next;
        }
        p
    }

    /// d/dt of (q, q̇, u, u̇) with the lumps `on`.
    fn rate(&self, y: &[f64], on: &[bool]) -> (Vec<f64>, Vec<f64>) {
        let n = self.omega.len();
        let (q, v) = (&y[..n], &y[n..2 * n]);
        let mut dy = vec![0.0; y.len()];
        let mut forces = vec![0.0; self.strikers.len()];
        for j in 0..self.strikers.len() {
            if on[j] {
                forces[j] = self.force(j, q, y[2 * n + 2 * j]);
                dy[2 * n + 2 * j] = y[2 * n + 2 * j + 1];
                dy[2 * n + 2 * j + 1] = -forces[j] / self.strikers[j].mass;
            }
        }
        for i in 0..n {
            let w = self.omega[i];
            let f: f64 = (0..forces.len()).map(|j| self.points[j].0[i] * forces[j]).sum();
            dy[i] = v[i];
            dy[n + i] = f - w * w * q[i] - 2.0 * self.zeta * w * v[i];
        }
        (dy, forces)
    }

    /// The deflection at `sensor` every `every` steps of `dt` and each lump's largest force.
    fn run(&self, dt: f64, steps: usize, every: usize, sensor: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n = self.omega.len();
        let lumps = self.strikers.len();
        let mut y = vec![0.0; 2 * n + 2 * lumps];
        let mut on = vec![false; lumps];
        let mut peaks = vec![0.0f64; lumps];
        let mut out = vec![0.0];
        for s in 0..steps {
            for j in 0..lumps {
                if self.arrive[j] == s {
                    on[j] = true;
                    y[2 * n + 2 * j] = self.points[j].0.iter().zip(&y[..n]).map(|(f, q)| f * q).sum();
                    y[2 * n + 2 * j + 1] = self.strikers[j].velocity;
                }
            }
            let (k1, f) = self.rate(&y, &on);
            for j in 0..lumps {
                peaks[j] = peaks[j].max(f[j]);
            }
            let at = |y: &[f64], k: &[f64], h: f64| y.iter().zip(k).map(|(a, b)| a + h * b).collect::<Vec<_>>();
            let (k2, _) = self.rate(&at(&y, &k1, 0.5 * dt), &on);
            let (k3, _) = self.rate(&at(&y, &k2, 0.5 * dt), &on);
            let (k4, _) = self.rate(&at(&y, &k3, dt), &on);
            for i in 0..y.len() {
                y[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
            if (s + 1) % every == 0 {
                out.push(sensor.iter().zip(&y[..n]).map(|(f, q)| f * q).sum());
            }
        }
        (out, peaks)
    }
}

#[test]
fn two_lumps_in_contact_together_are_one_coupled_system() {
    let plate = plate();
    let set = SupportSet::new("Con 1", Supports::con1());
    let sphere = rock("gangue", 2400.0, 16e9);
    // Hertz's law: Flores's at e = 1.
    let strikers = [striker(&plate, &sphere, 1.0, 2.0), striker(&plate, &sphere, 1.0, 1.4)];
    let spec = SignalSpec {
        window: 0.004,
        quantities: vec![Quantity::Displacement],
        corners: false,
        ..SignalSpec::new(vec![(0.3, 0.12)])
    };
    let (p1, p2) = ((0.2, 0.2), (0.26, 0.16));
    // The second lump touches 2 samples (0.1 ms) into the first's contact (t_c ≈ 0.21 ms).
    let lag = 2;
    let run = |steps_per_contact: f64| -> (ReducedModel, StreamResponse) {
        let settings = ReducedSettings { modes: 24, elements: 8, steps_per_contact, ..ReducedSettings::default() };
        let model = ReducedModel::new(&plate, &set, settings).unwrap();
        let probes = model.probes(&spec).unwrap();
        let arrivals = [
            Arrival { time: 0.0, striker: strikers[0], x: p1.0, z: p1.1 },
            Arrival { time: lag as f64 / spec.rate_hz, striker: strikers[1], x: p2.0, z: p2.1 },
        ];
        let stream = model.stream(&arrivals, &probes, spec.window).unwrap();
        (model, stream)
    };
    let (model, coarse) = run(50.0);
    let (_, fine) = run(200.0);
    assert!(coarse.joint_steps > 10 && coarse.lumps.iter().all(|l| l.overlapped), "{coarse:?}");
    assert_eq!(coarse.unconverged_steps, 0);
    let omega = model.modes().omegas().to_vec();
    let points = [p1, p2].iter().map(|&(x, z)| model.at(x, z).unwrap()).collect();
    let (sensor, _) = model.at(0.3, 0.12).unwrap();
    let every = 2000;
    let dt = 1.0 / spec.rate_hz / every as f64;
    let reference = Reference {
        omega: &omega,
        zeta: ReducedSettings::default().damping_ratio,
        points,
        strikers: &strikers,
        arrive: vec![0, lag * every],
    };
    let samples = spec.samples();
    let (w_ref, peaks) = reference.run(dt, (samples - 1) * every, every, &sensor);
    let peak_error = |s: &StreamResponse| -> f64 {
        s.lumps.iter().zip(&peaks).map(|(l, p)| (l.force_max / p - 1.0).abs()).fold(0.0, f64::max)
    };
    let signal_error = |s: &StreamResponse| -> f64 {
        let c = s.signals.channel(ChannelKind::Displacement { sensor: 0 }).unwrap();
        let scale = w_ref.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        // After both contacts (0.35 ms): during them the stream's channel also carries the
        // static correction at the sensor, N(s)ᵀRN(p)P, which the reference has no data for.
        c.samples.iter().zip(&w_ref).skip(8).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / scale
    };
    let (ec, ef) = (signal_error(&coarse), signal_error(&fine));
    eprintln!("peak force error {:e} -> {:e}; signal {ec:e} -> {ef:e}", peak_error(&coarse), peak_error(&fine));
    assert!(peak_error(&fine) < 1e-4, "{} against {peaks:?}", peak_error(&fine));
    assert!((ec / ef) > 8.0 && (ec / ef) < 32.0, "signal error {ec:e} -> {ef:e}: not second order");
}

#[test]
fn an_empty_stream_is_silent() {
    let plate = plate();
    let set = SupportSet::new("Con 1", Supports::con1());
    let model =
        ReducedModel::new(&plate, &set, ReducedSettings { modes: 10, elements: 6, ..ReducedSettings::default() })
            .unwrap();
    let probes = model.probes(&SignalSpec::new(vec![(0.1, 0.1)])).unwrap();
    let s = model.stream(&[], &probes, 0.05).unwrap();
    assert!(s.lumps.is_empty());
    assert!(s.signals.channels.iter().all(|c| c.samples.len() == 1000 && c.samples.iter().all(|&x| x == 0.0)));
}

/// Arrivals out of time order, a negative time and a duration that is not positive are
/// refused with the value named, before anything runs.
#[test]
fn bad_arrivals_are_refused() {
    let plate = plate();
    let set = SupportSet::new("Con 1", Supports::con1());
    let model =
        ReducedModel::new(&plate, &set, ReducedSettings { modes: 10, elements: 6, ..ReducedSettings::default() })
            .unwrap();
    let probes = model.probes(&SignalSpec::new(vec![(0.1, 0.1)])).unwrap();
    let s = striker(&plate, &rock("coal", 1380.0, 2.26e9), 0.65, 1.0);
    let at = |time: f64| Arrival { time, striker: s, x: 0.2, z: 0.2 };
    let e = model.stream(&[at(0.02), at(0.01)], &probes, 0.05).unwrap_err().to_string();
    assert!(e.contains("arrival 1's time") && e.contains("0.01"), "{e}");
    let e = model.stream(&[at(-1.0)], &probes, 0.05).unwrap_err().to_string();
    assert!(e.contains("arrival 0's time") && e.contains("-1"), "{e}");
    let e = model.stream(&[], &probes, f64::NAN).unwrap_err().to_string();
    assert!(e.contains("duration"), "{e}");
}
