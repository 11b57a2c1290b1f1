//! A caving stream on the reduced plate: many lumps striking one plate, one after another and
//! at times together, recorded as one continuous signal.
//!
//! **Superposition.** The plate is linear, so its modal state (qᵢ, q̇ᵢ) carries every earlier
//! lump's response: between contacts each mode is propagated exactly
//! ([`super::signals::free_map`]), sample by sample ([`super::window`]), and a lump that
//! arrives finds the plate moving. It touches at its arrival, the sphere at the plate's
//! deflection there (δ = 0, with δ = u - w(p) as in one impact), and from then on it is
//! stepped as [`super::ReducedModel::impact`] steps one impact: Newmark's rule on every mode
//! while a force acts, the exact map over a step that starts free, the contact law solved at
//! each step's end, the truncated modes as the static correction C_res(p)P.
//!
//! **Simultaneous contacts.** While K lumps are in contact the step-end forces are coupled:
//! lump j's compression is δⱼ = d₀ⱼ - Σₖ Gⱼₖ Pₖ - Δt²Pⱼ/(4mⱼ), with the modes' step
//! flexibility Gⱼₖ = Σᵢ hᵢφᵢ(pⱼ)φᵢ(pₖ) (hᵢ = 1/(ωᵢ² + 4ζᵢωᵢ/Δt + 4/Δt²), Newmark's step-end
//! deflection per unit force) plus C_res(pⱼ) on the diagonal. Each law's force is monotone in
//! its own δ and G is positive semi-definite, so the joint solve by nonlinear Gauss-Seidel
//! (each lump's scalar law solve, [`crate::transient::contact_force_after`], with the others'
//! forces held) converges (Ortega & Rheinboldt 1970, §13.4, for monotone systems with a
//! diagonally positive symmetric coupling); with one lump it is the single impact's solve.
//! The cross term of the static correction, N(pⱼ)ᵀRN(pₖ), is left out: R is kept only in
//! element blocks. Since R is positive semi-definite it is at most √(C_res(pⱼ)C_res(pₖ))
//! (Cauchy-Schwarz), and the stream reports that bound against the static compliance.
//!
//! **A lump leaves** when it provably makes no further contact within one impact's window
//! after its touch, under the plate's free motion: no force, and the sphere's free flight
//! u + u̇τ + gτ²/2 over the rest of the window stays below -Σᵢ|φᵢ(p)|Aᵢ, under which no later
//! free deflection at p reaches ([`super::target`]); or at the window's end, where one
//! impact stops following it too. A lump under gravity that would come back after its window
//! is not followed back, as in one impact; nor is a departed sphere checked against the
//! plate's motion from later lumps: it has fallen away.
//!
//! **Time grid.** Arrivals are placed on the model's sample grid (rounded to the nearest
//! sample, within T_s/2), so that every contact starts, as one impact's does, at a sample;
//! the contact step is T_s/m with m from the stiffest lump in contact
//! ([`super::ReducedModel::impact_with`]'s rule).

use super::impact::{at_point, channel_row};
use super::signals::{dot, FreeMaps, Probes, Signals};
use super::target::ChannelRow;
use super::window::free_window;
use super::{Correction, ReducedModel};
use crate::error::ModelError;
use crate::transient::{approach_velocity, contact_force_after, Striker};
use serde::Serialize;
use std::collections::HashMap;

/// A lump of the stream: its sphere and law, its arrival and where it strikes.
#[derive(Debug, Clone)]
pub struct Arrival {
    /// Its first touch, s from the stream's start.
    pub time: f64,
    /// The sphere, its law and speed.
    pub striker: Striker,
    /// The struck point (x, z), m.
    pub x: f64,
    /// See `x`.
    pub z: f64,
}

/// What happened to one lump.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LumpResponse {
    /// The sample of its first touch (its arrival on the sample grid).
    pub sample: usize,
    /// Contacts it made.
    pub contacts: usize,
    /// Duration of its first contact, s, to the contact step.
    pub contact_time: f64,
    /// Largest contact force, N.
    pub force_max: f64,
    /// Largest compression, m.
    pub compression_max: f64,
    /// Whether another lump was in contact in one of its contact steps.
    pub overlapped: bool,
}

