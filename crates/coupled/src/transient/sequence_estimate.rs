//! Error estimates for the whole impact: every contact's start, duration, peak force and
//! impulse, the final velocity and the total impulse, from the same five levels as the first
//! contact's estimate ([`mod@super::estimate`]: (n, N), (n, 2N), (n, N/2), (2n, N) and (n/2, N)),
//! each run followed through every contact.
//!
//! Contact k of one level is compared with contact k of the others. Where a level has a
//! different number of contacts (a grazing re-contact that appears or vanishes with h or Δt),
//! the contacts beyond the fewest are not estimated and say so (`error` None), and the final
//! velocity and total impulse, which then differ by a whole contact's impulse, are not
//! estimated either: no number is invented for a contact that does not exist on every level.

use super::estimate::{richardson, sum, Components};
use super::{Contact, Outcome, Sample};
use serde::Serialize;

/// What one contact of the sequence is, as the estimate compares it across levels.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactValues {
    /// When δ became positive, s.
    pub start: f64,
    /// How long δ stayed positive, s.
    pub duration: f64,
    /// The largest force, N: on the first contact's in-step interpolant for the first, the
    /// vertex of the parabola through the largest sample and its neighbours for a later one
    /// (both O(Δt²), where the largest sample is O(Δt)).
    pub peak_force: f64,
    /// ∫P dt, N·s.
    pub impulse: f64,
}

impl Components for ContactValues {
    fn to_list(self) -> Vec<f64> {
        vec![self.start, self.duration, self.peak_force, self.impulse]
    }
    fn from_list(l: &[f64]) -> Self {
        Self { start: l[0], duration: l[1], peak_force: l[2], impulse: l[3] }
    }
}

/// The end of the impact: the sphere's final velocity (m/s) and the total impulse (N·s).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EndValues {
    /// Sphere velocity at the end of the run, m/s.
    pub final_velocity: f64,
    /// The sum of the contacts' impulses, N·s.
    pub total_impulse: f64,
}

impl Components for EndValues {
    fn to_list(self) -> Vec<f64> {
        vec![self.final_velocity, self.total_impulse]
    }
    fn from_list(l: &[f64]) -> Self {
        Self { final_velocity: l[0], total_impulse: l[1] }
    }
}

/// One contact and its estimated absolute errors.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactEstimate {
    /// The values, from the (n, N) run.
    pub values: ContactValues,
    /// Their estimated absolute errors (Richardson in Δt plus in h, with the safety factor of
    /// [`super::estimate::SAFETY`]); None where some level has no such contact.
    pub error: Option<ContactValues>,
}

/// The whole impact with its error estimates.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SequenceEstimate {
    /// Every completed contact in order, the first included.
    pub contacts: Vec<ContactEstimate>,
    /// The final velocity and total impulse.
    pub end: EndValues,
    /// Their estimated absolute errors; None where the levels' contact counts differ.
    pub end_error: Option<EndValues>,
    /// The completed contacts on each level: (n, N), (n, 2N), (n, N/2), (2n, N), (n/2, N)
    /// (the last where there is a coarser mesh).
    pub counts: Vec<usize>,
}

impl SequenceEstimate {
    /// Whether the number of contacts changes between the estimate's levels: the count is
    /// then not a converged property of the impact.
    pub fn count_changes(&self) -> bool {
        self.counts.iter().any(|&c| c != self.counts[0])
    }
}

/// Every contact of a run with its peak interpolated ([`ContactValues::peak_force`]).
pub fn contact_values(o: &Outcome) -> Vec<ContactValues> {
    let samples: Vec<&Sample> = o.history.iter().chain(&o.later_history).collect();
    o.contacts
        .iter()
        .enumerate()
        .map(|(k, c)| ContactValues {
            start: c.start,
            duration: c.duration,
            peak_force: if k == 0 { o.force_max_interpolated } else { parabolic_peak(&samples, c) },
            impulse: c.impulse,
        })
        .collect()
}

/// The vertex of the parabola through the largest sampled force of contact `c` and its two
/// neighbours (equally spaced in time); the largest sample itself where it has no two
/// neighbours or the three do not bend down.
fn parabolic_peak(samples: &[&Sample], c: &Contact) -> f64 {
    let end = c.start + c.duration;
    let inside: Vec<usize> = (0..samples.len()).filter(|&i| samples[i].t >= c.start && samples[i].t <= end).collect();
    let Some(&k) = inside.iter().max_by(|&&a, &&b| samples[a].force.total_cmp(&samples[b].force)) else {
        return c.peak_force;
    };
    if k == 0 || k + 1 >= samples.len() {
        return samples[k].force;
    }
    let (y0, y1, y2) = (samples[k - 1].force, samples[k].force, samples[k + 1].force);
    let curvature = y0 - 2.0 * y1 + y2;
    if curvature >= 0.0 {
        return y1;
    }
    // Vertex at offset p = (y0 - y2)/(2 curvature) steps from the middle sample, |p| ≤ 1/2.
    let p = (y0 - y2) / (2.0 * curvature);
    y1 - 0.25 * (y0 - y2) * p
}

/// The end values of a run.
fn end_of(o: &Outcome) -> EndValues {
    EndValues { final_velocity: o.final_velocity, total_impulse: o.total_impulse }
}

/// The estimate from the five runs: `o` (n, N), `dt` its (n, 2N) and (n, N/2), `h` its
/// (2n, N) and (n/2, N) where there is a coarser mesh.
pub fn sequence_estimate(
    o: &Outcome,
    (fine_dt, coarse_dt): (&Outcome, &Outcome),
    (fine_h, coarse_h): (&Outcome, Option<&Outcome>),
) -> SequenceEstimate {
    let levels: Vec<Vec<ContactValues>> = [Some(o), Some(fine_dt), Some(coarse_dt), Some(fine_h), coarse_h]
        .into_iter()
        .flatten()
        .map(contact_values)
        .collect();
    let counts: Vec<usize> = levels.iter().map(Vec::len).collect();
    let everywhere = counts.iter().copied().min().unwrap_or(0);
    let error_of = |k: usize| -> ContactValues {
        let at = |level: usize| levels[level][k];
        let time = richardson(at(0), at(1), Some(at(2))).1;
        let mesh = richardson(at(0), at(3), coarse_h.map(|_| at(4))).1;
        sum(time, mesh)
    };
    let contacts = (0..counts[0])
        .map(|k| ContactEstimate { values: levels[0][k], error: (k < everywhere).then(|| error_of(k)) })
        .collect();
    let same = counts.iter().all(|&c| c == counts[0]);
    let end_error = same.then(|| {
        let time = richardson(end_of(o), end_of(fine_dt), Some(end_of(coarse_dt))).1;
        let mesh = richardson(end_of(o), end_of(fine_h), coarse_h.map(end_of)).1;
        sum(time, mesh)
    });
    SequenceEstimate { contacts, end: end_of(o), end_error, counts }
}
