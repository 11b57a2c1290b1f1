//! The tail beam of a hydraulic support as a welded box of flat plates, on hinge pins and
//! jacks.
//!
//! x runs along the beam from the hinged end (x = 0) to the free tip (x = L), z across its
//! width (0 to B), y up through its depth (0 at the bottom plate, H at the top plate, the face
//! the caving rock strikes). The walls are the top and bottom plates, two side webs (z = 0 and
//! B), two end plates (x = 0 and L), optional longitudinal ribs (vertical plates at given z
//! along the whole length) and optional diaphragms (transverse plates at given x across the
//! whole section, as box girders are stiffened against distortion), all on their
//! mid-surfaces and welded where they meet: they share the nodes of their common edges.
//!
//! **Supports.** The hinge pins are lines across the width on the hinged end plate, at a given
//! height: every node on them is held in translation and free to rotate (a pin is a line of
//! stated length, so the support has a footprint and the shell's compliance a mesh limit). The
//! jacks are springs to ground along their axis, in the x-y plane at a given angle to x, each
//! acting on a square pad of the bottom plate whose nodes share its stiffness: a pad of
//! stated side, for the same reason.

use super::gmsh::{Cell, Group, MeshFile};
use super::{Face, FaceId, Restraints, Spring, Structure};
use crate::FemError;
use serde::Serialize;

/// A jack: a spring to ground on a square pad of the bottom plate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Jack {
    /// The pad's centre along the beam (m).
    pub x: f64,
    /// The pad's centre across the width (m).
    pub z: f64,
    /// The pad's side (m).
    pub pad: f64,
    /// The jack's axial stiffness (N/m): the oil column and the cylinder in series.
    pub stiffness: f64,
    /// The angle of its axis to the beam's x axis in the x-y plane (rad).
    pub angle: f64,
}

/// The box: dimensions, wall thicknesses, ribs, pins and jacks, all in SI units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TailBeam {
    /// Length L along x (m).
    pub length: f64,
    /// Width B along z (m).
    pub width: f64,
    /// Depth H along y between the top and bottom plates' mid-surfaces (m).
    pub height: f64,
    /// Top plate thickness (m): the struck plate.
    pub top: f64,
    /// Bottom plate thickness (m).
    pub bottom: f64,
    /// Side webs' thickness (m).
    pub webs: f64,
    /// End plates' thickness (m).
    pub ends: f64,
    /// Longitudinal ribs' positions across the width (m), strictly inside (0, B).
    pub ribs: Vec<f64>,
    /// Ribs' thickness (m).
    pub rib: f64,
    /// Transverse diaphragms, if any (left out of the serialised box without them, so that a
    /// box without keeps its provenance hash).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub diaphragms: Option<Diaphragms>,
    /// The pins' height on the hinged end plate (m), in [0, H].
    pub pin_height: f64,
    /// The pins' spans across the width, [z0, z1] (m), each of positive length.
    pub pins: Vec<[f64; 2]>,
    /// The jacks.
    pub jacks: Vec<Jack>,
}

/// Transverse diaphragms: plates across the whole section (top to bottom, web to web).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Diaphragms {
    /// Their positions along the length (m), strictly inside (0, L).
    pub x: Vec<f64>,
    /// Their thickness (m).
    pub thickness: f64,
}

/// A tail beam meshed and restrained.
pub struct Built {
    /// The structure.
    pub structure: Structure,
    /// The top plate (the struck face; its face coordinates are (z, x)).
    pub top: FaceId,
    /// The pins and jacks.
    pub restraints: Restraints,
    /// Each jack's springs in `restraints.springs`, in the order of [`TailBeam::jacks`].
    pub jacks: Vec<std::ops::Range<usize>>,
}

impl Built {
    /// Each jack's springs, in the order of [`TailBeam::jacks`]: the groups whose forces are
    /// the jacks'.
    pub fn jack_groups(&self) -> Vec<Vec<Spring>> {
        self.jacks.iter().map(|r| self.restraints.springs[r.clone()].to_vec()).collect()
    }
}

