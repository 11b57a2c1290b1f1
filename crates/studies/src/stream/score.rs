//! A detector's score on a stream's windows: its out-of-fold AUC over windows with a
//! block-bootstrap interval, and its operating answer (delay, false alarms per hour).
//!
//! **Interval.** Overlapping windows share lumps and samples, so their scores are not
//! independent and DeLong's error (which assumes they are) would be too narrow. The interval
//! resamples whole time blocks (the cross-validation's test blocks) with replacement, the
//! moving-block bootstrap's answer to dependence (Künsch 1989, *Ann. Statist.* 17:1217),
//! with blocks far longer than the windows' overlap; blocks that are mostly one class are
//! resampled apart from those mostly the other, so that every resample scores both.

use super::Baseline;
use crate::Failure;
use identify::classify::FitError;
use identify::detect::{operate, out_of_fold, out_of_fold_across, Fold, Window};
use identify::ensemble::{impact_stream, open_uniform};
use identify::roc::auc;
use serde::Serialize;

/// Resamples of the block bootstrap.
const RESAMPLES: usize = 400;

/// A detector on one group of channels.
#[derive(Debug, Clone, Serialize)]
pub struct Score {
    /// Which channels it reads.
    pub group: String,
    /// Its out-of-fold AUC over the scored windows (gangue-rich against the rest).
    pub auc: f64,
    /// The 95 % block-bootstrap interval.
    pub interval: (f64, f64),
    /// Windows scored (those straddling a block edge are not).
    pub scored_windows: usize,
    /// Per stream: delay from the onset to the first alarm after it, s.
    pub delays_s: Vec<Option<f64>>,
    /// Their median over the streams that detected.
    pub median_delay_s: Option<f64>,
    /// Alarm episodes before the onset.
    pub false_alarms: usize,
    /// Per hour of windows before the onset.
    pub false_alarms_per_hour: Option<f64>,
}

/// The windows of a run and what scores them: labels, folds, onsets.
pub(super) struct Windows {
    pub windows: Vec<Window>,
    pub labels: Vec<bool>,
    pub folds: Vec<Fold>,
    /// Each stream's start on the common time axis, s.
    pub offsets: Vec<f64>,
    pub onset: f64,
    pub alarm: f64,
    pub seed: u64,
}

impl Windows {
    /// Whether the cross-validation can score: every block's training windows hold both
    /// classes, and the scored windows hold both.
    pub fn check(&self) -> Result<(), Failure> {
        let both = |idx: &mut dyn Iterator<Item = &usize>| {
            let (mut rich, mut poor) = (false, false);
            for &i in idx {
                (rich, poor) = (rich || self.labels[i], poor || !self.labels[i]);
            }
            rich && poor
        };
        let blocks = self.folds.len();
        for (b, f) in self.folds.iter().enumerate() {
            if !both(&mut f.train.iter()) {
                return Err(format!(
                    "stream.blocks: block {} of {blocks} leaves training windows of one class only (gangue-rich or not); use as many blocks as streams (leave-one-stream-out), or more streams",
                    b + 1
                )
                .into());
            }
        }
        if !both(&mut self.folds.iter().flat_map(|f| f.test.iter())) {
            return Err("stream.blocks: the scored windows hold one class only; use as many blocks as streams".into());
        }
        Ok(())
    }

    /// The detector on `rows` (one per window; `scale` per column), named `group`, and its
    /// out-of-fold probabilities.
    pub fn score(&self, group: &str, rows: &[Vec<f64>], scale: &[bool]) -> Result<(Score, Vec<Option<f64>>), Failure> {
        let probabilities = out_of_fold(rows, &self.labels, scale, &self.folds).map_err(|e: FitError| e.to_string())?;
        let score = self.scored(group, &probabilities);
        Ok((score, probabilities))
    }

