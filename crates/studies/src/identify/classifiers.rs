//! Whole sensors scored: the cross-validated accuracy of a ridge logistic classifier on every
//! feature of a group of channels, and its change from N/2 to N modes on the same impacts and
//! folds. The groups: the best sensor, the reference feature's sensor, the corners, and
//! everything a named instrument records.

use super::check::Truncation;
use super::Accuracy;
use crate::channel::{mm, ChannelInfo};
use crate::Failure;
use coupled::identification::ConditionRun;
use identify::features::FEATURES;
use identify::placement::{classifier, Separability};

/// A group of channels and its description.
pub type Group = (String, Vec<usize>);

/// Every channel of the sensor that recorded `s`, described as `what` the sensor is.
fn sensor_group(infos: &[ChannelInfo], s: &Separability, what: &str) -> Group {
    let sensor = infos[s.channel].sensor;
    let chans: Vec<usize> = (0..infos.len()).filter(|&c| infos[c].sensor == sensor).collect();
    (
        format!(
            "{what} {} quantities × {} features, at ({}, {}) mm",
            chans.len(),
            FEATURES.len(),
            mm(infos[s.channel].at.0),
            mm(infos[s.channel].at.1)
        ),
        chans,
    )
}

/// The groups the classifiers see, of a run with channels `infos` and `named` named sensors:
/// the best sensor's channels, the reference feature's sensor's (if another sensor), the
/// corners', and every named sensor's with the corners'.
pub fn groups(
    infos: &[ChannelInfo],
    best_sensor: Option<Separability>,
    converged: Option<Separability>,
    named: usize,
) -> Vec<Group> {
    let mut groups = Vec::new();
    if let Some(s) = best_sensor {
        groups.push(sensor_group(infos, &s, "the best sensor's"));
    }
    if let Some(s) = converged.filter(|c| infos[c.channel].sensor.is_some()) {
        if best_sensor.is_none_or(|b| infos[b.channel].sensor != infos[s.channel].sensor) {
            groups.push(sensor_group(infos, &s, "the reference feature's sensor:"));
        }
    }
    let corners: Vec<usize> = (0..infos.len()).filter(|&c| infos[c].sensor.is_none()).collect();
    if !corners.is_empty() {
        groups.push((
            format!("the {} corner channels (spring forces, reactions) × {} features", corners.len(), FEATURES.len()),
            corners.clone(),
        ));
    }
    if named > 0 {
        let channels = super::sensors::stated_channels(infos, named);
        groups.push((
            format!(
                "every named sensor and corner channel ({} channels) × {} features",
                channels.len(),
                FEATURES.len()
            ),
            channels,
        ));
    }
    groups
}

/// Each group's accuracy on `run`, and its change from N/2 to N modes on the impacts the
/// `check` struck again; the k-th group's folds dealt by the stream of `seed ^ (3 + k)`.
pub fn accuracies(
    run: &ConditionRun,
    check: &Truncation,
    groups: Vec<Group>,
    seed: u64,
) -> Result<Vec<Accuracy>, Failure> {
    let mut out = Vec::new();
    for (k, (features, chans)) in groups.into_iter().enumerate() {
        let result = classifier(&run.table, &chans, seed ^ (3 + k as u64))?;
        let coarse = classifier(&check.half.table, &chans, seed ^ (3 + k as u64))?;
        let fine = if check.sampled() {
            classifier(&check.main(run).table, &chans, seed ^ (3 + k as u64))?.accuracy
        } else {
            result.accuracy
        };
        out.push(Accuracy { features, result, resolution: fine - coarse.accuracy });
    }
    Ok(out)
}
