//! The Mindlin plate (MITC4) against its references: the constant-moment patch test on a
//! graded grid, Navier's series with shear for thick plates (with the observed convergence
//! rate), and the Bogner-Fox-Schmit Kirchhoff plate in the thin limit, on edges and on the
//! paper's corner supports.

use plate_fem::convergence::richardson;
use plate_fem::mindlin::{self, series, Patch, Plate};
use plate_fem::{CornerSupport, FemError, Mesh, Model, PlateProperties, Supports};

fn plate(length: f64, width: f64, thickness: f64) -> PlateProperties {
    PlateProperties { length, width, thickness, youngs_modulus: 210e9, poisson_ratio: 0.3, density: 7850.0 }
}

/// Patch test: constant moments M_x = M₀ on the edges x = 0, L of a plate held at three
/// corners (statically determinate, so the reactions vanish) give the constant curvature
/// κ = D_b⁻¹ (M₀, 0, 0) everywhere. The FE field must be the exact quadratic w (less the
/// plane through the supports) at every node, with θ = ∇w, on a graded grid, thick or thin.
#[test]
fn constant_moment_patch_test_on_a_graded_grid() -> Result<(), FemError> {
    let (l, b) = (0.6, 0.4);
    let mesh = Mesh::from_lines(vec![0.0, 0.07, 0.2, 0.33, 0.41, 0.6], vec![0.0, 0.05, 0.22, 0.31, 0.4])?;
    for h in [0.002, 0.05] {
        let props = plate(l, b, h);
        let p = Plate::new(props, mesh.clone())?;
        use CornerSupport::{Fixed, Free};
        let supported = p.factorize(&Supports::corners([Fixed, Fixed, Fixed, Free]))?;
        // Consistent nodal moments: ∫ M₀ θ_x dz on each edge side, ±M₀ℓ/2 to its two nodes.
        let m0 = 1.0e3;
        let mut f = vec![0.0; p.dofs()];
        let (xs, zs) = (mesh.xs(), mesh.zs());
        for (i, sign) in [(0, -1.0), (mesh.nx(), 1.0)] {
            for j in 0..mesh.nz() {
                let half = sign * m0 * (zs[j + 1] - zs[j]) / 2.0;
                f[3 * mesh.node(i, j) + 1] += half;
                f[3 * mesh.node(i, j + 1) + 1] += half;
            }
        }
        let u = supported.solve(&f);
        // κ from M = D_b κ: κ_x = M₀/(D(1-ν²)), κ_z = -ν κ_x.
        let (d, nu) = (props.rigidity(), props.poisson_ratio);
        let (kx, kz) = (m0 / (d * (1.0 - nu * nu)), -nu * m0 / (d * (1.0 - nu * nu)));
        let w = |x: f64, z: f64| 0.5 * kx * x * (x - l) + 0.5 * kz * z * (z - b);
        let scale = kx * l * l;
        for (j, &z) in zs.iter().enumerate() {
            for (i, &x) in xs.iter().enumerate() {
                let n = 3 * mesh.node(i, j);
                let exact = [w(x, z), kx * (x - l / 2.0), kz * (z - b / 2.0)];
                for q in 0..3 {
                    let s = if q == 0 { scale } else { scale / l };
                    assert!(
                        (u[n + q] - exact[q]).abs() < 1e-10 * s,
                        "h = {h}, node ({i}, {j}), dof {q}: {} against {}",
                        u[n + q],
                        exact[q]
                    );
                }
            }
        }
    }
    Ok(())
}

