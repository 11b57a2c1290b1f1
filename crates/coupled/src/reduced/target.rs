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
//! [`free_map`]); if a contact begins within it, the force enters through the same hᵢ (the
//! contact's first step, where P is smallest). Between contacts nothing is time-stepped in
//! the Newmark sense, so no period error accumulates there.

use super::signals::{free_map, Probes};
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

/// What a corner contributes: its deflection is Σ rowᵢ qᵢ + d P.
#[derive(Debug, Clone)]
pub(crate) struct CornerPoint {
    pub row: Vec<f64>,
    pub d: f64,
    pub spring: f64,
}

/// The modal plate struck at one point.
pub(crate) struct ModalTarget<'a> {
    omega: &'a [f64],
    zeta: f64,
    phi_p: Vec<f64>,
    c_res: f64,
    dt: f64,
    h: Vec<f64>,
    step_map: Vec<[f64; 4]>,
    q: Vec<f64>,
    v: Vec<f64>,
    qh: Vec<f64>,
    vh: Vec<f64>,
    force: f64,
    res_v: f64,
    res_vh: f64,
    g: f64,
    free: FreeSteps,
    corners: [Option<CornerPoint>; 4],
    // Recording: a sample every `every` steps.
    probes: Option<&'a Probes>,
    direct: Vec<f64>,
    every: usize,
    step: usize,
    pub(crate) out: Vec<Vec<f64>>,
}

impl<'a> ModalTarget<'a> {
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        omega: &'a [f64],
        zeta: f64,
        phi_p: Vec<f64>,
        c_res: f64,
        dt: f64,
        free: FreeSteps,
        corners: [Option<CornerPoint>; 4],
        recording: Option<(&'a Probes, Vec<f64>, usize)>,
    ) -> Self {
        let n = omega.len();
        let h: Vec<f64> = omega.iter().map(|&w| 1.0 / (w * w + 4.0 * zeta * w / dt + 4.0 / (dt * dt))).collect();
        let g = h.iter().zip(&phi_p).map(|(h, f)| h * f * f).sum::<f64>() + c_res;
        let step_map = match free {
            FreeSteps::Exact => omega.iter().map(|&w| free_map(w, zeta, dt)).collect(),
            FreeSteps::Newmark => Vec::new(),
        };
        let (probes, direct, every) = match recording {
            Some((p, d, e)) => (Some(p), d, e.max(1)),
            None => (None, Vec::new(), 1),
        };
        let mut t = Self {
            omega,
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
            free,
            corners,
            probes,
            direct,
            every,
            step: 0,
            out: Vec::new(),
        };
        if let Some(p) = t.probes {
            t.out = vec![Vec::with_capacity(p.spec.samples()); p.rows.len()];
            t.record();
        }
        t
    }

    /// Steps taken so far.
    pub(crate) fn steps(&self) -> usize {
        self.step
    }

    /// The modal state (q, q̇) and the force now.
    pub(crate) fn state(&self) -> (&[f64], &[f64], f64) {
        (&self.q, &self.v, self.force)
    }

    /// Appends one sample of every channel: y = A·q + B·q̇ + D P.
    fn record(&mut self) {
        let Some(p) = self.probes else { return };
        let want = p.spec.samples();
        for (c, rows) in p.rows.iter().enumerate() {
            if self.out[c].len() >= want {
                return;
            }
            let y = rows.a.iter().zip(&self.q).map(|(a, q)| a * q).sum::<f64>()
                + rows.b.iter().zip(&self.v).map(|(b, v)| b * v).sum::<f64>()
                + self.direct[c] * self.force;
            self.out[c].push(y);
        }
    }
}

impl Target for ModalTarget<'_> {
    fn point_flexibility(&self) -> f64 {
        self.g
    }

    fn predict(&mut self) -> (f64, f64) {
        let dt = self.dt;
        if self.force == 0.0 && self.free == FreeSteps::Exact {
            for i in 0..self.q.len() {
                let m = &self.step_map[i];
                self.qh[i] = m[0] * self.q[i] + m[1] * self.v[i];
                self.vh[i] = m[2] * self.q[i] + m[3] * self.v[i];
            }
            self.res_vh = 0.0;
        } else {
            let (c0, c1) = (4.0 / (dt * dt), 2.0 / dt);
            for i in 0..self.q.len() {
                let w = self.omega[i];
                let (q, v) = (self.q[i], self.v[i]);
                let a = self.phi_p[i] * self.force - w * w * q - 2.0 * self.zeta * w * v;
                let qh = self.h[i] * (c0 * (q + dt * v) + a + 2.0 * self.zeta * w * (c1 * q + v));
                self.qh[i] = qh;
                self.vh[i] = c1 * (qh - q) - v;
            }
            // The residual's trapezoidal velocity: v₊ = (2/Δt)C_res(P₊ - P) - v.
            self.res_vh = if self.force == 0.0 { 0.0 } else { -c1 * self.c_res * self.force - self.res_v };
        }
        let wp = self.qh.iter().zip(&self.phi_p).map(|(q, f)| q * f).sum::<f64>();
        let vp = self.vh.iter().zip(&self.phi_p).map(|(v, f)| v * f).sum::<f64>() + self.res_vh;
        (wp, vp)
    }

    fn commit(&mut self, f: f64) {
        let c1 = 2.0 / self.dt;
        for i in 0..self.q.len() {
            let dq = self.h[i] * self.phi_p[i] * f;
            self.q[i] = self.qh[i] + dq;
            self.v[i] = self.vh[i] + c1 * dq;
        }
        self.res_v = self.res_vh + c1 * self.c_res * f;
        self.force = f;
        self.step += 1;
        if self.probes.is_some() && self.step % self.every == 0 {
            self.record();
        }
    }

    fn point_state(&self) -> (f64, f64) {
        let w = self.q.iter().zip(&self.phi_p).map(|(q, f)| q * f).sum::<f64>() + self.c_res * self.force;
        let v = self.v.iter().zip(&self.phi_p).map(|(v, f)| v * f).sum::<f64>() + self.res_v;
        (w, v)
    }

    /// ½Σq̇ᵢ² (kinetic), ½Σωᵢ²qᵢ² + ½C_res P² (potential: the modes and the truncated modes'
    /// static energy, which are K-orthogonal), split into the springs' ½Σk w_c² and the rest.
    fn energy(&self) -> PlateEnergy {
        let kinetic = 0.5 * self.v.iter().map(|v| v * v).sum::<f64>();
        let potential = 0.5 * self.q.iter().zip(self.omega).map(|(q, w)| w * w * q * q).sum::<f64>()
            + 0.5 * self.c_res * self.force * self.force;
        let springs: f64 = self
            .corners
            .iter()
            .flatten()
            .filter(|c| c.spring > 0.0)
            .map(|c| {
                let w = c.row.iter().zip(&self.q).map(|(r, q)| r * q).sum::<f64>() + c.d * self.force;
                0.5 * c.spring * w * w
            })
            .sum();
        PlateEnergy { kinetic, strain: potential - springs, springs }
    }

    fn corner_displacements(&self) -> [f64; 4] {
        std::array::from_fn(|i| {
            self.corners[i]
                .as_ref()
                .map_or(0.0, |c| c.row.iter().zip(&self.q).map(|(r, q)| r * q).sum::<f64>() + c.d * self.force)
        })
    }
}
