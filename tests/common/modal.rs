//! An independent modal model of a plate held at its four corners and struck at its centre,
//! sharing no code with the FE or the transient model: Ritz modes from even Legendre
//! polynomials, and the sphere on them integrated by the classical Runge-Kutta rule with
//! each contact's start and end located by bisection within the step.
//!
//! The trial functions are ψ_ab(ξ, η) = P_a(ξ) P_b(η) - 1 for even a, b ≤ 2n, not both zero,
//! with ξ = 2x/L - 1 and η = 2z/B - 1: each vanishes at the four corners (P_k(±1) = 1 for
//! even k), is free elsewhere, and is symmetric about both centrelines, the only modes a
//! load at the centre excites. Mass and stiffness (Kirchhoff's energy, with the Poisson and
//! twisting terms) are integrated by 40-point Gauss-Legendre, exact for these degrees.

use super::reference::{Ball, Sheet};
use nalgebra::{DMatrix, DVector, SymmetricEigen};
use std::f64::consts::PI;

/// Gauss-Legendre nodes and weights on [-1, 1] by Newton's iteration on P_n.
fn gauss(n: usize) -> Vec<(f64, f64)> {
    (1..=n)
        .map(|i| {
            let mut x = (PI * (i as f64 - 0.25) / (n as f64 + 0.5)).cos();
            for _ in 0..100 {
                let (p, dp, _) = legendre(n, x);
                let step = p / dp;
                x -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            let dp = legendre(n, x).1;
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// P_k(x), P_k'(x) and P_k''(x) by the three-term recurrences.
fn legendre(k: usize, x: f64) -> (f64, f64, f64) {
    let (mut p, mut dp, mut ddp) = ([1.0, x], [0.0, 1.0], [0.0, 0.0]);
    if k == 0 {
        return (1.0, 0.0, 0.0);
    }
    for j in 1..k {
        let jf = j as f64;
        let next = ((2.0 * jf + 1.0) * x * p[1] - jf * p[0]) / (jf + 1.0);
        let dnext = dp[0] + (2.0 * jf + 1.0) * p[1];
        let ddnext = ddp[0] + (2.0 * jf + 1.0) * dp[1];
        (p, dp, ddp) = ([p[1], next], [dp[1], dnext], [ddp[1], ddnext]);
    }
    (p[1], dp[1], ddp[1])
}

/// The centre-symmetric modes of the corner-held `plate` from polynomials of degree up to 2n:
/// each (ω, Φ(centre)) with the mode normalised to unit modal mass.
pub fn centre_modes(plate: Sheet, n: usize) -> Vec<(f64, f64)> {
    let (l, b, h, e, nu, rho) = plate;
    let d = e * h.powi(3) / (12.0 * (1.0 - nu * nu));
    let (gx, gz) = (2.0 / l, 2.0 / b);
    let q = gauss(40);
    let degrees: Vec<usize> = (0..=n).map(|i| 2 * i).collect();
    // Per degree and quadrature node: P, P', P''.
    let tab: Vec<Vec<(f64, f64, f64)>> =
        degrees.iter().map(|&k| q.iter().map(|&(x, _)| legendre(k, x)).collect()).collect();
    let basis: Vec<(usize, usize)> =
        (0..=n).flat_map(|i| (0..=n).map(move |j| (i, j))).filter(|&(i, j)| i + j > 0).collect();
    let m = basis.len();
    let (mut kk, mut mm) = (DMatrix::<f64>::zeros(m, m), DMatrix::<f64>::zeros(m, m));
    for (u, v) in q.iter().enumerate().flat_map(|(u, _)| (0..q.len()).map(move |v| (u, v))) {
        let w = q[u].1 * q[v].1 * l * b / 4.0;
        // ψ, ψ_xx, ψ_zz, ψ_xz of every trial function at this node.
        let f: Vec<[f64; 4]> = basis
            .iter()
            .map(|&(i, j)| {
                let ((p, dp, ddp), (r, dr, ddr)) = (tab[i][u], tab[j][v]);
                [p * r - 1.0, gx * gx * ddp * r, gz * gz * p * ddr, gx * gz * dp * dr]
            })
            .collect();
        for (s, fs) in f.iter().enumerate() {
            for (t, ft) in f.iter().enumerate().skip(s) {
                let mass = rho * h * fs[0] * ft[0];
                let bend = fs[1] * ft[1] + fs[2] * ft[2] + nu * (fs[1] * ft[2] + fs[2] * ft[1]);
                let stiff = d * (bend + 2.0 * (1.0 - nu) * fs[3] * ft[3]);
                mm[(s, t)] += w * mass;
                kk[(s, t)] += w * stiff;
            }
        }
    }
    mm.fill_lower_triangle_with_upper_triangle();
    kk.fill_lower_triangle_with_upper_triangle();
    // K x = ω² M x through M = LLᵀ: (L⁻¹ K L⁻ᵀ) y = ω² y, x = L⁻ᵀ y (unit modal mass).
    let chol = mm.cholesky().expect("the mass matrix is positive definite");
    let linv = chol.l().try_inverse().expect("L is invertible");
    let a: DMatrix<f64> = &linv * &kk * linv.transpose();
    let eig = SymmetricEigen::new((&a + a.transpose()) * 0.5);
    let centre: DVector<f64> = DVector::from_iterator(
        m,
        basis.iter().map(|&(i, j)| legendre(degrees[i], 0.0).0 * legendre(degrees[j], 0.0).0 - 1.0),
    );
    let x = linv.transpose() * &eig.eigenvectors;
    (0..m).map(|k| (eig.eigenvalues[k].sqrt(), x.column(k).dot(&centre))).collect()
}

/// The state's rate for the sphere of `mass` and the `modes` under the contact force `f`:
/// (u̇, -f/m, q̇ₖ, -ωₖ²qₖ + Φₖf).
fn rate(modes: &[(f64, f64)], mass: f64, f: f64, y: &[f64]) -> Vec<f64> {
    let n = modes.len();
    let mut r = vec![0.0; y.len()];
    r[0] = y[1];
    r[1] = -f / mass;
    for (i, &(w, phi)) in modes.iter().enumerate() {
        r[2 + i] = y[2 + n + i];
        r[2 + n + i] = -w * w * y[2 + i] + phi * f;
    }
    r
}

/// One classical Runge-Kutta step of `dt` from `y` for ẏ = `rate`(y).
fn rk4(rate: impl Fn(&[f64]) -> Vec<f64>, y: &[f64], dt: f64) -> Vec<f64> {
    let add = |a: &[f64], b: &[f64], s: f64| a.iter().zip(b).map(|(x, r)| x + s * r).collect::<Vec<_>>();
    let k1 = rate(y);
    let k2 = rate(&add(y, &k1, dt / 2.0));
    let k3 = rate(&add(y, &k2, dt / 2.0));
    let k4 = rate(&add(y, &k3, dt));
    (0..y.len()).map(|i| y[i] + dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])).collect()
}

/// One contact of the modal model: start and end (s), peak force (N), largest compression (m).
#[derive(Debug, Clone, Copy)]
pub struct Contact {
    pub start: f64,
    pub end: f64,
    pub peak_force: f64,
    pub compression_max: f64,
}

/// The sphere and the modes: the state is (u, u̇, q₁.., q̇₁..), u the sphere's travel into
/// the plate, q the modal coordinates; the contact compresses δ = u - Σ Φ_k q_k.
struct Struck<'a> {
    modes: &'a [(f64, f64)],
    mass: f64,
    k: f64,
    /// Flores's 8(1 - e)/(5e) (eqs. 1-2).
    damping: f64,
    /// The approach velocity δ̇⁻ of the contact under way (Flores et al. scale each contact's
    /// damping by its own): v₀ for the first, δ̇ at the located touch for a later one.
    approach: std::cell::Cell<f64>,
}

impl Struck<'_> {
    /// δ and δ̇ of state `y`.
    fn compression(&self, y: &[f64]) -> (f64, f64) {
        let n = self.modes.len();
        let (w, wd) = self
            .modes
            .iter()
            .enumerate()
            .fold((0.0, 0.0), |(w, wd), (i, &(_, phi))| (w + phi * y[2 + i], wd + phi * y[2 + n + i]));
        (y[0] - w, y[1] - wd)
    }

    /// The Flores force P = Kδ^{3/2}(1 + 8(1-e)/(5e) δ̇/δ̇⁻), never negative, zero apart.
    fn force(&self, y: &[f64]) -> f64 {
        let (d, dd) = self.compression(y);
        if d > 0.0 {
            (self.k * d * d.sqrt() * (1.0 + self.damping * dd / self.approach.get())).max(0.0)
        } else {
            0.0
        }
    }

    fn rate(&self, y: &[f64]) -> Vec<f64> {
        rate(self.modes, self.mass, self.force(y), y)
    }

    /// One classical Runge-Kutta step of `dt` from `y`.
    fn step(&self, y: &[f64], dt: f64) -> Vec<f64> {
        rk4(|z| self.rate(z), y, dt)
    }

    /// The largest plate displacement at the centre its free vibration can reach:
    /// Σ |Φ_k| √(q_k² + (q̇_k/ω_k)²).
    fn reach(&self, y: &[f64]) -> f64 {
        let n = self.modes.len();
        self.modes.iter().enumerate().map(|(i, &(w, phi))| phi.abs() * y[2 + i].hypot(y[2 + n + i] / w)).sum()
    }
}

