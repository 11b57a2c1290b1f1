//! The paper's conclusions (section V, items 1-5) tested under the beam and the plate FE
//! model, with the numbers behind each verdict.

use crate::paper::Paper;
use crate::present::table::{sig, Cell, Table};
use analytic::{respond, yield_velocity, Condition, DruckerPrager, Method, Response, Sphere};
use coupled::plan::impact_of;
use coupled::PlateModel;
use coupled::{BeamModel, ComplianceModel};
use scene::{even_points, Scene, SupportSet};

use crate::Failure;

const METHOD: Method = Method::Bracketed { tolerance: 1e-13, max_iterations: 200 };

/// Yield velocities, contact forces and spring energy ratios over a k_T sweep.
type Sweep = (Vec<f64>, Vec<f64>, Vec<f64>);

/// One verdict.
pub struct Check {
    pub item: &'static str,
    pub statement: String,
    pub beam: String,
    pub plate: String,
    pub beam_holds: bool,
    pub plate_holds: bool,
}

/// Both models at the points of one line for a set of conditions.
struct Line<'a> {
    scene: &'a Scene,
    model: PlateModel,
    xs: Vec<f64>,
    z: f64,
}

impl<'a> Line<'a> {
    fn new(scene: &'a Scene, conds: &[SupportSet], z: f64) -> Result<Self, Failure> {
        let xs = even_points(scene.plate.length(), 101);
        let pts: Vec<(f64, f64)> = xs.iter().map(|&x| (x, z)).collect();
        let model =
            PlateModel::compute(&scene.plate, conds, &pts, studies::settings::BASE_MESH, studies::settings::LEVELS)?;
        Ok(Self { scene, model, xs, z })
    }
    fn compliance(&self, plate: bool, c: &SupportSet, x: f64) -> Result<analytic::PointCompliance, Failure> {
        Ok(if plate {
            self.model.compliance(c, x, self.z)?.compliance
        } else {
            BeamModel { plate: &self.scene.plate }.compliance(c, x, 0.0)?.compliance
        })
    }
    fn response(&self, plate: bool, c: &SupportSet, body: &Sphere, x: f64, v: f64) -> Result<Response, Failure> {
        Ok(respond(&impact_of(self.scene, body, v), &self.compliance(plate, c, x)?, METHOD)?)
    }
    fn vy(&self, plate: bool, c: &SupportSet, body: &Sphere, x: f64) -> Result<f64, Failure> {
        let imp = impact_of(self.scene, body, 1.0);
        let d = DruckerPrager::of(body).yield_compression(body.radius(), imp.contact_stiffness);
        Ok(yield_velocity(body, &imp, self.compliance(plate, c, x)?.total(), d))
    }
    /// (argmin x, argmax x) of f along the line, in units of L.
    fn extremes(&self, f: impl Fn(f64) -> Result<f64, Failure>) -> Result<(f64, f64, f64, f64), Failure> {
        let vals: Vec<f64> = self.xs.iter().map(|&x| f(x)).collect::<Result<_, _>>()?;
        let l = self.scene.plate.length();
        let (imin, imax) = vals
            .iter()
            .enumerate()
            .fold((0, 0), |(a, b), (i, v)| (if *v < vals[a] { i } else { a }, if *v > vals[b] { i } else { b }));
        Ok((self.xs[imin] / l, vals[imin], self.xs[imax] / l, vals[imax]))
    }
}

fn named(name: &str, condition: Condition) -> SupportSet {
    SupportSet::preset(name, condition)
}

fn both<T>(f: impl Fn(bool) -> Result<T, Failure>) -> Result<(T, T), Failure> {
    Ok((f(false)?, f(true)?))
}

