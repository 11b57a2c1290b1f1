//! Gangue detection over windows of a continuous caving stream, as a caving operator needs it:
//! is the stream now gangue-rich, how long after the change does the detector say so, and how
//! often does it say so wrongly.
//!
//! **Windows.** Sliding windows of length W every hop H over each stream, their features
//! those of one impact's ([`crate::features`]) computed on the window's samples. A window's
//! truth is its lumps (touching within it) and the profile's mean gangue share over it
//! ([`crate::stream::Profile::mean_share`]); it is *gangue-rich* when that mean share is at
//! least half-way from the share before the change to the share after it.
//!
//! **Cross-validation by time blocks.** Neighbouring windows overlap (H < W) and share lumps,
//! so shuffled folds would train on the test windows' own signal (Roberts et al. 2017,
//! *Ecography* 40:913, on blocking for dependent data). The streams' time axis is cut into
//! contiguous blocks; each block's windows are scored by the logistic model
//! ([`crate::classify::Logistic`]) fitted on the windows outside the block (a window
//! straddling a block's edge is left out of both), so no training window shares a sample
//! with a test window. With several streams laid end to end with gaps and one block per
//! stream, this is leave-one-stream-out and every window is scored.
//!
//! **Operating answer.** An alarm is raised at the end of every scored window whose
//! out-of-fold probability reaches the threshold (a window no fold scores is passed over).
//! The delay is the time from the onset of the change to the end of the first alarmed window
//! ending after it; a false alarm is an alarm episode (a run of alarmed windows) that starts
//! in a window ending before the onset, counted per hour of such windows.

use crate::classify::{FitError, Logistic, RIDGE};
use serde::Serialize;

/// A window [start, end), s on the streams' common time axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Window {
    /// Which stream it belongs to.
    pub stream: usize,
    /// Start, s.
    pub start: f64,
    /// End, s.
    pub end: f64,
}

impl Window {
    /// Whether the two windows share any time.
    pub fn overlaps(&self, other: &Window) -> bool {
        self.start < other.end && other.start < self.end
    }
}

/// The windows of length `length` every `hop` over a stream from `offset` to
/// `offset + duration` (the last window ends at or before the stream's end).
pub fn windows(stream: usize, offset: f64, duration: f64, length: f64, hop: f64) -> Vec<Window> {
    let mut out = Vec::new();
    let mut k = 0usize;
    loop {
        let start = k as f64 * hop;
        if start + length > duration + 1e-9 * duration {
            return out;
        }
        out.push(Window { stream, start: offset + start, end: offset + start + length });
        k += 1;
    }
}

/// One fold of the time-block cross-validation: windows to score and windows to fit on.
#[derive(Debug, Clone, PartialEq)]
pub struct Fold {
    /// Indices of the windows scored.
    pub test: Vec<usize>,
    /// Indices of the windows fitted on: none overlaps a test window.
    pub train: Vec<usize>,
}

/// `blocks` contiguous blocks of equal length over the span of `windows`: block b's test
/// windows lie wholly inside it; its training windows lie wholly outside it, so they overlap
/// no test window.
pub fn time_block_folds(windows: &[Window], blocks: usize) -> Vec<Fold> {
    let (Some(t0), Some(t1)) =
        (windows.iter().map(|w| w.start).min_by(f64::total_cmp), windows.iter().map(|w| w.end).max_by(f64::total_cmp))
    else {
        return Vec::new();
    };
    let blocks = blocks.max(1);
    let edge = |b: usize| t0 + (t1 - t0) * b as f64 / blocks as f64;
    (0..blocks)
        .map(|b| {
            let (lo, hi) = (edge(b), edge(b + 1));
            let test: Vec<usize> =
                (0..windows.len()).filter(|&i| windows[i].start >= lo && windows[i].end <= hi).collect();
            let train = (0..windows.len()).filter(|&i| windows[i].end <= lo || windows[i].start >= hi).collect();
            Fold { test, train }
        })
        .filter(|f| !f.test.is_empty())
        .collect()
}

/// The out-of-fold probability of every window (None: in no fold's test set, or its fold
/// had only one class to fit on), the model of each fold fitted on its training windows.
pub fn out_of_fold(
    rows: &[Vec<f64>],
    labels: &[bool],
    scale: &[bool],
    folds: &[Fold],
) -> Result<Vec<Option<f64>>, FitError> {
    out_of_fold_across(rows, rows, labels, scale, folds)
}

