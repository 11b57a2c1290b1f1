//! `[shell_mesh]`: a shell structure read from a Gmsh MSH file (`plate_fem::shell::gmsh`), its
//! groups' thicknesses, holds and springs, the struck face and points. Everything is checked
//! before the ladder is computed: the file is read and parsed, every group named exists with
//! the right dimension, the finest mesh's size is budgeted, and the file's own mesh is built,
//! restrained, factorized and loaded at every point (a small fraction of the ladder's cost),
//! so that a bad element, a mechanism or a point off the struck face is refused here.

use super::{other, Invalid, MM};
use crate::limits;
use crate::raw::{RawGroupSpring, RawHold, RawShellMesh};
use analytic::params::{check, Range};
use analytic::Plate;
use coupled::compliance::shell_mesh::{GroupSpring, ShellMeshScene};
use coupled::scene::Analysis;
use plate_fem::shell::gmsh::{Budget, MeshFile};
use plate_fem::shell::DISC_RULE;
use sha2::{Digest, Sha256};
use std::path::Path;

/// Largest mesh file, bytes.
pub(crate) const MAX_MESH_FILE_BYTES: u64 = 1 << 28;
/// The mesh's length unit, mm per unit of the file.
pub(crate) const UNIT_MM: Range = Range::closed(1e-3, 1e4);
/// Meshes in the ladder: the file's and its refinements.
pub(crate) const LEVELS: Range = Range::closed(2.0, 4.0);
/// The DOFs a hold may name, in the order of the structure's six per node.
pub(crate) const DOF_NAMES: [&str; 6] = ["ux", "uy", "uz", "rx", "ry", "rz"];

/// Reads `[shell_mesh] file` (relative to `base`, or one of `embedded`) into the raw table.
pub(crate) fn read_file(raw: &mut RawShellMesh, base: Option<&Path>, embedded: &[(&str, &str)]) -> Result<(), Invalid> {
    if let Some((_, text)) = embedded.iter().find(|(name, _)| *name == raw.file) {
        raw.bytes = Some(text.as_bytes().to_vec());
        return Ok(());
    }
    let full = match base {
        Some(dir) if Path::new(&raw.file).is_relative() => dir.join(&raw.file),
        _ => Path::new(&raw.file).to_path_buf(),
    };
    let shown = full.display();
    let field = "shell_mesh.file";
    let meta = std::fs::metadata(&full).map_err(|e| other(field, format!("'{shown}' cannot be read: {e}")))?;
    if !meta.is_file() || meta.len() > MAX_MESH_FILE_BYTES {
        return Err(other(field, format!("'{shown}' is not a regular file of at most {MAX_MESH_FILE_BYTES} bytes")));
    }
    raw.bytes = Some(std::fs::read(&full).map_err(|e| other(field, format!("'{shown}' cannot be read: {e}")))?);
    Ok(())
}

/// `[shell_mesh]`, present exactly when the analyses name "shell-mesh"; the walls take
/// `plate`'s material.
pub(super) fn table(
    raw: Option<&RawShellMesh>,
    analyses: &[Analysis],
    plate: &Plate,
) -> Result<Option<ShellMeshScene>, Invalid> {
    match (raw, analyses.contains(&Analysis::ShellMesh)) {
        (Some(t), true) => Ok(Some(validate(t, plate)?)),
        (None, false) => Ok(None),
        (None, true) => Err(other("shell_mesh", "the \"shell-mesh\" analysis needs a [shell_mesh] table")),
        (Some(_), false) => Err(other(
            "shell_mesh",
            "is read only by the \"shell-mesh\" analysis; add it to analyses or remove the table",
        )),
    }
}

