//! The reduced plate as a [`Target`] of the transient loop: N modes stepped by Newmark's
//! rule while a force acts, propagated exactly while none does, plus the static
//! correction of the truncated modes at the struck point.
//!
//! Mode i (mass-normalised) obeys q̈ᵢ + 2ζωᵢq̇ᵢ + ωᵢ²qᵢ = φᵢ(p)P. Newmark's average-acceleration
//! rule, with the acceleration at the step start taken from the equation of motion, is
//! (qᵢ, q̇ᵢ)ₙ₊₁ = Nᵢ(qᵢ, q̇ᵢ)ₙ + (γᵢ, (2/Δt)γᵢ)(Pₙ + Pₙ₊₁), with hᵢ = 1/(ωᵢ² + 4ζωᵢ/Δt + 4/Δt²),
//! γᵢ = hᵢφᵢ(p) and Nᵢ the rule's map of the free oscillator
//! ([`super::signals::newmark_map`]): affine in the step-end force, as the contact solve
//! needs, and with all modes and ζ = 0 it is the full model's Newmark step written in modal
//! coordinates (the modal transformation commutes with any linear one-step rule). The
//! truncated modes answer quasi-statically, w_res = C_res(p) P with C_res(p) = N(p)ᵀRN(p)
//! (plate_fem::modes), so the point flexibility is g = Σ γᵢφᵢ(p) + C_res(p); their velocity
//! follows the same trapezoidal rule while a force acts and is zero once none does (a
//! static response to no load).
//!
//! A step that starts with no force is propagated exactly (the damped free vibration,
//! [`super::signals::free_map`], in place of Nᵢ and without the Pₙ term); if a contact
//! begins within it, the force enters through the same γᵢ (the contact's first step, where
//! P is smallest). Between contacts nothing is time-stepped in the Newmark sense, so no
//! period error accumulates there.
//!
//! **One pass per step.** The step's prediction (the state it would reach without a
//! step-end force) only needs the state at its start and the force then, so it is computed
//! as soon as the previous step ends, in the same pass over the modes that ends that step:
//! per mode, add the step-end force, accumulate the sums the loop asks for (energies,
//! corner deflections), apply the next step's map and accumulate the predicted point
//! deflection and velocity. The point deflection and velocity at the step end follow
//! without a pass: Σφᵢqᵢ = Σφᵢq̂ᵢ + P Σγᵢφᵢ.

use super::signals::{dot, FreeMaps};
use crate::transient::Target;
use plate_fem::dynamics::PlateEnergy;

/// How a step without force is propagated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FreeSteps {
    /// The exact damped free vibration (the reduced model).
    Exact,
    /// Newmark's rule as in contact (to reproduce the full model's stepping exactly).
    Newmark,
}

/// What a corner contributes: its deflection is row·q + d P.
#[derive(Debug, Clone)]
pub(crate) struct CornerPoint {
    pub row: Vec<f64>,
    pub d: f64,
    pub spring: f64,
}

/// One channel of one impact: y = A·q + B·q̇ + D P (A, B None where zero).
#[derive(Debug, Clone)]
pub(crate) struct ChannelRow {
    pub a: Option<Vec<f64>>,
    pub b: Option<Vec<f64>>,
    pub d: f64,
}

/// The channels of one impact, recorded every `every` steps.
pub(crate) struct Recording {
    pub rows: Vec<ChannelRow>,
    pub every: usize,
    pub samples: usize,
}

/// Partial sums in this many lanes, so that the passes over the modes vectorize (a plain
/// sum fixes the order of the additions and cannot be).
const LANES: usize = 4;

