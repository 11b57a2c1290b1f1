//! The reduced-order transient model: the supported plate's lowest N modes plus the static
//! correction of the rest, struck by the sphere with the full model's contact laws and
//! contact sequence, and the sensor signals of the impact.
//!
//! **Model.** The plate FE model of [`crate::transient`] (same mesh rule, same supports) is
//! projected on its lowest N modes (plate_fem::modes, shift-invert Krylov on the support
//! set's factorization, computed once per plate and support set in [`ReducedModel::new`]).
//! The modes left out answer the contact force quasi-statically through their residual
//! flexibility R = K⁻¹ - Σ_{i≤N} φᵢφᵢᵀ/ωᵢ² (the static correction): at the struck point
//! C_res(p) = N(p)ᵀRN(p), between the struck point and a sensor or corner N(p)ᵀR f. Every
//! mode carries the modal damping ratio ζ of the settings.
//!
//! **Impact.** The modal plate is a [`crate::transient::Target`] ([`target`]), so
//! [`crate::transient::simulate_with`] runs it: the same contact law solve per step, the same
//! contact sequence, the same stopping rule (with the full FE static compliance at p, which
//! bounds the modal point deflection too). While a force acts each mode takes Newmark's step,
//! as the full model does; while none acts each mode is propagated exactly. The step is
//! Δt = T_s/m, the largest divisor of the sample interval T_s = 1/rate not above
//! t_c/`steps_per_contact` (t_c the rigid-target Hertz time), so samples fall on step ends.
//! Once the sphere has provably left, the rest of the window is exact free vibration at the
//! sample times ([`window`]): nothing is time-stepped there.
//!
//! **Speed.** Every pass over the modes (a step's end and prediction, the stopping rule's
//! bound, the window's states and channels) runs on the widest vector instructions the
//! processor has, chosen at run time; the operations and their order are those of plain
//! x86-64 code, so the results are the same bits on any processor.
//!
//! **Damping.** The full model is undamped; the default modal damping ratio is
//! [`ReducedSettings::DEFAULT_DAMPING_RATIO`] = 0.5 %, the structural damping of a bolted
//! steel structure (Eurocode EN 1991-1-4, Table F.2: logarithmic decrement 0.03 for bolted
//! steel, 0.02 welded, i.e. ζ = δ/2π = 0.48 % and 0.32 %). Comparisons with the full model
//! use ζ = 0.
//!
//! ```
//! use analytic::{Elastic, Plate, RockStrength, Sphere};
//! use coupled::reduced::{ReducedModel, ReducedSettings, SignalSpec};
//! use coupled::transient::case::striker;
//! use coupled::SupportSet;
//! use plate_fem::Supports;
//! let plate = Plate::new(0.4584, 0.36, 0.008, 7850.0, Elastic::new(210e9, 0.3)?)?;
//! let settings = ReducedSettings { modes: 20, elements: 8, ..ReducedSettings::default() };
//! let model = ReducedModel::new(&plate, &SupportSet::new("Con 1", Supports::con1()), settings)?;
//! let coal = Sphere::new("coal", 1380.0, 0.025, Elastic::new(2.26e9, 0.28)?, RockStrength::new(8.39e6, 25.0)?)?;
//! let probes = model.probes(&SignalSpec::new(vec![(0.1, 0.1)]))?;
//! let hit = model.impact(&striker(&plate, &coal, 0.65, 0.008), 0.2292, 0.18, &probes)?;
//! assert_eq!(hit.outcome.contacts.len(), 1);
//! // 20 ms at 20 kHz: 400 samples per channel; 3 sensor channels and 4 corner reactions.
//! assert_eq!(hit.signals.channels.len(), 7);
//! assert!(hit.signals.channels.iter().all(|c| c.samples.len() == 400));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod channels;
mod corners;
mod impact;
pub mod plan;
pub mod signals;
pub mod stream;
pub mod structure;
pub mod target;
pub mod window;

pub use signals::{free_map, newmark_map, Channel, ChannelKind, Probes, Quantity, SignalSpec, Signals};

pub use target::FreeSteps;
pub use window::Arithmetic;

use crate::discretisation::{mesh_for, plate_properties};
use crate::error::ModelError;
use crate::supports::SupportSet;
use crate::transient::{Outcome, Striker};
use analytic::params::{check, Range};
use analytic::Plate;
use corners::{corner_data, CornerData};
use plate_fem::dynamics::Rayleigh;
use plate_fem::modes::shape_at;
use plate_fem::{Mesh, Model, Modes, ResidualFlexibility};
use serde::Serialize;
use signals::FreeMaps;

