//! The reduced plate as a [`Target`] of the transient loop: N modes stepped by Newmark's
//! rule while a force acts, propagated exactly while none does, plus the static
//! correction of the truncated modes at the struck point.
//!
//! Mode i (mass-normalised) obeys q̈ᵢ + 2ζωᵢq̇ᵢ + ωᵢ²qᵢ = φᵢ(p)P. Newmark's average-acceleration
//! rule gives, with hᵢ = 1/(ωᵢ² + 4ζωᵢ/Δt + 4/Δt²),
//! qᵢ,ₙ₊₁ = q̂ᵢ + hᵢφᵢ(p)Pₙ₊₁, q̂ᵢ = hᵢ[(4/Δt²)(qᵢ,ₙ + Δt q̇ᵢ,ₙ) + q̈ᵢ,ₙ + 2ζωᵢ(2qᵢ,ₙ/Δt + q̇ᵢ,ₙ)],
//! q̇ᵢ,ₙ₊₁ = (2/Δt)(qᵢ,ₙ₊₁ - qᵢ,ₙ) - q̇ᵢ,ₙ:
//! affine in the step-end force, as the contact solve needs, and with all modes and ζ = 0 it
//! is the full model's Newmark step written in modal coordinates (the modal transformation
//! commutes with any linear one-step rule). The truncated modes answer quasi-statically,
//! w_res = C_res(p) P with C_res(p) = N(p)ᵀRN(p) (plate_fem::modes), so the point
//! flexibility is g = Σ hᵢφᵢ(p)² + C_res(p); their velocity follows the same trapezoidal
//! rule while a force acts and is zero once none does (a static response to no load).
//!
//! A step that starts with no force is propagated exactly (the damped free vibration,
//! [`super::signals::free_map`]); if a contact begins within it, the force enters through the same hᵢ (the
//! contact's first step, where P is smallest). Between contacts nothing is time-stepped in
//! the Newmark sense, so no period error accumulates there.

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

/// The channels of one impact: y = A·q + B·q̇ + D P, recorded every `every` steps.
pub(crate) struct Recording {
    pub a: Vec<Vec<f64>>,
    pub b: Vec<Option<Vec<f64>>>,
    pub d: Vec<f64>,
    pub every: usize,
    pub samples: usize,
}

/// The modal plate struck at one point.
pub(crate) struct ModalTarget {
    omega: Vec<f64>,
    omega2: Vec<f64>,
    zeta: f64,
    phi_p: Vec<f64>,
    c_res: f64,
    dt: f64,
    h: Vec<f64>,
    step_map: Option<FreeMaps>,
    q: Vec<f64>,
    v: Vec<f64>,
    qh: Vec<f64>,
    vh: Vec<f64>,
    force: f64,
    res_v: f64,
    res_vh: f64,
    g: f64,
    corners: [Option<CornerPoint>; 4],
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
        zeta: f64,
        phi_p: Vec<f64>,
        c_res: f64,
        dt: f64,
        step_map: Option<FreeMaps>,
        corners: [Option<CornerPoint>; 4],
        recording: Option<Recording>,
    ) -> Self {
        let n = omega.len();
        let h: Vec<f64> = omega.iter().map(|&w| 1.0 / (w * w + 4.0 * zeta * w / dt + 4.0 / (dt * dt))).collect();
        let g = h.iter().zip(&phi_p).map(|(h, f)| h * f * f).sum::<f64>() + c_res;
        let omega2 = omega.iter().map(|w| w * w).collect();
        let out = recording.as_ref().map_or(Vec::new(), |r| vec![Vec::with_capacity(r.samples); r.a.len()]);
        let mut t = Self {
            omega,
            omega2,
            zeta,
            phi_p,
            c_res,
            dt,
            h,
            step_map,
            q: vec![0.0; n],
            v: vec![0.0; n],
            qh: vec![0.0; n],
            vh: vec![0.0; n],
            force: 0.0,
            res_v: 0.0,
            res_vh: 0.0,
            g,
            corners,
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
        self.step_map.is_some()
    }

    /// Samples recorded so far.
    pub(crate) fn recorded(&self) -> usize {
        self.out.first().map_or(0, |o| o.len())
    }

    /// The modal state (q, q̇).
    pub(crate) fn state(&self) -> (&[f64], &[f64]) {
        (&self.q, &self.v)
    }

    /// Appends one sample of every channel: y = A·q + B·q̇ + D P.
    fn record(&mut self) {
        let Some(r) = self.recording.as_ref() else { return };
        if self.out.first().is_some_and(|o| o.len() >= r.samples) {
            return;
        }
        for (c, o) in self.out.iter_mut().enumerate() {
            let b = r.b[c].as_ref().map_or(0.0, |b| dot(b, &self.v));
            o.push(dot(&r.a[c], &self.q) + b + r.d[c] * self.force);
        }
    }

    /// The step end with force `f`, without recording.
    fn commit_state(&mut self, f: f64) {
        let c1 = 2.0 / self.dt;
        let n = self.q.len();
        let (h, phi, qh, vh, om2) = (&self.h[..n], &self.phi_p[..n], &self.qh[..n], &self.vh[..n], &self.omega2[..n]);
        let (q, v) = (&mut self.q[..n], &mut self.v[..n]);
        // One pass: the update and the sums the loop asks for next (point deflection and
        // velocity, kinetic and strain energy), in four lanes so that it vectorizes.
        let mut acc = [[0.0f64; 4]; 4];
        let lanes = n - n % 4;
        for base in (0..lanes).step_by(4) {
            // Explicit lanes: the accumulators are indexed by lane so that they vectorize.
            #[allow(clippy::needless_range_loop)]
            for l in 0..4 {
                let i = base + l;
                let dq = h[i] * phi[i] * f;
                let (qi, vi) = (qh[i] + dq, vh[i] + c1 * dq);
                q[i] = qi;
                v[i] = vi;
                acc[0][l] += phi[i] * qi;
                acc[1][l] += phi[i] * vi;
                acc[2][l] += vi * vi;
                acc[3][l] += om2[i] * qi * qi;
            }
        }
        for i in lanes..n {
            let dq = h[i] * phi[i] * f;
            let (qi, vi) = (qh[i] + dq, vh[i] + c1 * dq);
            q[i] = qi;
            v[i] = vi;
            acc[0][0] += phi[i] * qi;
            acc[1][0] += phi[i] * vi;
            acc[2][0] += vi * vi;
            acc[3][0] += om2[i] * qi * qi;
        }
        self.sums = acc.map(|a| (a[0] + a[2]) + (a[1] + a[3]));
        self.res_v = self.res_vh + c1 * self.c_res * f;
        self.force = f;
        for (w, c) in self.corner_w.iter_mut().zip(&self.corners) {
            if let Some(c) = c {
                *w = dot(&c.row, &self.q) + c.d * f;
            }
        }
        self.step += 1;
    }
}

