//! A logistic-regression classifier of coal against gangue and its cross-validated accuracy.
//!
//! **Model.** P(gangue | x) = σ(b + wᵀz), σ(t) = 1/(1 + e^{-t}), with z the standardised
//! features: each column shifted by its training mean and divided by its training standard
//! deviation (a column constant on the training data is left out: z = 0). Scale features
//! (peak, RMS, energy: [`crate::features::Feature::is_scale`]) enter as their natural
//! logarithm when all their training values are positive, because they spread over decades
//! and separate by ratio.
//!
//! **Fit.** Maximum penalised likelihood: minimise
//! -Σ [y ln p + (1 - y) ln(1 - p)] + (λ/2)‖w‖² (the intercept b is not penalised) by Newton's
//! method, i.e. iteratively reweighted least squares: gradient Zᵀ(p - y) + λw, Hessian
//! ZᵀWZ + λI with W = diag(p(1 - p)), the step solved by Cholesky (faer), halved while it does not
//! lower the objective. The objective is strictly convex for λ > 0, so this converges
//! from zero to the unique minimum; with the ridge the weights stay finite even on separable
//! data, where the plain likelihood has no maximum. λ = [`RIDGE`] is small against the
//! data's curvature (ΣW grows with n) and only matters where the data do not decide.
//!
//! **Accuracy.** Stratified k-fold cross-validation: each class shuffled by a seeded stream
//! and dealt round-robin into k folds, so every fold has the class ratio of the whole; each
//! fold predicted (p ≥ ½: gangue) by the model fitted, standardisation included, on the
//! other k - 1. The accuracy is the fraction of all impacts predicted right, with its
//! binomial standard error √(a(1 - a)/n).
//!
//! linfa-logistic would do the fit too; it brings ndarray and argmin (a quasi-Newton fit
//! without the exact Hessian) for what is here a hundred lines with the equations in view.

use crate::ensemble::{impact_stream, open_uniform};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::{Mat, Par};
use serde::{Deserialize, Serialize};

/// The ridge λ on the standardised weights.
pub const RIDGE: f64 = 1.0;
/// Folds of the cross-validation.
pub const FOLDS: usize = 5;
/// Newton iterations at most (convergence takes 5-10 on the ensembles here).
pub const MAX_ITERATIONS: usize = 100;

/// How one column enters the model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Column {
    /// Taken as ln x.
    pub log: bool,
    /// Mean of the (transformed) training values.
    pub mean: f64,
    /// Their standard deviation; 0 drops the column.
    pub sd: f64,
}

impl Column {
    fn z(&self, x: f64) -> f64 {
        if self.sd > 0.0 {
            let v = if self.log { x.ln() } else { x };
            (v - self.mean) / self.sd
        } else {
            0.0
        }
    }
}

/// A fitted model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Logistic {
    /// b.
    pub intercept: f64,
    /// w, one per column (0 for dropped columns).
    pub weights: Vec<f64>,
    /// The standardisation of each column.
    pub columns: Vec<Column>,
    /// Newton iterations taken.
    pub iterations: usize,
}

/// Why a fit failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    /// Rows of different lengths, no rows, or labels not matching rows.
    #[error("the data are malformed: {0}")]
    Shape(String),
    /// A value is NaN or infinite.
    #[error("row {row}, column {column} is not a finite number")]
    NotFinite {
        /// Row.
        row: usize,
        /// Column.
        column: usize,
    },
}

fn sigmoid(t: f64) -> f64 {
    if t >= 0.0 {
        1.0 / (1.0 + (-t).exp())
    } else {
        let e = t.exp();
        e / (1.0 + e)
    }
}

/// ln(1 + e^t) without overflow.
fn softplus(t: f64) -> f64 {
    if t > 0.0 {
        t + (-t).exp().ln_1p()
    } else {
        t.exp().ln_1p()
    }
}

