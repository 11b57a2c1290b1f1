//! The plate model on the scene's own plate: Richardson ladders under Con 1-3, the rank-4
//! corner update against fresh factorizations, and the extreme cases (thickness, aspect
//! ratio, load on an edge or a corner).

use super::classical::unit_plate;
use super::PAPER_K_T;
use crate::Failure;
use analytic::Condition;
use coupled::discretisation::{ladder_meshes, mesh_for};
use coupled::supports::corner_supports;
use plate_fem::classical::{LevyPlate, YEdge};
use plate_fem::convergence::richardson;
use plate_fem::{CornerFamily, EdgeSupport, FemError, Mesh, Model, PlateProperties, Supports};
use serde::Serialize;

/// Elements across the short side in the aspect-ratio cases.
pub const SHORT_SIDE: usize = 16;
/// The spring stiffnesses of the corner-update check, N/m: from nearly free corners to
/// nearly fixed ones, the paper's k_T among them.
pub const UPDATE_SPRINGS: [f64; 9] = [1.0, 1e2, 1e4, 5e4, 1e6, PAPER_K_T, 1e10, 1e12, 1e15];
/// h/L of the thickness cases: Kirchhoff's C ∝ 1/h³ must hold for every one.
pub const THICKNESS_RATIOS: [f64; 5] = [1e-3, 1e-2, 0.0175, 0.1, 0.2];
/// B/L of the aspect-ratio cases.
pub const ASPECT_RATIOS: [f64; 5] = [0.05, 0.2, 1.0, 5.0, 20.0];
/// The reference thickness of the thickness cases, m: C·h³ of this plate.
pub const REFERENCE_THICKNESS: f64 = 0.008;
/// The length of the aspect-ratio plates, m (the paper's L).
const ASPECT_LENGTH: f64 = 0.4584;

/// Con 1-3 with corner spring stiffness `k_t`, by name.
fn conditions(k_t: f64) -> [(&'static str, Condition); 3] {
    [
        ("Con 1", Condition::BothFixed),
        ("Con 2", Condition::BothSprings { k_t }),
        ("Con 3", Condition::FixedAndSprings { k_t }),
    ]
}

/// One support set and load point of the ladders on the scene's plate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PaperPlateRow {
    /// "Con 1", "Con 2" or "Con 3".
    pub condition: String,
    /// The point's name.
    pub point: String,
    /// C on the finest mesh, m/N.
    pub finest: f64,
    /// The Richardson value of the ladder, m/N.
    pub extrapolated: f64,
    /// |C(second finest)/Richardson - 1|; none where the Richardson value is 0.
    pub second_error: Option<f64>,
    /// The estimated error of the finest mesh, relative.
    pub estimate: f64,
    /// From the three finest meshes.
    pub observed_rate: Option<f64>,
    /// Whether the rate lies in [1.5, 2.5] (else the estimate is the last difference).
    pub asymptotic: bool,
}

/// Ladders of four meshes on the scene's plate at five points under Con 1-3.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PaperPlate {
    /// Condition by condition, point by point.
    pub rows: Vec<PaperPlateRow>,
    /// The coarsest mesh (nx, nz).
    pub coarsest: (usize, usize),
    /// The finest mesh (nx, nz).
    pub finest: (usize, usize),
    /// The point near the corner, where the rate is not 2.
    pub corner_point: String,
    /// The observed rates at it, where not asymptotic: (condition, rate).
    pub corner_rates: Vec<(String, f64)>,
}

