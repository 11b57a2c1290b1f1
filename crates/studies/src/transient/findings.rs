//! The numbers the transient study's findings quote: over the cases, how many were struck
//! more than once, ended outside their window, went beyond the elastic range or the
//! tolerance; the regime rule against the measured quasi-static error; per body, the range of
//! t_c/T₁, of that error and of the plate's share of the energy.

use super::cases::{contact_count, median, TransientCase};
use coupled::regimes::{OlssonRegime, RULE_LIMIT};
use coupled::transient::Discretisation;
use scene::Scene;
use serde::Serialize;

/// The counts behind the findings, as `findings.json` lists them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Numbers {
    /// Cases.
    pub cases: usize,
    /// The smallest and largest quasi-static force error (transient/QS plate - 1).
    pub quasi_static_force_error: (f64, f64),
    /// Cases with more than one contact.
    pub struck_more_than_once: usize,
    /// The most contacts of any case (1 if none is struck again).
    pub most_contacts: usize,
    /// Cases whose sphere had not provably left at the end of the window.
    pub unfinished_in_window: usize,
    /// Cases beyond δ_my under an elastic law.
    pub beyond_elastic_with_elastic_law: usize,
    /// The largest relative error estimate on P_max and t_c.
    pub largest_relative_error_estimate: f64,
    /// The tolerance the cases were run to; `None` for a fixed discretisation.
    pub tolerance: Option<f64>,
    /// Cases whose estimate is above the tolerance.
    pub above_tolerance: usize,
    /// The median wall-clock time of a case, s.
    pub median_seconds_per_case: Option<f64>,
    /// Cases the closed-form rule trusts as quasi-static.
    pub rule_trusts: usize,
    /// Of them, cases whose measured error is beyond the rule's limit.
    pub rule_trusts_wrongly: usize,
    /// Cases the rule flags although their error is within the limit.
    pub rule_flags_needlessly: usize,
    /// Cases in Olsson's wave-controlled regime.
    pub olsson_wave_controlled: usize,
}

/// The case struck again hardest, against its own first contact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Recontact {
    /// Its index in the cases.
    pub case: usize,
    /// The largest peak force of its later contacts, N.
    pub later_peak: f64,
    /// Its first contact's peak force on the interpolant, N.
    pub first_peak: f64,
}

/// One body's ranges over its cases (min, max; NaN where a contact had not ended is passed
/// over).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BodyRanges {
    /// The body's name.
    pub body: String,
    /// t_c/T₁.
    pub contact_ratio: (f64, f64),
    /// Transient/QS plate P_max - 1.
    pub force_error: (f64, f64),
    /// The transient plate energy at δ_max over E₀.
    pub plate_energy: (f64, f64),
    /// The quasi-static plate's share of E₀.
    pub quasi_static_plate_energy: (f64, f64),
}

/// Everything the findings and the sections' prose quote.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Findings {
    /// The counts of `findings.json`.
    pub numbers: Numbers,
    /// The case struck again hardest, if any was struck again.
    pub hardest_recontact: Option<Recontact>,
    /// The largest δ_max/δ_my of the cases beyond the elastic range (0 if none is).
    pub worst_beyond_elastic: f64,
    /// The slowest case, s.
    pub slowest_seconds: f64,
    /// Cases that did not reach the tolerance within the budget.
    pub not_met: usize,
    /// The finest mesh any case needed, elements along the longer side.
    pub finest_elements: usize,
    /// Cases with δ_max beyond δ_my.
    pub beyond_yield: usize,
    /// Per body of the scene with cases, in the scene's order.
    pub bodies: Vec<BodyRanges>,
}

/// The later contact that strikes hardest against its own first contact: (later peak, first).
fn later(c: &TransientCase) -> (f64, f64) {
    let o = c.outcome();
    let first = o.force_max_interpolated;
    let peak = o.contacts.iter().chain(&o.unfinished_contact).skip(1).map(|k| k.peak_force).fold(0.0, f64::max);
    (peak, first)
}

