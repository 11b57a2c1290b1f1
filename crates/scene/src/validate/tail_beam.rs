//! `[tail_beam]`: the box, its pins and jacks, the mesh and the struck points, checked in the
//! file's units, converted to SI, and the finest mesh's size budgeted before anything is built.

use super::{other, pair, Invalid, MM};
use crate::limits;
use crate::raw::{RawJack, RawTailBeam};
use analytic::params::check;
use coupled::compliance::tail_beam::{TailBeamScene, TAIL_BEAM_LEVELS};
use coupled::reduced::SignalSettings;
use coupled::scene::Analysis;
use identify::measurement::{ChainSpec, Measurand};
use plate_fem::shell::element::DOFS_PER_NODE;
use plate_fem::shell::tail_beam::{Diaphragms, Jack, TailBeam};

/// `[tail_beam]`, present exactly when the analyses name "tail-beam".
pub(super) fn table(raw: Option<&RawTailBeam>, analyses: &[Analysis]) -> Result<Option<TailBeamScene>, Invalid> {
    match (raw, analyses.contains(&Analysis::TailBeam)) {
        (Some(t), true) => Ok(Some(validate_tail_beam(t)?)),
        (None, false) => Ok(None),
        (None, true) => Err(other("tail_beam", "the \"tail-beam\" analysis needs a [tail_beam] table")),
        (Some(_), false) => Err(other(
            "tail_beam",
            "is read only by the \"tail-beam\" analysis; add it to analyses or remove the table",
        )),
    }
}

/// What a tail beam's stream (`on_box`) needs of the scene: modes given as a number (the
/// chain's rule chooses a plate's), and a chain, if any, that records what the box's channels
/// are: its jacks' forces, and accelerations where it has sensors.
pub(super) fn check_stream(on_box: bool, signals: &SignalSettings, chain: Option<&ChainSpec>) -> Result<(), Invalid> {
    if !on_box {
        return Ok(());
    }
    let records = |m: Measurand| chain.is_none_or(|c| c.recordings.iter().any(|r| r.measurand == m));
    for (m, key, needed, what) in [
        (Measurand::SupportForce, "measurement.support_force", true, "the jacks' forces"),
        (
            Measurand::Acceleration,
            "measurement.acceleration",
            !signals.sensors.is_empty(),
            "the sensors' accelerations",
        ),
    ] {
        if needed && !records(m) {
            return Err(other(
                key,
                format!("is missing: a tail beam's stream records {what} through the chain; add the table"),
            ));
        }
    }
    if signals.modes_from_chain {
        return Err(other(
            "signals.modes",
            "\"chain\" chooses a plate's modes by its chain; a tail beam's stream keeps a number of them (give one)",
        ));
    }
    Ok(())
}

/// `[tail_beam]` into a [`TailBeamScene`].
fn validate_tail_beam(raw: &RawTailBeam) -> Result<TailBeamScene, Invalid> {
    let size = |name: &str, v: f64| check(&format!("tail_beam.{name}"), v, limits::PLATE_SIZE_MM, "mm");
    let (l, b, h) =
        (size("length_mm", raw.length_mm)?, size("width_mm", raw.width_mm)?, size("height_mm", raw.height_mm)?);
    let walls = walls(raw, l, b, h)?;
    let (pin_height, pins) = pins(raw, b, h)?;
    if raw.jacks.is_empty() {
        return Err(other(
            "tail_beam.jacks",
            "needs at least one [[tail_beam.jacks]]: the pins alone leave the beam free to turn",
        ));
    }
    let jacks = raw.jacks.iter().enumerate().map(|(i, j)| jack(i, j, l, b)).collect::<Result<Vec<_>, _>>()?;
    let beam = TailBeam {
        length: l * MM,
        width: b * MM,
        height: h * MM,
        top: walls.top,
        bottom: walls.bottom,
        webs: walls.webs,
        ends: walls.ends,
        ribs: walls.ribs,
        rib: walls.rib,
        diaphragms: walls.diaphragms,
        pin_height,
        pins,
        jacks,
    };
    beam.validate().map_err(|e| other("tail_beam", e.to_string()))?;
    let element = check("tail_beam.element_mm", raw.element_mm, limits::PLATE_SIZE_MM, "mm")?;
    let nodes = beam
        .nodes_bound(element * MM, TAIL_BEAM_LEVELS - 1)
        .map_err(|e| other("tail_beam.element_mm", e.to_string()))?;
    let dofs = DOFS_PER_NODE * nodes;
    if dofs > limits::MAX_TAIL_BEAM_DOFS {
        return Err(other(
            "tail_beam.element_mm",
            format!(
                "{element} mm gives about {dofs} unknowns on the finest of the {TAIL_BEAM_LEVELS} meshes (element {} mm); the budget is {}: give a larger element",
                element / 4.0,
                limits::MAX_TAIL_BEAM_DOFS
            ),
        ));
    }
    Ok(TailBeamScene { beam, element: element * MM, points: points(&raw.points_mm, l, b)? })
}