/// As [`out_of_fold`], each fold's model fitted on the training windows of `fitted` and
/// scoring the test windows of `scored`: the same windows recorded under two conditions (a
/// detector carried from one to the other, no window it scores sharing time with one it
/// was fitted on).
pub fn out_of_fold_across(
    fitted: &[Vec<f64>],
    scored: &[Vec<f64>],
    labels: &[bool],
    scale: &[bool],
    folds: &[Fold],
) -> Result<Vec<Option<f64>>, FitError> {
    if fitted.len() != labels.len() || scored.len() != labels.len() {
        return Err(FitError::Shape(format!(
            "{} rows fitted and {} scored for {} labels",
            fitted.len(),
            scored.len(),
            labels.len()
        )));
    }
    let mut scores = vec![None; scored.len()];
    for f in folds {
        let train_labels: Vec<bool> = f.train.iter().map(|&i| labels[i]).collect();
        if !(train_labels.contains(&true) && train_labels.contains(&false)) {
            continue;
        }
        let train_rows: Vec<Vec<f64>> = f.train.iter().map(|&i| fitted[i].clone()).collect();
        let model = Logistic::fit(&train_rows, &train_labels, scale, RIDGE)?;
        for &i in &f.test {
            scores[i] = Some(model.probability(&scored[i]));
        }
    }
    Ok(scores)
}

/// A detector's operating answer on the windows of one or more streams.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Operating {
    /// The probability at which it raises an alarm.
    pub threshold: f64,
    /// Per stream: the delay from the onset to the end of its first alarmed window ending
    /// after it, s (None: no alarm after the onset).
    pub delays: Vec<Option<f64>>,
    /// Alarm episodes starting before the onset, all streams together.
    pub false_alarms: usize,
    /// Hours of windows ending before the onset, all streams together.
    pub hours_before_onset: f64,
}

impl Operating {
    /// False alarms per hour (None without time before the onset).
    pub fn false_alarms_per_hour(&self) -> Option<f64> {
        (self.hours_before_onset > 0.0).then(|| self.false_alarms as f64 / self.hours_before_onset)
    }

    /// The median delay over the streams that detected, s.
    pub fn median_delay(&self) -> Option<f64> {
        let mut d: Vec<f64> = self.delays.iter().flatten().copied().collect();
        d.sort_by(f64::total_cmp);
        match d.len() {
            0 => None,
            n if n % 2 == 1 => Some(d[n / 2]),
            n => Some(0.5 * (d[n / 2 - 1] + d[n / 2])),
        }
    }
}

