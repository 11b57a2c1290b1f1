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

/// The difference AUC_b − AUC_a of two scores of the same impacts (`a` and `b`, each as
/// (coal, gangue) in the same impact order), with DeLong's standard error of the paired
/// difference (DeLong, DeLong & Clarke-Pearson 1988, eq. 4): from each impact's structural
/// components V₁₀ (a gangue score's placement among the coal scores) and V₀₁ (a coal
/// score's among the gangue), Var = (S¹⁰_aa + S¹⁰_bb − 2S¹⁰_ab)/n₁ + (S⁰¹_aa + S⁰¹_bb −
/// 2S⁰¹_ab)/n₀. Two scores of the same impacts are correlated, and the paired error is far
/// below either score's own.
pub fn paired_difference(a: (&[f64], &[f64]), b: (&[f64], &[f64])) -> (f64, f64) {
    let components = |(coal, gangue): (&[f64], &[f64])| {
        let mut c = coal.to_vec();
        let mut g = gangue.to_vec();
        c.sort_by(f64::total_cmp);
        g.sort_by(f64::total_cmp);
        let v10 = placements(gangue, &c);
        let v01: Vec<f64> = placements(coal, &g).iter().map(|p| 1.0 - p).collect();
        (v10, v01)
    };
    if a.0.is_empty() || a.1.is_empty() || a.0.len() != b.0.len() || a.1.len() != b.1.len() {
        return (0.0, 0.0);
    }
    let ((a10, a01), (b10, b01)) = (components(a), components(b));
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let cov = |x: &[f64], y: &[f64]| {
        if x.len() < 2 {
            return 0.0;
        }
        let (mx, my) = (mean(x), mean(y));
        x.iter().zip(y).map(|(p, q)| (p - mx) * (q - my)).sum::<f64>() / (x.len() - 1) as f64
    };
    let d10: Vec<f64> = b10.iter().zip(&a10).map(|(p, q)| p - q).collect();
    let d01: Vec<f64> = b01.iter().zip(&a01).map(|(p, q)| p - q).collect();
    let var = cov(&d10, &d10) / d10.len() as f64 + cov(&d01, &d01) / d01.len() as f64;
    (mean(&b10) - mean(&a10), var.max(0.0).sqrt())
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
    percentile_interval(aucs, level)
}

/// The percentile interval at confidence `level` of resampled AUCs: the values at the
/// (1 - level)/2 and (1 + level)/2 quantiles, nearest rank.
fn percentile_interval(mut aucs: Vec<f64>, level: f64) -> (f64, f64) {
    aucs.sort_by(f64::total_cmp);
    let q = |p: f64| {
        let idx = (p * (aucs.len() - 1) as f64).round() as usize;
        aucs[idx.min(aucs.len() - 1)]
    };
    let tail = 0.5 * (1.0 - level);
    (q(tail), q(1.0 - tail))
}

/// The AUC when values closer than `tolerance` cannot be told apart: a gangue value above a
/// coal value by more than `tolerance` counts 1, within ±`tolerance` ½ (a tie), else 0. With
/// `tolerance` 0 it is [`auc`]. What a quantity measured to a resolution separates: on the
/// logarithm of a mass with `tolerance` ln(1.01), masses within 1 % are ties. Each coal value
/// finds its ties and the gangue values above by two binary searches in the sorted gangue.
pub fn auc_within(coal: &[f64], gangue: &[f64], tolerance: f64) -> f64 {
    let mut g = gangue.to_vec();
    g.sort_by(f64::total_cmp);
    let prefix = running_sum(&vec![1.0; g.len()]);
    within_weighted(coal, &vec![1.0; coal.len()], &g, &prefix, tolerance)
}

/// [`bootstrap_interval`] for [`auc_within`]: the same stratified resampling, each resample's
/// multiplicities as weights.
pub fn bootstrap_interval_within(
    coal: &[f64],
    gangue: &[f64],
    tolerance: f64,
    (resamples, level): (usize, f64),
    seed: u64,
) -> (f64, f64) {
    if coal.is_empty() || gangue.is_empty() || resamples == 0 {
        return (0.5, 0.5);
    }
    let mut g = gangue.to_vec();
    g.sort_by(f64::total_cmp);
    let mut rng = impact_stream(seed, 0);
    let (mut wc, mut wg) = (vec![0.0; coal.len()], vec![0.0; g.len()]);
    let mut aucs = Vec::with_capacity(resamples);
    for _ in 0..resamples {
        for w in [&mut wc, &mut wg] {
            let n = w.len();
            w.iter_mut().for_each(|x| *x = 0.0);
            for _ in 0..n {
                w[((open_uniform(&mut rng) * n as f64) as usize).min(n - 1)] += 1.0;
            }
        }
        aucs.push(within_weighted(coal, &wc, &g, &running_sum(&wg), tolerance));
    }
    percentile_interval(aucs, level)
}

/// prefix[k] = Σ_{i<k} w[i].
fn running_sum(w: &[f64]) -> Vec<f64> {
    let mut prefix = Vec::with_capacity(w.len() + 1);
    prefix.push(0.0);
    for x in w {
        prefix.push(prefix[prefix.len() - 1] + x);
    }
    prefix
}

