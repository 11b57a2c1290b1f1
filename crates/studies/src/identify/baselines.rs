//! What a signal feature has to beat: the trivial baselines. A sensor is worth its cost only
//! where it separates coal from gangue better than what needs no sensor at all: the lump's
//! mass (a scale under the hopper), or the contact itself, its duration t_c and its peak force
//! P_max (the paper's quantities, which a force cell under the plate would give). Each is
//! scored as a feature is (ROC AUC, DeLong's error, a percentile bootstrap interval; the mass
//! at a 1 % resolution, [`MASS_RESOLUTION`]), and the set's headline compares the best signal
//! feature with the best of them.
//!
//! Separation is max(AUC, 1 - AUC): a threshold works in either direction. A baseline
//! "already separates" the classes when its separation reaches [`SEPARATES`]; a feature's
//! gain over the best baseline is "resolved" when the lower end of the feature's interval
//! lies above the upper end of the baseline's (both as separations), the conservative test of
//! two intervals that do not overlap.

use super::separability::split;
use super::Ranked;
use coupled::identification::ConditionRun;
use identify::roc::{auc_within, bootstrap_interval_within, Auc, BOOTSTRAP_RESAMPLES};
use serde::Serialize;

/// The separation at and above which a threshold on one quantity misorders fewer than 1 % of
/// coal-gangue pairs: that quantity alone separates the classes.
pub const SEPARATES: f64 = 0.99;

/// One baseline quantity, scored as a feature is.
#[derive(Debug, Clone, Serialize)]
pub struct Baseline {
    /// What it is, e.g. "contact time t_c".
    pub quantity: &'static str,
    /// AUC (P(gangue > coal)) with DeLong's standard error.
    pub auc: Auc,
    /// The 95 % percentile bootstrap interval of the AUC.
    pub interval: (f64, f64),
}

impl Baseline {
    /// max(AUC, 1 - AUC) and its interval in the same orientation.
    pub fn separation(&self) -> (f64, (f64, f64)) {
        oriented(self.auc.auc, self.interval)
    }
}

/// An AUC and its interval as a separation, max(AUC, 1 - AUC), with the interval mapped the
/// same way (an AUC below ½ reads as 1 - AUC, its interval (1 - hi, 1 - lo)).
pub fn oriented(auc: f64, (lo, hi): (f64, f64)) -> (f64, (f64, f64)) {
    if auc >= 0.5 {
        (auc, (lo, hi))
    } else {
        (1.0 - auc, (1.0 - hi, 1.0 - lo))
    }
}

/// What the best signal feature adds over the best baseline.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// The best baseline alone separates the classes ([`SEPARATES`]); a signal can add little.
    BaselineSeparates,
    /// The best feature separates better, beyond both intervals.
    FeatureAdds,
    /// The intervals overlap: no resolved gain over the baseline.
    NoResolvedGain,
    /// The best baseline separates better than the best feature, beyond both intervals.
    BaselineBetter,
}

/// The best signal feature against the baselines.
#[derive(Debug, Clone, Serialize)]
pub struct Headline {
    /// Contact time, P_max and mass, in that order.
    pub baselines: Vec<Baseline>,
    /// The feature compared, "feature channel": the most separating one whose AUC the modal
    /// truncation does not move (a number the model resolves), else the most separating one.
    pub feature: String,
    /// Whether that feature is resolved by the model (its AUC moves between N/2 and N modes
    /// by less than its sampling error).
    pub resolved: bool,
    /// The index of the most separating baseline.
    pub best_baseline: usize,
    /// The best feature's separation minus the best baseline's.
    pub gain: f64,
    /// What that gain means.
    pub verdict: Verdict,
}

/// The relative resolution at which lump masses are compared: masses within 1 % are ties.
/// Rank statistics separate any two distinct numbers, and the paper's gangue 1 has coal's mass
/// to 6 digits; a mass that separates only below what weighing single lumps resolves does not
/// separate.
pub const MASS_RESOLUTION: f64 = 0.01;

