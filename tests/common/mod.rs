//! What the integration tests share: running the `impact` binary ([`run`]), closed-form
//! references ([`reference`]) and an independent modal model of a struck plate ([`modal`]),
//! the small scenes they compute on ([`scenes`], the `test_scenes` crate the studies' tests
//! share), and a temporary directory for scene files and output ([`tmp`]).

// Each test file is a crate of its own and uses only part of this module; the rest would be
// reported as dead code in every one of them.
#![allow(dead_code, unused_imports)]

pub mod modal;
pub mod reference;
pub mod run;
pub mod tmp;

pub use run::{impact, Impact, Run, BIN};
/// The small scenes, shared with the studies' tests.
pub use test_scenes as scenes;
pub use tmp::{leftovers, tmp, Tmp};
