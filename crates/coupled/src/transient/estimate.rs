//! Error estimates for the transient numbers from each case's own discretisation.
//!
//! The scheme is second order in Δt (Newmark's average-acceleration rule with the contact
//! law solved at the step ends), and the plate's point response converges at O(h²) in the
//! interior (the point-load compliance of the BFS plate). With Q(n, N) a quantity on n
//! elements along the longer side and N steps per Hertz time, Richardson's argument gives
//! the error of Q(n, N) in each direction from its change on halving,
//! |Q(n, N) - Q(n, 2N)|/(1 - 2^{-p}), p the order. The order is observed from a third,
//! coarser level in each direction, p = log₂(|Q(N/2) - Q(N)|/|Q(N) - Q(2N)|) (likewise for
//! n/2, n, 2n), and clamped to [1, 2]: never credited above the scheme's order 2, and never
//! below first order where the coarse levels are not yet asymptotic: on the paper's plate
//! the mesh order observed from 10, 20, 40 elements is often near 1, and the estimate with
//! order 2 assumed fell up to 27 % short of the error measured against 80 elements and 800
//! steps (gangue at the middle of a free edge). Each part is multiplied by a safety factor
//! F, and the estimate is their sum. Roache's grid convergence index uses 1.25 with an
//! observed order; on the paper's sample at 20 elements and 200 steps that still fell 6 %
//! short for the peak force of gangue 2 at the middle of a free edge under Con 2 (the peak
//! carries the plate's high modes, whose convergence the coarse levels do not show), and
//! F = 1.5 fell 7 % short for the peak force of coal at the middle of a free edge under
//! Con 2 at 40 elements and 400 steps, against a run four times finer in both
//! (docs/transient-estimate-coverage.md), so F is 2. Without a coarser mesh level (counts
//! not multiples of 4) the mesh order is taken as 2. The quantities are the ones on the in-step interpolant
//! ([`super::interpolate`]), which vary smoothly with Δt; the sampled maxima jump with the
//! phase of the steps and do not.

use super::sequence_estimate::{sequence_estimate, SequenceEstimate};
use super::{Outcome, Striker, TransientCase, TransientSettings};
use crate::error::ModelError;
use crate::supports::SupportSet;
use analytic::Plate;
use serde::Serialize;
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

/// The safety factor on the Richardson estimates (see the module documentation).
pub const SAFETY: f64 = 2.0;

/// The transient numbers an estimate covers.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Quantities {
    /// Peak contact force (Flores, damping included), N.
    pub peak_force: f64,
    /// Force at maximum compression, the law's force at δ_max with δ̇ = 0 (Kδ_max^{3/2} for
    /// the elastic laws), N.
    pub force_at_max_compression: f64,
    /// δ_max, m.
    pub compression: f64,
    /// Duration of the first contact, s (NaN if it had not ended in the window).
    pub contact_time: f64,
    /// Apparent restitution -v_rebound/v₀ of the first contact (NaN as above).
    pub restitution: f64,
}

impl Quantities {
    /// The interpolated first-contact quantities of a run.
    pub fn of(o: &Outcome, s: &Striker) -> Self {
        let first = o.contacts.first();
        Self {
            peak_force: o.force_max_interpolated,
            force_at_max_compression: s.force_at_max_compression(o.compression_max_interpolated),
            compression: o.compression_max_interpolated,
            contact_time: first.map_or(f64::NAN, |c| c.duration),
            restitution: first.map_or(f64::NAN, |c| -c.rebound_velocity / s.velocity),
        }
    }

    /// The largest relative error of P_max (the force at maximum compression, the paper's)
    /// and the first contact time, `self` the errors of `values`: the measure a tolerance
    /// holds ([`choose`]). The peak force, which carries the Flores damping and the plate's
    /// highest modes, converges more slowly; its estimate is reported beside it
    /// ([`Self::relative_peak`]) but does not drive the choice.
    pub fn relative_to(&self, values: &Quantities) -> f64 {
        [self.force_at_max_compression / values.force_at_max_compression, self.contact_time / values.contact_time]
            .into_iter()
            .map(|r| if r.is_nan() { f64::INFINITY } else { r.abs() })
            .fold(0.0, f64::max)
    }

