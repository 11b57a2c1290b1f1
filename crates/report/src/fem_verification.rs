//! The plate FE verification report (`reports/fem/index.md`): every check of the plate elements
//! with its reference, measured convergence rates and the extreme cases.

use crate::present::plot::{series_csv, Axis, Plot, Series};
use crate::present::table::{Cell, Table};
use analytic::Condition;
use coupled::discretisation::{ladder_meshes, mesh_for, plate_properties};
use coupled::supports::corner_supports;
use output::Artifacts;
use plate_fem::classical::{LevyPlate, YEdge};
use plate_fem::convergence::{observed_rate, richardson};
use plate_fem::{CornerFamily, EdgeSupport, FemError, Mesh, Model, PlateProperties, Supports};
use scene::Scene;

use crate::template::render;
use crate::Failure;

/// The report's prose: every section runs every time, so one template holds them all.
const TEMPLATE: &str = include_str!("templates/fem_verification.md");

/// The centre deflection coefficient of the simply supported square plate under a point
/// load as Timoshenko & Woinowsky-Krieger print it (Table 23), beside our summed series.
const TIMOSHENKO_TABLE_23: &str = "0.01160";
/// The off-centre Navier plate (m) and its load point.
const OFF_CENTRE: (f64, f64) = (1.0, 0.7);
const OFF_CENTRE_POINT: (f64, f64) = (0.3, 0.2);
/// The Lévy plate (m): ends simply supported, sides free.
const LEVY: (f64, f64) = (1.0, 0.6);
/// The paper's corner spring stiffness k_T, N/m.
const PAPER_K_T: f64 = 5.11545e8;
/// Elements across the short side in the aspect-ratio cases.
const SHORT_SIDE: usize = 16;

/// A length in mm as the prose writes it: to 0.1 mm, no trailing zeros.
fn mm(v: f64) -> String {
    ((v * 1e4).round() / 10.0).to_string()
}

/// The convergence figure: relative error of the point compliance against the element size
/// h (over the plate length L) on log-log axes, with the slope-2 line the r² ln r singularity
/// of the point-load Green's function predicts, drawn parallel to the first ladder (a third
/// below its finest point).
fn convergence_figure(ladders: &[(String, Vec<(f64, f64)>)]) -> Plot {
    let mut plot = Plot::new(
        "Plate FE: error of the point compliance against element size",
        Axis::log("h / L"),
        Axis::log("|C_FE / C_exact - 1|"),
    );
    for (name, pts) in ladders {
        plot = plot.with(Series::new(name.clone(), pts.clone()));
    }
    if let Some(&(h0, e0)) = ladders.first().and_then(|l| l.1.last()) {
        let (lo, hi) = ladders
            .iter()
            .flat_map(|l| l.1.iter().map(|p| p.0))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), h| (a.min(h), b.max(h)));
        // A third below the first ladder's finest point, so it runs beside the data, not on it.
        let e0 = e0 / 3.0;
        plot = plot
            .with(Series::guide("slope 2 (O(h²))", vec![(lo, e0 * (lo / h0).powi(2)), (hi, e0 * (hi / h0).powi(2))]));
    }
    plot
}

/// FE compliance at `p` for a ladder of meshes (n·2^k by m·2^k).
fn ladder(
    props: PlateProperties,
    supports: &Supports,
    n: usize,
    m: usize,
    levels: u32,
    p: (f64, f64),
) -> Result<Vec<(usize, usize, f64)>, FemError> {
    (0..levels)
        .map(|k| {
            let (nx, nz) = (n << k, m << k);
            let model = Model::new(props, Mesh::uniform(props.length, props.width, nx, nz)?)?;
            Ok((nx, nz, model.factorize(supports)?.with_refinement(1).respond(p.0, p.1)?.compliance))
        })
        .collect()
}

