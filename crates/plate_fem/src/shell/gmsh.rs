//! Shell meshes from Gmsh's MSH files: format 4.1 or 2.2, ASCII.
//!
//! MSH is the format Gmsh writes and meshio reads and writes (`meshio convert mesh.vtu
//! mesh.msh --output-format gmsh22` turns any format meshio knows into one read here), and the
//! one that carries named groups: Gmsh's physical groups, `$PhysicalNames`, name the surfaces
//! that get a thickness, the curves and points that are held, sprung or instrumented, and the
//! struck face. What is read:
//!
//! - `$MeshFormat`: version 4.1 or 2.2, file type 0 (ASCII; a binary file is refused with how
//!   to write ASCII);
//! - `$PhysicalNames` (dimension, tag, name); a physical tag without a name is named by its
//!   number;
//! - `$Entities` (4.1: the physical tags of each geometric entity, which its elements carry);
//! - `$Nodes` and `$Elements`: 4-node quadrilaterals (type 3), 2-node lines (type 1) and points
//!   (type 15). Triangles, second-order and volume elements are refused, each with the Gmsh
//!   option that avoids it. Every other section is skipped.
//!
//! Coordinates are multiplied by the file's unit (m per mesh unit) once, here. A quadrilateral
//! keeps its corners in the order written, around its boundary (Gmsh writes them
//! counter-clockwise about the surface's normal). [`MeshFile::refined`] splits every
//! quadrilateral into four at its edges' midpoints and its centre (and every line into two),
//! which for flat quadrilaterals is the same geometry on a finer mesh: the ladder of a
//! convergence study on a mesh the user made.

use super::Structure;
use crate::FemError;
use nalgebra::Vector3;
use std::collections::HashMap;

/// A physical group: its dimension (0 points, 1 curves, 2 surfaces), Gmsh tag and name.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Group {
    /// 0, 1 or 2.
    pub dim: u8,
    /// Gmsh's physical tag.
    pub tag: i64,
    /// Its name (its tag as text where the file names none).
    pub name: String,
}

/// A cell of `N` nodes: node indices into [`MeshFile::nodes`], its groups (indices into
/// [`MeshFile::groups`]) and its tag in the file (for messages).
#[derive(Debug, Clone, PartialEq)]
pub struct Cell<const N: usize> {
    /// Its nodes.
    pub nodes: [usize; N],
    /// The groups it belongs to.
    pub groups: Vec<usize>,
    /// Its element tag in the file (0 for cells made by refinement).
    pub tag: u64,
}

/// A shell mesh read from an MSH file: nodes (m), quadrilaterals, lines, points and groups.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshFile {
    /// Node positions (m).
    pub nodes: Vec<Vector3<f64>>,
    /// Quadrilaterals, corners around the boundary.
    pub quads: Vec<Cell<4>>,
    /// Lines.
    pub lines: Vec<Cell<2>>,
    /// Points.
    pub points: Vec<Cell<1>>,
    /// Physical groups.
    pub groups: Vec<Group>,
}

/// Whitespace-separated tokens of a section, with their line numbers, read as they are asked
/// for (nothing is collected, so a file's declared counts are checked before its size in
/// tokens costs memory).
struct Tokens<'s, 'a> {
    origin: &'a str,
    lines: std::slice::Iter<'s, (usize, &'a str)>,
    current: Option<(usize, std::str::SplitWhitespace<'a>)>,
    last: usize,
}

