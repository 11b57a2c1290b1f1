//! The reference's sections of `[tail_beam]`: the box-section tail beam (`plate_fem::shell`,
//! `coupled::compliance::tail_beam`).

use super::{key, num, Section, NO_UNIT, REQUIRED};
use crate::limits;

/// `[tail_beam]` and `[[tail_beam.jacks]]`.
pub(super) fn sections() -> Vec<Section> {
    let t = limits::THICKNESS_MM;
    vec![
        Section {
            title: "[tail_beam]",
            about: format!(
                "A hydraulic support's tail beam as a welded box of flat shell walls (membrane, MITC4 bending with transverse shear, drilling), struck on its top plate by the scene's bodies at the scene's velocities (\"tail-beam\" only). x runs from the hinged end (x = 0) to the tip, z across the width, y up from the bottom plate's mid-surface to the top plate's. The walls' material is `[plate]`'s. Three nested meshes (elements of `element_mm`, then halved twice) give the compliance and its error estimate; the finest may hold at most {} unknowns, checked before anything is built.",
                limits::MAX_TAIL_BEAM_DOFS
            ),
            keys: vec![
                num("length_mm", "mm", limits::PLATE_SIZE_MM, REQUIRED, "Length L along x"),
                num("width_mm", "mm", limits::PLATE_SIZE_MM, REQUIRED, "Width B along z"),
                num("height_mm", "mm", limits::PLATE_SIZE_MM, REQUIRED, "Depth H between the top and bottom plates' mid-surfaces"),
                num("top_mm", "mm", t, REQUIRED, "Top plate thickness (the struck plate; the contact patch's side); below the box's smallest side, as every wall's"),
                num("bottom_mm", "mm", t, REQUIRED, "Bottom plate thickness"),
                num("webs_mm", "mm", t, REQUIRED, "Side webs' thickness (z = 0 and B)"),
                num("ends_mm", "mm", t, REQUIRED, "End plates' thickness (x = 0 and L)"),
                key("ribs_z_mm", "list of numbers", "mm", "each in (0, B)", "none", "Longitudinal ribs: vertical plates along the whole length at these z"),
                key("rib_mm", "number", "mm", t.to_string(), "`webs_mm`; required with ribs, refused without", "Ribs' thickness"),
                key("diaphragms_x_mm", "list of numbers", "mm", "each in (0, L), apart from each other and the ends by more than their thickness", "none", "Diaphragms: transverse plates across the whole section (top to bottom, web to web) at these x, welded to every wall they meet"),
                key("diaphragm_mm", "number", "mm", t.to_string(), "required with diaphragms, refused without", "Diaphragms' thickness"),
                key("pin_height_mm", "number", "mm", "[0, H]", REQUIRED, "Height of the hinge pins' line on the end plate x = 0"),
                key("pins_z_mm", "list of [z0, z1]", "mm", "0 ≤ z0 < z1 ≤ B; at least one", REQUIRED, "The pins' spans across the width: every node on them is held in translation, free to rotate"),
                num("element_mm", "mm", limits::PLATE_SIZE_MM, REQUIRED, "Element side of the coarsest mesh"),
                key("points_mm", "list of [x, z]", "mm", format!("x in [0, L], z in [0, B]; 1 to {}", limits::MAX_TAIL_BEAM_POINTS), REQUIRED, "Struck points on the top plate"),
                key("jacks", "array of tables", NO_UNIT, "see `[[tail_beam.jacks]]`", "required, at least one", "The jacks: springs to ground on pads of the bottom plate"),
            ],
        },
        Section {
            title: "[[tail_beam.jacks]]",
            about: "A jack as a spring to ground along its axis, acting on a square pad of the bottom plate whose nodes share its stiffness. Its axis must not pass through the pins' line (it would hold nothing).".into(),
            keys: vec![
                key("x_mm", "number", "mm", "the pad on the bottom plate", REQUIRED, "Pad centre along the beam"),
                key("z_mm", "number", "mm", "the pad on the bottom plate", REQUIRED, "Pad centre across the width"),
                num("pad_mm", "mm", limits::PLATE_SIZE_MM, REQUIRED, "Pad side"),
                num("stiffness_n_per_m", "N/m", limits::SPRING_N_PER_M, REQUIRED, "Axial stiffness (oil column and cylinder in series)"),
                num("angle_deg", "°", limits::JACK_ANGLE_DEG, REQUIRED, "Angle of the axis to x in the x-y plane"),
            ],
        },
    ]
}