    /// The relative error of the peak force, `self` the errors of `values`.
    pub fn relative_peak(&self, values: &Quantities) -> f64 {
        (self.peak_force / values.peak_force).abs()
    }
}

/// The state at maximum compression (on the in-step interpolant, [`super::interpolate`])
/// that the response rows report beside [`Quantities`]: the plate's deflection, the
/// corners' and the energy split. Its error is estimated from the same runs, component by
/// component, as that of [`Quantities`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct State {
    /// Plate deflection w at the struck point, m.
    pub plate_displacement: f64,
    /// Corner deflections in [`plate_fem::Corner::ALL`] order (zero at held corners), m.
    pub corners: [f64; 4],
    /// Energy in the rock: stored in the contact plus dissipated by it, J.
    pub rock_total: f64,
    /// Energy stored in the contact, J.
    pub rock_stored: f64,
    /// Kinetic and strain energy of the plate, J.
    pub plate: f64,
    /// Energy of the corner springs, J.
    pub springs: f64,
    /// Kinetic energy of the sphere, J.
    pub sphere_kinetic: f64,
}

impl State {
    /// The state at maximum compression of a run.
    pub fn of(o: &Outcome) -> Self {
        let m = o.at_max_compression_interpolated;
        Self {
            plate_displacement: m.plate_displacement,
            corners: o.corners_at_max_compression_interpolated,
            rock_total: m.contact + m.dissipated,
            rock_stored: m.contact,
            plate: m.plate_kinetic + m.plate_strain,
            springs: m.springs,
            sphere_kinetic: m.sphere_kinetic,
        }
    }
}

/// A set of numbers an estimate covers, as a list in a fixed order, so that one Richardson
/// estimate ([`richardson`]) serves [`Quantities`] and [`State`] alike.
pub(super) trait Components: Copy {
    fn to_list(self) -> Vec<f64>;
    fn from_list(list: &[f64]) -> Self;
}

impl Components for Quantities {
    fn to_list(self) -> Vec<f64> {
        vec![self.peak_force, self.force_at_max_compression, self.compression, self.contact_time, self.restitution]
    }

    fn from_list(l: &[f64]) -> Self {
        Self {
            peak_force: l[0],
            force_at_max_compression: l[1],
            compression: l[2],
            contact_time: l[3],
            restitution: l[4],
        }
    }
}

impl Components for State {
    fn to_list(self) -> Vec<f64> {
        let [c0, c1, c2, c3] = self.corners;
        vec![
            self.plate_displacement,
            c0,
            c1,
            c2,
            c3,
            self.rock_total,
            self.rock_stored,
            self.plate,
            self.springs,
            self.sphere_kinetic,
        ]
    }

    fn from_list(l: &[f64]) -> Self {
        Self {
            plate_displacement: l[0],
            corners: [l[1], l[2], l[3], l[4]],
            rock_total: l[5],
            rock_stored: l[6],
            plate: l[7],
            springs: l[8],
            sphere_kinetic: l[9],
        }
    }
}

/// Richardson's estimate in one direction (Δt or h), component by component: the order p
/// observed from the `coarse`, value and `fine` levels ([`observed_order`]; 2 without a
/// coarse level) and the absolute error F|Q - Q_fine|/(1 - 2^{-p}). Returns (orders, errors).
pub(super) fn richardson<Q: Components>(q: Q, fine: Q, coarse: Option<Q>) -> (Q, Q) {
    let (q, fine, coarse) = (q.to_list(), fine.to_list(), coarse.map(Q::to_list));
    let order: Vec<f64> =
        (0..q.len()).map(|i| coarse.as_ref().map_or(2.0, |c| observed_order(c[i], q[i], fine[i]))).collect();
    let error: Vec<f64> =
        (0..q.len()).map(|i| SAFETY * (q[i] - fine[i]).abs() / (1.0 - 0.5f64.powf(order[i]))).collect();
    (Q::from_list(&order), Q::from_list(&error))
}