impl Target for ModalTarget {
    fn point_flexibility(&self) -> f64 {
        self.g
    }

    fn predict(&mut self) -> (f64, f64) {
        let dt = self.dt;
        if let (0.0, Some(map)) = (self.force, self.step_map.as_ref()) {
            map.apply(&self.q, &self.v, &mut self.qh, &mut self.vh);
            self.res_vh = 0.0;
        } else {
            let (c0, c1) = (4.0 / (dt * dt), 2.0 / dt);
            let n = self.q.len();
            let (om, om2, h, phi) = (&self.omega[..n], &self.omega2[..n], &self.h[..n], &self.phi_p[..n]);
            let (q, v, qh, vh) = (&self.q[..n], &self.v[..n], &mut self.qh[..n], &mut self.vh[..n]);
            let (f, z2) = (self.force, 2.0 * self.zeta);
            for i in 0..n {
                let a = phi[i] * f - om2[i] * q[i] - z2 * om[i] * v[i];
                let qhi = h[i] * (c0 * (q[i] + dt * v[i]) + a + z2 * om[i] * (c1 * q[i] + v[i]));
                qh[i] = qhi;
                vh[i] = c1 * (qhi - q[i]) - v[i];
            }
            // The residual's trapezoidal velocity: v₊ = (2/Δt)C_res(P₊ - P) - v.
            self.res_vh = if self.force == 0.0 { 0.0 } else { -c1 * self.c_res * self.force - self.res_v };
        }
        let wp = dot(&self.qh, &self.phi_p);
        let vp = dot(&self.vh, &self.phi_p) + self.res_vh;
        (wp, vp)
    }

    fn commit(&mut self, f: f64) {
        self.commit_state(f);
        if self.recording.as_ref().is_some_and(|r| self.step % r.every == 0) {
            self.record();
        }
    }

    fn point_state(&self) -> (f64, f64) {
        (self.sums[0] + self.c_res * self.force, self.sums[1] + self.res_v)
    }

    /// ½Σq̇ᵢ² (kinetic), ½Σωᵢ²qᵢ² + ½C_res P² (potential: the modes and the truncated modes'
    /// static energy, which are K-orthogonal), split into the springs' ½Σk w_c² and the rest.
    fn energy(&self) -> PlateEnergy {
        let kinetic = 0.5 * self.sums[2];
        let potential = 0.5 * self.sums[3] + 0.5 * self.c_res * self.force * self.force;
        let springs: f64 = self
            .corners
            .iter()
            .zip(&self.corner_w)
            .filter_map(|(c, w)| c.as_ref().map(|c| 0.5 * c.spring * w * w))
            .sum();
        PlateEnergy { kinetic, strain: potential - springs, springs }
    }

    /// Σᵢ|φᵢ(p)|Aᵢ with Aᵢ = √(qᵢ² + q̇ᵢ²/ωᵢ²): free of force, each mode's ωᵢ²qᵢ² + q̇ᵢ² has the
    /// rate -4ζωᵢq̇ᵢ² ≤ 0, so |qᵢ| stays below Aᵢ for all later time, and the point deflection
    /// (no static part without a force) below the sum. By Cauchy-Schwarz this never exceeds
    /// the energy bound √(2E C_modal).
    fn free_reach(&self) -> Option<f64> {
        let n = self.q.len();
        let (q, v, phi, om2) = (&self.q[..n], &self.v[..n], &self.phi_p[..n], &self.omega2[..n]);
        Some((0..n).map(|i| phi[i].abs() * (q[i] * q[i] + v[i] * v[i] / om2[i]).sqrt()).sum())
    }

    fn corner_displacements(&self) -> [f64; 4] {
        self.corner_w
    }
}