/// Solves H x = g for the symmetric positive definite H (row-major, n × n; its lower
/// triangle is read) by faer's Cholesky factorisation H = LLᵀ; None where H is not
/// numerically positive definite. Sequential: the systems are small (one row per parameter),
/// and a result that does not depend on the number of threads is worth more here than speed.
fn cholesky_solve(h: &[f64], g: &[f64], n: usize) -> Option<Vec<f64>> {
    let par = Par::Seq;
    let mut l = Mat::from_fn(n, n, |i, j| if j <= i { h[i * n + j] } else { 0.0 });
    let mut mem = MemBuffer::new(llt::factor::cholesky_in_place_scratch::<f64>(n, par, Default::default()));
    llt::factor::cholesky_in_place(l.as_mut(), Default::default(), par, MemStack::new(&mut mem), Default::default())
        .ok()?;
    let mut x = Mat::from_fn(n, 1, |i, _| g[i]);
    let mut mem = MemBuffer::new(llt::solve::solve_in_place_scratch::<f64>(n, 1, par));
    llt::solve::solve_in_place(l.as_ref(), x.as_mut(), par, MemStack::new(&mut mem));
    Some(x.col(0).iter().copied().collect())
}

fn check_shape(rows: &[Vec<f64>], labels: &[bool]) -> Result<usize, FitError> {
    if rows.is_empty() || rows.len() != labels.len() {
        return Err(FitError::Shape(format!("{} rows and {} labels", rows.len(), labels.len())));
    }
    let p = rows[0].len();
    for (i, r) in rows.iter().enumerate() {
        if r.len() != p {
            return Err(FitError::Shape(format!("row {i} has {} columns, row 0 has {p}", r.len())));
        }
        if let Some(j) = r.iter().position(|v| !v.is_finite()) {
            return Err(FitError::NotFinite { row: i, column: j });
        }
    }
    Ok(p)
}

impl Logistic {
    /// Fits the model to `rows` (one feature vector per impact) and `labels` (true:
    /// gangue) with the ridge `lambda`; `scale[j]` says whether column j is a scale feature.
    pub fn fit(rows: &[Vec<f64>], labels: &[bool], scale: &[bool], lambda: f64) -> Result<Self, FitError> {
        let p = check_shape(rows, labels)?;
        let n = rows.len() as f64;
        let columns: Vec<Column> =
            (0..p).map(|j| Column::of(rows, j, scale.get(j).copied().unwrap_or(false))).collect();
        // Each row as x = (1, z): the intercept's column first, so that the Hessian's rows
        // are contiguous products.
        let xs: Vec<Vec<f64>> = rows
            .iter()
            .map(|r| std::iter::once(1.0).chain(r.iter().zip(&columns).map(|(&x, c)| c.z(x))).collect())
            .collect();
        let z: Vec<&[f64]> = xs.iter().map(|x| &x[1..]).collect();
        let y: Vec<f64> = labels.iter().map(|&g| if g { 1.0 } else { 0.0 }).collect();
        // Parameters θ = (b, w); the penalty skips b.
        let d = p + 1;
        let objective = |theta: &[f64]| -> f64 {
            let nll: f64 = z
                .iter()
                .zip(&y)
                .map(|(zi, yi)| {
                    let t = theta[0] + zi.iter().zip(&theta[1..]).map(|(a, b)| a * b).sum::<f64>();
                    softplus(t) - yi * t
                })
                .sum();
            nll + 0.5 * lambda * theta[1..].iter().map(|w| w * w).sum::<f64>()
        };
        let mut theta = vec![0.0; d];
        let mut f = objective(&theta);
        let mut iterations = 0;
        for it in 0..MAX_ITERATIONS {
            iterations = it + 1;
            let (mut g, mut h) = newton_system(&xs, &y, &theta);
            for a in 1..d {
                g[a] += lambda * theta[a];
                h[a * d + a] += lambda;
            }
            // A column left out has z = 0: its weight is pinned by the ridge alone; keep H
            // definite for the intercept too.
            h[0] += 1e-12 * n;
            let Some(step) = cholesky_solve(&h, &g, d) else { break };
            let mut scale_step = 1.0;
            let mut accepted = false;
            for _ in 0..40 {
                let trial: Vec<f64> = theta.iter().zip(&step).map(|(t, s)| t - scale_step * s).collect();
                let ft = objective(&trial);
                if ft <= f {
                    theta = trial;
                    f = ft;
                    accepted = true;
                    break;
                }
                scale_step *= 0.5;
            }
            let size = step.iter().fold(0.0f64, |m, s| m.max(s.abs())) * scale_step;
            if !accepted || size < 1e-10 {
                break;
            }
        }
        Ok(Logistic { intercept: theta[0], weights: theta[1..].to_vec(), columns, iterations })
    }

