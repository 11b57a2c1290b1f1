//! The reduced model of a shell structure against the full structure stepped in time.
//!
//! The reference is written here and shares no code with the model under test beyond the
//! structure's stiffness, lumped mass and contact load: every DOF of a small structure (a welded angle on
//! a clamped end, struck on one leg) is stepped by Newmark's average-acceleration rule,
//! (K + 4M/Δt²)u₊ = fP₊ + M(4u/Δt² + 4u̇/Δt) + (fP - Ku), with dense matrices, and the
//! sphere by the same rule, the step-end force solved from Hertz's law P = Kδ^{3/2} by
//! bisection. Undamped, the reduced model is the same discrete scheme in modal coordinates
//! while the sphere is in contact (the modal transformation commutes with Newmark's rule),
//! except for the truncated modes, which it carries by their static correction: the peak
//! force's difference is the truncation's alone, and must shrink as modes are added
//! (measured 0.24, 5.8e-3, 5.4e-6 and 2.5e-6 with 5, 20, 80 and 160 of the 324 DOFs). The
//! spring's peak comes after the sphere has left, where the reduced model is exact and the
//! reference keeps Newmark's period error ((ωΔt)²/12 in phase per unit time); they differ by
//! 5e-4 to 7e-4 from 80 modes on.

use coupled::reduced::structure::{Readings, StructureModel, StructureSettings};
use coupled::reduced::ModalDamping;
use coupled::transient::{law::Flores, ContactLaw, Striker};
use nalgebra::{DMatrix, DVector};
use plate_fem::shell::{Factorized, Restraints, ShellMass, Spring, Structure, DISC_RULE};

/// Two 0.3 x 0.2 m legs at a right angle along x, 8 mm thick, 6 x 4 elements each, clamped
/// at x = 0, with a spring at the free end's corner.
fn angle() -> (Structure, Restraints) {
    let mut s = Structure::new(210e9, 0.3).unwrap();
    let (l, w, t) = (0.3, 0.2, 0.008);
    for i in 0..6 {
        for k in 0..4 {
            let (x0, x1) = (l * i as f64 / 6.0, l * (i + 1) as f64 / 6.0);
            let (a, b) = (w * k as f64 / 4.0, w * (k + 1) as f64 / 4.0);
            s.add_quad([[x0, 0.0, a], [x1, 0.0, a], [x1, 0.0, b], [x0, 0.0, b]], t).unwrap();
            s.add_quad([[x0, a, 0.0], [x1, a, 0.0], [x1, b, 0.0], [x0, b, 0.0]], t).unwrap();
        }
    }
    let mut r = Restraints::default();
    for n in s.nodes_where(|p| p[0] == 0.0) {
        r.hold(n, &[0, 1, 2, 3, 4, 5]);
    }
    let (tip, _) = s.nearest_node([l, w, 0.0]).unwrap();
    // An oblique spring, its direction not of unit length.
    r.springs.push(Spring { node: tip, direction: [0.0, 2.0, 0.5], stiffness: 2e6 });
    (s, r)
}

fn ball() -> Striker {
    Striker { k: 8e9, restitution: 1.0, mass: 0.05, velocity: 1.0, law: ContactLaw::Flores(Flores), gravity: 0.0 }
}

/// A sphere of the full model: its load vector, its striker and the step it touches at.
struct Sphere<'a> {
    load: &'a [f64],
    striker: Striker,
    start: usize,
}

/// What the full model records over its steps: each sphere's step-end forces, a
/// displacement functional's value (a spring's force) and one DOF's acceleration.
struct FullRun {
    forces: Vec<Vec<f64>>,
    reading: Vec<f64>,
    acceleration: Vec<f64>,
}

