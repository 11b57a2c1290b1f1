//! Structural dynamics of the supported plate: M ẅ + K w = N(p) F(t), with Newmark's
//! average-acceleration scheme (β = 1/4, γ = 1/2: unconditionally stable, second order, no
//! numerical damping, energy-conserving for linear systems).
//!
//! With Rayleigh damping C = αM + βK ([`Rayleigh`]) the equation is Mẅ + Cẇ + Kw = N(p)F(t)
//! and the effective matrix K + (2/Δt)C + (4/Δt²)M = (1 + 2β/Δt)K + (4/Δt² + 2α/Δt)M keeps
//! the pattern and the symbolic factorization of the undamped one.
//!
//! The effective matrix K + (4/Δt²)M is factorized once per time step size. The load acts
//! at one point p, so each step splits into a predictor w_hat (the response if F_{n+1} = 0,
//! one solve) and the precomputed response G = (K + 4M/Δt²)⁻¹ N to a unit force: the point
//! displacement at the end of the step is w_hat(p) + g F_{n+1} with g = Nᵀ G. A caller with
//! a nonlinear force law (contact) solves one scalar equation per step and commits F.
//! The module knows nothing of what produces F.

use crate::model::{
    mass_stiffness_pass, symmetric_upper_apply, symmetric_upper_apply_into, symmetric_upper_quadratic, Factorization,
    Model,
};
use crate::supports::{Corner, CornerSupport, EdgeSupport, Supports};
use crate::FemError;
use faer::{sparse::SparseColMat, Mat};

/// Rayleigh damping C = αM + βK (Rayleigh, *The Theory of Sound* §97; Chopra, *Dynamics of
/// Structures*, §11.4): classical, so it leaves the undamped modes uncoupled, with the
/// damping ratio ζᵢ = α/(2ωᵢ) + βωᵢ/2 of mode i ([`Rayleigh::ratio`]).
///
/// ```
/// use plate_fem::dynamics::Rayleigh;
/// // 1 % of critical at 100 Hz and at 2 kHz, less between them.
/// let (a, b) = (2.0 * std::f64::consts::PI * 100.0, 2.0 * std::f64::consts::PI * 2000.0);
/// let r = Rayleigh::through(0.01, a, b);
/// assert!((r.ratio(a) - 0.01).abs() < 1e-15 && (r.ratio(b) - 0.01).abs() < 1e-15);
/// assert!(r.ratio((a * b).sqrt()) < 0.01);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Rayleigh {
    /// α, 1/s: the mass-proportional part, which damps the low modes.
    pub alpha: f64,
    /// β, s: the stiffness-proportional part, which damps the high modes.
    pub beta: f64,
}

impl Rayleigh {
    /// The α and β that give the damping ratio `zeta` at the circular frequencies `wa` and
    /// `wb` (rad/s), Chopra eq. 11.4.9 with ζ equal at both: α = 2ζω_aω_b/(ω_a + ω_b),
    /// β = 2ζ/(ω_a + ω_b).
    pub fn through(zeta: f64, wa: f64, wb: f64) -> Self {
        Self { alpha: 2.0 * zeta * wa * wb / (wa + wb), beta: 2.0 * zeta / (wa + wb) }
    }

    /// The damping ratio of a mode of circular frequency `omega`: ζ = α/(2ω) + βω/2.
    pub fn ratio(&self, omega: f64) -> f64 {
        self.alpha / (2.0 * omega) + 0.5 * self.beta * omega
    }
}

/// The time-stepping state and its operators.
pub struct Newmark<'m> {
    model: &'m Model,
    supports: Supports,
    effective: Factorization<'m>,
    stiffness: SparseColMat<usize, f64>,
    mass: SparseColMat<usize, f64>,
    dt: f64,
    /// N(p), the load vector of a unit force at p, as its nonzero entries (index, value) in
    /// index order: the shape functions of one element, so a point value costs 16 products.
    load: Vec<(usize, f64)>,
    /// (K + 4M/Δt²)⁻¹ N.
    unit_response: Vec<f64>,
    w: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    w_hat: Vec<f64>,
    /// The step's right-hand side, then its predictor (one column, reused every step).
    rhs: Mat<f64>,
    /// Scratch for the predictor's combination y = c₀w + c₁v + a (reused every step).
    combination: Vec<f64>,
    /// M y for the next step's predictor, computed with the energies at the end of each
    /// undamped step (the damped predictor forms its own right-hand side).
    next_rhs: Vec<f64>,
    /// (ẇᵀMẇ, wᵀKw) of the present state.
    quadratic: (f64, f64),
    /// Whether M and K share their pattern, so one pass gives M y and both energies.
    shared_pattern: bool,
    /// The damping and the energy it has taken so far, J.
    damping: Option<(Rayleigh, f64)>,
}