/// The contacts of `ball` striking the corner-held `plate` at its centre at `v0` with the
/// Flores law of restitution `e`, on `modes` ([`centre_modes`]), time step `dt`. A step in
/// which the compression changes sign is cut at the crossing, found by bisection on a
/// shorter step from its start; the run ends once the sphere, flying back, is farther than
/// the plate's free vibration can reach (no gravity, as in the model), or after one second.
pub fn impact(modes: &[(f64, f64)], ball: Ball, plate: Sheet, e: f64, v0: f64, dt: f64) -> Vec<Contact> {
    let s = Struck {
        modes,
        mass: ball.0 * 4.0 / 3.0 * PI * ball.3.powi(3),
        k: super::reference::hertz_stiffness(ball, plate),
        damping: 8.0 * (1.0 - e) / (5.0 * e),
        approach: std::cell::Cell::new(v0),
    };
    let mut y = vec![0.0; 2 + 2 * modes.len()];
    y[1] = v0;
    let (mut t, mut contacts) = (0.0, Vec::<Contact>::new());
    let mut open: Option<Contact> = None;
    while t < 1.0 {
        let mut next = s.step(&y, dt);
        let mut h = dt;
        let inside = |z: &[f64]| s.compression(z).0 > 0.0;
        if inside(&next) != inside(&y) {
            // The crossing: the shortest step that changes the side, to 1e-12 of dt.
            let (mut lo, mut hi) = (0.0, dt);
            while hi - lo > 1e-12 * dt {
                let mid = 0.5 * (lo + hi);
                if inside(&s.step(&y, mid)) != inside(&y) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            (h, next) = (hi, s.step(&y, hi));
        }
        (t, y) = (t + h, next);
        let (d, _) = s.compression(&y);
        match (&mut open, d > 0.0) {
            (None, true) => {
                if !contacts.is_empty() {
                    s.approach.set(s.compression(&y).1);
                }
                open = Some(Contact { start: t, end: t, peak_force: 0.0, compression_max: 0.0 });
            }
            (Some(c), true) => {
                c.peak_force = c.peak_force.max(s.force(&y));
                c.compression_max = c.compression_max.max(d);
            }
            (Some(c), false) => {
                c.end = t;
                contacts.push(*c);
                open = None;
            }
            (None, false) => {
                if y[1] < 0.0 && y[0] < -s.reach(&y) {
                    break;
                }
            }
        }
    }
    contacts
}

/// One contact of the modal model under Hertz's law with the static correction: start, end
/// (s), peak force (N) and impulse m(u̇ before - u̇ after) (N·s).
#[derive(Debug, Clone, Copy)]
pub struct HertzContact {
    pub start: f64,
    pub end: f64,
    pub peak_force: f64,
    pub impulse: f64,
}

/// The sphere on the modes plus the static correction c_res of the truncated ones: the
/// point deflection is Σ Φ_k q_k + c_res P, so under Hertz's law P = K(δ₀ - c_res P)^{3/2}
/// with δ₀ = u - Σ Φ_k q_k, one increasing function of P solved by Newton's method from
/// above (the truncated modes answer quasi-statically: their periods are far below the
/// contact time).
struct Corrected<'a> {
    modes: &'a [(f64, f64)],
    mass: f64,
    k: f64,
    c_res: f64,
}

