//! `impact`: the command line around the physics libraries. Scene files are read and
//! validated here (`scene`), results are presented here (`present`: tables, plots, row
//! layouts), studies are written up here (`report`), files are written here (`output`),
//! and a scene is run with the chosen models here (`run`, shared by the command line and
//! the Python package in `python/`). The physics lives in `analytic` (the paper),
//! `plate_fem` (plate finite elements) and `coupled` (support sets, compliance models, the plan, validity, the
//! transient model).

pub mod output;
pub mod present;
pub mod provenance;
pub mod report;
pub mod run;
pub mod scene;
