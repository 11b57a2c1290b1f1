//! The plate's deflection field under a unit load, and the plate at an impact's quasi-static
//! maximum force: the data `impact field` writes (`impact-plate-field/1`, see
//! reference/README.md; .vtu with the bending stresses) and the main report's colour maps
//! draw.
//!
//! Near the load the moments are not converged: under a point load the Kirchhoff moment is
//! logarithmically singular, so the element-centre moments (and stresses) of the elements
//! touching the load point grow without bound as the mesh is refined. [`FieldFile::near_load`]
//! marks those elements; deflections and the moments away from the load converge.
//!
//! The plate model is linear, so the field under the quasi-static maximum force P_max is the
//! unit-load field times P_max ([`plate_at_peak`]). The stress there is the von Mises stress of
//! the surface bending stresses σ = 6M/h², the quantity a steel plate's yield is judged by.

use crate::Failure;
use analytic::Sphere;
use coupled::discretisation::{mesh_for, plate_properties};
use coupled::plan::{ModelKind, ResponseValues};
use plate_fem::{FemError, Model};
use scene::{Analysis, Points, Scene, SupportSet};
use serde::Serialize;

/// The elements along the longer side of the field behind the main report's colour maps.
pub const FIELD_ELEMENTS: usize = 80;

/// The JSON document `impact-plate-field/1`.
#[derive(Debug, Serialize)]
pub struct FieldFile {
    /// `impact-plate-field/1`.
    pub format: &'static str,
    /// The scene's name.
    pub scene: String,
    /// The support set's name.
    pub condition: String,
    /// The unit point load: (x, z) in m, force 1 N.
    pub load: [f64; 2],
    /// Node coordinates (x, z) in m; node (i, j) is number j·(nx+1) + i.
    pub points: Vec<[f64; 2]>,
    /// Quadrilaterals, counter-clockwise node numbers.
    pub quads: Vec<[usize; 4]>,
    /// Nodal fields per unit load: w (m/N), w_x, w_z (1/N), w_xz (1/(m·N)).
    pub point_data: PointData,
    /// Element-centre moments per unit load: M_x, M_z, M_xz (N·m/m per N).
    pub cell_data: CellData,
    /// Relative residual of the solve.
    pub residual: f64,
    /// Plate thickness h, m, for the bending stress σ = 6M/h². Left out of the JSON, whose
    /// format `impact-plate-field/1` is fixed; the scene carries it.
    #[serde(skip)]
    pub thickness: f64,
}

/// Nodal fields per unit load.
#[derive(Debug, Serialize)]
pub struct PointData {
    /// Deflection w, m/N.
    pub w: Vec<f64>,
    /// ∂w/∂x, 1/N.
    pub w_x: Vec<f64>,
    /// ∂w/∂z, 1/N.
    pub w_z: Vec<f64>,
    /// ∂²w/∂x∂z, 1/(m·N).
    pub w_xz: Vec<f64>,
}

/// Element-centre moments per unit load, N·m/m per N.
#[derive(Debug, Serialize)]
pub struct CellData {
    /// M_x.
    #[serde(rename = "M_x")]
    pub m_x: Vec<f64>,
    /// M_z.
    #[serde(rename = "M_z")]
    pub m_z: Vec<f64>,
    /// M_xz.
    #[serde(rename = "M_xz")]
    pub m_xz: Vec<f64>,
}

impl FieldFile {
    /// Surface bending stresses per unit load, σ = 6M/h² for M_x, M_z, M_xz (Pa per N), the
    /// stress of a linear distribution through the thickness at the faces.
    pub fn stresses(&self) -> [Vec<f64>; 3] {
        let s = 6.0 / (self.thickness * self.thickness);
        let c = &self.cell_data;
        [&c.m_x, &c.m_z, &c.m_xz].map(|m| m.iter().map(|v| s * v).collect())
    }

    /// Per element: whether it touches the load point (the closed rectangle contains it).
    /// Their moments are those of a logarithmic singularity sampled at the element centre,
    /// so they grow with refinement; one to four elements, by where the load falls.
    pub fn near_load(&self) -> Vec<bool> {
        let [x, z] = self.load;
        // A load on a node or an element edge touches every element sharing it; the
        // tolerance keeps a load typed in millimetres on a node from missing by rounding.
        let extent = self.points.iter().fold(0.0f64, |a, p| a.max(p[0].abs()).max(p[1].abs()));
        let tol = 1e-9 * extent;
        self.quads
            .iter()
            .map(|q| {
                let (lo, hi) = (self.points[q[0]], self.points[q[2]]);
                (lo[0] - tol..=hi[0] + tol).contains(&x) && (lo[1] - tol..=hi[1] + tol).contains(&z)
            })
            .collect()
    }

    /// The node lines (x and z, sorted) and `v` (one value per node) on them, `[i][j]` at
    /// (x_i, z_j).
    pub fn node_grid(&self, v: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<Vec<f64>>) {
        let lines = |k: usize| {
            let mut c: Vec<f64> = self.points.iter().map(|p| p[k]).collect();
            c.sort_by(f64::total_cmp);
            c.dedup();
            c
        };
        let (xs, zs) = (lines(0), lines(1));
        let nx1 = xs.len();
        let grid = (0..xs.len()).map(|i| (0..zs.len()).map(|j| v[j * nx1 + i]).collect()).collect();
        (xs, zs, grid)
    }
}