impl<'s, 'a> Tokens<'s, 'a> {
    fn new(origin: &'a str, lines: &'s [(usize, &'a str)], end: usize) -> Self {
        Self { origin, lines: lines.iter(), current: None, last: end }
    }

    /// The next token and its line.
    fn token(&mut self) -> Option<(usize, &'a str)> {
        loop {
            if let Some((n, words)) = &mut self.current {
                if let Some(t) = words.next() {
                    return Some((*n, t));
                }
            }
            let &(n, line) = self.lines.next()?;
            self.current = Some((n, line.split_whitespace()));
        }
    }

    fn error(&self, line: usize, message: String) -> FemError {
        FemError::MeshFile { origin: self.origin.to_string(), line, message }
    }

    /// The next token parsed as `T`, or an error naming `what`.
    fn next<T: std::str::FromStr>(&mut self, what: &str) -> Result<T, FemError> {
        match self.token() {
            Some((line, t)) => {
                self.last = line;
                t.parse().map_err(|_| self.error(line, format!("expected {what}, found '{t}'")))
            }
            None => Err(self.error(self.last, format!("the section ends where {what} was expected"))),
        }
    }

    /// A count, refused above `limit` (a budget checked before anything is allocated).
    fn count(&mut self, what: &str, limit: usize) -> Result<usize, FemError> {
        let n: usize = self.next(what)?;
        if n > limit {
            return Err(self.error(self.last, format!("{what} = {n} is above the limit of {limit}")));
        }
        Ok(n)
    }
}

/// The most entries of any kind a file may declare: 2e7 (a shell mesh of that size would
/// need far more memory than a factorization on this kind of machine has).
pub const MAX_ENTRIES: usize = 20_000_000;

/// The most nodes and elements a file may declare, checked on the section headers before
/// anything is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Budget {
    /// Nodes.
    pub nodes: usize,
    /// Elements of every kind together.
    pub elements: usize,
}

impl Default for Budget {
    /// [`MAX_ENTRIES`] of each.
    fn default() -> Self {
        Self { nodes: MAX_ENTRIES, elements: MAX_ENTRIES }
    }
}

/// Nodes of the element types Gmsh writes, by type number, with why a shell cannot take
/// those it refuses.
fn element_type(kind: u32) -> Result<(usize, Option<&'static str>), String> {
    Ok(match kind {
        1 => (2, None),
        3 => (4, None),
        15 => (1, None),
        2 => (3, Some("triangles are not read: recombine the surfaces into quadrilaterals (Gmsh: Mesh.RecombineAll = 1)")),
        8 | 9 | 10 | 16 => (
            [3, 6, 9, 8][[8, 9, 10, 16].iter().position(|&k| k == kind).unwrap_or(0)],
            Some("second-order elements are not read: mesh at first order (Gmsh: Mesh.ElementOrder = 1)"),
        ),
        4..=7 => (
            [4, 8, 6, 5][(kind - 4) as usize],
            Some("volume elements are not read: a shell mesh is of surfaces (save only the physical surfaces, curves and points)"),
        ),
        other => return Err(format!("element type {other} is not one of 1 (line), 3 (quadrilateral) and 15 (point)")),
    })
}

/// A section: its name, the line of its header, and its lines (number, text).
type Section<'a> = (&'a str, usize, Vec<(usize, &'a str)>);
/// The file's sections.
type Sections<'a> = Vec<Section<'a>>;
/// A cell as read: its nodes, its physical tags as (dimension, tag), its element tag.
type Tagged<const N: usize> = ([usize; N], Vec<(u8, i64)>, u64);

fn sections<'a>(text: &'a str, origin: &str) -> Result<Sections<'a>, FemError> {
    let mut out: Sections = Vec::new();
    let mut open: Option<Section> = None;
    for (i, raw) in text.lines().enumerate() {
        let (n, line) = (i + 1, raw.trim());
        match (&mut open, line.strip_prefix('$')) {
            (Some((name, _, _)), Some(tag)) if tag.strip_prefix("End") == Some(*name) => {
                out.push(open.take().unwrap_or_default());
            }
            (Some((name, _, _)), Some(_)) => {
                return Err(FemError::MeshFile {
                    origin: origin.into(),
                    line: n,
                    message: format!("'{line}' inside ${name}, which is not closed by $End{name}"),
                })
            }
            (Some((_, _, lines)), None) => lines.push((n, line)),
            (None, Some(tag)) => open = Some((tag, n, Vec::new())),
            (None, None) if line.is_empty() => {}
            (None, None) => {
                return Err(FemError::MeshFile {
                    origin: origin.into(),
                    line: n,
                    message: format!("'{line}' outside any $Section: not an MSH file"),
                })
            }
        }
    }
    if let Some((name, line, _)) = open {
        return Err(FemError::MeshFile { origin: origin.into(), line, message: format!("${name} is never closed") });
    }
    Ok(out)
}

/// What the element sections hand over: quads, lines and points with their physical tags.
#[derive(Default)]
struct Raw {
    nodes: Vec<Vector3<f64>>,
    index: HashMap<u64, usize>,
    quads: Vec<Tagged<4>>,
    lines: Vec<Tagged<2>>,
    points: Vec<Tagged<1>>,
}

