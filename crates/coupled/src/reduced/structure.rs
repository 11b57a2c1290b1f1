//! The reduced model of a shell structure (a tail beam, a structure read from a mesh) struck
//! by the sphere: the plate's reduced model ([`super`]) on the structure's own modes.
//!
//! **Model.** The restrained structure's lowest N modes with its lumped mass
//! ([`plate_fem::shell::ShellModes`]), each with the modal damping ratio of the settings;
//! the contact force acts as a pressure of unit resultant over a small area at the struck
//! point (load vector f), so mode i feels φᵢ(p)P with φᵢ(p) = φᵢᵀf, and the structure's
//! deflection there is Σφᵢ(p)qᵢ + C_res(p)P, where C_res(p) = fᵀK⁻¹f - Σφᵢ(p)²/ωᵢ² is the
//! truncated modes' static correction (Craig & Kurdila, *Fundamentals of Structural
//! Dynamics*, 2nd ed., 2006). The impact runs through the plate's time loop
//! ([`crate::transient::simulate_with`]) on the same modal target ([`super::target`]):
//! Newmark's rule on every mode while a force acts, the exact damped free vibration while
//! none does, the contact law solved at each step's end, and the stopping rule with the
//! static compliance fᵀK⁻¹f. The step is the rigid-target Hertz time over
//! `steps_per_contact`.
//!
//! **Springs.** A group of springs to ground (a jack's pad) carries the force Σ gᵀu, g its
//! springs' coefficients ([`plate_fem::shell::Spring::coefficients`]): on the modes
//! Σ(gᵀφᵢ)qᵢ, plus the static correction's part (gᵀK⁻¹f - Σ gᵀφᵢ φᵢᵀf/ωᵢ²)P. It is recorded
//! at every step over the window, free vibration after the sphere has left included, so its
//! peak is the jack's dynamic force, whose quasi-static counterpart is the force under the
//! peak contact force held still.
//!
//! ```
//! use coupled::reduced::structure::{Readings, StructureModel, StructureSettings};
//! use coupled::transient::{ContactLaw, Striker, law::Flores};
//! use plate_fem::shell::{Face, Restraints, ShellMass, Structure, DISC_RULE};
//! // A 0.4 x 0.3 m steel plate, 10 mm thick, its edges held in translation, as a shell.
//! let mut s = Structure::new(210e9, 0.3)?;
//! let lines = |l: f64, n: usize| (0..=n).map(|i| l * i as f64 / n as f64).collect::<Vec<_>>();
//! let face = Face::new([0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], lines(0.4, 12), lines(0.3, 9), 0.01)?;
//! s.add_face(&face)?;
//! let mut r = Restraints::default();
//! for n in s.nodes_where(|p| p[0] == 0.0 || p[0] == 0.4 || p[2] == 0.0 || p[2] == 0.3) {
//!     r.hold(n, &[0, 1, 2]);
//! }
//! let fact = s.factorize(&r)?;
//! let load = s.disc_load([0.2, 0.0, 0.15], 0.005, &(0..s.elements()).collect::<Vec<_>>(), DISC_RULE)?;
//! let settings = StructureSettings { modes: 30, ..StructureSettings::default() };
//! let model = StructureModel::new(&fact, &ShellMass::lumped(&s, 7850.0), &[load], Readings::default(), settings)?;
//! let ball = Striker { k: 5e9, restitution: 1.0, mass: 0.1, velocity: 1.0, law: ContactLaw::Flores(Flores), gravity: 0.0 };
//! let hit = model.impact(&ball, 0, 2e-3)?;
//! // Softer than a rigid target: the force stays below Hertz's.
//! assert!(hit.outcome.force_max > 0.0 && hit.outcome.force_max < ball.hertz_force());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::signals::{ChannelKind, ChannelRows, FreeMaps, Probes, SignalSpec};
use super::stream::{Arrival, Span, StreamResponse, Struck, StruckAt};
use super::target::{ChannelRow, ModalTarget, Recording};
use super::{modal_compliance, Arithmetic, ModalDamping, ReducedSettings};
use crate::error::ModelError;
use crate::transient::{simulate_with, Outcome, PlateFacts, Striker};
use analytic::params::{check, Range};
use plate_fem::shell::{Factorized, ShellMass, ShellModes, Spring};
use serde::Serialize;

