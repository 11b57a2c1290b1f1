//! The paper's figures redone with both models along the centreline: the beam's curves (as
//! the paper draws them, eqs. 14, 25, 46 and 51-54 with the beam's compliance) beside the
//! plate FE model's through the same balance.

use super::line::Line;
use crate::paper::{Paper, K_LENGTH_STUDY, K_STUDY, LENGTH_FACTORS, V_TABLE3, V_TABLE6};
use crate::Failure;
use analytic::{Condition, Response};
use scene::{Scene, SupportSet};
use serde::Serialize;

/// One curve: a quantity along the line by one model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Curve {
    /// By the plate FE model (else the beam).
    pub plate: bool,
    /// The support set, body or plate length it is drawn for.
    pub label: String,
    /// (x in mm, value).
    pub points: Vec<(f64, f64)>,
}

/// A figure of the paper redone, named by its file stem.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyFigure {
    /// The file stem, `study-fig..`.
    pub stem: String,
    /// Its curves, beam and plate alternating.
    pub curves: Vec<Curve>,
}

fn figure(stem: &str, curves: Vec<Curve>) -> StudyFigure {
    StudyFigure { stem: stem.into(), curves }
}

/// Con 1-3 at the paper's k_T, then Con 2 and Con 3 at each of [`K_STUDY`].
fn conditions(paper: &Paper) -> Vec<SupportSet> {
    let k = paper.k_t;
    let mut conds = vec![
        SupportSet::preset("Con 1", Condition::BothFixed),
        SupportSet::preset("Con 2", Condition::BothSprings { k_t: k }),
        SupportSet::preset("Con 3", Condition::FixedAndSprings { k_t: k }),
    ];
    for kk in K_STUDY {
        conds.push(SupportSet::preset(format!("Con 2, k_T = {kk:e}"), Condition::BothSprings { k_t: kk }));
    }
    for kk in K_STUDY {
        conds.push(SupportSet::preset(format!("Con 3, k_T = {kk:e}"), Condition::FixedAndSprings { k_t: kk }));
    }
    conds
}

/// A quantity of the response of `body` at velocity `v`, along the line.
type Quantity<'a> = &'a dyn Fn(bool, &SupportSet, f64) -> Result<f64, Failure>;

/// The curve of `f` along `line` for `c`, by one model.
fn curve(line: &Line, p: bool, c: &SupportSet, f: Quantity) -> Result<Curve, Failure> {
    let points = line.xs.iter().map(|&x| Ok((x * 1e3, f(p, c, x)?))).collect::<Result<Vec<_>, Failure>>()?;
    Ok(Curve { plate: p, label: c.name.clone(), points })
}

/// The spring force of the spring named (beam: `beam` in its name; plate: the corner
/// `corner`), N, or NaN.
fn spring_force(r: &Response, beam: &str, corner: &str) -> f64 {
    r.spring_forces.iter().find(|s| s.name.contains(beam) || s.name.ends_with(corner)).map_or(f64::NAN, |s| s.force)
}

/// Every figure, each curve in `points - 1` equal parts of the length.
pub fn figures(paper: &Paper, points: usize) -> Result<Vec<StudyFigure>, Failure> {
    let scene = &paper.scene;
    let conds = conditions(paper);
    let line = Line::new(scene, &conds, scene.plate.width() / 2.0, points)?;
    let mut figs = supports_figures(paper, &line, &conds)?;
    figs.extend(bodies_figures(paper, &line, &conds[1], &conds[0])?);
    figs.extend(length_figures(paper, points)?);
    Ok(figs)
}

/// Figs. 8, 10-13: Con 1-3 and the stiffness study, coal.
fn supports_figures(paper: &Paper, line: &Line, conds: &[SupportSet]) -> Result<Vec<StudyFigure>, Failure> {
    let coal = &paper.coal;
    let vy_coal = |p: bool, c: &SupportSet, x: f64| line.vy(p, c, coal, x);
    let p_coal = |p: bool, c: &SupportSet, x: f64| Ok(line.response(p, c, coal, x, V_TABLE3)?.contact_force);
    let defl = |p: bool, c: &SupportSet, x: f64| Ok(line.response(p, c, coal, x, V_TABLE3)?.deflection * 1e6);
    let spring_energy = |p: bool, c: &SupportSet, x: f64| Ok(line.response(p, c, coal, x, V_TABLE3)?.spring_ratio);
    let (mut s8, mut s10, mut s10d) = (Vec::new(), Vec::new(), Vec::new());
    for c in &conds[..3] {
        for p in [false, true] {
            s8.push(curve(line, p, c, &vy_coal)?);
            s10.push(curve(line, p, c, &p_coal)?);
            s10d.push(curve(line, p, c, &defl)?);
        }
    }
    let mut s11 = Vec::new();
    for c in &conds[3..6] {
        for p in [false, true] {
            s11.push(curve(line, p, c, &vy_coal)?);
        }
    }
    let (mut s12, mut s13) = (Vec::new(), Vec::new());
    for c in &conds[3..] {
        for p in [false, true] {
            if c.name.starts_with("Con 3") {
                s12.push(curve(line, p, c, &vy_coal)?);
            }
            s13.push(curve(line, p, c, &spring_energy)?);
        }
    }
    Ok(vec![
        figure("study-fig08-yield-coal", s8),
        figure("study-fig10-contact-force", s10),
        figure("study-fig10-deflection", s10d),
        figure("study-fig11-yield-stiffness", s11),
        figure("study-fig12-yield-stiffness-con3", s12),
        figure("study-fig13-spring-energy", s13),
    ])
}