impl Raw {
    fn add_node(&mut self, t: &Tokens<'_, '_>, tag: u64, p: Vector3<f64>) -> Result<(), FemError> {
        if !(p.x.is_finite() && p.y.is_finite() && p.z.is_finite()) {
            return Err(t.error(t.last, format!("node {tag} at {p:?} is not finite")));
        }
        if self.index.insert(tag, self.nodes.len()).is_some() {
            return Err(t.error(t.last, format!("node {tag} is defined twice")));
        }
        self.nodes.push(p);
        Ok(())
    }

    /// One element of type `kind` with node tags `tags` and physical tags `physical`.
    fn add_element(
        &mut self,
        t: &Tokens<'_, '_>,
        id: u64,
        kind: u32,
        tags: &[u64],
        physical: Vec<(u8, i64)>,
    ) -> Result<(), FemError> {
        let (_, refused) = element_type(kind).map_err(|m| t.error(t.last, m))?;
        if let Some(why) = refused {
            return Err(t.error(t.last, format!("element {id}: {why}")));
        }
        let mut nodes = Vec::with_capacity(tags.len());
        for tag in tags {
            let at = self.index.get(tag).ok_or_else(|| {
                t.error(t.last, format!("element {id} names node {tag}, which $Nodes does not define"))
            })?;
            nodes.push(*at);
        }
        match nodes.len() {
            4 => self.quads.push(([nodes[0], nodes[1], nodes[2], nodes[3]], physical, id)),
            2 => self.lines.push(([nodes[0], nodes[1]], physical, id)),
            _ => self.points.push(([nodes[0]], physical, id)),
        }
        Ok(())
    }
}

/// The dimension of an element type's cells.
fn dimension(kind: u32) -> u8 {
    match kind {
        15 => 0,
        1 | 8 => 1,
        _ => 2,
    }
}

/// `$PhysicalNames`: one group per line, `dim tag "name"`.
fn physical_names(origin: &str, lines: &[(usize, &str)]) -> Result<Vec<Group>, FemError> {
    let error = |line: usize, message: String| FemError::MeshFile { origin: origin.into(), line, message };
    let mut groups = Vec::new();
    for &(n, line) in lines.iter().skip(1) {
        let mut parts = line.splitn(3, char::is_whitespace);
        let dim = parts.next().and_then(|d| d.parse::<u8>().ok());
        let tag = parts.next().and_then(|d| d.parse::<i64>().ok());
        let name = parts.next().map(|s| s.trim().trim_matches('"').to_string());
        match (dim, tag, name) {
            (Some(dim), Some(tag), Some(name)) if dim <= 3 && !name.is_empty() => groups.push(Group { dim, tag, name }),
            _ => return Err(error(n, format!("expected 'dimension tag \"name\"', found '{line}'"))),
        }
    }
    Ok(groups)
}

/// 4.1's `$Entities`: the physical tags of every (dimension, entity tag).
fn entities(t: &mut Tokens<'_, '_>) -> Result<HashMap<(u8, i64), Vec<i64>>, FemError> {
    let counts: [usize; 4] = [
        t.count("points", MAX_ENTRIES)?,
        t.count("curves", MAX_ENTRIES)?,
        t.count("surfaces", MAX_ENTRIES)?,
        t.count("volumes", MAX_ENTRIES)?,
    ];
    let mut out = HashMap::new();
    for (dim, &count) in counts.iter().enumerate() {
        for _ in 0..count {
            let tag: i64 = t.next("an entity tag")?;
            for _ in 0..if dim == 0 { 3 } else { 6 } {
                t.next::<f64>("a coordinate of the entity's box")?;
            }
            let n = t.count("its number of physical tags", MAX_ENTRIES)?;
            let physical = (0..n).map(|_| t.next::<i64>("a physical tag")).collect::<Result<Vec<_>, _>>()?;
            if dim > 0 {
                let bounding = t.count("its number of bounding entities", MAX_ENTRIES)?;
                for _ in 0..bounding {
                    t.next::<i64>("a bounding entity")?;
                }
            }
            out.insert((dim as u8, tag), physical);
        }
    }
    Ok(out)
}