    /// The detector fitted, fold by fold, on `fitted` (the windows under one condition) and
    /// scoring `scored` (the same windows under another), as [`Windows::score`] scores.
    pub fn carried(
        &self,
        group: &str,
        fitted: &[Vec<f64>],
        scored: &[Vec<f64>],
        scale: &[bool],
    ) -> Result<Score, Failure> {
        let probabilities = out_of_fold_across(fitted, scored, &self.labels, scale, &self.folds)
            .map_err(|e: FitError| e.to_string())?;
        Ok(self.scored(group, &probabilities))
    }

    /// The score of out-of-fold `probabilities` (None: not scored).
    fn scored(&self, group: &str, probabilities: &[Option<f64>]) -> Score {
        let values: Vec<f64> = probabilities.iter().map(|p| p.unwrap_or(f64::NAN)).collect();
        let (a, interval) = self.auc_and_interval(&values, false);
        let op = operate(&self.windows, probabilities, self.alarm, self.onset, &self.offsets);
        Score {
            group: group.to_string(),
            auc: a,
            interval,
            scored_windows: probabilities.iter().flatten().count(),
            median_delay_s: op.median_delay(),
            false_alarms_per_hour: op.false_alarms_per_hour(),
            false_alarms: op.false_alarms,
            delays_s: op.delays,
        }
    }

    /// A baseline: `values` (one per window, NaN where it has none) as the score, oriented.
    pub fn baseline(&self, quantity: &'static str, values: &[f64]) -> Baseline {
        let (auc, interval) = self.auc_and_interval(values, true);
        Baseline { quantity, auc, interval }
    }

    /// The AUC of `values` over the scored windows (NaN: left out) and its block-bootstrap
    /// interval; `oriented`: as max(A, 1 - A), the interval turned with it.
    fn auc_and_interval(&self, values: &[f64], oriented: bool) -> (f64, (f64, f64)) {
        let (a, resampled) = self.bootstrap(|i| values[i].is_finite(), |pick| self.auc_of(values, pick));
        let turn = |x: f64| if oriented && a < 0.5 { 1.0 - x } else { x };
        (turn(a), quantiles(resampled.into_iter().map(turn).collect()))
    }

    /// The gain in AUC from the out-of-fold probabilities `before` to `after` (None: not
    /// scored) over the windows both score, with the paired block-bootstrap interval: both AUCs
    /// on the same resampled blocks, so that what the windows share cancels in the difference.
    pub fn paired_gain(&self, before: &[Option<f64>], after: &[Option<f64>]) -> (f64, (f64, f64)) {
        let value = |p: &[Option<f64>], i: usize| p[i].unwrap_or(f64::NAN);
        let b: Vec<f64> = (0..before.len()).map(|i| value(before, i)).collect();
        let a: Vec<f64> = (0..after.len()).map(|i| value(after, i)).collect();
        let (gain, resampled) = self
            .bootstrap(|i| a[i].is_finite() && b[i].is_finite(), |pick| self.auc_of(&a, pick) - self.auc_of(&b, pick));
        (gain, quantiles(resampled))
    }

    /// `stat` over the scored windows where `usable`, and over [`RESAMPLES`] resamples of
    /// whole blocks with replacement: blocks by their majority class, each kind resampled to
    /// its own count, so that every resample has both classes (a block is mostly one phase of
    /// the stream).
    fn bootstrap(&self, usable: impl Fn(usize) -> bool, stat: impl Fn(&[usize]) -> f64) -> (f64, Vec<f64>) {
        let blocks: Vec<Vec<usize>> =
            self.folds.iter().map(|f| f.test.iter().copied().filter(|&i| usable(i)).collect()).collect();
        let all: Vec<usize> = blocks.iter().flatten().copied().collect();
        let mostly_gangue = |b: &Vec<usize>| 2 * b.iter().filter(|&&i| self.labels[i]).count() > b.len();
        let (gangue, coal): (Vec<&Vec<usize>>, Vec<&Vec<usize>>) =
            blocks.iter().filter(|b| !b.is_empty()).partition(|b| mostly_gangue(b));
        let mut rng = impact_stream(self.seed, 0);
        let mut draw = |kind: &[&Vec<usize>], pick: &mut Vec<usize>| {
            for _ in 0..kind.len() {
                let b = ((open_uniform(&mut rng) * kind.len() as f64) as usize).min(kind.len() - 1);
                pick.extend_from_slice(kind[b]);
            }
        };
        let resampled = (0..RESAMPLES)
            .map(|_| {
                let mut pick = Vec::new();
                draw(&coal, &mut pick);
                draw(&gangue, &mut pick);
                stat(&pick)
            })
            .collect();
        (stat(&all), resampled)
    }