/// The walls' thicknesses (m) and the ribs' and diaphragms' positions (m).
struct Walls {
    top: f64,
    bottom: f64,
    webs: f64,
    ends: f64,
    rib: f64,
    ribs: Vec<f64>,
    diaphragms: Option<Diaphragms>,
}

/// `tail_beam.{name}` (m): each position inside (0, `extent`) mm, the `along` dimension.
fn positions(name: &str, list: &[f64], extent: f64, along: &str) -> Result<Vec<f64>, Invalid> {
    let mut out = Vec::with_capacity(list.len());
    for (i, &v) in list.iter().enumerate() {
        if !(v > 0.0 && v < extent) {
            return Err(other(
                format!("tail_beam.{name}[{i}]"),
                format!("{v} mm is not inside the {along}, (0, {extent}) mm"),
            ));
        }
        out.push(v * MM);
    }
    Ok(out)
}

/// The walls of an `l` x `b` x `h` mm box: each thickness below its smallest side, the ribs
/// inside the width, the diaphragms inside the length.
fn walls(raw: &RawTailBeam, l: f64, b: f64, h: f64) -> Result<Walls, Invalid> {
    let smallest = h.min(b).min(l);
    let thick = |name: &str, v: f64| -> Result<f64, Invalid> {
        let t = check(&format!("tail_beam.{name}"), v, limits::THICKNESS_MM, "mm")?;
        if t >= smallest {
            return Err(other(
                format!("tail_beam.{name}"),
                format!("{v} mm is not below the box's smallest side, {smallest} mm: the walls are plates"),
            ));
        }
        Ok(t * MM)
    };
    let webs = thick("webs_mm", raw.webs_mm)?;
    let rib = match raw.rib_mm {
        Some(v) if raw.ribs_z_mm.is_empty() => {
            return Err(other(
                "tail_beam.rib_mm",
                format!("= {v} is given but ribs_z_mm is empty: no rib has that thickness"),
            ))
        }
        Some(v) => thick("rib_mm", v)?,
        None if raw.ribs_z_mm.is_empty() => webs,
        None => return Err(other("tail_beam.rib_mm", "is required with ribs_z_mm (the ribs' thickness)")),
    };
    let ribs = positions("ribs_z_mm", &raw.ribs_z_mm, b, "width")?;
    let ends = thick("ends_mm", raw.ends_mm)?;
    let diaphragms = match (raw.diaphragms_x_mm.is_empty(), raw.diaphragm_mm) {
        (true, None) => None,
        (true, Some(v)) => {
            return Err(other(
                "tail_beam.diaphragm_mm",
                format!("= {v} is given but diaphragms_x_mm is empty: no diaphragm has that thickness"),
            ))
        }
        (false, Some(v)) => Some(Diaphragms {
            x: positions("diaphragms_x_mm", &raw.diaphragms_x_mm, l, "length")?,
            thickness: thick("diaphragm_mm", v)?,
        }),
        (false, None) => {
            return Err(other("tail_beam.diaphragm_mm", "is required with diaphragms_x_mm (the diaphragms' thickness)"))
        }
    };
    Ok(Walls {
        top: thick("top_mm", raw.top_mm)?,
        bottom: thick("bottom_mm", raw.bottom_mm)?,
        webs,
        ends,
        rib,
        ribs,
        diaphragms,
    })
}