/// The mass baseline of `run` at [`MASS_RESOLUTION`] ([`auc_within`] on ln m), its bootstrap
/// stream from `seed` (the set calls it with `seed ^ 300`, apart from the streams of the
/// features, classifiers and variability runs). DeLong's error has no form for ties within a
/// tolerance; the standard error given is the bootstrap interval's half-width over 1.96.
pub fn mass(run: &ConditionRun, seed: u64) -> Baseline {
    let (c, g) = split(&run.mass, run.table.classes());
    let (c, g): (Vec<f64>, Vec<f64>) = (c.iter().map(|m| m.ln()).collect(), g.iter().map(|m| m.ln()).collect());
    let tolerance = MASS_RESOLUTION.ln_1p();
    let interval = bootstrap_interval_within(&c, &g, tolerance, (BOOTSTRAP_RESAMPLES, super::LEVEL), seed);
    Baseline {
        quantity: "lump mass m",
        auc: Auc { auc: auc_within(&c, &g, tolerance), standard_error: (interval.1 - interval.0) / (2.0 * 1.96) },
        interval,
    }
}

/// A contact quantity already scored as a feature, as a baseline.
pub fn of_ranked(quantity: &'static str, r: &Ranked) -> Baseline {
    Baseline { quantity, auc: r.auc, interval: r.interval }
}

/// The headline of a set: `best` the most separating signal feature, `converged` the most
/// separating one the model resolves (None without one). A feature the modal truncation
/// moves cannot carry a claim, so the resolved one is compared where the best is not.
pub fn headline(baselines: Vec<Baseline>, best: Option<&Ranked>, converged: Option<&Ranked>) -> Headline {
    let best = match best {
        Some(b) if b.converged() => Some(b),
        _ => converged.or(best),
    };
    let best_baseline = (0..baselines.len())
        .max_by(|&a, &b| baselines[a].separation().0.total_cmp(&baselines[b].separation().0))
        .unwrap_or(0);
    let (base, (base_lo, base_hi)) = baselines.get(best_baseline).map_or((0.5, (0.5, 0.5)), Baseline::separation);
    let (feature, (lo, hi)) = best.map_or((0.5, (0.5, 0.5)), |r| oriented(r.auc.auc, r.interval));
    let verdict = if base >= SEPARATES {
        Verdict::BaselineSeparates
    } else if lo > base_hi {
        Verdict::FeatureAdds
    } else if base_lo > hi {
        Verdict::BaselineBetter
    } else {
        Verdict::NoResolvedGain
    };
    Headline {
        baselines,
        feature: best.map_or_else(String::new, |r| format!("{} {}", r.feature.name(), r.channel)),
        resolved: best.is_some_and(Ranked::converged),
        best_baseline,
        gain: feature - base,
        verdict,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn baseline(auc: f64, interval: (f64, f64)) -> Baseline {
        Baseline { quantity: "q", auc: Auc { auc, standard_error: 0.01 }, interval }
    }

    #[test]
    fn an_auc_below_a_half_reads_as_its_mirror() {
        let (s, (lo, hi)) = oriented(0.2, (0.15, 0.25));
        assert!((s - 0.8).abs() < 1e-15 && (lo - 0.75).abs() < 1e-15 && (hi - 0.85).abs() < 1e-15);
    }

    /// A perfectly reversed baseline (AUC 0, as contact time is for gangue, which is stiffer
    /// and so shorter in contact) separates perfectly.
    #[test]
    fn a_reversed_perfect_baseline_separates() {
        let h = headline(vec![baseline(0.7, (0.65, 0.75)), baseline(0.0, (0.0, 0.0))], None, None);
        assert_eq!((h.best_baseline, h.verdict), (1, Verdict::BaselineSeparates));
    }

    /// The verdict follows the intervals: apart and above, apart and below, overlapping.
    #[test]
    fn the_verdict_reads_the_intervals() {
        let feature = |auc: f64, interval: (f64, f64)| {
            let mut r = super::super::separability::ranked(
                "c".into(),
                identify::features::FEATURES[0],
                (&[0.0, 1.0], &[0.5, 2.0]),
                None,
                1,
            );
            r.auc.auc = auc;
            r.interval = interval;
            r
        };
        let base = || vec![baseline(0.3, (0.25, 0.35)), baseline(0.6, (0.55, 0.65))];
        let adds = headline(base(), Some(&feature(0.9, (0.85, 0.95))), None);
        assert_eq!((adds.best_baseline, adds.verdict), (0, Verdict::FeatureAdds));
        assert!((adds.gain - 0.2).abs() < 1e-12);
        // A feature with AUC 0.2 separates as 0.8: against a baseline of 0.7, within reach.
        let near = headline(base(), Some(&feature(0.27, (0.22, 0.32))), None);
        assert_eq!(near.verdict, Verdict::NoResolvedGain);
        let worse = headline(base(), Some(&feature(0.55, (0.5, 0.6))), None);
        assert_eq!(worse.verdict, Verdict::BaselineBetter);
    }
}