/// The findings' numbers over `cases` of `scene`.
pub fn findings(scene: &Scene, cases: &[TransientCase]) -> Findings {
    let repeated: Vec<usize> = (0..cases.len()).filter(|&i| contact_count(cases[i].outcome()) > 1).collect();
    let hardest_recontact = repeated
        .iter()
        .copied()
        .max_by(|&a, &b| {
            let (pa, fa) = later(&cases[a]);
            let (pb, fb) = later(&cases[b]);
            (pa / fa).total_cmp(&(pb / fb))
        })
        .map(|case| {
            let (later_peak, first_peak) = later(&cases[case]);
            Recontact { case, later_peak, first_peak }
        });
    let beyond: Vec<f64> =
        cases.iter().filter_map(|c| c.validity.elastic.filter(|e| !e.valid).map(|e| e.value)).collect();
    let secs: Vec<f64> = cases.iter().map(|c| c.seconds).collect();
    let tolerance = match scene.transient_discretisation {
        Discretisation::Tolerance { tolerance, .. } => Some(tolerance),
        Discretisation::Fixed { .. } => None,
    };
    let trusted = |c: &&TransientCase| c.rule.trusts();
    let within = |c: &&TransientCase| c.force_error().abs() <= RULE_LIMIT;
    let force_errors = cases
        .iter()
        .map(|c| c.force_error())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), e| (a.min(e), b.max(e)));
    let numbers = Numbers {
        cases: cases.len(),
        quasi_static_force_error: force_errors,
        struck_more_than_once: repeated.len(),
        most_contacts: repeated.iter().map(|&i| contact_count(cases[i].outcome())).max().unwrap_or(1),
        unfinished_in_window: cases.iter().filter(|c| c.outcome().left_at.is_none()).count(),
        beyond_elastic_with_elastic_law: beyond.len(),
        largest_relative_error_estimate: cases.iter().map(|c| c.estimate.relative_error()).fold(0.0, f64::max),
        tolerance,
        above_tolerance: cases.iter().filter(|c| c.validity.discretisation.is_some_and(|d| !d.valid)).count(),
        median_seconds_per_case: median(&secs),
        rule_trusts: cases.iter().filter(trusted).count(),
        rule_trusts_wrongly: cases.iter().filter(|c| trusted(c) && !within(c)).count(),
        rule_flags_needlessly: cases.iter().filter(|c| !trusted(c) && within(c)).count(),
        olsson_wave_controlled: cases
            .iter()
            .filter(|c| OlssonRegime::of(c.mass_ratio) == OlssonRegime::WaveControlled)
            .count(),
    };
    Findings {
        numbers,
        hardest_recontact,
        worst_beyond_elastic: beyond.iter().copied().fold(0.0, f64::max),
        slowest_seconds: secs.iter().copied().fold(0.0, f64::max),
        not_met: cases.iter().filter(|c| !c.estimate.met_tolerance).count(),
        finest_elements: cases.iter().map(|c| c.estimate.elements).max().unwrap_or(0),
        beyond_yield: cases.iter().filter(|c| c.yield_ratio > 1.0).count(),
        bodies: body_ranges(scene, cases),
    }
}

/// Per body: the range of the quasi-static error, of t_c/T₁ and of the energy shares over the
/// body's cases; a body without cases has no range and is left out.
fn body_ranges(scene: &Scene, cases: &[TransientCase]) -> Vec<BodyRanges> {
    let mut out = Vec::new();
    for body in &scene.bodies {
        let of_body: Vec<&TransientCase> = cases.iter().filter(|c| c.body == body.name).collect();
        if of_body.is_empty() {
            continue;
        }
        // A t_c/T₁ of a contact that did not end is NaN, which min and max pass over.
        let range = |f: &dyn Fn(&TransientCase) -> f64| {
            of_body.iter().map(|c| f(c)).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)))
        };
        out.push(BodyRanges {
            body: body.name.clone(),
            contact_ratio: range(&|c| c.contact_ratio().unwrap_or(f64::NAN)),
            force_error: range(&|c| c.force_error()),
            plate_energy: range(&|c| c.plate_energy),
            quasi_static_plate_energy: range(&|c| c.quasi_static_plate_energy),
        });
    }
    out
}
