//! The statistics of `identify` against answers known without it: identical and disjoint
//! classes, the AUC of two normal populations in closed form, a logistic model with known
//! coefficients, and bit-identical ensembles on one and two threads.

use identify::classify::{cross_validate, Logistic};
use identify::distribution::{phi, Distribution};
use identify::ensemble::{for_each_ordered, impact_stream, open_uniform, Class, Ensemble, Family, Held, Region, Speed};
use identify::features::Extractor;
use identify::placement::{separabilities, FeatureTable};
use identify::roc::{auc, auc_with_error, bootstrap_interval};

/// `n` draws of N(mean, sd²) from the stream (seed, stream).
fn normals(mean: f64, sd: f64, n: usize, seed: u64, stream: usize) -> Vec<f64> {
    let d = Distribution::Normal { mean, sd, min: mean - 40.0 * sd, max: mean + 40.0 * sd };
    let mut rng = impact_stream(seed, stream);
    (0..n).map(|_| d.quantile(open_uniform(&mut rng))).collect()
}

#[test]
fn identical_classes_give_one_half_inside_the_interval() {
    // Coal and gangue drawn from the same law: the true AUC is ½. A 95 % interval must
    // cover it in about 95 % of 40 independent ensembles: the count covered is binomial
    // (40, 0.95), mean 38 and standard deviation 1.4, so fewer than 34 would say the
    // interval is too narrow (3 standard deviations).
    let mut covered = 0;
    for s in 0..40 {
        let coal = normals(0.0, 1.0, 150, 100 + s, 0);
        let gangue = normals(0.0, 1.0, 150, 100 + s, 1);
        let (lo, hi) = bootstrap_interval(&coal, &gangue, 1000, 0.95, s);
        assert!(lo < hi);
        if lo <= 0.5 && 0.5 <= hi {
            covered += 1;
        }
    }
    assert!(covered >= 34, "{covered} of 40 intervals cover 0.5");
}

#[test]
fn disjoint_classes_give_one() {
    let coal = normals(0.0, 1.0, 200, 1, 0);
    let gangue: Vec<f64> = normals(0.0, 1.0, 200, 1, 1).iter().map(|v| v + 100.0).collect();
    assert_eq!(auc(&coal, &gangue), 1.0);
    assert_eq!(bootstrap_interval(&coal, &gangue, 500, 0.95, 3), (1.0, 1.0));
    // And reversed, 0: a perfect separation the other way round.
    assert_eq!(auc(&gangue, &coal), 0.0);
}

