//! One contact step of the lumps followed (the module docs of [`super`]): the modes'
//! prediction and end, the joint solve of the step-end forces, and the step flexibility that
//! couples them.

use super::{Active, Struck, SWEEPS};
use crate::reduced::signals::{dot, FreeMaps, Probes};
use crate::transient::{approach_velocity, contact_force_after};

/// The step maps of one step Δt = T_s/m: Newmark's, the exact one, and hᵢ.
pub(super) struct StepMaps {
    pub(super) dt: f64,
    pub(super) newmark: FreeMaps,
    pub(super) exact: FreeMaps,
    pub(super) h: Vec<f64>,
}

/// The maps of the step T_s/`every`.
pub(super) fn step_maps(model: &dyn Struck, probes: &Probes, every: usize) -> StepMaps {
    let dt = probes.spec.interval() / every as f64;
    let zeta = model.damping();
    let omega = model.omega();
    StepMaps {
        dt,
        newmark: FreeMaps::newmark(omega, zeta, dt),
        exact: probes.step_map(every),
        h: omega.iter().map(|&w| 1.0 / (w * w + 4.0 * zeta.at(w) * w / dt + 4.0 / (dt * dt))).collect(),
    }
}

/// Gⱼₖ = Σᵢ hᵢφᵢ(pⱼ)φᵢ(pₖ) + δⱼₖC_res(pⱼ) over the lumps followed, row-major (the cross
/// static corrections, where the model carries them, are added by the caller).
pub(super) fn flexibility(active: &[Active], h: &[f64]) -> Vec<f64> {
    let k = active.len();
    let mut g = vec![0.0; k * k];
    for j in 0..k {
        for l in j..k {
            let s: f64 = h.iter().zip(&active[j].phi).zip(&active[l].phi).map(|((h, a), b)| h * a * b).sum();
            g[j * k + l] = s;
            g[l * k + j] = s;
        }
        g[j * k + j] += active[j].c_res;
    }
    g
}

/// The per-step work arrays, kept between steps.
#[derive(Default)]
pub(super) struct Scratch {
    /// Σⱼφᵢ(pⱼ)Pⱼ at the step's start, then at its end.
    pub(super) force: Vec<f64>,
    pub(super) qh: Vec<f64>,
    pub(super) vh: Vec<f64>,
    /// Per lump: d₀, d₁, r₀, r₁, û, v̂ (module docs of [`step`]).
    pub(super) free: Vec<[f64; 6]>,
    pub(super) forces: Vec<f64>,
    pub(super) approach: Vec<f64>,
}

impl Scratch {
    /// Σⱼφᵢ(pⱼ)Pⱼ into `force` with the forces `p`.
    fn modal_force(&mut self, active: &[Active], p: impl Fn(usize, &Active) -> f64) {
        self.force.iter_mut().for_each(|f| *f = 0.0);
        for (j, l) in active.iter().enumerate() {
            let pj = p(j, l);
            if pj != 0.0 {
                for (fi, phi) in self.force.iter_mut().zip(&l.phi) {
                    *fi += phi * pj;
                }
            }
        }
    }
}

