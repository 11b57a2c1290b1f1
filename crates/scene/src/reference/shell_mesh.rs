//! The reference's sections of `[shell_mesh]`: a shell structure read from a Gmsh MSH file
//! (`plate_fem::shell::gmsh`, `coupled::compliance::shell_mesh`).

use super::{key, num, whole, Section, NO_UNIT, REQUIRED};
use crate::limits;
use crate::validate::shell_mesh::{DOF_NAMES, LEVELS, MAX_MESH_FILE_BYTES, UNIT_MM};

/// `[shell_mesh]`, `[[shell_mesh.holds]]` and `[[shell_mesh.springs]]`.
pub(super) fn sections() -> Vec<Section> {
    vec![
        Section {
            title: "[shell_mesh]",
            about: format!(
                "A shell structure of your own (a tail beam, canopy or chute) read from a Gmsh MSH file, format 4.1 or 2.2, ASCII, of 4-node quadrilaterals (and lines and points for groups), struck by the scene's bodies at the scene's velocities (\"shell-mesh\" only). Gmsh's physical groups, by name, say what is what; meshio converts other formats (`meshio convert in.vtu out.msh --output-format gmsh22`). The walls' material is `[plate]`'s. The contact force is spread over a disc of diameter t (the struck group's thickness) about each point. The compliance comes from a ladder of the file's mesh and its uniform refinements (each quadrilateral split in four), extrapolated at the observed rate. A curved surface stays as faceted as the file meshes it. The finest mesh may hold at most {} unknowns, and the file's own mesh is built, restrained and loaded at every point before the ladder runs. The file's SHA-256 enters the scene's provenance.",
                limits::MAX_TAIL_BEAM_DOFS
            ),
            keys: vec![
                key("file", "string", NO_UNIT, format!("an MSH file of at most {MAX_MESH_FILE_BYTES} bytes"), REQUIRED, "The mesh, relative to the scene file's folder"),
                num("unit_mm", "mm", UNIT_MM, "1 (the file in millimetres)", "The length of one unit of the file's coordinates"),
                key("thickness_mm", "table: group = number", "mm", format!("{} each; surface groups", limits::THICKNESS_MM), REQUIRED, "Each surface group's wall thickness (`{ top = 30.0, webs = 20.0 }`); every quadrilateral must be in one of them"),
                key("holds", "array of tables", NO_UNIT, "see `[[shell_mesh.holds]]`", "none", "Groups whose nodes are held"),
                key("springs", "array of tables", NO_UNIT, "see `[[shell_mesh.springs]]`", "none", "Springs to ground on groups (jacks on their pads)"),
                key("struck", "string", NO_UNIT, "a surface group with a thickness", REQUIRED, "The face the lumps strike"),
                key("points_mm", "list of [x, y, z]", "mm", format!("on the struck group, the contact disc on its flat part; 1 to {}", limits::MAX_TAIL_BEAM_POINTS), REQUIRED, "Struck points, in the file's frame"),
                whole("levels", LEVELS, "3", "Meshes in the ladder: the file's and its refinements (three measure a convergence rate, four confirm it)"),
            ],
        },
        Section {
            title: "[[shell_mesh.holds]]",
            about: "DOFs held at zero at every node of a group (a pin's line, a clamped edge, a symmetry plane).".into(),
            keys: vec![
                key("group", "string", NO_UNIT, "a group of the file", REQUIRED, "The group"),
                key("dofs", "list of strings", NO_UNIT, format!("some of {DOF_NAMES:?}, each once"), REQUIRED, "Translations and rotations about the global axes"),
            ],
        },
        Section {
            title: "[[shell_mesh.springs]]",
            about: "A spring to ground (a jack) whose stiffness is shared equally by a group's nodes (its pad), along a line of action.".into(),
            keys: vec![
                key("group", "string", NO_UNIT, "a group of the file", REQUIRED, "The pad's group"),
                num("stiffness_n_per_m", "N/m", limits::SPRING_N_PER_M, REQUIRED, "Total axial stiffness"),
                key("direction", "list of 3 numbers", NO_UNIT, "not all zero", REQUIRED, "Line of action in the file's frame (normalised)"),
            ],
        },
    ]
}