/// Figs. 17-19: the three spheres at 0.0025 m/s; the right-end spring force (beam: each of
/// its two springs; plate: the corner (L, 0) spring) and the spring energy ratio under
/// `con2`, P_max under `con1`.
fn bodies_figures(
    paper: &Paper,
    line: &Line,
    con2: &SupportSet,
    con1: &SupportSet,
) -> Result<Vec<StudyFigure>, Failure> {
    let (mut s18, mut s19) = (Vec::new(), Vec::new());
    for body in paper.bodies() {
        for p in [false, true] {
            let (mut pts18, mut pts19) = (Vec::new(), Vec::new());
            for &x in &line.xs {
                let r = line.response(p, con2, body, x, V_TABLE6)?;
                pts18.push((x * 1e3, spring_force(&r, "right", "(L, 0)")));
                pts19.push((x * 1e3, r.spring_ratio));
            }
            s18.push(Curve { plate: p, label: body.name.clone(), points: pts18 });
            s19.push(Curve { plate: p, label: body.name.clone(), points: pts19 });
        }
    }
    let mut s17 = Vec::new();
    for body in paper.bodies() {
        for p in [false, true] {
            let f = |p: bool, c: &SupportSet, x: f64| Ok(line.response(p, c, body, x, V_TABLE6)?.contact_force);
            s17.push(Curve { label: body.name.clone(), ..curve(line, p, con1, &f)? });
        }
    }
    Ok(vec![
        figure("study-fig18-spring-force", s18),
        figure("study-fig19-spring-energy", s19),
        figure("study-fig17-contact-force-bodies", s17),
    ])
}

/// Figs. 14-16: four plate lengths; the left-end spring force (beam: each spring; plate: the
/// corner (0, 0) spring) and the spring energy ratio under Con 2 at the length study's
/// k_T, P_max under Con 1.
fn length_figures(paper: &Paper, points: usize) -> Result<Vec<StudyFigure>, Failure> {
    let scene = &paper.scene;
    let (mut s14, mut s15, mut s16) = (Vec::new(), Vec::new(), Vec::new());
    for f in LENGTH_FACTORS {
        let plate = scene.plate.with_length(scene.plate.length() * f)?;
        let s = Scene { plate, ..scene.clone() };
        let c1 = SupportSet::preset("Con 1", Condition::BothFixed);
        // Section IV-C uses k_T = 5e6 N/m for the length study.
        let c2 = SupportSet::preset("Con 2", Condition::BothSprings { k_t: K_LENGTH_STUDY });
        let ln = Line::new(&s, &[c1.clone(), c2.clone()], scene.plate.width() / 2.0, points)?;
        let label = format!("L = {:.0} mm", plate.length() * 1e3);
        for p in [false, true] {
            let (mut force, mut energy) = (Vec::new(), Vec::new());
            for &x in &ln.xs {
                let r = ln.response(p, &c2, &paper.coal, x, V_TABLE3)?;
                force.push((x * 1e3, spring_force(&r, "left", "(0, 0)")));
                energy.push((x * 1e3, r.spring_ratio));
            }
            s15.push(Curve { plate: p, label: label.clone(), points: force });
            s16.push(Curve { plate: p, label: label.clone(), points: energy });
        }
        for p in [false, true] {
            let pts = ln
                .xs
                .iter()
                .map(|&x| Ok((x * 1e3, ln.response(p, &c1, &paper.coal, x, V_TABLE3)?.contact_force)))
                .collect::<Result<Vec<_>, Failure>>()?;
            s14.push(Curve { plate: p, label: label.clone(), points: pts });
        }
    }
    Ok(vec![
        figure("study-fig15-spring-force-length", s15),
        figure("study-fig16-spring-energy-length", s16),
        figure("study-fig14-contact-force-length", s14),
    ])
}
