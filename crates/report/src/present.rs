//! Presentation: tables, plots, and the layout of result rows.

pub mod columns;
pub mod plot;
pub mod rows;
pub mod table;
pub mod vtk;