/// How the truncated modes enter.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Correction {
    /// Quasi-statically, w_res = C_res(p)P: the static correction (mode acceleration).
    #[default]
    Static,
    /// As one more mode: the residual shape ψ = RN(p) with its stiffness and mass
    /// (plate_fem::ResidualFlexibility), which keeps the static compliance and adds the
    /// truncated modes' inertia.
    ResidualMode,
}

/// How the reduced model is built.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ReducedSettings {
    /// N, the modes kept.
    pub modes: usize,
    /// Modal damping ratio ζ of every mode.
    pub damping_ratio: f64,
    /// Rayleigh damping in place of `damping_ratio`: mode i gets ζᵢ = α/(2ωᵢ) + βωᵢ/2, the
    /// ratio the full model's C = αM + βK gives it, so that both models answer the same
    /// question.
    pub rayleigh: Option<Rayleigh>,
    /// Elements along the longer side of the plate (the full model's mesh rule).
    pub elements: usize,
    /// The time step in contact is at most the Hertz time over this.
    pub steps_per_contact: f64,
    /// How the truncated modes enter.
    pub correction: Correction,
    /// How the window's free part is summed into its channels. Left out of the serialised
    /// settings when exact, so that a model without it keeps its provenance hash.
    #[serde(skip_serializing_if = "Arithmetic::is_exact")]
    pub arithmetic: Arithmetic,
}

impl ReducedSettings {
    /// Default N.
    pub const DEFAULT_MODES: usize = 80;
    /// Default steps per Hertz contact time: 100. Newmark's rule is second order with the
    /// full model's error near 4e-5 in the peak force at 200 steps, so 100 steps put it near
    /// 1.6e-4, inside the 1e-3 the reduced model is held to, at half the cost of the
    /// contact phase (which dominates an impact's cost).
    pub const DEFAULT_STEPS_PER_CONTACT: f64 = 100.0;
    /// Default ζ (see the module documentation).
    pub const DEFAULT_DAMPING_RATIO: f64 = 0.005;
    /// Allowed ζ: the exact free-vibration map needs ζ < 1; beyond half of critical a mode
    /// no longer rings, and no plate structure is damped that much.
    pub const DAMPING_RATIO: Range = Range::closed(0.0, 0.5);
    /// Allowed N (the plate's free DOFs are a further bound, checked on the mesh).
    pub const MODES: Range = Range::closed(1.0, 2000.0);
}

impl ReducedSettings {
    /// The damping of the modes: Rayleigh's where given, else the one ratio.
    pub fn damping(&self) -> ModalDamping {
        self.rayleigh.map_or(ModalDamping::Ratio(self.damping_ratio), ModalDamping::Rayleigh)
    }
}

/// The damping ratio of each mode.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum ModalDamping {
    /// The same ratio ζ for every mode.
    Ratio(f64),
    /// Rayleigh's C = αM + βK: ζᵢ = α/(2ωᵢ) + βωᵢ/2.
    Rayleigh(Rayleigh),
}

impl ModalDamping {
    /// The damping ratio of the mode of circular frequency `omega` (rad/s).
    pub fn at(&self, omega: f64) -> f64 {
        match self {
            ModalDamping::Ratio(z) => *z,
            ModalDamping::Rayleigh(r) => r.ratio(omega),
        }
    }
}

impl Default for ReducedSettings {
    /// N = [`Self::DEFAULT_MODES`], ζ = 0.5 %, the full model's 20 elements,
    /// [`Self::DEFAULT_STEPS_PER_CONTACT`] steps per contact time, the static correction.
    fn default() -> Self {
        Self {
            modes: Self::DEFAULT_MODES,
            damping_ratio: Self::DEFAULT_DAMPING_RATIO,
            rayleigh: None,
            elements: 20,
            steps_per_contact: Self::DEFAULT_STEPS_PER_CONTACT,
            correction: Correction::default(),
            arithmetic: Arithmetic::Exact,
        }
    }
}