#[test]
fn auc_of_two_normals_is_the_closed_form_within_its_error() {
    // X ~ N(0, 1), Y ~ N(0.8, 1.5²): AUC = P(Y > X) = Φ(0.8/√(1 + 2.25)) = 0.6716. Over 60
    // independent ensembles of 300 + 300, the mean AUC must lie within 3 standard errors of
    // the mean of it, and DeLong's error must describe the spread between ensembles (its
    // mean within 15 % of their standard deviation: the sampling error of a standard
    // deviation from 60 values is 1/√(2·59) = 9 %).
    let exact = phi(0.8 / (1.0f64 + 2.25).sqrt());
    let mut aucs = Vec::new();
    let mut ses = Vec::new();
    for s in 0..60 {
        let a = auc_with_error(&normals(0.0, 1.0, 300, 500 + s, 0), &normals(0.8, 1.5, 300, 500 + s, 1));
        aucs.push(a.auc);
        ses.push(a.standard_error);
    }
    let n = aucs.len() as f64;
    let mean = aucs.iter().sum::<f64>() / n;
    let sd = (aucs.iter().map(|a| (a - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    let se_mean = ses.iter().sum::<f64>() / n;
    assert!((mean - exact).abs() < 3.0 * sd / n.sqrt(), "mean {mean} vs {exact} (sd {sd})");
    assert!((se_mean / sd - 1.0).abs() < 0.15, "DeLong {se_mean} vs spread {sd}");
}

#[test]
fn logistic_regression_finds_known_coefficients() {
    // y ~ Bernoulli(σ(0.5 + 1.5x₁ - 2x₂)), x ~ N(0, 1)², n = 20000. The maximum-likelihood
    // coefficients' standard errors here are about 0.03 (inverse Fisher information
    // n·E[p(1-p)xxᵀ]); the ridge of 1 shifts them by about λ/n·β relative, 1e-4. Within 0.12
    // is four standard errors. The fit is on standardised columns: β = w/sd,
    // b = intercept - Σ w·mean/sd.
    let n = 20000;
    let x1 = normals(0.0, 1.0, n, 9, 0);
    let x2 = normals(0.0, 1.0, n, 9, 1);
    let mut rng = impact_stream(9, 2);
    let truth = |a: f64, b: f64| 1.0 / (1.0 + (-(0.5 + 1.5 * a - 2.0 * b)).exp());
    let labels: Vec<bool> = (0..n).map(|i| open_uniform(&mut rng) < truth(x1[i], x2[i])).collect();
    let rows: Vec<Vec<f64>> = (0..n).map(|i| vec![x1[i], x2[i]]).collect();
    let m = Logistic::fit(&rows, &labels, &[false, false], 1.0).unwrap();
    let beta: Vec<f64> = m.weights.iter().zip(&m.columns).map(|(w, c)| w / c.sd).collect();
    let b = m.intercept - m.weights.iter().zip(&m.columns).map(|(w, c)| w * c.mean / c.sd).sum::<f64>();
    assert!((beta[0] - 1.5).abs() < 0.12 && (beta[1] + 2.0).abs() < 0.12 && (b - 0.5).abs() < 0.12, "{b} {beta:?}");
    assert!(m.iterations < 20);
    // The cross-validated accuracy is that of the Bayes rule with the true coefficients,
    // E[max(p, 1-p)], to within its binomial error (three standard errors, 0.009).
    let bayes = (0..n).map(|i| truth(x1[i], x2[i])).map(|p| p.max(1.0 - p)).sum::<f64>() / n as f64;
    let cv = cross_validate(&rows, &labels, &[false, false], 1.0, 5, 4).unwrap();
    assert!((cv.accuracy - bayes).abs() < 3.0 * cv.standard_error, "{} vs {bayes}", cv.accuracy);
}

#[test]
fn logistic_regression_separates_separable_classes() {
    // Classes 10 standard deviations apart on one of three features: every held-out impact
    // is right, and the ridge keeps the weights finite.
    let n = 200;
    let noise = normals(0.0, 1.0, 3 * n, 5, 0);
    let labels: Vec<bool> = (0..n).map(|i| i % 2 == 1).collect();
    let rows: Vec<Vec<f64>> = (0..n)
        .map(|i| vec![noise[3 * i], noise[3 * i + 1] + if labels[i] { 10.0 } else { 0.0 }, noise[3 * i + 2]])
        .collect();
    let cv = cross_validate(&rows, &labels, &[false; 3], 1.0, 5, 1).unwrap();
    assert_eq!(cv.accuracy, 1.0);
    let m = Logistic::fit(&rows, &labels, &[false; 3], 1.0).unwrap();
    assert!(m.weights.iter().all(|w| w.is_finite()) && m.weights[1] > 0.0);
}

fn ensemble() -> Ensemble {
    let fam = |name: &str, class, density: f64| Family {
        name: name.into(),
        class,
        count: 300,
        density: Distribution::Normal { mean: density, sd: 100.0, min: density - 400.0, max: density + 400.0 },
        youngs_modulus: Distribution::LogNormal { median: 5e9, sigma_log: 0.5, min: 1e9, max: 3e10 },
        poisson_ratio: Distribution::Fixed { value: 0.28 },
        cohesion: Distribution::Fixed { value: 8.39e6 },
        friction_angle_deg: Distribution::Fixed { value: 25.0 },
        radius: Distribution::RosinRammler { scale: 0.03, shape: 2.0, min: 0.01, max: 0.08 },
    };
    Ensemble {
        region: Region { x: (0.0, 0.4584), z: (0.0, 0.36) },
        speed: Speed::FallHeight(Distribution::LogNormal { median: 1.0, sigma_log: 0.5, min: 0.1, max: 3.0 }),
        families: vec![fam("coal", Class::Coal, 1380.0), fam("gangue", Class::Gangue, 2400.0)],
        seed: 2024,
    }
}

/// The ensemble through a stand-in signal (a decaying tone whose amplitude, frequency and
/// decay depend on every drawn variable), features and AUCs on a pool of `threads`.
fn run_on(threads: usize) -> (Vec<u64>, Vec<u64>) {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| {
        let e = ensemble();
        let rate = 40_000.0;
        let ex = Extractor::new(800, rate);
        let mut table = FeatureTable::new(2);
        let mut bits = Vec::new();
        for_each_ordered(
            e.len(),
            64,
            |i| {
                let d = e.draw(i, Held::NONE).unwrap();
                let f0 = 200.0 + 2000.0 * d.x + 1e-7 * d.youngs_modulus.sqrt();
                let signal: Vec<f64> = (0..800)
                    .map(|k| {
                        let t = k as f64 / rate;
                        d.density
                            * d.radius.powi(3)
                            * d.velocity
                            * (-t / (0.002 + d.z)).exp()
                            * (std::f64::consts::TAU * f0 * t).sin()
                    })
                    .collect();
                let spring: Vec<f64> = signal.iter().map(|v| v * v).collect();
                (d.class, [ex.features(&signal), ex.features(&spring)].concat())
            },
            |_, (class, f)| {
                bits.extend(f.iter().copied().map(f64::to_bits));
                table.push(class, &f);
                Ok::<(), ()>(())
            },
        )
        .unwrap();
        let aucs = separabilities(&table).iter().map(|s| s.auc.auc.to_bits()).collect();
        (bits, aucs)
    })
}

#[test]
fn ensemble_is_bit_identical_on_one_and_two_threads() {
    let (one, auc_one) = run_on(1);
    let (two, auc_two) = run_on(2);
    assert_eq!(one.len(), 600 * 2 * identify::FEATURES.len());
    assert!(one == two, "features differ between 1 and 2 threads");
    assert!(auc_one == auc_two);
}
