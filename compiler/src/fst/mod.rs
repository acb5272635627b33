//! ROC Function Sequence Tables (FST): the CSV reader, the checker and the
//! lowering to the shared instruction set (`docs/fst.md`).
//!
//! Data flows one way: CSV text → [`reader::read`] → [`Table`] (cells with
//! spans) → [`check::check`] against a database → [`Checked`] (every
//! argument resolved) → `lower::lower` → one FST unit of an object.

pub mod check;
pub mod commands;
pub(crate) mod errors;
pub mod list;
pub(crate) mod lower;
pub mod reader;
pub mod tlp;
pub mod translate;

pub use commands::Cmd;

use crate::diag::span::Span;
use crate::diag::Diagnostic;
use linc_format::object::{Class, ObjectFile};
use linc_format::Database;

/// One cell of the table as written, with where it is in the CSV text.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    pub text: String,
    pub span: Span,
}

/// A row of the table as read: a step. Empty cells are `None`.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// 0, 1, 2 … (the STEP column, checked to count up without gaps).
    pub step: u32,
    /// 1-based line of the row in the CSV file.
    pub line: u32,
    /// 1-based column (in characters) of the CMD cell, for [`Step::col`].
    pub col: u32,
    pub label: Option<Cell>,
    pub cmd: Cell,
    pub arg1: Option<Cell>,
    pub arg2: Option<Cell>,
    /// Kept for listings and diagnostics; never compiled.
    pub comment: String,
}

/// A table as read: its rows up to the first blank command.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    pub rows: Vec<Row>,
    /// Line and column (1-based) just after the last row of the program:
    /// where an END the table leaves out is placed.
    pub end_line: u32,
    pub end_col: u32,
}

/// A resolved database parameter: a field of a block, as a symbol of the
/// object names it. An empty `block` is the FST running the table (timer
/// numbers 1–4 of ST and CT).
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    pub block: String,
    pub field: String,
    pub class: Class,
    pub readonly: bool,
    /// The argument as written, for listings and messages.
    pub written: String,
}

/// A checked argument.
#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    None,
    /// A numeric constant (as the device holds it: single precision).
    Const(f32),
    /// A branch target: the index of the step the label is on.
    Label(u32),
    /// Message text (MSG, ALM, EVT): MSG keeps 30 characters, ALM/EVT 10.
    Text(String),
    Param(Param),
}

/// A checked step: command and resolved arguments, with its position.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    pub cmd: Cmd,
    pub arg1: Arg,
    pub arg2: Arg,
    /// Line and column (1-based) of the command cell.
    pub line: u32,
    pub col: u32,
}

/// A table that checked clean: its steps, exactly one of them END (appended
/// when the table has none).
#[derive(Clone, Debug, PartialEq)]
pub struct Checked {
    pub steps: Vec<Step>,
}

/// Reads, checks and (with a database) lowers one table. `name` names the
/// unit, `file` is the source file recorded in it. Compiling needs the
/// database the table's points live in; without one the table is checked
/// as far as it can be and no object is made.
pub fn compile(text: &str, name: &str, file: &str, db: Option<&Database>) -> (Vec<Diagnostic>, Option<ObjectFile>) {
    let (table, mut diagnostics) = reader::read(text);
    let (checked, more) = check::check(&table, db);
    diagnostics.extend(more);
    if diagnostics.iter().any(Diagnostic::is_error) {
        return (diagnostics, None);
    }
    let object = checked.map(|c| lower::lower(&c, name, file));
    match object {
        Some(Ok(o)) => (diagnostics, Some(o)),
        Some(Err(errors)) => {
            diagnostics.extend(errors.iter().map(|e| e.to_diagnostic()));
            (diagnostics, None)
        }
        None => (diagnostics, None),
    }
}

/// Each step's instruction offset in a compiled table (label `n` is step `n`).
pub fn offsets(object: &ObjectFile) -> Option<Vec<u32>> {
    let unit = object.units.first()?;
    Some(unit.main()?.labels.get(..unit.steps.len())?.to_vec())
}
