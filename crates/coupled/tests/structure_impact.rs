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

use coupled::reduced::structure::{StructureModel, StructureSettings};
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

/// The full model's step-end forces over `steps` steps of `dt`, and the spring's largest |force|.
fn full_newmark(
    fact: &Factorized<'_>,
    mass: &ShellMass,
    f: &[f64],
    spring: &Spring,
    dt: f64,
    steps: usize,
) -> (Vec<f64>, f64) {
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
    // Held DOFs have empty rows and columns: a unit diagonal keeps them at zero.
    let mut eff = &k + &m * (4.0 / (dt * dt));
    for d in 0..n {
        if eff[(d, d)] == 0.0 {
            eff[(d, d)] = 1.0;
        }
    }
    let chol = nalgebra::Cholesky::new(eff).expect("positive definite");
    let fv = DVector::from_column_slice(f);
    let gvec = chol.solve(&fv);
    let g = fv.dot(&gvec);
    let s = ball();
    let (mut u, mut v) = (DVector::zeros(n), DVector::zeros(n));
    let (mut x, mut xv, mut p) = (0.0, s.velocity, 0.0);
    // The spring's force k d̂·u at its node, d̂ its unit direction.
    let norm = spring.direction.iter().map(|d| d * d).sum::<f64>().sqrt();
    let mut coeff = DVector::zeros(n);
    for i in 0..3 {
        coeff[6 * spring.node + i] = spring.stiffness * spring.direction[i] / norm;
    }
    let (mut forces, mut spring_max) = (Vec::with_capacity(steps), 0.0f64);
    for _ in 0..steps {
        let rhs = &m * (&u * (4.0 / (dt * dt)) + &v * (4.0 / dt)) + &fv * p - &k * &u;
        let u_hat = chol.solve(&rhs);
        let x_hat = x + dt * xv - dt * dt / (4.0 * s.mass) * p;
        let d0 = x_hat - fv.dot(&u_hat);
        let c = g + dt * dt / (4.0 * s.mass);
        // P = K (d0 - cP)^{3/2}: monotone in P, bisected to rounding.
        let p_new = if d0 <= 0.0 {
            0.0
        } else {
            let (mut lo, mut hi) = (0.0, s.k * d0.powf(1.5));
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid < s.k * (d0 - c * mid).max(0.0).powf(1.5) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            0.5 * (lo + hi)
        };
        let u_new = u_hat + &gvec * p_new;
        v = (&u_new - &u) * (2.0 / dt) - &v;
        u = u_new;
        let x_new = x_hat - dt * dt / (4.0 * s.mass) * p_new;
        xv = 2.0 * (x_new - x) / dt - xv;
        x = x_new;
        p = p_new;
        forces.push(p);
        spring_max = spring_max.max(coeff.dot(&u).abs());
    }
    (forces, spring_max)
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
    let (reference, spring_ref) = full_newmark(&fact, &mass, &f, &spring, dt, steps);
    let p_ref = reference.iter().copied().fold(0.0, f64::max);
    let run = |modes: usize| {
        let settings = StructureSettings { modes, damping: ModalDamping::Ratio(0.0), steps_per_contact: 100.0 };
        let model = StructureModel::new(&fact, &mass, std::slice::from_ref(&f), &[vec![spring]], settings).unwrap();
        model.impact(&ball(), 0, window).unwrap()
    };
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
    let settings = StructureSettings { modes: 160, damping: ModalDamping::Ratio(0.0), steps_per_contact: 100.0 };
    let big = StructureModel::new(&fact, &mass, std::slice::from_ref(&f), &[vec![spring]], settings).unwrap();
    let (cut, direct) = (big.truncated(20).unwrap().impact(&ball(), 0, window).unwrap(), run(20));
    assert!((cut.outcome.force_max / direct.outcome.force_max - 1.0).abs() < 1e-9);
    assert!((cut.group_force_max[0] / direct.group_force_max[0] - 1.0).abs() < 1e-9);
    assert!(big.truncated(0).is_err() && big.truncated(161).is_err());
}
