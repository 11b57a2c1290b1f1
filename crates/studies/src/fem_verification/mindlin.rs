//! The Reissner-Mindlin plate (MITC4) against its references: Navier's series with shear on
//! thick plates (with the observed convergence rate and Reddy's tabulated value), the thin
//! limit against the BFS Kirchhoff plate under the same patch, and the logarithmic growth of a
//! node support that theory predicts.

use crate::Failure;
use plate_fem::convergence::richardson;
use plate_fem::mindlin::{node_support_growth, series, Patch, Plate};
use plate_fem::{Mesh, Model, PlateProperties, Supports};
use serde::Serialize;

/// Reddy's centre deflection of the hard simply supported square under a uniform load,
/// a/h = 10, ν = 0.3, k_s = 5/6, in q a⁴/D (*Theory and Analysis of Elastic Plates and
/// Shells*, 2nd ed., Table 10.2.2, FSDT).
pub const REDDY_UNIFORM: f64 = 4.273e-3;
/// Thickness-to-side ratios of the thick ladders.
pub const THICK_RATIOS: [f64; 2] = [0.1, 0.2];
/// Elements a side of the thick ladders.
pub const THICK_MESHES: [usize; 4] = [8, 16, 32, 64];
/// The thin limit's h/L and meshes (Mindlin's, then the BFS plate's).
pub const THIN: (f64, (usize, usize), (usize, usize)) = (1e-3, (80, 64), (20, 16));
/// Elements a side of the node-support ladder (h/L = 0.1, four fixed corners).
pub const NODE_MESHES: [usize; 4] = [32, 64, 128, 256];

/// One thick ladder against the series.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ThickLadder {
    /// h/L of the square plate.
    pub ratio: f64,
    /// (elements a side, compliance m/N) per mesh.
    pub values: Vec<(usize, f64)>,
    /// The series' compliance (m/N) and its truncation estimate.
    pub series: (f64, f64),
    /// The series' shear part over its compliance.
    pub shear_share: f64,
    /// The observed rate of the three finest meshes.
    pub rate: Option<f64>,
    /// Richardson's value from the two finest, relative to the series, minus 1.
    pub extrapolated_error: f64,
    /// The Richardson error estimate of the finest mesh, relative.
    pub estimate: f64,
    /// The finest mesh's actual error, relative.
    pub finest_error: f64,
}

/// The thin limit: Mindlin, BFS and Kirchhoff's series under one patch.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ThinLimit {
    /// h/L.
    pub ratio: f64,
    /// Mindlin FE, BFS FE and the series' Kirchhoff part, m/N.
    pub mindlin: f64,
    /// The BFS plate's compliance under the same patch, m/N.
    pub bfs: f64,
    /// Kirchhoff's series, m/N.
    pub series: f64,
}

/// The node-support ladder: compliances and the increments against theory.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NodeGrowth {
    /// (elements a side, compliance m/N).
    pub values: Vec<(usize, f64)>,
    /// Σ R² (2/π) ln 2/(k_s G h) with R = 1/4 at each corner, m/N.
    pub predicted: f64,
}

/// What the Mindlin verification computed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MindlinVerification {
    /// The series' uniform-load centre deflection at a/h = 10, in q a⁴/D.
    pub uniform: f64,
    /// The thick ladders.
    pub thick: Vec<ThickLadder>,
    /// The thin limit.
    pub thin: ThinLimit,
    /// The node supports' growth.
    pub growth: NodeGrowth,
}

fn steel(length: f64, width: f64, thickness: f64) -> PlateProperties {
    PlateProperties { length, width, thickness, youngs_modulus: 210e9, poisson_ratio: 0.3, density: 7850.0 }
}

/// A square plate of side 1 m, all edges simply supported, a centred patch of a quarter side.
fn thick_ladder(ratio: f64) -> Result<ThickLadder, Failure> {
    let props = steel(1.0, 1.0, ratio);
    let patch = Patch { x: 0.5, z: 0.5, side_x: 0.25, side_z: 0.25 };
    let s = series::navier_patch(&props, &patch)?;
    let mut values = Vec::new();
    for n in THICK_MESHES {
        let p = Plate::new(props, Mesh::uniform(1.0, 1.0, n, n)?)?;
        values.push((n, p.factorize(&Supports::all_edges_simple())?.respond(&patch)?.compliance));
    }
    let seq: Vec<f64> = values.iter().map(|v| v.1).collect();
    let e = richardson(&seq).ok_or("the thick ladder has four meshes")?;
    Ok(ThickLadder {
        ratio,
        series: (s.compliance, s.truncation),
        shear_share: s.shear / s.compliance,
        rate: e.observed_rate,
        extrapolated_error: e.extrapolated / s.compliance - 1.0,
        estimate: e.error_estimate / s.compliance,
        finest_error: e.finest / s.compliance - 1.0,
        values,
    })
}

/// The thin limit on a 1 m x 0.8 m simply supported plate, patch 0.1 m at (0.4, 0.3).
fn thin_limit() -> Result<ThinLimit, Failure> {
    let (ratio, (mx, mz), (bx, bz)) = THIN;
    let props = steel(1.0, 0.8, ratio);
    let patch = Patch { x: 0.4, z: 0.3, side_x: 0.1, side_z: 0.1 };
    let supports = Supports::all_edges_simple();
    let mindlin = Plate::new(props, Mesh::uniform(1.0, 0.8, mx, mz)?)?.factorize(&supports)?.respond(&patch)?;
    let bfs = Model::new(props, Mesh::uniform(1.0, 0.8, bx, bz)?)?.factorize(&supports)?.respond_patch(&patch)?;
    Ok(ThinLimit { ratio, mindlin: mindlin.compliance, bfs, series: series::navier_patch(&props, &patch)?.kirchhoff })
}

/// Four fixed corners on nodes, h/L = 0.1, a centred patch of 1/8 the side.
fn node_growth() -> Result<NodeGrowth, Failure> {
    let props = steel(1.0, 1.0, 0.1);
    let patch = Patch { x: 0.5, z: 0.5, side_x: 0.125, side_z: 0.125 };
    let mut values = Vec::new();
    let mut predicted = 0.0;
    for n in NODE_MESHES {
        let p = Plate::new(props, Mesh::uniform(1.0, 1.0, n, n)?)?;
        predicted = node_support_growth(&[0.25; 4], p.shear_rigidity());
        values.push((n, p.factorize(&Supports::con1())?.respond(&patch)?.compliance));
    }
    Ok(NodeGrowth { values, predicted })
}

/// Every check of the Mindlin plate.
pub fn verify() -> Result<MindlinVerification, Failure> {
    let props = steel(1.0, 1.0, 0.1);
    let whole = series::navier_patch(&props, &Patch { x: 0.5, z: 0.5, side_x: 1.0, side_z: 1.0 })?;
    Ok(MindlinVerification {
        uniform: whole.centre_deflection * props.rigidity(),
        thick: THICK_RATIOS.iter().map(|&r| thick_ladder(r)).collect::<Result<_, _>>()?,
        thin: thin_limit()?,
        growth: node_growth()?,
    })
}