/// The ladders of [`PaperPlate`] for the plate `props` with springs `k_t`.
pub fn ladders(props: PlateProperties, k_t: f64) -> Result<PaperPlate, Failure> {
    let (l, b) = (props.length, props.width);
    let pts = [
        ("centre", (l / 2.0, b / 2.0)),
        ("(L/4, B/4)", (l / 4.0, b / 4.0)),
        ("edge (L/2, 0)", (l / 2.0, 0.0)),
        ("end (0, B/2)", (0.0, b / 2.0)),
        ("near corner (L/20, B/20)", (l / 20.0, b / 20.0)),
    ];
    let meshes = ladder_meshes(&props, 10, 4)?;
    let (corner_name, _) = pts[pts.len() - 1];
    let (mut rows, mut corner_rates) = (Vec::new(), Vec::new());
    for (name, cond) in conditions(k_t) {
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
                    corner_rates.push((name.to_string(), r));
                }
            }
            let x = ext.extrapolated;
            rows.push(PaperPlateRow {
                condition: name.into(),
                point: pname.to_string(),
                finest: v[3],
                extrapolated: x,
                second_error: (x != 0.0).then(|| (v[2] - x).abs() / x),
                estimate: ext.error_estimate / x.abs(),
                observed_rate: ext.observed_rate,
                asymptotic: ext.asymptotic,
            });
        }
    }
    let size = |m: &Mesh| (m.nx(), m.nz());
    Ok(PaperPlate {
        rows,
        coarsest: meshes.first().map(size).ok_or("no mesh")?,
        finest: meshes.last().map(size).ok_or("no mesh")?,
        corner_point: corner_name.trim_start_matches("near corner ").to_string(),
        corner_rates,
    })
}

/// One spring stiffness, condition and point of the corner-update check.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct UpdateRow {
    /// k_T, N/m.
    pub k_t: f64,
    /// Con 2 or Con 3.
    pub con: u8,
    /// The point (m).
    pub point: (f64, f64),
    /// C by the update from one factorization, m/N.
    pub update: f64,
    /// C by a fresh factorization, m/N.
    pub fresh: f64,
    /// |update/fresh - 1|; none where the fresh C is 0.
    pub difference: Option<f64>,
    /// The fresh solve's relative residual.
    pub fresh_residual: f64,
    /// The exact C (Con 2 at the centre: C_Con1 + 1/(4k)).
    pub exact: Option<f64>,
}

/// The rank-4 corner update against fresh factorizations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CornerUpdate {
    /// Every row.
    pub rows: Vec<UpdateRow>,
    /// The mesh (nx, nz).
    pub mesh: (usize, usize),
    /// The family's default base stiffness, N/m.
    pub base_stiffness: f64,
    /// The base stiffness k_b, N/m.
    pub k_base: f64,
    /// The update's a-priori error bound.
    pub bound: f64,
    /// The springs for which the bound holds, N/m: from the condition growth at the soft end
    /// to the round-off of k w at the stiff end.
    pub window: (f64, f64),
    /// The largest |update/fresh - 1| at the paper's k_T.
    pub paper_difference: f64,
}

