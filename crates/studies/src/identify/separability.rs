//! How well each feature of each channel separates coal from gangue: its ROC AUC
//! (Mann-Whitney, with DeLong's standard error), ranked by max(AUC, 1 - AUC), with a
//! percentile bootstrap interval for the entries shown and the change of the AUC from N/2 to
//! N modes on the same impacts ([`super::check`]).

use super::check::{Shift, Truncation};
use super::{resolved, ClassValues, Ranked, LEVEL, TOP};
use crate::channel::ChannelInfo;
use coupled::identification::ConditionRun;
use identify::features::{Duration, Peak, FEATURES};
use identify::placement::{best, separabilities, Separability};
use identify::roc::{auc_with_error, bootstrap_interval, BOOTSTRAP_RESAMPLES};
use identify::{Class, Feature};

/// `values` split by `classes` into coal's and gangue's, in impact order.
pub fn split(values: &[f64], classes: &[Class]) -> (Vec<f64>, Vec<f64>) {
    let mut c = Vec::new();
    let mut g = Vec::new();
    for (v, k) in values.iter().zip(classes) {
        match k {
            Class::Coal => c.push(*v),
            Class::Gangue => g.push(*v),
        }
    }
    (c, g)
}

/// One column's AUC with its error and bootstrap interval (resampled by the stream of
/// `seed`), and its `shift` from N/2 to N modes.
pub fn ranked(
    channel: String,
    feature: &'static dyn Feature,
    (coal, gangue): (&[f64], &[f64]),
    shift: Option<Shift>,
    seed: u64,
) -> Ranked {
    Ranked {
        channel,
        feature,
        auc: auc_with_error(coal, gangue),
        interval: bootstrap_interval(coal, gangue, BOOTSTRAP_RESAMPLES, LEVEL, seed),
        resolution: shift.map(|s| s.change),
        resolution_error: shift.and_then(|s| s.error),
    }
}

/// The paper's contact quantities, P_max and the first contact's duration t_c, scored as
/// features are, with their shift from N/2 to N modes (`check`).
pub fn contact_quantities(run: &ConditionRun, check: &Truncation, seed: u64) -> (Ranked, Ranked) {
    let classes = run.table.classes();
    let score = |name: &str, feature: &'static dyn Feature, of: fn(&ConditionRun) -> &[f64], seed: u64| {
        let (c, g) = split(of(run), classes);
        let shift = check.shift_of(auc_with_error(&c, &g).auc, of);
        ranked(name.into(), feature, (&c, &g), Some(shift), seed)
    };
    let force_max = score("contact force P_max", &Peak, |r| &r.force_max, seed ^ 1);
    let contact_time = score("contact time t_c", &Duration, |r| &r.contact_time, seed ^ 2);
    (force_max, contact_time)
}

/// The separability of every feature of every channel of a run beside the same impacts' on
/// half the modes.
pub struct Separation<'a> {
    run: &'a ConditionRun,
    infos: &'a [ChannelInfo],
    seed: u64,
    /// Every entry's shift from N/2 to N modes, channel-major.
    pub shifts: Vec<Shift>,
    /// Every channel's every feature, channel-major.
    pub all: Vec<Separability>,
    /// The same, most separating first (ties to the earlier channel).
    pub order: Vec<Separability>,
    /// The most separating entry whose AUC the modal truncation moves by less than its
    /// sampling error or the resolution ([`resolved`]).
    pub converged: Option<Separability>,
    /// The most separating entry at a sensor (not a corner).
    pub best_sensor: Option<Separability>,
}

impl<'a> Separation<'a> {
    /// The separabilities of `run` (its channels `infos`) and their shifts from N/2 to N
    /// modes (`check`); bootstrap streams derive from `seed`.
    pub fn new(run: &'a ConditionRun, check: &Truncation, infos: &'a [ChannelInfo], seed: u64) -> Self {
        let all = separabilities(&run.table);
        let shifts = check.shifts(&all);
        let mut order = all.clone();
        order.sort_by(|a, b| b.auc.separability().total_cmp(&a.auc.separability()).then(a.channel.cmp(&b.channel)));
        let shift = |s: &Separability| shifts[s.channel * FEATURES.len() + s.feature.index()].change;
        let converged = order.iter().find(|s| resolved(shift(s), s.auc.standard_error)).copied();
        let sensor_channels: Vec<usize> = (0..infos.len()).filter(|&c| infos[c].sensor.is_some()).collect();
        let best_sensor = if sensor_channels.is_empty() { None } else { best(&all, &sensor_channels) };
        Self { run, infos, seed, shifts, all, order, converged, best_sensor }
    }

    /// The reference feature of the variability study: the most separating one the modal
    /// truncation does not move, else the best sensor's.
    pub fn reference(&self) -> Option<Separability> {
        self.converged.or(self.best_sensor)
    }

    /// `s` scored with its interval (the `k`-th bootstrap stream) and its change from N/2 modes.
    pub fn ranked(&self, s: &Separability, k: usize) -> Ranked {
        let (c, g) = self.run.table.split(s.channel, s.feature);
        let shift = self.shifts[s.channel * FEATURES.len() + s.feature.index()];
        ranked(self.infos[s.channel].label(), s.feature, (&c, &g), Some(shift), self.seed.wrapping_add(k as u64))
    }

    /// The [`TOP`] most separating entries, scored.
    pub fn ranking(&self) -> Vec<Ranked> {
        self.order.iter().take(TOP).enumerate().map(|(k, s)| self.ranked(s, k)).collect()
    }

    /// The best sensor's point (x, z), mm, and its best feature, scored.
    pub fn best_sensor_ranked(&self) -> Option<((f64, f64), Ranked)> {
        self.best_sensor.map(|s| {
            let at = self.infos[s.channel].at;
            ((at.0 * 1e3, at.1 * 1e3), self.ranked(&s, TOP + 1))
        })
    }

    /// The most separating entry the modal truncation does not move, scored.
    pub fn converged_ranked(&self) -> Option<Ranked> {
        self.converged.map(|s| self.ranked(&s, TOP + 2))
    }

    /// The variability study's reference feature, scored.
    pub fn reference_ranked(&self) -> Option<Ranked> {
        self.reference().map(|s| self.ranked(&s, TOP + 3))
    }

    /// The most separating feature's values by class, for its histogram.
    pub fn best_values(&self) -> Option<ClassValues> {
        let top = self.order.first()?;
        let (coal, gangue) = self.run.table.split(top.channel, top.feature);
        let info = &self.infos[top.channel];
        Some(ClassValues {
            label: format!("{} {} ({})", info.label(), top.feature.name(), top.feature.unit(info.unit)),
            coal,
            gangue,
            scale: top.feature.is_scale(),
        })
    }
}
