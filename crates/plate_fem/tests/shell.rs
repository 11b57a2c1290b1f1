//! The flat shell structure against its references: Navier's plate with shear (the membrane
//! decoupled), the Scordelis-Lo roof and the pinched cylinder (MacNeal & Harder 1985), and a
//! thin-walled box cantilever against Timoshenko's beam.

use plate_fem::mindlin::{series, Patch};
use plate_fem::shell::{Face, Restraints, Structure};
use plate_fem::PlateProperties;

fn lines(length: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|i| length * i as f64 / n as f64).collect()
}

/// The Scordelis-Lo roof: a cylindrical panel of radius 25, length 50 and half-angle 40°,
/// t = 0.25, E = 4.32e8, ν = 0, under its weight 90 per unit area, on rigid diaphragms
/// (u_y = u_z = 0) at its curved ends, straight edges free. The vertical deflection at the
/// midpoint of a free edge, on `n` x `n` flat facets over the whole roof, with drilling
/// factor `alpha`.
fn scordelis_lo(n: usize, alpha: f64) -> f64 {
    let (r, l, half, t) = (25.0_f64, 50.0, 40f64.to_radians(), 0.25);
    let mut s = Structure::new(4.32e8, 0.0).unwrap().with_drilling_factor(alpha).unwrap();
    let point = |x: f64, phi: f64| [x, r * phi.cos(), r * phi.sin()];
    let angle = |j: usize| -half + 2.0 * half * j as f64 / n as f64;
    for j in 0..n {
        for i in 0..n {
            let (x0, x1) = (l * i as f64 / n as f64, l * (i + 1) as f64 / n as f64);
            let (p0, p1) = (angle(j), angle(j + 1));
            s.add_facet([point(x0, p0), point(x1, p0), point(x0, p1), point(x1, p1)], t).unwrap();
        }
    }
    let mut rest = Restraints::default();
    for node in s.nodes_where(|p| p[0].abs() < 1e-9 || (p[0] - l).abs() < 1e-9) {
        rest.hold(node, &[1, 2]);
    }
    // The axial rigid motion, held at a node of the symmetry plane, where u_x = 0 anyway.
    let (mid, _) = s.nearest_node([l / 2.0, r, 0.0]).unwrap();
    rest.hold(mid, &[0]);
    let u = s.factorize(&rest).unwrap().solve(&s.area_load([0.0, -90.0, 0.0]));
    let (edge, d) = s.nearest_node(point(l / 2.0, half)).unwrap();
    assert!(d < 1e-9);
    -u[6 * edge + 1]
}

/// MacNeal & Harder's reference 0.3024 (Finite Elem. Anal. Des. 1, 3-20, 1985; deep shell
/// theory gives 0.3006, and MacNeal & Harder grade an element "A" within 2 %). Measured with
/// the default drilling factor: 0.30391, 0.30173, 0.30145 on 16, 32 and 64 facets a side over
/// the whole roof (a quarter model's 8-32), converging from above to within 0.4 % of 0.3024
/// and 0.3 % of 0.3006.
#[test]
fn scordelis_lo_roof_meets_macneal_harder() {
    let alpha = plate_fem::shell::element::DRILLING_FACTOR;
    let values: Vec<f64> = [16, 32, 64].map(|n| scordelis_lo(n, alpha)).to_vec();
    for (v, tol) in values.iter().zip([1e-2, 5e-3, 5e-3]) {
        assert!((v / 0.3024 - 1.0).abs() < tol, "{values:?}");
    }
    assert!((values[2] / 0.3006 - 1.0).abs() < 5e-3, "{values:?}");
    assert!(values[0] > values[1] && values[1] > values[2], "not monotone: {values:?}");
}

/// The drilling penalty is a device, not mechanics: a decade of its factor above the default
/// moves the roof on 64 x 64 facets (where facets meet at angles, so ω₃ couples to bending)
/// by 3.1e-4 (held to 6e-4), and the box cantilever by 1.2e-4 (held to 3e-4).
#[test]
fn drilling_factor_hardly_matters() {
    let alpha = plate_fem::shell::element::DRILLING_FACTOR;
    let (roof, stiffer) = (scordelis_lo(64, alpha), scordelis_lo(64, 10.0 * alpha));
    assert!((roof / stiffer - 1.0).abs() < 6e-4, "α = {alpha}: {roof}, 10α: {stiffer}");
    let (boxed, stiffer) = (box_cantilever(8, alpha), box_cantilever(8, 10.0 * alpha));
    assert!((boxed / stiffer - 1.0).abs() < 3e-4, "α = {alpha}: {boxed:e}, 10α: {stiffer:e}");
}

