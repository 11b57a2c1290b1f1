//! The plate FE bench (`impact fem-bench`): mesh selection by a convergence study, and the
//! cost of the plate compliance map with one factorization and rank-4 corner updates against
//! fresh factorizations. Timings are the study's data: it measures itself.

use analytic::Condition;
use coupled::discretisation::{ladder_meshes, plate_properties};
use coupled::supports::corner_supports;
use plate_fem::convergence::richardson;
use plate_fem::{CornerFamily, EdgeSupport, FemError, Mesh, Model, PlateProperties, Supports};
use scene::Scene;
use serde::Serialize;
use std::time::Instant;

/// One rung of a mesh ladder.
#[derive(Debug, Clone, Serialize)]
pub struct Rung {
    pub nx: usize,
    pub nz: usize,
    pub dofs: usize,
    pub compliance: f64,
    /// |C - C_ref|/C_ref against the Richardson value of the two finest rungs.
    pub error: f64,
    pub seconds: f64,
}

/// Con 1 centre compliance on a ladder of meshes: the rungs, the extrapolated value and
/// its observed rate.
pub fn centre_ladder(
    props: &PlateProperties,
    base: usize,
    levels: u32,
) -> Result<(Vec<Rung>, f64, Option<f64>), FemError> {
    let mut rungs = Vec::new();
    for mesh in ladder_meshes(props, base, levels)? {
        let t = Instant::now();
        let (nx, nz) = (mesh.nx(), mesh.nz());
        let model = Model::new(*props, mesh)?;
        let c = model.factorize(&Supports::con1())?.respond(props.length / 2.0, props.width / 2.0)?.compliance;
        rungs.push(Rung { nx, nz, dofs: model.dofs(), compliance: c, error: 0.0, seconds: t.elapsed().as_secs_f64() });
    }
    let values: Vec<f64> = rungs.iter().map(|r| r.compliance).collect();
    let ext = richardson(&values).ok_or_else(|| FemError::Mesh("a ladder needs two meshes".into()))?;
    for r in &mut rungs {
        r.error = (r.compliance - ext.extrapolated).abs() / ext.extrapolated;
    }
    Ok((rungs, ext.extrapolated, ext.observed_rate))
}

fn peak_memory_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

/// Timings of the compliance map.
#[derive(Debug, Clone, Serialize)]
pub struct BenchReport {
    pub ladder: Vec<Rung>,
    pub extrapolated_centre: f64,
    pub observed_rate: Option<f64>,
    pub chosen: (usize, usize),
    pub dofs: usize,
    pub nonzeros: usize,
    pub points: usize,
    pub assembly_s: f64,
    pub factorization_s: f64,
    /// The base at every distinct point: its selected inverse, or one solve each where
    /// that is cheaper (plate_fem::Factorization::selected_inverse_pays), s.
    pub probe_s: f64,
    pub update_s: f64,
    pub total_s: f64,
    pub reference_s: f64,
    /// The largest relative residual of the base's solves (with the selected inverse, of
    /// the solve that checks it).
    pub max_residual: f64,
    pub max_difference_to_reference: f64,
    /// Peak resident memory of the process up to the end of the mesh ladder (MiB).
    pub peak_memory_mib: Option<f64>,
    /// Peak resident memory during the map alone (after a high-water reset), if the
    /// platform allows the reset.
    pub map_peak_memory_mib: Option<f64>,
}

/// `impact fem-bench`: choose the mesh that reaches `tolerance` at the centre, then time
/// the compliance at `nx_pts` x `nz_pts` impact points for Con 1-3 with one factorization
/// and rank-4 updates (the base probed through its selected inverse where that beats one
/// solve per point), against three fresh factorizations with unblocked solves.
pub fn bench(scene: &Scene, tolerance: f64, nx_pts: usize, nz_pts: usize) -> Result<BenchReport, FemError> {
    let props = plate_properties(&scene.plate);
    let (ladder, extrapolated_centre, observed_rate) = centre_ladder(&props, 10, 5)?;
    let Some(chosen) = ladder.iter().find(|r| r.error <= tolerance) else {
        let best = ladder.iter().map(|r| r.error).fold(f64::INFINITY, f64::min);
        return Err(FemError::Mesh(format!(
            "--tolerance {tolerance:e} was not met: the finest mesh of the ladder ({}) reaches {best:.1e}; choose a tolerance of at least that",
            ladder.last().map_or(String::new(), |r| format!("{} x {}", r.nx, r.nz))
        )));
    };
    let k_t = scene.conditions.iter().find_map(|c| c.spring_stiffnesses().next()).unwrap_or(5.11545e8);
    let conditions = [Condition::BothFixed, Condition::BothSprings { k_t }, Condition::FixedAndSprings { k_t }];
    let points: Vec<(f64, f64)> = coupled::scene::even_points(props.length, nx_pts)
        .into_iter()
        .flat_map(|x| coupled::scene::even_points(props.width, nz_pts).into_iter().map(move |z| (x, z)))
        .collect();

    // Reset the resident-set high-water mark (Linux: 5 > /proc/self/clear_refs), so the
    // peak below is the map's alone, not the ladder's finest mesh.
    let ladder_peak = peak_memory_mib();
    let reset = std::fs::write("/proc/self/clear_refs", "5").is_ok();
    let t0 = Instant::now();
    let model = Model::new(props, Mesh::uniform(props.length, props.width, chosen.nx, chosen.nz)?)?;
    let t1 = Instant::now();
    let family = CornerFamily::new(&model, [EdgeSupport::Free; 4], CornerFamily::default_base_stiffness(&model))?;
    let t2 = Instant::now();
    let base = family.probe_map(&points)?;
    let t3 = Instant::now();
    let mut maps = Vec::new();
    for c in conditions {
        let corners = corner_supports(c).corners;
        maps.push(base.iter().map(|b| family.respond(b, corners)).collect::<Result<Vec<_>, _>>()?);
    }
    let t4 = Instant::now();
    let map_peak = if reset { peak_memory_mib() } else { None };

    // Reference: a fresh factorization per condition and one unrefined solve per point.
    let r0 = Instant::now();
    let mut max_diff: f64 = 0.0;
    for (c, map) in conditions.iter().zip(&maps) {
        let f = model.factorize(&corner_supports(*c))?.with_refinement(0);
        for (p, m) in points.iter().zip(map) {
            let r = f.respond(p.0, p.1)?;
            if r.compliance > 0.0 {
                max_diff = max_diff.max((r.compliance - m.compliance).abs() / r.compliance);
            }
        }
    }
    let reference_s = r0.elapsed().as_secs_f64();
    Ok(BenchReport {
        ladder: ladder.clone(),
        extrapolated_centre,
        observed_rate,
        chosen: (chosen.nx, chosen.nz),
        dofs: model.dofs(),
        nonzeros: model.nonzeros(),
        points: points.len(),
        assembly_s: (t1 - t0).as_secs_f64(),
        factorization_s: (t2 - t1).as_secs_f64(),
        probe_s: (t3 - t2).as_secs_f64(),
        update_s: (t4 - t3).as_secs_f64(),
        total_s: (t4 - t0).as_secs_f64(),
        reference_s,
        max_residual: base.iter().map(|b| b.residual).fold(0.0, f64::max),
        max_difference_to_reference: max_diff,
        peak_memory_mib: ladder_peak,
        map_peak_memory_mib: map_peak,
    })
}
