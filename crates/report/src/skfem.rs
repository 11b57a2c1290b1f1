//! The scikit-fem reference data (reference/data/*.json, written by
//! reference/python/plate_reference.py) and the matching Rust runs.

use coupled::discretisation::ladder_meshes;
use plate_fem::convergence::{richardson, Extrapolation};
use plate_fem::{CornerSupport, EdgeSupport, FemError, Model, PlateProperties, Supports};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The cases the reference script writes.
pub const CASES: [&str; 5] = ["paper-con1", "paper-con2", "paper-con3", "paper-simple-all", "paper-simple-free"];

/// One mesh of one element.
#[derive(Debug, Clone)]
pub struct Run {
    pub nx: usize,
    pub nz: usize,
    pub dofs: usize,
    pub seconds: f64,
    pub compliance: Vec<f64>,
}

/// A reference case.
#[derive(Debug, Clone)]
pub struct Case {
    pub name: String,
    pub props: PlateProperties,
    pub supports: Supports,
    pub points: Vec<(f64, f64)>,
    pub argyris: Vec<Run>,
    pub morley: Vec<Run>,
    pub versions: Value,
}

/// reference/data in the source tree.
pub fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../reference/data")
}

fn bad(what: &str) -> String {
    format!("reference data: missing or malformed {what}")
}

/// Reads one case.
pub fn load(name: &str) -> Result<Case, String> {
    let path = data_dir().join(format!("{name}.json"));
    let v: Value =
        serde_json::from_str(&std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?)
            .map_err(|e| format!("{}: {e}", path.display()))?;
    let f = |x: &Value, what: &str| x.as_f64().ok_or_else(|| bad(what));
    let p = &v["plate"];
    let props = PlateProperties {
        length: f(&p["length"], "plate.length")?,
        width: f(&p["width"], "plate.width")?,
        thickness: f(&p["thickness"], "plate.thickness")?,
        youngs_modulus: f(&p["youngs_modulus"], "plate.youngs_modulus")?,
        poisson_ratio: f(&p["poisson_ratio"], "plate.poisson_ratio")?,
        density: 7850.0,
    };
    let s = &v["supports"];
    let corner = |c: &Value| match c {
        Value::String(k) if k == "fixed" => Ok(CornerSupport::Fixed),
        Value::String(k) if k == "free" => Ok(CornerSupport::Free),
        Value::Number(n) => Ok(CornerSupport::Spring(n.as_f64().unwrap_or(f64::NAN))),
        _ => Err(bad("supports.corners")),
    };
    let edge = |name: &str| match s["edges"][name].as_str() {
        Some("free") => Ok(EdgeSupport::Free),
        Some("simple") => Ok(EdgeSupport::Simple),
        Some("clamped") => Ok(EdgeSupport::Clamped),
        _ => Err(bad("supports.edges")),
    };
    let cs: Vec<CornerSupport> =
        s["corners"].as_array().ok_or_else(|| bad("supports.corners"))?.iter().map(corner).collect::<Result<_, _>>()?;
    if cs.len() != 4 {
        return Err(bad("supports.corners (four)"));
    }
    let supports = Supports {
        corners: [cs[0], cs[1], cs[2], cs[3]],
        edges: [edge("left")?, edge("right")?, edge("near")?, edge("far")?],
    };
    let points = v["points"]
        .as_array()
        .ok_or_else(|| bad("points"))?
        .iter()
        .map(|q| Ok((f(&q[0], "points")?, f(&q[1], "points")?)))
        .collect::<Result<Vec<_>, String>>()?;
    let runs = |e: &str| -> Result<Vec<Run>, String> {
        v["results"][e]
            .as_array()
            .ok_or_else(|| bad(e))?
            .iter()
            .map(|r| {
                Ok(Run {
                    nx: r["nx"].as_u64().ok_or_else(|| bad("nx"))? as usize,
                    nz: r["nz"].as_u64().ok_or_else(|| bad("nz"))? as usize,
                    dofs: r["dofs"].as_u64().ok_or_else(|| bad("dofs"))? as usize,
                    seconds: f(&r["assembly_s"], "assembly_s")? + f(&r["solve_s"], "solve_s")?,
                    compliance: r["compliance"]
                        .as_array()
                        .ok_or_else(|| bad("compliance"))?
                        .iter()
                        .map(|c| f(c, "compliance"))
                        .collect::<Result<_, _>>()?,
                })
            })
            .collect()
    };
    Ok(Case {
        name: name.into(),
        props,
        supports,
        points,
        argyris: runs("argyris")?,
        morley: runs("morley")?,
        versions: v["versions"].clone(),
    })
}

/// Per point, the extrapolation of a ladder of runs.
pub fn extrapolate(runs: &[Run]) -> Vec<Extrapolation> {
    let n = runs.first().map_or(0, |r| r.compliance.len());
    (0..n).filter_map(|i| richardson(&runs.iter().map(|r| r.compliance[i]).collect::<Vec<_>>())).collect()
}

/// The Rust BFS compliances of a case on the ladder 10 x 8, 20 x 16, ... (`levels` meshes).
pub fn rust_runs(case: &Case, levels: u32) -> Result<Vec<Run>, FemError> {
    ladder_meshes(&case.props, 10, levels)?
        .into_iter()
        .map(|mesh| {
            let t = std::time::Instant::now();
            let (nx, nz) = (mesh.nx(), mesh.nz());
            let model = Model::new(case.props, mesh)?;
            let c = model.factorize(&case.supports)?.respond_many(&case.points)?;
            Ok(Run {
                nx,
                nz,
                dofs: model.dofs(),
                seconds: t.elapsed().as_secs_f64(),
                compliance: c.iter().map(|r| r.compliance).collect(),
            })
        })
        .collect()
}