/// One contact step of every lump followed (module docs): the modes predicted from the
/// step's start (exactly if no force acts then, else by Newmark's rule with the start
/// forces), the step-end forces solved together, then modes, spheres and static corrections
/// committed. Newmark's rule for a sphere: û = u + Δt u̇ + Δt²/4 ü, v̂ = u̇ + Δt/2 ü, plus
/// gravity's Δt²/4 g and Δt/2 g; per lump the force-free compression d₀ and rate r₀ at the
/// step end and its own flexibilities d₁, r₁ (the sphere's and the plate's).
pub(super) fn step(
    active: &mut [Active],
    (q, v): (&mut [f64], &mut [f64]),
    maps: &StepMaps,
    (g, cross): (&[f64], Option<&[f64]>),
    w: &mut Scratch,
) -> bool {
    let (dt, n, k) = (maps.dt, q.len(), active.len());
    let c1 = 2.0 / dt;
    let free_start = active.iter().all(|l| l.force == 0.0);
    let [m0, m1, m2, m3] = if free_start { maps.exact.entries() } else { maps.newmark.entries() };
    w.force.resize(n, 0.0);
    w.qh.resize(n, 0.0);
    w.vh.resize(n, 0.0);
    w.modal_force(active, |_, l| l.force);
    predict([m0, m1, m2, m3], &maps.h, (q, v), &w.force, c1, (&mut w.qh, &mut w.vh));
    w.free.clear();
    for (j, l) in active.iter().enumerate() {
        let s = &l.striker;
        let (mut u_hat, mut v_hat) = (l.u + dt * l.v + 0.25 * dt * dt * l.a, l.v + 0.5 * dt * l.a);
        if s.gravity != 0.0 {
            u_hat += 0.25 * dt * dt * s.gravity;
            v_hat += 0.5 * dt * s.gravity;
        }
        let (wp, vp) = (dot(&l.phi, &w.qh), dot(&l.phi, &w.vh) + residual_rate(l, c1));
        let gjj = g[j * k + j];
        w.free.push([
            u_hat - wp,
            0.25 * dt * dt / s.mass + gjj,
            v_hat - vp,
            0.5 * dt / s.mass + c1 * gjj,
            u_hat,
            v_hat,
        ]);
    }
    let converged = solve(active, g, c1, w);
    let forces = std::mem::take(&mut w.forces);
    w.modal_force(active, |j, _| forces[j]);
    commit(&maps.h, (&w.qh, &w.vh), &w.force, c1, (q, v));
    for (j, l) in active.iter_mut().enumerate() {
        let [d0, d1, r0, r1, u_hat, v_hat] = w.free[j];
        let coupled: f64 = (0..k).filter(|&m| m != j).map(|m| g[j * k + m] * forces[m]).sum();
        let p = forces[j];
        let (delta, rate) = (d0 - coupled - d1 * p, r0 - c1 * coupled - r1 * p);
        let a_contact = -p / l.striker.mass;
        l.u = u_hat + 0.25 * dt * dt * a_contact;
        l.v = v_hat + 0.5 * dt * a_contact;
        l.a = if l.striker.gravity != 0.0 { l.striker.gravity + a_contact } else { a_contact };
        l.approach = w.approach[j];
        l.res_v = residual_rate(l, c1) + c1 * l.c_res * p;
        // Without cross terms (the plate's, or one lump followed) the others add nothing.
        l.w_cross = match cross {
            Some(c) => {
                let w_cross: f64 = (0..k).filter(|&m| m != j).map(|m| c[j * k + m] * forces[m]).sum();
                l.res_v += c1 * w_cross;
                w_cross
            }
            None => 0.0,
        };
        l.dmax = l.dmax.max(delta);
        l.last = (delta, rate);
        l.record(p, dt);
    }
    w.forces = forces;
    converged
}

/// (q̂, v̂) = M(q, q̇) + (h, (2/Δt)h)F per mode: the step's prediction from its start state
/// and start force F (every slice cut to the modes, so that the loop vectorizes).
fn predict(
    m: [&[f64]; 4],
    h: &[f64],
    (q, v): (&[f64], &[f64]),
    f: &[f64],
    c1: f64,
    (qh, vh): (&mut [f64], &mut [f64]),
) {
    let n = q.len();
    let (m0, m1, m2, m3, h, v, f) = (&m[0][..n], &m[1][..n], &m[2][..n], &m[3][..n], &h[..n], &v[..n], &f[..n]);
    let (qh, vh) = (&mut qh[..n], &mut vh[..n]);
    for i in 0..n {
        let hf = h[i] * f[i];
        qh[i] = m0[i] * q[i] + m1[i] * v[i] + hf;
        vh[i] = m2[i] * q[i] + m3[i] * v[i] + c1 * hf;
    }
}