/// The corner update on the 40-element mesh of `props`, and that model (the extreme cases'
/// edge and corner points use it).
pub fn corner_update(props: PlateProperties) -> Result<(CornerUpdate, Model), Failure> {
    let (l, b) = (props.length, props.width);
    let model = Model::new(props, mesh_for(&props, 40)?)?;
    let family = CornerFamily::new(&model, [EdgeSupport::Free; 4], CornerFamily::default_base_stiffness(&model))?;
    let probe = [(l / 2.0, b / 2.0), (l / 4.0, 0.0), (l, b / 2.0), (0.0, 0.0)];
    let base = family.probe_many(&probe)?;
    let c1_centre = family.respond(&base[0], corner_supports(Condition::BothFixed).corners)?.compliance;
    let mut paper_difference = 0.0f64;
    let mut rows = Vec::new();
    for k in UPDATE_SPRINGS {
        for (con, cond) in [(2, Condition::BothSprings { k_t: k }), (3, Condition::FixedAndSprings { k_t: k })] {
            let corners = corner_supports(cond).corners;
            let fresh = model.factorize(&Supports::corners(corners))?.with_refinement(2).respond_many(&probe)?;
            for (bp, fr) in base.iter().zip(&fresh) {
                let up = family.respond(bp, corners)?;
                // At the centre of Con 2 each spring carries exactly 1/4 by double symmetry, so
                // the plate deforms as with fixed corners: C = C_Con1 + 1/(4k), exactly.
                let centre = con == 2 && bp.x == l / 2.0 && bp.z == b / 2.0;
                let difference =
                    (fr.compliance != 0.0).then(|| (up.compliance - fr.compliance).abs() / fr.compliance.abs());
                if k == PAPER_K_T {
                    paper_difference = paper_difference.max(difference.unwrap_or(0.0));
                }
                rows.push(UpdateRow {
                    k_t: k,
                    con,
                    point: (bp.x, bp.z),
                    update: up.compliance,
                    fresh: fr.compliance,
                    difference,
                    fresh_residual: fr.residual,
                    exact: centre.then(|| c1_centre + 0.25 / k),
                });
            }
        }
    }
    let family_twist = family.twist_stiffness_value().ok_or("the paper's plate has free edges")?;
    let kb = family.k_base();
    let bound = plate_fem::corners::UPDATE_ERROR_BOUND;
    let update = CornerUpdate {
        rows,
        mesh: (model.mesh().nx(), model.mesh().nz()),
        base_stiffness: CornerFamily::default_base_stiffness(&model),
        k_base: kb,
        bound,
        window: (f64::EPSILON * kb * (1.0 + kb / (4.0 * family_twist)) / bound, bound * kb / f64::EPSILON),
        paper_difference,
    };
    Ok((update, model))
}

/// An extreme case.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum ExtremeCase {
    /// Con 1 at the centre with h = ratio · L.
    Thickness {
        /// h/L.
        ratio: f64,
    },
    /// The Lévy plate of the paper's L with B = ratio · L, at its centre.
    Aspect {
        /// B/L.
        ratio: f64,
    },
    /// A support set at an edge or corner point.
    Support {
        /// "Con 1", "Con 2" or "Con 3".
        condition: String,
        /// The point's name.
        point: String,
    },
}

/// What an extreme case is checked against.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum ExtremeReference {
    /// C·h³ of the [`REFERENCE_THICKNESS`] plate (Kirchhoff: C ∝ 1/h³).
    ThicknessScaling,
    /// The Lévy series.
    LevySeries,
    /// 0: a fixed corner.
    FixedCorner,
    /// Just below 1/k_T: the plate relieves the spring.
    SpringCorner {
        /// k_T, N/m.
        k_t: f64,
    },
    /// Finite and positive.
    FinitePositive,
}

/// One extreme case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExtremeRow {
    /// The case.
    pub case: ExtremeCase,
    /// The mesh (nx, nz).
    pub mesh: (usize, usize),
    /// C, m/N.
    pub compliance: f64,
    /// What it is checked against.
    pub reference: ExtremeReference,
    /// The relative error against the reference, where it is a number.
    pub error: Option<f64>,
    /// The solve's relative residual.
    pub residual: f64,
    /// Finite (and, at edge and corner points, not negative beyond round-off).
    pub finite: bool,
}

/// Con 1's centre for h/L of [`THICKNESS_RATIOS`], Lévy plates of [`ASPECT_RATIOS`], and
/// edge and corner points under Con 1-3 on `model`.
pub fn extremes(props: PlateProperties, model: &Model, k_t: f64) -> Result<Vec<ExtremeRow>, FemError> {
    let (l, b) = (props.length, props.width);
    let mut out = Vec::new();
    // h/L: Kirchhoff C ∝ 1/h³ exactly; C·h³ must not move.
    let c_ref = {
        let p = unit_plate(l, b, REFERENCE_THICKNESS);
        let m = Model::new(p, mesh_for(&p, 20)?)?;
        m.factorize(&Supports::con1())?.respond(l / 2.0, b / 2.0)?.compliance * REFERENCE_THICKNESS.powi(3)
    };
    for hl in THICKNESS_RATIOS {
        let h = hl * l;
        let p = unit_plate(l, b, h);
        let m = Model::new(p, mesh_for(&p, 20)?)?;
        let r = m.factorize(&Supports::con1())?.respond(l / 2.0, b / 2.0)?;
        out.push(ExtremeRow {
            case: ExtremeCase::Thickness { ratio: hl },
            mesh: (m.mesh().nx(), m.mesh().nz()),
            compliance: r.compliance,
            reference: ExtremeReference::ThicknessScaling,
            error: Some(((r.compliance * h.powi(3) - c_ref) / c_ref).abs()),
            residual: r.residual,
            finite: r.compliance.is_finite(),
        });
    }
    for bl in ASPECT_RATIOS {
        out.push(aspect(bl)?);
    }
    out.extend(edges_and_corners(props, model, k_t)?);
    Ok(out)
}

