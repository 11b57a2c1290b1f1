//! The paper's conclusions (section V, items 1-5) tested under the beam and the plate FE
//! model, on the paper's scene along the centreline and the free edge, with the numbers
//! behind each verdict.

use super::line::{both, Extremes, Line};
use crate::paper::Paper;
use crate::settings::AREAS;
use crate::Failure;
use analytic::{respond, Condition};
use coupled::plan::impact_of;
use coupled::{BeamModel, ComplianceModel, PlateModel};
use scene::{Scene, SupportSet};
use serde::Serialize;

/// The spring stiffnesses of item 3 (Con 2), N/m.
pub const STIFFNESSES: [f64; 3] = [5e4, 2.50025e8, 5e8];
/// The plate lengths of item 4, as multiples of the paper's L.
pub const LENGTH_FACTORS: [f64; 4] = [0.8, 1.0, 1.2, 1.4];
/// The impact point of item 4, m from the left end (the same for every length).
pub const LENGTH_POINT: f64 = 0.2;
/// The velocities of items 1-4 and of item 5, m/s (the paper's Tables 3 and 6).
const V_COAL: f64 = 0.008;
const V_GANGUE: f64 = 0.0025;

/// The line a statement is tested along.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Along {
    /// z = B/2.
    Centreline,
    /// z = 0.
    FreeEdge,
}

/// A statement of section V.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Statement {
    /// Item 1: coal v_y is least at an end and greatest near the midpoint (Con 1).
    YieldShape,
    /// Item 1: coal P_max at 0.008 m/s is least near the midpoint (Con 1).
    ForceShape,
    /// Item 1: the impact-point deflection is greatest near the midpoint (Con 1).
    DeflectionShape,
    /// Item 2: v_y(Con 2) ≥ v_y(Con 3) ≥ v_y(Con 1) at Areas 1-7.
    YieldOrder,
    /// Item 2: the springs take more energy in Con 2 than in Con 3 at L/2.
    SpringShare,
    /// Item 2: P_max(Con 1) ≥ P_max(Con 3) ≥ P_max(Con 2) at L/2.
    ForceOrder,
    /// Item 3: stiffer springs lower v_y, raise P_max and lower the spring energy share.
    StiffnessSweep,
    /// Item 4: longer plates lower P_max and raise the deflection at the same point.
    Length,
    /// Item 5: gangue against coal: smaller δ, larger P_max, deflection and plate energy.
    GangueHarder,
    /// Item 5: elastic supports reduce the coal-gangue difference in P_max.
    GangueDifference,
}

/// The numbers behind a verdict, under one model.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Evidence {
    /// The least and greatest value along the line and where (in units of L).
    Extremes {
        /// x/L of the minimum.
        min_at: f64,
        /// The minimum.
        min: f64,
        /// x/L of the maximum.
        max_at: f64,
        /// The maximum.
        max: f64,
    },
    /// The Areas where the order holds, and the least v_y(Con 2)/v_y(Con 1) - 1.
    Order {
        /// Areas where it holds.
        held: usize,
        /// Areas.
        areas: usize,
        /// min over the Areas of v_y(Con 2)/v_y(Con 1) - 1.
        worst: f64,
    },
    /// Values compared in the statement's order (with the digits they are shown to).
    Values {
        /// The values.
        values: Vec<f64>,
    },
    /// v_y, P_max and the spring energy ratio over the stiffnesses.
    Sweep {
        /// v_y, m/s.
        yield_velocity: Vec<f64>,
        /// P_max, N.
        contact_force: Vec<f64>,
        /// Spring energy over E₀.
        spring_ratio: Vec<f64>,
    },
    /// P_max,coal - P_max,gangue 1 per support set, N.
    Differences {
        /// (support set, ΔP).
        values: Vec<(String, f64)>,
    },
    /// (P_max, deflection) per plate length.
    Lengths {
        /// (N, m).
        values: Vec<(f64, f64)>,
    },
}