/// Thick plates (h/L = 0.1 and 0.2) simply supported on all edges under a centred patch of
/// a quarter of the side: the FE compliance converges to Navier's series with shear at the
/// observed rate 2 (the energy error of a bilinear element under a load smooth on each
/// element), and its Richardson estimate bounds the finest mesh's distance from the series.
#[test]
fn thick_plates_converge_to_the_mindlin_series() -> Result<(), FemError> {
    for h in [0.1, 0.2] {
        let props = plate(1.0, 1.0, h);
        let patch = Patch { x: 0.5, z: 0.5, side_x: 0.25, side_z: 0.25 };
        let reference = series::navier_patch(&props, &patch)?;
        assert!(reference.truncation < 1e-9 * reference.compliance);
        let share = reference.shear / reference.compliance;
        let mut values = Vec::new();
        for n in [8, 16, 32, 64] {
            let p = Plate::new(props, Mesh::uniform(1.0, 1.0, n, n)?)?;
            let r = p.factorize(&Supports::all_edges_simple())?.respond(&patch)?;
            values.push(r.compliance);
            // The FE shear share tracks the series', its relative error falling as n⁻² like
            // the compliance's (measured 0.52/n² at h/L = 0.1 and 0.44/n² at 0.2).
            let miss = (r.shear / r.compliance / share - 1.0).abs();
            assert!(miss < 0.6 / (n * n) as f64, "h = {h}, n = {n}: shear share off by {miss:e}");
        }
        let e = richardson(&values).expect("four meshes");
        let rate = e.observed_rate.expect("three or more meshes");
        assert!((1.8..2.2).contains(&rate), "h = {h}: observed rate {rate}");
        let error = (e.finest - reference.compliance).abs();
        // Richardson's estimate assumes the rate 2; at the observed 1.99 it falls 0.2 % short.
        assert!(
            error <= e.error_estimate * 1.01,
            "h = {h}: |FE - series| = {error:e} against the estimate {:e}",
            e.error_estimate
        );
        assert!(
            (e.extrapolated / reference.compliance - 1.0).abs() < 1e-4,
            "h = {h}: extrapolated {:e} against {:e}",
            e.extrapolated,
            reference.compliance
        );
    }
    Ok(())
}

/// The thin limit on edges: at h/L = 1e-3 the Mindlin and Kirchhoff compliances of the
/// simply supported plate under a patch agree to the meshes' discretisation error (the
/// shear share is 1e-5 there), and both meet Kirchhoff's series; MITC4 does not lock.
#[test]
fn thin_limit_is_kirchhoff_on_edges() -> Result<(), FemError> {
    let props = plate(1.0, 0.8, 1e-3);
    let patch = Patch { x: 0.4, z: 0.3, side_x: 0.1, side_z: 0.1 };
    let reference = series::navier_patch(&props, &patch)?;
    assert!(reference.shear / reference.compliance < 2e-5);
    let model = Model::new(props, Mesh::uniform(1.0, 0.8, 20, 16)?)?;
    let bfs = model.factorize(&Supports::all_edges_simple())?.respond_patch(&patch)?;
    assert!((bfs / reference.kirchhoff - 1.0).abs() < 1e-3, "BFS {bfs:e} against series {:e}", reference.kirchhoff);
    let p = Plate::new(props, Mesh::uniform(1.0, 0.8, 80, 64)?)?;
    let mindlin = p.factorize(&Supports::all_edges_simple())?.respond(&patch)?.compliance;
    // Bilinear elements of 1/80 of the side: about 1e-3 (from the thick plates' rate).
    assert!((mindlin / bfs - 1.0).abs() < 3e-3, "Mindlin {mindlin:e} against BFS {bfs:e}");
    Ok(())
}

