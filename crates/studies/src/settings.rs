//! Settings shared by the studies: one place for each.

use analytic::Method;

/// Elements along the longer side of the coarser mesh of the plate model's ladder: 20 x 16
/// and 40 x 32 for the paper's plate, Richardson-extrapolated (the FE verification report
/// shows the estimate is conservative there).
pub const BASE_MESH: usize = 20;
/// Meshes in the plate model's ladder.
pub const LEVELS: u32 = 2;
/// The map grid along the length: L in 100 parts, as in the paper.
pub const MAP_X: usize = 101;
/// The map grid across the width: B in 20 parts.
pub const MAP_Z: usize = 21;
/// The paper's Areas 1-7 (Table 2), as fractions of L.
pub const AREAS: [f64; 7] = [0.03, 0.25, 0.46, 0.5, 0.54, 0.75, 0.98];
/// Steps per Hertz contact time in the transient runs (force error ~4e-5, energy error
/// ~5e-5: see the transient report).
pub const STEPS_PER_CONTACT: f64 = 200.0;
/// Elements along the longer side for the transient runs.
pub const DYNAMIC_MESH: usize = 20;
/// Relative tolerance of the main report's transient cases (the error estimate of every
/// P_max and contact time within it). The report's transient conclusions are quasi-static
/// errors of 5-70 %; at 1e-3 nearly every case stays on 20 elements and 200 steps per Hertz
/// time (about 0.7 s a case with its estimate), where `impact dynamic`'s default 1e-4 takes
/// several seconds a case on the 40-element mesh.
pub const REPORT_TOLERANCE: f64 = 1e-3;
/// The balance solver of the studies: bracketed Newton to 1e-13.
pub const METHOD: Method = Method::Bracketed { tolerance: 1e-13, max_iterations: 200 };

/// The settings a study runs with, as one value: the defaults are the constants above, and a
/// caller (the command line's flags, a Python keyword) changes a field, never a constant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Elements along the longer side of the coarser plate mesh ([`BASE_MESH`]).
    pub base_mesh: usize,
    /// Meshes in the plate model's ladder ([`LEVELS`]).
    pub levels: u32,
    /// The balance solver ([`METHOD`]).
    pub method: Method,
    /// Relative tolerance of the transient cases of a report ([`REPORT_TOLERANCE`]).
    pub transient_tolerance: f64,
    /// The FE bench: the relative error the chosen mesh reaches at the centre.
    pub bench_tolerance: f64,
    /// The FE bench: impact points along the length and across the width of the map.
    pub bench_points: (usize, usize),
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            base_mesh: BASE_MESH,
            levels: LEVELS,
            method: METHOD,
            transient_tolerance: REPORT_TOLERANCE,
            bench_tolerance: 1e-4,
            bench_points: (101, 21),
        }
    }
}