/// What a scene asks of the reduced model and its signals (validated, SI units).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SignalSettings {
    /// Window from first touch, s.
    pub window: f64,
    /// Sampling rate, Hz.
    pub rate_hz: f64,
    /// Modal damping ratio ζ.
    pub damping_ratio: f64,
    /// The scene's plate damping, which replaces `damping_ratio` when given.
    pub rayleigh: Option<Rayleigh>,
    /// N, the modes kept; with `modes_from_chain`, the most that may be kept.
    pub modes: usize,
    /// Whether each support set keeps only the modes the measurement chain needs: the fewest
    /// whose highest the chain's gain above stays within its band tolerance
    /// (`identify::measurement::Chain::modes_needed`), at most `modes`. Left out of the
    /// serialised scene when false, so that a scene without it keeps its provenance hash.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub modes_from_chain: bool,
    /// Sensor points (x, z), m.
    pub sensors: Vec<(f64, f64)>,
    /// The share of each family's impacts that the identification's check on N/2 modes
    /// strikes again (a stratified random subsample, `identify::subsample`), within (0, 1].
    /// Left out of the serialised scene at 1, so that a scene without it keeps its
    /// provenance hash.
    #[serde(skip_serializing_if = "is_whole")]
    pub truncation_check: f64,
    /// How the window's free part is summed into its channels ([`Arithmetic`]). Left out of
    /// the serialised scene when exact, so that a scene without it keeps its provenance hash.
    #[serde(skip_serializing_if = "Arithmetic::is_exact")]
    pub arithmetic: Arithmetic,
}

/// Whether a share is the whole.
fn is_whole(share: &f64) -> bool {
    *share == 1.0
}

impl Default for SignalSettings {
    /// 20 ms at 20 kHz, ζ = 0.5 %, N = 80, no sensors (corner channels only).
    fn default() -> Self {
        Self {
            window: SignalSpec::DEFAULT_WINDOW,
            rate_hz: SignalSpec::DEFAULT_RATE_HZ,
            damping_ratio: ReducedSettings::DEFAULT_DAMPING_RATIO,
            rayleigh: None,
            modes: ReducedSettings::DEFAULT_MODES,
            modes_from_chain: false,
            sensors: Vec::new(),
            truncation_check: 1.0,
            arithmetic: Arithmetic::Exact,
        }
    }
}

impl SignalSettings {
    /// The signal spec: every quantity at every sensor, and the corner channels.
    pub fn spec(&self) -> SignalSpec {
        SignalSpec { window: self.window, rate_hz: self.rate_hz, ..SignalSpec::new(self.sensors.clone()) }
    }
    /// The reduced model's settings (the other fields at their defaults).
    pub fn reduced(&self) -> ReducedSettings {
        ReducedSettings {
            modes: self.modes,
            damping_ratio: self.damping_ratio,
            rayleigh: self.rayleigh,
            arithmetic: self.arithmetic,
            ..ReducedSettings::default()
        }
    }
}

/// The reduced model of one plate on one support set.
pub struct ReducedModel {
    set: SupportSet,
    settings: ReducedSettings,
    model: Model,
    modes: Modes,
    omega: Vec<f64>,
    /// φ by DOF: `phi[d * N + i]` is mode i at DOF d.
    phi: Vec<f64>,
    residual: ResidualFlexibility,
    corners: Vec<CornerData>,
    /// The widest vector instruction set of this processor (detected once): the passes
    /// over the modes run on it, with the same operations in the same order as on plain
    /// x86-64, so with the same results.
    simd: pulp::Arch,
}

/// The outcome of one reduced impact.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReducedOutcome {
    /// The contact sequence and first-contact numbers, as the full model reports them.
    pub outcome: Outcome,
    /// The sensor and corner signals.
    pub signals: Signals,
    /// The time step used in contact, s.
    pub dt: f64,
    /// The FE static compliance at the struck point, m/N.
    pub static_compliance: f64,
    /// Its part carried by the truncated modes, C_res(p), m/N.
    pub residual_compliance: f64,
    /// The residual mode's frequency ω_ψ/2π, Hz (None with the static correction, or when
    /// the kept modes carry the whole compliance).
    pub residual_mode_hz: Option<f64>,
}

/// What the modes and the truncated modes give at one impact point.
struct Point {
    dofs: [usize; 16],
    shape: plate_fem::element::Vec16,
    phi: Vec<f64>,
    c_res: f64,
    /// m_ψ, the residual shape's mass (with the residual-mode correction only).
    m_res: Option<f64>,
}