/// One verdict.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// The item of section V.
    pub item: u8,
    /// What it states.
    pub statement: Statement,
    /// Along which line (none: item 4, on the centreline of plates of several lengths).
    pub along: Option<Along>,
    /// The beam's numbers.
    pub beam: Evidence,
    /// The plate's numbers.
    pub plate: Evidence,
    /// Whether it holds under the beam.
    pub beam_holds: bool,
    /// Whether it holds under the plate.
    pub plate_holds: bool,
}

impl Check {
    fn new(
        item: u8,
        statement: Statement,
        along: Along,
        (beam, plate): (Evidence, Evidence),
        holds: (bool, bool),
    ) -> Self {
        Self { item, statement, along: Some(along), beam, plate, beam_holds: holds.0, plate_holds: holds.1 }
    }
}

fn named(name: &str, condition: Condition) -> SupportSet {
    SupportSet::preset(name, condition)
}

fn extremes((min_at, min, max_at, max): Extremes) -> Evidence {
    Evidence::Extremes { min_at, min, max_at, max }
}

fn values(v: &[f64]) -> Evidence {
    Evidence::Values { values: v.to_vec() }
}

/// The support sets the checks run on: Con 1-3 with the paper's k_T, then Con 2 at
/// [`STIFFNESSES`].
fn conditions(paper: &Paper) -> Vec<SupportSet> {
    let k = paper.k_t;
    let mut conds = vec![
        named("Con 1", Condition::BothFixed),
        named("Con 2", Condition::BothSprings { k_t: k }),
        named("Con 3", Condition::FixedAndSprings { k_t: k }),
    ];
    for kk in STIFFNESSES {
        conds.push(named(&format!("Con 2 k{kk:e}"), Condition::BothSprings { k_t: kk }));
    }
    conds
}

/// Runs every check on the paper's scene, on the centreline and on the free edge, each line
/// in `points - 1` equal parts (the paper's 100: 101 points).
pub fn checks(paper: &Paper, points: usize) -> Result<Vec<Check>, Failure> {
    let scene = &paper.scene;
    let conds = conditions(paper);
    let mut out = Vec::new();
    for (along, z) in [(Along::Centreline, scene.plate.width() / 2.0), (Along::FreeEdge, 0.0)] {
        let line = Line::new(scene, &conds, z, points)?;
        out.extend(shapes(paper, &line, &conds, along)?);
        out.extend(supports(paper, &line, &conds, along)?);
        out.push(stiffness(paper, &line, &conds, along)?);
        out.extend(gangue(paper, &line, &conds, along)?);
    }
    out.push(lengths(paper)?);
    out.sort_by_key(|c| c.item);
    Ok(out)
}

/// Item 1: the shapes of v_y, P_max and the deflection along the plate (Con 1).
fn shapes(paper: &Paper, line: &Line, conds: &[SupportSet], along: Along) -> Result<Vec<Check>, Failure> {
    let (c1, coal) = (&conds[0], &paper.coal);
    let end = |x: f64| !(0.05..=0.95).contains(&x);
    let middle = |x: f64| (0.4..=0.6).contains(&x);
    let (eb, ep) = both(|p| line.extremes(|x| line.vy(p, c1, coal, x)))?;
    let yields = Check::new(
        1,
        Statement::YieldShape,
        along,
        (extremes(eb), extremes(ep)),
        (end(eb.0) && middle(eb.2), end(ep.0) && middle(ep.2)),
    );
    let (eb, ep) = both(|p| line.extremes(|x| Ok(line.response(p, c1, coal, x, V_COAL)?.contact_force)))?;
    let forces = Check::new(
        1,
        Statement::ForceShape,
        along,
        (extremes(eb), extremes(ep)),
        (middle(eb.0) && end(eb.2), middle(ep.0) && end(ep.2)),
    );
    let (eb, ep) = both(|p| line.extremes(|x| Ok(line.response(p, c1, coal, x, V_COAL)?.deflection)))?;
    let deflections =
        Check::new(1, Statement::DeflectionShape, along, (extremes(eb), extremes(ep)), (middle(eb.2), middle(ep.2)));
    Ok(vec![yields, forces, deflections])
}