    /// P(gangue | row).
    pub fn probability(&self, row: &[f64]) -> f64 {
        let t = self.intercept
            + row.iter().zip(&self.columns).zip(&self.weights).map(|((&x, c), w)| c.z(x) * w).sum::<f64>();
        sigmoid(t)
    }

    /// Predicts gangue when P(gangue) ≥ ½.
    pub fn predict(&self, row: &[f64]) -> bool {
        self.probability(row) >= 0.5
    }
}

/// The result of a cross-validation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CrossValidated {
    /// Fraction of impacts predicted right.
    pub accuracy: f64,
    /// √(a(1 - a)/n).
    pub standard_error: f64,
    /// Impacts.
    pub n: usize,
    /// Folds.
    pub folds: usize,
}

/// The fold (0..k) of each row: each class shuffled by the stream of `seed` (Fisher-Yates)
/// and dealt round-robin.
pub fn stratified_folds(labels: &[bool], k: usize, seed: u64) -> Vec<usize> {
    let mut fold = vec![0; labels.len()];
    let mut rng = impact_stream(seed, 0);
    for class in [false, true] {
        let mut idx: Vec<usize> = (0..labels.len()).filter(|&i| labels[i] == class).collect();
        for i in (1..idx.len()).rev() {
            let j = ((open_uniform(&mut rng) * (i + 1) as f64) as usize).min(i);
            idx.swap(i, j);
        }
        for (r, &i) in idx.iter().enumerate() {
            fold[i] = r % k.max(1);
        }
    }
    fold
}

/// Stratified `k`-fold cross-validated accuracy of [`Logistic::fit`] with ridge `lambda`:
/// each row predicted by the model fitted without its fold ([`out_of_fold`]).
pub fn cross_validate(
    rows: &[Vec<f64>],
    labels: &[bool],
    scale: &[bool],
    lambda: f64,
    k: usize,
    seed: u64,
) -> Result<CrossValidated, FitError> {
    let p = fold_probabilities(rows, labels, scale, lambda, k, seed)?;
    // A row no fold scored (possible only with fewer rows than folds) is not counted right.
    let correct = p.iter().zip(labels).filter(|(p, &l)| p.is_some_and(|p| (p >= 0.5) == l)).count();
    let n = rows.len();
    let a = correct as f64 / n as f64;
    Ok(CrossValidated {
        accuracy: a,
        standard_error: (a * (1.0 - a) / n as f64).sqrt(),
        n,
        folds: k.clamp(2, n.max(2)),
    })
}

/// Each row's probability of gangue from [`Logistic::fit`] (ridge `lambda`) fitted without
/// its fold, [`stratified_folds`] of `k` (at least 2) from `seed`; ½ for a row no fold
/// scores (possible only with fewer rows than folds).
pub fn out_of_fold(
    rows: &[Vec<f64>],
    labels: &[bool],
    scale: &[bool],
    lambda: f64,
    k: usize,
    seed: u64,
) -> Result<Vec<f64>, FitError> {
    Ok(fold_probabilities(rows, labels, scale, lambda, k, seed)?.into_iter().map(|p| p.unwrap_or(0.5)).collect())
}