/// (q, q̇) = (q̂, v̂) + (h, (2/Δt)h)F per mode: the step's end with its end force F.
fn commit(h: &[f64], (qh, vh): (&[f64], &[f64]), f: &[f64], c1: f64, (q, v): (&mut [f64], &mut [f64])) {
    let n = q.len();
    let (h, qh, vh, f, v) = (&h[..n], &qh[..n], &vh[..n], &f[..n], &mut v[..n]);
    for i in 0..n {
        let hf = h[i] * f[i];
        q[i] = qh[i] + hf;
        v[i] = vh[i] + c1 * hf;
    }
}

/// The static correction's velocity at the step's end before its end force, by the
/// trapezoidal rule (w₊ - w)(2/Δt) - v with this step's Δt, w = C_res P + Σₖ≠ⱼ RⱼₖPₖ the
/// correction at the lump's point: (2/Δt)w₊ is added once the forces are known; without a
/// load the correction is at rest (a static response to no load).
fn residual_rate(l: &Active, c1: f64) -> f64 {
    if l.force == 0.0 && l.w_cross == 0.0 {
        0.0
    } else {
        -c1 * l.c_res * l.force - c1 * l.w_cross - l.res_v
    }
}

/// The step-end forces of every lump followed into `w.forces`, solved together by nonlinear
/// Gauss-Seidel on δⱼ = d₀ⱼ - Σₖ≠ⱼ GⱼₖPₖ - d₁ⱼPⱼ (module docs), and each lump's approach
/// velocity into `w.approach`; false if the sweeps ran out before the forces settled.
fn solve(active: &[Active], g: &[f64], c1: f64, w: &mut Scratch) -> bool {
    let k = active.len();
    w.forces.clear();
    w.forces.extend(active.iter().map(|l| l.force));
    w.approach.clear();
    w.approach.extend(active.iter().map(|l| l.approach));
    let (p, approach) = (&mut w.forces, &mut w.approach);
    for _ in 0..SWEEPS {
        let mut change: f64 = 0.0;
        for j in 0..k {
            let l = &active[j];
            let s = &l.striker;
            let [d0, d1, r0, r1, ..] = w.free[j];
            let coupled: f64 = (0..k).filter(|&m| m != j).map(|m| g[j * k + m] * p[m]).sum();
            let (d0, r0) = (d0 - coupled, r0 - c1 * coupled);
            if l.force == 0.0 {
                approach[j] = approach_velocity(s.permanent_set(l.dmax), l.last, d0, r0).unwrap_or(l.approach);
            }
            let pj = contact_force_after(s, &s.state_in(l.dmax, approach[j]), d0, d1, r0, r1);
            change = change.max((pj - p[j]).abs());
            p[j] = pj;
        }
        let scale = p.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
        if k == 1 || change <= 1e-12 * scale {
            return true;
        }
    }
    false
}

impl Active {
    /// The highest the sphere's free flight u + u̇τ + gτ²/2 reaches over the next `tau`
    /// seconds: at one of its ends (g ≥ 0, a parabola opening upward, or a line).
    pub(super) fn highest(&self, tau: f64) -> f64 {
        self.u.max(self.u + self.v * tau + 0.5 * self.striker.gravity * tau * tau)
    }

    /// The compression δ_p at which its contact opens: the permanent set its law has left.
    pub(super) fn opens_at(&self) -> f64 {
        self.striker.permanent_set(self.dmax)
    }

    /// The contact bookkeeping of a step ending with force `p`.
    pub(super) fn record(&mut self, p: f64, dt: f64) {
        if p > 0.0 && self.force == 0.0 {
            self.response.contacts += 1;
            if self.opened.is_none() {
                self.opened = Some(self.time);
            }
        }
        self.time += dt;
        if p == 0.0 && self.force > 0.0 && self.response.contacts == 1 {
            self.response.contact_time = self.time - self.opened.unwrap_or(0.0);
        }
        self.force = p;
        self.steps += 1;
        self.response.force_max = self.response.force_max.max(p);
        self.response.compression_max = self.response.compression_max.max(self.last.0);
    }
}