/// The modal plate struck at one point.
pub(crate) struct ModalTarget {
    /// The instruction set the passes over the modes run on.
    simd: pulp::Arch,
    /// The modes (the arrays below are padded to whole lanes).
    modes: usize,
    /// φᵢ(p).
    phi: Vec<f64>,
    /// γᵢ = hᵢφᵢ(p): mode i's step-end deflection per unit step-end force.
    gamma: Vec<f64>,
    /// (2/Δt)γᵢ: its step-end velocity per unit step-end force.
    gamma_rate: Vec<f64>,
    omega2: Vec<f64>,
    /// 1/ωᵢ².
    inv_omega2: Vec<f64>,
    c_res: f64,
    /// 2/Δt.
    c1: f64,
    /// Σγᵢφᵢ(p), the kept modes' part of g.
    g_modes: f64,
    g: f64,
    /// Newmark's map Nᵢ over Δt.
    newmark: FreeMaps,
    /// The exact map over Δt (None: free steps by Newmark's rule too).
    exact: Option<FreeMaps>,
    q: Vec<f64>,
    v: Vec<f64>,
    qh: Vec<f64>,
    vh: Vec<f64>,
    /// Σφᵢq̂ᵢ and Σφᵢv̂ᵢ of the step under way.
    predicted: (f64, f64),
    force: f64,
    res_v: f64,
    res_vh: f64,
    /// The corners with a deflection, as (corner index, d, spring), and their rows, one
    /// after another in `corner_rows`.
    corner_terms: Vec<(usize, f64, f64)>,
    corner_rows: Vec<f64>,
    /// The corner deflections at the last step end (zero where held).
    corner_w: [f64; 4],
    /// At the last step end: Σφᵢ(p)qᵢ, Σφᵢ(p)q̇ᵢ, Σq̇ᵢ², Σωᵢ²qᵢ².
    sums: [f64; 4],
    recording: Option<Recording>,
    step: usize,
    pub(crate) out: Vec<Vec<f64>>,
}