impl Corrected<'_> {
    fn free_compression(&self, y: &[f64]) -> f64 {
        y[0] - self.modes.iter().enumerate().map(|(i, &(_, phi))| phi * y[2 + i]).sum::<f64>()
    }

    fn force(&self, y: &[f64]) -> f64 {
        let d0 = self.free_compression(y);
        if d0 <= 0.0 || self.c_res == 0.0 {
            return self.k * d0.max(0.0).powf(1.5);
        }
        // f(P) = P - K(δ₀ - cP)^{3/2} is increasing and convex where δ₀ - cP > 0: Newton from
        // P = δ₀/c·(1 - tiny) (f > 0 there) decreases monotonically to the root.
        let mut p = (self.k * d0.powf(1.5)).min(d0 / self.c_res);
        for _ in 0..100 {
            let d = (d0 - self.c_res * p).max(0.0);
            let f = p - self.k * d.powf(1.5);
            let df = 1.0 + 1.5 * self.k * self.c_res * d.sqrt();
            let next = p - f / df;
            if (next - p).abs() <= 1e-15 * p.abs() {
                return next;
            }
            p = next;
        }
        p
    }

    fn rate(&self, y: &[f64]) -> Vec<f64> {
        rate(self.modes, self.mass, self.force(y), y)
    }

    fn step(&self, y: &[f64], dt: f64) -> Vec<f64> {
        rk4(|z| self.rate(z), y, dt)
    }
}

