//! What every front end of linc shares, between the compiler and runtime
//! below and the `linc` command line (and the coming monitor, language
//! server and protocol servers) above: files read and written under one set
//! of rules ([`files`]), and one reporter through which every problem of
//! every stage reaches the user ([`report`]).

pub mod build;
pub mod coverage;
pub mod coverage_map;
pub mod database;
pub mod draw;
pub mod eval;
pub mod files;
pub mod fmt;
pub mod fst_translate;
pub mod ladder;
pub mod report;
pub mod roc;
pub mod scenarios;
pub mod single;
pub mod source;
pub mod state;
pub mod strategy;

pub use report::Reporter;
