//! The area under the ROC curve of one feature, coal against gangue, with its uncertainty.
//!
//! AUC = P(Y > X) + ½P(Y = X) for X a coal value and Y a gangue value: the Mann-Whitney
//! statistic U over n₀n₁ (Mann & Whitney 1947; Bamber 1975), ties counted one half. 0.5 means
//! the feature does not separate the classes, 1 (or 0) that a threshold separates them
//! perfectly; the separability of a feature is max(AUC, 1 - AUC) with the direction stated.
//!
//! Uncertainty, two ways:
//! - DeLong's standard error (DeLong, DeLong & Clarke-Pearson, Biometrics 44 (1988) 837):
//!   Var = s₁²/n₁ + s₀²/n₀ with s₁², s₀² the sample variances of the placement values
//!   V(Y_i) = P(X < Y_i) + ½P(X = Y_i) and V(X_j) = P(Y > X_j) + ½P(Y = X_j). Cheap
//!   (one sort), for every cell of a placement map.
//! - A percentile bootstrap interval ([`bootstrap_interval`]): both classes resampled with
//!   replacement at their own sizes (stratified), the AUC of each resample, the 2.5 % and
//!   97.5 % quantiles of [`BOOTSTRAP_RESAMPLES`] resamples. Each resample is one O(n) sweep
//!   over the pooled values sorted once, with the resample's multiplicities as weights.

use crate::ensemble::{impact_stream, open_uniform};
use serde::Serialize;

/// Bootstrap resamples of [`bootstrap_interval`]: the percentile interval's end points are
/// then within about ±0.002 (in AUC) of their limit values for the ensembles here.
pub const BOOTSTRAP_RESAMPLES: usize = 2000;

/// The AUC of one feature with its uncertainty.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Auc {
    /// P(gangue > coal) + ½P(=).
    pub auc: f64,
    /// DeLong's standard error.
    pub standard_error: f64,
}

impl Auc {
    /// max(AUC, 1 - AUC): how well a threshold on the feature separates the classes, in
    /// whichever direction.
    pub fn separability(&self) -> f64 {
        self.auc.max(1.0 - self.auc)
    }

    /// Whether gangue reads higher than coal on this feature.
    pub fn gangue_higher(&self) -> bool {
        self.auc >= 0.5
    }
}

/// The pooled values sorted once, with their class (true: gangue).
fn pooled(coal: &[f64], gangue: &[f64]) -> Vec<(f64, bool)> {
    let mut all: Vec<(f64, bool)> = coal.iter().map(|&v| (v, false)).chain(gangue.iter().map(|&v| (v, true))).collect();
    all.sort_by(|a, b| a.0.total_cmp(&b.0));
    all
}

/// U/(n₀n₁) from the sorted pooled values with weights (multiplicities) `w` per entry.
fn weighted_auc(sorted: &[(f64, bool)], w: impl Fn(usize) -> f64) -> f64 {
    let (mut coal_below, mut u, mut n0, mut n1) = (0.0, 0.0, 0.0, 0.0);
    let mut i = 0;
    while i < sorted.len() {
        let mut j = i;
        let (mut c, mut g) = (0.0, 0.0);
        while j < sorted.len() && sorted[j].0 == sorted[i].0 {
            if sorted[j].1 {
                g += w(j);
            } else {
                c += w(j);
            }
            j += 1;
        }
        u += g * (coal_below + 0.5 * c);
        coal_below += c;
        n0 += c;
        n1 += g;
        i = j;
    }
    if n0 > 0.0 && n1 > 0.0 {
        u / (n0 * n1)
    } else {
        0.5
    }
}

/// The AUC of gangue against coal (0.5 if either class is empty).
pub fn auc(coal: &[f64], gangue: &[f64]) -> f64 {
    weighted_auc(&pooled(coal, gangue), |_| 1.0)
}

/// For each value of `of`, the fraction of `sorted` below it plus half the fraction equal.
fn placements(of: &[f64], sorted: &[f64]) -> Vec<f64> {
    let n = sorted.len() as f64;
    of.iter()
        .map(|&v| {
            let below = sorted.partition_point(|&s| s < v);
            let upto = sorted.partition_point(|&s| s <= v);
            (below as f64 + 0.5 * (upto - below) as f64) / n
        })
        .collect()
}