/// Corner supports on nodes and on pads, on a thick square plate (h/L = 0.1) with its four
/// corners fixed and a centred patch. On nodes the compliance grows by a constant per halving
/// of the mesh, the quarter plane's ln 2 · Σ R² (2/π)/(k_s G h) with R = 1/4 at each corner
/// (plate_fem::mindlin::node_support_growth): the increments fall toward it (5 % above it
/// from 128 to 256 elements a side, 1.3 % from 256 to 512, measured; the rest is the
/// discretisation error, falling as n⁻²). On pads of side h the sequence converges at the observed rate 2.
#[test]
fn node_supports_grow_logarithmically_and_pads_converge() -> Result<(), FemError> {
    let h = 0.1;
    let props = plate(1.0, 1.0, h);
    let patch = Patch { x: 0.5, z: 0.5, side_x: 0.125, side_z: 0.125 };
    let (mut nodes, mut pads) = (Vec::new(), Vec::new());
    let mut growth = 0.0;
    for n in [32, 64, 128, 256] {
        let p = Plate::new(props, Mesh::uniform(1.0, 1.0, n, n)?)?;
        growth = mindlin::node_support_growth(&[0.25; 4], p.shear_rigidity());
        let r = p.factorize(&Supports::con1())?.respond(&patch)?;
        // Equilibrium: the four corners carry the load, a quarter each by symmetry.
        assert!(r.corner_reaction.iter().all(|&q| (q - 0.25).abs() < 1e-9), "{:?}", r.corner_reaction);
        nodes.push(r.compliance);
        let padded = p.with_pad(h)?;
        pads.push(padded.factorize(&Supports::con1())?.respond(&patch)?.compliance);
    }
    let last = nodes[3] - nodes[2];
    assert!((last / growth - 1.0).abs() < 0.07, "increment {last:e} against {growth:e}");
    assert!(nodes[2] - nodes[1] > last && last > growth, "the increments fall toward the constant: {nodes:?}");
    let e = richardson(&pads).expect("four meshes");
    let rate = e.observed_rate.expect("four meshes");
    assert!((1.8..2.2).contains(&rate), "pads: rate {rate}, {pads:?}");
    Ok(())
}

/// A spring corner's pad is carried by its spring: on the paper's plate (458.4 x 360 x 8 mm)
/// under Con 2 (four springs of k_T) and a centred load, by symmetry each spring takes a
/// quarter of the load, so each pad's mean deflection is 1/(4 k_T) per unit load; with node
/// supports the corner node's deflection is the same.
#[test]
fn spring_pads_carry_a_quarter_each_under_con2() -> Result<(), FemError> {
    let (l, b, k) = (0.4584, 0.36, 5.11545e8);
    let props = plate(l, b, 0.008);
    let patch = Patch { x: l / 2.0, z: b / 2.0, side_x: 0.008, side_z: 0.008 };
    for pad in [None, Some(0.008)] {
        let mut p = Plate::new(props, Mesh::uniform(l, b, 40, 40)?)?;
        if let Some(side) = pad {
            p = p.with_pad(side)?;
        }
        let r = p.factorize(&Supports::con2(k))?.respond(&patch)?;
        for (w, reaction) in r.corner_deflection.iter().zip(r.corner_reaction) {
            assert!((w * 4.0 * k - 1.0).abs() < 1e-9, "pad {pad:?}: {w:e} against {:e}", 0.25 / k);
            // The pad's reaction from the residual f - Ku is the spring's force k w̄.
            assert!(
                (reaction / (k * w) - 1.0).abs() < 1e-8,
                "pad {pad:?}: reaction {reaction} against k w = {}",
                k * w
            );
        }
    }
    Ok(())
}

