//! Where to put the sensor: the separability of every feature of every channel over an
//! ensemble, and the best sensor and feature.
//!
//! The ensemble's features are held as columns ([`FeatureTable`]): one value per impact for
//! each channel and feature, and each impact's class; the signals themselves are never
//! kept. Each column's AUC (coal against gangue, [`crate::roc`]) with DeLong's standard
//! error is one sort; a placement map is the column of one quantity and feature at every
//! candidate sensor point of a grid.

use crate::classify::{cross_validate, CrossValidated, FitError, FOLDS, RIDGE};
use crate::ensemble::Class;
use crate::features::{Feature, FEATURES};
use crate::roc::{auc_with_error, Auc};
use rayon::prelude::*;
use serde::Serialize;

/// The features of an ensemble, column by column.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FeatureTable {
    channels: usize,
    classes: Vec<Class>,
    /// Column channel·[`FEATURES`].len() + feature, one value per impact.
    values: Vec<Vec<f64>>,
}

impl FeatureTable {
    /// An empty table for `channels` channels.
    pub fn new(channels: usize) -> Self {
        Self { channels, classes: Vec::new(), values: vec![Vec::new(); channels * FEATURES.len()] }
    }

    /// Appends one impact: its class and the [`FEATURES`] of each channel, channel after
    /// channel (exactly `channels` × [`FEATURES`].len() values).
    pub fn push(&mut self, class: Class, features: &[f64]) {
        assert_eq!(features.len(), self.values.len(), "the registry's features of every channel");
        self.classes.push(class);
        for (column, &v) in self.values.iter_mut().zip(features) {
            column.push(v);
        }
    }

    /// Impacts held.
    pub fn len(&self) -> usize {
        self.classes.len()
    }

    /// Whether no impact is held.
    pub fn is_empty(&self) -> bool {
        self.classes.is_empty()
    }

    /// Channels per impact.
    pub fn channels(&self) -> usize {
        self.channels
    }

    /// The class of each impact.
    pub fn classes(&self) -> &[Class] {
        &self.classes
    }

    /// The values of one feature (of [`FEATURES`]) of one channel, one per impact.
    pub fn column(&self, channel: usize, feature: &dyn Feature) -> &[f64] {
        &self.values[channel * FEATURES.len() + feature.index()]
    }

    /// The column split by class: (coal, gangue).
    pub fn split(&self, channel: usize, feature: &dyn Feature) -> (Vec<f64>, Vec<f64>) {
        let col = self.column(channel, feature);
        let mut coal = Vec::new();
        let mut gangue = Vec::new();
        for (v, c) in col.iter().zip(&self.classes) {
            match c {
                Class::Coal => coal.push(*v),
                Class::Gangue => gangue.push(*v),
            }
        }
        (coal, gangue)
    }

    /// The impacts `rows` of the table, in that order.
    pub fn select(&self, rows: &[usize]) -> Self {
        Self {
            channels: self.channels,
            classes: rows.iter().map(|&i| self.classes[i]).collect(),
            values: self.values.iter().map(|column| rows.iter().map(|&i| column[i]).collect()).collect(),
        }
    }

    /// Bytes the values occupy (8 per impact, channel and feature, plus one per class).
    pub fn bytes(&self) -> usize {
        self.values.iter().map(|v| v.capacity() * 8).sum::<usize>() + self.classes.capacity()
    }
}

/// The separability of one feature of one channel.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Separability {
    /// The channel.
    pub channel: usize,
    /// The feature.
    pub feature: &'static dyn Feature,
    /// Its AUC with DeLong's standard error.
    pub auc: Auc,
}

/// The AUC of every feature of every channel, channel-major (columns in parallel; the
/// result does not depend on the number of threads).
pub fn separabilities(table: &FeatureTable) -> Vec<Separability> {
    (0..table.channels() * FEATURES.len())
        .into_par_iter()
        .map(|col| {
            let (channel, feature) = (col / FEATURES.len(), FEATURES[col % FEATURES.len()]);
            let (coal, gangue) = table.split(channel, feature);
            Separability { channel, feature, auc: auc_with_error(&coal, &gangue) }
        })
        .collect()
}

/// The most separating entry among those of `channels` (all if empty); ties go to the
/// earlier entry.
pub fn best(all: &[Separability], channels: &[usize]) -> Option<Separability> {
    all.iter().filter(|s| channels.is_empty() || channels.contains(&s.channel)).fold(
        None,
        |b: Option<Separability>, s| match b {
            Some(b) if b.auc.separability() >= s.auc.separability() => Some(b),
            _ => Some(*s),
        },
    )
}

/// The AUC of `feature` at each of `channels` (one per grid point): a placement map.
pub fn map(all: &[Separability], channels: &[usize], feature: &dyn Feature) -> Vec<Auc> {
    channels
        .iter()
        .map(|&c| {
            all.iter()
                .find(|s| s.channel == c && *s.feature == *feature)
                .map_or(Auc { auc: 0.5, standard_error: 0.0 }, |s| s.auc)
        })
        .collect()
}

/// The cross-validated accuracy of the logistic classifier on every feature of `channels`
/// together (e.g. all channels of one sensor), [`FOLDS`] folds, ridge [`RIDGE`].
pub fn classifier(table: &FeatureTable, channels: &[usize], seed: u64) -> Result<CrossValidated, FitError> {
    let (rows, scale) = crate::design::rows_of(table, channels);
    let labels: Vec<bool> = table.classes().iter().map(|c| *c == Class::Gangue).collect();
    cross_validate(&rows, &labels, &scale, RIDGE, FOLDS, seed)
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::features::Peak;

    /// One channel's features: `peak`, every other 1.
    fn f(peak: f64) -> Vec<f64> {
        FEATURES.iter().map(|f| if f.key() == "peak" { peak } else { 1.0 }).collect()
    }

    #[test]
    fn table_columns_and_best_channel() {
        // Channel 0 separates perfectly on its peak (gangue higher), channel 1 not at all.
        let mut t = FeatureTable::new(2);
        for i in 0..10 {
            t.push(Class::Coal, &[f(i as f64), f(1.0)].concat());
            t.push(Class::Gangue, &[f(100.0 + i as f64), f(1.0)].concat());
        }
        assert_eq!(t.len(), 20);
        assert_eq!(t.column(0, &Peak)[1], 100.0);
        let s = separabilities(&t);
        assert_eq!(s.len(), 2 * FEATURES.len());
        let b = best(&s, &[]).unwrap();
        assert_eq!((b.channel, b.feature.key(), b.auc.auc), (0, "peak", 1.0));
        let m = map(&s, &[0, 1], &Peak);
        assert_eq!((m[0].auc, m[1].auc), (1.0, 0.5));
        assert_eq!(best(&s, &[1]).unwrap().auc.auc, 0.5);
    }
}
