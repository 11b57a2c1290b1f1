//! The plate against the beam at the scene's own points: per support set the beam describes,
//! the range of C_plate/C_beam - 1, of P_max and of v_y.

use super::{same_case, same_cell};
use coupled::plan::Results;
use scene::Scene;
use serde::Serialize;

/// Plate against beam at the scene's points, for one support set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PointFinding {
    /// The support set's name.
    pub condition: String,
    /// The range of C_plate/C_beam - 1 over the points where the beam's C is not 0.
    pub compliance: Option<(f64, f64)>,
    /// Those points.
    pub points: usize,
    /// The largest relative FE error of the plate's C there.
    pub fe_error: f64,
    /// Points at a supported end, where the beam's C is 0 and the ratio has no value.
    pub ends: usize,
    /// The largest plate C at those ends, m/N.
    pub ends_compliance: f64,
    /// The range of P_max,plate/P_max,beam - 1 over the cases.
    pub contact_force: Option<(f64, f64)>,
    /// Those cases.
    pub force_cases: usize,
    /// The range of v_y,plate/v_y,beam - 1 (where the scene asks for yield velocities).
    pub yield_velocity: Option<(f64, f64)>,
}

/// The range of `v`, none when it is empty.
fn range(v: &[f64]) -> Option<(f64, f64)> {
    (!v.is_empty()).then(|| v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x))))
}

/// The yield velocities' plate/beam - 1 under `condition`.
fn yield_ratios(beam: &Results, plate: &Results, condition: &str) -> Vec<f64> {
    plate
        .yields
        .iter()
        .filter(|r| r.condition == condition)
        .filter_map(|py| Some(py.values()?.yield_velocity / same_cell(beam, py)?.values()?.yield_velocity - 1.0))
        .collect()
}

/// The findings at the scene's points, one per support set the beam describes that has a
/// case both models answer.
pub fn point_findings(scene: &Scene, beam: &Results, plate: &Results) -> Vec<PointFinding> {
    let mut out = Vec::new();
    for cond in scene.conditions.iter().filter(|c| c.beam_condition().is_some()) {
        let (mut ratios, mut fe, mut ends, mut ends_c, mut forces) = (vec![], 0.0f64, 0usize, 0.0f64, vec![]);
        let mut seen: Vec<(f64, f64)> = Vec::new();
        for pr_row in plate.responses.iter().filter(|r| r.condition == cond.name) {
            let (Some(p), Some(b)) = (pr_row.values(), same_case(beam, pr_row).and_then(|b| b.values())) else {
                continue;
            };
            let (cp, cb) = (p.compliance.unwrap_or(f64::NAN), b.compliance.unwrap_or(f64::NAN));
            if !seen.contains(&(pr_row.x, pr_row.z)) {
                seen.push((pr_row.x, pr_row.z));
                if cb > 0.0 {
                    ratios.push(cp / cb - 1.0);
                    fe = fe.max(p.compliance_error.unwrap_or(0.0) / cp);
                } else {
                    ends += 1;
                    ends_c = ends_c.max(cp);
                }
            }
            if b.contact_force > 0.0 {
                forces.push(p.contact_force / b.contact_force - 1.0);
            }
        }
        if ratios.is_empty() && forces.is_empty() {
            continue;
        }
        out.push(PointFinding {
            condition: cond.name.clone(),
            compliance: range(&ratios),
            points: ratios.len(),
            fe_error: fe,
            ends,
            ends_compliance: ends_c,
            contact_force: range(&forces),
            force_cases: forces.len(),
            yield_velocity: range(&yield_ratios(beam, plate, &cond.name)),
        });
    }
    out
}
