//! The yield velocity under three models, written up: the paper's beam (eqs. 51-54), the
//! quasi-static plate FE compliance through the same formula, and the transient plate (the v
//! at which the transient δ_max reaches δ_my of eq. 51). Table 2, Table 5's minimum and
//! Figs. 8-9 redone with all three, and the paper's statements about yield velocities tested
//! on the results ([`study`]); the same three models on a scene of one's own ([`scene_study`]).
//!
//! The studies compute in [`studies::yield_models`]; the transient root is
//! [`coupled::yield_root::transient_yield`]. Here they become Markdown, tables, figures and
//! CSV files.

mod paper;
mod scene;

use crate::paper::PrintedTables;
use crate::Failure;
use ::scene::Scene;
pub use coupled::yield_root::{rigid_yield, transient_yield, TransientYield};
use output::Artifacts;
use studies::progress::{Progress, Silent};
use studies::settings::Settings;
use studies::study::{SceneYield, Study};
use studies::yield_models::paper::{PaperYieldData, Printed, PrintedRow, Quoted};
pub use studies::yield_models::{log_root, FINE, ROOT_TOLERANCE};

/// What the main report shows of a three-model yield study: its section (links relative to
/// the main report's page) and its line among the findings.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct YieldSummary {
    /// The Markdown section: the table, the figures and the link to the study's page.
    pub section: String,
    /// One Markdown bullet line for the findings.
    pub finding: String,
}

/// The folder the main report nests the study in, for the links of [`YieldSummary`].
pub const FOLDER: &str = "yield-three-models";

/// What the study needs of the paper's printed tables: Areas 1-7, Table 2 and section IV-D.
pub fn printed_inputs(printed: &PrintedTables) -> Printed {
    let quoted = &printed.section4d;
    let q = |p: &crate::paper::PrintedText| Quoted { value: p.printed.value, text: p.text.clone() };
    Printed {
        areas: printed.table2.x.iter().map(|p| p.printed.value).collect(),
        table2: printed
            .table2
            .rows
            .iter()
            .map(|r| PrintedRow {
                body: r.body.clone(),
                condition: r.condition,
                values: r.values.iter().map(|p| p.printed.value).collect(),
            })
            .collect(),
        min_yield_velocity: quoted.min_yield_velocity.printed.value,
        coal_min_exceeds: q(&quoted.coal_min_exceeds),
        coal_over_gangue_exceeds: q(&quoted.coal_over_gangue_exceeds),
    }
}

/// The three-model yield study on the paper's own scene, whatever scene is given, against
/// the paper's printed tables (which this crate holds, so the study is declared here and
/// computes in [`studies::yield_models::paper`]).
pub struct PaperYield;

impl Study for PaperYield {
    const KEY: &'static str = "paper-yield-three-models";
    type Data = PaperYieldData;
    fn compute(_scene: &Scene, settings: &Settings, progress: &dyn Progress) -> Result<Self::Data, Failure> {
        let printed = PrintedTables::embedded()?;
        studies::yield_models::paper::compute(&printed_inputs(&printed), settings, progress)
    }
}

/// The study: the paper's own scene, whatever `scene` is.
pub fn report(scene: &Scene) -> Result<Artifacts, Failure> {
    Ok(study(scene, &Silent)?.0)
}

/// [`report`], and what the main report shows of it.
pub fn study(scene: &Scene, progress: &dyn Progress) -> Result<(Artifacts, YieldSummary), Failure> {
    let data = PaperYield::compute(scene, &Settings::default(), progress)?;
    paper::files(&data, &PrintedTables::embedded()?)
}

/// The paper study's files from its data, whoever computed it: the pages, tables, figures
/// and the run times, which only `timing.md` carries.
pub fn render(data: &PaperYieldData) -> Result<Artifacts, Failure> {
    Ok(paper::files(data, &PrintedTables::embedded()?)?.0)
}

/// The three-model yield study on a scene of one's own: the yield velocity of every body
/// under every support set at the scene's transient points, by the beam (Con 1-3 only), the
/// quasi-static plate and the transient plate, each with its error estimate, and whether the
/// transient v_y lies below the quasi-static plate's by more than both errors.
pub fn scene_study(scene: &Scene, progress: &dyn Progress) -> Result<(Artifacts, YieldSummary), Failure> {
    let data = SceneYield::compute(scene, &Settings::default(), progress)?;
    scene::files(scene, &data)
}
