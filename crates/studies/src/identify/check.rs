//! The check of the modal truncation: impacts of the main run struck again on the model with
//! half its modes, and the change of every AUC between the two.
//!
//! On every impact (`signals.truncation_check_fraction` = 1) the change is the ensemble's own
//! and has no sampling error; the coverage study then asks how well a stratified subsample
//! of a tenth, a quarter or half of each family would have stood for it
//! (`identify::subsample`): how often its 95 % interval held the whole ensemble's change, how
//! far it missed, and how often the check's verdict on the entries the ranking shows came out
//! the same. On a subsample (fraction below 1) only those impacts are struck again: each change
//! is the subsample's, with DeLong's paired error times the finite population correction.

use super::ensemble::half_modes;
use super::resolved;
use crate::progress::Progress;
use crate::Failure;
use coupled::identification::{ConditionRun, Impacts};
use identify::features::FEATURES;
use identify::placement::Separability;
use identify::subsample::{column_changes, population_correction, sampled_changes, stratified, Coverage, Sampled};
use identify::Study;
use scene::{Scene, SupportSet};
use serde::Serialize;
use std::borrow::Cow;

/// The fractions whose subsamples the coverage study draws.
pub const COVERAGE_FRACTIONS: [f64; 3] = [0.1, 0.25, 0.5];
/// Subsamples drawn for each fraction.
pub const COVERAGE_REPEATS: usize = 20;
/// The coverage study's subsamples, apart from every other stream of the set's seed.
const COVERAGE_KEY: u64 = 500;
/// The check's own subsample, apart from the coverage study's.
const SAMPLE_KEY: u64 = 600;

/// The seed of the `index`-th support set's bootstrap, fold and subsample streams, apart
/// from the other sets' (`ensemble_seed` is the scene's).
pub fn set_seed(ensemble_seed: u64, index: usize) -> u64 {
    ensemble_seed ^ (index as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15)
}

/// The impacts the check strikes again on the support set of seed `seed` ([`set_seed`]):
/// None for all of them (a `fraction` of 1), else the stratified subsample of `fraction` of
/// each family of `counts`.
pub fn checked_impacts(fraction: f64, counts: &[usize], seed: u64) -> Option<Vec<usize>> {
    (fraction < 1.0).then(|| stratified(counts, fraction, seed ^ SAMPLE_KEY, 0))
}

/// The change of one AUC from N/2 to N modes, with its error as an estimate of the whole
/// ensemble's change (None: measured on every impact, no sampling error).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shift {
    /// AUC(N) − AUC(N/2).
    pub change: f64,
    /// Its standard error, on a subsample.
    pub error: Option<f64>,
}

/// The half-mode run of one support set and which of the main run's impacts it struck.
pub struct Truncation {
    /// The main run's impacts struck again (None: every one).
    pub rows: Option<Vec<usize>>,
    /// Those impacts on N/2 modes.
    pub half: ConditionRun,
    /// The ensemble's size.
    population: usize,
}

impl Truncation {
    /// The impacts the scene's `signals.truncation_check_fraction` selects
    /// ([`checked_impacts`] of `seed`), struck on the model of `set` with half its modes at
    /// `sensors`.
    pub fn run(
        scene: &Scene,
        study: &Study,
        (set, sensors): (&SupportSet, &[(f64, f64)]),
        seed: u64,
        progress: &dyn Progress,
    ) -> Result<Self, Failure> {
        let counts: Vec<usize> = study.ensemble.families.iter().map(|f| f.count).collect();
        let rows = checked_impacts(scene.signals.truncation_check, &counts, seed);
        let impacts = rows.as_deref().map_or(Impacts::All, Impacts::Only);
        let half = half_modes(scene, (study, impacts), set, sensors, progress)?;
        Ok(Self { rows, half, population: study.ensemble.len() })
    }