/// The stream's continuous signals and what each lump did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StreamResponse {
    /// The channels of the probes, every sample of the stream.
    pub signals: Signals,
    /// One per lump that touched before the stream's last sample, in arrival order.
    pub lumps: Vec<LumpResponse>,
    /// Contact steps taken (at the contact step, between the samples).
    pub steps: usize,
    /// Contact steps taken with two or more lumps in contact.
    pub joint_steps: usize,
    /// Joint steps whose Gauss-Seidel solve had not converged to 1e-12 in its iterations.
    pub unconverged_steps: usize,
    /// The left-out cross static correction's bound √(C_res(pⱼ)C_res(pₖ)) over the smaller
    /// static compliance of the two points, largest over the pairs in contact together (0
    /// when none were).
    pub cross_residual_bound: f64,
}

/// Most Gauss-Seidel sweeps of a joint solve.
const SWEEPS: usize = 200;

/// A lump while it is followed.
struct Active {
    index: usize,
    striker: Striker,
    phi: Vec<f64>,
    c_res: f64,
    static_compliance: f64,
    /// Its direct term Dⱼ in every channel.
    d: Vec<f64>,
    every: usize,
    /// Sphere displacement toward the plate (from the stream's datum), velocity, acceleration.
    u: f64,
    v: f64,
    a: f64,
    dmax: f64,
    approach: f64,
    force: f64,
    /// (δ, δ̇) at the last step end.
    last: (f64, f64),
    /// The static correction's trapezoidal velocity at the step end and in the prediction.
    res_v: f64,
    res_vh: f64,
    touched: usize,
    steps: usize,
    /// Time since the touch, s.
    time: f64,
    /// When the first contact opened (the start of its first step with a force), s.
    opened: Option<f64>,
    response: LumpResponse,
}

/// The step maps of one step Δt = T_s/m: Newmark's, the exact one, and hᵢ.
struct StepMaps {
    dt: f64,
    newmark: FreeMaps,
    exact: FreeMaps,
    h: Vec<f64>,
}

impl ReducedModel {
    /// The continuous signals of `probes` over `duration` seconds of the stream `arrivals`
    /// (in order of time; see the module). The probes' window is the longest a lump is
    /// followed after its touch.
    pub fn stream(&self, arrivals: &[Arrival], probes: &Probes, duration: f64) -> Result<StreamResponse, ModelError> {
        if self.settings.correction != Correction::Static {
            return Err(ModelError::Missing(
                "a stream carries the truncated modes as the static correction; set correction = \"static\"".into(),
            ));
        }
        let rate = probes.spec.rate_hz;
        let total = (duration * rate - 1e-9).ceil().max(1.0) as usize;
        let mut run = Run::new(self, probes, total);
        let mut next = 0;
        let mut k = 0;
        while k + 1 < total {
            while next < arrivals.len() && sample_of(arrivals[next].time, rate) <= k {
                run.admit(next, &arrivals[next], k)?;
                next += 1;
            }
            if run.active.is_empty() {
                let target = arrivals.get(next).map_or(total - 1, |a| sample_of(a.time, rate).min(total - 1));
                run.free(target - k);
                k = target;
            } else {
                run.contact_interval();
                k += 1;
                run.retire(k);
            }
        }
        Ok(run.finish())
    }
}

/// The sample an arrival at `time` falls on.
fn sample_of(time: f64, rate: f64) -> usize {
    (time * rate).round().max(0.0) as usize
}

/// The stream under way.
struct Run<'a> {
    model: &'a ReducedModel,
    probes: &'a Probes,
    rows: Vec<ChannelRow>,
    q: Vec<f64>,
    v: Vec<f64>,
    out: Vec<Vec<f64>>,
    active: Vec<Active>,
    done: Vec<(usize, LumpResponse)>,
    maps: HashMap<usize, StepMaps>,
    window_samples: usize,
    steps: usize,
    joint_steps: usize,
    unconverged_steps: usize,
    cross_residual_bound: f64,
    scratch: Scratch,
}

