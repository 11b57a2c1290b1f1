//! The yield velocity as a root of the transient model: the impact velocity at which the
//! first contact's largest compression δ_max reaches δ_my of eq. 51, on a plate that is
//! integrated in time rather than reduced to one quasi-static compliance.
//!
//! f(ln v) = ln(δ_max/δ_my) increases with ln v (δ_max ∝ v^{4/5} on a rigid target, steeper
//! where the plate gives way). [`YieldSearch`] finds its root in two stages:
//!
//! 1. **Reduced.** The reduced modal model of the same plate ([`crate::reduced`]: the lowest
//!    80 modes and the static correction of the rest, the full model's damping, the same Δt
//!    rule, the same striker, gravity included) finds its own root v_r by [`log_root`] from
//!    the rigid-target value, in about five modal runs of a millisecond each, and its slope
//!    d f/d ln v there.
//! 2. **Full.** The full model ([`TransientCase::first_contact`]) is run at v_r and one Newton
//!    step away with the reduced slope, lengthened past the root ([`log_root_near`]); the two
//!    runs straddle the root and Illinois false position closes the bracket to the same
//!    relative width [`YIELD_ROOT_TOLERANCE`] as before, usually with one more run.
//!
//! Only the full model decides the root: the reduced one places the bracket. Over the
//! paper's plate (Con 1-3, the three spheres, nine points: the corners (0, 0) and (L, 0), the
//! midpoints of the ends, of a free edge and of the plate, and Areas 1, 2 and 6) the full
//! root lay within 9.2e-5 of v_r (relative) and the reduced slope at v_r within 5.1e-4 of the
//! full one's (a central difference at the full root), so the search stays within
//! [`REDUCED_REACH`] (3e-4) of v_r and its Newton step misses the root by under 5e-8 in
//! ln v, a twentieth of the final width: 2-3 full runs a root.
//!
//! Every full run keeps its own Δt = t_H(v)/N (N steps per Hertz time t_H ∝ v^{-1/5}) and its
//! own factorization of K + 4M/Δt², as in the search from scratch, so both searches find the
//! root of the same f. Holding one Δt over the bracket, to factorize once per root, was
//! measured and left out: the factorization is 5-10 % of a first-contact run on the
//! 20-element mesh (4 % on 40), so it saved about 4 % of the three-model yield study, but
//! the held Δt moves the instants at which δ is sampled against its peak, and with them the
//! sampled δ_max (by up to ½(πΔt/t_c)² ≈ 1e-4 per step of shift): the roots moved by up to
//! 8.3e-7 (29 of Table 2's 42 cells by more than their bracket width) where with each run at
//! its own Δt they stay within 3.9e-7 of the search from scratch.
//!
//! Where the reduced model cannot be built or its root does not bracket the full one within
//! the reach, the search falls back to [`transient_yield_from_rigid`]: the bracket from the
//! rigid-target value (eq. 14 with C = 0, the smallest v that reaches δ_my) with the Hertz
//! slope, closed by Illinois false position, each run at its own Δt (3-5 runs, 4.9 on
//! average over the paper's 138 cells).

use crate::error::ModelError;
use crate::plan::{impact_of, log_root, log_root_near, scene_striker, Guess, YIELD_ROOT_TOLERANCE};
use crate::reduced::{ReducedModel, ReducedSettings};
use crate::scene::Scene;
use crate::supports::SupportSet;
use crate::transient::TransientCase;
use analytic::{contact_stiffness, yield_velocity, DruckerPrager, Plate, Sphere};
use plate_fem::Supports;
use serde::Serialize;

/// How far, in ln v, the full model's root may lie from the reduced model's: about three
/// times the largest distance measured on the paper's plate (9.2e-5 with N = 80, see the
/// module documentation). The full search never leaves it, and falls back beyond it.
pub const REDUCED_REACH: f64 = 3e-4;

/// The relative disagreement allowed between the reduced and the full slope d ln δ_max/d ln v
/// at the root: about four times the largest measured on the paper's plate (5.1e-4, see the
/// module documentation). With it the Newton step from v_r passes the root by less than
/// 0.45 of the final width, so that one more run closes the bracket
/// ([`log_root_near`]).
pub const REDUCED_SLOPE_SPREAD: f64 = 2e-3;

/// A transient yield velocity and how it was found.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TransientYield {
    /// v_y, m/s: the geometric middle of the final bracket.
    pub velocity: f64,
    /// Width of the final bracket hi - lo, m/s: f(lo) < 0 ≤ f(hi).
    pub width: f64,
    /// Runs of the full transient model it took.
    pub runs: usize,
    /// Runs of the reduced model that placed the bracket (0 without it).
    pub reduced_runs: usize,
    /// δ_my of eq. 51, m.
    pub yield_compression: f64,
}