/// 4.1's `$Nodes`.
fn nodes_41(t: &mut Tokens<'_, '_>, raw: &mut Raw, budget: Budget) -> Result<(), FemError> {
    let blocks = t.count("the number of node blocks", MAX_ENTRIES)?;
    let total = t.count("the number of nodes", budget.nodes)?;
    t.next::<u64>("the least node tag")?;
    t.next::<u64>("the greatest node tag")?;
    raw.nodes.reserve(total);
    for _ in 0..blocks {
        let dim: usize = t.next("the block's entity dimension")?;
        t.next::<i64>("the block's entity tag")?;
        let parametric: u8 = t.next("0 or 1 (parametric)")?;
        let n = t.count("the block's number of nodes", total)?;
        let tags = (0..n).map(|_| t.next::<u64>("a node tag")).collect::<Result<Vec<_>, _>>()?;
        for tag in tags {
            let p = Vector3::new(t.next("x")?, t.next("y")?, t.next("z")?);
            for _ in 0..if parametric == 1 { dim } else { 0 } {
                t.next::<f64>("a parametric coordinate")?;
            }
            raw.add_node(t, tag, p)?;
        }
    }
    Ok(())
}

/// 4.1's `$Elements`, each carrying its entity's physical tags.
fn elements_41(
    t: &mut Tokens<'_, '_>,
    raw: &mut Raw,
    entities: &HashMap<(u8, i64), Vec<i64>>,
    budget: Budget,
) -> Result<(), FemError> {
    let blocks = t.count("the number of element blocks", MAX_ENTRIES)?;
    let total = t.count("the number of elements", budget.elements)?;
    t.next::<u64>("the least element tag")?;
    t.next::<u64>("the greatest element tag")?;
    for _ in 0..blocks {
        let dim: u8 = t.next("the block's entity dimension")?;
        let entity: i64 = t.next("the block's entity tag")?;
        let kind: u32 = t.next("the block's element type")?;
        let n = t.count("the block's number of elements", total)?;
        let (per, _) = element_type(kind).map_err(|m| t.error(t.last, m))?;
        let physical: Vec<(u8, i64)> =
            entities.get(&(dim, entity)).map_or(Vec::new(), |p| p.iter().map(|&g| (dim, g)).collect());
        for _ in 0..n {
            let id: u64 = t.next("an element tag")?;
            let tags = (0..per).map(|_| t.next::<u64>("a node tag")).collect::<Result<Vec<_>, _>>()?;
            raw.add_element(t, id, kind, &tags, physical.clone())?;
        }
    }
    Ok(())
}

/// 2.2's `$Nodes`.
fn nodes_22(t: &mut Tokens<'_, '_>, raw: &mut Raw, budget: Budget) -> Result<(), FemError> {
    let n = t.count("the number of nodes", budget.nodes)?;
    raw.nodes.reserve(n);
    for _ in 0..n {
        let tag: u64 = t.next("a node tag")?;
        let p = Vector3::new(t.next("x")?, t.next("y")?, t.next("z")?);
        raw.add_node(t, tag, p)?;
    }
    Ok(())
}

/// 2.2's `$Elements`: the first of an element's tags is its physical group (0: none).
fn elements_22(t: &mut Tokens<'_, '_>, raw: &mut Raw, budget: Budget) -> Result<(), FemError> {
    let n = t.count("the number of elements", budget.elements)?;
    for _ in 0..n {
        let id: u64 = t.next("an element tag")?;
        let kind: u32 = t.next("an element type")?;
        let (per, _) = element_type(kind).map_err(|m| t.error(t.last, m))?;
        let count = t.count("the element's number of tags", 64)?;
        let tags = (0..count).map(|_| t.next::<i64>("a tag")).collect::<Result<Vec<_>, _>>()?;
        let nodes = (0..per).map(|_| t.next::<u64>("a node tag")).collect::<Result<Vec<_>, _>>()?;
        let physical = tags.first().filter(|&&g| g != 0).map_or(Vec::new(), |&g| vec![(dimension(kind), g)]);
        raw.add_element(t, id, kind, &nodes, physical)?;
    }
    Ok(())
}

/// Cells with their physical tags as group indices (`group_of`).
fn cells<const N: usize>(list: Vec<Tagged<N>>, group_of: &mut impl FnMut((u8, i64)) -> usize) -> Vec<Cell<N>> {
    list.into_iter()
        .map(|(nodes, physical, tag)| Cell { nodes, groups: physical.into_iter().map(&mut *group_of).collect(), tag })
        .collect()
}

