//! The published criteria scored on the map: each trusts the quasi-static balance in some
//! cases and flags it in others, and the measured force error (within the rule's 3 % or not)
//! says whether it was right.

use super::{MapRow, Slice};
use coupled::regimes::{OlssonRegime, OLSSON_QUASI_STATIC, OLSSON_WAVE_CONTROLLED, RULE_LIMIT};
use coupled::validity::QUASI_STATIC_MIN_RATIO;
use serde::Serialize;

/// How one criterion fares on a set of cases.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Score {
    /// Cases it trusts.
    pub trusted: usize,
    /// Of them off by more than the rule's limit.
    pub trusted_wrong: usize,
    /// The largest error among them (0 if none).
    pub worst_trusted: f64,
    /// Cases it flags.
    pub flagged: usize,
    /// Of them within the rule's limit.
    pub flagged_fine: usize,
}

/// `trusts` scored on `rows`.
pub fn score<'a>(rows: impl Iterator<Item = &'a MapRow>, trusts: impl Fn(&MapRow) -> bool) -> Score {
    let mut s = Score::default();
    for r in rows {
        if trusts(r) {
            s.trusted += 1;
            s.worst_trusted = s.worst_trusted.max(r.error());
            s.trusted_wrong += usize::from(!r.quasi_static());
        } else {
            s.flagged += 1;
            s.flagged_fine += usize::from(r.quasi_static());
        }
    }
    s
}

/// A published criterion as a test of one case.
type CaseTest = Box<dyn Fn(&MapRow) -> bool>;

/// The criteria set beside the measured error, each as a test of one case.
fn criteria() -> Vec<(&'static str, CaseTest)> {
    vec![
        ("Olsson: large mass, M_i/M_p > 2", Box::new(|r: &MapRow| r.mass_ratio > OLSSON_QUASI_STATIC)),
        ("Olsson: not small mass, M_i/M_p ≥ 0.23", Box::new(|r: &MapRow| r.mass_ratio >= OLSSON_WAVE_CONTROLLED)),
        (
            "t_H/T₁ ≥ 0.2 (T₁ from the plate FE; the validity status)",
            Box::new(|r: &MapRow| r.period_ratio() >= QUASI_STATIC_MIN_RATIO),
        ),
        (
            "Christoforou and Yigit: B ≤ 3 % (ζ < 1)",
            Box::new(|r: &MapRow| r.rule.parameters.error_bound() <= RULE_LIMIT && r.rule.parameters.loss_factor < 1.0),
        ),
        ("the closed-form rule", Box::new(|r: &MapRow| r.rule.trusts())),
        (
            "the validity status: t_H/T₁ ≥ 0.2 and the rule",
            Box::new(|r: &MapRow| r.period_ratio() >= QUASI_STATIC_MIN_RATIO && r.rule.trusts()),
        ),
    ]
}

/// One criterion on the centre cases and at the scene's points.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CriterionScore {
    /// The criterion, in words.
    pub criterion: String,
    /// On the centre cases.
    pub centre: Score,
    /// At the scene's points.
    pub points: Score,
}

impl CriterionScore {
    /// Its score on `slice`.
    pub fn on(&self, slice: Slice) -> &Score {
        match slice {
            Slice::Centre => &self.centre,
            Slice::Points => &self.points,
        }
    }
}

/// Every criterion scored on both slices.
pub(super) fn criteria_scores(rows: &[MapRow]) -> Vec<CriterionScore> {
    criteria()
        .into_iter()
        .map(|(name, trusts)| CriterionScore {
            criterion: name.into(),
            centre: score(rows.iter().filter(|r| r.slice == Slice::Centre), &trusts),
            points: score(rows.iter().filter(|r| r.slice == Slice::Points), &trusts),
        })
        .collect()
}

/// One of Olsson's regimes against the measured error (centre cases).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OlssonRow {
    /// The regime.
    pub regime: OlssonRegime,
    /// Cases in it.
    pub cases: usize,
    /// Of them within the rule's limit.
    pub within: usize,
    /// The largest and smallest error (None without cases).
    pub largest: Option<f64>,
    /// The smallest.
    pub smallest: Option<f64>,
    /// Cases with repeated contacts.
    pub repeated: usize,
}

/// Olsson's three regimes against the measured error.
pub(super) fn olsson_rows(rows: &[MapRow]) -> Vec<OlssonRow> {
    [OlssonRegime::WaveControlled, OlssonRegime::Mixed, OlssonRegime::QuasiStatic]
        .into_iter()
        .map(|regime| {
            let of: Vec<&MapRow> =
                rows.iter().filter(|r| r.slice == Slice::Centre && OlssonRegime::of(r.mass_ratio) == regime).collect();
            let errors = of.iter().map(|r| r.error());
            let any = !of.is_empty();
            OlssonRow {
                regime,
                cases: of.len(),
                within: of.iter().filter(|r| r.quasi_static()).count(),
                largest: any.then(|| errors.clone().fold(0.0, f64::max)),
                smallest: any.then(|| errors.fold(f64::INFINITY, f64::min)),
                repeated: of.iter().filter(|r| r.measured.contacts > 1).count(),
            }
        })
        .collect()
}

/// The rule at one of the scene's points.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PointScore {
    /// The point (x, z), m.
    pub point: (f64, f64),
    /// Cases there.
    pub cases: usize,
    /// Of them within the rule's limit.
    pub within: usize,
    /// The closed-form rule there.
    pub rule: Score,
    /// Cases with repeated contacts.
    pub repeated: usize,
}

/// The points slice, point by point: how the rule fares there.
pub(super) fn point_scores(rows: &[MapRow]) -> Vec<PointScore> {
    let of: Vec<&MapRow> = rows.iter().filter(|r| r.slice == Slice::Points).collect();
    let mut points: Vec<(f64, f64)> = Vec::new();
    for r in &of {
        if !points.contains(&r.point) {
            points.push(r.point);
        }
    }
    points
        .into_iter()
        .map(|p| {
            let here: Vec<&&MapRow> = of.iter().filter(|r| r.point == p).collect();
            PointScore {
                point: p,
                cases: here.len(),
                within: here.iter().filter(|r| r.quasi_static()).count(),
                rule: score(here.iter().map(|r| **r), |r| r.rule.trusts()),
                repeated: here.iter().filter(|r| r.measured.contacts > 1).count(),
            }
        })
        .collect()
}
