//! `impact`: the command line around the libraries. The scene crate reads and validates
//! scenes, `studies` computes, `report` renders and `output` writes files whole or not at all;
//! the physics lives in `analytic` (the paper), `plate_fem` (plate finite elements),
//! `coupled` (support sets, compliance models, the plan, validity, the transient and reduced
//! models) and `identify` (ensembles, features, classifiers). These re-exports keep the
//! command line's tests on the same paths as the libraries.

pub use output;
pub use report;
pub use report::{present, provenance};
pub use scene;
pub use studies::run;