/// How a structure's reduced model is built and stepped.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StructureSettings {
    /// N, the modes kept.
    pub modes: usize,
    /// The damping ratio of the modes.
    pub damping: ModalDamping,
    /// The time step is at most the Hertz time over this.
    pub steps_per_contact: f64,
    /// How the free samples are summed into the channels (left out of the serialised
    /// settings when exact: the provenance hashes of exact runs stay as they were).
    #[serde(skip_serializing_if = "Arithmetic::is_exact")]
    pub arithmetic: Arithmetic,
}

impl Default for StructureSettings {
    /// The plate's reduced model's defaults: 80 modes, ζ = 0.5 %, 100 steps per contact.
    fn default() -> Self {
        Self {
            modes: ReducedSettings::DEFAULT_MODES,
            damping: ModalDamping::Ratio(ReducedSettings::DEFAULT_DAMPING_RATIO),
            steps_per_contact: ReducedSettings::DEFAULT_STEPS_PER_CONTACT,
            arithmetic: Arithmetic::Exact,
        }
    }
}

/// What an impact at one point needs of the modes.
#[derive(Debug, Clone)]
struct StruckPoint {
    /// φᵢ(p) = φᵢᵀf.
    phi: Vec<f64>,
    /// fᵀK⁻¹f, m/N.
    static_compliance: f64,
    /// C_res(p), m/N.
    residual: f64,
    /// Per spring group, its force's static-correction part per unit contact force,
    /// gᵀK⁻¹f - Σ gᵀφᵢ φᵢᵀf/ωᵢ².
    group_d: Vec<f64>,
    /// Per spring group, its force per unit static contact force.
    group_static: Vec<f64>,
}

/// A structure's modes and its struck points, built once for many impacts.
pub struct StructureModel {
    omega: Vec<f64>,
    settings: StructureSettings,
    points: Vec<StruckPoint>,
    /// Per spring group, its force on the modes, gᵀφᵢ.
    group_rows: Vec<Vec<f64>>,
    /// Per accelerometer, its reading on the modes, aᵀφᵢ.
    accelerometers: Vec<Vec<f64>>,
    /// The static cross compliances fⱼᵀK⁻¹fₖ of the load points, row-major.
    static_cross: Vec<f64>,
    basis: usize,
    largest_residual: f64,
    simd: pulp::Arch,
}

/// One impact on the structure.
#[derive(Debug, Clone, Serialize)]
pub struct StructureImpact {
    /// The contact's course.
    pub outcome: Outcome,
    /// Each spring group's largest |force| over the window, N.
    pub group_force_max: Vec<f64>,
    /// The time step, s.
    pub dt: f64,
}

