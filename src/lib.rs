//! `impact`: the scene files, the plan and the reports around the paper's model
//! (`analytic`) and the plate finite elements (`plate_fem`).

pub mod compare;
pub mod conclusions;
pub mod dynamic;
pub mod dynreport;
pub mod fem;
pub mod femreport;
pub mod field;
pub mod output;
pub mod paper;
pub mod platemodel;
pub mod plot;
pub mod reference;
pub mod run;
pub mod scene;
pub mod table;
pub mod views;
