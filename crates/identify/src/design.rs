//! Sensor design: given a budget of B sensors of one kind and the candidate points of a
//! placement grid, the points whose features together tell coal from gangue best, chosen one
//! at a time (greedy forward selection), with what each added sensor gains.
//!
//! A set S of sensors is scored by the cross-validated AUC of the logistic classifier on every
//! feature of every sensor in S ([`cross_validated_auc`]): each impact's probability of gangue
//! comes from the model fitted without its fold, and the AUC of those out-of-fold
//! probabilities carries DeLong's standard error (which treats them as independent, and so
//! slightly understates the spread of a cross-validated score). Step k adds the candidate that
//! maximises the score of S ∪ {c}; its map is that score for every candidate c not yet chosen,
//! and its gain over the step before carries DeLong's paired standard error
//! ([`crate::roc::paired_difference`]: both sets score the same impacts).
//!
//! Two cautions. Greedy selection is not guaranteed to find the best set of more than one
//! sensor. And each step's AUC is the largest of many scored on the same folds, so it is
//! biased upward by the choice (the winner's curse): a step's gain means something only well
//! beyond its standard error, and a cross-validated ridge fit can lose AUC when a sensor adds
//! only noise.

pub use crate::classify::out_of_fold;
use crate::classify::{FitError, FOLDS, RIDGE};
use crate::ensemble::Class;
use crate::features::FEATURES;
use crate::placement::FeatureTable;
use crate::roc::{auc_with_error, paired_difference, Auc};
use rayon::prelude::*;
use serde::Serialize;

/// One step of the design: the sensor added, the set's score and its gain over the last step.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Step {
    /// The candidate added (its position in the candidate list).
    pub added: usize,
    /// The cross-validated AUC of the set after this step.
    pub auc: Auc,
    /// AUC after this step minus AUC before it (the first step's is over 0.5, chance).
    pub gain: f64,
    /// DeLong's paired standard error of the gain (the first step's: its AUC's own).
    pub gain_standard_error: f64,
    /// For each candidate, the set's AUC had it been added instead (None: already chosen).
    pub map: Vec<Option<f64>>,
}

/// The cross-validated AUC of the logistic classifier ([`crate::classify::Logistic::fit`], ridge `lambda`) on
/// `rows` labelled `labels` (true: gangue), [`crate::classify::stratified_folds`] of `k` from `seed`.
///
/// ```
/// use identify::design::cross_validated_auc;
/// // One column that separates the classes perfectly.
/// let rows: Vec<Vec<f64>> = (0..40).map(|i| vec![if i % 2 == 0 { i as f64 } else { 100.0 + i as f64 }]).collect();
/// let labels: Vec<bool> = (0..40).map(|i| i % 2 == 1).collect();
/// let a = cross_validated_auc(&rows, &labels, &[false], 1.0, 5, 7).unwrap();
/// assert_eq!(a.auc, 1.0);
/// ```
pub fn cross_validated_auc(
    rows: &[Vec<f64>],
    labels: &[bool],
    scale: &[bool],
    lambda: f64,
    k: usize,
    seed: u64,
) -> Result<Auc, FitError> {
    let p = out_of_fold(rows, labels, scale, lambda, k, seed)?;
    let (coal, gangue) = by_class(&p, labels);
    Ok(auc_with_error(&coal, &gangue))
}

/// `values` split by `labels` into (coal, gangue), in order.
pub fn by_class(values: &[f64], labels: &[bool]) -> (Vec<f64>, Vec<f64>) {
    let (mut coal, mut gangue) = (Vec::new(), Vec::new());
    for (v, &l) in values.iter().zip(labels) {
        if l {
            gangue.push(*v);
        } else {
            coal.push(*v);
        }
    }
    (coal, gangue)
}