/// A convergence table against an exact value.
fn convergence_table(rows: &[(usize, usize, f64)], exact: f64) -> Table {
    let mut t =
        Table::new("", &["mesh", "C (m/N)", "rel. error", "observed rate", "Richardson value", "its rel. error"]);
    let vals: Vec<f64> = rows.iter().map(|r| r.2).collect();
    for (i, r) in rows.iter().enumerate() {
        let rate = if i >= 2 {
            observed_rate(vals[i - 2], vals[i - 1], vals[i]).map_or(Cell::Empty, |r| Cell::Sig(r, 4))
        } else {
            Cell::Empty
        };
        let (rv, re) = if i >= 1 {
            let e = richardson(&vals[..=i]).expect("two values").extrapolated;
            (Cell::Num(e), Cell::Sig((e - exact).abs() / exact, 2))
        } else {
            (Cell::Empty, Cell::Empty)
        };
        t.push(vec![
            format!("{} x {}", r.0, r.1).into(),
            r.2.into(),
            Cell::Sig((r.2 - exact).abs() / exact, 3),
            rate,
            rv,
            re,
        ]);
    }
    t
}

fn unit_plate(l: f64, b: f64, h: f64) -> PlateProperties {
    PlateProperties { length: l, width: b, thickness: h, youngs_modulus: 210e9, poisson_ratio: 0.3, density: 7850.0 }
}

/// A yes/no shown as "true"/"false".
fn truth(yes: bool) -> Cell {
    Cell::Flag { yes, shown: if yes { "true" } else { "false" } }
}