    /// The AUC of `values` over the windows `pick` (½ without both classes).
    fn auc_of(&self, values: &[f64], pick: &[usize]) -> f64 {
        let (mut coal, mut gangue) = (Vec::new(), Vec::new());
        for &i in pick {
            if self.labels[i] {
                gangue.push(values[i]);
            } else {
                coal.push(values[i]);
            }
        }
        if coal.is_empty() || gangue.is_empty() {
            return 0.5;
        }
        auc(&coal, &gangue)
    }
}

/// The 95 % interval of bootstrap values: their 2.5 % and 97.5 % order statistics.
fn quantiles(mut resampled: Vec<f64>) -> (f64, f64) {
    resampled.sort_by(f64::total_cmp);
    let q = |p: f64| resampled[((p * resampled.len() as f64) as usize).min(resampled.len() - 1)];
    (q(0.025), q(0.975))
}

#[cfg(test)]
mod tests {
    use super::*;
    use identify::detect::{time_block_folds, Window};

    /// Forty disjoint windows of one stream, coal for the first half and gangue after, in
    /// four time blocks.
    fn windows() -> Windows {
        let all: Vec<Window> = (0..40).map(|i| Window { stream: 0, start: i as f64, end: i as f64 + 1.0 }).collect();
        let labels = (0..40).map(|i| i >= 20).collect();
        let folds = time_block_folds(&all, 4);
        Windows { windows: all, labels, folds, offsets: vec![0.0], onset: 20.0, alarm: 0.5, seed: 5 }
    }

    /// Scores `shift`·label plus a shared uniform draw per window (a fixed sequence).
    fn scores(shift: f64) -> Vec<Option<f64>> {
        (0..40u64).map(|i| Some(((i * 7919) % 97) as f64 / 97.0 + if i >= 20 { shift } else { 0.0 })).collect()
    }

    /// The paired gain of a score over itself is nothing, on every resample; from a score that
    /// cannot rank (a constant: 0.5 on every resample) to one that ranks perfectly (1 on every
    /// resample, which always holds both classes) it is 0.5, on every resample.
    #[test]
    fn a_paired_gain_is_exact_where_both_scores_are() {
        let w = windows();
        let s = scores(0.3);
        assert_eq!(w.paired_gain(&s, &s), (0.0, (0.0, 0.0)));
        let constant = vec![Some(0.5); 40];
        let perfect: Vec<Option<f64>> = (0..40).map(|i| Some(if i >= 20 { 1.0 } else { 0.0 })).collect();
        assert_eq!(w.paired_gain(&constant, &perfect), (0.5, (0.5, 0.5)));
    }

    /// Two scores that share most of their noise: their AUCs move together from resample to
    /// resample, so the paired interval of the difference is narrower than either score's own
    /// (Var(A - B) = Var A + Var B - 2 Cov(A, B)); its gain is the difference of the AUCs.
    #[test]
    fn pairing_cancels_what_the_scores_share() {
        let w = windows();
        let (before, after) = (scores(0.2), scores(0.3));
        let (gain, (lo, hi)) = w.paired_gain(&before, &after);
        let value = |p: &[Option<f64>]| p.iter().map(|v| v.unwrap()).collect::<Vec<f64>>();
        let (a, (alo, ahi)) = w.auc_and_interval(&value(&after), false);
        let (b, (blo, bhi)) = w.auc_and_interval(&value(&before), false);
        assert!((gain - (a - b)).abs() < 1e-15 && lo <= gain && gain <= hi);
        assert!(hi - lo < (ahi - alo).min(bhi - blo), "paired {lo}..{hi}, after {alo}..{ahi}, before {blo}..{bhi}");
    }
}