impl TailBeam {
    /// Checks what the builder needs: positive sizes, ribs, pins and pads on the box, a jack
    /// that holds the rotation about the pins.
    pub fn validate(&self) -> Result<(), FemError> {
        let positive = [
            ("tail beam length", self.length),
            ("tail beam width", self.width),
            ("tail beam height", self.height),
            ("top plate thickness", self.top),
            ("bottom plate thickness", self.bottom),
            ("web thickness", self.webs),
            ("end plate thickness", self.ends),
            ("rib thickness", self.rib),
        ];
        for (name, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(FemError::Property { name, value, allowed: "(0, inf) m" });
            }
        }
        let inside = |v: f64, hi: f64| v.is_finite() && v > 0.0 && v < hi;
        if let Some(&z) = self.ribs.iter().find(|&&z| !inside(z, self.width)) {
            return Err(FemError::Property { name: "rib position", value: z, allowed: "(0, B) m" });
        }
        // Walls closer than their thickness would overlap (and coincident ribs would double).
        let mut walls: Vec<f64> = [0.0, self.width].into_iter().chain(self.ribs.iter().copied()).collect();
        walls.sort_by(f64::total_cmp);
        let gap = self.rib.max(self.webs);
        if let Some(w) = walls.windows(2).find(|w| w[1] - w[0] < gap) {
            return Err(FemError::Support(format!(
                "walls at z = {} m and {} m are closer than their thickness, {gap} m: ribs must stand apart from each other and from the webs",
                w[0], w[1]
            )));
        }
        self.validate_diaphragms()?;
        if !(self.pin_height >= 0.0 && self.pin_height <= self.height) {
            return Err(FemError::Property { name: "pin height", value: self.pin_height, allowed: "[0, H] m" });
        }
        if self.pins.is_empty() || self.jacks.is_empty() {
            return Err(FemError::Support("a tail beam needs at least one pin span and one jack".into()));
        }
        for &[z0, z1] in &self.pins {
            if !(z0 >= 0.0 && z1 > z0 && z1 <= self.width) {
                return Err(FemError::Support(format!("pin span [{z0}, {z1}] m must satisfy 0 <= z0 < z1 <= B")));
            }
        }
        for j in &self.jacks {
            let h = j.pad / 2.0;
            let on = j.x - h >= 0.0 && j.x + h <= self.length && j.z - h >= 0.0 && j.z + h <= self.width;
            if !(j.pad > 0.0 && on) {
                return Err(FemError::Support(format!(
                    "jack pad of side {} m at ({}, {}) m must lie on the bottom plate",
                    j.pad, j.x, j.z
                )));
            }
            if !(j.stiffness.is_finite() && j.stiffness > 0.0) {
                return Err(FemError::Property { name: "jack stiffness", value: j.stiffness, allowed: "(0, inf) N/m" });
            }
            // The pins leave the rotation about their line free; a jack holds it unless its
            // axis passes through the pin line.
            let arm = self.pin_height * j.angle.cos() + j.x * j.angle.sin();
            if !(j.angle.is_finite() && arm.abs() > 1e-6 * self.length) {
                return Err(FemError::Support(format!(
                    "the jack at x = {} m with angle {} rad points at the pins and holds nothing",
                    j.x, j.angle
                )));
            }
        }
        Ok(())
    }

    /// Each diaphragm's position along the length and thickness (m).
    pub fn diaphragm_walls(&self) -> Vec<(f64, f64)> {
        self.diaphragms.iter().flat_map(|d| d.x.iter().map(move |&x| (x, d.thickness))).collect()
    }

    /// The diaphragms: positive thickness, inside the length, apart from each other and from
    /// the end plates by more than the thicker wall (else they would overlap or double).
    fn validate_diaphragms(&self) -> Result<(), FemError> {
        let Some(d) = &self.diaphragms else { return Ok(()) };
        if !(d.thickness.is_finite() && d.thickness > 0.0) {
            return Err(FemError::Property { name: "diaphragm thickness", value: d.thickness, allowed: "(0, inf) m" });
        }
        if let Some(&x) = d.x.iter().find(|&&x| !(x.is_finite() && x > 0.0 && x < self.length)) {
            return Err(FemError::Property { name: "diaphragm position", value: x, allowed: "(0, L) m" });
        }
        let mut across: Vec<f64> = [0.0, self.length].into_iter().chain(d.x.iter().copied()).collect();
        across.sort_by(f64::total_cmp);
        let gap = d.thickness.max(self.ends);
        if let Some(w) = across.windows(2).find(|w| w[1] - w[0] < gap) {
            return Err(FemError::Support(format!(
                "walls at x = {} m and {} m are closer than their thickness, {gap} m: diaphragms must stand apart from each other and from the end plates",
                w[0], w[1]
            )));
        }
        Ok(())
    }

    /// Mass of the walls (kg) for steel of density `rho`: mid-surface areas times thickness.
    pub fn mass(&self, rho: f64) -> f64 {
        let (l, b, h) = (self.length, self.width, self.height);
        rho * (l * b * (self.top + self.bottom)
            + 2.0 * l * h * self.webs
            + 2.0 * b * h * self.ends
            + self.ribs.len() as f64 * l * h * self.rib
            + self.diaphragm_walls().iter().map(|(_, t)| b * h * t).sum::<f64>())
    }

    /// The grid lines along x, y and z for elements of at most `element` (m, positive), refined
    /// by 2^level (level at most [`MAX_LEVEL`]): every breakpoint (pin height and spans, ribs,
    /// diaphragms, jack pads) on a line.
    pub fn lines(&self, element: f64, level: u32) -> Result<[Vec<f64>; 3], FemError> {
        let longest = self.length.max(self.width).max(self.height);
        // Lines per direction before allocating them: at most a million.
        let per_side = longest / element * f64::from(1u32 << level.min(MAX_LEVEL));
        if !(element.is_finite() && element > 0.0 && per_side <= 1e6) || level > MAX_LEVEL {
            return Err(FemError::Mesh(format!(
                "element {element} m at level {level}: the element must be positive, the level at most {MAX_LEVEL}, and the finest mesh at most a million lines along the box's longest side"
            )));
        }
        let mut bx = vec![0.0, self.length];
        bx.extend(self.diaphragm_walls().iter().map(|w| w.0));
        let by = vec![0.0, self.height, self.pin_height];
        let mut bz = vec![0.0, self.width];
        bz.extend(self.ribs.iter().copied());
        bz.extend(self.pins.iter().flatten().copied());
        for j in &self.jacks {
            bx.extend([j.x - j.pad / 2.0, j.x + j.pad / 2.0]);
            bz.extend([j.z - j.pad / 2.0, j.z + j.pad / 2.0]);
        }
        Ok([bx, by, bz].map(|b| subdivide(b, element, level)))
    }

    /// Nodes of the mesh of [`Self::lines`] (an upper bound: walls counted apart).
    pub fn nodes_bound(&self, element: f64, level: u32) -> Result<usize, FemError> {
        let [x, y, z] = self.lines(element, level)?.map(|l| l.len());
        Ok(2 * x * z + (2 + self.ribs.len()) * x * y + (2 + self.diaphragm_walls().len()) * y * z)
    }

    /// Meshes and restrains the box with Young's modulus `e` and Poisson ratio `nu`.
    pub fn build(&self, e: f64, nu: f64, element: f64, level: u32) -> Result<Built, FemError> {
        self.validate()?;
        let [xs, ys, zs] = self.lines(element, level)?;
        let (l, b, h) = (self.length, self.width, self.height);
        let (ex, ey, ez) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        let mut s = Structure::new(e, nu)?;
        // The top plate's axes (z, x) make its normal e₁ x e₂ = +y, outward, so that a patch
        // presses it down.
        let top = s.add_face(&Face::new([0.0, h, 0.0], ez, ex, zs.clone(), xs.clone(), self.top)?)?;
        s.add_face(&Face::new([0.0; 3], ex, ez, xs.clone(), zs.clone(), self.bottom)?)?;
        for (z, t) in [(0.0, self.webs), (b, self.webs)].into_iter().chain(self.ribs.iter().map(|&z| (z, self.rib))) {
            s.add_face(&Face::new([0.0, 0.0, z], ex, ey, xs.clone(), ys.clone(), t)?)?;
        }
        let ends = [(0.0, self.ends), (l, self.ends)].into_iter();
        for (x, t) in ends.chain(self.diaphragm_walls()) {
            s.add_face(&Face::new([x, 0.0, 0.0], ey, ez, ys.clone(), zs.clone(), t)?)?;
        }
        let tol = 1e-9 * l.max(b).max(h);
        let mut restraints = Restraints::default();
        let mut jacks = Vec::with_capacity(self.jacks.len());
        for &[z0, z1] in &self.pins {
            let on = |p: [f64; 3]| {
                p[0].abs() < tol && (p[1] - self.pin_height).abs() < tol && p[2] > z0 - tol && p[2] < z1 + tol
            };
            for node in s.nodes_where(on) {
                restraints.hold(node, &[0, 1, 2]);
            }
        }
        for j in &self.jacks {
            let half = j.pad / 2.0 + tol;
            let on = |p: [f64; 3]| p[1].abs() < tol && (p[0] - j.x).abs() < half && (p[2] - j.z).abs() < half;
            let pad = s.nodes_where(on);
            let direction = [j.angle.cos(), j.angle.sin(), 0.0];
            let share = j.stiffness / pad.len().max(1) as f64;
            let first = restraints.springs.len();
            restraints.springs.extend(pad.into_iter().map(|node| Spring { node, direction, stiffness: share }));
            jacks.push(first..restraints.springs.len());
        }
        Ok(Built { structure: s, top, restraints, jacks })
    }
}

