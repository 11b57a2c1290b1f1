//! Where to put a sensor: for each quantity, the separability max(AUC, 1 - AUC) of one
//! feature at every point of the candidate grid, that feature being the one whose best grid
//! value is highest.

use super::sensors::quantity_name;
use super::PlacementMap;
use crate::channel::ChannelInfo;
use coupled::reduced::Quantity;
use identify::placement::{best, map, Separability};
use identify::Study;

/// The placement maps of a run: `grid` gives the sensor recording each candidate point (in
/// [`Study::candidates`] order), `infos` the run's channels and `all` their separabilities.
/// A quantity not recorded at every grid point has no map; no grid, no maps.
pub fn maps(study: &Study, grid: &[usize], infos: &[ChannelInfo], all: &[Separability]) -> Vec<PlacementMap> {
    if grid.is_empty() {
        return Vec::new();
    }
    let nz = study.candidates_z.len();
    Quantity::ALL
        .into_iter()
        .chain([Quantity::Strain])
        .filter_map(|q| {
            let quantity = quantity_name(q);
            // One channel per grid point, in grid order: a point at a named sensor is its channel.
            let chans = grid
                .iter()
                .map(|&s| infos.iter().position(|i| i.sensor == Some(s) && i.quantity == quantity))
                .collect::<Option<Vec<usize>>>()?;
            let top = best(all, &chans)?;
            let values = map(all, &chans, top.feature);
            Some(PlacementMap {
                quantity,
                feature: top.feature,
                x_mm: study.candidates_x.iter().map(|x| x * 1e3).collect(),
                z_mm: study.candidates_z.iter().map(|z| z * 1e3).collect(),
                separability: (0..study.candidates_x.len())
                    .map(|i| (0..nz).map(|j| values[i * nz + j].separability()).collect())
                    .collect(),
            })
        })
        .collect()
}
