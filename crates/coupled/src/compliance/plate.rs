//! The plate FE model as a compliance provider for the shared energy balance.
//!
//! Everything a scene needs is computed up front: for each mesh of a short ladder (h and
//! h/2), one base factorization ([`CornerFamily`]), one blocked solve per distinct impact
//! point (mirror images share it), and a rank-4 update per condition. The two meshes are
//! combined by Richardson extrapolation into the compliance that feeds the balance, with
//! the error estimate it carries. Downstream code sees an `analytic::PointCompliance`, as
//! it does for the beam.

use super::table::PointValues;
use super::{ComplianceModel, Estimate};
use crate::discretisation::{ladder_meshes, plate_properties};
use crate::error::ModelError;
use crate::supports::SupportSet;
use analytic::compliance::InvalidCompliance;
use analytic::{Plate, PointCompliance, SpringReaction, Store, StoreKind};
use plate_fem::convergence::richardson_at_rate;
use plate_fem::{Corner, CornerFamily, CornerSupport, Model, PointResponse};
use std::time::Instant;

/// The plate model's value at one point: a compliance with its discretisation error.
pub type FeCompliance = Estimate;

/// One mesh of the ladder and what it cost.
#[derive(Debug, Clone, serde::Serialize)]
pub struct LevelCost {
    /// Elements along the length.
    pub nx: usize,
    /// Elements across the width.
    pub nz: usize,
    /// Degrees of freedom.
    pub dofs: usize,
    /// Assembly, factorizations, solves and updates on this mesh, s.
    pub seconds: f64,
}

/// Precomputed plate compliances for every (condition, x, z) a scene needs.
pub struct PlateModel {
    name: String,
    values: PointValues,
    /// The meshes used, coarse to fine, with their costs.
    pub levels: Vec<LevelCost>,
}

/// Bilinear weights of the four corners at (x, z).
pub(crate) fn corner_weights(x: f64, z: f64, l: f64, b: f64) -> [f64; 4] {
    let (s, t) = (x / l, z / b);
    [(1.0 - s) * (1.0 - t), s * (1.0 - t), (1.0 - s) * t, s * t]
}

/// The spring corners' part of a compliance at `at` on an `l` x `b` plate: a store and a
/// reaction per spring, and the plane through the spring corners' deflections at `at` (the
/// rigid motion on the springs, which the bending deflection leaves out). `part` gives, for
/// corner index i of stiffness k, its store (m/N), its force per unit load and its deflection
/// per unit load (m/N).
pub(crate) fn spring_parts(
    corners: [CornerSupport; 4],
    at: (f64, f64),
    l: f64,
    b: f64,
    part: impl Fn(usize, f64) -> (f64, f64, f64),
) -> (Vec<Store>, Vec<SpringReaction>, f64) {
    let weights = corner_weights(at.0, at.1, l, b);
    let (mut stores, mut springs, mut plane) = (Vec::new(), Vec::new(), 0.0);
    for c in Corner::ALL {
        let i = c.index();
        if let CornerSupport::Spring(k) = corners[i] {
            let (store, reaction, deflection) = part(i, k);
            let name = format!("spring at {}", c.name());
            stores.push(Store { name: name.clone(), kind: StoreKind::Spring, compliance: store });
            springs.push(SpringReaction { name, per_unit_load: reaction });
            plane += weights[i] * deflection;
        }
    }
    (stores, springs, plane)
}

/// The analytic compliance of one FE response: plate store, one store per spring, spring
/// reactions, and the bending deflection (w at the point minus the bilinear plane through
/// the corner deflections, the plate's analogue of eq. 11, which leaves out the rigid
/// motion on the springs).
fn to_analytic(
    r: &PointResponse,
    corners: [CornerSupport; 4],
    l: f64,
    b: f64,
) -> Result<PointCompliance, InvalidCompliance> {
    let (mut stores, springs, support_plane) = spring_parts(corners, (r.x, r.z), l, b, |i, k| {
        let c = &r.corners[i];
        (c.spring_compliance, c.reaction, c.reaction / k)
    });
    stores.insert(
        0,
        Store { name: "plate bending".into(), kind: StoreKind::Plate, compliance: r.plate_compliance.max(0.0) },
    );
    PointCompliance::new(stores, springs, r.compliance - support_plane)
}

/// Richardson-extrapolates each component of two analytic compliances (same layout).
pub(crate) fn extrapolate(
    coarse: &PointCompliance,
    fine: &PointCompliance,
    finer_of: &[PointCompliance],
) -> Result<FeCompliance, ModelError> {
    extrapolate_at_rate(2.0, coarse, fine, finer_of)
}

/// [`extrapolate`] at the nominal convergence rate `rate` ([`richardson_at_rate`]).
pub(crate) fn extrapolate_at_rate(
    rate: f64,
    coarse: &PointCompliance,
    fine: &PointCompliance,
    finer_of: &[PointCompliance],
) -> Result<FeCompliance, ModelError> {
    let ext = |a: f64, b: f64| richardson_at_rate(&[a, b], rate).map_or(b, |e| e.extrapolated);
    let stores = coarse
        .stores()
        .iter()
        .zip(fine.stores())
        .map(|(a, b)| Store {
            name: b.name.clone(),
            kind: b.kind,
            compliance: ext(a.compliance, b.compliance).max(0.0),
        })
        .collect();
    let springs = coarse
        .springs()
        .iter()
        .zip(fine.springs())
        .map(|(a, b)| SpringReaction { name: b.name.clone(), per_unit_load: ext(a.per_unit_load, b.per_unit_load) })
        .collect();
    let deflection = ext(coarse.deflection_per_unit_load(), fine.deflection_per_unit_load());
    let compliance = PointCompliance::new(stores, springs, deflection)?;
    let totals: Vec<f64> = finer_of.iter().map(|c| c.total()).collect();
    let e = richardson_at_rate(&totals, rate)
        .ok_or_else(|| ModelError::Missing("Richardson extrapolation needs two meshes".into()))?;
    Ok(FeCompliance { compliance, error_estimate: e.error_estimate, asymptotic: e.asymptotic })
}