/// The component-wise sum of two error estimates.
pub(super) fn sum<Q: Components>(a: Q, b: Q) -> Q {
    let (a, b) = (a.to_list(), b.to_list());
    Q::from_list(&a.iter().zip(&b).map(|(x, y)| x + y).collect::<Vec<_>>())
}

/// A case's numbers with their error estimates.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Estimated {
    /// Elements along the longer side of the run the values come from.
    pub elements: usize,
    /// Its steps per Hertz time.
    pub steps_per_contact: f64,
    /// The values, from the (n, N) run.
    pub values: Quantities,
    /// The order used for the time part, observed from N/2, N, 2N and clamped to [1, 2].
    pub time_order: Quantities,
    /// The order used for the mesh part, observed from n/2, n, 2n (2 without n/2).
    pub mesh_order: Quantities,
    /// Estimated absolute error from the time step, F|Q(n, N) - Q(n, 2N)|/(1 - 2^{-p}).
    pub time_error: Quantities,
    /// Estimated absolute error from the mesh, F|Q(n, N) - Q(2n, N)|/(1 - 2^{-p}).
    pub mesh_error: Quantities,
    /// Their sum: the estimate of the absolute error of `values`.
    pub error: Quantities,
    /// The estimated absolute error of the state at maximum compression ([`State::of`] the
    /// `outcome`), from the same runs.
    pub state_error: State,
    /// The relative tolerance [`choose`] aimed at (None from [`estimate_on`]).
    pub tolerance: Option<f64>,
    /// Whether the error met that tolerance (true from [`estimate_on`]).
    pub met_tolerance: bool,
    /// The (n, N) run itself, followed through every contact.
    pub outcome: Outcome,
    /// Every contact of an impact struck more than once, and its end, with their errors from
    /// the same levels followed through every contact (None for a single contact, whose
    /// numbers are the first contact's above).
    pub sequence: Option<SequenceEstimate>,
}

impl Estimated {
    /// The largest relative error estimate of P_max and the contact time, the measure
    /// [`choose`] holds to its tolerance.
    pub fn relative_error(&self) -> f64 {
        self.error.relative_to(&self.values)
    }
}

/// The observed order from the coarse, middle and fine levels, clamped to [1, 2] (2 where
/// the differences do not define one).
fn observed_order(coarse: f64, middle: f64, fine: f64) -> f64 {
    let p = ((coarse - middle).abs() / (middle - fine).abs()).log2();
    if p.is_nan() {
        2.0
    } else {
        p.clamp(1.0, 2.0)
    }
}

/// A run's first-contact quantities and its state at maximum compression.
type Run = (Quantities, State);

/// The run's [`Run`] numbers.
fn run_of(o: &Outcome, s: &Striker) -> Run {
    (Quantities::of(o, s), State::of(o))
}

/// The estimate from the runs: `q` the (n, N) values, `q_dt` (n, 2N), `q_2dt` (n, N/2),
/// `q_h` (2n, N) and `q_2h` (n/2, N) where there is a coarser mesh.
fn combine(
    (q, state): Run,
    ((q_2dt, s_2dt), (q_dt, s_dt)): (Run, Run),
    (r_2h, (q_h, s_h)): (Option<Run>, Run),
    (elements, steps_per_contact): (usize, f64),
    outcome: Outcome,
) -> Estimated {
    let (time_order, time_error) = richardson(q, q_dt, Some(q_2dt));
    let (mesh_order, mesh_error) = richardson(q, q_h, r_2h.map(|r| r.0));
    let state_error = sum(richardson(state, s_dt, Some(s_2dt)).1, richardson(state, s_h, r_2h.map(|r| r.1)).1);
    Estimated {
        elements,
        steps_per_contact,
        values: q,
        time_order,
        mesh_order,
        time_error,
        mesh_error,
        error: sum(time_error, mesh_error),
        state_error,
        tolerance: None,
        met_tolerance: true,
        outcome,
        sequence: None,
    }
}

