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
//! sample times ([`signals::free_map`]): nothing is time-stepped there.
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

pub mod signals;
pub mod target;

pub use signals::{free_map, Channel, ChannelKind, Probes, Quantity, SignalSpec, Signals};
pub use target::FreeSteps;

use crate::discretisation::{mesh_for, plate_properties};
use crate::error::ModelError;
use crate::supports::SupportSet;
use crate::transient::{simulate_with, Outcome, PlateFacts, Striker};
use analytic::params::{check, Range};
use analytic::Plate;
use plate_fem::modes::shape_at;
use plate_fem::{element, Corner, CornerSupport, Mesh, Model, Modes, ResidualFlexibility};
use serde::Serialize;
use signals::ChannelRows;
use target::{CornerPoint, ModalTarget};

/// How the reduced model is built.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ReducedSettings {
    /// N, the modes kept.
    pub modes: usize,
    /// Modal damping ratio ζ of every mode.
    pub damping_ratio: f64,
    /// Elements along the longer side of the plate (the full model's mesh rule).
    pub elements: usize,
    /// The time step in contact is at most the Hertz time over this.
    pub steps_per_contact: f64,
}

impl ReducedSettings {
    /// Default N.
    pub const DEFAULT_MODES: usize = 60;
    /// Default ζ (see the module documentation).
    pub const DEFAULT_DAMPING_RATIO: f64 = 0.005;
    /// Allowed ζ: the exact free-vibration map needs ζ < 1; beyond half of critical a mode
    /// no longer rings, and no plate structure is damped that much.
    pub const DAMPING_RATIO: Range = Range::closed(0.0, 0.5);
    /// Allowed N (the plate's free DOFs are a further bound, checked on the mesh).
    pub const MODES: Range = Range::closed(1.0, 2000.0);
}

impl Default for ReducedSettings {
    /// N = 60, ζ = 0.5 %, the full model's 20 elements and 200 steps per contact time.
    fn default() -> Self {
        Self {
            modes: Self::DEFAULT_MODES,
            damping_ratio: Self::DEFAULT_DAMPING_RATIO,
            elements: 20,
            steps_per_contact: 200.0,
        }
    }
}

/// One corner's data: its support and what it contributes to channels and energies.
#[derive(Debug, Clone)]
struct CornerData {
    corner: Corner,
    support: CornerSupport,
    /// The corner's w DOF.
    dof: usize,
    /// Spring or free corner: φᵢ(c). Fixed corner: the reaction's coefficients on qᵢ,
    /// ωᵢ²(Mφᵢ)_c - (Kφᵢ)_c.
    row: Vec<f64>,
    /// Fixed corner: -(Mφᵢ)_c, the coefficients of φᵢ(p) in the reaction's direct term.
    direct_modal: Option<Vec<f64>>,
    /// R e_c (spring or free corner) or R k_c (fixed corner, k_c its stiffness row).
    field: Vec<f64>,
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
}