fn validate(raw: &RawShellMesh, plate: &Plate) -> Result<ShellMeshScene, Invalid> {
    // Everything that needs no mesh first.
    let unit = check("shell_mesh.unit_mm", raw.unit_mm, UNIT_MM, "mm")? * MM;
    let levels = check("shell_mesh.levels", raw.levels as f64, LEVELS, "")? as u32;
    let mut thickness = Vec::new();
    for (name, &t) in &raw.thickness_mm {
        thickness.push((
            name.clone(),
            check(&format!("shell_mesh.thickness_mm.{name}"), t, limits::THICKNESS_MM, "mm")? * MM,
        ));
    }
    if !raw.thickness_mm.contains_key(&raw.struck) {
        return Err(other(
            "shell_mesh.struck",
            format!("'{}' has no thickness in shell_mesh.thickness_mm", raw.struck),
        ));
    }
    let holds = raw.holds.iter().enumerate().map(|(i, h)| hold(i, h)).collect::<Result<Vec<_>, _>>()?;
    let springs = raw.springs.iter().enumerate().map(|(i, s)| spring(i, s)).collect::<Result<Vec<_>, _>>()?;
    let points = points(&raw.points_mm)?;
    let bytes = raw.bytes.as_deref().ok_or_else(|| other("shell_mesh.file", "was not read"))?;
    let mesh = read_mesh(raw, bytes, unit, levels)?;
    let groups = thickness.iter().map(|(g, _)| (format!("shell_mesh.thickness_mm.{g}"), g, true));
    let groups = groups
        .chain(holds.iter().enumerate().map(|(i, (g, _))| (format!("shell_mesh.holds[{i}].group"), g, false)))
        .chain(springs.iter().enumerate().map(|(i, s)| (format!("shell_mesh.springs[{i}].group"), &s.group, false)))
        .chain(std::iter::once(("shell_mesh.struck".to_string(), &raw.struck, true)));
    for (field, name, surface) in groups {
        group(&mesh, field, name, surface)?;
    }
    let scene = ShellMeshScene {
        mesh,
        file: raw.file.clone(),
        sha256: Sha256::digest(bytes).iter().map(|b| format!("{b:02x}")).collect(),
        thickness,
        holds,
        springs,
        struck: raw.struck.clone(),
        points,
        levels,
    };
    try_coarsest(&scene, plate)?;
    Ok(scene)
}

/// The file's mesh, its declared size refused beyond what `levels` meshes may hold.
fn read_mesh(raw: &RawShellMesh, bytes: &[u8], unit: f64, levels: u32) -> Result<MeshFile, Invalid> {
    let text =
        std::str::from_utf8(bytes).map_err(|_| other("shell_mesh.file", "is not text: save the MSH file as ASCII"))?;
    let refinement = 4usize.pow(levels - 1);
    // Each node carries six unknowns; a shell mesh has about as many quadrilaterals as nodes.
    let cap = limits::MAX_TAIL_BEAM_DOFS / 6 / refinement;
    let over = |what: String| {
        format!(
            "{what}: the finest of {levels} meshes (each quadrilateral split in four {} times) may hold at most {} unknowns (the budget); give fewer levels or a coarser mesh",
            levels - 1,
            limits::MAX_TAIL_BEAM_DOFS
        )
    };
    let mesh =
        MeshFile::parse_within(text, &raw.file, unit, Budget { nodes: cap, elements: 2 * cap }).map_err(|e| {
            other(
                "shell_mesh.file",
                if e.to_string().contains("above the limit") { over(e.to_string()) } else { e.to_string() },
            )
        })?;
    if mesh.quads.is_empty() {
        return Err(other("shell_mesh.file", format!("'{}' has no quadrilaterals", raw.file)));
    }
    let dofs = 6 * mesh.nodes.len() * refinement;
    if dofs > limits::MAX_TAIL_BEAM_DOFS || mesh.quads.len() > cap {
        return Err(other(
            "shell_mesh.levels",
            over(format!(
                "{} nodes and {} quadrilaterals give about {dofs} unknowns on the finest mesh",
                mesh.nodes.len(),
                mesh.quads.len()
            )),
        ));
    }
    Ok(mesh)
}

/// The group `name` of `mesh`, named by `field` in errors: it must exist, have cells (a
/// surface where `surface`), and its lines must be edges of quadrilaterals (a line that is
/// not would leave its midpoint on no element once refined).
fn group(mesh: &MeshFile, field: String, name: &str, surface: bool) -> Result<(), Invalid> {
    let g = mesh.group(name).map_err(|e| other(&field, e.to_string()))?;
    if surface && mesh.groups[g].dim != 2 {
        return Err(other(field, format!("'{name}' is a group of dimension {}, not a surface", mesh.groups[g].dim)));
    }
    if mesh.nodes_of(name).map_err(|e| other(&field, e.to_string()))?.is_empty() {
        return Err(other(field, format!("'{name}' has no elements in the file")));
    }
    let edges: std::collections::HashSet<(usize, usize)> = mesh
        .quads
        .iter()
        .flat_map(|q| (0..4).map(move |k| (q.nodes[k], q.nodes[(k + 1) % 4])))
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    if let Some(line) = mesh
        .lines
        .iter()
        .find(|l| l.groups.contains(&g) && !edges.contains(&(l.nodes[0].min(l.nodes[1]), l.nodes[0].max(l.nodes[1]))))
    {
        return Err(other(field, format!("'{name}' has the line {} that is no quadrilateral's edge", line.tag)));
    }
    Ok(())
}