/// Every feature of `channels` of `table`, one row per impact, and their scale flags.
pub(crate) fn rows_of(table: &FeatureTable, channels: &[usize]) -> (Vec<Vec<f64>>, Vec<bool>) {
    let rows = (0..table.len())
        .map(|i| channels.iter().flat_map(|&c| FEATURES.iter().map(move |&f| table.column(c, f)[i])).collect())
        .collect();
    let scale = channels.iter().flat_map(|_| FEATURES.iter().map(|f| f.is_scale())).collect();
    (rows, scale)
}

/// One step of a greedy forward selection: the candidate added, the chosen set's score, and
/// every candidate's AUC had it been added instead (None: already chosen).
#[derive(Debug, Clone)]
pub struct Chosen<S> {
    /// The candidate added (its position among the candidates).
    pub added: usize,
    /// The score of the set after this step.
    pub score: S,
    /// For each candidate, the AUC of the set had it been added instead.
    pub map: Vec<Option<f64>>,
}

/// Greedy forward selection of up to `budget` of `candidates` candidates (at most as many
/// steps as candidates): step k scores every set of the k - 1 chosen and one candidate not yet
/// chosen by `score` (in parallel) and adds the one whose `auc` is highest; ties go to the
/// earlier candidate. Every set is scored by the same `score`, so that on the same folds the
/// sets are compared on the same splits.
///
/// ```
/// use identify::design::forward_selection;
/// // Candidate c alone scores 0.5 + c/10; a set scores its best member's score plus 0.01 a member.
/// let score = |set: &[usize]| -> Result<f64, ()> {
///     Ok(set.iter().map(|&c| 0.5 + c as f64 / 10.0).fold(0.0, f64::max) + 0.01 * set.len() as f64)
/// };
/// let steps = forward_selection(4, 2, score, |s: &f64| *s).unwrap();
/// assert_eq!(steps.iter().map(|s| s.added).collect::<Vec<_>>(), [3, 0]);
/// assert_eq!(steps[1].map[3], None);
/// ```
pub fn forward_selection<S, E>(
    candidates: usize,
    budget: usize,
    score: impl Fn(&[usize]) -> Result<S, E> + Sync,
    auc: impl Fn(&S) -> f64 + Sync,
) -> Result<Vec<Chosen<S>>, E>
where
    S: Send,
    E: Send,
{
    let mut chosen: Vec<usize> = Vec::new();
    let mut steps = Vec::new();
    for _ in 0..budget.min(candidates) {
        let mut scores: Vec<Option<S>> = (0..candidates)
            .into_par_iter()
            .map(|c| {
                if chosen.contains(&c) {
                    return Ok(None);
                }
                let set: Vec<usize> = chosen.iter().copied().chain([c]).collect();
                score(&set).map(Some)
            })
            .collect::<Result<_, E>>()?;
        // A score that is not a number ranks below every other.
        let value = |k: usize| scores[k].as_ref().map(&auc).filter(|a| !a.is_nan()).unwrap_or(f64::MIN);
        // The first best: ties go to the earlier candidate.
        let Some(added) = (0..candidates).filter(|&c| scores[c].is_some()).fold(None, |b: Option<usize>, c| match b {
            Some(b) if value(b) >= value(c) => Some(b),
            _ => Some(c),
        }) else {
            break;
        };
        let map = scores.iter().map(|s| s.as_ref().map(&auc)).collect();
        let Some(score) = scores[added].take() else { break };
        chosen.push(added);
        steps.push(Chosen { added, score, map });
    }
    Ok(steps)
}