impl ModalTarget {
    /// Modes `omega` (with φᵢ(p) in `phi_p`), a static correction `c_res`, step `dt`; free
    /// steps by `step_map` (the exact maps over `dt`) or, when None, by Newmark's rule.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        omega: Vec<f64>,
        zeta: super::ModalDamping,
        phi_p: Vec<f64>,
        c_res: f64,
        dt: f64,
        step_map: Option<FreeMaps>,
        corners: [Option<CornerPoint>; 4],
        recording: Option<Recording>,
        simd: pulp::Arch,
    ) -> Self {
        let modes = omega.len();
        // Every per-mode array is padded to whole lanes with zero modes (no coupling, no
        // state), so that the passes have no tail.
        let n = modes.div_ceil(LANES) * LANES;
        let pad = |mut x: Vec<f64>| {
            x.resize(n, 0.0);
            x
        };
        let c1 = 2.0 / dt;
        let gamma: Vec<f64> = pad(omega
            .iter()
            .zip(&phi_p)
            .map(|(&w, f)| f / (w * w + 4.0 * zeta.at(w) * w / dt + 4.0 / (dt * dt)))
            .collect());
        let g_modes = gamma.iter().zip(&phi_p).map(|(c, f)| c * f).sum::<f64>();
        let gamma_rate = gamma.iter().map(|c| c1 * c).collect();
        let omega2: Vec<f64> = pad(omega.iter().map(|w| w * w).collect());
        let inv_omega2 = pad(omega.iter().map(|w| 1.0 / (w * w)).collect());
        let out = recording
            .as_ref()
            .map_or(Vec::new(), |r| (0..r.rows.len()).map(|_| Vec::with_capacity(r.samples)).collect());
        let mut corner_terms = Vec::new();
        let mut corner_rows = Vec::new();
        for (k, c) in corners.iter().enumerate() {
            if let Some(c) = c {
                corner_terms.push((k, c.d, c.spring));
                corner_rows.extend_from_slice(&c.row[..modes]);
                corner_rows.resize(corner_rows.len() + n - modes, 0.0);
            }
        }
        let mut t = Self {
            simd,
            newmark: FreeMaps::newmark(&omega, zeta, dt).padded(n),
            modes,
            phi: pad(phi_p),
            gamma,
            gamma_rate,
            omega2,
            inv_omega2,
            c_res,
            c1,
            g_modes,
            g: g_modes + c_res,
            exact: step_map.map(|m| m.padded(n)),
            q: vec![0.0; n],
            v: vec![0.0; n],
            qh: vec![0.0; n],
            vh: vec![0.0; n],
            predicted: (0.0, 0.0),
            force: 0.0,
            res_v: 0.0,
            res_vh: 0.0,
            corner_terms,
            corner_rows,
            corner_w: [0.0; 4],
            sums: [0.0; 4],
            recording,
            step: 0,
            out,
        };
        t.record();
        t
    }

    /// Steps taken so far.
    pub(crate) fn steps(&self) -> usize {
        self.step
    }

    /// Propagates the free plate `steps` steps on, recording as in contact (exactly, or by
    /// Newmark's rule when the target has no exact maps); the force must be zero.
    pub(crate) fn advance_free(&mut self, steps: usize) {
        for _ in 0..steps {
            self.predict();
            self.commit(0.0);
        }
    }

    /// Whether free steps are exact.
    pub(crate) fn exact(&self) -> bool {
        self.exact.is_some()
    }

    /// Samples recorded so far.
    pub(crate) fn recorded(&self) -> usize {
        self.out.first().map_or(0, |o| o.len())
    }

    /// The modal state (q, q̇).
    pub(crate) fn state(&self) -> (&[f64], &[f64]) {
        (&self.q[..self.modes], &self.v[..self.modes])
    }

    /// Appends one sample of every channel: y = A·q + B·q̇ + D P.
    #[inline(always)]
    fn record(&mut self) {
        let Some(r) = self.recording.as_ref() else { return };
        if self.out.first().is_some_and(|o| o.len() >= r.samples) {
            return;
        }
        for (row, o) in r.rows.iter().zip(self.out.iter_mut()) {
            let a = row.a.as_ref().map_or(0.0, |a| dot(a, &self.q));
            let b = row.b.as_ref().map_or(0.0, |b| dot(b, &self.v));
            o.push(a + b + row.d * self.force);
        }
    }

    /// The channels' rows (none without a recording).
    pub(crate) fn rows(&self) -> &[ChannelRow] {
        self.recording.as_ref().map_or(&[], |r| &r.rows)
    }

    /// Ends the step with force `f` and predicts the next one (see the module), recording
    /// at sample steps.
    #[inline(always)]
    fn end_step(&mut self, f: f64) {
        let c1 = self.c1;
        self.sums[0] = self.predicted.0 + f * self.g_modes;
        self.sums[1] = self.predicted.1 + c1 * f * self.g_modes;
        self.res_v = self.res_vh + c1 * self.c_res * f;
        self.force = f;
        // The next step starts with force f: exact without one (when the target has the
        // exact map), else Newmark's rule with its start-of-step term.
        let (map, start_force) = match (&self.exact, f == 0.0) {
            (Some(exact), true) => (exact, 0.0),
            _ => (&self.newmark, f),
        };
        // The residual's trapezoidal velocity: v₊ = (2/Δt)C_res(P₊ - P) - v.
        self.res_vh = if f == 0.0 { 0.0 } else { -c1 * self.c_res * f - self.res_v };
        if f == 0.0 {
            // A step without force ends where it was predicted, and the next starts free.
            std::mem::swap(&mut self.q, &mut self.qh);
            std::mem::swap(&mut self.v, &mut self.vh);
            map.apply(&self.q, &self.v, &mut self.qh, &mut self.vh);
        } else {
            let pass = Pass { gamma: &self.gamma, gamma_rate: &self.gamma_rate, map: map.entries(), f, start_force };
            pass.run(&mut self.q, &mut self.v, &mut self.qh, &mut self.vh);
        }
        self.sums[2] = dot(&self.v, &self.v);
        self.sums[3] = weighted_squares(&self.omega2, &self.q);
        self.predicted = (dot(&self.phi, &self.qh), dot(&self.phi, &self.vh));
        let n = self.q.len();
        for (k, &(corner, d, _)) in self.corner_terms.iter().enumerate() {
            self.corner_w[corner] = dot(&self.corner_rows[k * n..(k + 1) * n], &self.q) + d * f;
        }
        self.step += 1;
        if self.recording.as_ref().is_some_and(|r| self.step % r.every == 0) {
            self.record();
        }
    }

    /// Σᵢ|φᵢ(p)|Aᵢ (see [`Target::free_reach`]).
    #[inline(always)]
    fn reach(&self) -> f64 {
        let n = self.q.len();
        let (q, v, phi, inv) = (&self.q[..n], &self.v[..n], &self.phi[..n], &self.inv_omega2[..n]);
        let mut acc = [0.0; LANES];
        for base in (0..n).step_by(LANES) {
            for (l, a) in acc.iter_mut().enumerate() {
                let i = base + l;
                *a += phi[i].abs() * (q[i] * q[i] + v[i] * v[i] * inv[i]).sqrt();
            }
        }
        lane_sum(acc)
    }
}

/// A step's end on the instruction set detected at run time (the same operations in the
/// same order on every one, so the same results).
struct EndStep<'a> {
    target: &'a mut ModalTarget,
    f: f64,
}

impl pulp::WithSimd for EndStep<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        self.target.end_step(self.f)
    }
}

/// [`ModalTarget::reach`] on the instruction set detected at run time.
struct Reach<'a>(&'a ModalTarget);

impl pulp::WithSimd for Reach<'_> {
    type Output = f64;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> f64 {
        self.0.reach()
    }
}