/// Item 2: elastic supports raise v_y and lower P_max; Con 2's springs take more energy.
fn supports(paper: &Paper, line: &Line, conds: &[SupportSet], along: Along) -> Result<Vec<Check>, Failure> {
    let (c1, c2, c3) = (&conds[0], &conds[1], &conds[2]);
    let coal = &paper.coal;
    let l = paper.scene.plate.length();
    let areas: Vec<f64> = AREAS.iter().map(|f| f * l).collect();
    let order = |p: bool| -> Result<Evidence, Failure> {
        let mut held = 0;
        let mut worst = f64::INFINITY;
        for &x in &areas {
            let (v1, v2, v3) = (line.vy(p, c1, coal, x)?, line.vy(p, c2, coal, x)?, line.vy(p, c3, coal, x)?);
            if v2 >= v3 * (1.0 - 1e-12) && v3 >= v1 * (1.0 - 1e-12) {
                held += 1;
            }
            worst = worst.min(v2 / v1 - 1.0);
        }
        Ok(Evidence::Order { held, areas: areas.len(), worst })
    };
    let all = |e: &Evidence| matches!(e, Evidence::Order { held, areas, .. } if held == areas);
    let ev = both(order)?;
    let holds = (all(&ev.0), all(&ev.1));
    let yields = Check::new(2, Statement::YieldOrder, along, ev, holds);
    let mid = l / 2.0;
    let spring = |p: bool| -> Result<[f64; 2], Failure> {
        Ok([
            line.response(p, c2, coal, mid, V_COAL)?.spring_ratio,
            line.response(p, c3, coal, mid, V_COAL)?.spring_ratio,
        ])
    };
    let (b, p) = both(spring)?;
    let springs = Check::new(2, Statement::SpringShare, along, (values(&b), values(&p)), (b[0] > b[1], p[0] > p[1]));
    let force = |p: bool| -> Result<[f64; 3], Failure> {
        Ok([c1, c3, c2].map(|c| line.response(p, c, coal, mid, V_COAL).map(|r| r.contact_force).unwrap_or(f64::NAN)))
    };
    let (fb, fp) = both(force)?;
    let descending = |f: &[f64; 3]| f[0] >= f[1] && f[1] >= f[2];
    let forces =
        Check::new(2, Statement::ForceOrder, along, (values(&fb), values(&fp)), (descending(&fb), descending(&fp)));
    Ok(vec![yields, springs, forces])
}

/// Item 3: stiffer springs lower v_y, raise P_max and lower the springs' share (Con 2, L/2).
fn stiffness(paper: &Paper, line: &Line, conds: &[SupportSet], along: Along) -> Result<Check, Failure> {
    let mid = paper.scene.plate.length() / 2.0;
    let sweep = |p: bool| -> Result<Evidence, Failure> {
        let (mut yield_velocity, mut contact_force, mut spring_ratio) = (vec![], vec![], vec![]);
        for c in &conds[3..] {
            yield_velocity.push(line.vy(p, c, &paper.coal, mid)?);
            let r = line.response(p, c, &paper.coal, mid, V_COAL)?;
            contact_force.push(r.contact_force);
            spring_ratio.push(r.spring_ratio);
        }
        Ok(Evidence::Sweep { yield_velocity, contact_force, spring_ratio })
    };
    let dec = |v: &[f64]| v.windows(2).all(|w| w[1] <= w[0]);
    let inc = |v: &[f64]| v.windows(2).all(|w| w[1] >= w[0]);
    let holds = |e: &Evidence| match e {
        Evidence::Sweep { yield_velocity, contact_force, spring_ratio } => {
            dec(yield_velocity) && inc(contact_force) && dec(spring_ratio)
        }
        _ => false,
    };
    let ev = both(sweep)?;
    let verdicts = (holds(&ev.0), holds(&ev.1));
    Ok(Check::new(3, Statement::StiffnessSweep, along, ev, verdicts))
}