impl TailBeam {
    /// The box as a shell mesh with named groups, for a mesher or [`super::gmsh`]: the walls'
    /// quadrilaterals in the surface groups "top", "bottom", "webs", "ribs" (if any), "ends"
    /// and "diaphragms" (if any); the pins as the curve group "pins" (lines along each pin's span); each jack's
    /// pad as the surface group "jack 1", "jack 2", ... (the bottom plate's quadrilaterals
    /// under it, taken out of "bottom": MSH 2.2 gives an element one group, so a converter
    /// keeps the pads only if no quadrilateral is in two). The mesh of [`Self::build`] at
    /// `element` and `level`; every refinement of it holds and springs the nodes the builder's
    /// finer meshes do.
    pub fn mesh_file(&self, element: f64, level: u32) -> Result<MeshFile, FemError> {
        let built = self.build(1.0, 0.0, element, level)?;
        let s = &built.structure;
        let named = ["top", "bottom", "webs", "ribs", "ends", "diaphragms"];
        let present = |name: &&str| match *name {
            "ribs" => !self.ribs.is_empty(),
            "diaphragms" => !self.diaphragm_walls().is_empty(),
            _ => true,
        };
        // Tags by place in the list, whether or not every wall is there.
        let mut groups: Vec<Group> = (named.iter().zip(1..))
            .filter(|(name, _)| present(name))
            .map(|(name, tag)| Group { dim: 2, tag, name: name.to_string() })
            .collect();
        // The faces in the builder's order: top, bottom, the webs, the ribs, the ends, the
        // diaphragms.
        let walls = 4 + self.ribs.len();
        let group_of_face = |k: usize| match k {
            0 => "top",
            1 => "bottom",
            2 | 3 => "webs",
            k if k < walls => "ribs",
            k if k < walls + 2 => "ends",
            _ => "diaphragms",
        };
        let mut quads = Vec::new();
        for (k, (_, elements)) in s.faces().enumerate() {
            let g = groups.iter().position(|g| g.name == group_of_face(k)).unwrap_or(0);
            for &e in elements {
                let [a, b, c, d] = s.element_nodes(e);
                quads.push(Cell { nodes: [a, b, d, c], groups: vec![g], tag: 0 });
            }
        }
        // The pins as lines along their span and each pad as the bottom plate's
        // quadrilaterals under it, so that a refined mesh holds and springs every node the
        // builder's finer meshes do.
        groups.push(Group { dim: 1, tag: groups.len() as i64 + 1, name: "pins".into() });
        let pins_group = groups.len() - 1;
        let mut held: Vec<usize> = built.restraints.held.iter().map(|&(n, _)| n).collect();
        held.dedup();
        let mut lines = Vec::new();
        for &[z0, z1] in &self.pins {
            let tol = 1e-9 * self.width;
            let mut on: Vec<usize> =
                held.iter().copied().filter(|&n| (z0 - tol..=z1 + tol).contains(&s.nodes()[n].z)).collect();
            on.sort_by(|a, b| s.nodes()[*a].z.total_cmp(&s.nodes()[*b].z));
            lines.extend(on.windows(2).map(|w| Cell { nodes: [w[0], w[1]], groups: vec![pins_group], tag: 0 }));
        }
        for (j, range) in built.jacks.iter().enumerate() {
            groups.push(Group { dim: 2, tag: groups.len() as i64 + 1, name: format!("jack {}", j + 1) });
            let g = groups.len() - 1;
            let pad: Vec<usize> = built.restraints.springs[range.clone()].iter().map(|sp| sp.node).collect();
            for q in quads.iter_mut().filter(|q| q.nodes.iter().all(|n| pad.contains(n))) {
                q.groups = vec![g];
            }
        }
        Ok(MeshFile { nodes: s.nodes().to_vec(), quads, lines, points: Vec::new(), groups })
    }
}

