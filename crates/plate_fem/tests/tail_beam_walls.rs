//! The tail beam's optional walls: a diaphragm welded across the section under the struck
//! point. Castigliano's theorem bounds it: on the same mesh of the other walls, a welded wall
//! adds a positive semi-definite stiffness (and unknowns of its own, eliminated by a Schur
//! complement of the same sign), so the compliance f·K⁻¹f at any load can only fall; its
//! mass is its mid-surface area times its thickness; and written as a mesh file and read back
//! it is the builder's.

mod common;

use common::{read_back, test_box};
use plate_fem::shell::gmsh::MeshFile;
use plate_fem::shell::tail_beam::{Diaphragms, TailBeam};
use plate_fem::shell::DISC_RULE;

/// The test box with diaphragms at `x`, 16 mm thick (none if `x` is empty).
fn beam(x: Vec<f64>) -> TailBeam {
    test_box((!x.is_empty()).then_some(Diaphragms { x, thickness: 0.016 }))
}

/// The compliance at (x, H, z) under a 15 mm disc on the top plate, and the node count.
fn compliance(b: &TailBeam, x: f64, z: f64) -> (f64, usize) {
    let built = b.build(210e9, 0.3, 0.1, 0).unwrap();
    let top: Vec<usize> = built.structure.faces().next().unwrap().1.to_vec();
    let f = built.structure.disc_load([x, b.height, z], 0.015, &top, DISC_RULE).unwrap();
    let u = built.structure.factorize(&built.restraints).unwrap().solve(&f);
    (f.iter().zip(&u).map(|(a, b)| a * b).sum(), built.structure.nodes().len())
}

#[test]
fn a_welded_diaphragm_stiffens_the_box_and_weighs_its_area() {
    let (bare, with) = (beam(vec![]), beam(vec![0.65]));
    let rho = 7850.0;
    let added = with.mass(rho) - bare.mass(rho);
    assert!((added / (rho * 1.4 * 0.25 * 0.016) - 1.0).abs() < 1e-12, "{added}");
    // Over the diaphragm, mid-panel between the web and the rib, the top plate now spans
    // between it and the walls (measured 51 % less compliant; held to a fall of 30 %); far
    // from it, the box resists distortion and twist better (measured 37 % less; held to any
    // fall, which is all the theorem says).
    for (x, z, at_least) in [(0.65, 0.35, 0.3), (1.3, 1.05, 0.0)] {
        let ((c0, n0), (c1, n1)) = (compliance(&bare, x, z), compliance(&with, x, z));
        assert!(n1 > n0, "the diaphragm adds its own nodes");
        assert!(c1 < c0 * (1.0 - at_least), "({x}, {z}): {c1:e} against {c0:e}");
    }
    // Diaphragms that overlap each other or an end plate, or stand off the box, are refused.
    for bad in [vec![0.65, 0.66], vec![0.005], vec![1.6], vec![-0.1]] {
        assert!(beam(bad.clone()).validate().is_err(), "{bad:?}");
    }
}

/// The box with a diaphragm written as a mesh file (its walls as named groups, "diaphragms"
/// among them) and read back gives the builder's compliance: the group holds exactly the
/// diaphragm's elements, at its thickness.
#[test]
fn a_diaphragm_goes_through_a_mesh_file() {
    let b = beam(vec![0.65]);
    let (e, nu, at) = (210e9, 0.3, [0.65, 0.25, 0.35]);
    let text = b.mesh_file(0.1, 0).unwrap().to_msh41(1e-3);
    let mesh = MeshFile::parse(&text, "tail-beam.msh", 1e-3).unwrap();
    let (builder, _) = compliance(&b, at[0], at[2]);
    let walls = [
        ("top", 0.03),
        ("bottom", 0.02),
        ("jack 1", 0.02),
        ("webs", 0.02),
        ("ribs", 0.016),
        ("ends", 0.02),
        ("diaphragms", 0.016),
    ];
    let (read, _, _) = read_back(&mesh, &b, &walls, (e, nu), at);
    assert!((read / builder - 1.0).abs() < 1e-9, "builder {builder:e}, read {read:e}");
}
