//! Where to put a sensor: for each quantity, the separability max(AUC, 1 - AUC) of one
//! feature at every point of the candidate grid, that feature being the one whose best grid
//! value is highest.

use super::ensemble::run;
use super::sensors::quantity_name;
use super::{BackgroundDesign, DesignStep, PlacementMap, SensorDesign};
use crate::channel::ChannelInfo;
use crate::progress::Progress;
use coupled::identification::{ConditionRun, Instrument};
use coupled::reduced::Quantity;
use identify::placement::{best, map, separabilities, FeatureTable, Separability};
use identify::{Held, Study};
use scene::SupportSet;

/// The placement maps of a run: `grid` gives the sensor recording each candidate point (in
/// [`Study::candidates`] order), `infos` the run's channels and `all` their separabilities.
/// A quantity not recorded at every grid point has no map; no grid, no maps.
pub fn maps(study: &Study, grid: &[usize], infos: &[ChannelInfo], all: &[Separability]) -> Vec<PlacementMap> {
    if grid.is_empty() {
        return Vec::new();
    }
    Quantity::ALL
        .into_iter()
        .chain([Quantity::Strain])
        .filter_map(|q| {
            let quantity = quantity_name(q);
            let chans = grid_channels(grid, infos, quantity)?;
            let top = best(all, &chans)?;
            let values = map(all, &chans, top.feature);
            Some(PlacementMap {
                quantity,
                feature: top.feature,
                x_mm: study.candidates_x.iter().map(|x| x * 1e3).collect(),
                z_mm: study.candidates_z.iter().map(|z| z * 1e3).collect(),
                separability: study.by_x_and_z(&values.iter().map(|v| v.separability()).collect::<Vec<_>>()),
            })
        })
        .collect()
}

/// One channel of `quantity` per grid point, in grid order (a point at a named sensor is its
/// channel); None if some grid point does not record it.
fn grid_channels(grid: &[usize], infos: &[ChannelInfo], quantity: &str) -> Option<Vec<usize>> {
    grid.iter().map(|&s| infos.iter().position(|i| i.sensor == Some(s) && i.quantity == quantity)).collect()
}

/// The sensor design of a run ([`identify::design::greedy`]): `study.design_sensors` sensors
/// of the quantity whose placement map (`maps`) peaks highest, chosen among the grid's points
/// on the features of `table`; None without a budget or a map.
pub fn design(
    study: &Study,
    grid: &[usize],
    infos: &[ChannelInfo],
    maps: &[PlacementMap],
    table: &FeatureTable,
    seed: u64,
) -> Result<Option<SensorDesign>, crate::Failure> {
    let peak = |m: &PlacementMap| m.separability.iter().flatten().fold(0.0f64, |a, &b| a.max(b));
    let top = maps.iter().fold(None, |b: Option<&PlacementMap>, m| match b {
        Some(b) if peak(b) >= peak(m) => Some(b),
        _ => Some(m),
    });
    let (Some(map), true) = (top, study.design_sensors > 0) else { return Ok(None) };
    let Some(chans) = grid_channels(grid, infos, map.quantity) else { return Ok(None) };
    let steps = identify::design::greedy(table, &chans, study.design_sensors, seed)?;
    let nz = study.candidates_z.len();
    let at = |k: usize| (study.candidates_x[k / nz] * 1e3, study.candidates_z[k % nz] * 1e3);
    Ok(Some(SensorDesign {
        quantity: map.quantity,
        x_mm: map.x_mm.clone(),
        z_mm: map.z_mm.clone(),
        steps: steps
            .into_iter()
            .map(|s| DesignStep {
                at_mm: at(s.added),
                auc: s.auc,
                gain: s.gain,
                gain_standard_error: s.gain_standard_error,
                map: study.by_x_and_z(&s.map),
            })
            .collect(),
    }))
}

/// The design chosen again with the chain's background scaled by each of
/// `study.design_backgrounds`: the main run's impacts re-recorded at that level by the main
/// run's `instrument` (its channels `infos`, the grid's sensors at `grid`), its placement
/// maps and greedy design with the main design's folds (`seed`). At the stated level (1) that
/// is the main run `main` and its design `stated`, which are taken as they are. The
/// instrument is left at the last level.
pub fn at_backgrounds(
    study: &Study,
    set: &SupportSet,
    (instrument, main, stated): (&mut Instrument<'_>, &ConditionRun, Option<&SensorDesign>),
    (infos, grid): (&[ChannelInfo], &[usize]),
    seed: u64,
    progress: &dyn Progress,
) -> Result<Vec<BackgroundDesign>, crate::Failure> {
    let mut out = Vec::with_capacity(study.design_backgrounds.len());
    for &scale in &study.design_backgrounds {
        let rerun;
        let (r, design) = if scale == 1.0 {
            (main, stated.cloned())
        } else {
            instrument.set_noise_scale(scale);
            let what = format!("design at background × {}", analytic::params::compact(scale));
            rerun = run(study, Held::NONE, instrument, &set.name, &what, progress, |_| Ok(()))?;
            let maps = maps(study, grid, infos, &separabilities(&rerun.table));
            (&rerun, design(study, grid, infos, &maps, &rerun.table, seed)?)
        };
        let snr_db = design.as_ref().and_then(|d| {
            let first = d.steps.first()?;
            let k = study.candidates().iter().position(|&(x, z)| (x * 1e3, z * 1e3) == first.at_mm)?;
            let c = infos.iter().position(|i| i.sensor == Some(grid[k]) && i.quantity == d.quantity)?;
            super::measured::scaled_snr(r, c, instrument.chain()?, scale)
        });
        out.push(BackgroundDesign { scale, snr_db, design });
    }
    Ok(out)
}