/// The Lévy plate of B/L = `bl` at its centre on near-square elements, [`SHORT_SIDE`] across
/// the short side, against its series.
fn aspect(bl: f64) -> Result<ExtremeRow, FemError> {
    let bb = bl * ASPECT_LENGTH;
    let p = unit_plate(ASPECT_LENGTH, bb, REFERENCE_THICKNESS);
    let long = (SHORT_SIDE as f64 * bl.max(1.0 / bl)).round() as usize;
    let (nx, nz) = if bl < 1.0 { (long, SHORT_SIDE) } else { (SHORT_SIDE, long) };
    let m = Model::new(p, Mesh::uniform(ASPECT_LENGTH, bb, nx, nz)?)?;
    let mid = ASPECT_LENGTH / 2.0;
    let r = m.factorize(&Supports::simple_free())?.respond(mid, bb / 2.0)?;
    let exact = LevyPlate { a: ASPECT_LENGTH, b: bb, d: p.rigidity(), nu: 0.3, y_edges: YEdge::Free }.converged(
        (mid, 0.0),
        (mid, 0.0),
        1e-11,
    );
    Ok(ExtremeRow {
        case: ExtremeCase::Aspect { ratio: bl },
        mesh: (nx, nz),
        compliance: r.compliance,
        reference: ExtremeReference::LevySeries,
        error: Some(((r.compliance - exact) / exact).abs()),
        residual: r.residual,
        finite: r.compliance.is_finite(),
    })
}

/// Points on edges and corners under Con 1-3 with springs `k_t`, on `model`.
fn edges_and_corners(props: PlateProperties, model: &Model, k_t: f64) -> Result<Vec<ExtremeRow>, FemError> {
    let (l, b) = (props.length, props.width);
    let mut out = Vec::new();
    for (name, cond) in conditions(k_t) {
        let f = model.factorize(&corner_supports(cond))?.with_refinement(1);
        for (pname, p) in [
            ("corner (0, 0)", (0.0, 0.0)),
            ("corner (L, B)", (l, b)),
            ("edge (L/2, B)", (l / 2.0, b)),
            ("end (L, B/2)", (l, b / 2.0)),
        ] {
            let r = f.respond(p.0, p.1)?;
            let reference = match (cond, pname.starts_with("corner")) {
                (Condition::BothFixed, true) => ExtremeReference::FixedCorner,
                (Condition::BothSprings { k_t }, true) => ExtremeReference::SpringCorner { k_t },
                (Condition::FixedAndSprings { .. }, true) if p.0 == 0.0 => ExtremeReference::FixedCorner,
                (Condition::FixedAndSprings { k_t }, true) => ExtremeReference::SpringCorner { k_t },
                _ => ExtremeReference::FinitePositive,
            };
            out.push(ExtremeRow {
                case: ExtremeCase::Support { condition: name.into(), point: pname.into() },
                mesh: (model.mesh().nx(), model.mesh().nz()),
                compliance: r.compliance,
                reference,
                error: None,
                residual: r.residual,
                finite: r.compliance.is_finite() && r.compliance >= -1e-25,
            });
        }
    }
    Ok(out)
}
