//! The yield velocity under three models: the paper's beam (eqs. 51-54), the quasi-static
//! plate FE compliance through the same formula, and the transient plate (the v at which
//! the transient δ_max reaches δ_my of eq. 51, [`coupled::yield_root`]).
//!
//! * [`paper`]: Table 2, Table 5's minimum and Figs. 8-9 redone on the paper's scene with all
//!   three models, and the paper's statements about yield velocities tested on the results
//!   ([`statements`]);
//! * [`scene`]: the three models on a scene of one's own, at its transient points.
//!
//! Each transient root is a bracket on ln v closed to [`ROOT_TOLERANCE`]; its width, the
//! plate's Richardson error and (on the paper's scene) a finer transient discretisation are
//! the resolution every comparison between models is judged against.

pub mod paper;
pub mod scene;
pub mod statements;

use crate::Failure;
use ::scene::Scene;
pub use coupled::plan::log_root;
use coupled::plan::{YieldRow, YieldValues};
use coupled::transient::{TransientCase, TransientSettings};
pub use coupled::yield_root::{rigid_yield, transient_yield, Root, TransientYield, YieldSearch};
use coupled::SupportSet;
use rayon::prelude::*;
use std::collections::HashMap;

/// Relative width of the bracket that closes each transient root: hi/lo - 1.
pub const ROOT_TOLERANCE: f64 = coupled::plan::YIELD_ROOT_TOLERANCE;
/// The finer transient discretisation that estimates the default one's error.
pub const FINE: TransientSettings = TransientSettings {
    elements: 40,
    steps_per_contact: 400.0,
    window_contacts: coupled::transient::case::WINDOW_HERTZ_TIMES,
    damping: None,
};
/// Points of the beam and plate curves (L in 100 parts, as section IV-A).
pub const SWEEP: usize = 101;
/// Points of the transient curves (each a root of about 3 time integrations).
pub const TRANSIENT_SWEEP: usize = 13;
/// The quasi-static plate's search grid for Table 5: x and z points, edges included.
pub const GRID: (usize, usize) = (11, 5);

/// A coordinate as an integer key (nm): points computed twice compare equal.
fn key(v: f64) -> i64 {
    (v * 1e9).round() as i64
}

/// The quasi-static v_y rows of one model, looked up by (body, condition, x, z).
struct QuasiStatic(HashMap<(String, String, i64, i64), YieldValues>);

impl QuasiStatic {
    fn new(rows: Vec<YieldRow>) -> Self {
        Self(
            rows.into_iter()
                .filter_map(|r| {
                    let v = r.values()?.clone();
                    Some(((r.body, r.condition, key(r.x), key(r.z)), v))
                })
                .collect(),
        )
    }
    fn get(&self, body: &str, cond: &str, x: f64, z: f64) -> Result<&YieldValues, Failure> {
        self.0
            .get(&(body.to_string(), cond.to_string(), key(x), key(z)))
            .ok_or_else(|| format!("no quasi-static v_y for {body} on {cond} at ({x}, {z}) m").into())
    }
    fn v(&self, body: &str, cond: &str, x: f64, z: f64) -> Result<f64, Failure> {
        Ok(self.get(body, cond, x, z)?.yield_velocity)
    }
}

/// Transient roots, each computed once: Table 2, Table 5 and the figures share cells, and
/// every root its support set's reduced model ([`YieldSearch`]).
struct Transients<'a> {
    scene: &'a Scene,
    case: TransientCase,
    search: YieldSearch,
    cells: HashMap<(String, String, i64, i64), TransientYield>,
}

impl Transients<'_> {
    fn get(&mut self, body: &analytic::Sphere, set: &SupportSet, x: f64, z: f64) -> Result<TransientYield, Failure> {
        let k = (body.name.clone(), set.name.clone(), key(x), key(z));
        if let Some(t) = self.cells.get(&k) {
            return Ok(*t);
        }
        let steps_per_contact = self.case.settings().steps_per_contact;
        let t = self.search.root(&Root {
            scene: self.scene,
            case: &self.case,
            steps_per_contact,
            set,
            body,
            at: (x, z),
        })?;
        self.cells.insert(k, t);
        Ok(t)
    }
    /// Computes the roots of `cells` (body, support set, x, z) not computed yet, on every
    /// core: the roots are independent, and each support set's reduced model is built once
    /// before them. The loops that follow find every cell here.
    fn prefetch(&mut self, cells: &[(&analytic::Sphere, &SupportSet, f64, f64)]) -> Result<(), Failure> {
        let mut missing: Vec<(&analytic::Sphere, &SupportSet, f64, f64)> = Vec::new();
        for &(body, set, x, z) in cells {
            let k = (body.name.clone(), set.name.clone(), key(x), key(z));
            let seen = missing.iter().any(|m| (m.0.name.clone(), m.1.name.clone(), key(m.2), key(m.3)) == k);
            if !seen && !self.cells.contains_key(&k) {
                missing.push((body, set, x, z));
            }
        }
        for &(_, set, _, _) in &missing {
            self.search.prepare(&self.case, set);
        }
        let (scene, case, search) = (self.scene, &self.case, &self.search);
        let steps = case.settings().steps_per_contact;
        let roots: Vec<Result<TransientYield, String>> = missing
            .par_iter()
            .map(|&(body, set, x, z)| {
                let root = Root { scene, case, steps_per_contact: steps, set, body, at: (x, z) };
                search.root_prepared(&root).map_err(|e| e.to_string())
            })
            .collect();
        for (&(body, set, x, z), root) in missing.iter().zip(roots) {
            self.cells.insert((body.name.clone(), set.name.clone(), key(x), key(z)), root?);
        }
        Ok(())
    }

    /// Runs of the full and of the reduced model over every root.
    fn runs(&self) -> (usize, usize) {
        self.cells.values().fold((0, 0), |(f, r), t| (f + t.runs, r + t.reduced_runs))
    }
}