/// The estimate for one case: `base`, `fine` and `coarse` are the same plate on n, 2n and
/// n/2 elements ([`TransientCase::refined`], [`TransientCase::coarsened`]);
/// `steps_per_contact` is N. The (n, N) run follows every contact; the four runs that only
/// estimate its error stop at the first separation ([`TransientCase::first_contact`]) when the
/// impact is one contact that ended, and otherwise follow every contact too, for the
/// estimate of the whole sequence ([`sequence_estimate`]).
pub fn estimate_on(
    base: &TransientCase,
    fine: &TransientCase,
    coarse: Option<&TransientCase>,
    set: &SupportSet,
    s: &Striker,
    (x, z): (f64, f64),
    steps_per_contact: f64,
) -> Result<Estimated, ModelError> {
    let o = base.run_steps(set, s, x, z, steps_per_contact)?;
    let q = run_of(&o, s);
    let single = o.contacts.len() == 1 && o.unfinished_contact.is_none() && o.left_at.is_some();
    // The first contact's numbers are those of the whole run up to its first separation, so
    // a level followed through every contact gives the same first-contact estimate.
    let level = |c: &TransientCase, n: f64| -> Result<Outcome, ModelError> {
        if single {
            c.first_contact(set, s, x, z, n)
        } else {
            c.run_steps(set, s, x, z, n)
        }
    };
    let o_dt = level(base, 2.0 * steps_per_contact)?;
    let o_2dt = level(base, 0.5 * steps_per_contact)?;
    let o_h = level(fine, steps_per_contact)?;
    let o_2h = coarse.map(|c| level(c, steps_per_contact)).transpose()?;
    let sequence = (!single).then(|| sequence_estimate(&o, (&o_dt, &o_2dt), (&o_h, o_2h.as_ref())));
    let (q_dt, q_2dt, q_h) = (run_of(&o_dt, s), run_of(&o_2dt, s), run_of(&o_h, s));
    let q_2h = o_2h.as_ref().map(|o| run_of(o, s));
    let mut e = combine(q, (q_2dt, q_dt), (q_2h, q_h), (base.settings().elements, steps_per_contact), o);
    e.sequence = sequence;
    Ok(e)
}

/// The estimate of the whole sequence of `o`, an impact on `levels` (base, fine, coarse) at
/// `steps` per Hertz time, from the four levels each followed through every contact; None for
/// one contact that ended, whose numbers are the first contact's.
fn whole_impact(
    o: &Outcome,
    (base, fine, coarse): (&TransientCase, &TransientCase, Option<&TransientCase>),
    set: &SupportSet,
    s: &Striker,
    (x, z): (f64, f64),
    steps: f64,
) -> Result<Option<SequenceEstimate>, ModelError> {
    if o.contacts.len() == 1 && o.unfinished_contact.is_none() && o.left_at.is_some() {
        return Ok(None);
    }
    let o_dt = base.run_steps(set, s, x, z, 2.0 * steps)?;
    let o_2dt = base.run_steps(set, s, x, z, 0.5 * steps)?;
    let o_h = fine.run_steps(set, s, x, z, steps)?;
    let o_2h = coarse.map(|c| c.run_steps(set, s, x, z, steps)).transpose()?;
    Ok(Some(sequence_estimate(o, (&o_dt, &o_2dt), (&o_h, o_2h.as_ref()))))
}

/// The estimate for one case on `elements` and `steps_per_contact` (builds the meshes).
pub fn estimate(
    plate: &Plate,
    set: &SupportSet,
    s: &Striker,
    point: (f64, f64),
    settings: TransientSettings,
) -> Result<Estimated, ModelError> {
    let base = TransientCase::new(plate, settings)?;
    let fine = base.refined(plate)?;
    let coarse = base.coarsened(plate).transpose()?;
    estimate_on(&base, &fine, coarse.as_ref(), set, s, point, settings.steps_per_contact)
}

/// How far [`choose`] may refine.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Budget {
    /// Most elements along the longer side for the values' run (the estimate runs 2n).
    pub max_elements: usize,
    /// Most steps per Hertz time for the values' run (the estimate runs 2N).
    pub max_steps_per_contact: f64,
}

impl Default for Budget {
    fn default() -> Self {
        // The estimate at n = 40 runs the 80-element mesh (20k DOFs), seconds a case.
        Self { max_elements: 40, max_steps_per_contact: 1600.0 }
    }
}

