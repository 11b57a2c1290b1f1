//! The scikit-fem reference (`reference/data/*.json`, written by
//! `reference/python/plate_reference.py`): the paper's plate on Argyris and Morley triangles,
//! an independent code, against the BFS ladder of the same plate.
//!
//! Argyris is conforming and Morley is not, so on the paper's plate the Argyris compliances
//! rise to the limit from below like BFS, and Morley's fall to it from above: the BFS
//! Richardson value must lie between the finest BFS and the finest Morley value.

use coupled::discretisation::ladder_meshes;
use plate_fem::convergence::{richardson, Extrapolation};
use plate_fem::{CornerSupport, EdgeSupport, FemError, Model, PlateProperties, Supports};
use serde::Serialize;
use serde_json::Value;

/// The cases the reference script writes for the verification, each with its data as
/// committed (embedded, so the study reads no file).
pub const CASES: [(&str, &str); 5] = [
    ("paper-con1", include_str!("../../../../reference/data/paper-con1.json")),
    ("paper-con2", include_str!("../../../../reference/data/paper-con2.json")),
    ("paper-con3", include_str!("../../../../reference/data/paper-con3.json")),
    ("paper-simple-all", include_str!("../../../../reference/data/paper-simple-all.json")),
    ("paper-simple-free", include_str!("../../../../reference/data/paper-simple-free.json")),
];
/// The reference script's timings (`timing.csv`).
pub const TIMING: &str = include_str!("../../../../reference/data/timing.csv");

/// Levels of the BFS ladder beside the reference: 10 x 8 to 80 x 64 on the paper's plate.
pub const BFS_LEVELS: u32 = 4;

/// One mesh of one element.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Run {
    /// Elements along x.
    pub nx: usize,
    /// Elements along z.
    pub nz: usize,
    /// Degrees of freedom.
    pub dofs: usize,
    /// Assembly and solve, s.
    pub seconds: f64,
    /// The compliance at each of the case's points, m/N.
    pub compliance: Vec<f64>,
}

/// A reference case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Case {
    /// Its name (the file's stem).
    pub name: String,
    /// The plate.
    #[serde(skip)]
    pub props: PlateProperties,
    /// Its supports.
    #[serde(skip)]
    pub supports: Supports,
    /// The load points (x, z), m.
    pub points: Vec<(f64, f64)>,
    /// Argyris triangles, coarsest first.
    pub argyris: Vec<Run>,
    /// Morley triangles, coarsest first.
    pub morley: Vec<Run>,
    /// The versions of the reference's software, by name, in the file's order.
    pub versions: Vec<(String, String)>,
}

fn bad(what: &str) -> String {
    format!("reference data: missing or malformed {what}")
}

/// The supports of a case's JSON.
fn supports(s: &Value) -> Result<Supports, String> {
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
    Ok(Supports {
        corners: [cs[0], cs[1], cs[2], cs[3]],
        edges: [edge("left")?, edge("right")?, edge("near")?, edge("far")?],
    })
}

/// The runs of one element in a case's JSON.
fn runs(v: &Value, element: &str) -> Result<Vec<Run>, String> {
    let f = |x: &Value, what: &str| x.as_f64().ok_or_else(|| bad(what));
    v["results"][element]
        .as_array()
        .ok_or_else(|| bad(element))?
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
}