/// The operating answer at `threshold` of the scores of `windows` (in time order within each
/// of `streams` streams), the change starting `onset` seconds into each stream whose
/// windows start at `offsets[stream]`. Unscored windows are passed over.
pub fn operate(windows: &[Window], scores: &[Option<f64>], threshold: f64, onset: f64, offsets: &[f64]) -> Operating {
    let mut delays = vec![None; offsets.len()];
    let (mut false_alarms, mut before) = (0, 0.0);
    let mut last_alarm = vec![false; offsets.len()];
    let mut hop_before = vec![None::<f64>; offsets.len()];
    for (w, s) in windows.iter().zip(scores) {
        let r = w.stream;
        // A window nobody scored is no evidence either way: it neither alarms nor ends an
        // episode, and its time is not counted as watched.
        let Some(p) = s else { continue };
        let alarm = *p >= threshold;
        let end = w.end - offsets[r];
        if end <= onset {
            // The time a window adds is its hop (its end less the previous scored window's
            // end), at most its length.
            let length = w.end - w.start;
            before += (end - hop_before[r].unwrap_or(end - length)).min(length);
            hop_before[r] = Some(end);
            if alarm && !last_alarm[r] {
                false_alarms += 1;
            }
        } else if alarm && delays[r].is_none() {
            delays[r] = Some(end - onset);
        }
        last_alarm[r] = alarm;
    }
    Operating { threshold, delays, false_alarms, hours_before_onset: before / 3600.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whatever the windows and blocks, no training window shares time with a test window,
    /// every test window lies in one fold, and every window wholly inside a block is scored.
    #[test]
    fn time_blocks_never_train_on_an_overlapping_window() {
        for (length, hop, blocks, streams) in [(1.0, 0.25, 5, 1), (2.0, 0.5, 7, 3), (0.5, 0.5, 4, 2), (3.0, 0.1, 3, 1)]
        {
            let duration = 60.0;
            let all: Vec<Window> =
                (0..streams).flat_map(|s| windows(s, s as f64 * (duration + length), duration, length, hop)).collect();
            let folds = time_block_folds(&all, blocks);
            let mut seen = vec![0; all.len()];
            for f in &folds {
                for &t in &f.test {
                    seen[t] += 1;
                    for &r in &f.train {
                        assert!(!all[t].overlaps(&all[r]), "{:?} trains on {:?}", all[t], all[r]);
                    }
                }
                assert!(!f.train.is_empty());
            }
            assert!(seen.iter().all(|&s| s <= 1));
            // Only windows straddling a block edge go unscored: at most ⌈W/H⌉ per inner edge.
            let unscored = seen.iter().filter(|&&s| s == 0).count();
            assert!(unscored <= (blocks - 1) * (length / hop).ceil() as usize, "{unscored}");
        }
    }

    #[test]
    fn windows_tile_the_stream() {
        let w = windows(0, 10.0, 5.0, 1.0, 0.5);
        assert_eq!(w.len(), 9);
        assert_eq!((w[0].start, w[8].end), (10.0, 15.0));
    }

    /// Scores that step up two windows after the onset: the delay is the end of that window
    /// less the onset; one spurious alarm episode of two windows before it counts once.
    #[test]
    fn delay_and_false_alarms_by_hand() {
        let w = windows(0, 0.0, 20.0, 1.0, 1.0);
        let onset = 10.0;
        let mut scores: Vec<Option<f64>> =
            w.iter().map(|w| Some(if w.start >= onset + 2.0 { 0.9 } else { 0.1 })).collect();
        scores[3] = Some(0.8);
        scores[4] = Some(0.7);
        let op = operate(&w, &scores, 0.5, onset, &[0.0]);
        assert_eq!(op.delays, vec![Some(3.0)]);
        assert_eq!(op.false_alarms, 1);
        assert!((op.hours_before_onset - 10.0 / 3600.0).abs() < 1e-12);
        assert!((op.false_alarms_per_hour().unwrap() - 360.0).abs() < 1e-9);
    }

    /// An unscored window is passed over: it neither breaks an alarm episode nor counts as
    /// watched time.
    #[test]
    fn unscored_windows_are_passed_over() {
        let w = windows(0, 0.0, 20.0, 1.0, 1.0);
        let mut scores: Vec<Option<f64>> = w.iter().map(|w| Some(if w.start >= 12.0 { 0.9 } else { 0.1 })).collect();
        (scores[2], scores[3], scores[4]) = (Some(0.8), None, Some(0.8));
        let op = operate(&w, &scores, 0.5, 10.0, &[0.0]);
        assert_eq!(op.false_alarms, 1, "one episode across the unscored window");
        assert!((op.hours_before_onset - 9.0 / 3600.0).abs() < 1e-12);
        assert_eq!(op.delays, vec![Some(3.0)]);
    }

    /// A feature that separates the classes up to noise is learned across blocks: the
    /// out-of-fold probabilities rank gangue-rich windows above the others.
    #[test]
    fn out_of_fold_scores_learn_a_separating_feature() {
        let w = windows(0, 0.0, 100.0, 1.0, 0.5);
        let labels: Vec<bool> = w.iter().map(|w| w.start >= 50.0).collect();
        let rows: Vec<Vec<f64>> = w
            .iter()
            .enumerate()
            .map(|(i, w)| vec![if w.start >= 50.0 { 2.0 } else { 1.0 } + 0.3 * ((i * 7919 % 101) as f64 / 101.0 - 0.5)])
            .collect();
        // Blocks of 10 s: every block has one class, training spans both.
        let folds = time_block_folds(&w, 10);
        let s = out_of_fold(&rows, &labels, &[false], &folds).unwrap();
        let (mut c, mut g) = (vec![], vec![]);
        for (s, &l) in s.iter().zip(&labels) {
            if let Some(p) = s {
                if l {
                    g.push(*p)
                } else {
                    c.push(*p)
                }
            }
        }
        assert_eq!(crate::roc::auc(&c, &g), 1.0);
    }
}
