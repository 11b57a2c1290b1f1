//! Both models' compliance over the plate, for every support set of the scene.

use crate::settings::{BASE_MESH, LEVELS, MAP_X, MAP_Z};
use crate::Failure;
use coupled::{BeamModel, ComplianceModel, PlateModel};
use scene::{even_points, Scene};
use serde::Serialize;

/// The part of the length the maps and their statistics cover, as fractions of L: towards
/// the ends the beam's compliance falls to zero and the ratio to it diverges.
pub const INNER: (f64, f64) = (0.1, 0.9);

/// Compliance maps of both models over the plate for the scene's support sets.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Maps {
    /// The grid along the length, m.
    pub xs: Vec<f64>,
    /// The grid across the width, m.
    pub zs: Vec<f64>,
    /// Per support set, `[ix][iz]`: the plate's compliance, m/N.
    pub plate: Vec<Vec<Vec<f64>>>,
    /// Per support set, `[ix][iz]`: its FE error estimate, m/N.
    pub error: Vec<Vec<Vec<f64>>>,
    /// Per support set, `[ix]`: the beam's compliance (the same across the width; 0 where the
    /// beam does not describe the set), m/N.
    pub beam: Vec<Vec<f64>>,
}

impl Maps {
    /// C_plate/C_beam - 1 of support set `ci` at grid point (i, j); NaN where the beam's C is 0.
    pub fn ratio(&self, ci: usize, i: usize, j: usize) -> f64 {
        if self.beam[ci][i] > 0.0 {
            self.plate[ci][i][j] / self.beam[ci][i] - 1.0
        } else {
            f64::NAN
        }
    }

    /// Whether grid column `i` lies within [`INNER`] of a plate of length `l`.
    pub fn inner(&self, i: usize, l: f64) -> bool {
        (INNER.0..=INNER.1).contains(&(self.xs[i] / l))
    }
}

/// The index of the value of `v` nearest `x`.
pub fn nearest(v: &[f64], x: f64) -> usize {
    v.iter().enumerate().min_by(|a, b| (a.1 - x).abs().total_cmp(&(b.1 - x).abs())).map_or(0, |(i, _)| i)
}

/// The map grid: L in `MAP_X - 1` parts, B in `MAP_Z - 1`.
pub fn map_points(scene: &Scene) -> Vec<(f64, f64)> {
    let zs = even_points(scene.plate.width(), MAP_Z);
    even_points(scene.plate.length(), MAP_X).into_iter().flat_map(|x| zs.iter().map(move |&z| (x, z))).collect()
}

/// The maps, with their own plate model.
pub fn maps(scene: &Scene) -> Result<Maps, Failure> {
    maps_from(scene, &PlateModel::compute(&scene.plate, &scene.conditions, &map_points(scene), BASE_MESH, LEVELS)?)
}

/// The maps from a plate model that holds the map grid.
pub fn maps_from(scene: &Scene, model: &PlateModel) -> Result<Maps, Failure> {
    let xs = even_points(scene.plate.length(), MAP_X);
    let zs = even_points(scene.plate.width(), MAP_Z);
    let beam = BeamModel { plate: &scene.plate };
    let (mut plate, mut error, mut beam_c) = (Vec::new(), Vec::new(), Vec::new());
    for c in &scene.conditions {
        let (mut grid, mut egrid, mut brow) = (Vec::new(), Vec::new(), Vec::new());
        for &x in &xs {
            // The beam describes only Con 1-3; the map's beam row is unused for other sets.
            brow.push(match beam.compliance(c, x, 0.0) {
                Ok(e) => e.compliance.total(),
                Err(coupled::ModelError::NotApplicable { .. }) => 0.0,
                Err(e) => return Err(e.into()),
            });
            let (mut col, mut ecol) = (Vec::new(), Vec::new());
            for &z in &zs {
                let v = model.get(&c.name, x, z).ok_or("map point missing")?;
                col.push(v.compliance.total());
                ecol.push(v.error_estimate);
            }
            grid.push(col);
            egrid.push(ecol);
        }
        plate.push(grid);
        error.push(egrid);
        beam_c.push(brow);
    }
    Ok(Maps { xs, zs, plate, error, beam: beam_c })
}

/// The map of one support set the beam describes, in numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MapFinding {
    /// The support set's name.
    pub condition: String,
    /// Its index among the scene's support sets (and the maps').
    pub index: usize,
    /// The lowest C_plate/C_beam - 1 within [`INNER`].
    pub lowest: f64,
    /// The highest.
    pub highest: f64,
    /// At mid-span on the centreline.
    pub centre: f64,
    /// At mid-span on the free edge z = 0.
    pub free_edge: f64,
    /// The grid indices of mid-span, of the centreline and of the free edge.
    pub grid: (usize, usize, usize),
}

/// The maps' statistics, per support set the beam describes.
pub fn map_findings(scene: &Scene, mp: &Maps) -> Vec<MapFinding> {
    let l = scene.plate.length();
    let mut out = Vec::new();
    for (ci, c) in scene.conditions.iter().enumerate().filter(|(_, c)| c.beam_condition().is_some()) {
        // Interior statistics (away from the ends, where the beam ratio is singular).
        let inner: Vec<f64> = (0..mp.xs.len())
            .filter(|&i| mp.inner(i, l))
            .flat_map(|i| (0..mp.zs.len()).map(move |j| (i, j)))
            .map(|(i, j)| mp.ratio(ci, i, j))
            .filter(|v| v.is_finite())
            .collect();
        let (lo, hi) = inner.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
        let mid = nearest(&mp.xs, l / 2.0);
        let (zc, ze) = (nearest(&mp.zs, scene.plate.width() / 2.0), 0);
        out.push(MapFinding {
            condition: c.name.clone(),
            index: ci,
            lowest: lo,
            highest: hi,
            centre: mp.ratio(ci, mid, zc),
            free_edge: mp.ratio(ci, mid, ze),
            grid: (mid, zc, ze),
        });
    }
    out
}