/// Energies of the plate (J).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PlateEnergy {
    /// ½ ẇᵀ M ẇ.
    pub kinetic: f64,
    /// ½ wᵀ K w without the springs: the plate's bending strain energy.
    pub strain: f64,
    /// Σ ½ k_i w_i² over the corner springs, plus ½ k ∮ w² ds over the elastic edges.
    pub springs: f64,
}

impl<'m> Newmark<'m> {
    /// A plate at rest, loaded at (x, z), stepping with `dt`.
    pub fn new(model: &'m Model, supports: Supports, dt: f64, x: f64, z: f64) -> Result<Self, FemError> {
        Self::damped(model, supports, dt, (x, z), None)
    }

    /// A plate at rest with the Rayleigh `damping` (None: undamped, as [`Self::new`]),
    /// loaded at (x, z), stepping with `dt`. The effective matrix is s(K + c M) with
    /// s = 1 + 2β/Δt and c = (4/Δt² + 2α/Δt)/s, so one shifted factorization serves, every
    /// solve scaled by 1/s.
    pub fn damped(
        model: &'m Model,
        supports: Supports,
        dt: f64,
        (x, z): (f64, f64),
        damping: Option<Rayleigh>,
    ) -> Result<Self, FemError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(FemError::Mesh(format!("time step {dt} s is outside the allowed range (0, inf) s")));
        }
        let (scale, shift) = match damping {
            None => (1.0, 4.0 / (dt * dt)),
            Some(r) => {
                let s = 1.0 + 2.0 * r.beta / dt;
                (s, (4.0 / (dt * dt) + 2.0 * r.alpha / dt) / s)
            }
        };
        // K + 4M/Δt² is dominated by the mass term at any step a contact needs, so one solve
        // is accurate without refinement: relative residuals ≤ 8e-11 on 80-element meshes of
        // the paper's plate (2-32 mm, Δt 1e-6 to 1e-3 s, corner springs 1e-3 to 1e11 N/m),
        // against a refinement step that doubled the cost of every time step.
        let effective = model.factorize_shifted(&supports, shift)?.with_refinement(0);
        let stiffness = model.supported_matrix(&supports, 1.0, 0.0, false)?;
        let mass = model.supported_mass(&supports)?;
        let load = effective.load_vector(x, z)?;
        let n = load.len();
        let mut g = Mat::from_fn(n, 1, |i, _| load[i]);
        effective.solve_in_place(&mut g);
        let unit_response = (0..n).map(|i| g[(i, 0)] / scale).collect();
        let shared_pattern = mass.symbolic().col_ptr() == stiffness.symbolic().col_ptr()
            && mass.symbolic().row_idx() == stiffness.symbolic().row_idx();
        let load = load.iter().enumerate().filter(|(_, v)| **v != 0.0).map(|(i, v)| (i, *v)).collect();
        Ok(Self {
            model,
            supports,
            effective,
            stiffness,
            mass,
            dt,
            load,
            unit_response,
            w: vec![0.0; n],
            v: vec![0.0; n],
            a: vec![0.0; n],
            w_hat: vec![0.0; n],
            rhs: Mat::zeros(n, 1),
            combination: vec![0.0; n],
            next_rhs: vec![0.0; n],
            quadratic: (0.0, 0.0),
            shared_pattern,
            damping: damping.map(|r| (r, 0.0)),
        })
    }

    /// The time step Δt (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// g = Nᵀ (K + 4M/Δt²)⁻¹ N: the point's displacement at the end of a step per unit force.
    pub fn point_flexibility(&self) -> f64 {
        self.at_load(&self.unit_response)
    }

    /// Point displacement and velocity now.
    pub fn point_state(&self) -> (f64, f64) {
        (self.at_load(&self.w), self.at_load(&self.v))
    }

    /// The predictor for the next step: (w_hat(p), v_hat(p)), the point's displacement and
    /// velocity at the end of the step if no force acted in it. The velocity then grows by
    /// (2/Δt) g F with the force.
    pub fn predict(&mut self) -> (f64, f64) {
        let (c0, c1) = (4.0 / (self.dt * self.dt), 4.0 / self.dt);
        match self.damping {
            None => self.rhs.col_as_slice_mut(0).copy_from_slice(&self.next_rhs),
            Some((r, _)) => {
                let rhs = self.damped_rhs(r);
                self.rhs.col_as_slice_mut(0).copy_from_slice(&rhs);
            }
        }
        // K + 4M/Δt² is mass-dominated: one solve is accurate without refinement or a
        // residual (see `damped`).
        self.effective.solve_unchecked(&mut self.rhs);
        let scale = self.damping.map_or(1.0, |(r, _)| 1.0 + 2.0 * r.beta / self.dt);
        for (w, m) in self.w_hat.iter_mut().zip(self.rhs.col_as_slice(0)) {
            *w = m / scale;
        }
        let wp = self.at_load(&self.w_hat);
        // v_{n+1} = v_n + Δt/2 (a_n + a_{n+1}), a_{n+1} = c0 (w_{n+1} - w_n) - c1 v_n - a_n.
        let vp = self
            .load
            .iter()
            .map(|&(i, l)| l * (self.v[i] + 0.5 * self.dt * (c0 * (self.w_hat[i] - self.w[i]) - c1 * self.v[i])))
            .sum();
        (wp, vp)
    }

    /// Nᵀx: the value of the field `x` at the load point.
    fn at_load(&self, x: &[f64]) -> f64 {
        self.load.iter().map(|&(i, l)| l * x[i]).sum()
    }

    /// The right-hand side of a damped step: M(c₀w + c₁v + a) + C((2/Δt)w + v) with
    /// C = αM + βK, i.e. M((c₀ + 2α/Δt)w + (c₁ + α)v + a) + βK((2/Δt)w + v).
    fn damped_rhs(&self, r: Rayleigh) -> Vec<f64> {
        let (c0, c1, dt) = (4.0 / (self.dt * self.dt), 4.0 / self.dt, self.dt);
        let n = self.w.len();
        let y: Vec<f64> =
            (0..n).map(|i| (c0 + 2.0 * r.alpha / dt) * self.w[i] + (c1 + r.alpha) * self.v[i] + self.a[i]).collect();
        let mut rhs = symmetric_upper_apply(&self.mass, &y);
        if r.beta != 0.0 {
            let q: Vec<f64> = (0..n).map(|i| r.beta * (2.0 / dt * self.w[i] + self.v[i])).collect();
            let kq = symmetric_upper_apply(&self.stiffness, &q);
            rhs.iter_mut().zip(&kq).for_each(|(a, b)| *a += b);
        }
        rhs
    }

    /// Ends the step with force `f` at the point. With damping, the energy the step's
    /// damping takes is added to [`Self::damping_loss`]: Δt v̄ᵀCv̄ with v̄ = Δw/Δt the step's
    /// mean velocity, exactly what the average-acceleration rule's energy balance loses.
    pub fn commit(&mut self, f: f64) {
        if let Some((r, loss)) = self.damping {
            let dw: Vec<f64> =
                (0..self.w.len()).map(|i| self.w_hat[i] + f * self.unit_response[i] - self.w[i]).collect();
            let mut step = r.alpha * dot(&dw, &symmetric_upper_apply(&self.mass, &dw));
            if r.beta != 0.0 {
                step += r.beta * dot(&dw, &symmetric_upper_apply(&self.stiffness, &dw));
            }
            self.damping = Some((r, loss + step / self.dt));
        }
        let (c0, c1) = (4.0 / (self.dt * self.dt), 4.0 / self.dt);
        for i in 0..self.w.len() {
            let w_new = self.w_hat[i] + f * self.unit_response[i];
            let a_new = c0 * (w_new - self.w[i]) - c1 * self.v[i] - self.a[i];
            self.v[i] += 0.5 * self.dt * (self.a[i] + a_new);
            self.a[i] = a_new;
            self.w[i] = w_new;
        }
        self.refresh();
    }

    /// After a step: the energies' quadratic forms of the new state and, undamped, the next
    /// predictor's right-hand side M(c₀w + c₁v + a), in one pass where the patterns allow.
    fn refresh(&mut self) {
        if self.damping.is_some() {
            self.quadratic =
                (symmetric_upper_quadratic(&self.mass, &self.v), symmetric_upper_quadratic(&self.stiffness, &self.w));
            return;
        }
        let (c0, c1) = (4.0 / (self.dt * self.dt), 4.0 / self.dt);
        for i in 0..self.w.len() {
            self.combination[i] = c0 * self.w[i] + c1 * self.v[i] + self.a[i];
        }
        if self.shared_pattern {
            self.quadratic = mass_stiffness_pass(
                (&self.mass, &self.stiffness),
                (&self.combination, &self.v, &self.w),
                &mut self.next_rhs,
            );
        } else {
            symmetric_upper_apply_into(&self.mass, &self.combination, &mut self.next_rhs);
            self.quadratic =
                (symmetric_upper_quadratic(&self.mass, &self.v), symmetric_upper_quadratic(&self.stiffness, &self.w));
        }
    }

    /// The energy the plate's damping has taken since rest, J (0 undamped).
    pub fn damping_loss(&self) -> f64 {
        self.damping.map_or(0.0, |(_, loss)| loss)
    }

    /// Kinetic, strain and spring energy of the plate now.
    pub fn energy(&self) -> PlateEnergy {
        let (kinetic, total) = (0.5 * self.quadratic.0, 0.5 * self.quadratic.1);
        let mesh = self.model.mesh();
        let mut springs: f64 = Corner::ALL
            .iter()
            .zip(&self.supports.corners)
            .map(|(c, s)| match *s {
                CornerSupport::Spring(k) => 0.5 * k * self.w[mesh.corner_w_dof(c.index())].powi(2),
                _ => 0.0,
            })
            .sum();
        if self.supports.edges.iter().any(|e| matches!(e, EdgeSupport::Elastic(_))) {
            springs += 0.5 * self.model.edge_spring_store(&self.supports, &self.w);
        }
        PlateEnergy { kinetic, strain: total - springs, springs }
    }

    /// Deflections of the four corners now, in [`Corner::ALL`] order.
    pub fn corner_displacements(&self) -> [f64; 4] {
        let mesh = self.model.mesh();
        Corner::ALL.map(|c| self.w[mesh.corner_w_dof(c.index())])
    }

    /// The deflection field now.
    pub fn field(&self) -> &[f64] {
        &self.w
    }

    /// The velocity field ẇ now.
    pub fn velocity_field(&self) -> &[f64] {
        &self.v
    }

    /// The acceleration field ẅ now (the rule's step-end acceleration, which satisfies the
    /// equation of motion there).
    pub fn acceleration_field(&self) -> &[f64] {
        &self.a
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The fundamental angular frequency ω₁ of the supported plate (rad/s), by inverse
/// iteration with the Rayleigh quotient; returns (ω₁, relative change of the last step).
pub fn fundamental_frequency(model: &Model, supports: &Supports, iterations: usize) -> Result<(f64, f64), FemError> {
    let f = model.factorize(supports)?;
    let k = model.supported_matrix(supports, 1.0, 0.0, false)?;
    let m = model.supported_mass(supports)?;
    let n = model.dofs();
    // Start from the static deflection under a uniform-ish load (all w DOFs 1).
    let mut x: Vec<f64> = (0..n).map(|i| if i % 4 == 0 { 1.0 } else { 0.0 }).collect();
    let (mut omega2, mut change) = (f64::NAN, f64::NAN);
    for _ in 0..iterations.max(2) {
        let mx = symmetric_upper_apply(&m, &x);
        let mut y = Mat::from_fn(n, 1, |i, _| mx[i]);
        f.solve_in_place(&mut y);
        x = (0..n).map(|i| y[(i, 0)]).collect();
        let kx = symmetric_upper_apply(&k, &x);
        let mx = symmetric_upper_apply(&m, &x);
        let q = dot(&x, &kx) / dot(&x, &mx);
        change = ((q - omega2) / q).abs();
        omega2 = q;
        let norm = dot(&x, &mx).sqrt();
        x.iter_mut().for_each(|v| *v /= norm);
        if change < 1e-13 {
            break;
        }
    }
    Ok((omega2.sqrt(), change))
}