/// Runs every check on the paper's scene, on the centreline and on the free edge.
pub fn checks() -> Result<Vec<Check>, Failure> {
    let paper = Paper::new();
    let scene = &paper.scene;
    let (l, b) = (scene.plate.length(), scene.plate.width());
    let k = paper.k_t;
    let mut conds = vec![
        named("Con 1", Condition::BothFixed),
        named("Con 2", Condition::BothSprings { k_t: k }),
        named("Con 3", Condition::FixedAndSprings { k_t: k }),
    ];
    let ks = [5e4, 2.50025e8, 5e8];
    for kk in ks {
        conds.push(named(&format!("Con 2 k{kk:e}"), Condition::BothSprings { k_t: kk }));
    }
    let mut out = Vec::new();
    for (where_, z) in [("centreline", b / 2.0), ("free edge z = 0", 0.0)] {
        let line = Line::new(scene, &conds, z)?;
        let (c1, c2, c3) = (&conds[0], &conds[1], &conds[2]);
        let (coal, g1, g2) = (&paper.coal, &paper.gangue1, &paper.gangue2);
        let fmt_ext = |e: (f64, f64, f64, f64)| {
            format!("min {} at x = {:.2} L, max {} at x = {:.2} L", sig(e.1, 5), e.0, sig(e.3, 5), e.2)
        };
        let end = |x: f64| !(0.05..=0.95).contains(&x);
        let middle = |x: f64| (0.4..=0.6).contains(&x);

        // Item 1: shapes along the plate.
        let (eb, ep) = both(|p| line.extremes(|x| line.vy(p, c1, coal, x)))?;
        out.push(Check {
            item: "1",
            statement: format!(
                "coal v_y along the plate ({where_}, Con 1): minimum at an end, maximum near the midpoint"
            ),
            beam: fmt_ext(eb),
            plate: fmt_ext(ep),
            beam_holds: end(eb.0) && middle(eb.2),
            plate_holds: end(ep.0) && middle(ep.2),
        });
        let (eb, ep) = both(|p| line.extremes(|x| Ok(line.response(p, c1, coal, x, 0.008)?.contact_force)))?;
        out.push(Check {
            item: "1",
            statement: format!(
                "coal P_max at 0.008 m/s ({where_}, Con 1): decreases then increases, minimum near the midpoint"
            ),
            beam: fmt_ext(eb),
            plate: fmt_ext(ep),
            beam_holds: middle(eb.0) && end(eb.2),
            plate_holds: middle(ep.0) && end(ep.2),
        });
        let (eb, ep) = both(|p| line.extremes(|x| Ok(line.response(p, c1, coal, x, 0.008)?.deflection)))?;
        out.push(Check {
            item: "1",
            statement: format!("impact-point deflection ({where_}, Con 1): maximum near the midpoint"),
            beam: fmt_ext(eb),
            plate: fmt_ext(ep),
            beam_holds: middle(eb.2),
            plate_holds: middle(ep.2),
        });

        // Item 2: elastic supports raise v_y and lower P_max; Con 2 springs take more energy.
        let areas: Vec<f64> = studies::settings::AREAS.iter().map(|f| f * l).collect();
        let order = |p: bool| -> Result<(usize, String), Failure> {
            let mut n = 0;
            let mut worst = f64::INFINITY;
            for &x in &areas {
                let (v1, v2, v3) = (line.vy(p, c1, coal, x)?, line.vy(p, c2, coal, x)?, line.vy(p, c3, coal, x)?);
                if v2 >= v3 * (1.0 - 1e-12) && v3 >= v1 * (1.0 - 1e-12) {
                    n += 1;
                }
                worst = worst.min(v2 / v1 - 1.0);
            }
            Ok((n, format!("{n}/7 areas; v_y(Con 2)/v_y(Con 1) - 1 ≥ {}", sig(worst, 3))))
        };
        let ((nb, sb), (np, sp)) = both(order)?;
        out.push(Check {
            item: "2",
            statement: format!("v_y(Con 2) ≥ v_y(Con 3) ≥ v_y(Con 1) at Areas 1-7 ({where_})"),
            beam: sb,
            plate: sp,
            beam_holds: nb == 7,
            plate_holds: np == 7,
        });
        let mid = l / 2.0;
        let spring = |p: bool| -> Result<(f64, f64), Failure> {
            Ok((
                line.response(p, c2, coal, mid, 0.008)?.spring_ratio,
                line.response(p, c3, coal, mid, 0.008)?.spring_ratio,
            ))
        };
        let ((b2, b3), (p2, p3)) = both(spring)?;
        out.push(Check {
            item: "2",
            statement: format!("spring energy ratio Con 2 > Con 3 at x = L/2 ({where_})"),
            beam: format!("{} vs {}", sig(b2, 4), sig(b3, 4)),
            plate: format!("{} vs {}", sig(p2, 4), sig(p3, 4)),
            beam_holds: b2 > b3,
            plate_holds: p2 > p3,
        });
        let force = |p: bool| -> Result<[f64; 3], Failure> {
            Ok([c1, c3, c2].map(|c| line.response(p, c, coal, mid, 0.008).map(|r| r.contact_force).unwrap_or(f64::NAN)))
        };
        let (fb, fp) = both(force)?;
        out.push(Check {
            item: "2",
            statement: format!(
                "supports soften the impact: P_max(Con 1) ≥ P_max(Con 3) ≥ P_max(Con 2) at x = L/2 ({where_})"
            ),
            beam: fb.map(|v| sig(v, 7)).join(" ≥ "),
            plate: fp.map(|v| sig(v, 7)).join(" ≥ "),
            beam_holds: fb[0] >= fb[1] && fb[1] >= fb[2],
            plate_holds: fp[0] >= fp[1] && fp[1] >= fp[2],
        });

        // Item 3: stiffer springs lower v_y, raise P_max, lower the spring energy share.
        let sweep = |p: bool| -> Result<Sweep, Failure> {
            let (mut vy, mut pm, mut sr) = (vec![], vec![], vec![]);
            for c in &conds[3..] {
                vy.push(line.vy(p, c, coal, mid)?);
                let r = line.response(p, c, coal, mid, 0.008)?;
                pm.push(r.contact_force);
                sr.push(r.spring_ratio);
            }
            Ok((vy, pm, sr))
        };
        let ((vb, pb, sb), (vp, pp, sp)) = both(sweep)?;
        let dec = |v: &[f64]| v.windows(2).all(|w| w[1] <= w[0]);
        let inc = |v: &[f64]| v.windows(2).all(|w| w[1] >= w[0]);
        let show = |v: &[f64]| v.iter().map(|x| sig(*x, 6)).collect::<Vec<_>>().join(" → ");
        out.push(Check {
            item: "3",
            statement: format!("k_T = 5e4 → 2.5e8 → 5e8 N/m (Con 2, x = L/2, {where_}): v_y falls, P_max rises, spring energy ratio falls"),
            beam: format!("v_y {}; P {}; springs {}", show(&vb), show(&pb), show(&sb)),
            plate: format!("v_y {}; P {}; springs {}", show(&vp), show(&pp), show(&sp)),
            beam_holds: dec(&vb) && inc(&pb) && dec(&sb),
            plate_holds: dec(&vp) && inc(&pp) && dec(&sp),
        });

        // Item 5: gangue against coal at the midpoint, v = 0.0025 m/s.
        let gang = |p: bool| -> Result<(bool, String, [f64; 3]), Failure> {
            let mut ok = true;
            let mut diffs = [0.0; 3];
            let mut text = Vec::new();
            for (i, c) in [c1, c2, c3].iter().enumerate() {
                let rc = line.response(p, c, coal, mid, 0.0025)?;
                for g in [g1, g2] {
                    let rg = line.response(p, c, g, mid, 0.0025)?;
                    ok &= rg.compression < rc.compression
                        && rg.contact_force > rc.contact_force
                        && rg.deflection > rc.deflection
                        && rg.plate_ratio > rc.plate_ratio;
                }
                let rg = line.response(p, c, g1, mid, 0.0025)?;
                diffs[i] = (rc.contact_force - rg.contact_force).abs();
                text.push(format!("{}: ΔP(coal - gangue 1) = {}", c.name, sig(rc.contact_force - rg.contact_force, 6)));
            }
            Ok((ok, text.join("; "), diffs))
        };
        let ((okb, tb, db), (okp, tp, dp)) = both(gang)?;
        out.push(Check {
            item: "5",
            statement: format!("gangue (same mass or size) against coal at x = L/2, 0.0025 m/s ({where_}): smaller δ, larger P_max, deflection and plate energy"),
            beam: tb.clone(),
            plate: tp.clone(),
            beam_holds: okb,
            plate_holds: okp,
        });
        out.push(Check {
            item: "5",
            statement: format!(
                "elastic supports reduce the coal-gangue difference in P_max: |ΔP| Con 1 > Con 3 > Con 2 ({where_})"
            ),
            beam: db.map(|v| sig(v, 7)).join(", "),
            plate: dp.map(|v| sig(v, 7)).join(", "),
            beam_holds: db[0] > db[2] && db[2] > db[1],
            plate_holds: dp[0] > dp[2] && dp[2] > dp[1],
        });
    }

    // Item 4: longer plates, same absolute point x = 0.2 m on the centreline, Con 1.
    let x = 0.2;
    let mut rows = (vec![], vec![]);
    for f in [0.8, 1.0, 1.2, 1.4] {
        let plate = scene.plate.with_length(scene.plate.length() * f)?;
        let s = Scene { plate, ..scene.clone() };
        let pts = [(x, plate.width() / 2.0)];
        let c = named("Con 1", Condition::BothFixed);
        let model = PlateModel::compute(
            &s.plate,
            std::slice::from_ref(&c),
            &pts,
            studies::settings::BASE_MESH,
            studies::settings::LEVELS,
        )?;
        let imp = impact_of(&s, &paper.coal, 0.008);
        let rb = respond(&imp, &BeamModel { plate: &s.plate }.compliance(&c, x, 0.0)?.compliance, METHOD)?;
        let rp = respond(&imp, &model.compliance(&c, x, plate.width() / 2.0)?.compliance, METHOD)?;
        rows.0.push((rb.contact_force, rb.deflection));
        rows.1.push((rp.contact_force, rp.deflection));
    }
    let holds = |v: &[(f64, f64)]| v.windows(2).all(|w| w[1].0 < w[0].0 && w[1].1 > w[0].1);
    let show = |v: &[(f64, f64)]| {
        v.iter().map(|(p, d)| format!("{}/{}", sig(*p, 5), sig(*d, 4))).collect::<Vec<_>>().join(" → ")
    };
    out.push(Check {
        item: "4",
        statement: "L = 0.8, 1.0, 1.2, 1.4 x 458.4 mm (Con 1, x = 0.2 m, centreline, coal 0.008 m/s): P_max falls and deflection rises (shown P (N)/deflection (m))".into(),
        beam: show(&rows.0),
        plate: show(&rows.1),
        beam_holds: holds(&rows.0),
        plate_holds: holds(&rows.1),
    });
    out.sort_by_key(|c| c.item);
    Ok(out)
}