impl StructureModel {
    /// The lowest `settings.modes` modes of the structure `fact` (factorized) with `mass`,
    /// and the struck points' load vectors `loads` (unit resultant, all DOFs); the forces of
    /// the spring groups of `readings` are followed in every impact, and its accelerometers
    /// are recorded in a stream ([`Self::probes`]).
    pub fn new(
        fact: &Factorized<'_>,
        mass: &ShellMass,
        loads: &[Vec<f64>],
        readings: Readings<'_>,
        settings: StructureSettings,
    ) -> Result<Self, ModelError> {
        let groups = readings.groups;
        check("modes", settings.modes as f64, ReducedSettings::MODES, "")?;
        check("steps_per_contact", settings.steps_per_contact, Range::closed(4.0, 1e5), "")?;
        check("load points", loads.len() as f64, Range::closed(0.0, MAX_LOAD_POINTS as f64), "")?;
        let dofs = fact.dofs();
        for (k, f) in loads.iter().enumerate() {
            if f.len() != dofs || !f.iter().all(|v| v.is_finite()) {
                return Err(ModelError::Missing(format!(
                    "load {k} has {} entries (finite: {}) for a structure of {dofs} DOFs",
                    f.len(),
                    f.iter().all(|v| v.is_finite())
                )));
            }
        }
        for s in groups.iter().flatten() {
            s.check(dofs / 6)?;
        }
        for (k, a) in readings.accelerometers.iter().enumerate() {
            if a.len() != dofs || !a.iter().all(|v| v.is_finite()) {
                return Err(ModelError::Missing(format!(
                    "accelerometer {k} has {} entries (finite: {}) for a structure of {dofs} DOFs",
                    a.len(),
                    a.iter().all(|v| v.is_finite())
                )));
            }
        }
        let modes = fact.modes(mass, settings.modes)?;
        for (i, &w) in modes.omegas().iter().enumerate() {
            check(
                &format!("damping ratio of mode {}", i + 1),
                settings.damping.at(w),
                ReducedSettings::DAMPING_RATIO,
                "",
            )?;
        }
        let functionals: Vec<Vec<f64>> = groups.iter().map(|g| functional(g, fact.dofs())).collect();
        let group_rows: Vec<Vec<f64>> = functionals.iter().map(|g| modes.modal(g)).collect();
        let (points, static_cross) = struck_points(fact, &modes, loads, (&functionals, &group_rows));
        Ok(Self {
            omega: modes.omegas().to_vec(),
            settings,
            points,
            group_rows,
            accelerometers: readings.accelerometers.iter().map(|a| modes.modal(a)).collect(),
            static_cross,
            basis: modes.basis(),
            largest_residual: modes.residuals().iter().copied().fold(0.0, f64::max),
            simd: pulp::Arch::new(),
        })
    }

    /// The same model on its lowest `n` modes only (1 ≤ n ≤ N), the others joining the static
    /// correction: C_res grows by Σ_{i>n} φᵢ(p)²/ωᵢ², a spring group's static part by
    /// Σ_{i>n} gᵀφᵢ φᵢ(p)/ωᵢ². The truncation's error estimate without a second eigensolution.
    pub fn truncated(&self, n: usize) -> Result<Self, ModelError> {
        check("modes", n as f64, Range::closed(1.0, self.omega.len() as f64), "")?;
        let dropped = |a: &[f64], b: &[f64]| -> f64 {
            a[n..].iter().zip(&b[n..]).zip(&self.omega[n..]).map(|((x, y), w)| x * y / (w * w)).sum()
        };
        let points = self
            .points
            .iter()
            .map(|p| StruckPoint {
                phi: p.phi[..n].to_vec(),
                static_compliance: p.static_compliance,
                residual: p.residual + dropped(&p.phi, &p.phi),
                group_d: self.group_rows.iter().zip(&p.group_d).map(|(g, d)| d + dropped(g, &p.phi)).collect(),
                group_static: p.group_static.clone(),
            })
            .collect();
        Ok(Self {
            omega: self.omega[..n].to_vec(),
            settings: StructureSettings { modes: n, ..self.settings },
            points,
            group_rows: self.group_rows.iter().map(|g| g[..n].to_vec()).collect(),
            accelerometers: self.accelerometers.iter().map(|a| a[..n].to_vec()).collect(),
            static_cross: self.static_cross.clone(),
            basis: self.basis,
            largest_residual: self.largest_residual,
            simd: self.simd,
        })
    }

    /// How the modes are damped.
    pub fn damping(&self) -> ModalDamping {
        self.settings.damping
    }

    /// The slowest decay rate of its kept modes, minᵢ ζᵢωᵢ, 1/s (a stream's warm-up,
    /// [`super::stream::span::warm_up_s`]).
    pub fn slowest_decay(&self) -> f64 {
        super::stream::span::slowest_decay(&self.omega, self.settings.damping)
    }

    /// The modes' frequencies, Hz.
    pub fn frequencies_hz(&self) -> Vec<f64> {
        self.omega.iter().map(|w| w / std::f64::consts::TAU).collect()
    }