    /// The main run's impacts that were struck again: all of `main`, or its subsample.
    pub fn main<'a>(&self, main: &'a ConditionRun) -> Cow<'a, ConditionRun> {
        match &self.rows {
            None => Cow::Borrowed(main),
            Some(rows) => Cow::Owned(main.select(rows)),
        }
    }

    /// The shift of `auc` (the main run's AUC of a quantity) given the same quantity's AUC on
    /// the checked impacts at N modes (`checked`) and at N/2 (`half`), with the paired
    /// `error` on a subsample.
    fn shift(&self, auc: f64, (checked, half): (f64, f64), error: f64) -> Shift {
        match self.rows {
            None => Shift { change: auc - half, error: None },
            Some(_) => Shift { change: checked - half, error: Some(error) },
        }
    }

    /// The shift of every entry of `all` (the main run's separabilities, channel-major).
    pub fn shifts(&self, main: &ConditionRun, all: &[Separability]) -> Vec<Shift> {
        let half = identify::placement::separabilities(&self.half.table);
        match &self.rows {
            None => all.iter().zip(&half).map(|(s, h)| self.shift(s.auc.auc, (s.auc.auc, h.auc.auc), 0.0)).collect(),
            Some(_) => {
                let changes = column_changes(&self.half.table, &self.main(main).table, self.population, None);
                changes.iter().map(|&(change, error)| Shift { change, error: Some(error) }).collect()
            }
        }
    }

    /// The shift of a per-impact quantity of the runs (`of` picks it) whose main-run AUC is
    /// `auc`.
    pub fn shift_of(&self, main: &ConditionRun, auc: f64, of: impl Fn(&ConditionRun) -> &[f64]) -> Shift {
        let checked = self.main(main);
        let split = |run: &ConditionRun| super::separability::split(of(run), run.table.classes());
        let (cc, cg) = split(&checked);
        let (hc, hg) = split(&self.half);
        let (change, se) = identify::roc::paired_difference((&hc, &hg), (&cc, &cg));
        let correction = population_correction(checked.table.len(), self.population);
        let half = identify::roc::auc_with_error(&hc, &hg).auc;
        self.shift(auc, (half + change, half), se * correction)
    }

    /// How well subsamples of [`COVERAGE_FRACTIONS`] of `counts` would have stood for this
    /// check on every impact, whose shifts are `shifts` (every entry's, channel-major) and
    /// whose ranking shows `top`, over the columns of the `stated` channels (the named
    /// sensors' and the supports') and of `top`; none if the check itself ran on a
    /// subsample.
    pub fn coverage(
        &self,
        main: &ConditionRun,
        (counts, stated): (&[usize], &[usize]),
        (top, shifts): (&[Separability], &[Shift]),
        seed: u64,
    ) -> Vec<SubsampleCheck> {
        if self.rows.is_some() {
            return Vec::new();
        }
        let column = |s: &Separability| s.channel * FEATURES.len() + s.feature.index();
        let mut columns: Vec<usize> =
            stated.iter().flat_map(|c| c * FEATURES.len()..(c + 1) * FEATURES.len()).collect();
        columns.extend(top.iter().map(column));
        columns.sort_unstable();
        columns.dedup();
        let tables = (&self.half.table, &main.table);
        let whole = column_changes(tables.0, tables.1, self.population, Some(&columns));
        let top: Vec<(usize, f64, bool)> = (top.iter())
            .map(|s| {
                let at = columns.binary_search(&column(s)).unwrap_or_default();
                let se = s.auc.standard_error;
                (at, se, resolved(shifts[column(s)].change, se))
            })
            .collect();
        COVERAGE_FRACTIONS
            .iter()
            .map(|&fraction| {
                let key = (COVERAGE_REPEATS, seed ^ COVERAGE_KEY);
                let samples = sampled_changes(tables, (counts, Some(&columns)), fraction, key);
                SubsampleCheck {
                    coverage: Coverage::of(&whole, &samples, fraction, super::AUC_RESOLUTION),
                    same_verdict: same_verdicts(&samples, &top),
                }
            })
            .collect()
    }
}

/// The share of (subsample, entry of `top`) pairs whose verdict (the truncation moves the
/// AUC by less than its error or the resolution, [`resolved`]) is the whole ensemble's; each
/// entry of `top` is its position among the samples' columns, its AUC's standard error and
/// the whole ensemble's verdict.
fn same_verdicts(samples: &[Sampled], top: &[(usize, f64, bool)]) -> f64 {
    let (mut same, mut all) = (0usize, 0usize);
    for sample in samples {
        for &(at, se, whole) in top {
            same += usize::from(resolved(sample.changes[at].0, se) == whole);
            all += 1;
        }
    }
    same as f64 / all.max(1) as f64
}

/// How well subsamples of one fraction stood for the check on every impact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SubsampleCheck {
    /// Their coverage of every entry's change.
    pub coverage: Coverage,
    /// The share of subsamples and ranked entries whose verdict on the truncation was the
    /// whole ensemble's.
    pub same_verdict: f64,
}