impl PlateModel {
    /// Computes the compliances of `conditions` at `points` on the ladder of meshes with
    /// `base` elements along the longer side, then 2·base, ... (`levels` ≥ 2).
    ///
    /// ```
    /// use analytic::{Elastic, Plate, Condition};
    /// use coupled::{ComplianceModel, PlateModel, SupportSet};
    /// let plate = Plate::new(0.4584, 0.36, 0.008, 7850.0, Elastic::new(210e9, 0.3)?)?;
    /// let con1 = SupportSet::preset("Con 1", Condition::BothFixed);
    /// let centre = (0.2292, 0.18);
    /// let model = PlateModel::compute(&plate, &[con1.clone()], &[centre], 10, 2)?;
    /// let c = model.compliance(&con1, centre.0, centre.1)?;
    /// // The plate is about 20 % more compliant than the beam at the centre (reports/).
    /// let beam = 0.4584f64.powi(3) / (48.0 * plate.beam_bending_stiffness());
    /// assert!((c.compliance.total() / beam - 1.2).abs() < 0.01);
    /// assert!(c.relative_error() < 1e-3);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn compute(
        plate: &Plate,
        conditions: &[SupportSet],
        points: &[(f64, f64)],
        base: usize,
        levels: u32,
    ) -> Result<Self, ModelError> {
        let props = plate_properties(plate);
        Self::on_meshes(plate, conditions, points, ladder_meshes(&props, base, levels.max(2))?)
    }

    /// The same on given meshes, each twice as fine as the one before. With one mesh the
    /// values are that mesh's, with no error estimate (NaN).
    pub fn on_meshes(
        plate: &Plate,
        conditions: &[SupportSet],
        points: &[(f64, f64)],
        meshes: Vec<plate_fem::Mesh>,
    ) -> Result<Self, ModelError> {
        let props = plate_properties(plate);
        let (l, b) = (props.length, props.width);
        let mut per_level: Vec<Vec<Vec<PointCompliance>>> = Vec::new(); // level -> condition -> point
        let mut costs = Vec::new();
        for mesh in meshes {
            let t = Instant::now();
            let (nx, nz) = (mesh.nx(), mesh.nz());
            let model = Model::new(props, mesh)?;
            // One base factorization per distinct edge set; the corners of every support
            // set with those edges follow from it by the rank-4 update.
            let mut per_cond: Vec<Option<Vec<PointCompliance>>> = vec![None; conditions.len()];
            for (ci, c) in conditions.iter().enumerate() {
                if per_cond[ci].is_some() {
                    continue;
                }
                let edges = c.supports.edges;
                let family = CornerFamily::new(&model, edges, CornerFamily::default_base_stiffness(&model))?;
                let base_points = family.probe_map(points)?;
                for (cj, other) in conditions.iter().enumerate().skip(ci) {
                    if other.supports.edges != edges {
                        continue;
                    }
                    let corners = other.supports.corners;
                    let row = base_points
                        .iter()
                        .map(|bp| Ok(to_analytic(&family.respond(bp, corners)?, corners, l, b)?))
                        .collect::<Result<Vec<_>, ModelError>>()?;
                    per_cond[cj] = Some(row);
                }
            }
            let per_cond: Vec<Vec<PointCompliance>> = per_cond.into_iter().flatten().collect();
            costs.push(LevelCost { nx, nz, dofs: model.dofs(), seconds: t.elapsed().as_secs_f64() });
            per_level.push(per_cond);
        }
        let n = per_level.len();
        let mut values = PointValues::new(l, b);
        for (ci, c) in conditions.iter().enumerate() {
            for (pi, &(x, z)) in points.iter().enumerate() {
                let seq: Vec<PointCompliance> = per_level.iter().map(|lv| lv[ci][pi].clone()).collect();
                let fe = if n >= 2 {
                    extrapolate(&seq[n - 2], &seq[n - 1], &seq)?
                } else {
                    // One mesh: no estimate is possible; say so with an infinite error rather
                    // than a number that looks like one.
                    FeCompliance { compliance: seq[0].clone(), error_estimate: f64::INFINITY, asymptotic: false }
                };
                values.insert(&c.name, x, z, fe);
            }
        }
        let finest = costs.last().map(|c| format!("{} x {}", c.nx, c.nz)).unwrap_or_default();
        let name =
            if n >= 2 { format!("plate FE (extrapolated from {finest})") } else { format!("plate FE ({finest})") };
        Ok(Self { name, values, levels: costs })
    }

    /// The FE value at (condition, x, z), if computed.
    pub fn get(&self, condition: &str, x: f64, z: f64) -> Option<&FeCompliance> {
        self.values.get(condition, x, z)
    }
}

impl ComplianceModel for PlateModel {
    fn name(&self) -> &str {
        &self.name
    }
    fn resolves_width(&self) -> bool {
        true
    }
    fn compliance(&self, set: &SupportSet, x: f64, z: f64) -> Result<Estimate, ModelError> {
        self.values.require("plate", set, x, z)
    }
}