impl<'a> Run<'a> {
    fn new(model: &'a ReducedModel, probes: &'a Probes, total: usize) -> Self {
        let n = model.omega.len();
        let rows =
            probes.rows.iter().map(|r| ChannelRow { a: nonzero(&r.a), b: nonzero(&r.b), d: 0.0 }).collect::<Vec<_>>();
        let mut out: Vec<Vec<f64>> = rows.iter().map(|_| Vec::with_capacity(total)).collect();
        for o in &mut out {
            o.push(0.0);
        }
        Self {
            model,
            probes,
            rows,
            q: vec![0.0; n],
            v: vec![0.0; n],
            out,
            active: Vec::new(),
            done: Vec::new(),
            maps: HashMap::new(),
            window_samples: probes.spec.samples(),
            steps: 0,
            joint_steps: 0,
            unconverged_steps: 0,
            cross_residual_bound: 0.0,
            scratch: Scratch::default(),
        }
    }

    /// Lump `index` touches at sample `k`: the sphere at the plate's deflection there.
    fn admit(&mut self, index: usize, a: &Arrival, k: usize) -> Result<(), ModelError> {
        let m = self.model;
        let pt = m.point(a.x, a.z)?;
        let zeta = m.settings.damping();
        let field_at_p: Vec<f64> = self.probes.fields.iter().map(|f| at_point(&pt, f)).collect();
        let d = self
            .probes
            .rows
            .iter()
            .map(|r| channel_row(r, &pt, &field_at_p, None, (pt.c_res, zeta), &pt.phi).d)
            .collect();
        let ts = self.probes.spec.interval();
        let every = (ts / (a.striker.hertz_time() / m.settings.steps_per_contact)).ceil().max(1.0) as usize;
        let static_compliance = super::modal_compliance(&pt.phi, &m.omega) + pt.c_res;
        let (w, wv) = (dot(&pt.phi, &self.q), dot(&pt.phi, &self.v));
        self.active.push(Active {
            index,
            striker: a.striker,
            c_res: pt.c_res,
            static_compliance,
            phi: pt.phi,
            d,
            every,
            u: w,
            v: a.striker.velocity,
            a: a.striker.gravity,
            dmax: 0.0,
            approach: a.striker.velocity,
            force: 0.0,
            last: (0.0, a.striker.velocity - wv),
            res_v: 0.0,
            res_vh: 0.0,
            touched: k,
            steps: 0,
            time: 0.0,
            opened: None,
            response: LumpResponse {
                sample: k,
                contacts: 0,
                contact_time: 0.0,
                force_max: 0.0,
                compression_max: 0.0,
                overlapped: false,
            },
        });
        Ok(())
    }

    /// `count` samples of free vibration from the current sample.
    fn free(&mut self, count: usize) {
        if count == 0 {
            return;
        }
        let m = self.model;
        let maps = [self.probes.block_maps.modes()];
        free_window(m.simd, &maps, &self.q, &self.v, &self.rows, &mut self.out, count);
        let zeta = m.settings.damping();
        let tau = count as f64 * self.probes.spec.interval();
        for (i, &w) in m.omega.iter().enumerate() {
            let f = super::free_map(w, zeta.at(w), tau);
            let (q, v) = (self.q[i], self.v[i]);
            self.q[i] = f[0] * q + f[1] * v;
            self.v[i] = f[2] * q + f[3] * v;
        }
    }

