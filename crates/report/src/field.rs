//! Deflection fields for viewing: the mesh and fields in a simple documented JSON form
//! (`impact-plate-field/1`, see reference/README.md) that reference/python/export_fields.py
//! turns into .vtu and .xdmf with meshio; `crate::present::vtk` writes the same field as
//! .vtu directly, with the bending stresses and the elements at the load marked.
//!
//! Near the load the moments are not converged: under a point load the Kirchhoff moment is
//! logarithmically singular, so the element-centre moments (and stresses) of the elements
//! touching the load point grow without bound as the mesh is refined. `near_load` marks those
//! elements; deflections and the moments away from the load converge.

use crate::template::render;
use crate::Failure;
use analytic::Sphere;
use coupled::discretisation::{mesh_for, plate_properties};
use coupled::plan::{ModelKind, ResponseValues};
use coupled::Validity;
use plate_fem::{FemError, Model};
use scene::{Analysis, Points, Scene, SupportSet};
use serde::Serialize;

const P_MAX: &str = include_str!("templates/field/p-max.md");
const CAVEAT: &str = include_str!("templates/field/caveat.md");

/// The JSON document.
#[derive(Debug, Serialize)]
pub struct FieldFile {
    pub format: &'static str,
    pub scene: String,
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
}

#[derive(Debug, Serialize)]
pub struct PointData {
    pub w: Vec<f64>,
    pub w_x: Vec<f64>,
    pub w_z: Vec<f64>,
    pub w_xz: Vec<f64>,
}

#[derive(Debug, Serialize)]
pub struct CellData {
    #[serde(rename = "M_x")]
    pub m_x: Vec<f64>,
    #[serde(rename = "M_z")]
    pub m_z: Vec<f64>,
    #[serde(rename = "M_xz")]
    pub m_xz: Vec<f64>,
}

/// The field of `condition` under a unit load at (x, z), on a mesh of `n` elements along
/// the longer side.
pub fn field(scene: &Scene, condition: &SupportSet, x: f64, z: f64, n: usize) -> Result<FieldFile, FemError> {
    let props = plate_properties(&scene.plate);
    let mesh = mesh_for(&props, n)?;
    let model = Model::new(props, mesh.clone())?;
    let f = model.factorize(&condition.supports)?;
    let w = f.deflection_field(x, z)?;
    let residual = f.respond(x, z)?.residual;
    let (points, quads) = (mesh.node_points(), mesh.quads());
    let comp = |q: usize| (0..mesh.nodes()).map(|n| w[4 * n + q]).collect::<Vec<f64>>();
    let moments = model.centre_moments(&w);
    Ok(FieldFile {
        format: "impact-plate-field/1",
        scene: scene.name.clone(),
        condition: condition.name.clone(),
        load: [x, z],
        points,
        quads,
        point_data: PointData { w: comp(0), w_x: comp(1), w_z: comp(2), w_xz: comp(3) },
        cell_data: CellData {
            m_x: moments.iter().map(|m| m[0]).collect(),
            m_z: moments.iter().map(|m| m[1]).collect(),
            m_xz: moments.iter().map(|m| m[2]).collect(),
        },
        residual,
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
    let rows = studies::run::results(&one, &[ModelKind::Plate], &studies::progress::Silent)?;
    let row = rows.responses.first().and_then(|r| r.values()).ok_or("the plate model gave no response row")?;
    Ok(row.clone())
}

/// The sentence that a quasi-static field does not describe the plate of a case the
/// quasi-static balance is not trusted for (its quasi-static or regime-rule criterion fails);
/// empty where it is trusted.
pub fn quasi_static_caveat(v: &Validity) -> Result<String, Failure> {
    let untrusted = v.quasi_static.is_some_and(|c| !c.valid) || v.regime.is_some_and(|c| !c.valid);
    Ok(if untrusted { render("field/caveat.md", CAVEAT, &[])? } else { String::new() })
}

/// What a field scaled to the quasi-static P_max of `case` is, in words: the force, its
/// error, the model, the case (`what`) and its validity.
pub fn p_max_text(case: &ResponseValues, what: &str) -> Result<String, Failure> {
    use crate::present::table::sig;
    Ok(render(
        "field/p-max.md",
        P_MAX,
        &[
            ("p_max", sig(case.contact_force, 4)),
            ("p_max_error", case.contact_force_error.map_or("not estimated".into(), |e| sig(e, 2))),
            ("what", what.to_string()),
            ("validity", crate::present::rows::validity_text(&case.validity)),
            ("caveat", quasi_static_caveat(&case.validity)?),
        ],
    )?)
}
