//! A stratified random subsample of an ensemble's impacts, and how well the change of an AUC
//! measured on it stands for the change over the whole ensemble.
//!
//! **The sample.** Each family keeps ⌈f·count⌉ of its impacts (at least one), chosen by
//! selection sampling (Knuth, *The Art of Computer Programming* vol. 2, §3.4.2, Algorithm S):
//! impact t of a family of N is taken with probability (n − m)/(N − t), m taken so far, which
//! makes every n-subset equally likely and returns them in order. Stratifying by family keeps
//! the class sizes in the whole ensemble's proportion, so the two classes are sampled apart,
//! as DeLong's variance assumes.
//!
//! **The error of a subsample's difference.** A difference of two AUCs of the same impacts
//! (N modes against N/2) measured on a simple random sample of n of the N impacts estimates
//! the whole ensemble's difference with DeLong's paired standard error times the finite
//! population correction √(1 − n/N) (Cochran, *Sampling Techniques*, 3rd ed., 1977, eq.
//! 2.8 for a mean; the AUC difference is a mean of the structural components to first
//! order). [`Coverage`] says how often the 95 % interval so made held the whole ensemble's
//! difference: its check, not an assumption. The normal interval needs changes spread over
//! many impacts; a change made by a few impacts swapping ranks is mostly absent from a
//! small subsample, whose error then reads near 0, and such intervals hold the whole
//! change less often than stated.

use crate::ensemble::{impact_stream, open_uniform};
use crate::placement::FeatureTable;
use crate::roc::paired_difference;
use crate::FEATURES;
use rayon::prelude::*;

/// z of a two-sided 95 % normal interval.
const Z95: f64 = 1.959_963_984_540_054;

/// Impacts a subsample keeps of each family at the least (all of a smaller one): DeLong's
/// variance needs two of a class.
pub const MIN_PER_FAMILY: usize = 2;

/// The indices (into 0..Σcounts, families one after the other) of a stratified random
/// subsample: ⌈`fraction`·count⌉ of each family (at least [`MIN_PER_FAMILY`], at most all),
/// in increasing order, chosen by the uniforms of stream `stream` of `seed`. `fraction` is
/// within (0, 1].
pub fn stratified(counts: &[usize], fraction: f64, seed: u64, stream: usize) -> Vec<usize> {
    let mut rng = impact_stream(seed, stream);
    let mut out = Vec::new();
    let mut first = 0;
    for &count in counts {
        // fraction·count rounds up to the next whole impact, not past a whole one it hits.
        let share = (fraction * count as f64 * (1.0 - 1e-12)).ceil() as usize;
        let keep = share.clamp(count.min(MIN_PER_FAMILY), count);
        let mut taken = 0;
        for t in 0..count {
            if taken == keep {
                break;
            }
            // Algorithm S: take t with probability (keep − taken)/(count − t).
            if ((count - t) as f64) * open_uniform(&mut rng) < (keep - taken) as f64 {
                out.push(first + t);
                taken += 1;
            }
        }
        first += count;
    }
    out
}

/// The change AUC_b − AUC_a of each of `columns` (indices channel-major, as
/// [`crate::placement::separabilities`]; every column if None) of two tables of the same n
/// impacts (`a` and `b`, the same classes in the same order), with DeLong's paired standard
/// error times the finite population correction √(1 − n/`population`): the error of the
/// change as an estimate of the change over all `population` impacts the n were sampled
/// from (0 when they are all of them).
pub fn column_changes(
    a: &FeatureTable,
    b: &FeatureTable,
    population: usize,
    columns: Option<&[usize]>,
) -> Vec<(f64, f64)> {
    let correction = population_correction(a.len(), population);
    let all: Vec<usize>;
    let columns = match columns {
        Some(c) => c,
        None => {
            all = (0..a.channels() * FEATURES.len()).collect();
            &all
        }
    };
    columns
        .par_iter()
        .map(|&column| {
            let (channel, feature) = (column / FEATURES.len(), FEATURES[column % FEATURES.len()]);
            let ((ac, ag), (bc, bg)) = (a.split(channel, feature), b.split(channel, feature));
            let (change, se) = paired_difference((&ac, &ag), (&bc, &bg));
            (change, se * correction)
        })
        .collect()
}