impl MeshFile {
    /// Reads the MSH `text` (its file name `origin`, for messages) with coordinates in units of
    /// `unit` metres (1e-3 for a mesh in millimetres).
    pub fn parse(text: &str, origin: &str, unit: f64) -> Result<Self, FemError> {
        Self::parse_within(text, origin, unit, Budget::default())
    }

    /// [`Self::parse`] refusing a file that declares more nodes or elements than `budget`.
    pub fn parse_within(text: &str, origin: &str, unit: f64, budget: Budget) -> Result<Self, FemError> {
        let error = |line: usize, message: String| FemError::MeshFile { origin: origin.into(), line, message };
        if !(unit.is_finite() && unit > 0.0) {
            return Err(error(0, format!("the mesh unit {unit} m is not positive and finite")));
        }
        let sections = sections(text, origin)?;
        let find = |name: &str| sections.iter().find(|(n, _, _)| *n == name);
        let tokens = |name: &str| find(name).map(|(_, line, lines)| Tokens::new(origin, lines, *line));
        let mut format = tokens("MeshFormat").ok_or_else(|| error(0, "no $MeshFormat: not an MSH file".into()))?;
        let version: String = format.next("the format version")?;
        let binary: u8 = format.next("the file type")?;
        if binary != 0 {
            return Err(error(
                format.last,
                "a binary MSH file: save it as ASCII (Gmsh: Mesh.Binary = 0; meshio: binary=False)".into(),
            ));
        }
        let v41 = match version.as_str() {
            "4.1" => true,
            "2.2" => false,
            other => {
                return Err(error(
                    format.last,
                    format!("MSH version {other}: versions 4.1 and 2.2 are read (Gmsh: Mesh.MshFileVersion)"),
                ))
            }
        };
        let mut raw = Raw::default();
        let mut nodes = tokens("Nodes").ok_or_else(|| error(0, "no $Nodes".into()))?;
        let mut elements = tokens("Elements").ok_or_else(|| error(0, "no $Elements".into()))?;
        if v41 {
            let entities = match tokens("Entities") {
                Some(mut t) => entities(&mut t)?,
                None => HashMap::new(),
            };
            nodes_41(&mut nodes, &mut raw, budget)?;
            elements_41(&mut elements, &mut raw, &entities, budget)?;
        } else {
            nodes_22(&mut nodes, &mut raw, budget)?;
            elements_22(&mut elements, &mut raw, budget)?;
        }
        let mut groups = match find("PhysicalNames") {
            Some((_, _, lines)) => physical_names(origin, lines)?,
            None => Vec::new(),
        };
        if let Some((a, b)) = groups
            .iter()
            .enumerate()
            .find_map(|(i, g)| groups[i + 1..].iter().find(|h| h.name == g.name).map(|h| (g.clone(), h.clone())))
        {
            return Err(error(
                0,
                format!(
                    "$PhysicalNames names two groups '{}' (dimensions {} and {}): names must be unique",
                    a.name, a.dim, b.dim
                ),
            ));
        }
        let mut group_of = |(dim, tag): (u8, i64)| -> usize {
            if let Some(i) = groups.iter().position(|g| g.dim == dim && g.tag == tag) {
                return i;
            }
            groups.push(Group { dim, tag, name: tag.to_string() });
            groups.len() - 1
        };
        let quads = cells(raw.quads, &mut group_of);
        let lines = cells(raw.lines, &mut group_of);
        let points = cells(raw.points, &mut group_of);
        let nodes = raw.nodes.into_iter().map(|p| p * unit).collect();
        Ok(Self { nodes, quads, lines, points, groups })
    }

    /// The index of the group named `name`, or an error listing the names there are.
    pub fn group(&self, name: &str) -> Result<usize, FemError> {
        self.groups.iter().position(|g| g.name == name).ok_or_else(|| {
            let names: Vec<&str> = self.groups.iter().map(|g| g.name.as_str()).collect();
            FemError::Mesh(format!("the mesh has no physical group '{name}'; it has {names:?}"))
        })
    }