/// Greedy forward selection of `budget` sensors among `candidates` (the table's channel of
/// each candidate point), each set scored by [`cross_validated_auc`] with [`FOLDS`] folds and
/// ridge [`RIDGE`] from `seed` (the same folds for every set, so that sets are compared on
/// the same splits; [`forward_selection`]), each step's gain by DeLong's paired error.
pub fn greedy(table: &FeatureTable, candidates: &[usize], budget: usize, seed: u64) -> Result<Vec<Step>, FitError> {
    let labels: Vec<bool> = table.classes().iter().map(|c| *c == Class::Gangue).collect();
    let score = |set: &[usize]| -> Result<(Auc, Vec<f64>), FitError> {
        let channels: Vec<usize> = set.iter().map(|&k| candidates[k]).collect();
        let (rows, scale) = rows_of(table, &channels);
        let p = out_of_fold(&rows, &labels, &scale, RIDGE, FOLDS, seed)?;
        let (coal, gangue) = by_class(&p, &labels);
        Ok((auc_with_error(&coal, &gangue), p))
    };
    let chosen = forward_selection(candidates.len(), budget, score, |s: &(Auc, Vec<f64>)| s.0.auc)?;
    let mut before: Option<&Vec<f64>> = None;
    let mut steps = Vec::with_capacity(chosen.len());
    for Chosen { added, score: (auc, p), map } in &chosen {
        let (gain, gain_standard_error) = match before {
            None => (auc.auc - 0.5, auc.standard_error),
            Some(q) => {
                let ((qc, qg), (pc, pg)) = (by_class(q, &labels), by_class(p, &labels));
                paired_difference((&qc, &qg), (&pc, &pg))
            }
        };
        steps.push(Step { added: *added, auc: *auc, gain, gain_standard_error, map: map.clone() });
        before = Some(p);
    }
    Ok(steps)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distribution::phi;
    use crate::features::Peak;
    use rand_chacha::rand_core::SeedableRng;
    use rand_distr::{Distribution, Normal};

    /// Channel features whose peak is `peak`, every other feature 1.
    fn f(peak: f64) -> Vec<f64> {
        FEATURES.iter().map(|f| if f.key() == "peak" { peak } else { 1.0 }).collect()
    }

    /// Three candidates: 0 carries nothing, 1 the class shifted by d₁ in unit normal noise, 2
    /// by d₂ < d₁ in independent noise. The first step must take candidate 1 at AUC near
    /// Φ(d₁/√2) (the binormal AUC), the second candidate 2 at near Φ(√(d₁² + d₂²)/√2) (the
    /// two independent shifts add as a Mahalanobis distance), each within 3 standard errors.
    #[test]
    fn greedy_takes_the_informative_sensor_then_the_complementary_one() {
        let (d1, d2): (f64, f64) = (1.0, 0.8);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        let n = Normal::<f64>::new(0.0, 1.0).unwrap();
        let mut t = FeatureTable::new(3);
        for i in 0..1200 {
            let class = if i % 2 == 0 { Class::Coal } else { Class::Gangue };
            let s: f64 = if class == Class::Gangue { 1.0 } else { 0.0 };
            // Peaks kept positive (a scale feature is read as its logarithm where positive):
            // the shift is applied to the logarithm.
            let row = [
                f(n.sample(&mut rng).exp()),
                f((n.sample(&mut rng) + s * d1).exp()),
                f((n.sample(&mut rng) + s * d2).exp()),
            ]
            .concat();
            t.push(class, &row);
        }
        assert!(crate::Feature::is_scale(&Peak));
        let steps = greedy(&t, &[0, 1, 2], 3, 4).unwrap();
        assert_eq!(steps.iter().map(|s| s.added).collect::<Vec<_>>(), [1, 2, 0]);
        let one = phi(d1 / 2f64.sqrt());
        let two = phi((d1 * d1 + d2 * d2).sqrt() / 2f64.sqrt());
        for (s, expected) in steps.iter().zip([one, two]) {
            assert!((s.auc.auc - expected).abs() < 3.0 * s.auc.standard_error, "{} against {expected}", s.auc.auc);
        }
        // The second sensor's gain is resolved by the paired error; the uninformative third
        // gains nothing beyond its own.
        assert!(steps[1].gain > 3.0 * steps[1].gain_standard_error, "{:?}", steps[1]);
        assert!(steps[2].gain.abs() < 3.0 * steps[2].gain_standard_error.max(1e-12), "{:?}", steps[2]);
        assert_eq!(steps[1].map[1], None);
        assert!(steps[0].map[0].unwrap() < steps[0].map[2].unwrap());
    }
}
