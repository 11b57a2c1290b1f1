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
use super::separability::Separation;
use super::{resolved, TruncationCheck, TOP};
use crate::progress::Progress;
use crate::Failure;
use coupled::identification::{ConditionRun, Impacts};
use identify::features::FEATURES;
use identify::placement::Separability;
use identify::subsample::{column_changes, population_correction, sampled_changes, stratified, Coverage, Sampled};
use identify::Study;
use scene::{Scene, SupportSet};
use serde::Serialize;

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
/// the stratified subsample of `fraction` of each family of `counts`, or None where that is
/// every impact.
pub fn checked_impacts(fraction: f64, counts: &[usize], seed: u64) -> Option<Vec<usize>> {
    let rows = stratified(counts, fraction, seed ^ SAMPLE_KEY, 0);
    (rows.len() < counts.iter().sum()).then_some(rows)
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
    /// Those impacts of the main run, when a subsample.
    checked: Option<ConditionRun>,
    /// The scene's share.
    fraction: f64,
    /// Each family's impacts in the ensemble.
    counts: Vec<usize>,
}

impl Truncation {
    /// The impacts of `main` (the set's main run) that the scene's
    /// `signals.truncation_check_fraction` selects ([`checked_impacts`] of `seed`), struck on
    /// the model of `set` with half its modes at `sensors`.
    pub fn run(
        scene: &Scene,
        (study, main): (&Study, &ConditionRun),
        (set, sensors): (&SupportSet, &[(f64, f64)]),
        seed: u64,
        progress: &dyn Progress,
    ) -> Result<Self, Failure> {
        let counts: Vec<usize> = study.ensemble.families.iter().map(|f| f.count).collect();
        let fraction = scene.signals.truncation_check;
        let rows = checked_impacts(fraction, &counts, seed);
        let impacts = rows.as_deref().map_or(Impacts::All, Impacts::Only);
        let half = half_modes(scene, (study, impacts), set, sensors, progress)?;
        let checked = rows.as_deref().map(|r| main.select(r));
        Ok(Self { rows, half, checked, fraction, counts })
    }

    /// The main run's impacts that were struck again: all of `main`, or its subsample.
    pub fn main<'a>(&'a self, main: &'a ConditionRun) -> &'a ConditionRun {
        self.checked.as_ref().unwrap_or(main)
    }

    /// Whether the check struck only some of the impacts again.
    pub fn sampled(&self) -> bool {
        self.rows.is_some()
    }

    /// √(1 − n/N) for the impacts struck again ([`population_correction`]).
    fn correction(&self) -> f64 {
        population_correction(self.half.table.len(), self.counts.iter().sum())
    }

    /// The shift of every entry of `all` (the main run's separabilities, channel-major): on
    /// every impact the difference of the two runs' AUCs, on a subsample the subsample's
    /// paired difference with its error.
    pub fn shifts(&self, all: &[Separability]) -> Vec<Shift> {
        if let Some(checked) = &self.checked {
            let changes = column_changes(&self.half.table, &checked.table, self.counts.iter().sum(), None);
            return changes.iter().map(|&(change, error)| Shift { change, error: Some(error) }).collect();
        }
        let half = identify::placement::separabilities(&self.half.table);
        all.iter().zip(&half).map(|(s, h)| Shift { change: s.auc.auc - h.auc.auc, error: None }).collect()
    }

    /// The shift of a per-impact quantity of the runs (`of` picks it) whose main-run AUC is
    /// `auc`.
    pub fn shift_of(&self, auc: f64, of: impl Fn(&ConditionRun) -> &[f64]) -> Shift {
        let split = |run: &ConditionRun| super::separability::split(of(run), run.table.classes());
        let (hc, hg) = split(&self.half);
        match &self.checked {
            None => Shift { change: auc - identify::roc::auc_with_error(&hc, &hg).auc, error: None },
            Some(checked) => {
                let (cc, cg) = split(checked);
                let (change, se) = identify::roc::paired_difference((&hc, &hg), (&cc, &cg));
                Shift { change, error: Some(se * self.correction()) }
            }
        }
    }

    /// What the check struck again and, on every impact, how well subsamples of
    /// [`COVERAGE_FRACTIONS`] would have stood for it over the columns of the `stated`
    /// channels of `main` (the named sensors' and the supports') and of the [`TOP`] entries
    /// of `sep`'s ranking.
    pub fn summary(
        &self,
        (main, stated): (&ConditionRun, &[usize]),
        sep: &Separation<'_>,
        seed: u64,
    ) -> TruncationCheck {
        let top: Vec<Separability> = sep.order.iter().take(TOP).copied().collect();
        let coverage = if self.sampled() { Vec::new() } else { self.coverage(main, stated, (&top, &sep.shifts), seed) };
        TruncationCheck {
            impacts: self.half.table.len(),
            of: main.table.len(),
            fraction: self.fraction,
            sampled: self.sampled(),
            coverage,
        }
    }

    /// The coverage study of [`Truncation::summary`].
    fn coverage(
        &self,
        main: &ConditionRun,
        stated: &[usize],
        (top, shifts): (&[Separability], &[Shift]),
        seed: u64,
    ) -> Vec<SubsampleCheck> {
        let column = |s: &Separability| s.channel * FEATURES.len() + s.feature.index();
        let mut columns: Vec<usize> =
            stated.iter().flat_map(|c| c * FEATURES.len()..(c + 1) * FEATURES.len()).collect();
        columns.extend(top.iter().map(column));
        columns.sort_unstable();
        columns.dedup();
        let whole: Vec<(f64, f64)> = columns.iter().map(|&c| (shifts[c].change, 0.0)).collect();
        let top: Vec<(usize, f64, bool)> = (top.iter())
            .map(|s| {
                let at = columns.binary_search(&column(s)).expect("every ranked entry's column is compared");
                let se = s.auc.standard_error;
                (at, se, resolved(shifts[column(s)].change, se))
            })
            .collect();
        let tables = (&self.half.table, &main.table);
        COVERAGE_FRACTIONS
            .iter()
            .map(|&fraction| {
                let key = (COVERAGE_REPEATS, seed ^ COVERAGE_KEY);
                let samples = sampled_changes(tables, (&self.counts, Some(&columns)), fraction, key);
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