/// A hard simply supported 1 m square plate built as a shell in the x-z plane under a central
/// patch of side 0.25 m: (FE, Navier with shear) compliances and the FE membrane energy.
fn flat_plate(h: f64, n: usize) -> (f64, f64, f64) {
    let (a, e, nu) = (1.0, 210e9, 0.3);
    let mut s = Structure::new(e, nu).unwrap();
    let grid = Face::new([0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], lines(a, n), lines(a, n), h).unwrap();
    let face = s.add_face(&grid).unwrap();
    let mut r = Restraints::default();
    // w, the in-plane translations, and the rotation about the edge's normal in the plate's
    // plane (which is the slope along the edge) on each edge.
    for node in s.nodes_where(|p| p[0] == 0.0 || p[0] == a) {
        r.hold(node, &[0, 1, 2, 3]);
    }
    for node in s.nodes_where(|p| p[2] == 0.0 || p[2] == a) {
        r.hold(node, &[0, 1, 2, 5]);
    }
    let patch = Patch { x: 0.5, z: 0.5, side_x: 0.25, side_z: 0.25 };
    let fe = s.factorize(&r).unwrap().respond(face, &patch).unwrap();
    let props =
        PlateProperties { length: a, width: a, thickness: h, youngs_modulus: e, poisson_ratio: nu, density: 7850.0 };
    let navier = series::navier_patch(&props, &patch).unwrap();
    (fe.compliance, navier.compliance, fe.membrane)
}

/// The flat shell is the MITC4 plate: it converges to Navier's series with shear at rate 2
/// (measured errors -5.2 %, -1.32 %, -0.333 % on 8, 16, 32 elements a side at h/L = 0.1, and
/// -5.1 %, -1.31 %, -0.329 % at h/L = 0.01), Richardson on 16 and 32 meets the series to
/// 3e-5, and a load normal to a flat plate strains no membrane.
#[test]
fn flat_plate_meets_navier_with_shear() {
    for h in [0.1, 0.01] {
        let [(c8, n8, _), (c16, n16, _), (c32, n32, m)] = [8, 16, 32].map(|n| flat_plate(h, n));
        let (e8, e16, e32) = (c8 / n8 - 1.0, c16 / n16 - 1.0, c32 / n32 - 1.0);
        let rates = [(e8 / e16).log2(), (e16 / e32).log2()];
        assert!(rates.iter().all(|r| (1.9..2.1).contains(r)), "h = {h}: rates {rates:?}");
        let richardson = (4.0 * c32 - c16) / 3.0;
        assert!((richardson / n32 - 1.0).abs() < 1e-4, "h = {h}: Richardson {richardson:e} against {n32:e}");
        assert!(m.abs() < 1e-12 * c32, "h = {h}: membrane {m:e}");
    }
}

/// A thin-walled box cantilever (L = 3 m, 0.3 m wide, 0.2 m high, walls 5 mm, a 50 mm end
/// plate), clamped at x = 0, under a unit vertical force spread over the nodes of its end
/// section, with `n` elements across a wall and drilling factor `alpha`: the mean tip
/// deflection and Timoshenko's, PL³/3EI + PL/(G·2Ht) with the webs as the shear area.
fn box_cantilever(n: usize, alpha: f64) -> f64 {
    let (l, b, hgt, t) = (3.0, 0.3, 0.2, 0.005);
    let mut s = Structure::new(210e9, 0.3).unwrap().with_drilling_factor(alpha).unwrap();
    let (xs, zs, ys) = (lines(l, 10 * n), lines(b, n), lines(hgt, n));
    let wall =
        |o: [f64; 3], e2: [f64; 3], l2: &Vec<f64>, t: f64| Face::new(o, [1.0, 0.0, 0.0], e2, xs.clone(), l2.clone(), t);
    for y in [0.0, hgt] {
        s.add_face(&wall([0.0, y, 0.0], [0.0, 0.0, 1.0], &zs, t).unwrap()).unwrap();
    }
    for z in [0.0, b] {
        s.add_face(&wall([0.0, 0.0, z], [0.0, 1.0, 0.0], &ys, t).unwrap()).unwrap();
    }
    s.add_face(&Face::new([l, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], ys.clone(), zs.clone(), 0.05).unwrap())
        .unwrap();
    let mut r = Restraints::default();
    for node in s.nodes_where(|p| p[0] == 0.0) {
        r.hold(node, &[0, 1, 2, 3, 4, 5]);
    }
    let tip = s.nodes_where(|p| (p[0] - l).abs() < 1e-12);
    let mut f = vec![0.0; s.dofs()];
    for &node in &tip {
        f[6 * node + 1] = -1.0 / tip.len() as f64;
    }
    let u = s.factorize(&r).unwrap().solve(&f);
    -tip.iter().map(|&node| u[6 * node + 1]).sum::<f64>() / tip.len() as f64
}

