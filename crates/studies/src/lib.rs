//! The studies of `impact` as computations: a scene in, data out. Nothing here writes a file
//! or draws on a terminal; rendering (the `report` crate) and the command line build on it,
//! and the Python package calls it directly.
//!
//! * [`run`]: a scene by the models a caller picks (beam, plate FE, transient), within the
//!   memory and run budgets, the one entry point the command line and Python share;
//! * [`study`]: the [`study::Study`] trait every study implements (`compute(&Scene,
//!   &Settings, &dyn Progress) -> Data`), so far by [`signals`], [`fem_bench`],
//!   [`transient`], the three-model yield study on a scene ([`yield_models::scene`]), the
//!   regime maps ([`regimes`]), the beam against the plate ([`comparison`]), the plate FE
//!   verification ([`fem_verification`]), the paper's studies under both models
//!   ([`paper_studies`]), the paper's reproduction ([`paper::reproduce`]) and the
//!   identification ([`identify`]); the yield study on the paper's scene
//!   ([`yield_models::paper`]) computes here too;
//! * [`comparison`]: the beam and the plate FE model through the same balance, at the scene's
//!   points, over the plate, across widths and on extreme inputs (`impact compare`);
//! * [`fem_verification`]: the plate elements against the classical series, on the scene's
//!   plate, and against scikit-fem;
//! * [`paper_studies`]: section V's conclusions, Tables 6-8 and 11 and the figures under
//!   both models;
//! * [`paper`]: the paper's setting, its printed tables and their reproduction (`impact paper`);
//! * [`identify`]: coal-gangue identification over a random-impact ensemble (`impact identify`);
//! * [`transient`]: the transient model against the quasi-static ones, the contact laws,
//!   the size map and the model's verification (`impact dynamic`);
//! * [`tail_beam`]: the scene's impacts on a box-section tail beam beside the paper's beam and
//!   Kirchhoff plate;
//! * [`in_time`]: the tail beam's and a mesh file's impacts in time on the structure's own
//!   modes;
//! * [`field_series`]: the plate's deflection recorded during one contact;
//! * [`verdict`]: a statement's verdict under one model, to the model's resolution;
//! * [`columns`]: one schema for the result rows (key with unit, header, kind, getter);
//! * [`settings`]: the studies' shared settings, one place for each;
//! * [`channel`]: the names of an identification's channels;
//! * [`progress`]: how a long study reports how far it is.
//!
//! ```
//! use scene::SceneSource;
//! let scene = scene::Scene::default_scene();
//! let models = studies::run::model_kinds("beam").unwrap();
//! let rows = studies::run::results(&scene, &models, &studies::progress::Silent).unwrap();
//! assert!(!rows.responses.is_empty());
//! ```

pub mod channel;
pub mod columns;
pub mod comparison;
pub mod drops;
pub mod fem_bench;
pub mod fem_verification;
pub mod field;
pub mod field_series;
pub mod identify;
pub mod in_time;
pub mod paper;
pub mod paper_studies;
pub mod progress;
pub mod regimes;
pub mod run;
pub mod settings;
pub mod shell_mesh;
pub mod signals;
pub mod stream;
pub mod study;
pub mod tail_beam;
pub mod transient;
pub mod verdict;
pub mod yield_models;

/// Any failure of a study, with its source.
pub type Failure = Box<dyn std::error::Error>;