    /// The Krylov basis the modes were found in, and their largest relative residual.
    pub fn search(&self) -> (usize, f64) {
        (self.basis, self.largest_residual)
    }

    /// The static compliance fᵀK⁻¹f at point `point`, m/N, and the share of it the kept modes
    /// carry, Σφᵢ(p)²/ωᵢ² over it.
    pub fn compliance(&self, point: usize) -> Option<(f64, f64)> {
        let p = self.points.get(point)?;
        Some((p.static_compliance, modal_compliance(&p.phi, &self.omega) / p.static_compliance))
    }

    /// Each spring group's force per unit contact force held still at `point` (the static
    /// answer), N/N.
    pub fn group_static(&self, point: usize) -> Option<&[f64]> {
        self.points.get(point).map(|p| p.group_static.as_slice())
    }

    /// The impact of `striker` at load `point`, followed over `window` seconds from the
    /// first touch (the spring groups' forces over all of it).
    pub fn impact(&self, striker: &Striker, point: usize, window: f64) -> Result<StructureImpact, ModelError> {
        let p = self.points.get(point).ok_or_else(|| {
            ModelError::Missing(format!("struck point {point} of a structure with {} points", self.points.len()))
        })?;
        check("window", window, Range::open(0.0, 10.0), "s")?;
        let dt = striker.hertz_time() / self.settings.steps_per_contact;
        let steps = (window / dt).ceil() as usize;
        if steps > MAX_STEPS {
            return Err(ModelError::Missing(format!(
                "a window of {window} s at the step {dt:e} s is {steps} steps, above {MAX_STEPS}"
            )));
        }
        let zeta = self.settings.damping;
        let rows: Vec<ChannelRow> = self
            .group_rows
            .iter()
            .zip(&p.group_d)
            .map(|(g, &d)| ChannelRow { a: Some(g.clone()), b: None, d })
            .collect();
        let recording = (!rows.is_empty()).then(|| Recording { rows, every: 1, samples: steps + 1 });
        let map = FreeMaps::new(&self.omega, zeta, dt);
        let mut target = ModalTarget::new(
            self.omega.clone(),
            zeta,
            p.phi.clone(),
            p.residual,
            dt,
            Some(map),
            Default::default(),
            recording,
            self.simd,
        );
        let facts =
            PlateFacts { static_compliance: Some(p.static_compliance), corner_springs: None, follow_unbounded: true };
        let outcome = simulate_with(striker, Some(&mut target), facts, dt, window + 2.0 * dt);
        while !p.group_d.is_empty() && target.recorded() < steps + 1 {
            target.advance_free(1);
        }
        let group_force_max = target.out.iter().map(|s| s.iter().fold(0.0, |m: f64, f| m.max(f.abs()))).collect();
        Ok(StructureImpact { outcome, group_force_max, dt })
    }
}

/// What a structure's signals read besides the contact.
#[derive(Debug, Clone, Copy, Default)]
pub struct Readings<'a> {
    /// Spring groups (a jack on its pad), each read as its force Σ gᵀu.
    pub groups: &'a [Vec<Spring>],
    /// Accelerometers, each a functional a over the DOFs read as aᵀü (a unit normal on a
    /// node's translations for one mounted on a wall).
    pub accelerometers: &'a [Vec<f64>],
}

