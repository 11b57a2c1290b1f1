//! The paper's own studies redone with both models, on the paper's scene whatever scene is
//! given: its conclusions (section V) item by item ([`checks`]), Tables 6-8 and 11 at the
//! midpoint ([`midpoint`]), and its figures along the centreline ([`figures`]).
//!
//! Both models go through the same energy balance at maximum compression (eqs. 14, 25, 46)
//! and the same yield model (eqs. 51-54); only the compliance C differs: the beam's closed
//! form (section II) or the plate FE model's Richardson value.

pub mod checks;
pub mod figures;
pub mod line;

pub use checks::{Along, Check, Evidence, Statement};
pub use figures::{Curve, StudyFigure};

use crate::paper::{Paper, SWEEP};
use crate::progress::Progress;
use crate::settings::{BASE_MESH, LEVELS, METHOD};
use crate::Failure;
use analytic::Response;
use coupled::{BeamModel, ComplianceModel, PlateModel};
use serde::Serialize;

/// The impact velocity of the paper's Tables 6-8 and 11, m/s.
pub const TABLES_VELOCITY: f64 = 0.0025;

/// What a table of the paper reports at maximum compression, under one model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Midpoint {
    /// P_max, N.
    pub contact_force: f64,
    /// δ_max, m.
    pub compression: f64,
    /// The impact-point deflection, m.
    pub deflection: f64,
    /// The rock's total energy over E₀.
    pub rock_total_ratio: f64,
    /// The plate's strain energy over E₀.
    pub plate_ratio: f64,
    /// The springs' energy over E₀.
    pub spring_ratio: f64,
}

impl From<&Response> for Midpoint {
    fn from(r: &Response) -> Self {
        Self {
            contact_force: r.contact_force,
            compression: r.compression,
            deflection: r.deflection,
            rock_total_ratio: r.rock_total_ratio,
            plate_ratio: r.plate_ratio,
            spring_ratio: r.spring_ratio,
        }
    }
}

/// One support set and body of Tables 6-8 and 11, by both models.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MidpointRow {
    /// The support set.
    pub condition: String,
    /// The body.
    pub body: String,
    /// By the beam.
    pub beam: Midpoint,
    /// By the plate.
    pub plate: Midpoint,
}

/// What the paper's studies computed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PaperStudiesData {
    /// Section V's statements, item by item, under both models.
    pub checks: Vec<Check>,
    /// The velocity of Tables 6-8 and 11, m/s.
    pub velocity: f64,
    /// Tables 6-8 and 11 at the midpoint.
    pub midpoint: Vec<MidpointRow>,
    /// The figures redone.
    pub figures: Vec<StudyFigure>,
}

/// Tables 6-8 and 11 of the paper (the plate's midpoint, [`TABLES_VELOCITY`], three spheres)
/// under both models.
pub fn midpoint(paper: &Paper) -> Result<Vec<MidpointRow>, Failure> {
    let sc = &paper.scene;
    let mid = (sc.plate.length() / 2.0, sc.plate.width() / 2.0);
    let model = PlateModel::compute(&sc.plate, &sc.conditions, &[mid], BASE_MESH, LEVELS)?;
    let beam = BeamModel { plate: &sc.plate };
    let mut rows = Vec::new();
    for cond in &sc.conditions {
        for body in paper.bodies() {
            let imp = coupled::plan::impact_of(sc, body, TABLES_VELOCITY);
            let rb = analytic::respond(&imp, &beam.compliance(cond, mid.0, mid.1)?.compliance, METHOD)?;
            let rp = analytic::respond(&imp, &model.compliance(cond, mid.0, mid.1)?.compliance, METHOD)?;
            rows.push(MidpointRow {
                condition: cond.name.clone(),
                body: body.name.clone(),
                beam: (&rb).into(),
                plate: (&rp).into(),
            });
        }
    }
    Ok(rows)
}

/// The paper's studies on the paper's scene, every line in the paper's [`SWEEP`] points.
pub fn compute(progress: &dyn Progress) -> Result<PaperStudiesData, Failure> {
    let paper = Paper::new();
    progress.start(3, "the paper's studies under both models");
    let checks = checks::checks(&paper, SWEEP)?;
    progress.advance(1);
    let midpoint = midpoint(&paper)?;
    progress.advance(1);
    let figures = figures::figures(&paper, SWEEP)?;
    progress.advance(1);
    progress.finish();
    Ok(PaperStudiesData { checks, velocity: TABLES_VELOCITY, midpoint, figures })
}
