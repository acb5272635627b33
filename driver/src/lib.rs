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

/// Compiling files into an object (`linc compile`), and a program's object.
pub mod build;
/// `linc check`: every file in one session.
pub mod check;
/// A console session over a plant, line by line.
pub mod console;
/// Coverage reports: lcov, Cobertura, a summary, and the gate.
pub mod coverage;
mod coverage_map;
/// The database file, `--set`, `--show`, `--now`, `--for`, `--out`.
pub mod database;
/// The listing of an object file.
pub mod disasm;
/// Pictures of sources, with the state a run left.
pub mod draw;
/// One expression evaluated.
pub mod eval;
/// The rules every file read or written follows.
pub mod files;
/// Which files `linc fmt` formats, and formatting one.
pub mod fmt;
/// FST tables: list, and translations to ST and to sequences.
pub mod fst;
/// Ladder files: the ST they compile as, their rungs drawn with values.
pub mod ladder;
/// The one plant builder.
pub mod plant;
/// JUnit and VCD files of a test run.
pub mod reports;
/// `linc roc poll`: the ROC host over a command list.
pub mod roc;
/// Running a plant: for a time, or actions for cycles.
pub mod run;
/// Scenario tests: files read, plants built, run on all cores.
pub mod scenarios;
/// Sequences with maps and resources, and generic sequences.
pub mod sfc;
mod single;
/// What kind of file a path names, and reading a source.
pub mod source;
mod state;

pub use linc_compiler::diag::Problems;