/// The relative tolerance [`choose`] aims at on P_max and the contact time.
pub const DEFAULT_TOLERANCE: f64 = 1e-4;

/// How the transient model is discretised, case by case.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Discretisation {
    /// The same mesh and step for every case, each with its error estimate.
    Fixed {
        /// The mesh, step and window.
        settings: TransientSettings,
    },
    /// Per case, the coarsest mesh and step of the ladder whose estimate meets a relative
    /// tolerance on P_max and the contact time ([`choose`]).
    Tolerance {
        /// The relative tolerance.
        tolerance: f64,
        /// How far the ladder may go.
        budget: Budget,
    },
}

impl Default for Discretisation {
    fn default() -> Self {
        Discretisation::tolerance(DEFAULT_TOLERANCE)
    }
}

impl Discretisation {
    /// Per-case choice to `tolerance` within the default budget.
    pub fn tolerance(tolerance: f64) -> Self {
        Discretisation::Tolerance { tolerance, budget: Budget::default() }
    }

    /// Where the ladder starts: the fixed settings, or 20 elements and 200 steps per Hertz
    /// time for a tolerance.
    pub fn start(&self) -> TransientSettings {
        match *self {
            Discretisation::Fixed { settings } => settings,
            Discretisation::Tolerance { .. } => TransientSettings::default(),
        }
    }

    /// The estimate for one case on `ladder` ([`Ladder::new`] with [`Self::start`]):
    /// the fixed settings' estimate, or [`choose_on`].
    pub fn estimate(
        &self,
        ladder: &Ladder,
        set: &SupportSet,
        s: &Striker,
        point: (f64, f64),
    ) -> Result<Estimated, ModelError> {
        match *self {
            Discretisation::Fixed { settings } => {
                let (base, fine, coarse) = ladder.levels(0)?;
                estimate_on(base, fine, coarse, set, s, point, settings.steps_per_contact)
            }
            Discretisation::Tolerance { tolerance, budget } => choose_on(ladder, set, s, point, tolerance, budget),
        }
    }
}

/// The deepest ladder a [`Ladder`] holds: h halved 15 times from the start (a 20-element
/// start would reach 655,360 elements; the memory limits refuse meshes long before).
const LADDER_SLOTS: usize = 16;

/// One plate's meshes for the estimates: the starting mesh, the one with h doubled (where
/// the starting counts allow it) and the ones with h halved, built when first needed and
/// shared by every case on the plate, also across threads (each level is built once, by
/// the first case that needs it).
pub struct Ladder {
    plate: Plate,
    coarse: Option<TransientCase>,
    /// levels[0] is the starting mesh, levels[k] has h halved k times.
    levels: Vec<OnceLock<TransientCase>>,
    /// Held while a level is built, so that no level is built twice.
    building: Mutex<()>,
}

impl Ladder {
    /// The ladder of `plate` starting at `settings`.
    pub fn new(plate: &Plate, settings: TransientSettings) -> Result<Self, ModelError> {
        let base = TransientCase::new(plate, settings)?;
        let coarse = base.coarsened(plate).transpose()?;
        let levels: Vec<OnceLock<TransientCase>> = (0..LADDER_SLOTS).map(|_| OnceLock::new()).collect();
        levels[0].get_or_init(|| base);
        Ok(Self { plate: *plate, coarse, levels, building: Mutex::new(()) })
    }

    /// The meshes at level `k` (h halved k times from the start), at 2k... i.e. (n, 2n,
    /// n/2) for the estimate at level k, building any that are missing.
    pub fn levels(&self, k: usize) -> Result<(&TransientCase, &TransientCase, Option<&TransientCase>), ModelError> {
        if k + 2 > LADDER_SLOTS {
            return Err(ModelError::Missing(format!(
                "the mesh ladder would need h halved {} times; at most {} are held",
                k + 1,
                LADDER_SLOTS - 1
            )));
        }
        for i in 1..=k + 1 {
            if self.levels[i].get().is_none() {
                // A poisoned lock only means another thread's build failed; building again
                // here is still correct.
                let _held = self.building.lock().unwrap_or_else(|e| e.into_inner());
                if self.levels[i].get().is_none() {
                    let finer = self.level(i - 1).refined(&self.plate)?;
                    self.levels[i].get_or_init(|| finer);
                }
            }
        }
        let coarse = if k == 0 { self.coarse.as_ref() } else { Some(self.level(k - 1)) };
        Ok((self.level(k), self.level(k + 1), coarse))
    }

