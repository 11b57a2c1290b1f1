use plate_fem::classical::*;
use plate_fem::*;
use std::time::Instant;

fn main() {
    let p = PlateProperties {
        length: 1.0,
        width: 1.0,
        thickness: 0.01,
        youngs_modulus: 1e9,
        poisson_ratio: 0.3,
        density: 1.0,
    };
    let d = p.rigidity();
    let navier =
        levy_converged(LevyPlate { a: 1.0, b: 1.0, d, nu: 0.3, y_edges: YEdge::Simple }, (0.5, 0.0), (0.5, 0.0), 1e-12);
    println!("navier centre {navier:e} coef {}", navier * d);
    let mut prev = vec![];
    for n in [4, 8, 16, 32, 64, 128] {
        let m = Model::new(p, Mesh::uniform(1.0, 1.0, n, n).unwrap()).unwrap();
        let f = m.factorize(&Supports::all_edges_simple()).unwrap();
        let c = f.respond(0.5, 0.5).unwrap().compliance;
        prev.push(c);
        println!("n {n} C {c:e} rel err {:e}", (c - navier) / navier);
    }
    println!("{:?}", convergence::richardson(&prev));
    // paper plate Con1 centre
    let pp = PlateProperties {
        length: 0.4584,
        width: 0.36,
        thickness: 0.008,
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
        density: 7850.0,
    };
    let mut v1 = vec![];
    for (nx, nz) in [(10, 8), (20, 16), (40, 32), (80, 64), (160, 128)] {
        let t = Instant::now();
        let m = Model::new(pp, Mesh::uniform(pp.length, pp.width, nx, nz).unwrap()).unwrap();
        let t1 = t.elapsed();
        let f = m.factorize(&Supports::con1()).unwrap();
        let t2 = t.elapsed();
        let r = f.respond(pp.length / 2.0, pp.width / 2.0).unwrap();
        let t3 = t.elapsed();
        v1.push(r.compliance);
        println!(
            "paper {nx}x{nz} dofs {} nnz {} C {:e} R {:?} asm {:?} fac {:?} solve {:?}",
            m.dofs(),
            m.nonzeros(),
            r.compliance,
            r.total_reaction(),
            t1,
            t2 - t1,
            t3 - t2
        );
        // woodbury
        let fam = CornerFamily::new(&m, [EdgeSupport::Free; 4], CornerFamily::default_base_stiffness(&m)).unwrap();
        let pts =
            [(pp.length / 2.0, pp.width / 2.0), (0.1, 0.0), (pp.length, pp.width / 2.0), (0.001, 0.001), (0.0, 0.0)];
        let bps = fam.probe_many(&pts).unwrap();
        for k in [1.0, 5e4, 5.11545e8, 1e15] {
            for sup in [Supports::con1(), Supports::con2(k), Supports::con3(k)] {
                let fresh = m.factorize(&sup).unwrap().with_refinement(3).respond_many(&pts).unwrap();
                for (bp, fr) in bps.iter().zip(&fresh) {
                    let up = fam.respond(bp, sup.corners).unwrap();
                    let e = (up.compliance - fr.compliance).abs() / fr.compliance.abs().max(1e-300);
                    if e > 1e-10 {
                        println!(
                            "   woodbury k {k:e} {:?} at ({},{}) C {:e} vs {:e} rel {e:e}",
                            sup.corners[1], bp.x, bp.z, up.compliance, fr.compliance
                        );
                    }
                }
            }
        }
    }
    println!("{:?}", convergence::richardson(&v1));
}
