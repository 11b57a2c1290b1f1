//! The plate elements against the classical series: Navier's double series for the simply
//! supported rectangle, Lévy's single series for simply supported ends and free sides, and
//! the narrow Lévy plate against the Euler-Bernoulli beam it tends to as B/L → 0.

use plate_fem::classical::{LevyPlate, YEdge};
use plate_fem::convergence::{observed_rate, richardson};
use plate_fem::{FemError, Mesh, Model, PlateProperties, Supports};
use serde::Serialize;

/// The off-centre Navier plate (m).
pub const OFF_CENTRE: (f64, f64) = (1.0, 0.7);
/// Its load point (m).
pub const OFF_CENTRE_POINT: (f64, f64) = (0.3, 0.2);
/// The Lévy plate (m): ends simply supported, sides free.
pub const LEVY: (f64, f64) = (1.0, 0.6);
/// The Lévy plate's load points (m): centre, quarter span, between centre and edge, on the
/// free edge, and near a corner of the free edge.
pub const LEVY_POINTS: [(f64, f64); 5] = [(0.5, 0.3), (0.25, 0.3), (0.5, 0.15), (0.5, 0.6), (0.1, 0.6)];
/// The narrow-plate widths, B/L: from four times as wide as long to a strip.
pub const NARROW_RATIOS: [f64; 8] = [4.0, 2.0, 1.0, 0.5, 0.2, 0.1, 0.05, 0.02];

/// One mesh of a convergence ladder against an exact value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LadderRow {
    /// Elements along x.
    pub nx: usize,
    /// Elements along z.
    pub nz: usize,
    /// The FE point compliance, m/N.
    pub compliance: f64,
    /// |C_FE/C_exact - 1|.
    pub rel_error: f64,
    /// The observed order from this mesh and the two coarser ones.
    pub observed_rate: Option<f64>,
    /// The Richardson value from this mesh and the coarser ones, m/N.
    pub richardson: Option<f64>,
    /// Its relative error against the exact value.
    pub richardson_error: Option<f64>,
}

/// A ladder of meshes against a series solution.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Convergence {
    /// The series value, m/N.
    pub exact: f64,
    /// Coarsest first.
    pub rows: Vec<LadderRow>,
    /// (h/L, |C_FE/C_exact - 1|) per mesh, the convergence figure's points.
    pub errors: Vec<(f64, f64)>,
    /// The rate between the two finest meshes, ln(e₁/e₂)/ln(h₁/h₂).
    pub finest_rate: Option<f64>,
}

/// One load point of the Lévy plate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LevyRow {
    /// The load point (m).
    pub point: (f64, f64),
    /// The series compliance, m/N.
    pub exact: f64,
    /// On 24 x 16.
    pub coarse: f64,
    /// Its relative error.
    pub coarse_error: f64,
    /// On 96 x 64.
    pub fine: f64,
    /// Its relative error.
    pub fine_error: f64,
    /// From the three meshes.
    pub observed_rate: Option<f64>,
    /// The Richardson value's relative error.
    pub richardson_error: f64,
}

/// One width of the narrow-plate study: the Lévy plate over the beam of the same section.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NarrowRow {
    /// B/L.
    pub width_ratio: f64,
    /// C_plate/C_beam at the centre.
    pub centre: f64,
    /// At quarter span.
    pub quarter: f64,
    /// With the load on the free edge at mid-span.
    pub edge: f64,
    /// (centre ratio - 1)/(B/L)².
    pub coefficient: f64,
}

/// A steel plate (E = 210 GPa, ν = 0.3) of the given size.
pub fn unit_plate(l: f64, b: f64, h: f64) -> PlateProperties {
    PlateProperties { length: l, width: b, thickness: h, youngs_modulus: 210e9, poisson_ratio: 0.3, density: 7850.0 }
}

/// FE compliance at `p` for a ladder of meshes (n·2^k by m·2^k, k < `levels`).
pub fn ladder(
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

/// A ladder's rows against `exact`, with h/L of a mesh of `nx` elements along x given by
/// `h_over_l`.
pub fn convergence(rows: &[(usize, usize, f64)], exact: f64, h_over_l: impl Fn(usize) -> f64) -> Convergence {
    let vals: Vec<f64> = rows.iter().map(|r| r.2).collect();
    let ladder = rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let richardson = (i >= 1).then(|| richardson(&vals[..=i]).expect("two values").extrapolated);
            LadderRow {
                nx: r.0,
                nz: r.1,
                compliance: r.2,
                rel_error: (r.2 - exact).abs() / exact,
                observed_rate: if i >= 2 { observed_rate(vals[i - 2], vals[i - 1], vals[i]) } else { None },
                richardson,
                richardson_error: richardson.map(|e| (e - exact).abs() / exact),
            }
        })
        .collect();
    let errors: Vec<(f64, f64)> = rows.iter().map(|r| (h_over_l(r.0), (r.2 - exact).abs() / exact)).collect();
    let finest_rate = match errors.as_slice() {
        [.., a, b] => Some((a.1 / b.1).ln() / (a.0 / b.0).ln()),
        _ => None,
    };
    Convergence { exact, rows: ladder, errors, finest_rate }
}