/// [`out_of_fold`], a row no fold scores None.
fn fold_probabilities(
    rows: &[Vec<f64>],
    labels: &[bool],
    scale: &[bool],
    lambda: f64,
    k: usize,
    seed: u64,
) -> Result<Vec<Option<f64>>, FitError> {
    check_shape(rows, labels)?;
    let k = k.clamp(2, rows.len().max(2));
    let fold = stratified_folds(labels, k, seed);
    let mut probability = vec![None; rows.len()];
    for f in 0..k {
        let train: Vec<usize> = (0..rows.len()).filter(|&i| fold[i] != f).collect();
        let test: Vec<usize> = (0..rows.len()).filter(|&i| fold[i] == f).collect();
        if test.is_empty() || train.is_empty() {
            continue;
        }
        let tr: Vec<Vec<f64>> = train.iter().map(|&i| rows[i].clone()).collect();
        let tl: Vec<bool> = train.iter().map(|&i| labels[i]).collect();
        let model = Logistic::fit(&tr, &tl, scale, lambda)?;
        for i in test {
            probability[i] = Some(model.probability(&rows[i]));
        }
    }
    Ok(probability)
}

impl Column {
    /// Column `j` of `rows`: the logarithm where `scale` and every value is positive, its
    /// mean and standard deviation (0 where the spread is below rounding of the mean).
    fn of(rows: &[Vec<f64>], j: usize, scale: bool) -> Self {
        let n = rows.len() as f64;
        let log = scale && rows.iter().all(|r| r[j] > 0.0);
        let t = |v: f64| if log { v.ln() } else { v };
        let mean = rows.iter().map(|r| t(r[j])).sum::<f64>() / n;
        let var = rows.iter().map(|r| (t(r[j]) - mean).powi(2)).sum::<f64>() / n;
        // A spread below rounding of the mean is no spread.
        let sd = if var.sqrt() > 1e-12 * mean.abs().max(f64::MIN_POSITIVE) { var.sqrt() } else { 0.0 };
        Column { log, mean, sd }
    }
}

/// The gradient Σ(pᵢ - yᵢ)xᵢ and the lower triangle of the Hessian Σpᵢ(1 - pᵢ)xᵢxᵢᵀ of the
/// negative log-likelihood at `theta`, for rows x = (1, z) (the penalty is the caller's).
fn newton_system(xs: &[Vec<f64>], y: &[f64], theta: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let d = theta.len();
    let mut g = vec![0.0; d];
    // H is symmetric: its lower triangle is all the solve reads.
    let mut h = vec![0.0; d * d];
    for (xi, yi) in xs.iter().zip(y) {
        let t = theta[0] + xi[1..].iter().zip(&theta[1..]).map(|(a, b)| a * b).sum::<f64>();
        let pi = sigmoid(t);
        let wi = pi * (1.0 - pi);
        for a in 0..d {
            g[a] += (pi - yi) * xi[a];
            let wa = wi * xi[a];
            for (hb, xb) in h[a * d..=a * d + a].iter_mut().zip(&xi[..=a]) {
                *hb += wa * xb;
            }
        }
    }
    (g, h)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cholesky_solves_a_known_system() {
        // [[4, 2], [2, 3]] x = [2, 1] has x = [0.5, 0].
        let x = cholesky_solve(&[4.0, 2.0, 2.0, 3.0], &[2.0, 1.0], 2).unwrap();
        assert!((x[0] - 0.5).abs() < 1e-15 && x[1].abs() < 1e-15);
        assert!(cholesky_solve(&[1.0, 2.0, 2.0, 1.0], &[1.0, 1.0], 2).is_none());
    }

    #[test]
    fn folds_are_stratified() {
        let labels: Vec<bool> = (0..103).map(|i| i % 3 == 0).collect();
        let fold = stratified_folds(&labels, 5, 1);
        for f in 0..5 {
            let g = (0..103).filter(|&i| fold[i] == f && labels[i]).count();
            let c = (0..103).filter(|&i| fold[i] == f && !labels[i]).count();
            // 35 gangue and 68 coal dealt into 5: 7 each, and 13 or 14.
            assert_eq!(g, 7);
            assert!((13..=14).contains(&c));
        }
    }
}