    /// The nodes (indices into [`Self::nodes`]) of every cell of the group named `name`, each
    /// once, in increasing order.
    pub fn nodes_of(&self, name: &str) -> Result<Vec<usize>, FemError> {
        let g = self.group(name)?;
        let mut out: Vec<usize> = Vec::new();
        let quads = self.quads.iter().filter(|c| c.groups.contains(&g)).flat_map(|c| c.nodes);
        let lines = self.lines.iter().filter(|c| c.groups.contains(&g)).flat_map(|c| c.nodes);
        let points = self.points.iter().filter(|c| c.groups.contains(&g)).flat_map(|c| c.nodes);
        out.extend(quads.chain(lines).chain(points));
        out.sort_unstable();
        out.dedup();
        Ok(out)
    }

    /// The mesh with every quadrilateral split into four at its edges' midpoints and its
    /// centre, every line into two at its midpoint; points and groups kept.
    pub fn refined(&self) -> Self {
        let mut nodes = self.nodes.clone();
        let mut midpoints: HashMap<(usize, usize), usize> = HashMap::new();
        let mut mid = |a: usize, b: usize, nodes: &mut Vec<Vector3<f64>>| {
            *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                nodes.push((nodes[a] + nodes[b]) / 2.0);
                nodes.len() - 1
            })
        };
        let mut quads = Vec::with_capacity(4 * self.quads.len());
        for c in &self.quads {
            let [a, b, cc, d] = c.nodes;
            let (ab, bc, cd, da) =
                (mid(a, b, &mut nodes), mid(b, cc, &mut nodes), mid(cc, d, &mut nodes), mid(d, a, &mut nodes));
            nodes.push((nodes[a] + nodes[b] + nodes[cc] + nodes[d]) / 4.0);
            let o = nodes.len() - 1;
            for q in [[a, ab, o, da], [ab, b, bc, o], [o, bc, cc, cd], [da, o, cd, d]] {
                quads.push(Cell { nodes: q, groups: c.groups.clone(), tag: 0 });
            }
        }
        let mut lines = Vec::with_capacity(2 * self.lines.len());
        for c in &self.lines {
            let [a, b] = c.nodes;
            let m = mid(a, b, &mut nodes);
            lines.push(Cell { nodes: [a, m], groups: c.groups.clone(), tag: 0 });
            lines.push(Cell { nodes: [m, b], groups: c.groups.clone(), tag: 0 });
        }
        Self { nodes, quads, lines, points: self.points.clone(), groups: self.groups.clone() }
    }

    /// The shell structure of the quadrilaterals, of Young's modulus `e` and Poisson ratio
    /// `nu`, each as thick as the one group of `thickness` (group name, m) it belongs to; with
    /// each mesh node's node in the structure (None for a node of no quadrilateral). Element
    /// i of the structure is quadrilateral i. Refused: a quadrilateral in none of those groups
    /// or in two of different thickness, a group name the mesh lacks, and every quadrilateral
    /// [`Structure::add_quad`] refuses (named by its tag in the file).
    pub fn structure(
        &self,
        e: f64,
        nu: f64,
        thickness: &[(String, f64)],
    ) -> Result<(Structure, Vec<Option<usize>>), FemError> {
        let by_group =
            thickness.iter().map(|(name, t)| Ok((self.group(name)?, *t))).collect::<Result<Vec<_>, FemError>>()?;
        let mut s = Structure::new(e, nu)?;
        let mut node_of = vec![None; self.nodes.len()];
        for c in &self.quads {
            let mut ts = by_group.iter().filter(|(g, _)| c.groups.contains(g)).map(|&(_, t)| t);
            let t = ts.next().ok_or_else(|| {
                let names: Vec<&str> = c.groups.iter().map(|&g| self.groups[g].name.as_str()).collect();
                FemError::Mesh(format!(
                    "quadrilateral {} is in no group given a thickness (its groups: {names:?})",
                    c.tag
                ))
            })?;
            if let Some(other) = ts.find(|&o| o != t) {
                return Err(FemError::Mesh(format!(
                    "quadrilateral {} is in two groups of different thickness, {t} and {other} m",
                    c.tag
                )));
            }
            let corners = c.nodes.map(|n| self.nodes[n].into());
            let e = s.add_quad(corners, t).map_err(|err| FemError::Mesh(format!("quadrilateral {}: {err}", c.tag)))?;
            for (k, n) in s.element_nodes(e).into_iter().enumerate() {
                // The element's nodes are in its parameter order 0, 1, 3, 2 of the boundary.
                node_of[c.nodes[[0, 1, 3, 2][k]]] = Some(n);
            }
        }
        Ok((s, node_of))
    }
}