impl ReducedModel {
    /// Meshes the plate, finds its lowest `settings.modes` modes on `set` and the residual
    /// flexibility of the rest.
    pub fn new(plate: &Plate, set: &SupportSet, settings: ReducedSettings) -> Result<Self, ModelError> {
        check("reduced.damping_ratio", settings.damping_ratio, ReducedSettings::DAMPING_RATIO, "")?;
        check("reduced.steps_per_contact", settings.steps_per_contact, Range::closed(4.0, 1e5), "")?;
        let model = mesh_model(plate, settings)?;
        let (fact, modes) = lowest_modes(&model, set, settings.modes)?;
        // The residual shape's mass (K⁻¹MK⁻¹, by solves) only where it enters as a mode.
        let residual = match settings.correction {
            Correction::Static => ResidualFlexibility::new(&fact, &modes)?,
            Correction::ResidualMode => ResidualFlexibility::with_inertia(&fact, &modes)?,
        };
        let n = modes.count();
        let ndof = model.dofs();
        let shapes = modes.shapes();
        let mut phi = vec![0.0; ndof * n];
        for d in 0..ndof {
            for i in 0..n {
                phi[d * n + i] = shapes[(d, i)];
            }
        }
        let omega = modes.omegas().to_vec();
        let corners = corner_data(&model, &fact, &modes, &set.supports, &phi);
        drop(fact);
        Ok(Self { set: set.clone(), settings, model, modes, omega, phi, residual, corners, simd: pulp::Arch::new() })
    }

    /// The settings it was built with.
    pub fn settings(&self) -> ReducedSettings {
        self.settings
    }
    /// The support set.
    pub fn support_set(&self) -> &SupportSet {
        &self.set
    }
    /// The modes (frequencies, shapes, residuals).
    pub fn modes(&self) -> &Modes {
        &self.modes
    }
    /// The mesh.
    pub fn mesh(&self) -> &Mesh {
        self.model.mesh()
    }

    fn point(&self, x: f64, z: f64) -> Result<Point, ModelError> {
        let mesh = self.model.mesh();
        let loc = mesh.locate(x, z)?;
        let (dofs, shape) = shape_at(mesh, x, z)?;
        // φᵢ(p) is the point functional of the shape functions on the modes.
        let phi = self.functional_modes(&dofs, &shape);
        let e = loc.ez * mesh.nx() + loc.ex;
        let c_res = self.residual.quadratic(e, &shape).max(0.0);
        let m_res = self.residual.mass_quadratic(e, &shape).map(|m| m.max(0.0));
        Ok(Point { dofs, shape, phi, c_res, m_res })
    }

    /// A point functional on the modes, ℓ(φᵢ) = Σ_k values_k φᵢ[dofs_k], for every mode: the
    /// deflection's (values the shape functions) or a strain gauge's.
    fn functional_modes(&self, dofs: &[usize; 16], values: &plate_fem::element::Vec16) -> Vec<f64> {
        let n = self.omega.len();
        let mut out = vec![0.0; n];
        for k in 0..16 {
            let row = &self.phi[dofs[k] * n..(dofs[k] + 1) * n];
            for (o, r) in out.iter_mut().zip(row) {
                *o += values[k] * r;
            }
        }
        out
    }

    /// φᵢ(p) for every mode and C_res(p), at p = (x, z).
    pub fn at(&self, x: f64, z: f64) -> Result<(Vec<f64>, f64), ModelError> {
        let p = self.point(x, z)?;
        Ok((p.phi, p.c_res))
    }

    /// The FE static compliance C(p) = Σφᵢ(p)²/ωᵢ² + C_res(p), m/N.
    pub fn static_compliance(&self, x: f64, z: f64) -> Result<f64, ModelError> {
        let (phi_p, c_res) = self.at(x, z)?;
        Ok(modal_compliance(&phi_p, &self.omega) + c_res)
    }

    /// One impact of `striker` at (x, z) with the signals of `probes` (see the module).
    pub fn impact(&self, striker: &Striker, x: f64, z: f64, probes: &Probes) -> Result<ReducedOutcome, ModelError> {
        self.impact_with(striker, x, z, probes, FreeSteps::Exact)
    }

    /// As [`Self::impact`], with the free steps propagated as `free` says.
    pub fn impact_with(
        &self,
        striker: &Striker,
        x: f64,
        z: f64,
        probes: &Probes,
        free: FreeSteps,
    ) -> Result<ReducedOutcome, ModelError> {
        let ts = probes.spec.interval();
        let dt_max = striker.hertz_time() / self.settings.steps_per_contact;
        let every = (ts / dt_max).ceil().max(1.0) as usize;
        let dt = ts / every as f64;
        let map = (free == FreeSteps::Exact).then(|| probes.step_map(every));
        self.run(striker, x, z, probes, map, dt, every)
    }