/// Under one model: whether gangue is harder on the plate under every support set, ΔP per
/// support set, and |ΔP| under Con 1, 2, 3.
type GangueEvidence = (bool, Vec<(String, f64)>, [f64; 3]);

/// Item 5: gangue against coal at the midpoint at 0.0025 m/s, and how the supports change
/// the difference in P_max.
fn gangue(paper: &Paper, line: &Line, conds: &[SupportSet], along: Along) -> Result<Vec<Check>, Failure> {
    let mid = paper.scene.plate.length() / 2.0;
    let (coal, g1, g2) = (&paper.coal, &paper.gangue1, &paper.gangue2);
    let one = |p: bool| -> Result<GangueEvidence, Failure> {
        let mut ok = true;
        let mut diffs = [0.0; 3];
        let mut values = Vec::new();
        for (i, c) in conds[..3].iter().enumerate() {
            let rc = line.response(p, c, coal, mid, V_GANGUE)?;
            for g in [g1, g2] {
                let rg = line.response(p, c, g, mid, V_GANGUE)?;
                ok &= rg.compression < rc.compression
                    && rg.contact_force > rc.contact_force
                    && rg.deflection > rc.deflection
                    && rg.plate_ratio > rc.plate_ratio;
            }
            let rg = line.response(p, c, g1, mid, V_GANGUE)?;
            diffs[i] = (rc.contact_force - rg.contact_force).abs();
            values.push((c.name.clone(), rc.contact_force - rg.contact_force));
        }
        Ok((ok, values, diffs))
    };
    let ((okb, vb, db), (okp, vp, dp)) = both(one)?;
    let differences = (Evidence::Differences { values: vb }, Evidence::Differences { values: vp });
    let harder = Check::new(5, Statement::GangueHarder, along, differences, (okb, okp));
    let order = |d: &[f64; 3]| d[0] > d[2] && d[2] > d[1];
    let smaller =
        Check::new(5, Statement::GangueDifference, along, (values(&db), values(&dp)), (order(&db), order(&dp)));
    Ok(vec![harder, smaller])
}

/// Item 4: longer plates at the same absolute point on the centreline, Con 1, coal at
/// 0.008 m/s: (P_max, deflection) by the beam and by the plate.
fn lengths(paper: &Paper) -> Result<Check, Failure> {
    let scene = &paper.scene;
    let x = LENGTH_POINT;
    let mut rows = (vec![], vec![]);
    for f in LENGTH_FACTORS {
        let plate = scene.plate.with_length(scene.plate.length() * f)?;
        let s = Scene { plate, ..scene.clone() };
        let pts = [(x, plate.width() / 2.0)];
        let c = named("Con 1", Condition::BothFixed);
        let model = PlateModel::compute(
            &s.plate,
            std::slice::from_ref(&c),
            &pts,
            crate::settings::BASE_MESH,
            crate::settings::LEVELS,
        )?;
        let imp = impact_of(&s, &paper.coal, V_COAL);
        let method = crate::settings::METHOD;
        let rb = respond(&imp, &BeamModel { plate: &s.plate }.compliance(&c, x, 0.0)?.compliance, method)?;
        let rp = respond(&imp, &model.compliance(&c, x, plate.width() / 2.0)?.compliance, method)?;
        rows.0.push((rb.contact_force, rb.deflection));
        rows.1.push((rp.contact_force, rp.deflection));
    }
    let holds = |v: &[(f64, f64)]| v.windows(2).all(|w| w[1].0 < w[0].0 && w[1].1 > w[0].1);
    Ok(Check {
        item: 4,
        statement: Statement::Length,
        along: None,
        beam_holds: holds(&rows.0),
        plate_holds: holds(&rows.1),
        beam: Evidence::Lengths { values: rows.0 },
        plate: Evidence::Lengths { values: rows.1 },
    })
}