impl ReducedModel {
    /// Meshes the plate, finds its lowest `settings.modes` modes on `set` and the residual
    /// flexibility of the rest.
    pub fn new(plate: &Plate, set: &SupportSet, settings: ReducedSettings) -> Result<Self, ModelError> {
        check("reduced.modes", settings.modes as f64, ReducedSettings::MODES, "")?;
        check("reduced.damping_ratio", settings.damping_ratio, ReducedSettings::DAMPING_RATIO, "")?;
        check("reduced.elements", settings.elements as f64, Range::closed(2.0, 400.0), "")?;
        check("reduced.steps_per_contact", settings.steps_per_contact, Range::closed(4.0, 1e5), "")?;
        let props = plate_properties(plate);
        let model = Model::new(props, mesh_for(&props, settings.elements)?)?;
        let fact = model.factorize(&set.supports)?;
        let modes = if model.dofs() <= plate_fem::modes::DENSE_LIMIT {
            Modes::dense(&model, &set.supports, settings.modes)?
        } else {
            Modes::krylov(&fact, settings.modes)?
        };
        let residual = ResidualFlexibility::new(&fact, &modes)?;
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
        let mesh = model.mesh().clone();
        let mut corners = Vec::new();
        for c in Corner::ALL {
            let support = set.supports.corners[c.index()];
            let dof = mesh.corner_w_dof(c.index());
            if fact.held().contains(&dof) && support != CornerSupport::Fixed {
                // Held by an edge: no channel, no deflection.
                continue;
            }
            let (ex, ez, local) = corner_element(&mesh, c);
            let entry = match support {
                CornerSupport::Fixed => {
                    let (a, b) = mesh.element_size(ex, ez);
                    let ke = element::stiffness(a, b, props.rigidity(), props.poisson_ratio);
                    let me = element::mass(a, b, props.density * props.thickness);
                    let dofs = mesh.element_dofs(ex, ez);
                    let row_of = |mat: &element::Mat16, i: usize| -> f64 {
                        (0..16).map(|k| mat[(local, k)] * phi[dofs[k] * n + i]).sum()
                    };
                    let row = (0..n).map(|i| omega[i] * omega[i] * row_of(&me, i) - row_of(&ke, i)).collect();
                    let direct = (0..n).map(|i| -row_of(&me, i)).collect();
                    let mut kc = vec![0.0; ndof];
                    for k in 0..16 {
                        if dofs[k] != dof {
                            kc[dofs[k]] += ke[(local, k)];
                        }
                    }
                    CornerData {
                        corner: c,
                        support,
                        dof,
                        row,
                        direct_modal: Some(direct),
                        field: modes.residual_field(&fact, &kc),
                    }
                }
                CornerSupport::Spring(_) | CornerSupport::Free => {
                    let mut e = vec![0.0; ndof];
                    e[dof] = 1.0;
                    CornerData {
                        corner: c,
                        support,
                        dof,
                        row: phi[dof * n..(dof + 1) * n].to_vec(),
                        direct_modal: None,
                        field: modes.residual_field(&fact, &e),
                    }
                }
            };
            corners.push(entry);
        }
        drop(fact);
        Ok(Self { set: set.clone(), settings, model, modes, omega, phi, residual, corners })
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

    /// φᵢ(p) for every mode and C_res(p), at p = (x, z).
    pub fn at(&self, x: f64, z: f64) -> Result<(Vec<f64>, f64), ModelError> {
        let (dofs, nv) = shape_at(self.model.mesh(), x, z)?;
        let n = self.omega.len();
        let mut phi_p = vec![0.0; n];
        for k in 0..16 {
            let row = &self.phi[dofs[k] * n..(dofs[k] + 1) * n];
            let s = nv[k];
            for (p, r) in phi_p.iter_mut().zip(row) {
                *p += s * r;
            }
        }
        let loc = self.model.mesh().locate(x, z)?;
        let e = loc.ez * self.model.mesh().nx() + loc.ex;
        Ok((phi_p, self.residual.quadratic(e, &nv).max(0.0)))
    }

    /// The FE static compliance C(p) = Σφᵢ(p)²/ωᵢ² + C_res(p), m/N.
    pub fn static_compliance(&self, x: f64, z: f64) -> Result<f64, ModelError> {
        let (phi_p, c_res) = self.at(x, z)?;
        Ok(modal_compliance(&phi_p, &self.omega) + c_res)
    }

    /// Prepares `spec` on this model: every channel's coefficient rows (one solve per
    /// sensor, for its static correction) and the exact map over one sample interval.
    pub fn probes(&self, spec: &SignalSpec) -> Result<Probes, ModelError> {
        check("signals.window", spec.window, Range::open_closed(0.0, 10.0), "s")?;
        check("signals.rate_hz", spec.rate_hz, Range::closed(10.0, 1e7), "Hz")?;
        check("signals.samples", spec.window * spec.rate_hz, Range::closed(1.0, 1e7), "")?;
        let n = self.omega.len();
        let zeta = self.settings.damping_ratio;
        let fact = self.model.factorize(&self.set.supports)?;
        let mut rows = Vec::new();
        for (s, &(x, z)) in spec.sensors.iter().enumerate() {
            let phi_s = self.at(x, z)?.0;
            let field = if spec.quantities.contains(&Quantity::Displacement) {
                Some(self.modes.residual_field(&fact, &fact.load_vector(x, z)?))
            } else {
                None
            };
            for q in &spec.quantities {
                rows.push(match q {
                    Quantity::Displacement => ChannelRows {
                        kind: ChannelKind::Displacement { sensor: s },
                        a: phi_s.clone(),
                        b: vec![0.0; n],
                        c: None,
                        field: field.clone().map(|f| (f, 1.0)),
                        direct: None,
                    },
                    Quantity::Velocity => ChannelRows {
                        kind: ChannelKind::Velocity { sensor: s },
                        a: vec![0.0; n],
                        b: phi_s.clone(),
                        c: None,
                        field: None,
                        direct: None,
                    },
                    // ẅ_s = Σφᵢ(s)q̈ᵢ, q̈ᵢ = φᵢ(p)P - ωᵢ²qᵢ - 2ζωᵢq̇ᵢ.
                    Quantity::Acceleration => ChannelRows {
                        kind: ChannelKind::Acceleration { sensor: s },
                        a: (0..n).map(|i| -self.omega[i] * self.omega[i] * phi_s[i]).collect(),
                        b: (0..n).map(|i| -2.0 * zeta * self.omega[i] * phi_s[i]).collect(),
                        c: Some(phi_s.clone()),
                        field: None,
                        direct: None,
                    },
                });
            }
        }
        if spec.corners {
            for c in &self.corners {
                match c.support {
                    CornerSupport::Spring(k) => rows.push(ChannelRows {
                        kind: ChannelKind::SpringForce { corner: c.corner },
                        a: c.row.iter().map(|r| k * r).collect(),
                        b: vec![0.0; n],
                        c: None,
                        field: Some((c.field.clone(), k)),
                        direct: None,
                    }),
                    CornerSupport::Fixed => rows.push(ChannelRows {
                        kind: ChannelKind::Reaction { corner: c.corner },
                        a: c.row.clone(),
                        b: vec![0.0; n],
                        c: c.direct_modal.clone(),
                        field: Some((c.field.clone(), -1.0)),
                        direct: Some(c.dof),
                    }),
                    CornerSupport::Free => {}
                }
            }
        }
        let ts = spec.interval();
        let sample_map = self.omega.iter().map(|&w| free_map(w, zeta, ts)).collect();
        Ok(Probes { spec: spec.clone(), rows, sample_map })
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
        self.run(striker, x, z, probes, free, dt, every)
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
        self.run(striker, x, z, probes, free, dt, every)
    }

    #[allow(clippy::too_many_arguments)]
    fn run(
        &self,
        striker: &Striker,
        x: f64,
        z: f64,
        probes: &Probes,
        free: FreeSteps,
        dt: f64,
        every: usize,
    ) -> Result<ReducedOutcome, ModelError> {
        let (phi_p, c_res) = self.at(x, z)?;
        let (dofs, nv) = shape_at(self.model.mesh(), x, z)?;
        let eval_field = |f: &[f64]| -> f64 { (0..16).map(|k| nv[k] * f[dofs[k]]).sum() };
        let direct: Vec<f64> = probes
            .rows
            .iter()
            .map(|r| {
                let modal = r.c.as_ref().map_or(0.0, |c| c.iter().zip(&phi_p).map(|(c, f)| c * f).sum());
                let res = r.field.as_ref().map_or(0.0, |(f, s)| s * eval_field(f));
                let own = r.direct.map_or(0.0, |d| (0..16).filter(|&k| dofs[k] == d).map(|k| nv[k]).sum());
                modal + res + own
            })
            .collect();
        let mut corner_points: [Option<CornerPoint>; 4] = Default::default();
        for c in &self.corners {
            if c.support != CornerSupport::Fixed {
                let spring = if let CornerSupport::Spring(k) = c.support { k } else { 0.0 };
                corner_points[c.corner.index()] =
                    Some(CornerPoint { row: c.row.clone(), d: eval_field(&c.field), spring });
            }
        }
        let static_compliance = modal_compliance(&phi_p, &self.omega) + c_res;
        let facts = PlateFacts {
            static_compliance: Some(static_compliance),
            corner_springs: Some(self.set.supports.corners.map(|c| match c {
                CornerSupport::Spring(k) => k,
                _ => 0.0,
            })),
            follow_unbounded: true,
        };
        let zeta = self.settings.damping_ratio;
        let mut target =
            ModalTarget::new(&self.omega, zeta, phi_p, c_res, dt, free, corner_points, Some((probes, direct, every)));
        let window = probes.spec.window;
        let outcome = simulate_with(striker, Some(&mut target), facts, dt, window + 2.0 * dt);
        // The rest of the window: exact free vibration at the sample times.
        let want = probes.spec.samples();
        let steps = target.steps();
        let (q, v, force) = target.state();
        let (mut q, mut v) = (q.to_vec(), v.to_vec());
        let mut out = std::mem::take(&mut target.out);
        let recorded = out.first().map_or(0, |c| c.len());
        if recorded < want {
            // The next sample after the last step, k·every ≥ steps.
            let k0 = recorded;
            let gap = (k0 * every).saturating_sub(steps) as f64 * dt;
            let n = q.len();
            for i in 0..n {
                let m = free_map(self.omega[i], zeta, gap);
                let (qi, vi) = (q[i], v[i]);
                q[i] = m[0] * qi + m[1] * vi;
                v[i] = m[2] * qi + m[3] * vi;
            }
            // A contact may still be on at the end of a window: its force is not carried on.
            let _ = force;
            for k in k0..want {
                if k > k0 {
                    for i in 0..n {
                        let m = &probes.sample_map[i];
                        let (qi, vi) = (q[i], v[i]);
                        q[i] = m[0] * qi + m[1] * vi;
                        v[i] = m[2] * qi + m[3] * vi;
                    }
                }
                for (c, r) in probes.rows.iter().enumerate() {
                    let y = r.a.iter().zip(&q).map(|(a, q)| a * q).sum::<f64>()
                        + r.b.iter().zip(&v).map(|(b, v)| b * v).sum::<f64>();
                    out[c].push(y);
                }
            }
        }
        let channels = probes.rows.iter().zip(out).map(|(r, samples)| Channel { kind: r.kind, samples }).collect();
        Ok(ReducedOutcome {
            outcome,
            signals: Signals { rate_hz: probes.spec.rate_hz, channels },
            dt,
            static_compliance,
            residual_compliance: c_res,
        })
    }
}

/// Σ φᵢ(p)²/ωᵢ²: the modes' part of the static compliance.
fn modal_compliance(phi_p: &[f64], omega: &[f64]) -> f64 {
    phi_p.iter().zip(omega).map(|(f, w)| f * f / (w * w)).sum()
}

/// The element holding a corner node and the corner's local w DOF in it.
fn corner_element(mesh: &Mesh, c: Corner) -> (usize, usize, usize) {
    match c {
        Corner::LeftNear => (0, 0, 0),
        Corner::RightNear => (mesh.nx() - 1, 0, 4),
        Corner::LeftFar => (0, mesh.nz() - 1, 8),
        Corner::RightFar => (mesh.nx() - 1, mesh.nz() - 1, 12),
    }
}