/// The pins' height on the end plate and their spans across a `b` mm width (m), the end plate
/// `h` mm deep.
fn pins(raw: &RawTailBeam, b: f64, h: f64) -> Result<(f64, Vec<[f64; 2]>), Invalid> {
    let pin_height = raw.pin_height_mm;
    if !(0.0..=h).contains(&pin_height) {
        return Err(other("tail_beam.pin_height_mm", format!("{pin_height} mm is not on the end plate, [0, {h}] mm")));
    }
    if raw.pins_z_mm.is_empty() {
        return Err(other("tail_beam.pins_z_mm", "needs at least one pin span [z0, z1] in mm"));
    }
    let mut pins = Vec::with_capacity(raw.pins_z_mm.len());
    for (i, span) in raw.pins_z_mm.iter().enumerate() {
        let field = format!("tail_beam.pins_z_mm[{i}]");
        let (z0, z1) = pair(&field, span, "[z0, z1]")?;
        if !(z0 >= 0.0 && z1 > z0 && z1 <= b) {
            return Err(other(field, format!("[{z0}, {z1}] mm must satisfy 0 <= z0 < z1 <= {b} mm (the width)")));
        }
        pins.push([z0 * MM, z1 * MM]);
    }
    Ok((pin_height * MM, pins))
}

/// One `[[tail_beam.jacks]]` entry, its pad on the bottom plate of an `l` x `b` mm box.
fn jack(i: usize, j: &RawJack, l: f64, b: f64) -> Result<Jack, Invalid> {
    let field = |k: &str| format!("tail_beam.jacks[{i}].{k}");
    let pad = check(&field("pad_mm"), j.pad_mm, limits::PLATE_SIZE_MM, "mm")?;
    let (x, z, half) = (j.x_mm, j.z_mm, pad / 2.0);
    if !(x - half >= 0.0 && x + half <= l && z - half >= 0.0 && z + half <= b) {
        return Err(other(
            format!("tail_beam.jacks[{i}]"),
            format!("a pad of {pad} mm at (x_mm, z_mm) = ({x}, {z}) does not lie on the bottom plate, [0, {l}] x [0, {b}] mm"),
        ));
    }
    Ok(Jack {
        x: x * MM,
        z: z * MM,
        pad: pad * MM,
        stiffness: check(&field("stiffness_n_per_m"), j.stiffness_n_per_m, limits::SPRING_N_PER_M, "N/m")?,
        angle: check(&field("angle_deg"), j.angle_deg, limits::JACK_ANGLE_DEG, "°")?.to_radians(),
    })
}

/// `tail_beam.points_mm`: at least one [x, z] on the top plate, at most the budget.
fn points(raw: &[Vec<f64>], l: f64, b: f64) -> Result<Vec<(f64, f64)>, Invalid> {
    if raw.is_empty() || raw.len() > limits::MAX_TAIL_BEAM_POINTS {
        return Err(other(
            "tail_beam.points_mm",
            format!("has {} points; give 1 to {} [x, z] pairs", raw.len(), limits::MAX_TAIL_BEAM_POINTS),
        ));
    }
    let mut out = Vec::with_capacity(raw.len());
    for (i, p) in raw.iter().enumerate() {
        let field = format!("tail_beam.points_mm[{i}]");
        let (x, z) = pair(&field, p, "[x, z]")?;
        if !((0.0..=l).contains(&x) && (0.0..=b).contains(&z)) {
            return Err(other(field, format!("[{x}, {z}] mm is not on the top plate, [0, {l}] x [0, {b}] mm")));
        }
        out.push((x * MM, z * MM));
    }
    Ok(out)
}