    /// One sample interval of contact steps, and the sample at its end; where no lump can
    /// touch within it, the interval in one exact step.
    fn contact_interval(&mut self) {
        if self.clear_interval() {
            return self.free_interval();
        }
        let every = self.active.iter().map(|a| a.every).max().unwrap_or(1);
        let (model, probes) = (self.model, self.probes);
        let maps = self.maps.entry(every).or_insert_with(|| step_maps(model, probes, every));
        let g = flexibility(&self.active, &maps.h);
        self.steps += every;
        for _ in 0..every {
            if !step(&mut self.active, &mut self.q, &mut self.v, maps, &g, &mut self.scratch) {
                self.unconverged_steps += 1;
            }
            let in_contact: Vec<usize> = (0..self.active.len()).filter(|&j| self.active[j].force > 0.0).collect();
            if in_contact.len() > 1 {
                self.joint_steps += 1;
                for (x, &j) in in_contact.iter().enumerate() {
                    self.active[j].response.overlapped = true;
                    for &k in &in_contact[x + 1..] {
                        let (a, b) = (&self.active[j], &self.active[k]);
                        let bound = (a.c_res * b.c_res).sqrt() / a.static_compliance.min(b.static_compliance);
                        self.cross_residual_bound = self.cross_residual_bound.max(bound);
                    }
                }
            }
        }
        for (c, (row, o)) in self.rows.iter().zip(self.out.iter_mut()).enumerate() {
            let a = row.a.as_ref().map_or(0.0, |a| dot(a, &self.q));
            let b = row.b.as_ref().map_or(0.0, |b| dot(b, &self.v));
            let direct: f64 = self.active.iter().map(|l| l.d[c] * l.force).sum();
            o.push(a + b + direct);
        }
    }

    /// Whether no lump is in contact and none can touch within the next sample interval:
    /// each sphere's flight over it stays below the lowest the plate's free deflection at its
    /// point can reach in it, the larger of -Σᵢ|φᵢ(p)|Aᵢ (ever) and w(p) - T_s Σᵢ|φᵢ(p)|ωᵢAᵢ
    /// (in T_s at the largest speed |ẇ(p)| can have).
    fn clear_interval(&self) -> bool {
        let ts = self.probes.spec.interval();
        let (q, v, omega) = (&self.q, &self.v, &self.model.omega);
        self.active.iter().all(|l| {
            if l.force != 0.0 {
                return false;
            }
            let (mut ever, mut speed) = (0.0, 0.0);
            for i in 0..omega.len() {
                let a = l.phi[i].abs() * (q[i] * q[i] + (v[i] / omega[i]).powi(2)).sqrt();
                ever += a;
                speed += a * omega[i];
            }
            l.highest(ts) < (-ever).max(dot(&l.phi, q) - ts * speed)
        })
    }

    /// A sample interval free of force: every mode by its exact map over T_s, every sphere on
    /// its flight (which Newmark's rule follows exactly under a constant body force), and
    /// the sample at its end.
    fn free_interval(&mut self) {
        let ts = self.probes.spec.interval();
        let map = self.probes.step_map(1);
        let w = &mut self.scratch;
        w.qh.resize(self.q.len(), 0.0);
        w.vh.resize(self.q.len(), 0.0);
        map.apply(&self.q, &self.v, &mut w.qh, &mut w.vh);
        std::mem::swap(&mut self.q, &mut w.qh);
        std::mem::swap(&mut self.v, &mut w.vh);
        for l in &mut self.active {
            let g = l.striker.gravity;
            l.u += l.v * ts + 0.5 * g * ts * ts;
            l.v += g * ts;
            l.a = g;
            l.res_v = 0.0;
            l.time += ts;
            l.last = (l.u - dot(&l.phi, &self.q), l.v - dot(&l.phi, &self.v));
        }
        for (row, o) in self.rows.iter().zip(self.out.iter_mut()) {
            let a = row.a.as_ref().map_or(0.0, |a| dot(a, &self.q));
            let b = row.b.as_ref().map_or(0.0, |b| dot(b, &self.v));
            o.push(a + b);
        }
    }

    /// Lets go of every lump that has left for good at sample `k`, or whose window has ended.
    fn retire(&mut self, k: usize) {
        let ts = self.probes.spec.interval();
        let mut kept = Vec::with_capacity(self.active.len());
        for l in std::mem::take(&mut self.active) {
            let reach = reach(&l.phi, &self.q, &self.v, &self.model.omega);
            let rest = self.window_samples.saturating_sub(k - l.touched) as f64 * ts;
            let left = l.force == 0.0 && l.steps > 0 && l.highest(rest) + reach < 0.0;
            if left || k - l.touched >= self.window_samples {
                self.done.push(l.response_of());
            } else {
                kept.push(l);
            }
        }
        self.active = kept;
    }