/// Mindlin's frequency of the hard simply supported plate in its (1, 1) mode: with
/// w = W sin αx sin βz, θ_x = X cos αx sin βz, θ_z = Z sin αx cos βz each harmonic decouples
/// into a 3 x 3 problem K v = ω² M v (Mindlin 1951; the energies written out here):
/// K = [[S k², -Sα, -Sβ], [-Sα, Dα² + D(1-ν)β²/2 + S, D(1+ν)αβ/2], [-Sβ, ·, Dβ² + D(1-ν)α²/2 + S]],
/// M = diag(ρh, ρh³/12, ρh³/12), S = k_s G h; the lowest root is the flexural one.
fn mindlin_frequency(props: &PlateProperties) -> f64 {
    use plate_fem::nalgebra::Matrix3;
    let (alpha, beta) = (std::f64::consts::PI / props.length, std::f64::consts::PI / props.width);
    let (d, nu) = (props.rigidity(), props.poisson_ratio);
    let s = mindlin::element::shear_rigidity(props.youngs_modulus, nu, props.thickness, mindlin::SHEAR_CORRECTION);
    let k = Matrix3::new(
        s * (alpha * alpha + beta * beta),
        -s * alpha,
        -s * beta,
        -s * alpha,
        d * alpha * alpha + d * (1.0 - nu) / 2.0 * beta * beta + s,
        d * (1.0 + nu) / 2.0 * alpha * beta,
        -s * beta,
        d * (1.0 + nu) / 2.0 * alpha * beta,
        d * beta * beta + d * (1.0 - nu) / 2.0 * alpha * alpha + s,
    );
    let m = [
        props.density * props.thickness,
        props.density * props.thickness.powi(3) / 12.0,
        props.density * props.thickness.powi(3) / 12.0,
    ];
    // M^{-1/2} K M^{-1/2}: symmetric, same eigenvalues as the pencil.
    let scaled = Matrix3::from_fn(|i, j| k[(i, j)] / (m[i] * m[j]).sqrt());
    let lowest = scaled.symmetric_eigenvalues().iter().copied().fold(f64::INFINITY, f64::min);
    lowest.sqrt()
}

/// The fundamental frequency of the hard simply supported plate against Mindlin's closed
/// form, thick (h/L = 0.1, 0.2: shear and rotary inertia lower it by 4.6 % and 15.0 % against
/// Kirchhoff's π²(1/a² + 1/b²)√(D/ρh)) and thin (h/L = 1e-3, where it is Kirchhoff's): the FE
/// frequency converges from above at the observed rate 2, within 1e-3 on 64 x 48 elements.
#[test]
fn fundamental_frequency_meets_mindlins_closed_form() -> Result<(), FemError> {
    for h in [1e-3, 0.1, 0.2] {
        let props = plate(1.0, 0.75, h);
        let exact = mindlin_frequency(&props);
        let kirchhoff = std::f64::consts::PI.powi(2)
            * (1.0 + 1.0 / 0.75f64.powi(2))
            * (props.rigidity() / (props.density * h)).sqrt();
        let mut values = Vec::new();
        for n in [16, 32, 64] {
            let p = Plate::new(props, Mesh::uniform(1.0, 0.75, n, 3 * n / 4)?)?;
            let f = p.factorize(&Supports::all_edges_simple())?.fundamental()?;
            assert!(f.omega > exact, "h = {h}, n = {n}: from above ({} against {exact})", f.omega);
            values.push(f.omega);
        }
        let rate = plate_fem::convergence::observed_rate(values[0], values[1], values[2]).expect("monotone");
        assert!((1.8..2.2).contains(&rate), "h = {h}: rate {rate}");
        assert!((values[2] / exact - 1.0) < 1e-3, "h = {h}: {} against {exact}", values[2]);
        if h < 0.01 {
            assert!((exact / kirchhoff - 1.0).abs() < 1e-5, "thin: {exact} against {kirchhoff}");
        }
    }
    Ok(())
}

/// Pads that would share nodes are refused before any assembly, naming both corners.
#[test]
fn overlapping_pads_are_refused() -> Result<(), FemError> {
    let p = Plate::new(plate(1.0, 1.0, 0.01), Mesh::uniform(1.0, 1.0, 2, 2)?)?.with_pad(0.5)?;
    match p.factorize(&Supports::con1()) {
        Err(FemError::Support(why)) => assert!(why.contains("share nodes") && why.contains("corner"), "{why}"),
        Err(e) => panic!("wrong error: {e}"),
        Ok(_) => panic!("overlapping pads accepted"),
    }
    Ok(())
}
