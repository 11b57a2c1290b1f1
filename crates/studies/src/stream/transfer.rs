//! What a detector trained on one condition scores on another, without refitting: a detector
//! on the sensors' channels fitted on one support set's main run, scored on another support
//! set's main run (the matrix), and on its own support set with the chain's background scaled,
//! at other arrival rates, with every lump's radius scaled (another size law), under other
//! contact laws and on the plate made thicker or thinner. The conditions record the same
//! streams (the same lumps on another support set or another plate, under more noise,
//! larger, or striking under another law; at another rate each stream draws the same lumps, arriving sooner or later), so the carried detector too is fitted and scored by the time
//! blocks: fitted on the training blocks under one condition, it scores the held-out block
//! under the other. With one block per stream (leave-one-stream-out, as the shipped scene)
//! no lump it was fitted on is in a window it scores; with blocks inside a stream, a rate
//! shift can move a lump's draw from a training block into the scored one. Beside each,
//! the matched detector: the same channels cross-validated on the test condition itself, so
//! that the loss is the shift's alone. The supports' channels are left out: their kinds
//! differ between support sets (a spring's force, a fixed corner's reaction).

use super::score::Windows;
use super::Score;
use crate::Failure;
use identify::detector::scale_flags;
use serde::Serialize;

/// One support set's sensor-channel rows under each condition it was run at, and its windows.
pub(super) struct Shifted {
    /// The support set.
    pub name: String,
    /// Sensor channels.
    pub channels: usize,
    /// The main run's rows (the scene's rate, the stated chain).
    pub main: Vec<Vec<f64>>,
    /// The other conditions: (what changed, rows).
    pub others: Vec<super::run::Condition>,
    /// The windows, labels and blocks (the same time grid under every condition).
    pub windows: Windows,
}

/// A detector trained on one condition and applied to another.
#[derive(Debug, Clone, Serialize)]
pub struct TransferPoint {
    /// Trained on: the support set's main run.
    pub trained_on: String,
    /// Applied to: a support set, and what differs from its main run (empty: nothing).
    pub tested_on: String,
    /// See `tested_on`.
    pub shift: String,
    /// The carried detector's AUC over the test condition's scored windows, with the
    /// block-bootstrap interval, delay and false alarms at the alarm probability.
    pub transferred: Score,
    /// The matched detector's, cross-validated on the test condition.
    pub matched: Score,
}

impl TransferPoint {
    /// How much AUC the shift costs: matched less transferred.
    pub fn loss(&self) -> f64 {
        self.matched.auc - self.transferred.auc
    }
}

/// Every transfer of the study: each support set to every other (main runs), and each to its
/// own other conditions.
pub(super) fn transfers(sets: &[Shifted]) -> Result<Vec<TransferPoint>, Failure> {
    let mut out = Vec::new();
    for train in sets {
        if train.channels == 0 {
            continue;
        }
        let scale = scale_flags(train.channels);
        for test in sets.iter().filter(|t| t.name != train.name && t.channels == train.channels) {
            out.push(point(train, test, "", &test.main, &scale)?);
        }
        for (shift, rows) in &train.others {
            out.push(point(train, train, shift, rows, &scale)?);
        }
    }
    Ok(out)
}

/// The detector carried from `train`'s main run to `rows` of `test` under `shift`.
fn point(
    train: &Shifted,
    test: &Shifted,
    shift: &str,
    rows: &[Vec<f64>],
    scale: &[bool],
) -> Result<TransferPoint, Failure> {
    let group = "sensors";
    let transferred = test.windows.carried(group, &train.main, rows, scale)?;
    let matched = test.windows.score(group, rows, scale)?.0;
    Ok(TransferPoint {
        trained_on: train.name.clone(),
        tested_on: test.name.clone(),
        shift: shift.to_string(),
        transferred,
        matched,
    })
}