/// `[[shell_mesh.holds]]` entry `i`: its group and DOFs.
fn hold(i: usize, h: &RawHold) -> Result<(String, Vec<usize>), Invalid> {
    let field = format!("shell_mesh.holds[{i}].dofs");
    if h.dofs.is_empty() {
        return Err(other(field, format!("is empty; name some of {DOF_NAMES:?}")));
    }
    let mut dofs = Vec::new();
    for d in &h.dofs {
        let k = DOF_NAMES
            .iter()
            .position(|n| n == d)
            .ok_or_else(|| other(&field, format!("'{d}' is not one of {DOF_NAMES:?}")))?;
        if dofs.contains(&k) {
            return Err(other(&field, format!("'{d}' is named twice")));
        }
        dofs.push(k);
    }
    Ok((h.group.clone(), dofs))
}

/// `[[shell_mesh.springs]]` entry `i`.
fn spring(i: usize, s: &RawGroupSpring) -> Result<GroupSpring, Invalid> {
    let stiffness = check(
        &format!("shell_mesh.springs[{i}].stiffness_n_per_m"),
        s.stiffness_n_per_m,
        limits::SPRING_N_PER_M,
        "N/m",
    )?;
    let field = format!("shell_mesh.springs[{i}].direction");
    let norm = s.direction.iter().map(|v| v * v).sum::<f64>().sqrt();
    if s.direction.len() != 3 || !(norm.is_finite() && norm > 0.0) {
        return Err(other(field, format!("{:?} is not three finite numbers, not all zero", s.direction)));
    }
    let direction = [s.direction[0] / norm, s.direction[1] / norm, s.direction[2] / norm];
    Ok(GroupSpring { group: s.group.clone(), stiffness, direction })
}

/// `points_mm`: each [x, y, z] in the mesh's frame (mm), to m.
fn points(raw: &[Vec<f64>]) -> Result<Vec<[f64; 3]>, Invalid> {
    if raw.is_empty() || raw.len() > limits::MAX_TAIL_BEAM_POINTS {
        return Err(other(
            "shell_mesh.points_mm",
            format!("has {} points; give 1 to {}", raw.len(), limits::MAX_TAIL_BEAM_POINTS),
        ));
    }
    raw.iter()
        .enumerate()
        .map(|(i, p)| match p.as_slice() {
            &[x, y, z] if x.is_finite() && y.is_finite() && z.is_finite() => Ok([x * MM, y * MM, z * MM]),
            _ => {
                Err(other(format!("shell_mesh.points_mm[{i}]"), format!("{p:?} is not three finite numbers [x, y, z]")))
            }
        })
        .collect()
}

/// The file's own mesh built, restrained, factorized and loaded at every point: what the
/// ladder would refuse, refused before it runs.
fn try_coarsest(scene: &ShellMeshScene, plate: &Plate) -> Result<(), Invalid> {
    let m = plate.material();
    let built = scene.build(&scene.mesh, m.youngs_modulus(), m.poisson_ratio()).map_err(|e| {
        let message = e.to_string();
        // A quadrilateral without a thickness is the thickness table's fault; any other, the file's.
        other(if message.contains("thickness") { "shell_mesh.thickness_mm" } else { "shell_mesh.file" }, message)
    })?;
    built.structure.factorize(&built.restraints).map_err(|e| other("shell_mesh.holds and springs", e.to_string()))?;
    let radius = scene.struck_thickness().map_err(|e| other("shell_mesh.struck", e.to_string()))? / 2.0;
    for (i, &p) in scene.points.iter().enumerate() {
        built
            .structure
            .disc_load(p, radius, &built.struck, DISC_RULE)
            .map_err(|e| other(format!("shell_mesh.points_mm[{i}]"), e.to_string()))?;
    }
    Ok(())
}
