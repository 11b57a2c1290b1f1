//! A study: a scene and settings in, serde data out. Rendering (the `report` crate) turns the
//! data into files; the command line and Python call [`Study::compute`] alike.

use crate::progress::Progress;
use crate::settings::Settings;
use crate::Failure;
use scene::Scene;

/// One study of a scene.
///
/// ```
/// use studies::{progress::{Progress, Silent}, settings::Settings, study::Study, Failure};
/// use scene::{Scene, SceneSource};
///
/// /// The number of impact points a scene names.
/// struct PointCount;
/// impl Study for PointCount {
///     const KEY: &'static str = "point-count";
///     type Data = usize;
///     fn compute(scene: &Scene, _: &Settings, _: &dyn Progress) -> Result<usize, Failure> {
///         Ok(scene.point_pairs().len())
///     }
/// }
/// let n = PointCount::compute(&Scene::default_scene(), &Settings::default(), &Silent).unwrap();
/// assert!(n > 0);
/// ```
pub trait Study {
    /// The study's name in folders and messages.
    const KEY: &'static str;
    /// What it computes: plain data, serializable, with no file or terminal in it.
    type Data: serde::Serialize;
    /// Runs the study on `scene`.
    fn compute(scene: &Scene, settings: &Settings, progress: &dyn Progress) -> Result<Self::Data, Failure>;
}

/// The signals study ([`crate::signals`]).
pub struct Signals;

impl Study for Signals {
    const KEY: &'static str = "signals";
    type Data = crate::signals::SignalsData;
    fn compute(scene: &Scene, settings: &Settings, progress: &dyn Progress) -> Result<Self::Data, Failure> {
        crate::signals::compute(scene, settings, progress)
    }
}

/// The plate FE bench ([`crate::fem_bench`]).
pub struct FemBench;

impl Study for FemBench {
    const KEY: &'static str = "fem-bench";
    type Data = crate::fem_bench::BenchReport;
    fn compute(scene: &Scene, settings: &Settings, _progress: &dyn Progress) -> Result<Self::Data, Failure> {
        let (nx, nz) = settings.bench_points;
        Ok(crate::fem_bench::bench(scene, settings.bench_tolerance, nx, nz)?)
    }
}

/// The transient study ([`crate::transient`]): `impact dynamic`, and the main report's
/// `dynamic` folder.
pub struct Transient;

impl Study for Transient {
    const KEY: &'static str = "dynamic";
    type Data = crate::transient::TransientData;
    fn compute(scene: &Scene, settings: &Settings, progress: &dyn Progress) -> Result<Self::Data, Failure> {
        crate::transient::compute(scene, settings, progress)
    }
}

/// The three-model yield study on the scene's own cases ([`crate::yield_models::scene`]).
pub struct SceneYield;

impl Study for SceneYield {
    const KEY: &'static str = "yield-three-models";
    type Data = crate::yield_models::scene::SceneYieldData;
    fn compute(scene: &Scene, settings: &Settings, progress: &dyn Progress) -> Result<Self::Data, Failure> {
        crate::yield_models::scene::compute(scene, settings, progress)
    }
}

/// The regime maps ([`crate::regimes`]).
pub struct RegimeMaps;

impl Study for RegimeMaps {
    const KEY: &'static str = "regimes";
    type Data = crate::regimes::RegimeData;
    fn compute(scene: &Scene, settings: &Settings, progress: &dyn Progress) -> Result<Self::Data, Failure> {
        crate::regimes::compute(scene, settings, progress)
    }
}

/// The coal-gangue identification over the scene's random-impact ensemble ([`crate::identify`]):
/// `impact identify`, and the identification pages of `impact report`.
pub struct Identify;

impl Study for Identify {
    const KEY: &'static str = "identify";
    type Data = crate::identify::IdentifyData;
    fn compute(scene: &Scene, _settings: &Settings, progress: &dyn Progress) -> Result<Self::Data, Failure> {
        crate::identify::compute(scene, progress)
    }
}

/// The plate FE verification ([`crate::fem_verification`]) on the scene's plate, against the
/// classical series and the committed scikit-fem data.
pub struct FemVerification;

impl Study for FemVerification {
    const KEY: &'static str = "fem";
    type Data = crate::fem_verification::FemVerificationData;
    fn compute(scene: &Scene, _settings: &Settings, progress: &dyn Progress) -> Result<Self::Data, Failure> {
        let reference = crate::fem_verification::Reference::embedded()?;
        crate::fem_verification::compute(scene, &reference, progress)
    }
}

/// The beam against the plate FE model ([`crate::comparison`]): `impact compare`.
pub struct Comparison;

impl Study for Comparison {
    const KEY: &'static str = "compare";
    type Data = crate::comparison::ComparisonData;
    fn compute(scene: &Scene, _settings: &Settings, progress: &dyn Progress) -> Result<Self::Data, Failure> {
        crate::comparison::compute(scene, progress)
    }
}

/// The paper's own studies under both models ([`crate::paper_studies`]), on the paper's
/// scene whatever scene is given.
pub struct PaperStudies;

impl Study for PaperStudies {
    const KEY: &'static str = "paper-studies";
    type Data = crate::paper_studies::PaperStudiesData;
    fn compute(_scene: &Scene, _settings: &Settings, progress: &dyn Progress) -> Result<Self::Data, Failure> {
        crate::paper_studies::compute(progress)
    }
}

/// The paper's section IV reproduced ([`crate::paper::reproduce`]): `impact paper`, on the
/// paper's scene whatever scene is given.
pub struct Reproduction;

impl Study for Reproduction {
    const KEY: &'static str = "paper";
    type Data = crate::paper::ReproductionData;
    fn compute(_scene: &Scene, _settings: &Settings, progress: &dyn Progress) -> Result<Self::Data, Failure> {
        crate::paper::reproduce(&crate::paper::PrintedTables::embedded()?, progress)
    }
}