/// Reads one case from its JSON text (`origin` names it in errors).
pub fn parse(name: &str, text: &str, origin: &str) -> Result<Case, String> {
    let v: Value = serde_json::from_str(text).map_err(|e| format!("{origin}: {e}"))?;
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
    let points = v["points"]
        .as_array()
        .ok_or_else(|| bad("points"))?
        .iter()
        .map(|q| Ok((f(&q[0], "points")?, f(&q[1], "points")?)))
        .collect::<Result<Vec<_>, String>>()?;
    let versions = v["versions"]
        .as_object()
        .map(|o| o.iter().map(|(k, v)| (k.clone(), v.as_str().unwrap_or("?").to_string())).collect())
        .unwrap_or_default();
    Ok(Case {
        name: name.into(),
        props,
        supports: supports(&v["supports"])?,
        points,
        argyris: runs(&v, "argyris")?,
        morley: runs(&v, "morley")?,
        versions,
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

/// The reference data the verification compares with.
#[derive(Debug, Clone, PartialEq)]
pub struct Reference {
    /// The cases.
    pub cases: Vec<Case>,
    /// The timing table's rows: code, element, mesh, DOFs, seconds, relative error.
    pub timing: Vec<[String; 6]>,
}

impl Reference {
    /// The committed data, as embedded.
    pub fn embedded() -> Result<Self, String> {
        let cases = CASES
            .iter()
            .map(|(name, text)| parse(name, text, &format!("reference/data/{name}.json")))
            .collect::<Result<_, _>>()?;
        Ok(Self { cases, timing: timing_rows(TIMING) })
    }
}

/// The rows of a `timing.csv` text (its header skipped, rows of other than seven fields left
/// out), without the compliance column.
pub fn timing_rows(text: &str) -> Vec<[String; 6]> {
    text.lines()
        .skip(1)
        .map(|line| line.split(',').collect::<Vec<_>>())
        .filter(|c| c.len() == 7)
        .map(|c| [c[0], c[1], c[2], c[3], c[4], c[6]].map(str::to_string))
        .collect()
}

/// One point of one case: BFS and Argyris extrapolated, and the finest Morley.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SkfemRow {
    /// The case's name.
    pub case: String,
    /// The point (x, z), m.
    pub point: (f64, f64),
    /// BFS Richardson value, m/N, and its error estimate.
    pub bfs: (f64, f64),
    /// Argyris Richardson value, m/N, and its error estimate.
    pub argyris: (f64, f64),
    /// |BFS/Argyris - 1|; none where both are 0 (a supported edge).
    pub difference: Option<f64>,
    /// Morley on its finest mesh, m/N.
    pub morley: f64,
    /// Finest BFS ≤ BFS Richardson ≤ finest Morley (or both references 0).
    pub bracketed: bool,
}

/// The comparison with scikit-fem.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SkfemComparison {
    /// Every point of every case.
    pub rows: Vec<SkfemRow>,
    /// The finest BFS mesh (nx, nz).
    pub bfs_finest: Option<(usize, usize)>,
    /// The finest Argyris mesh.
    pub argyris_finest: Option<(usize, usize)>,
    /// The largest |BFS/Argyris - 1|.
    pub worst: f64,
    /// The reference's software versions (of its first case).
    pub versions: Vec<(String, String)>,
    /// The timing rows, as [`Reference::timing`].
    pub timing: Vec<[String; 6]>,
}

/// Every case of `reference` against the BFS ladder of [`BFS_LEVELS`] meshes.
pub fn compare(reference: &Reference) -> Result<SkfemComparison, crate::Failure> {
    let mut out = SkfemComparison {
        rows: Vec::new(),
        bfs_finest: None,
        argyris_finest: None,
        worst: 0.0,
        versions: reference.cases.first().map(|c| c.versions.clone()).unwrap_or_default(),
        timing: reference.timing.clone(),
    };
    for case in &reference.cases {
        let bfs = rust_runs(case, BFS_LEVELS)?;
        let (ours, arg) = (extrapolate(&bfs), extrapolate(&case.argyris));
        let morley = &case.morley.last().ok_or("no Morley runs")?.compliance;
        let finest = &bfs.last().ok_or("no BFS runs")?.compliance;
        out.bfs_finest = bfs.last().map(|r| (r.nx, r.nz));
        out.argyris_finest = case.argyris.last().map(|r| (r.nx, r.nz));
        for (i, (r, g)) in ours.iter().zip(&arg).enumerate() {
            let zero = g.extrapolated.abs() < 1e-20;
            let difference = (!zero).then(|| (r.extrapolated - g.extrapolated).abs() / g.extrapolated);
            out.worst = out.worst.max(difference.unwrap_or(0.0));
            out.rows.push(SkfemRow {
                case: case.name.clone(),
                point: case.points[i],
                bfs: (r.extrapolated, r.error_estimate),
                argyris: (g.extrapolated, g.error_estimate),
                difference,
                morley: morley[i],
                bracketed: zero
                    || (finest[i] <= r.extrapolated * (1.0 + 1e-9) && morley[i] >= r.extrapolated * (1.0 - 1e-9)),
            });
        }
    }
    Ok(out)
}