    /// The signals and every lump's response, in arrival order.
    fn finish(mut self) -> StreamResponse {
        for l in std::mem::take(&mut self.active) {
            self.done.push(l.response_of());
        }
        self.done.sort_by_key(|r| r.0);
        let lumps = self.done.into_iter().map(|(_, r)| r).collect();
        let kinds = self.probes.kinds();
        let channels =
            kinds.into_iter().zip(self.out).map(|(kind, samples)| super::Channel { kind, samples }).collect();
        StreamResponse {
            signals: Signals { rate_hz: self.probes.spec.rate_hz, channels },
            lumps,
            steps: self.steps,
            joint_steps: self.joint_steps,
            unconverged_steps: self.unconverged_steps,
            cross_residual_bound: self.cross_residual_bound,
        }
    }
}

impl Active {
    fn response_of(self) -> (usize, LumpResponse) {
        (self.index, self.response)
    }
}

/// A row with its zero entries all zero: None.
fn nonzero(x: &[f64]) -> Option<Vec<f64>> {
    x.iter().any(|&x| x != 0.0).then(|| x.to_vec())
}

/// The maps of the step T_s/`every`.
fn step_maps(model: &ReducedModel, probes: &Probes, every: usize) -> StepMaps {
    let dt = probes.spec.interval() / every as f64;
    let zeta = model.settings.damping();
    let omega = &model.omega;
    StepMaps {
        dt,
        newmark: FreeMaps::newmark(omega, zeta, dt),
        exact: probes.step_map(every),
        h: omega.iter().map(|&w| 1.0 / (w * w + 4.0 * zeta.at(w) * w / dt + 4.0 / (dt * dt))).collect(),
    }
}

/// Gⱼₖ = Σᵢ hᵢφᵢ(pⱼ)φᵢ(pₖ) + δⱼₖC_res(pⱼ) over the lumps followed, row-major.
fn flexibility(active: &[Active], h: &[f64]) -> Vec<f64> {
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
struct Scratch {
    /// Σⱼφᵢ(pⱼ)Pⱼ at the step's start, then at its end.
    force: Vec<f64>,
    qh: Vec<f64>,
    vh: Vec<f64>,
    /// Per lump: d₀, d₁, r₀, r₁, û, v̂ (module docs of [`step`]).
    free: Vec<[f64; 6]>,
    forces: Vec<f64>,
    approach: Vec<f64>,
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
fn step(active: &mut [Active], q: &mut [f64], v: &mut [f64], maps: &StepMaps, g: &[f64], w: &mut Scratch) -> bool {
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
        let (wp, vp) = (dot(&l.phi, &w.qh), dot(&l.phi, &w.vh) + l.res_vh);
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
        l.res_v = l.res_vh + c1 * l.c_res * p;
        l.res_vh = if p == 0.0 { 0.0 } else { -c1 * l.c_res * p - l.res_v };
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

/// Σᵢ|φᵢ(p)|Aᵢ with Aᵢ = √(qᵢ² + q̇ᵢ²/ωᵢ²): no later free deflection at p reaches beyond it
/// ([`super::target`]).
fn reach(phi: &[f64], q: &[f64], v: &[f64], omega: &[f64]) -> f64 {
    (0..omega.len()).map(|i| phi[i].abs() * (q[i] * q[i] + (v[i] / omega[i]).powi(2)).sqrt()).sum()
}

impl Active {
    /// The highest the sphere's free flight u + u̇τ + gτ²/2 reaches over the next `tau`
    /// seconds: at one of its ends (g ≥ 0, a parabola opening upward, or a line).
    fn highest(&self, tau: f64) -> f64 {
        self.u.max(self.u + self.v * tau + 0.5 * self.striker.gravity * tau * tau)
    }

    /// The contact bookkeeping of a step ending with force `p`.
    fn record(&mut self, p: f64, dt: f64) {
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