    /// As [`Self::impact_with`] with the time step `dt` given (the sample interval is then
    /// rounded to a whole number of steps), for comparisons at the full model's step.
    pub fn impact_with_step(
        &self,
        striker: &Striker,
        x: f64,
        z: f64,
        probes: &Probes,
        free: FreeSteps,
        dt: f64,
    ) -> Result<ReducedOutcome, ModelError> {
        check("dt", dt, Range::open(0.0, f64::INFINITY), "s")?;
        let every = (probes.spec.interval() / dt).round().max(1.0) as usize;
        let map = (free == FreeSteps::Exact).then(|| FreeMaps::new(&self.omega, self.settings.damping(), dt));
        self.run(striker, x, z, probes, map, dt, every)
    }
}

/// The natural frequencies of the lowest `settings.modes` modes of `plate` on `set`, Hz, on
/// the reduced model's mesh: the modes [`ReducedModel::new`] would keep, without the residual
/// flexibility it builds on them (to choose how many to keep).
pub fn frequencies_hz(plate: &Plate, set: &SupportSet, settings: ReducedSettings) -> Result<Vec<f64>, ModelError> {
    let model = mesh_model(plate, settings)?;
    let (_, modes) = lowest_modes(&model, set, settings.modes)?;
    Ok(modes.omegas().iter().map(|w| w / (2.0 * std::f64::consts::PI)).collect())
}

/// The plate's FE model on the reduced model's mesh (`settings.elements` along the longer side).
fn mesh_model(plate: &Plate, settings: ReducedSettings) -> Result<Model, ModelError> {
    check("reduced.modes", settings.modes as f64, ReducedSettings::MODES, "")?;
    check("reduced.elements", settings.elements as f64, Range::closed(2.0, 400.0), "")?;
    let props = plate_properties(plate);
    Ok(Model::new(props, mesh_for(&props, settings.elements)?)?)
}

/// The factorization of `model` on `set` and its lowest `count` modes (dense below
/// [`plate_fem::modes::DENSE_LIMIT`] free DOFs, else shift-invert Krylov on the
/// factorization).
fn lowest_modes<'m>(
    model: &'m Model,
    set: &SupportSet,
    count: usize,
) -> Result<(plate_fem::Factorization<'m>, Modes), ModelError> {
    let fact = model.factorize(&set.supports)?;
    let free = model.dofs() - fact.held().len();
    let modes = if free <= plate_fem::modes::DENSE_LIMIT {
        Modes::dense(model, &set.supports, count)?
    } else {
        Modes::krylov(&fact, count)?
    };
    Ok((fact, modes))
}