/// δ_my of eq. 51: the compression at which the Drucker-Prager criterion is first met at
/// the sphere's contact, with the Hertz stiffness against the scene's plate.
fn yield_compression(scene: &Scene, body: &Sphere) -> f64 {
    let k = contact_stiffness(body, scene.plate.material());
    DruckerPrager::of(body).yield_compression(body.radius(), k)
}

/// The quasi-static yield velocity (eqs. 51-54) of rigid contact, C = 0 (eq. 14 with C = 0).
/// On any plate that gives way the transient root lies above it: this is where the search
/// from scratch starts.
pub fn rigid_yield(scene: &Scene, body: &Sphere) -> f64 {
    yield_velocity(body, &impact_of(scene, body, 1.0), 0.0, yield_compression(scene, body))
}

/// One root to find: `body` at `at` = (x, z) on the plate of `case`'s mesh held by `set`,
/// with the scene's contact law and `steps_per_contact` steps per Hertz time.
#[derive(Clone, Copy)]
pub struct Root<'a> {
    /// The scene (plate, contact law, restitution, gravity).
    pub scene: &'a Scene,
    /// The full model's mesh.
    pub case: &'a TransientCase,
    /// Steps per Hertz time of every run, each at its own Δt = t_H(v)/N.
    pub steps_per_contact: f64,
    /// The supports.
    pub set: &'a SupportSet,
    /// The sphere.
    pub body: &'a Sphere,
    /// The impact point (x, z), m.
    pub at: (f64, f64),
}

impl Root<'_> {
    /// δ_my of eq. 51 for this root's sphere.
    fn yield_compression(&self) -> f64 {
        yield_compression(self.scene, self.body)
    }

    /// ln(δ_max/δ_my) of the full model's first contact at velocity e^`lv`.
    fn full(&self, lv: f64, d_my: f64) -> Result<f64, ModelError> {
        let s = scene_striker(self.scene, self.body, lv.exp());
        let (x, z) = self.at;
        // δ_max is the first contact's: the run need not follow the later ones.
        Ok((self.case.first_contact(self.set, &s, x, z, self.steps_per_contact)?.compression_max / d_my).ln())
    }
}

/// The transient yield velocity of `body` at (x, z) on the plate held by `set`, with the
/// scene's contact law: the v at which the transient δ_max reaches δ_my of eq. 51, to a
/// relative width [`YIELD_ROOT_TOLERANCE`] ([`YieldSearch`], whose reduced model is built
/// for this one root: a caller with many roots keeps one [`YieldSearch`]).
pub fn transient_yield(
    scene: &Scene,
    case: &TransientCase,
    set: &SupportSet,
    body: &Sphere,
    x: f64,
    z: f64,
) -> Result<TransientYield, ModelError> {
    let steps_per_contact = case.settings().steps_per_contact;
    YieldSearch::new().root(&Root { scene, case, steps_per_contact, set, body, at: (x, z) })
}

/// The same root searched from scratch with `steps_per_contact` steps per Hertz time on
/// `case`'s mesh: bracketed from the rigid-target value [`rigid_yield`] with the Hertz slope
/// and closed by Illinois false position ([`log_root`]), each run at its own Δt.
pub fn transient_yield_from_rigid(root: &Root) -> Result<TransientYield, ModelError> {
    let d_my = root.yield_compression();
    let mut runs = 0;
    let (lo, hi) = {
        let mut reach = |lv: f64| -> Result<f64, ModelError> {
            runs += 1;
            root.full(lv, d_my)
        };
        log_root(&mut reach, rigid_yield(root.scene, root.body).ln(), YIELD_ROOT_TOLERANCE)?
    };
    Ok(found((lo, hi), runs, 0, d_my))
}

/// The root from its final bracket (ln lo, ln hi).
fn found((lo, hi): (f64, f64), runs: usize, reduced_runs: usize, yield_compression: f64) -> TransientYield {
    TransientYield {
        velocity: (0.5 * (lo + hi)).exp(),
        width: hi.exp() - lo.exp(),
        runs,
        reduced_runs,
        yield_compression,
    }
}

/// A reduced model of one plate and support set with the settings it was built with (None
/// if it could not be built: the roots on it are then searched from scratch).
struct Modal {
    plate: Plate,
    supports: Supports,
    settings: ReducedSettings,
    model: Option<ReducedModel>,
}

/// Transient yield roots bracketed by the reduced model (see the module): it keeps the
/// reduced models it builds, one per plate, support set and mesh, for the roots that follow.
#[derive(Default)]
pub struct YieldSearch {
    modal: Vec<Modal>,
}

