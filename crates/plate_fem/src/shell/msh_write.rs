//! Shell meshes out: a [`MeshFile`] as Gmsh's MSH 4.1 ASCII, which Gmsh, meshio and
//! [`MeshFile::parse`] read back (the reader is [`super::gmsh`]).

use super::gmsh::MeshFile;

impl MeshFile {
    /// The mesh as MSH 4.1 ASCII text, coordinates in units of `unit` metres: one geometric
    /// entity for each set of groups its cells share, so that Gmsh and [`Self::parse`] give
    /// every cell its groups back (tested by a round trip).
    pub fn to_msh41(&self, unit: f64) -> String {
        // Entities by (dimension, groups): tag, cells' nodes.
        let mut entities: Vec<(u8, Vec<usize>)> = Vec::new();
        let mut entity_of = |dim: u8, groups: &[usize]| -> usize {
            let mut key = groups.to_vec();
            key.sort_unstable();
            entities.iter().position(|e| e.0 == dim && e.1 == key).unwrap_or_else(|| {
                entities.push((dim, key));
                entities.len() - 1
            })
        };
        let quads: Vec<usize> = self.quads.iter().map(|c| entity_of(2, &c.groups)).collect();
        let lines: Vec<usize> = self.lines.iter().map(|c| entity_of(1, &c.groups)).collect();
        let points: Vec<usize> = self.points.iter().map(|c| entity_of(0, &c.groups)).collect();
        let mut s = String::from("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
        s += &format!("$PhysicalNames\n{}\n", self.groups.len());
        for g in &self.groups {
            s += &format!("{} {} \"{}\"\n", g.dim, g.tag, g.name);
        }
        s += "$EndPhysicalNames\n$Entities\n";
        let count = |d: u8| entities.iter().filter(|e| e.0 == d).count();
        s += &format!("{} {} {} 0\n", count(0), count(1), count(2));
        let (lo, hi) = self.nodes.iter().fold(([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]), |(lo, hi), p| {
            (std::array::from_fn(|i| lo[i].min(p[i] / unit)), std::array::from_fn(|i| hi[i].max(p[i] / unit)))
        });
        for dim in 0..3u8 {
            for (tag, (_, groups)) in entities.iter().enumerate().filter(|(_, e)| e.0 == dim) {
                let physical: Vec<String> = groups.iter().map(|&g| self.groups[g].tag.to_string()).collect();
                let place = if dim == 0 {
                    format!("{} {} {}", lo[0], lo[1], lo[2])
                } else {
                    format!("{} {} {} {} {} {}", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2])
                };
                let bounding = if dim == 0 { "" } else { " 0" };
                s += &format!("{} {place} {} {}{bounding}\n", tag + 1, physical.len(), physical.join(" "));
            }
        }
        s += "$EndEntities\n";
        // Every node in one block of the first entity of the highest dimension present.
        let host = entities
            .iter()
            .enumerate()
            .max_by_key(|(i, e)| (e.0, std::cmp::Reverse(*i)))
            .map_or((2, 1), |(i, e)| (e.0, i + 1));
        let n = self.nodes.len();
        s += &format!("$Nodes\n1 {n} 1 {n}\n{} {} 0 {n}\n", host.0, host.1);
        for k in 1..=n {
            s += &format!("{k}\n");
        }
        for p in &self.nodes {
            s += &format!("{:e} {:e} {:e}\n", p.x / unit, p.y / unit, p.z / unit);
        }
        s += "$EndNodes\n";
        let total = self.quads.len() + self.lines.len() + self.points.len();
        s += &format!("$Elements\n{} {total} 1 {total}\n", entities.len());
        let mut tag = 0;
        for (e, (dim, _)) in entities.iter().enumerate() {
            let (kind, cells): (u32, Vec<Vec<usize>>) = match dim {
                2 => {
                    (3, self.quads.iter().zip(&quads).filter(|(_, &q)| q == e).map(|(c, _)| c.nodes.to_vec()).collect())
                }
                1 => {
                    (1, self.lines.iter().zip(&lines).filter(|(_, &q)| q == e).map(|(c, _)| c.nodes.to_vec()).collect())
                }
                _ => (
                    15,
                    self.points.iter().zip(&points).filter(|(_, &q)| q == e).map(|(c, _)| c.nodes.to_vec()).collect(),
                ),
            };
            s += &format!("{dim} {} {kind} {}\n", e + 1, cells.len());
            for c in cells {
                tag += 1;
                let nodes: Vec<String> = c.iter().map(|n| (n + 1).to_string()).collect();
                s += &format!("{tag} {}\n", nodes.join(" "));
            }
        }
        s + "$EndElements\n"
    }
}
