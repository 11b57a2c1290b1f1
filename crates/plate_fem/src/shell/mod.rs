//! # Shell structures from flat elements: box beams, panels, faceted cylinders, meshes
//!
//! A structure is a set of flat quadrilateral shell elements ([`element`], [`quad`]) in space, sharing
//! nodes where they meet, with six DOFs a node in the global frame: translations (u_x, u_y,
//! u_z) and the rotation vector (ω_x, ω_y, ω_z). Each element's stiffness, integrated in its
//! own frame, is turned into the global one by the rotation Λ whose rows are its frame's
//! axes, K = Tᵀ K_local T with T = diag(Λ, ..., Λ). At a joint of two plates at an angle the
//! bending rotation of one is the drilling rotation of the other, so the box's walls hold each
//! other as welded plates do.
//!
//! - [`element`]: the flat shell rectangle (membrane with incompatible modes, MITC4 plate,
//!   drilling penalty);
//! - [`quad`]: the same element on any convex flat quadrilateral (QM6 membrane, covariant
//!   MITC4), for meshes that are not tensor grids;
//! - [`Structure`]: nodes merged by position, elements, and faces (a rectangular wall meshed
//!   as a tensor grid, where loads and sensors are placed by the wall's own coordinates);
//! - [`Restraints`]: held DOFs (pins, clamps, symmetry) and translational springs to ground
//!   (a jack);
//! - [`Factorized`]: the restrained stiffness, factorized once (faer's sparse Cholesky), the
//!   response to a patch pressure with its energy split, and the fundamental frequency with a
//!   lumped mass;
//! - [`ShellModes`]: the lowest modes with the lumped mass ([`Factorized::modes`]), the
//!   plate's shift-invert Krylov search, and a load's modal forces and residual flexibility;
//! - [`warp`]: a warped quadrilateral formed on its corners' projections and tied to its nodes
//!   by rigid links (MacNeal's warping correction);
//! - [`tail_beam`]: a hydraulic support's tail beam, a welded box on hinge pins and jacks.
//!
//! Walls of boxes are rectangles, and so are the facets of a cylinder meshed along its axis and
//! around it, which is how the curved benchmarks are built; [`Structure::add_quad`] takes any
//! convex quadrilateral (a skewed or graded mesh, a mesher's output, a twisted strip), each with
//! its own element matrices.
//!
//! # Example: a flat plate as a shell
//!
//! ```
//! use plate_fem::shell::{Face, Restraints, Structure};
//! use plate_fem::mindlin::{series, Patch};
//! use plate_fem::PlateProperties;
//!
//! // A 1 x 1 m square plate, 0.1 m thick, in the x-z plane, hard simply supported.
//! let (a, h, e, nu) = (1.0, 0.1, 210e9, 0.3);
//! let mut s = Structure::new(e, nu)?;
//! let lines: Vec<f64> = (0..=20).map(|i| a * i as f64 / 20.0).collect();
//! let face = s.add_face(&Face::new([0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], lines.clone(), lines, h)?)?;
//! let mut r = Restraints::default();
//! for n in s.nodes_where(|p| p[0] == 0.0 || p[0] == a) {
//!     r.hold(n, &[0, 1, 2, 3]); // u and the rotation about x: w and the slope along the edge
//! }
//! for n in s.nodes_where(|p| p[2] == 0.0 || p[2] == a) {
//!     r.hold(n, &[0, 1, 2, 5]);
//! }
//! let patch = Patch { x: 0.5, z: 0.5, side_x: 0.2, side_z: 0.2 };
//! let response = s.factorize(&r)?.respond(face, &patch)?;
//! let navier = series::navier_patch(&PlateProperties { length: a, width: a, thickness: h, youngs_modulus: e, poisson_ratio: nu, density: 7850.0 }, &patch)?;
//! assert!((response.compliance / navier.compliance - 1.0).abs() < 1e-2);
//! # Ok::<(), plate_fem::FemError>(())
//! ```

pub mod element;
pub mod gmsh;
mod load;
mod modes;
mod msh_write;
pub mod quad;
mod restraints;
mod structure;
pub mod tail_beam;
pub mod warp;

pub use load::DISC_RULE;
pub use modes::{ShellMass, ShellModes};
pub use structure::{Face, FaceId, Factorized, Restraints, ShellResponse, Spring, Structure, WARP_LIMIT};