/// The box cantilever against Timoshenko's beam. The beam leaves out shear lag and the root's
/// restraint of warping and of Poisson contraction, effects of order (B/L)² ≈ 1 %; measured
/// +0.013 % and +0.095 % on 4 and 8 elements across a wall, held to 0.3 %.
#[test]
fn box_cantilever_meets_timoshenko() {
    let (l, b, hgt, t, e, nu): (f64, f64, f64, f64, f64, f64) = (3.0, 0.3, 0.2, 0.005, 210e9, 0.3);
    let g = e / (2.0 * (1.0 + nu));
    let i = 2.0 * (b * t.powi(3) / 12.0 + b * t * (hgt / 2.0).powi(2)) + 2.0 * t * hgt.powi(3) / 12.0;
    let beam = l.powi(3) / (3.0 * e * i) + l / (g * 2.0 * hgt * t);
    for n in [4, 8] {
        let deflection = box_cantilever(n, plate_fem::shell::element::DRILLING_FACTOR);
        assert!((deflection / beam - 1.0).abs() < 3e-3, "{n} a wall: {deflection:e} against {beam:e}");
    }
}

/// A structure without enough restraint is refused, not solved.
#[test]
fn a_free_structure_is_refused() {
    let mut s = Structure::new(210e9, 0.3).unwrap();
    s.add_face(&Face::new([0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], lines(1.0, 4), lines(1.0, 4), 0.01).unwrap())
        .unwrap();
    let mut r = Restraints::default();
    r.hold(0, &[0, 1, 2]);
    assert!(s.factorize(&r).is_err());
    assert!(Face::new([0.0; 3], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], lines(1.0, 2), lines(1.0, 2), 0.01).is_err());
    assert!(s.add_facet([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.2, 0.0]], 0.01).is_err());
}

/// The pinched cylinder with rigid end diaphragms (MacNeal & Harder 1985): radius 300, length
/// 600, t = 3, E = 3e6, ν = 0.3, two opposite unit forces at mid-length; an octant on `n` x `n`
/// facets with its three symmetry planes. The deflection under the load.
fn pinched_cylinder(n: usize) -> f64 {
    let (r, l, t) = (300.0_f64, 600.0, 3.0);
    let mut s = Structure::new(3e6, 0.3).unwrap();
    let point = |x: f64, th: f64| [x, r * th.cos(), r * th.sin()];
    let q = std::f64::consts::FRAC_PI_2;
    for j in 0..n {
        for i in 0..n {
            let (x0, x1) = (0.5 * l * i as f64 / n as f64, 0.5 * l * (i + 1) as f64 / n as f64);
            let (a0, a1) = (q * j as f64 / n as f64, q * (j + 1) as f64 / n as f64);
            s.add_facet([point(x0, a0), point(x1, a0), point(x0, a1), point(x1, a1)], t).unwrap();
        }
    }
    let mut rest = Restraints::default();
    let near = |a: f64, b: f64| (a - b).abs() < 1e-9;
    for node in s.nodes_where(|p| near(p[0], 0.0)) {
        rest.hold(node, &[1, 2]); // the diaphragm holds the section's shape
    }
    for node in s.nodes_where(|p| near(p[0], l / 2.0)) {
        rest.hold(node, &[0, 4, 5]); // mirror plane x = L/2
    }
    for node in s.nodes_where(|p| near(p[2], 0.0)) {
        rest.hold(node, &[2, 3, 4]); // mirror plane z = 0
    }
    for node in s.nodes_where(|p| near(p[1], 0.0)) {
        rest.hold(node, &[1, 3, 5]); // mirror plane y = 0
    }
    let (load, d) = s.nearest_node([l / 2.0, r, 0.0]).unwrap();
    assert!(d < 1e-9);
    let mut f = vec![0.0; s.dofs()];
    f[6 * load + 1] = -0.25; // a quarter of the unit force on the octant
    let u = s.factorize(&rest).unwrap().solve(&f);
    -u[6 * load + 1]
}

/// Against the reference 1.8248e-5 (MacNeal & Harder's, from thin-shell theory). Measured
/// 0.754, 0.932, 0.989 and 1.007 of it on 8, 16, 32 and 64 facets a side of the octant (16 x 16:
/// 0.932, as MITC4's published 0.93); a shear-deformable shell under a point force has a
/// logarithmic term and so no mesh limit, which at t/R = 0.01 shows as the slight overshoot at
/// 64. Held: within 2 % on 32 (MacNeal and Harder's grade A), 8 % on 16, rising.
#[test]
fn pinched_cylinder_meets_macneal_harder() {
    let [a, b, c] = [8, 16, 32].map(|n| pinched_cylinder(n) / 1.8248e-5);
    assert!(a < b && b < c, "{a} {b} {c}");
    assert!((b - 1.0).abs() < 8e-2 && (c - 1.0).abs() < 2e-2, "{b} {c}");
}