/// The pass over the modes that ends a step and predicts the next: the point's modal data,
/// the next step's map, the step-end force `f` and the next step's start force
/// `start_force` (zero for an exact step).
struct Pass<'a> {
    gamma: &'a [f64],
    gamma_rate: &'a [f64],
    map: [&'a [f64]; 4],
    f: f64,
    start_force: f64,
}

impl Pass<'_> {
    /// Per mode i: qᵢ = q̂ᵢ + γᵢP, q̇ᵢ = v̂ᵢ + (2/Δt)γᵢP (the step end), then
    /// (q̂ᵢ, v̂ᵢ) = M(qᵢ, q̇ᵢ) + (γᵢ, (2/Δt)γᵢ)P_start (the next step's prediction). No sums
    /// here: an element-wise loop vectorizes as it stands.
    #[inline(always)]
    fn run(&self, q: &mut [f64], v: &mut [f64], qh: &mut [f64], vh: &mut [f64]) {
        let n = q.len();
        let (gamma, gamma_rate) = (&self.gamma[..n], &self.gamma_rate[..n]);
        let [m0, m1, m2, m3] = self.map;
        let (m0, m1, m2, m3) = (&m0[..n], &m1[..n], &m2[..n], &m3[..n]);
        let (v, qh, vh) = (&mut v[..n], &mut qh[..n], &mut vh[..n]);
        let (f, fs) = (self.f, self.start_force);
        for i in 0..n {
            let (qi, vi) = (qh[i] + gamma[i] * f, vh[i] + gamma_rate[i] * f);
            q[i] = qi;
            v[i] = vi;
            qh[i] = m0[i] * qi + m1[i] * vi + gamma[i] * fs;
            vh[i] = m2[i] * qi + m3[i] * vi + gamma_rate[i] * fs;
        }
    }
}

/// Σ wᵢxᵢ² in [`LANES`] partial sums.
#[inline(always)]
fn weighted_squares(w: &[f64], x: &[f64]) -> f64 {
    let mut acc = [0.0; LANES];
    for (w, x) in w.chunks_exact(LANES).zip(x.chunks_exact(LANES)) {
        for l in 0..LANES {
            acc[l] += w[l] * x[l] * x[l];
        }
    }
    lane_sum(acc)
}

/// (a₀ + a₂) + (a₁ + a₃): the lanes' sum.
#[inline(always)]
fn lane_sum(a: [f64; LANES]) -> f64 {
    (a[0] + a[2]) + (a[1] + a[3])
}

impl Target for ModalTarget {
    fn point_flexibility(&self) -> f64 {
        self.g
    }

    /// The prediction of the step under way, computed when the last one ended.
    fn predict(&mut self) -> (f64, f64) {
        (self.predicted.0, self.predicted.1 + self.res_vh)
    }

    fn commit(&mut self, f: f64) {
        let simd = self.simd;
        simd.dispatch(EndStep { target: self, f });
    }

    fn point_state(&self) -> (f64, f64) {
        (self.sums[0] + self.c_res * self.force, self.sums[1] + self.res_v)
    }

    /// ½Σq̇ᵢ² (kinetic), ½Σωᵢ²qᵢ² + ½C_res P² (potential: the modes and the truncated modes'
    /// static energy, which are K-orthogonal), split into the springs' ½Σk w_c² and the rest.
    fn energy(&self) -> PlateEnergy {
        let kinetic = 0.5 * self.sums[2];
        let potential = 0.5 * self.sums[3] + 0.5 * self.c_res * self.force * self.force;
        let springs: f64 =
            self.corner_terms.iter().map(|&(c, _, k)| 0.5 * k * self.corner_w[c] * self.corner_w[c]).sum();
        PlateEnergy { kinetic, strain: potential - springs, springs }
    }

    /// Σᵢ|φᵢ(p)|Aᵢ with Aᵢ = √(qᵢ² + q̇ᵢ²/ωᵢ²): free of force, each mode's ωᵢ²qᵢ² + q̇ᵢ² has the
    /// rate -4ζωᵢq̇ᵢ² ≤ 0, so |qᵢ| stays below Aᵢ for all later time, and the point deflection
    /// (no static part without a force) below the sum. By Cauchy-Schwarz this never exceeds
    /// the energy bound √(2E C_modal).
    fn free_reach(&self) -> Option<f64> {
        Some(self.simd.dispatch(Reach(self)))
    }

    fn corner_displacements(&self) -> [f64; 4] {
        self.corner_w
    }
}
