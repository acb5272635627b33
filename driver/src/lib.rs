//! linc's library: what every surface of linc — the command line, the
//! monitor and wire servers, the tests — calls to compile, build a plant,
//! run it, draw it and test it. Every function returns what it made and
//! what it ran into as data ([`Problems`]); nothing here prints or exits.
//!
//! - [`plant`] is the one plant builder: database, `--set`, clock, seed,
//!   watchdog, tier, retentive state and what runs. [`run`] runs a plant,
//!   [`console`] drives one line by line, [`draw`] pictures one, and
//!   [`scenarios`] tests one ([`coverage`], [`reports`]).
//! - [`check`], [`build`], [`sfc`], [`fst`], [`ladder`], [`fmt`],
//!   [`eval`], [`disasm`] and [`roc`] are the other commands' work.
//! - [`files`] holds the rules every file read or written follows;
//!   [`database`] and [`source`] read the two kinds of input.

pub mod build;
pub mod check;
pub mod console;
pub mod coverage;
mod coverage_map;
pub mod database;
pub mod disasm;
pub mod draw;
pub mod eval;
pub mod files;
pub mod fmt;
pub mod fst;
pub mod ladder;
pub mod plant;
pub mod reports;
pub mod roc;
pub mod run;
pub mod scenarios;
pub mod sfc;
pub mod single;
pub mod source;
pub mod state;

pub use linc_compiler::diag::Problems;
