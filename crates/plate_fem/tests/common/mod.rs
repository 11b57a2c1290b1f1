//! What the tail beam's integration tests share: one test box, and its compliance computed from
//! a mesh file the way a user's own mesh is (`impact`'s `[shell_mesh]`).

use plate_fem::shell::gmsh::MeshFile;
use plate_fem::shell::tail_beam::{Diaphragms, Jack, TailBeam};
use plate_fem::shell::{Restraints, Spring, DISC_RULE};

/// A 1.6 x 1.4 x 0.25 m box with one rib at z = 0.7 m, pinned near both ends of its bottom,
/// one jack at (0.6, 0.35) m, and `diaphragms` if given; its coarsest x lines hold
/// x = 0.65 m (the jack pad's edge), so that a diaphragm there leaves the other walls' mesh as
/// it was.
pub fn test_box(diaphragms: Option<Diaphragms>) -> TailBeam {
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
        diaphragms,
        pin_height: 0.125,
        pins: vec![[0.1, 0.3], [1.1, 1.3]],
        jacks: vec![Jack { x: 0.6, z: 0.35, pad: 0.1, stiffness: 4.3e7, angle: 1.0 }],
    }
}

/// The compliance f·K⁻¹f of `beam` read from its mesh file `mesh` (walls as named groups at
/// the thicknesses `walls`, steel `(e, nu)`) under a 15 mm disc at `at` on the "top" group:
/// the "pins" nodes held, the first jack's stiffness shared by the "jack 1" nodes along its
/// angle. Also the pad's nodes and the held DOFs, to set against the builder's.
pub fn read_back(
    mesh: &MeshFile,
    beam: &TailBeam,
    walls: &[(&str, f64)],
    (e, nu): (f64, f64),
    at: [f64; 3],
) -> (f64, usize, usize) {
    let walls: Vec<(String, f64)> = walls.iter().map(|&(g, t)| (g.to_string(), t)).collect();
    let (s, node_of) = mesh.structure(e, nu, &walls).unwrap();
    let mut r = Restraints::default();
    for n in mesh.nodes_of("pins").unwrap() {
        r.hold(node_of[n].unwrap(), &[0, 1, 2]);
    }
    let pad = mesh.nodes_of("jack 1").unwrap();
    let jack = &beam.jacks[0];
    for &n in &pad {
        let direction = [jack.angle.cos(), jack.angle.sin(), 0.0];
        r.springs.push(Spring { node: node_of[n].unwrap(), direction, stiffness: jack.stiffness / pad.len() as f64 });
    }
    let g = mesh.group("top").unwrap();
    let struck: Vec<usize> =
        mesh.quads.iter().enumerate().filter(|(_, c)| c.groups.contains(&g)).map(|(i, _)| i).collect();
    let f = s.disc_load(at, 0.015, &struck, DISC_RULE).unwrap();
    let u = s.factorize(&r).unwrap().solve(&f);
    (f.iter().zip(&u).map(|(a, b)| a * b).sum(), pad.len(), r.held.len())
}