/// The finest refinement of [`TailBeam::lines`]: 2^10 times the coarsest mesh.
pub const MAX_LEVEL: u32 = 10;

/// Breakpoints closer than this (m) are one line: a micrometre, far below any wall's thickness
/// and far above the nodes' merging distance.
const SAME_LINE: f64 = 1e-6;

/// Sorted, deduplicated breakpoints, each interval cut into 2^level · ⌈length/element⌉ equal
/// parts, so that the levels' meshes nest.
fn subdivide(mut breaks: Vec<f64>, element: f64, level: u32) -> Vec<f64> {
    breaks.sort_by(f64::total_cmp);
    breaks.dedup_by(|a, b| (*a - *b).abs() < SAME_LINE);
    let mut lines = vec![breaks[0]];
    for w in breaks.windows(2) {
        // Less a rounding allowance: an interval of exactly k elements stays k.
        let n = ((w[1] - w[0]) / element - 1e-9).ceil().max(1.0) as usize * (1 << level);
        lines.extend((1..=n).map(|i| if i == n { w[1] } else { w[0] + (w[1] - w[0]) * i as f64 / n as f64 }));
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(crate) fn example() -> TailBeam {
        TailBeam {
            length: 1.6,
            width: 1.4,
            height: 0.25,
            top: 0.03,
            bottom: 0.02,
            webs: 0.02,
            ends: 0.02,
            ribs: vec![0.7],
            rib: 0.016,
            diaphragms: None,
            pin_height: 0.125,
            pins: vec![[0.0, 0.2], [1.2, 1.4]],
            jacks: vec![Jack { x: 0.6, z: 0.7, pad: 0.1, stiffness: 3e7, angle: 1.0 }],
        }
    }

    /// The lines nest: each level doubles every interval and keeps every breakpoint.
    #[test]
    fn lines_nest_and_keep_the_breakpoints() {
        let t = example();
        let [x0, y0, z0] = t.lines(0.1, 0).unwrap();
        let [x1, y1, z1] = t.lines(0.1, 1).unwrap();
        for (coarse, fine) in [(&x0, &x1), (&y0, &y1), (&z0, &z1)] {
            assert_eq!(fine.len() - 1, 2 * (coarse.len() - 1));
            assert!(coarse.iter().all(|c| fine.iter().any(|f| (f - c).abs() < 1e-12)));
        }
        for v in [0.55, 0.65] {
            assert!(x0.iter().any(|x| (x - v).abs() < 1e-12), "jack pad edge {v}");
        }
        assert!(y0.iter().any(|y| (y - 0.125).abs() < 1e-12));
    }

    /// A jack whose axis passes through the pins is refused, as is a pad off the plate.
    #[test]
    fn a_jack_that_holds_nothing_is_refused() {
        let mut t = example();
        t.pin_height = 0.0;
        t.jacks[0].angle = 0.0;
        assert!(t.validate().is_err());
        let mut t = example();
        t.jacks[0].x = 1.58;
        assert!(t.validate().is_err());
        assert!(example().validate().is_ok());
        let mut t = example();
        t.ribs = vec![0.7, 0.7];
        assert!(t.validate().is_err(), "coincident ribs");
        assert!(example().lines(0.0, 0).is_err() && example().lines(0.1, MAX_LEVEL + 1).is_err());
    }
}