/// The verdicts as a table.
pub fn table(checks: &[Check]) -> Table {
    let mut t =
        Table::new("", &["item", "statement of section V", "beam", "holds (beam)", "plate FE", "holds (plate)"]);
    for c in checks {
        let yn = |yes: bool| Cell::Flag { yes, shown: if yes { "yes" } else { "**no**" } };
        t.push(vec![
            c.item.into(),
            c.statement.clone().into(),
            c.beam.clone().into(),
            yn(c.beam_holds),
            c.plate.clone().into(),
            yn(c.plate_holds),
        ]);
    }
    t.csv_name("statement of section V", &["statement"])
        .csv_name("beam", &["beam_evidence"])
        .csv_name("plate FE", &["plate_FE_evidence"])
}

/// A figure of the paper redone: file stem, title, y label and curves.
pub struct Figure {
    pub stem: String,
    pub title: String,
    pub y_label: String,
    pub series: Vec<crate::present::plot::Series>,
}

fn figure(stem: &str, title: &str, y_label: &str, series: Vec<crate::present::plot::Series>) -> Figure {
    Figure { stem: stem.into(), title: title.into(), y_label: y_label.into(), series }
}

/// The paper's figures redone with both models along the centreline; curves are named
/// "beam ..." and "plate ...".
pub fn study_figures() -> Result<Vec<Figure>, Failure> {
    use crate::present::plot::Series;
    let paper = Paper::new();
    let scene = &paper.scene;
    let (l, b) = (scene.plate.length(), scene.plate.width());
    let k = paper.k_t;
    let mut conds = vec![
        named("Con 1", Condition::BothFixed),
        named("Con 2", Condition::BothSprings { k_t: k }),
        named("Con 3", Condition::FixedAndSprings { k_t: k }),
    ];
    for kk in [5e4, 2.50025e8, 5e8] {
        conds.push(named(&format!("Con 2, k_T = {kk:e}"), Condition::BothSprings { k_t: kk }));
    }
    for kk in [5e4, 2.50025e8, 5e8] {
        conds.push(named(&format!("Con 3, k_T = {kk:e}"), Condition::FixedAndSprings { k_t: kk }));
    }
    let line = Line::new(scene, &conds, b / 2.0)?;
    let mm = |x: f64| x * 1e3;
    let mut figs = Vec::new();
    let curve = |p: bool,
                 c: &SupportSet,
                 f: &dyn Fn(bool, &SupportSet, f64) -> Result<f64, Failure>|
     -> Result<Series, Failure> {
        let pts = line.xs.iter().map(|&x| Ok((mm(x), f(p, c, x)?))).collect::<Result<Vec<_>, Failure>>()?;
        Ok(Series::new(format!("{} {}", if p { "plate" } else { "beam" }, c.name), pts))
    };
    let vy_coal = |p: bool, c: &SupportSet, x: f64| line.vy(p, c, &paper.coal, x);
    let p_coal = |p: bool, c: &SupportSet, x: f64| Ok(line.response(p, c, &paper.coal, x, 0.008)?.contact_force);
    let defl = |p: bool, c: &SupportSet, x: f64| Ok(line.response(p, c, &paper.coal, x, 0.008)?.deflection * 1e6);
    let mut s8 = Vec::new();
    let mut s10 = Vec::new();
    let mut s10d = Vec::new();
    for c in &conds[..3] {
        for p in [false, true] {
            s8.push(curve(p, c, &vy_coal)?);
            s10.push(curve(p, c, &p_coal)?);
            s10d.push(curve(p, c, &defl)?);
        }
    }
    figs.push(figure(
        "study-fig08-yield-coal",
        "Fig. 8 redone: coal yield velocity along the centreline",
        "v_y (m/s)",
        s8,
    ));
    figs.push(figure(
        "study-fig10-contact-force",
        "Fig. 10(1) redone: coal P_max at 0.008 m/s, centreline",
        "P_max (N)",
        s10,
    ));
    figs.push(figure(
        "study-fig10-deflection",
        "Fig. 10(3) redone: impact-point deflection, centreline",
        "deflection (µm)",
        s10d,
    ));
    let mut s11 = Vec::new();
    for c in &conds[3..6] {
        for p in [false, true] {
            s11.push(curve(p, c, &vy_coal)?);
        }
    }
    figs.push(figure(
        "study-fig11-yield-stiffness",
        "Fig. 11 redone: coal yield velocity, Con 2, three k_T",
        "v_y (m/s)",
        s11,
    ));
    let mut s12 = Vec::new();
    let mut s13 = Vec::new();
    let spring_energy = |p: bool, c: &SupportSet, x: f64| Ok(line.response(p, c, &paper.coal, x, 0.008)?.spring_ratio);
    for c in &conds[3..] {
        for p in [false, true] {
            if c.name.starts_with("Con 3") {
                s12.push(curve(p, c, &vy_coal)?);
            }
            s13.push(curve(p, c, &spring_energy)?);
        }
    }
    figs.push(figure(
        "study-fig12-yield-stiffness-con3",
        "Fig. 12 redone: coal yield velocity, Con 3, three k_T",
        "v_y (m/s)",
        s12,
    ));
    figs.push(figure(
        "study-fig13-spring-energy",
        "Fig. 13(8) redone: spring energy ratio, coal 0.008 m/s, three k_T",
        "spring energy / E0",
        s13,
    ));
    // Figs. 18-19, Con 2 at 0.0025 m/s: the right-end spring force (beam: each of its two
    // springs; plate: the corner (L, 0) spring) and the spring energy ratio.
    let mut s18 = Vec::new();
    let mut s19 = Vec::new();
    for body in [&paper.coal, &paper.gangue1, &paper.gangue2] {
        for p in [false, true] {
            let label = format!("{} {}", if p { "plate" } else { "beam" }, body.name);
            let mut pts18 = Vec::new();
            let mut pts19 = Vec::new();
            for &x in &line.xs {
                let r = line.response(p, &conds[1], body, x, 0.0025)?;
                let f = r
                    .spring_forces
                    .iter()
                    .find(|s| s.name.contains("right") || s.name.ends_with("(L, 0)"))
                    .map_or(f64::NAN, |s| s.force);
                pts18.push((mm(x), f));
                pts19.push((mm(x), r.spring_ratio));
            }
            s18.push(Series::new(label.clone(), pts18));
            s19.push(Series::new(label, pts19));
        }
    }
    figs.push(figure(
        "study-fig18-spring-force",
        "Fig. 18 redone: right-end spring force, Con 2, 0.0025 m/s",
        "spring force (N)",
        s18,
    ));
    figs.push(figure(
        "study-fig19-spring-energy",
        "Fig. 19 redone: spring energy ratio, Con 2, 0.0025 m/s",
        "spring energy / E0",
        s19,
    ));
    let mut s17 = Vec::new();
    for body in [&paper.coal, &paper.gangue1, &paper.gangue2] {
        for p in [false, true] {
            let f = |p: bool, c: &SupportSet, x: f64| Ok(line.response(p, c, body, x, 0.0025)?.contact_force);
            let mut s = curve(p, &conds[0], &f)?;
            s.name = format!("{} {}", if p { "plate" } else { "beam" }, body.name);
            s17.push(s);
        }
    }
    figs.push(figure(
        "study-fig17-contact-force-bodies",
        "Fig. 17(2) redone: P_max of three spheres at 0.0025 m/s, Con 1",
        "P_max (N)",
        s17,
    ));
    let mut s15 = Vec::new();
    let mut s16 = Vec::new();
    let mut s14 = Vec::new();
    for f in [0.8, 1.0, 1.2, 1.4] {
        let plate = scene.plate.with_length(l * f)?;
        let s = Scene { plate, ..scene.clone() };
        let c1 = named("Con 1", Condition::BothFixed);
        // Section IV-C uses k_T = 5e6 N/m for the length study.
        let c2 = named("Con 2", Condition::BothSprings { k_t: 5e6 });
        let ln = Line::new(&s, &[c1.clone(), c2.clone()], b / 2.0)?;
        for p in [false, true] {
            let (mut f, mut e) = (Vec::new(), Vec::new());
            for &x in &ln.xs {
                let r = ln.response(p, &c2, &paper.coal, x, 0.008)?;
                // Left end: the beam's each spring, the plate's corner (0, 0) spring.
                let left = r
                    .spring_forces
                    .iter()
                    .find(|s| s.name.contains("left") || s.name.ends_with("(0, 0)"))
                    .map_or(f64::NAN, |s| s.force);
                f.push((mm(x), left));
                e.push((mm(x), r.spring_ratio));
            }
            let label = format!("{} L = {:.0} mm", if p { "plate" } else { "beam" }, plate.length() * 1e3);
            s15.push(Series::new(label.clone(), f));
            s16.push(Series::new(label, e));
        }
        for p in [false, true] {
            let pts = ln
                .xs
                .iter()
                .map(|&x| Ok((mm(x), ln.response(p, &c1, &paper.coal, x, 0.008)?.contact_force)))
                .collect::<Result<Vec<_>, Failure>>()?;
            s14.push(Series::new(
                format!("{} L = {:.0} mm", if p { "plate" } else { "beam" }, plate.length() * 1e3),
                pts,
            ));
        }
    }
    figs.push(figure(
        "study-fig15-spring-force-length",
        "Fig. 15 redone: left-end spring force, Con 2, k_T = 5e6 N/m, coal 0.008 m/s, four lengths",
        "spring force (N)",
        s15,
    ));
    figs.push(figure(
        "study-fig16-spring-energy-length",
        "Fig. 16 redone: spring energy ratio, Con 2, k_T = 5e6 N/m, four lengths",
        "spring energy / E0",
        s16,
    ));
    figs.push(figure(
        "study-fig14-contact-force-length",
        "Fig. 14(1) redone: coal P_max at 0.008 m/s, Con 1, four lengths",
        "P_max (N)",
        s14,
    ));
    Ok(figs)
}