impl YieldSearch {
    /// No reduced model built yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// The reduced model's settings for `case`: N = 80 and the static correction as the
    /// signals have them, the full model's damping (none, ζ = 0, on the paper's plate; its
    /// Rayleigh damping mode by mode where the scene gives one), its mesh no finer than the
    /// signals' 20 elements (the full model's own where coarser: a finer one would cost more
    /// to build than the runs it saves).
    fn settings(case: &TransientCase) -> ReducedSettings {
        let signals = ReducedSettings::default();
        let full = case.settings();
        ReducedSettings {
            damping_ratio: 0.0,
            rayleigh: full.damping,
            elements: full.elements.min(signals.elements),
            ..signals
        }
    }

    /// Builds the reduced model of `case`'s plate on `set` unless it is built already: what
    /// [`Self::root_prepared`] needs, so that roots on several threads share one model.
    pub fn prepare(&mut self, case: &TransientCase, set: &SupportSet) {
        if self.position(case, set).is_none() {
            let (plate, supports, settings) = (*case.plate(), set.supports, Self::settings(case));
            let model = ReducedModel::new(&plate, set, settings).ok();
            self.modal.push(Modal { plate, supports, settings, model });
        }
    }

    fn position(&self, case: &TransientCase, set: &SupportSet) -> Option<usize> {
        let (plate, supports, settings) = (*case.plate(), set.supports, Self::settings(case));
        self.modal.iter().position(|m| m.plate == plate && m.supports == supports && m.settings == settings)
    }

    /// The reduced model [`Self::prepare`] built, if it did and the model could be built.
    fn built(&self, case: &TransientCase, set: &SupportSet) -> Option<&ReducedModel> {
        self.position(case, set).and_then(|i| self.modal[i].model.as_ref())
    }

    /// The transient yield velocity of `root` to a relative width [`YIELD_ROOT_TOLERANCE`]
    /// (see the module), building its reduced model first if this search has none yet.
    pub fn root(&mut self, root: &Root) -> Result<TransientYield, ModelError> {
        self.prepare(root.case, root.set);
        self.root_prepared(root)
    }

    /// [`Self::root`] without building: the reduced model [`Self::prepare`] built for the
    /// root's mesh and supports brackets the root; without one the search starts from the
    /// rigid-target value, as where the model cannot be built. Takes `&self`, so roots run in
    /// parallel.
    pub fn root_prepared(&self, root: &Root) -> Result<TransientYield, ModelError> {
        let d_my = root.yield_compression();
        let window = root.case.settings().window_contacts;
        let mut reduced_runs = 0;
        let guess =
            self.built(root.case, root.set).and_then(|m| reduced_guess(m, root, d_my, window, &mut reduced_runs).ok());
        let mut runs = 0;
        if let Some(g) = guess {
            let mut f = |lv: f64| -> Result<f64, ModelError> {
                runs += 1;
                root.full(lv, d_my)
            };
            if let Some(bracket) = log_root_near(&mut f, g, YIELD_ROOT_TOLERANCE)? {
                return Ok(found(bracket, runs, reduced_runs, d_my));
            }
        }
        let t = transient_yield_from_rigid(root)?;
        Ok(TransientYield { runs: t.runs + runs, reduced_runs, ..t })
    }
}

/// The reduced model's root of `root` (δ_my `d_my`) from the rigid-target value, each run at
/// its own Δt = t_H/N as the full search's, and the reduced slope d f/d ln v over its final
/// bracket: the guess the full search starts from.
fn reduced_guess(
    model: &ReducedModel,
    root: &Root,
    d_my: f64,
    window: f64,
    runs: &mut usize,
) -> Result<Guess, ModelError> {
    let mut seen: Vec<(f64, f64)> = Vec::new();
    let (lo, hi) = {
        let mut f = |lv: f64| -> Result<f64, ModelError> {
            *runs += 1;
            let s = scene_striker(root.scene, root.body, lv.exp());
            let th = s.hertz_time();
            let (x, z) = root.at;
            let o = model.first_contact(&s, x, z, th / root.steps_per_contact, window * th)?;
            let y = (o.compression_max / d_my).ln();
            seen.push((lv, y));
            Ok(y)
        };
        log_root(&mut f, rigid_yield(root.scene, root.body).ln(), YIELD_ROOT_TOLERANCE)?
    };
    let at = |p: f64| seen.iter().find(|s| s.0 == p).map(|s| s.1);
    let slope = match (at(lo), at(hi)) {
        (Some(a), Some(b)) => (b - a) / (hi - lo),
        _ => f64::NAN,
    };
    Ok(Guess { at: 0.5 * (lo + hi), slope, reach: REDUCED_REACH, slope_spread: REDUCED_SLOPE_SPREAD })
}