/// √(1 − n/N), the finite population correction of the standard error of a mean over a
/// simple random sample of n of N items (Cochran 1977, eq. 2.8); 0 when the sample is all
/// of them.
pub fn population_correction(n: usize, population: usize) -> f64 {
    (1.0 - n as f64 / population.max(1) as f64).max(0.0).sqrt()
}

/// The [`column_changes`] of `columns` in `repeats` stratified subsamples of `fraction` of
/// each family of `counts` (streams 0..repeats of `seed`) of two tables of all Σcounts
/// impacts.
pub fn sampled_changes(
    (a, b): (&FeatureTable, &FeatureTable),
    (counts, columns): (&[usize], Option<&[usize]>),
    fraction: f64,
    (repeats, seed): (usize, u64),
) -> Vec<Sampled> {
    (0..repeats)
        .map(|r| {
            let rows = stratified(counts, fraction, seed, r);
            let changes = column_changes(&a.select(&rows), &b.select(&rows), a.len(), columns);
            Sampled { impacts: rows.len(), changes }
        })
        .collect()
}

/// One subsample's changes.
#[derive(Debug, Clone, PartialEq)]
pub struct Sampled {
    /// Impacts in the subsample.
    pub impacts: usize,
    /// Each column's change and its error ([`column_changes`]).
    pub changes: Vec<(f64, f64)>,
}

/// How well subsamples of one size stood for the whole ensemble in the change of every
/// column's AUC between two tables of the same impacts.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Coverage {
    /// The fraction of each family kept.
    pub fraction: f64,
    /// Impacts in each subsample.
    pub impacts: usize,
    /// Independent subsamples drawn.
    pub repeats: usize,
    /// Column changes compared (columns × repeats).
    pub compared: usize,
    /// The share of them whose whole-ensemble change lay within the subsample's 95 %
    /// interval (nominally 0.95).
    pub covered: f64,
    /// The share of them that missed the whole ensemble's change by more than both the
    /// interval's half-width and a stated tolerance.
    pub beyond_tolerance: f64,
    /// The largest distance of a subsample's change from the whole ensemble's.
    pub largest_miss: f64,
    /// The median of that distance.
    pub median_miss: f64,
}