/// The simply supported square (1 m, 10 mm) loaded and read at its centre on six meshes, 4 x 4
/// to 128 x 128; its centre coefficient w D/(P a²); and the relative error of the Richardson
/// value of the whole ladder.
pub fn navier_square() -> Result<(Convergence, f64, f64), FemError> {
    let sq = unit_plate(1.0, 1.0, 0.01);
    let d = sq.rigidity();
    let navier = LevyPlate { a: 1.0, b: 1.0, d, nu: 0.3, y_edges: YEdge::Simple };
    let exact = navier.converged((0.5, 0.0), (0.5, 0.0), 1e-12);
    let rows = ladder(sq, &Supports::all_edges_simple(), 4, 4, 6, (0.5, 0.5))?;
    let vals: Vec<f64> = rows.iter().map(|r| r.2).collect();
    let navier_richardson = richardson(&vals).map_or(f64::NAN, |r| (r.extrapolated - exact).abs() / exact);
    Ok((convergence(&rows, exact, |nx| 1.0 / nx as f64), exact * d, navier_richardson))
}

/// The simply supported [`OFF_CENTRE`] rectangle loaded at [`OFF_CENTRE_POINT`], 10 x 7 to
/// 80 x 56.
pub fn off_centre() -> Result<Convergence, FemError> {
    let (ol, ow) = OFF_CENTRE;
    let (ox, oz) = OFF_CENTRE_POINT;
    let rect = unit_plate(ol, ow, 0.01);
    let np = LevyPlate { a: ol, b: ow, d: rect.rigidity(), nu: 0.3, y_edges: YEdge::Simple };
    let exact = np.converged((ox, oz - ow / 2.0), (ox, oz - ow / 2.0), 1e-12);
    let rows = ladder(rect, &Supports::all_edges_simple(), 10, 7, 4, (ox, oz))?;
    Ok(convergence(&rows, exact, |nx| ol / nx as f64 / ol))
}

/// The [`LEVY`] plate at [`LEVY_POINTS`] on 24 x 16, 48 x 32 and 96 x 64, and the largest
/// relative error of a Richardson value.
pub fn levy() -> Result<(Vec<LevyRow>, f64), FemError> {
    let lp = unit_plate(LEVY.0, LEVY.1, 0.01);
    let levy = LevyPlate { a: LEVY.0, b: LEVY.1, d: lp.rigidity(), nu: 0.3, y_edges: YEdge::Free };
    let mut worst = 0.0f64;
    let mut out = Vec::new();
    for (x, z) in LEVY_POINTS {
        let exact = levy.converged((x, z - LEVY.1 / 2.0), (x, z - LEVY.1 / 2.0), 1e-12);
        let rows = ladder(lp, &Supports::simple_free(), 24, 16, 3, (x, z))?;
        let v: Vec<f64> = rows.iter().map(|r| r.2).collect();
        let ext = richardson(&v).expect("three values");
        worst = worst.max((ext.extrapolated - exact).abs() / exact);
        out.push(LevyRow {
            point: (x, z),
            exact,
            coarse: v[0],
            coarse_error: (v[0] - exact).abs() / exact,
            fine: v[2],
            fine_error: (v[2] - exact).abs() / exact,
            observed_rate: ext.observed_rate,
            richardson_error: (ext.extrapolated - exact).abs() / exact,
        });
    }
    Ok((out, worst))
}

/// Lévy plates of [`NARROW_RATIOS`] against the simply supported beam of the same section,
/// C_beam(x) = x²(L - x)²/(3EIL), and the narrowest plate's (ratio - 1)/(B/L)².
pub fn narrow() -> (Vec<NarrowRow>, f64) {
    let mut coefficient = f64::NAN;
    let mut out = Vec::new();
    for bl in NARROW_RATIOS {
        let (l, h, e, nu) = (1.0f64, 0.01f64, 210e9f64, 0.3f64);
        let b = bl * l;
        let plate = LevyPlate { a: l, b, d: unit_plate(l, b, h).rigidity(), nu, y_edges: YEdge::Free };
        let ei = e * b * h.powi(3) / 12.0;
        let beam = |x: f64| (x * (l - x)).powi(2) / (3.0 * ei * l);
        let c = plate.converged((0.5, 0.0), (0.5, 0.0), 1e-10) / beam(0.5);
        let q = plate.converged((0.25, 0.0), (0.25, 0.0), 1e-10) / beam(0.25);
        let ed = plate.converged((0.5, b / 2.0), (0.5, b / 2.0), 1e-10) / beam(0.5);
        coefficient = (c - 1.0) / (bl * bl);
        out.push(NarrowRow { width_ratio: bl, centre: c, quarter: q, edge: ed, coefficient });
    }
    (out, coefficient)
}