/// Writes the report.
pub fn report(scene: &Scene) -> Result<Artifacts, Failure> {
    let mut a = Artifacts::new();

    // 1. Navier, square, centre.
    let sq = unit_plate(1.0, 1.0, 0.01);
    let d = sq.rigidity();
    let navier = LevyPlate { a: 1.0, b: 1.0, d, nu: 0.3, y_edges: YEdge::Simple };
    let exact = navier.converged((0.5, 0.0), (0.5, 0.0), 1e-12);
    let rows = ladder(sq, &Supports::all_edges_simple(), 4, 4, 6, (0.5, 0.5))?;
    let navier_table = convergence_table(&rows, exact);
    let navier_vals: Vec<f64> = rows.iter().map(|r| r.2).collect();
    let navier_richardson = richardson(&navier_vals).map_or(f64::NAN, |r| (r.extrapolated - exact).abs() / exact);
    let navier_errors: Vec<(f64, f64)> = rows.iter().map(|r| (1.0 / r.0 as f64, (r.2 - exact).abs() / exact)).collect();
    a.add("navier-square.csv", navier_table.to_csv());
    let navier_coefficient = format!("{:.7}", exact * d);

    // 2. Navier off-centre.
    let (ol, ow) = OFF_CENTRE;
    let (ox, oz) = OFF_CENTRE_POINT;
    let rect = unit_plate(ol, ow, 0.01);
    let np = LevyPlate { a: ol, b: ow, d: rect.rigidity(), nu: 0.3, y_edges: YEdge::Simple };
    let exact = np.converged((ox, oz - ow / 2.0), (ox, oz - ow / 2.0), 1e-12);
    let rows = ladder(rect, &Supports::all_edges_simple(), 10, 7, 4, (ox, oz))?;
    let off_centre_table = convergence_table(&rows, exact);
    let off_errors: Vec<(f64, f64)> =
        rows.iter().map(|r| (ol / r.0 as f64 / ol, (r.2 - exact).abs() / exact)).collect();
    let convergence = convergence_figure(&[
        ("Navier, square, centre".to_string(), navier_errors),
        (format!("Navier, {ol} x {ow} m, at ({ox}, {oz})"), off_errors),
    ]);
    let finest_rate = |pts: &[(f64, f64)]| match pts {
        [.., a, b] => format!("{:.3}", (a.1 / b.1).ln() / (a.0 / b.0).ln()),
        _ => "-".into(),
    };
    let (navier_rate, off_rate) =
        (finest_rate(&convergence.series[0].points), finest_rate(&convergence.series[1].points));
    a.add("convergence.svg", convergence.svg());
    a.add("convergence.csv", series_csv(&convergence.series, "h/L", "rel. error"));
    a.add("navier-off-centre.csv", off_centre_table.to_csv());

    // 3. Lévy SS-free-SS-free.
    let lp = unit_plate(LEVY.0, LEVY.1, 0.01);
    let levy = LevyPlate { a: LEVY.0, b: LEVY.1, d: lp.rigidity(), nu: 0.3, y_edges: YEdge::Free };
    let mut lt = Table::new(
        "",
        &[
            "load point",
            "series C (m/N)",
            "FE 24 x 16",
            "rel. error",
            "FE 96 x 64",
            "rel. error",
            "observed rate",
            "Richardson rel. error",
        ],
    );
    let mut levy_worst = 0.0f64;
    for (x, z) in [(0.5, 0.3), (0.25, 0.3), (0.5, 0.15), (0.5, 0.6), (0.1, 0.6)] {
        let exact = levy.converged((x, z - LEVY.1 / 2.0), (x, z - LEVY.1 / 2.0), 1e-12);
        let rows = ladder(lp, &Supports::simple_free(), 24, 16, 3, (x, z))?;
        let v: Vec<f64> = rows.iter().map(|r| r.2).collect();
        let ext = richardson(&v).expect("three values");
        levy_worst = levy_worst.max((ext.extrapolated - exact).abs() / exact);
        lt.push(vec![
            format!("({x}, {z})").into(),
            exact.into(),
            v[0].into(),
            ((v[0] - exact).abs() / exact).into(),
            v[2].into(),
            ((v[2] - exact).abs() / exact).into(),
            ext.observed_rate.map_or(Cell::Empty, Cell::Num),
            ((ext.extrapolated - exact).abs() / exact).into(),
        ]);
    }
    a.add("levy-simple-free.csv", lt.to_csv());

    // 4. Narrow plate against the beam.
    let mut nt = Table::new(
        "",
        &["B/L", "C_plate / C_beam, centre", "quarter span", "load on the free edge", "(centre ratio - 1)/(B/L)²"],
    );
    // (centre ratio - 1)/(B/L)² of the narrowest plate: the coefficient of the limit.
    let mut narrow_coefficient = f64::NAN;
    for bl in [4.0, 2.0, 1.0, 0.5, 0.2, 0.1, 0.05, 0.02] {
        let (l, h, e, nu) = (1.0f64, 0.01f64, 210e9f64, 0.3f64);
        let b = bl * l;
        let plate = LevyPlate { a: l, b, d: unit_plate(l, b, h).rigidity(), nu, y_edges: YEdge::Free };
        let ei = e * b * h.powi(3) / 12.0;
        let beam = |x: f64| (x * (l - x)).powi(2) / (3.0 * ei * l);
        let c = plate.converged((0.5, 0.0), (0.5, 0.0), 1e-10) / beam(0.5);
        let q = plate.converged((0.25, 0.0), (0.25, 0.0), 1e-10) / beam(0.25);
        let ed = plate.converged((0.5, b / 2.0), (0.5, b / 2.0), 1e-10) / beam(0.5);
        narrow_coefficient = (c - 1.0) / (bl * bl);
        nt.push(vec![bl.into(), c.into(), q.into(), ed.into(), narrow_coefficient.into()]);
    }
    a.add("narrow-plate-vs-beam.csv", nt.to_csv());

    // 5. The paper's plate: ladders at several points for Con 1-3.
    let props = plate_properties(&scene.plate);
    let k_t = scene.conditions.iter().find_map(|c| c.spring_stiffnesses().next()).unwrap_or(PAPER_K_T);
    let (l, b) = (props.length, props.width);
    let pts = [
        ("centre", (l / 2.0, b / 2.0)),
        ("(L/4, B/4)", (l / 4.0, b / 4.0)),
        ("edge (L/2, 0)", (l / 2.0, 0.0)),
        ("end (0, B/2)", (0.0, b / 2.0)),
        ("near corner (L/20, B/20)", (l / 20.0, b / 20.0)),
    ];
    let mut pt = Table::new(
        "",
        &[
            "condition",
            "point",
            "C on 80 x 64 (m/N)",
            "Richardson (m/N)",
            "error 40 x 32 vs Richardson",
            "estimated error 80 x 64",
            "observed rate",
            "asymptotic",
        ],
    );
    let meshes = ladder_meshes(&props, 10, 4)?;
    let (corner_name, _) = pts[pts.len() - 1];
    let mut corner_rates = Vec::new();
    for (name, cond) in [
        ("Con 1", Condition::BothFixed),
        ("Con 2", Condition::BothSprings { k_t }),
        ("Con 3", Condition::FixedAndSprings { k_t }),
    ] {
        let mut per_mesh: Vec<Vec<f64>> = Vec::new();
        for mesh in &meshes {
            let model = Model::new(props, mesh.clone())?;
            let f = model.factorize(&corner_supports(cond))?.with_refinement(1);
            let r = f.respond_many(&pts.iter().map(|p| p.1).collect::<Vec<_>>())?;
            per_mesh.push(r.iter().map(|r| r.compliance).collect());
        }
        for (i, (pname, _)) in pts.iter().enumerate() {
            let v: Vec<f64> = per_mesh.iter().map(|m| m[i]).collect();
            let ext = richardson(&v).expect("four values");
            if *pname == corner_name && !ext.asymptotic {
                if let Some(r) = ext.observed_rate {
                    corner_rates.push((name, r));
                }
            }
            let err = |c: f64| {
                if ext.extrapolated != 0.0 {
                    Cell::Num((c - ext.extrapolated).abs() / ext.extrapolated)
                } else {
                    Cell::Empty
                }
            };
            pt.push(vec![
                name.into(),
                pname.to_string().into(),
                v[3].into(),
                ext.extrapolated.into(),
                err(v[2]),
                Cell::Num(ext.error_estimate / ext.extrapolated.abs()),
                ext.observed_rate.map_or(Cell::Empty, Cell::Num),
                (if ext.asymptotic { "yes" } else { "no: estimate is the last difference" }).into(),
            ]);
        }
    }
    let pt = pt.csv_name("asymptotic", &["asymptotic_verdict"]);
    a.add("paper-plate-convergence.csv", pt.to_csv());

    // 6. Rank-4 corner update against fresh factorizations, k_T from 1 to 1e15.
    let model = Model::new(props, mesh_for(&props, 40)?)?;
    let family = CornerFamily::new(&model, [EdgeSupport::Free; 4], CornerFamily::default_base_stiffness(&model))?;
    let probe = [(l / 2.0, b / 2.0), (l / 4.0, 0.0), (l, b / 2.0), (0.0, 0.0)];
    let base = family.probe_many(&probe)?;
    let c1_centre = family.respond(&base[0], corner_supports(Condition::BothFixed).corners)?.compliance;
    let mut update_difference = 0.0f64;
    let mut kt = Table::new(
        "",
        &[
            "k_T (N/m)",
            "condition",
            "point",
            "C, one factorization: update or condensation (m/N)",
            "C, fresh factorization (m/N)",
            "rel. difference",
            "fresh residual",
            "exact (Con 2 centre)",
            "update error",
            "fresh error",
        ],
    );
    for k in [1.0, 1e2, 1e4, 5e4, 1e6, PAPER_K_T, 1e10, 1e12, 1e15] {
        for (name, cond) in
            [("Con 2", Condition::BothSprings { k_t: k }), ("Con 3", Condition::FixedAndSprings { k_t: k })]
        {
            let corners = corner_supports(cond).corners;
            let fresh = model.factorize(&Supports::corners(corners))?.with_refinement(2).respond_many(&probe)?;
            for (bp, fr) in base.iter().zip(&fresh) {
                let up = family.respond(bp, corners)?;
                // At the centre of Con 2 each spring carries exactly 1/4 by double symmetry, so
                // the plate deforms as with fixed corners: C = C_Con1 + 1/(4k), exactly.
                let centre = name == "Con 2" && bp.x == l / 2.0 && bp.z == b / 2.0;
                let exact = if centre { c1_centre + 0.25 / k } else { f64::NAN };
                let err = |c: f64| if exact.is_nan() { Cell::Empty } else { Cell::Num((c - exact).abs() / exact) };
                if k == PAPER_K_T && fr.compliance != 0.0 {
                    update_difference =
                        update_difference.max((up.compliance - fr.compliance).abs() / fr.compliance.abs());
                }
                let diff = if fr.compliance != 0.0 {
                    Cell::Num((up.compliance - fr.compliance).abs() / fr.compliance.abs())
                } else {
                    // No relative difference to a zero compliance: the absolute one, as a note.
                    Cell::Noted { value: f64::NAN, digits: 2, note: format!("abs {:.1e}", up.compliance.abs()) }
                };
                kt.push(vec![
                    k.into(),
                    name.into(),
                    Cell::Pair { x: bp.x, z: bp.z, scale: 1.0, decimals: 4 },
                    up.compliance.into(),
                    fr.compliance.into(),
                    diff,
                    fr.residual.into(),
                    if exact.is_nan() { Cell::Empty } else { Cell::Num(exact) },
                    err(up.compliance),
                    err(fr.compliance),
                ]);
            }
        }
    }
    let kt = kt.csv_name("point", &["x_m", "z_m"]);
    a.add("corner-update.csv", kt.to_csv());

    // 7. Extreme geometry.
    let mut xt = Table::new("", &["case", "mesh", "C (m/N)", "reference", "rel. error", "max residual", "finite"]);
    // h/L: Kirchhoff C ∝ 1/h³ exactly; C·h³ must not move.
    let c_ref = {
        let p = unit_plate(l, b, 0.008);
        let m = Model::new(p, mesh_for(&p, 20)?)?;
        m.factorize(&Supports::con1())?.respond(l / 2.0, b / 2.0)?.compliance * 0.008f64.powi(3)
    };
    let thickness_ratios = [1e-3, 1e-2, 0.0175, 0.1, 0.2];
    for hl in thickness_ratios {
        let h = hl * l;
        let p = unit_plate(l, b, h);
        let m = Model::new(p, mesh_for(&p, 20)?)?;
        let r = m.factorize(&Supports::con1())?.respond(l / 2.0, b / 2.0)?;
        xt.push(vec![
            format!("h/L = {hl}, Con 1 centre").into(),
            "20 x 16".into(),
            r.compliance.into(),
            "C·h³ of h = 8 mm".into(),
            ((r.compliance * h.powi(3) - c_ref) / c_ref).abs().into(),
            r.residual.into(),
            truth(r.compliance.is_finite()),
        ]);
    }
    // B/L: the Lévy plate (simply supported ends, free sides) against its series.
    let aspect_ratios = [0.05, 0.2, 1.0, 5.0, 20.0];
    for bl in aspect_ratios {
        let bb = bl * 0.4584;
        let p = unit_plate(0.4584, bb, 0.008);
        // Near-square elements, 16 across the short side.
        let long = (SHORT_SIDE as f64 * bl.max(1.0 / bl)).round() as usize;
        let (nx, nz) = if bl < 1.0 { (long, SHORT_SIDE) } else { (SHORT_SIDE, long) };
        let m = Model::new(p, Mesh::uniform(0.4584, bb, nx, nz)?)?;
        let r = m.factorize(&Supports::simple_free())?.respond(0.2292, bb / 2.0)?;
        let exact = LevyPlate { a: 0.4584, b: bb, d: p.rigidity(), nu: 0.3, y_edges: YEdge::Free }.converged(
            (0.2292, 0.0),
            (0.2292, 0.0),
            1e-11,
        );
        xt.push(vec![
            format!("B/L = {bl}, simply supported ends, centre").into(),
            format!("{nx} x {nz}").into(),
            r.compliance.into(),
            "Lévy series".into(),
            ((r.compliance - exact) / exact).abs().into(),
            r.residual.into(),
            truth(r.compliance.is_finite()),
        ]);
    }
    // Points on edges and corners, Con 1-3 with the scene's k_T, on the 40 x 32 mesh.
    for (name, cond) in [
        ("Con 1", Condition::BothFixed),
        ("Con 2", Condition::BothSprings { k_t }),
        ("Con 3", Condition::FixedAndSprings { k_t }),
    ] {
        let f = model.factorize(&corner_supports(cond))?.with_refinement(1);
        for (pname, p) in [
            ("corner (0, 0)", (0.0, 0.0)),
            ("corner (L, B)", (l, b)),
            ("edge (L/2, B)", (l / 2.0, b)),
            ("end (L, B/2)", (l, b / 2.0)),
        ] {
            let r = f.respond(p.0, p.1)?;
            let expected = match (cond, pname.starts_with("corner")) {
                (Condition::BothFixed, true) => "0 (fixed corner)".to_string(),
                (Condition::BothSprings { k_t }, true) => {
                    format!("just below 1/k_T = {:.4e} (the plate relieves the spring)", 1.0 / k_t)
                }
                (Condition::FixedAndSprings { .. }, true) if p.0 == 0.0 => "0 (fixed corner)".into(),
                (Condition::FixedAndSprings { k_t }, true) => {
                    format!("just below 1/k_T = {:.4e} (the plate relieves the spring)", 1.0 / k_t)
                }
                _ => "finite, positive".into(),
            };
            xt.push(vec![
                format!("{name}, {pname}").into(),
                "40 x 32".into(),
                r.compliance.into(),
                expected.into(),
                Cell::Empty,
                r.residual.into(),
                truth(r.compliance.is_finite() && r.compliance >= -1e-25),
            ]);
        }
    }
    a.add("extreme-cases.csv", xt.to_csv());
    // 8. Against scikit-fem (committed data).
    let mut st = Table::new(
        "",
        &[
            "case",
            "x (mm)",
            "z (mm)",
            "BFS extrapolated (m/N)",
            "± estimate",
            "Argyris extrapolated (m/N)",
            "± estimate",
            "rel. difference",
            "Morley 160 x 128",
            "bracketed",
        ],
    );
    let (mut bfs_finest, mut argyris_finest) = (String::new(), String::new());
    let mut skfem_worst = 0.0f64;
    for name in crate::skfem::CASES {
        let case = crate::skfem::load(name)?;
        let bfs = crate::skfem::rust_runs(&case, 4)?;
        let (ours, arg) = (crate::skfem::extrapolate(&bfs), crate::skfem::extrapolate(&case.argyris));
        let morley = &case.morley.last().ok_or("no Morley runs")?.compliance;
        let finest = &bfs.last().ok_or("no BFS runs")?.compliance;
        let mesh = |r: Option<&crate::skfem::Run>| r.map_or(String::new(), |r| format!("{} x {}", r.nx, r.nz));
        bfs_finest = mesh(bfs.last());
        argyris_finest = mesh(case.argyris.last());
        for (i, (r, g)) in ours.iter().zip(&arg).enumerate() {
            let (x, z) = case.points[i];
            let zero = g.extrapolated.abs() < 1e-20;
            if !zero {
                skfem_worst = skfem_worst.max((r.extrapolated - g.extrapolated).abs() / g.extrapolated);
            }
            st.push(vec![
                name.into(),
                Cell::Given(x * 1e3),
                Cell::Given(z * 1e3),
                r.extrapolated.into(),
                r.error_estimate.into(),
                g.extrapolated.into(),
                g.error_estimate.into(),
                // Both 0 on a supported edge: no relative difference exists.
                if zero { Cell::Empty } else { Cell::Num((r.extrapolated - g.extrapolated).abs() / g.extrapolated) },
                morley[i].into(),
                {
                    let yes = zero
                        || (finest[i] <= r.extrapolated * (1.0 + 1e-9) && morley[i] >= r.extrapolated * (1.0 - 1e-9));
                    Cell::Flag { yes, shown: if yes { "yes" } else { "NO" } }
                },
            ]);
        }
    }
    a.add("skfem-comparison.csv", st.to_csv());
    let versions = crate::skfem::load(crate::skfem::CASES[0])?.versions;
    let timing = std::fs::read_to_string(crate::skfem::data_dir().join("timing.csv")).unwrap_or_default();
    let mut tt = Table::new("", &["code", "element", "mesh", "DOFs", "time (s)", "rel. error"]);
    for line in timing.lines().skip(1) {
        let c: Vec<&str> = line.split(',').collect();
        if c.len() == 7 {
            let num = |t: &str| {
                t.parse::<u64>()
                    .map(Cell::Int)
                    .or_else(|_| t.parse::<f64>().map(Cell::Num))
                    .unwrap_or(Cell::Text(t.into()))
            };
            tt.push(vec![c[0].into(), c[1].into(), c[2].into(), num(c[3]), num(c[4]), num(c[6])]);
        }
    }
    let family_twist = family.twist_stiffness_value().ok_or("the paper's plate has free edges")?;
    let kb = family.k_base();
    // The springs for which the update's a-priori bound stays within UPDATE_ERROR_BOUND
    // (crates/plate_fem/src/corners.rs): the soft end from the condition growth, the stiff
    // end from the round-off of k w.
    let bound = plate_fem::corners::UPDATE_ERROR_BOUND;
    let window_from = f64::EPSILON * kb * (1.0 + kb / (4.0 * family_twist)) / bound;
    let window_to = bound * kb / f64::EPSILON;
    let (coarsest, finest) = (meshes.first().ok_or("no mesh")?, meshes.last().ok_or("no mesh")?);
    let corner_conditions: Vec<&str> = corner_rates.iter().map(|(c, _)| *c).collect();
    // The rates as printed, each once (the support sets share the corner's mesh behaviour).
    let mut corner_rates: Vec<String> = corner_rates.iter().map(|(_, r)| format!("{r:.2}")).collect();
    corner_rates.dedup();
    let version_list = versions
        .as_object()
        .map(|o| o.iter().map(|(k, v)| format!("{k} {}", v.as_str().unwrap_or("?"))).collect::<Vec<_>>().join(", "))
        .unwrap_or_default();
    let md = render(
        "fem_verification.md",
        TEMPLATE,
        &[
            ("navier_coefficient", navier_coefficient),
            ("timoshenko_coefficient", TIMOSHENKO_TABLE_23.into()),
            ("navier_table", navier_table.to_markdown()),
            ("off_length", ol.to_string()),
            ("off_width", ow.to_string()),
            ("off_x", ox.to_string()),
            ("off_z", oz.to_string()),
            ("off_centre_table", off_centre_table.to_markdown()),
            ("levy_length", LEVY.0.to_string()),
            ("levy_width", LEVY.1.to_string()),
            ("levy_table", lt.to_markdown()),
            ("narrow_coefficient", format!("{:.2}", -narrow_coefficient)),
            ("paper_aspect", format!("{:.3}", b / l)),
            ("narrow_table", nt.to_markdown()),
            ("paper_length", mm(l)),
            ("paper_width", mm(b)),
            ("paper_thickness", mm(props.thickness)),
            ("coarsest", format!("{} x {}", coarsest.nx(), coarsest.nz())),
            ("finest", format!("{} x {}", finest.nx(), finest.nz())),
            ("corner_rates", corner_rates.join(", ")),
            ("corner_point", corner_name.trim_start_matches("near corner ").to_string()),
            ("corner_conditions", corner_conditions.join(", ")),
            ("paper_table", pt.to_markdown()),
            ("base_factor", format!("{:.0e}", kb * l * b / props.rigidity())),
            ("base_stiffness", format!("{:.3e}", CornerFamily::default_base_stiffness(&model))),
            ("update_mesh", format!("{} x {}", model.mesh().nx(), model.mesh().nz())),
            ("update_bound", format!("{bound:e}")),
            ("window_from", format!("{window_from:.1e}")),
            ("window_to", format!("{window_to:.1e}")),
            ("update_difference", format!("{update_difference:.0e}")),
            ("paper_k", format!("{PAPER_K_T:.1e}")),
            ("update_table", kt.to_markdown()),
            ("thickest", thickness_ratios[thickness_ratios.len() - 1].to_string()),
            ("aspect_from", aspect_ratios[0].to_string()),
            ("aspect_to", aspect_ratios[aspect_ratios.len() - 1].to_string()),
            ("short_side", SHORT_SIDE.to_string()),
            ("extreme_table", xt.to_markdown()),
            ("versions", version_list),
            ("bfs_finest", bfs_finest),
            ("argyris_finest", argyris_finest),
            ("skfem_table", st.to_markdown()),
            ("timing_table", tt.to_markdown()),
            ("navier_rate_summary", navier_rate.clone()),
            ("navier_rate", navier_rate),
            ("navier_richardson", format!("{navier_richardson:.1e}")),
            ("levy_worst", format!("{levy_worst:.1e}")),
            ("narrow_summary", format!("{:.2}", -narrow_coefficient)),
            ("update_summary", format!("{update_difference:.0e}")),
            ("skfem_worst", format!("{skfem_worst:.1e}")),
            ("off_rate", off_rate),
        ],
    )?;
    a.add("index.md", md);
    Ok(a)
}
