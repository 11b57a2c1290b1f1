//! Which variability hides the difference: the same impacts (the same random numbers) rerun
//! with one variable of the draw at its median (position, size, speed or material, as the
//! scene's `hold` lists), then with everything but the material held, each scored by the
//! reference feature's AUC, the run's best feature, P_max and a classifier on every channel.
//!
//! The reruns record the reference instrument only: the named sensors, the reference
//! feature's sensor and the corners, so that they cost a fraction of the main run.

use super::ensemble::run;
use super::sensors::{channel_infos, spec};
use super::separability::{ranked, split};
use super::{held_label, Held1};
use crate::channel::ChannelInfo;
use crate::progress::Progress;
use crate::Failure;
use coupled::identification::Instrument;
use coupled::reduced::{ChannelKind, ReducedModel};
use identify::placement::{best, classifier, separabilities, Separability};
use identify::roc::{auc_with_error, Auc};
use identify::{Feature, Held, Study};
use scene::{Scene, SupportSet};

/// A feature of one channel, the channel by its kind.
type ChannelFeature = (ChannelKind, &'static dyn Feature);

/// The main run of a support set, which the variability study reruns in part.
pub struct MainRun<'a> {
    /// Its reduced model.
    pub model: &'a ReducedModel,
    /// Its sensors: the named ones, then the candidate grid's ([`super::run_sensors`]).
    pub sensors: &'a [(f64, f64)],
    /// Its channels.
    pub infos: &'a [ChannelInfo],
}

/// The reference feature on the reference instrument: its sensors (the named ones, then the
/// reference feature's if it is a grid point) and the reference's channel kind and feature
/// on them.
fn reference_instrument(
    named: &[(f64, f64)],
    main: &MainRun<'_>,
    reference: Option<Separability>,
) -> (Vec<(f64, f64)>, Option<ChannelFeature>) {
    let (sensors, infos) = (main.sensors, main.infos);
    let mut reference_sensors = named.to_vec();
    let mut reference = reference.map(|s| (infos[s.channel].kind, s.feature));
    if let Some((kind, feature)) = reference {
        if let Some(s) = infos.iter().find(|i| i.kind == kind).and_then(|i| i.sensor) {
            if s >= named.len() {
                reference_sensors.push(sensors[s]);
                let sensor = named.len();
                let moved = match kind {
                    ChannelKind::Displacement { .. } => ChannelKind::Displacement { sensor },
                    ChannelKind::Velocity { .. } => ChannelKind::Velocity { sensor },
                    ChannelKind::Acceleration { .. } => ChannelKind::Acceleration { sensor },
                    ChannelKind::Strain { .. } => ChannelKind::Strain { sensor },
                    other => other,
                };
                reference = Some((moved, feature));
            }
        }
    }
    (reference_sensors, reference)
}

/// The variables held, one run each: each of the scene's `hold`, then all but the material
/// (the paper's comparison: same position, size and speed); none if `hold` is empty.
pub fn variants(study: &Study) -> Vec<Held> {
    let mut variants: Vec<Held> = study.hold.iter().map(|v| Held::only(*v)).collect();
    if !study.hold.is_empty() {
        variants.push(Held { position: true, size: true, speed: true, material: false });
    }
    variants
}

/// The variability study on `set`, rerunning its `main` run's model, against the `reference`
/// entry of the main run; the k-th run's streams derive from `seed ^ (100 + k)` (bootstrap)
/// and `seed ^ (200 + k)` (folds). Returns the runs and the reference feature in words (its
/// channel on the reference instrument and its name).
pub fn held_runs(
    scene: &Scene,
    study: &Study,
    set: &SupportSet,
    main: &MainRun<'_>,
    reference: Option<Separability>,
    seed: u64,
    progress: &dyn Progress,
) -> Result<(Vec<Held1>, Option<String>), Failure> {
    let (ref_sensors, reference) = reference_instrument(&scene.signals.sensors, main, reference);
    let plate = &scene.plate;
    let spec = spec(scene, ref_sensors.clone());
    let instrument = Instrument::new(main.model, plate, &spec, scene)?;
    let ref_infos = channel_infos(&instrument, &ref_sensors, plate);
    let all_channels: Vec<usize> = (0..ref_infos.len()).collect();
    let mut held = Vec::new();
    for (k, h) in variants(study).into_iter().enumerate() {
        let r = run(study, h, &instrument, &set.name, &format!("{} held", held_label(h)), progress, |_| Ok(()))?;
        let seps = separabilities(&r.table);
        let reference_auc = reference
            .and_then(|(kind, f)| ref_infos.iter().position(|i| i.kind == kind).map(|c| (c, f)))
            .map_or(Auc { auc: 0.5, standard_error: 0.0 }, |(c, f)| {
                let (a, b) = r.table.split(c, f);
                auc_with_error(&a, &b)
            });
        let Some(top) = best(&seps, &[]) else { continue };
        let (a, b) = r.table.split(top.channel, top.feature);
        let (pc, pg) = split(&r.force_max, r.table.classes());
        held.push(Held1 {
            which: h,
            held: held_label(h),
            reference: reference_auc,
            best: ranked(ref_infos[top.channel].label(), top.feature, (&a, &b), None, seed ^ (100 + k as u64)),
            force_max: auc_with_error(&pc, &pg),
            accuracy: classifier(&r.table, &all_channels, seed ^ (200 + k as u64))?,
        });
    }
    let label = reference.map(|(k, f)| {
        let i = ref_infos.iter().find(|i| i.kind == k).map_or_else(|| "-".to_string(), |i| i.label());
        format!("{i}, {}", f.name())
    });
    Ok((held, label))
}