impl StructureModel {
    /// The channels a stream on this structure records, sampled at `rate_hz` and each
    /// lump followed for at most `window` seconds from its touch: every spring group's force
    /// (its static correction's part per lump at its point), then every accelerometer,
    /// aᵀü = Σ αᵢq̈ᵢ with q̈ᵢ = φᵢ(p)P - ωᵢ²qᵢ - 2ζωᵢq̇ᵢ (the truncated modes, answering
    /// statically, carry no acceleration).
    pub fn probes(&self, window: f64, rate_hz: f64) -> Result<Probes, ModelError> {
        check("window", window, Range::open_closed(0.0, 10.0), "s")?;
        check("rate_hz", rate_hz, Range::closed(10.0, 1e7), "Hz")?;
        check("window × rate_hz", window * rate_hz, Range::closed(1.0, 1e7), "samples")?;
        let spec = SignalSpec { window, rate_hz, sensors: Vec::new(), quantities: Vec::new(), corners: false };
        let zeta = self.settings.damping;
        let n = self.omega.len();
        let plain = |kind, a: Vec<f64>, b: Vec<f64>, c| ChannelRows {
            kind,
            a,
            b,
            c,
            direct: None,
            res: [None, None, None],
            damped_inertia: false,
        };
        let mut rows: Vec<ChannelRows> = (self.group_rows.iter().enumerate())
            .map(|(jack, g)| plain(ChannelKind::JackForce { jack }, g.clone(), vec![0.0; n], None))
            .collect();
        for (sensor, alpha) in self.accelerometers.iter().enumerate() {
            let w = &self.omega;
            let a = (0..n).map(|i| -w[i] * w[i] * alpha[i]).collect();
            let b = (0..n).map(|i| -2.0 * zeta.at(w[i]) * w[i] * alpha[i]).collect();
            rows.push(plain(ChannelKind::Acceleration { sensor }, a, b, Some(alpha.clone())));
        }
        Ok(Probes::new(&spec, rows, Vec::new(), &self.omega, zeta))
    }

    /// The continuous signals of `probes` ([`Self::probes`]) over `duration` seconds of the
    /// stream `arrivals` (in order of time), as on the plate ([`super::stream`]): each lump
    /// strikes the load point nearest its (x, z), `points[k]` being load k's place on the
    /// struck face. `span` runs a segment of it alone ([`super::stream::span`]; None: the
    /// whole stream).
    pub fn stream(
        &self,
        arrivals: &[Arrival],
        points: &[(f64, f64)],
        probes: &Probes,
        (duration, span): (f64, Option<Span>),
    ) -> Result<StreamResponse, ModelError> {
        if points.len() != self.points.len() {
            return Err(ModelError::Missing(format!(
                "{} places for a structure of {} load points",
                points.len(),
                self.points.len()
            )));
        }
        let fits = probes.rows.iter().all(|r| match r.kind {
            ChannelKind::JackForce { jack } => jack < self.group_rows.len(),
            ChannelKind::Acceleration { sensor } => sensor < self.accelerometers.len(),
            _ => false,
        });
        if probes.omega.len() != self.omega.len() || !fits {
            return Err(ModelError::Missing("the probes were prepared on another model".into()));
        }
        super::stream::stream(&OnFace { model: self, points }, arrivals, probes, duration, span)
    }
}

/// A structure with its load points' places on the struck face.
struct OnFace<'a> {
    model: &'a StructureModel,
    points: &'a [(f64, f64)],
}

impl Struck for OnFace<'_> {
    fn omega(&self) -> &[f64] {
        &self.model.omega
    }

    fn damping(&self) -> ModalDamping {
        self.model.settings.damping
    }

    fn steps_per_contact(&self) -> f64 {
        self.model.settings.steps_per_contact
    }

    fn passes(&self) -> (pulp::Arch, Arithmetic) {
        (self.model.simd, self.model.settings.arithmetic)
    }

    /// The nearest load point's modes; a spring group's direct term is its static
    /// correction's part, an accelerometer's Σ αᵢφᵢ(p).
    fn struck_at(&self, x: f64, z: f64, probes: &Probes) -> Result<StruckAt, ModelError> {
        let d2 = |&(a, b): &(f64, f64)| (a - x) * (a - x) + (b - z) * (b - z);
        let k = (0..self.points.len())
            .min_by(|&i, &j| d2(&self.points[i]).total_cmp(&d2(&self.points[j])))
            .ok_or_else(|| ModelError::Missing("a structure without load points".into()))?;
        let p = &self.model.points[k];
        let d = probes
            .rows
            .iter()
            .map(|r| match r.kind {
                ChannelKind::JackForce { jack } => p.group_d[jack],
                _ => r.c.as_ref().map_or(0.0, |c| c.iter().zip(&p.phi).map(|(a, b)| a * b).sum()),
            })
            .collect();
        Ok(StruckAt { phi: p.phi.clone(), c_res: p.residual, d, point: k })
    }

    /// fⱼᵀK⁻¹fₖ - Σᵢ φᵢ(pⱼ)φᵢ(pₖ)/ωᵢ² on the kept modes.
    fn cross_residual(&self, (j, phi_j): (usize, &[f64]), (k, phi_k): (usize, &[f64])) -> Option<f64> {
        let n = self.model.points.len();
        let modal: f64 = phi_j.iter().zip(phi_k).zip(&self.model.omega).map(|((a, b), w)| a * b / (w * w)).sum();
        Some(self.model.static_cross[j * n + k] - modal)
    }
}