fn sample_variance(v: &[f64]) -> f64 {
    let n = v.len() as f64;
    if v.len() < 2 {
        return 0.0;
    }
    let mean = v.iter().sum::<f64>() / n;
    v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)
}

/// The AUC with DeLong's standard error.
pub fn auc_with_error(coal: &[f64], gangue: &[f64]) -> Auc {
    if coal.is_empty() || gangue.is_empty() {
        return Auc { auc: 0.5, standard_error: 0.0 };
    }
    let mut c = coal.to_vec();
    let mut g = gangue.to_vec();
    c.sort_by(f64::total_cmp);
    g.sort_by(f64::total_cmp);
    let v_gangue = placements(gangue, &c);
    let v_coal: Vec<f64> = placements(coal, &g).iter().map(|p| 1.0 - p).collect();
    let auc = v_gangue.iter().sum::<f64>() / v_gangue.len() as f64;
    let var = sample_variance(&v_gangue) / g.len() as f64 + sample_variance(&v_coal) / c.len() as f64;
    Auc { auc, standard_error: var.max(0.0).sqrt() }
}

/// The percentile bootstrap interval of the AUC at confidence `level` (0.95: the 2.5 % and
/// 97.5 % quantiles) from `resamples` stratified resamples drawn from the stream of `seed`
/// (bit-identical for a seed).
pub fn bootstrap_interval(coal: &[f64], gangue: &[f64], resamples: usize, level: f64, seed: u64) -> (f64, f64) {
    if coal.is_empty() || gangue.is_empty() || resamples == 0 {
        return (0.5, 0.5);
    }
    let sorted = pooled(coal, gangue);
    // Where each original value sits in the sorted order, per class.
    let mut coal_pos = Vec::with_capacity(coal.len());
    let mut gangue_pos = Vec::with_capacity(gangue.len());
    for (k, (_, is_gangue)) in sorted.iter().enumerate() {
        if *is_gangue {
            gangue_pos.push(k);
        } else {
            coal_pos.push(k);
        }
    }
    let mut rng = impact_stream(seed, 0);
    let mut weights = vec![0.0; sorted.len()];
    let mut aucs = Vec::with_capacity(resamples);
    for _ in 0..resamples {
        weights.iter_mut().for_each(|w| *w = 0.0);
        for pos in [&coal_pos, &gangue_pos] {
            let n = pos.len();
            for _ in 0..n {
                let k = ((open_uniform(&mut rng) * n as f64) as usize).min(n - 1);
                weights[pos[k]] += 1.0;
            }
        }
        aucs.push(weighted_auc(&sorted, |j| weights[j]));
    }
    aucs.sort_by(f64::total_cmp);
    let q = |p: f64| {
        let idx = (p * (aucs.len() - 1) as f64).round() as usize;
        aucs[idx.min(aucs.len() - 1)]
    };
    let tail = 0.5 * (1.0 - level);
    (q(tail), q(1.0 - tail))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_cases_by_hand() {
        // Coal {1, 2}, gangue {2, 3}: pairs (1,2) 1, (1,3) 1, (2,2) ½, (2,3) 1 → 3.5/4.
        assert_eq!(auc(&[1.0, 2.0], &[2.0, 3.0]), 0.875);
        assert_eq!(auc(&[5.0, 6.0], &[1.0, 2.0]), 0.0);
        assert_eq!(auc(&[1.0; 3], &[1.0; 4]), 0.5);
        let a = auc_with_error(&[1.0, 2.0], &[2.0, 3.0]);
        assert_eq!(a.auc, 0.875);
        assert_eq!(a.separability(), 0.875);
    }

    #[test]
    fn delong_error_matches_the_variance_of_the_hand_case() {
        // Coal {1, 2}, gangue {2, 3}: gangue placements {3/4, 1}, coal placements {1, 3/4};
        // s² = 1/32 each, Var = 1/64 + 1/64, SE = √(1/32).
        let a = auc_with_error(&[1.0, 2.0], &[2.0, 3.0]);
        assert!((a.standard_error - (1.0f64 / 32.0).sqrt()).abs() < 1e-15);
    }
}