/// The contacts of `ball` striking the corner-held `plate` at its centre at `v0` under
/// Hertz's law, on `modes` ([`centre_modes`]) with the truncated modes' static compliance
/// `c_res` at the centre, by classical Runge-Kutta steps of `dt` with each contact's ends
/// located by bisection within the step, up to `window` s (a contact the window cuts is left
/// out). The force is continuous with a continuous first derivative except at the contact's
/// ends, which the located steps put at step boundaries, so the rule keeps its fourth order.
pub fn hertz_impact(
    modes: &[(f64, f64)],
    c_res: f64,
    ball: Ball,
    plate: Sheet,
    v0: f64,
    dt: f64,
    window: f64,
) -> Vec<HertzContact> {
    let s = Corrected {
        modes,
        mass: ball.0 * 4.0 / 3.0 * PI * ball.3.powi(3),
        k: super::reference::hertz_stiffness(ball, plate),
        c_res,
    };
    let mut y = vec![0.0; 2 + 2 * modes.len()];
    y[1] = v0;
    let (mut t, mut contacts) = (0.0, Vec::<HertzContact>::new());
    let mut open: Option<(HertzContact, f64)> = None;
    let inside = |z: &[f64]| s.free_compression(z) > 0.0;
    while t < window {
        let mut next = s.step(&y, dt);
        let mut h = dt;
        // Leaving the touch point (δ₀ = 0, rising) is not a crossing.
        let was = inside(&y) || (t == 0.0);
        if inside(&next) != was {
            let (mut lo, mut hi) = (0.0, dt);
            while hi - lo > 1e-13 * dt {
                let mid = 0.5 * (lo + hi);
                if inside(&s.step(&y, mid)) != was {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            (h, next) = (hi, s.step(&y, hi));
        }
        (t, y) = (t + h, next);
        match (&mut open, inside(&y)) {
            (None, true) => {
                let start = if contacts.is_empty() { 0.0 } else { t };
                let v_in = if contacts.is_empty() { v0 } else { y[1] };
                open = Some((HertzContact { start, end: t, peak_force: s.force(&y), impulse: 0.0 }, v_in));
            }
            (Some((c, _)), true) => c.peak_force = c.peak_force.max(s.force(&y)),
            (Some((c, v_in)), false) => {
                c.end = t;
                c.impulse = s.mass * (*v_in - y[1]);
                contacts.push(*c);
                open = None;
            }
            (None, false) => {}
        }
    }
    contacts
}