/// The field of `condition` under a unit load at (x, z), on a mesh of `n` elements along
/// the longer side: one factorization and one solve.
pub fn field(scene: &Scene, condition: &SupportSet, x: f64, z: f64, n: usize) -> Result<FieldFile, FemError> {
    let props = plate_properties(&scene.plate);
    let mesh = mesh_for(&props, n)?;
    let model = Model::new(props, mesh.clone())?;
    let (response, w) = model.factorize(&condition.supports)?.respond_with_field(x, z)?;
    let comp = |q: usize| (0..mesh.nodes()).map(|n| w[4 * n + q]).collect::<Vec<f64>>();
    let moments = model.centre_moments(&w);
    Ok(FieldFile {
        format: "impact-plate-field/1",
        scene: scene.name.clone(),
        condition: condition.name.clone(),
        load: [x, z],
        points: mesh.node_points(),
        quads: mesh.quads(),
        point_data: PointData { w: comp(0), w_x: comp(1), w_z: comp(2), w_xz: comp(3) },
        cell_data: CellData {
            m_x: moments.iter().map(|m| m[0]).collect(),
            m_z: moments.iter().map(|m| m[1]).collect(),
            m_xz: moments.iter().map(|m| m[2]).collect(),
        },
        residual: response.residual,
        thickness: scene.plate.thickness(),
    })
}

/// The quasi-static plate model's response to one impact, `sphere` at `v` (m/s) on
/// `condition` at (x, z) (m): the row `impact solve --model plate` gives for that case, with
/// P_max, its error and the case's validity.
pub fn quasi_static_impact(
    scene: &Scene,
    condition: &SupportSet,
    sphere: &Sphere,
    v: f64,
    x: f64,
    z: f64,
) -> Result<ResponseValues, Failure> {
    let mut one = scene.clone();
    one.bodies = vec![sphere.clone()];
    one.conditions = vec![condition.clone()];
    one.velocities = vec![v];
    one.points = Points::Pairs { pairs: vec![(x, z)] };
    one.analyses = vec![Analysis::Responses];
    let rows = crate::run::results(&one, &[ModelKind::Plate], &crate::progress::Silent)?;
    let row = rows.responses.first().and_then(|r| r.values()).ok_or("the plate model gave no response row")?;
    Ok(row.clone())
}

/// The von Mises stress of plane surface stresses, σ_vM = √(σ_x² − σ_xσ_z + σ_z² + 3τ_xz²).
pub fn von_mises(sx: f64, sz: f64, t: f64) -> f64 {
    (sx * sx - sx * sz + sz * sz + 3.0 * t * t).sqrt()
}

/// The plate at an impact's quasi-static maximum force P_max: the unit-load field times P_max.
#[derive(Debug, Clone, Serialize)]
pub struct PlateAtPeak {
    /// Node lines along x and z, m.
    pub xs: Vec<f64>,
    /// See `xs`.
    pub zs: Vec<f64>,
    /// Deflection w at P_max, m, `[i][j]` at (x_i, z_j).
    pub w: Vec<Vec<f64>>,
    /// Element centres along x and z, m.
    pub centres_x: Vec<f64>,
    /// See `centres_x`.
    pub centres_z: Vec<f64>,
    /// Surface von Mises stress at P_max, Pa, `[i][j]` at element centre (i, j); `None`
    /// within one plate thickness of the load (thin-plate theory does not hold there, and
    /// the point-load moment is singular).
    pub von_mises: Vec<Vec<Option<f64>>>,
    /// The largest deflection, m, and where, (x, z) in m.
    pub w_max: f64,
    /// See `w_max`.
    pub w_max_at: (f64, f64),
    /// The largest von Mises stress away from the load, Pa, and where.
    pub stress_max: f64,
    /// See `stress_max`.
    pub stress_max_at: (f64, f64),
    /// Elements left out near the load.
    pub left_out: usize,
}

/// The plate of `scene` on `condition` under `p_max` (N) at (x, z), on a mesh of
/// [`FIELD_ELEMENTS`] along the longer side.
pub fn plate_at_peak(scene: &Scene, cond: &SupportSet, x: f64, z: f64, p_max: f64) -> Result<PlateAtPeak, Failure> {
    let f = field(scene, cond, x, z, FIELD_ELEMENTS)?;
    let w: Vec<f64> = f.point_data.w.iter().map(|w| w * p_max).collect();
    let (xs, zs, grid) = f.node_grid(&w);
    let (imax, _) = w.iter().enumerate().fold((0, f64::NEG_INFINITY), |a, (i, &v)| if v > a.1 { (i, v) } else { a });
    let [sx, sz, sxz] = f.stresses();
    let cx: Vec<f64> = xs.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
    let cz: Vec<f64> = zs.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
    let ne = cx.len();
    let h = scene.plate.thickness();
    let touching = f.near_load();
    let near: Vec<bool> = (0..sx.len()).map(|e| touching[e] || (cx[e % ne] - x).hypot(cz[e / ne] - z) < h).collect();
    let vm: Vec<Option<f64>> =
        (0..sx.len()).map(|e| (!near[e]).then(|| p_max * von_mises(sx[e], sz[e], sxz[e]))).collect();
    let (emax, smax) = vm.iter().enumerate().fold((0, f64::NEG_INFINITY), |a, (e, v)| match v {
        Some(v) if *v > a.1 => (e, *v),
        _ => a,
    });
    Ok(PlateAtPeak {
        w_max: w[imax],
        w_max_at: (f.points[imax][0], f.points[imax][1]),
        stress_max: smax,
        stress_max_at: (cx[emax % ne], cz[emax / ne]),
        left_out: near.iter().filter(|&&n| n).count(),
        von_mises: (0..ne).map(|i| (0..cz.len()).map(|j| vm[j * ne + i]).collect()).collect(),
        xs,
        zs,
        w: grid,
        centres_x: cx,
        centres_z: cz,
    })
}