/// The full model over `steps` steps of `dt`: the spheres touching at their start steps
/// (each placed at the structure's deflection under it, moving at its speed), the step-end
/// forces of the spheres solved together by Gauss-Seidel sweeps (each a bisection of
/// Hertz's law with the others held) to rounding, the spring `reading` read as kd̂·u and
/// the acceleration of DOF `probe` by Newmark's rule, ü₊ = 4(u₊ - u)/Δt² - 4u̇/Δt - ü.
fn full_newmark(
    (fact, mass): (&Factorized<'_>, &ShellMass),
    spheres: &[Sphere<'_>],
    (reading, probe): (&Spring, usize),
    dt: f64,
    steps: usize,
) -> FullRun {
    let n = fact.dofs();
    let (k, m, chol) = dense_system(fact, mass, dt);
    let loads: Vec<DVector<f64>> = spheres.iter().map(|s| DVector::from_column_slice(s.load)).collect();
    let gvecs: Vec<DVector<f64>> = loads.iter().map(|f| chol.solve(f)).collect();
    let count = spheres.len();
    let g = |j: usize, l: usize| loads[j].dot(&gvecs[l]);
    let (mut u, mut v, mut a) = (DVector::zeros(n), DVector::zeros(n), DVector::zeros(n));
    // Per sphere: displacement toward the structure, velocity, step-end force.
    let (mut x, mut xv, mut p) = (vec![0.0; count], vec![0.0; count], vec![0.0; count]);
    let norm = reading.direction.iter().map(|d| d * d).sum::<f64>().sqrt();
    let mut coeff = DVector::zeros(n);
    for i in 0..3 {
        coeff[6 * reading.node + i] = reading.stiffness * reading.direction[i] / norm;
    }
    let mut out = FullRun { forces: vec![Vec::new(); count], reading: Vec::new(), acceleration: Vec::new() };
    for step in 0..steps {
        for (j, s) in spheres.iter().enumerate() {
            if s.start == step {
                x[j] = loads[j].dot(&u);
                xv[j] = s.striker.velocity;
            }
        }
        let live: Vec<usize> = (0..count).filter(|&j| spheres[j].start <= step).collect();
        let mut rhs = &m * (&u * (4.0 / (dt * dt)) + &v * (4.0 / dt)) - &k * &u;
        for &j in &live {
            rhs += &loads[j] * p[j];
        }
        let u_hat = chol.solve(&rhs);
        let x_hat: Vec<f64> =
            (0..count).map(|j| x[j] + dt * xv[j] - dt * dt / (4.0 * spheres[j].striker.mass) * p[j]).collect();
        let d0: Vec<f64> = (0..count).map(|j| x_hat[j] - loads[j].dot(&u_hat)).collect();
        let strikers: Vec<Striker> = spheres.iter().map(|s| s.striker).collect();
        let p_new = joint_forces(&strikers, &live, &d0, &g, dt);
        let mut u_new = u_hat;
        for &j in &live {
            u_new += &gvecs[j] * p_new[j];
        }
        let a_new = (&u_new - &u) * (4.0 / (dt * dt)) - &v * (4.0 / dt) - &a;
        v = (&u_new - &u) * (2.0 / dt) - &v;
        u = u_new;
        a = a_new;
        for &j in &live {
            let x_new = x_hat[j] - dt * dt / (4.0 * spheres[j].striker.mass) * p_new[j];
            xv[j] = 2.0 * (x_new - x[j]) / dt - xv[j];
            x[j] = x_new;
            p[j] = p_new[j];
        }
        for (record, &force) in out.forces.iter_mut().zip(&p) {
            record.push(force);
        }
        out.reading.push(coeff.dot(&u));
        out.acceleration.push(a[probe]);
    }
    out
}

/// The dense K, M and the Cholesky factor of K + 4M/Δt² over every DOF (held DOFs have empty
/// rows and columns: a unit diagonal keeps them at zero).
fn dense_system(
    fact: &Factorized<'_>,
    mass: &ShellMass,
    dt: f64,
) -> (DMatrix<f64>, DMatrix<f64>, nalgebra::Cholesky<f64, nalgebra::Dyn>) {
    let n = fact.dofs();
    let column = |op: &dyn Fn(&[f64]) -> Vec<f64>| {
        let mut a = DMatrix::<f64>::zeros(n, n);
        for j in 0..n {
            let mut e = vec![0.0; n];
            e[j] = 1.0;
            a.set_column(j, &DVector::from_vec(op(&e)));
        }
        a
    };
    let k = column(&|x| fact.stiffness_times(x).unwrap());
    let m = column(&|x| mass.apply(x));
    let mut eff = &k + &m * (4.0 / (dt * dt));
    for d in 0..n {
        if eff[(d, d)] == 0.0 {
            eff[(d, d)] = 1.0;
        }
    }
    (k, m, nalgebra::Cholesky::new(eff).expect("positive definite"))
}

/// The step-end forces of the `live` spheres: Pⱼ = Kⱼ(d₀ⱼ - Σₗ gⱼₗPₗ - Δt²Pⱼ/4mⱼ)^{3/2},
/// by Gauss-Seidel sweeps, each a bisection with the others held, to rounding.
fn joint_forces(
    strikers: &[Striker],
    live: &[usize],
    d0: &[f64],
    g: &dyn Fn(usize, usize) -> f64,
    dt: f64,
) -> Vec<f64> {
    let mut p = vec![0.0; strikers.len()];
    for _ in 0..500 {
        let before = p.clone();
        for &j in live {
            let s = &strikers[j];
            let others: f64 = live.iter().filter(|&&l| l != j).map(|&l| g(j, l) * p[l]).sum();
            let (free, c) = (d0[j] - others, g(j, j) + dt * dt / (4.0 * s.mass));
            // P = K (free - cP)^{3/2}: monotone in P, bisected to rounding.
            p[j] = if free <= 0.0 {
                0.0
            } else {
                let (mut lo, mut hi) = (0.0, s.k * free.powf(1.5));
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if mid < s.k * (free - c * mid).max(0.0).powf(1.5) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                0.5 * (lo + hi)
            };
        }
        let scale = p.iter().copied().fold(1e-300, f64::max);
        if p.iter().zip(&before).all(|(a, b)| (a - b).abs() <= 1e-14 * scale) {
            break;
        }
    }
    p
}

#[test]
fn the_reduced_structure_is_the_full_structure_in_modal_coordinates() {
    let (s, r) = angle();
    let fact = s.factorize(&r).unwrap();
    let mass = ShellMass::lumped(&s, 7850.0);
    let leg: Vec<usize> =
        (0..s.elements()).filter(|&e| s.element_nodes(e).iter().all(|&n| s.nodes()[n][1] == 0.0)).collect();
    let f = s.disc_load([0.2, 0.0, 0.1], 0.004, &leg, DISC_RULE).unwrap();
    let spring = r.springs[0];
    let dt = ball().hertz_time() / 100.0;
    // Three rigid-target contact times: the first contact and its aftermath.
    let window = 300.0 * dt;
    let steps = (window / dt).ceil() as usize;
    let sphere = Sphere { load: &f, striker: ball(), start: 0 };
    let full = full_newmark((&fact, &mass), &[sphere], (&spring, 0), dt, steps);
    let p_ref = full.forces[0].iter().copied().fold(0.0, f64::max);
    let spring_ref = full.reading.iter().fold(0.0, |m: f64, r| m.max(r.abs()));
    let groups = [vec![spring]];
    let model = |modes: usize| {
        let settings = StructureSettings {
            modes,
            damping: ModalDamping::Ratio(0.0),
            steps_per_contact: 100.0,
            ..Default::default()
        };
        let readings = Readings { groups: &groups, ..Readings::default() };
        StructureModel::new(&fact, &mass, std::slice::from_ref(&f), readings, settings).unwrap()
    };
    let run = |modes: usize| model(modes).impact(&ball(), 0, window).unwrap();
    let mut last = f64::INFINITY;
    for modes in [5, 20, 80, 160] {
        let hit = run(modes);
        let e = (hit.outcome.force_max / p_ref - 1.0).abs();
        let es = (hit.group_force_max[0] / spring_ref - 1.0).abs();
        eprintln!("{modes} modes: P_max error {e:.2e}, spring force error {es:.2e}");
        if modes >= 80 {
            assert!(es < 2e-3, "{modes}: spring {es:e}");
        }
        assert!(e < last.max(1e-6), "{modes}: {e:e} after {last:e}");
        last = e;
    }
    assert!(last < 1e-5, "{last:e}");
    // Truncating the 160-mode model to 20 is the 20-mode model (the dropped modes join the
    // static correction): the same discrete scheme, to rounding.
    let big = model(160);
    let (cut, direct) = (big.truncated(20).unwrap().impact(&ball(), 0, window).unwrap(), run(20));
    assert!((cut.outcome.force_max / direct.outcome.force_max - 1.0).abs() < 1e-9);
    assert!((cut.group_force_max[0] / direct.group_force_max[0] - 1.0).abs() < 1e-9);
    assert!(big.truncated(0).is_err() && big.truncated(161).is_err());
}

/// Two lumps on the structure's stream, 1 cm apart, the second touching while the first is
/// in contact, against the full structure with both contacts. While any lump is in contact
/// the stream steps Newmark's rule on the modes, the same discrete scheme as the reference in
/// modal coordinates, so the differences are the truncation's (80 and 160 of 324 DOFs); the
/// two points' cross static correction, which the structure carries, matters at 1 cm.
/// After both have left the stream is exact and the reference keeps Newmark's period error,
/// so the signals are compared up to the last contact's end.
#[test]
fn a_stream_of_two_overlapping_lumps_is_the_full_structure_with_both_contacts() {
    use coupled::reduced::stream::Arrival;
    let (s, r) = angle();
    let fact = s.factorize(&r).unwrap();
    let mass = ShellMass::lumped(&s, 7850.0);
    let leg: Vec<usize> =
        (0..s.elements()).filter(|&e| s.element_nodes(e).iter().all(|&n| s.nodes()[n][1] == 0.0)).collect();
    let places = [(0.2, 0.1), (0.21, 0.1)];
    let loads: Vec<Vec<f64>> =
        places.iter().map(|&(x, z)| s.disc_load([x, 0.0, z], 0.004, &leg, DISC_RULE).unwrap()).collect();
    let spring = r.springs[0];
    let (node, _) = s.nearest_node([0.15, 0.0, 0.15]).unwrap();
    let mut accelerometer = vec![0.0; fact.dofs()];
    accelerometer[6 * node + 1] = 1.0;
    let groups = [vec![spring]];
    let readings = Readings { groups: &groups, accelerometers: std::slice::from_ref(&accelerometer) };
    // A sample every 4.35 contact steps: the stream steps T_s/5 (its rule, ⌈T_s/Δt_H⌉ steps
    // per sample); the second sphere, heavier and faster, has the first's Hertz time.
    let first = ball();
    let second = Striker { mass: 0.08, velocity: first.velocity * (0.08f64 / 0.05).powi(2), ..first };
    let dt_h = first.hertz_time() / 100.0;
    let (rate, every) = (1.0 / (4.35 * dt_h), 5);
    let (ts, samples, later) = (4.35 * dt_h, 70, 8);
    let arrivals = [
        Arrival { time: 0.0, striker: first, x: places[0].0, z: places[0].1 },
        Arrival { time: later as f64 * ts, striker: second, x: places[1].0, z: places[1].1 },
    ];
    let spheres = [
        Sphere { load: &loads[0], striker: first, start: 0 },
        Sphere { load: &loads[1], striker: second, start: later * every },
    ];
    let full = full_newmark((&fact, &mass), &spheres, (&spring, 6 * node + 1), ts / every as f64, samples * every);
    // The last step with a force, as a sample.
    let last = (0..samples * every).rev().find(|&n| full.forces.iter().any(|f| f[n] > 0.0)).unwrap() / every + 1;
    // Jack force: the truncation's error, 5.5e-4 at 80 modes, 3.6e-6 at 160.
    for (modes, jack_tolerance) in [(80, 1e-3), (160, 2e-5)] {
        let settings = StructureSettings {
            modes,
            damping: ModalDamping::Ratio(0.0),
            steps_per_contact: 100.0,
            ..Default::default()
        };
        let model = StructureModel::new(&fact, &mass, &loads, readings, settings).unwrap();
        let probes = model.probes(samples as f64 * ts, rate).unwrap();
        let stream = model.stream(&arrivals, &places, &probes, (samples as f64 * ts, None)).unwrap();
        let [p_max, jack, acceleration] = compare(&stream, &full, (last, every));
        eprintln!("{modes} modes: P_max {p_max:.2e}, jack force {jack:.2e}, acceleration {acceleration:.2e} over {last} samples");
        assert!(jack < jack_tolerance, "{jack:e}");
        // P_max: 9.0e-6 and 4.6e-6; without the cross static correction of the two points
        // 1 cm apart, 6.7e-5 and 6.0e-5.
        assert!(p_max < 2e-5, "{p_max:e}");
        // The acceleration differs by 2.3e-3 (80 modes) and 1.8e-3 (160), barely shrinking:
        // not the truncation's alone, but also the reference's own, whose modes with ωΔt ≫ 1
        // Newmark's rule answers with an undamped high-frequency acceleration the modal
        // model leaves out.
        assert!(acceleration < 3e-3, "{acceleration:e}");
    }
}

/// The stream's P_max, contacts and overlap against the full model's, and the largest
/// difference of its jack force and acceleration samples from the reference's up to sample
/// `last` (steps of `every` per sample), relative to the reference's largest |value|.
fn compare(
    stream: &coupled::reduced::stream::StreamResponse,
    full: &FullRun,
    (last, every): (usize, usize),
) -> [f64; 3] {
    use coupled::reduced::ChannelKind;
    assert!(stream.lumps.iter().all(|l| l.contacts == 1 && l.overlapped), "{:?}", stream.lumps);
    assert!(stream.joint_steps > 0 && stream.unconverged_steps == 0);
    let p_max = |j: usize| {
        let p_ref = full.forces[j].iter().copied().fold(0.0, f64::max);
        (stream.lumps[j].force_max / p_ref - 1.0).abs()
    };
    let [jack, acceleration] = [
        (ChannelKind::JackForce { jack: 0 }, &full.reading),
        (ChannelKind::Acceleration { sensor: 0 }, &full.acceleration),
    ]
    .map(|(kind, reference)| {
        let channel = stream.signals.channel(kind).unwrap();
        let scale = reference.iter().fold(0.0, |m: f64, x| m.max(x.abs()));
        (1..=last).map(|k| (channel.samples[k] - reference[k * every - 1]).abs() / scale).fold(0.0, f64::max)
    });
    [p_max(0).max(p_max(1)), jack, acceleration]
}