/// Σ φᵢ(p)²/ωᵢ²: the modes' part of the static compliance.
fn modal_compliance(phi_p: &[f64], omega: &[f64]) -> f64 {
    phi_p.iter().zip(omega).map(|(f, w)| f * f / (w * w)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::transient::case::striker;
    use analytic::{Elastic, RockStrength, Sphere};
    use plate_fem::Supports;

    /// The passes over the modes run on the widest vector instructions the processor has
    /// (detected at run time) and must give exactly what plain x86-64 code gives: the same
    /// operations in the same order, only more of them at once, and no fused multiply-add.
    /// Against the model forced onto the baseline path: 16 impacts of coal and gangue at
    /// 0.5-4 m/s spread over the plate (Con 3, N = 30, 2 sensors, 10 ms, static correction
    /// and residual mode), every sample of every channel, every force of the history and
    /// the contact sequence are equal. (On a processor without AVX2 both runs take the
    /// baseline path.)
    #[test]
    fn vector_paths_give_the_baseline_results() {
        let plate = Plate::new(0.4584, 0.36, 0.008, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap();
        let set = SupportSet::new("Con 3", Supports::con3(5.11545e8));
        let bodies = [
            Sphere::new(
                "coal",
                1380.0,
                0.025,
                Elastic::new(2.26e9, 0.28).unwrap(),
                RockStrength::new(8.39e6, 25.0).unwrap(),
            )
            .unwrap(),
            Sphere::new(
                "gangue",
                2400.0,
                0.025,
                Elastic::new(16e9, 0.28).unwrap(),
                RockStrength::new(10e6, 30.0).unwrap(),
            )
            .unwrap(),
        ];
        for (correction, arithmetic) in [
            (Correction::Static, Arithmetic::Exact),
            (Correction::ResidualMode, Arithmetic::Exact),
            (Correction::Static, Arithmetic::Fast),
        ] {
            let settings =
                ReducedSettings { modes: 30, elements: 8, correction, arithmetic, ..ReducedSettings::default() };
            let fast = ReducedModel::new(&plate, &set, settings).unwrap();
            let mut plain = ReducedModel::new(&plate, &set, settings).unwrap();
            plain.simd = pulp::Arch::Scalar;
            let spec = SignalSpec { window: 0.01, ..SignalSpec::new(vec![(0.1, 0.1), (0.35, 0.3)]) };
            let (pf, pp) = (fast.probes(&spec).unwrap(), plain.probes(&spec).unwrap());
            for k in 0..16 {
                let s = striker(&plate, &bodies[k % 2], 0.65, 0.5 + 0.23 * k as f64);
                let (x, z) = (0.02 + 0.027 * k as f64, 0.33 - 0.019 * k as f64);
                let (a, b) = (fast.impact(&s, x, z, &pf).unwrap(), plain.impact(&s, x, z, &pp).unwrap());
                assert_eq!(a, b, "impact {k} ({correction:?}, {arithmetic:?})");
            }
        }
    }

    /// The fast arithmetic touches only the sums of the window's free part: over 16 impacts
    /// of coal and gangue at 0.5-4 m/s (Con 3, N = 30, two sensors with every quantity and the
    /// corners, 10 ms) the contact sequence, every force and every number of the outcome are
    /// the exact run's to the bit, and every sample of every channel lies within 2e-5 of the
    /// channel's largest value from the exact one: γ₆₂ = 3.7e-6 for its 2N + 2 terms in f32
    /// (Higham's bound) times Σ|cᵢsᵢ| over |y|, which the modes' partial cancellation keeps
    /// within a few units here. Some sample differs (the f32 sums are in use).
    #[test]
    fn fast_arithmetic_changes_only_the_free_sums() {
        let plate = Plate::new(0.4584, 0.36, 0.008, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap();
        let set = SupportSet::new("Con 3", Supports::con3(5.11545e8));
        let body = |name, rho, e| {
            Sphere::new(name, rho, 0.025, Elastic::new(e, 0.28).unwrap(), RockStrength::new(9e6, 28.0).unwrap())
                .unwrap()
        };
        let bodies = [body("coal", 1380.0, 2.26e9), body("gangue", 2400.0, 16e9)];
        let settings = ReducedSettings { modes: 30, elements: 8, ..ReducedSettings::default() };
        let exact = ReducedModel::new(&plate, &set, settings).unwrap();
        let fast =
            ReducedModel::new(&plate, &set, ReducedSettings { arithmetic: Arithmetic::Fast, ..settings }).unwrap();
        let spec = SignalSpec { window: 0.01, ..SignalSpec::new(vec![(0.1, 0.1), (0.35, 0.3)]) };
        let (pe, pf) = (exact.probes(&spec).unwrap(), fast.probes(&spec).unwrap());
        let (mut largest, mut differ) = (0.0f64, false);
        for k in 0..16 {
            let s = striker(&plate, &bodies[k % 2], 0.65, 0.5 + 0.23 * k as f64);
            let (x, z) = (0.02 + 0.027 * k as f64, 0.33 - 0.019 * k as f64);
            let (a, b) = (exact.impact(&s, x, z, &pe).unwrap(), fast.impact(&s, x, z, &pf).unwrap());
            assert_eq!(a.outcome, b.outcome, "impact {k}");
            assert_eq!(
                (a.dt, a.static_compliance, a.residual_compliance),
                (b.dt, b.static_compliance, b.residual_compliance)
            );
            for (ca, cb) in a.signals.channels.iter().zip(&b.signals.channels) {
                let top = ca.samples.iter().fold(0.0f64, |m, y| m.max(y.abs()));
                for (ya, yb) in ca.samples.iter().zip(&cb.samples) {
                    largest = largest.max((ya - yb).abs() / top);
                    differ |= ya != yb;
                }
            }
        }
        assert!(largest <= 2e-5, "largest difference {largest:e} of a channel's largest value");
        assert!(differ, "the fast run summed in f64");
    }
}
