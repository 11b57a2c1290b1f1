//! The plate FE verification: every check of the plate elements against its reference, with
//! measured convergence rates and the extreme cases.
//!
//! * [`classical`]: the simply supported plate under a point load against Navier's double
//!   series, the Lévy plate (simply supported ends, free sides) against its single series, and
//!   narrow Lévy plates against the beam they tend to;
//! * [`paper_plate`]: the paper's plate under Con 1-3, the rank-4 corner update against fresh
//!   factorizations over 15 decades of k_T, and extreme geometry and load points;
//! * [`reference`](mod@reference): the same plate against the independent scikit-fem elements (Argyris,
//!   Morley) of `reference/data`;
//! * [`mindlin`](mod@mindlin): the Reissner-Mindlin plate (MITC4) against Navier's series with
//!   shear, the thin limit and the node supports' logarithmic growth.
//!
//! Every point load's compliance converges as O(h²) on the conforming BFS element (the
//! r² ln r singularity of the point-load Green's function), so each ladder halves h and the
//! observed rate, the Richardson value and its error are the verification's numbers.

pub mod classical;
pub mod mindlin;
pub mod paper_plate;
pub mod reference;

pub use classical::{Convergence, LadderRow, LevyRow, NarrowRow};
pub use paper_plate::{CornerUpdate, ExtremeCase, ExtremeReference, ExtremeRow, PaperPlate, PaperPlateRow, UpdateRow};
pub use reference::{Reference, SkfemComparison};

use crate::progress::Progress;
use crate::Failure;
use coupled::discretisation::plate_properties;
use scene::Scene;
use serde::Serialize;

/// The paper's corner spring stiffness k_T, N/m: the stiffness the corner update is judged
/// at, and Con 2-3's when the scene names no spring.
pub const PAPER_K_T: f64 = 5.11545e8;

/// The plate the study runs on: the scene's, in SI.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlateSize {
    /// L, m.
    pub length: f64,
    /// B, m.
    pub width: f64,
    /// h, m.
    pub thickness: f64,
    /// D = E h³ / 12(1 - ν²), N·m.
    pub rigidity: f64,
}

/// What the verification computed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FemVerificationData {
    /// The simply supported square plate loaded and read at its centre (Navier).
    pub navier: Convergence,
    /// The centre deflection coefficient w D / (P a²) of [`Self::navier`]'s exact value.
    pub navier_coefficient: f64,
    /// The relative error of the Richardson value from the whole Navier ladder.
    pub navier_richardson: f64,
    /// The simply supported rectangle loaded off-centre (Navier).
    pub off_centre: Convergence,
    /// The Lévy plate at five load points.
    pub levy: Vec<LevyRow>,
    /// The largest relative error of a Lévy row's Richardson value.
    pub levy_worst: f64,
    /// Narrow Lévy plates against the beam.
    pub narrow: Vec<NarrowRow>,
    /// (C_plate/C_beam - 1)/(B/L)² at the centre of the narrowest plate.
    pub narrow_coefficient: f64,
    /// The scene's plate.
    pub plate: PlateSize,
    /// The scene's first corner spring stiffness (or [`PAPER_K_T`]), N/m.
    pub k_t: f64,
    /// Ladders on the scene's plate under Con 1-3.
    pub paper_plate: PaperPlate,
    /// The corner update against fresh factorizations.
    pub update: CornerUpdate,
    /// Extreme thickness, aspect ratio and load points.
    pub extremes: Vec<ExtremeRow>,
    /// Against scikit-fem.
    pub skfem: SkfemComparison,
    /// The Reissner-Mindlin plate's checks.
    pub mindlin: mindlin::MindlinVerification,
}

/// Runs every check on `scene`'s plate (and the fixed classical plates), against the
/// scikit-fem data in `reference`.
pub fn compute(scene: &Scene, reference: &Reference, progress: &dyn Progress) -> Result<FemVerificationData, Failure> {
    progress.start(7, "plate FE verification");
    let (navier, navier_coefficient, navier_richardson) = classical::navier_square()?;
    let off_centre = classical::off_centre()?;
    progress.advance(1);
    let (levy, levy_worst) = classical::levy()?;
    let (narrow, narrow_coefficient) = classical::narrow();
    progress.advance(1);
    let props = plate_properties(&scene.plate);
    let k_t = scene.conditions.iter().find_map(|c| c.spring_stiffnesses().next()).unwrap_or(PAPER_K_T);
    let paper_plate = paper_plate::ladders(props, k_t)?;
    progress.advance(1);
    let (update, model) = paper_plate::corner_update(props)?;
    progress.advance(1);
    let extremes = paper_plate::extremes(props, &model, k_t)?;
    progress.advance(1);
    let skfem = reference::compare(reference)?;
    progress.advance(1);
    let mindlin = mindlin::verify()?;
    progress.advance(1);
    progress.finish();
    Ok(FemVerificationData {
        navier,
        navier_coefficient,
        navier_richardson,
        off_centre,
        levy,
        levy_worst,
        narrow,
        narrow_coefficient,
        plate: PlateSize {
            length: props.length,
            width: props.width,
            thickness: props.thickness,
            rigidity: props.rigidity(),
        },
        k_t,
        paper_plate,
        update,
        extremes,
        skfem,
        mindlin,
    })
}