    /// A level already built (every level up to the deepest one asked for is).
    fn level(&self, k: usize) -> &TransientCase {
        self.levels[k].get().expect("levels are built in order, coarse to fine")
    }
}

/// Chooses the discretisation of one case from a relative `tolerance` on P_max (the force at
/// maximum compression) and the first contact time ([`Quantities::relative_to`]): starts at 20 elements and 200
/// steps per Hertz time, and doubles N while the time part of the estimate exceeds half the
/// tolerance and n while the mesh part does, within `budget`. Returns the last estimate;
/// `met_tolerance` says whether it reached the tolerance.
pub fn choose(
    plate: &Plate,
    set: &SupportSet,
    s: &Striker,
    point: (f64, f64),
    tolerance: f64,
    budget: Budget,
) -> Result<Estimated, ModelError> {
    let ladder = Ladder::new(plate, TransientSettings::default())?;
    choose_on(&ladder, set, s, point, tolerance, budget)
}

/// [`choose`] on a shared [`Ladder`]. Each level's runs are kept, so a run that one level
/// needs and the previous one made (the (n, 2N) run becomes the next level's (n/2, N)
/// after both double, the (2n, N) run its (n, N/2)) is not repeated; only the values' run
/// follows every contact.
pub fn choose_on(
    ladder: &Ladder,
    set: &SupportSet,
    s: &Striker,
    (x, z): (f64, f64),
    tolerance: f64,
    budget: Budget,
) -> Result<Estimated, ModelError> {
    let mut runs: HashMap<(usize, u64), Run> = HashMap::new();
    let (mut level, mut steps) = (0usize, TransientSettings::default().steps_per_contact);
    let base_elements = ladder.levels(0)?.0.settings().elements;
    loop {
        let (base, fine, coarse) = ladder.levels(level)?;
        let mut first = |c: &TransientCase, k: usize, n: f64| -> Result<Run, ModelError> {
            if let Some(q) = runs.get(&(k, n.to_bits())) {
                return Ok(*q);
            }
            let q = run_of(&c.first_contact(set, s, x, z, n)?, s);
            runs.insert((k, n.to_bits()), q);
            Ok(q)
        };
        // The coarse mesh is level - 1 (or the ladder's h-doubled start, keyed below 0).
        let coarse_key = level.wrapping_sub(1);
        let q_dt = first(base, level, 2.0 * steps)?;
        let q_2dt = first(base, level, 0.5 * steps)?;
        let q_h = first(fine, level + 1, steps)?;
        let q_2h = coarse.map(|c| first(c, coarse_key, steps)).transpose()?;
        let o = base.run_steps(set, s, x, z, steps)?;
        let q = run_of(&o, s);
        runs.insert((level, steps.to_bits()), q);
        let mut e = combine(q, (q_2dt, q_dt), (q_2h, q_h), (base_elements << level, steps), o);
        e.tolerance = Some(tolerance);
        if e.relative_error() <= tolerance {
            e.sequence = whole_impact(&e.outcome, (base, fine, coarse), set, s, (x, z), steps)?;
            return Ok(e);
        }
        let refine_t =
            e.time_error.relative_to(&e.values) > 0.5 * tolerance && 2.0 * steps <= budget.max_steps_per_contact;
        let refine_h = e.mesh_error.relative_to(&e.values) > 0.5 * tolerance
            && (base_elements << (level + 1)) <= budget.max_elements;
        if !refine_t && !refine_h {
            e.met_tolerance = false;
            e.sequence = whole_impact(&e.outcome, (base, fine, coarse), set, s, (x, z), steps)?;
            return Ok(e);
        }
        if refine_t {
            steps *= 2.0;
        }
        if refine_h {
            level += 1;
        }
    }
}