/// The weighted AUC at a resolution: coal values with weights `wc`, gangue values `g` sorted
/// with the running sum `prefix` of their weights.
fn within_weighted(coal: &[f64], wc: &[f64], g: &[f64], prefix: &[f64], tolerance: f64) -> f64 {
    let total = prefix[g.len()];
    let (mut u, mut n0) = (0.0, 0.0);
    for (&c, &w) in coal.iter().zip(wc) {
        if w == 0.0 {
            continue;
        }
        let lo = g.partition_point(|&x| x < c - tolerance);
        let hi = g.partition_point(|&x| x <= c + tolerance);
        u += w * ((total - prefix[hi]) + 0.5 * (prefix[hi] - prefix[lo]));
        n0 += w;
    }
    if n0 > 0.0 && total > 0.0 {
        u / (n0 * total)
    } else {
        0.5
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// DeLong's paired error against the bootstrap's: two correlated scores of 300 + 300
    /// impacts (a common part and each its own noise), the spread of AUC_b − AUC_a over 4000
    /// stratified resamples of the impacts (both scores resampled together) by the pair
    /// count [`auc`], which shares nothing with the structural components. The bootstrap's
    /// standard deviation is itself known to about 1/√(2·4000) = 1.1 %; DeLong's is
    /// asymptotic; 10 % holds both. The same score twice differs by exactly 0 ± 0.
    #[test]
    fn the_paired_error_is_the_bootstraps() {
        use rand_chacha::rand_core::{RngCore, SeedableRng};
        use rand_distr::{Distribution, Normal};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let n = Normal::<f64>::new(0.0, 1.0).unwrap();
        let mut draw = |shift: f64| {
            let common = n.sample(&mut rng) + shift;
            (common + 0.5 * n.sample(&mut rng), common + 0.7 * n.sample(&mut rng))
        };
        let coal: Vec<(f64, f64)> = (0..300).map(|_| draw(0.0)).collect();
        let gangue: Vec<(f64, f64)> = (0..300).map(|_| draw(0.8)).collect();
        let split =
            |v: &[(f64, f64)]| (v.iter().map(|p| p.0).collect::<Vec<_>>(), v.iter().map(|p| p.1).collect::<Vec<_>>());
        let ((ca, cb), (ga, gb)) = (split(&coal), split(&gangue));
        let (d, se) = paired_difference((&ca, &ga), (&cb, &gb));
        assert!((d - (auc(&cb, &gb) - auc(&ca, &ga))).abs() < 1e-12);
        let mut diffs = Vec::new();
        for _ in 0..4000 {
            let pick = |v: &[(f64, f64)], rng: &mut rand_chacha::ChaCha8Rng| -> Vec<(f64, f64)> {
                (0..v.len()).map(|_| v[(rng.next_u64() % v.len() as u64) as usize]).collect()
            };
            let (c, g) = (pick(&coal, &mut rng), pick(&gangue, &mut rng));
            let ((ca, cb), (ga, gb)) = (split(&c), split(&g));
            diffs.push(auc(&cb, &gb) - auc(&ca, &ga));
        }
        let m = diffs.iter().sum::<f64>() / diffs.len() as f64;
        let sd = (diffs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (diffs.len() - 1) as f64).sqrt();
        assert!((se / sd - 1.0).abs() < 0.1, "DeLong {se}, bootstrap {sd}");
        assert_eq!(paired_difference((&ca, &ga), (&ca, &ga)), (0.0, 0.0));
    }

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

    /// Against the definition, pair by pair, on values with ties and near-ties; and with no
    /// tolerance it is the Mann-Whitney AUC.
    #[test]
    fn auc_within_a_tolerance_counts_near_pairs_as_ties() {
        let coal: Vec<f64> = (0..37).map(|i| ((i * 7) % 11) as f64 * 0.1).collect();
        let gangue: Vec<f64> = (0..29).map(|i| ((i * 5) % 13) as f64 * 0.1 + 0.03).collect();
        for tol in [0.0, 0.02, 0.05, 0.2] {
            let mut u = 0.0;
            for c in &coal {
                for g in &gangue {
                    u += if g - c > tol {
                        1.0
                    } else if (g - c).abs() <= tol {
                        0.5
                    } else {
                        0.0
                    };
                }
            }
            let pairwise = u / (coal.len() * gangue.len()) as f64;
            assert!((auc_within(&coal, &gangue, tol) - pairwise).abs() < 1e-12, "tolerance {tol}");
        }
        assert!((auc_within(&coal, &gangue, 0.0) - auc(&coal, &gangue)).abs() < 1e-12);
        let (lo, hi) = bootstrap_interval_within(&coal, &gangue, 0.05, (500, 0.95), 7);
        let a = auc_within(&coal, &gangue, 0.05);
        assert!(lo <= a && a <= hi && hi - lo < 0.5, "({lo}, {hi}) around {a}");
    }
}
