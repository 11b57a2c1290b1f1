//! `impact`: the command line around the physics libraries. Scene files are read and
//! validated here (`scene`), results are presented here (`present`: tables, plots, row
//! layouts), studies are written up here (`report`), and files are written here
//! (`output`). The physics lives in `analytic` (the paper), `plate_fem` (plate finite
//! elements) and `coupled` (support sets, compliance models, the plan, validity, the
//! transient model).

pub mod output;
pub mod present;
pub mod provenance;
pub mod report;
pub mod scene;