impl Coverage {
    /// The coverage of `samples` (of `fraction`) against `whole`, the change of every column
    /// over all impacts, with misses beyond `tolerance` counted apart.
    pub fn of(whole: &[(f64, f64)], samples: &[Sampled], fraction: f64, tolerance: f64) -> Self {
        let mut misses = Vec::with_capacity(samples.len() * whole.len());
        let (mut covered, mut beyond) = (0usize, 0usize);
        for sample in samples {
            for ((change, se), (full, _)) in sample.changes.iter().zip(whole) {
                let miss = (change - full).abs();
                // An interval of width 0 holds a change equal to it up to rounding of the sums.
                let half_width = Z95 * se + 1e-12;
                covered += usize::from(miss <= half_width);
                beyond += usize::from(miss > half_width.max(tolerance));
                misses.push(miss);
            }
        }
        misses.sort_by(f64::total_cmp);
        let compared = misses.len();
        Self {
            fraction,
            impacts: samples.first().map_or(0, |s| s.impacts),
            repeats: samples.len(),
            compared,
            covered: covered as f64 / compared.max(1) as f64,
            beyond_tolerance: beyond as f64 / compared.max(1) as f64,
            largest_miss: misses.last().copied().unwrap_or(0.0),
            median_miss: if compared == 0 { 0.0 } else { misses[compared / 2] },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Class;

    #[test]
    fn each_family_keeps_its_share_in_order() {
        let counts = [10, 7, 0, 1, 20];
        let rows = stratified(&counts, 0.3, 5, 0);
        // ⌈3⌉, ⌈2.1⌉, none of none, the one of one, 0.3·20 = 6 exactly (not 7).
        let per: Vec<usize> = [(0, 10), (10, 17), (17, 17), (17, 18), (18, 38)]
            .iter()
            .map(|&(lo, hi)| rows.iter().filter(|&&i| i >= lo && i < hi).count())
            .collect();
        assert_eq!(per, vec![3, 3, 0, 1, 6]);
        assert!(rows.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(stratified(&counts, 1.0, 5, 0), (0..38).collect::<Vec<_>>());
        // At least two of a family, so that each class has a variance.
        assert_eq!(stratified(&[100], 0.001, 5, 0).len(), MIN_PER_FAMILY);
    }

    #[test]
    fn every_impact_is_equally_likely_to_be_kept() {
        // Algorithm S keeps each of N items with probability n/N: over S samples each count
        // is binomial(S, n/N); 4.5 standard deviations bound all ten at once (p < 1e-4).
        let (n, keep, samples) = (10usize, 3usize, 8000usize);
        let mut hits = vec![0usize; n];
        for s in 0..samples {
            for i in stratified(&[n], keep as f64 / n as f64, 11, s) {
                hits[i] += 1;
            }
        }
        let p = keep as f64 / n as f64;
        let sd = (samples as f64 * p * (1.0 - p)).sqrt();
        for (i, &h) in hits.iter().enumerate() {
            assert!((h as f64 - samples as f64 * p).abs() < 4.5 * sd, "impact {i}: {h} of {samples}");
        }
    }

    #[test]
    fn the_whole_ensemble_is_its_own_sample_and_has_no_error() {
        let mut a = FeatureTable::new(1);
        let mut b = FeatureTable::new(1);
        for i in 0..40 {
            let class = if i % 2 == 0 { Class::Coal } else { Class::Gangue };
            let v = (i as f64 * 0.37).sin() + if class == Class::Gangue { 0.5 } else { 0.0 };
            let row = vec![v; FEATURES.len()];
            a.push(class, &row);
            b.push(class, &row.iter().map(|x| x + 0.3 * (i as f64 * 1.7).cos()).collect::<Vec<_>>());
        }
        let whole = column_changes(&a, &b, 40, None);
        let sampled = sampled_changes((&a, &b), (&[40], None), 1.0, (1, 0));
        assert_eq!(sampled[0].changes, whole);
        assert!(whole.iter().all(|c| c.1 == 0.0 && c.0 != 0.0));
    }

    #[test]
    fn intervals_of_subsamples_hold_the_whole_change_about_as_often_as_stated() {
        // A population of 4000 impacts whose two scores differ by noise: the whole change is
        // a fixed number, and 95 % intervals from samples of half of it should hold it in
        // about 95 % of 400 samples (the binomial's sd at 0.95 is 1.1 %; 3.5 sd either way,
        // 0.038). Without the finite population correction the intervals would be √2 wider
        // and hold it 99.4 % of the time, outside that band.
        let mut a = FeatureTable::new(1);
        let mut b = FeatureTable::new(1);
        let mut rng = impact_stream(3, 0);
        let normal = |rng: &mut rand_chacha::ChaCha8Rng| {
            let (u, v) = (open_uniform(rng), open_uniform(rng));
            (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
        };
        for i in 0..4000 {
            let class = if i < 2000 { Class::Coal } else { Class::Gangue };
            let shift = if class == Class::Gangue { 1.0 } else { 0.0 };
            let x = normal(&mut rng) + shift;
            a.push(class, &vec![x; FEATURES.len()]);
            let y = x + 0.5 * normal(&mut rng);
            b.push(class, &vec![y; FEATURES.len()]);
        }
        let whole = column_changes(&a, &b, 4000, Some(&[0]));
        let samples = sampled_changes((&a, &b), (&[2000, 2000], Some(&[0])), 0.5, (400, 9));
        let c = Coverage::of(&whole, &samples, 0.5, 1.0);
        assert_eq!((c.impacts, c.compared, c.beyond_tolerance), (2000, 400, 0.0));
        assert!((c.covered - 0.95).abs() < 0.038, "covered {}", c.covered);
    }
}
