//! What an identification run records: the named sensors and the candidate grid as one list
//! of sensors, their channels, and what the features of a run cost in memory.

use crate::channel::ChannelInfo;
use crate::Failure;
use coupled::identification::{measurand_of, Instrument};
use coupled::reduced::{Quantity, ReducedSettings, SignalSpec};
use identify::features::FEATURES;
use identify::measurement::Measurand;
use identify::Study;
use scene::{Scene, SupportSet};

/// The reduced model's settings on `set`: the scene's, with the fewest modes the measurement
/// chain needs where `[signals] modes = "chain"` (the modes whose highest the chain's gain
/// above stays within its band tolerance, `identify::measurement::Chain::modes_needed`;
/// all the scene allows if none suffices, which the report then flags).
pub fn reduced_settings(scene: &Scene, set: &SupportSet) -> Result<ReducedSettings, Failure> {
    let settings = scene.signals.reduced();
    let (true, Some(spec)) = (scene.signals.modes_from_chain, &scene.measurement) else { return Ok(settings) };
    // The most modes this plate's mesh resolves (a swept plate may resolve fewer than the
    // scene's, whose most `signals.modes` holds under the chain's rule).
    let plate = &scene.plate;
    let most = scene::limits::max_modes(plate.length() * 1e3, plate.width() * 1e3);
    let settings = ReducedSettings { modes: settings.modes.min(most), ..settings };
    let chain = identify::measurement::Chain::new(spec.clone(), scene.signals.rate_hz)?;
    let frequencies = coupled::reduced::frequencies_hz(&scene.plate, set, settings)?;
    let modes = chain.modes_needed(&frequencies).unwrap_or(frequencies.len());
    Ok(ReducedSettings { modes, ..settings })
}

/// Channels an identification records per impact on `set`: each recorded quantity at every
/// named and candidate sensor (once where they coincide), and the held or sprung corners if
/// their forces are recorded ([`spec`]).
pub fn channels_per_impact(scene: &Scene, study: &Study, set: &SupportSet) -> usize {
    let sensors = run_sensors(&scene.signals.sensors, study, &scene.plate).0.len();
    let spec = spec(scene, Vec::new());
    let corners = set.supports.corners.iter().filter(|c| !matches!(c, plate_fem::CornerSupport::Free)).count();
    spec.quantities.len() * sensors + if spec.corners { corners } else { 0 }
}

/// The sensors of an identification run: the named sensors, then the candidate grid's points
/// that are not at a named sensor; and, for each grid point in [`Study::candidates`] order,
/// the index of the sensor that records it. A grid point at a named sensor is that sensor (the
/// same signals), so its channels are recorded, ranked and written once, under the named
/// sensor. Positions coincide within 1e-9 of the plate's larger side, far below the
/// millimetre digits a scene gives them in.
pub fn run_sensors(named: &[(f64, f64)], study: &Study, plate: &analytic::Plate) -> (Vec<(f64, f64)>, Vec<usize>) {
    let tol = 1e-9 * plate.length().max(plate.width());
    let mut sensors = named.to_vec();
    let grid = study
        .candidates()
        .into_iter()
        .map(|(x, z)| {
            named.iter().position(|&(nx, nz)| (nx - x).abs() <= tol && (nz - z).abs() <= tol).unwrap_or_else(|| {
                sensors.push((x, z));
                sensors.len() - 1
            })
        })
        .collect();
    (sensors, grid)
}

/// The channels of `infos` at the first `named` sensors (the scene's named ones) and at the
/// supports: what a user states, as against the candidate grid's.
pub fn stated_channels(infos: &[ChannelInfo], named: usize) -> Vec<usize> {
    (0..infos.len()).filter(|&c| infos[c].sensor.is_none_or(|s| s < named)).collect()
}

/// Bytes of features one run holds: [`FEATURES`] of 8 bytes each per impact and channel.
pub fn feature_bytes(impacts: usize, channels: usize) -> usize {
    impacts.saturating_mul(channels).saturating_mul(FEATURES.len() * 8)
}

/// The error of a support set on which nothing is recorded.
pub fn no_channels(set: &str) -> Failure {
    format!(
        "support set '{set}' records no channel (no named sensor, no candidate grid, no spring or fixed corner): give [signals] sensors_mm or [ensemble.placement]"
    )
    .into()
}

/// The signals of a run at `sensors`: the scene's window and rate; the three kinematic
/// quantities and the corners, or under a measurement chain only what it records (its
/// strain gauges included; nothing else is computed).
pub fn spec(scene: &Scene, sensors: Vec<(f64, f64)>) -> SignalSpec {
    let settings = &scene.signals;
    let quantities = match &scene.measurement {
        None => Quantity::ALL.to_vec(),
        Some(c) => {
            let records = |q: Quantity| c.recordings.iter().any(|r| r.measurand == measurand_of(q));
            Quantity::ALL.into_iter().chain([Quantity::Strain]).filter(|&q| records(q)).collect()
        }
    };
    let corners =
        scene.measurement.as_ref().is_none_or(|c| c.recordings.iter().any(|r| r.measurand == Measurand::SupportForce));
    SignalSpec { window: settings.window, rate_hz: settings.rate_hz, sensors, quantities, corners }
}

/// The channels `instrument` records at `sensors` on `plate`, named.
pub fn channel_infos(instrument: &Instrument<'_>, sensors: &[(f64, f64)], plate: &analytic::Plate) -> Vec<ChannelInfo> {
    instrument.channels().into_iter().map(|k| ChannelInfo::new(k, sensors, plate)).collect()
}

/// The name of a recorded quantity, as [`ChannelInfo::quantity`] has it.
pub fn quantity_name(q: Quantity) -> &'static str {
    match q {
        Quantity::Displacement => "displacement",
        Quantity::Velocity => "velocity",
        Quantity::Acceleration => "acceleration",
        Quantity::Strain => "strain",
    }
}