/// Most time steps of one impact's window (a sample per step is kept per spring group).
pub const MAX_STEPS: usize = 2_000_000;

/// The springs' force coefficients as one vector over `dofs` DOFs.
fn functional(springs: &[Spring], dofs: usize) -> Vec<f64> {
    let mut g = vec![0.0; dofs];
    for s in springs {
        for (d, c) in s.coefficients() {
            g[d] += c;
        }
    }
    g
}

/// The most load points a structure's model holds: their static cross compliances take
/// 8 bytes a pair (128 MB at the most).
pub const MAX_LOAD_POINTS: usize = 4_000;

/// The modal view of every load (see the module) and their static cross compliances
/// fⱼᵀK⁻¹fₖ, row-major, symmetrised (each load is nonzero on its patch's few DOFs only).
fn struck_points(
    fact: &Factorized<'_>,
    modes: &ShellModes,
    loads: &[Vec<f64>],
    (groups, group_rows): (&[Vec<f64>], &[Vec<f64>]),
) -> (Vec<StruckPoint>, Vec<f64>) {
    let n = loads.len();
    let sparse: Vec<Vec<(usize, f64)>> = loads
        .iter()
        .map(|f| f.iter().enumerate().filter(|(_, v)| **v != 0.0).map(|(i, v)| (i, *v)).collect())
        .collect();
    let mut cross = vec![0.0; n * n];
    let mut points = Vec::with_capacity(n);
    for (k, f) in loads.iter().enumerate() {
        let field = fact.solve(f);
        for (j, s) in sparse.iter().enumerate() {
            cross[j * n + k] = s.iter().map(|&(i, v)| v * field[i]).sum();
        }
        points.push(struck_point(modes, (f, &sparse[k]), &field, (groups, group_rows)));
    }
    for j in 0..n {
        for k in j + 1..n {
            let mean = 0.5 * (cross[j * n + k] + cross[k * n + j]);
            cross[j * n + k] = mean;
            cross[k * n + j] = mean;
        }
    }
    (points, cross)
}

/// The modal view of the load `f` (with its nonzero entries) whose static field is `field` =
/// K⁻¹f (see the module), with the spring groups' functionals and their modal rows.
fn struck_point(
    modes: &ShellModes,
    (f, entries): (&[f64], &[(usize, f64)]),
    field: &[f64],
    (groups, group_rows): (&[Vec<f64>], &[Vec<f64>]),
) -> StruckPoint {
    let static_compliance: f64 = f.iter().zip(field).map(|(a, b)| a * b).sum();
    let phi = modes.modal_sparse(entries);
    let residual = modes.residual_of(static_compliance, &phi, &phi).max(0.0);
    let group_d = (groups.iter().zip(group_rows))
        .map(|(g, row)| modes.residual_of(g.iter().zip(field).map(|(a, b)| a * b).sum(), row, &phi))
        .collect();
    let group_static = groups.iter().map(|g| g.iter().zip(field).map(|(a, b)| a * b).sum()).collect();
    StruckPoint { phi, static_compliance, residual, group_d, group_static }
}
