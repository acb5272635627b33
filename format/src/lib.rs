//! What the compiler and the runtime share, beneath both: the instruction
//! set ([`isa`]), the `.sto` object format ([`object`], [`wire`]) and why
//! one is refused ([`errors`]), the function-block database schema and its
//! JSON ([`db`]), the text form of values ([`text`]) and the
//! rules every input file is read by ([`input`]). The compiler
//! writes objects against a database with these and never needs the VM,
//! the verifier or the engines (ADR 0013).

/// The registry of diagnostic codes, each with its page.
pub mod code;
/// The function-block database: templates, blocks, aliases, tasks, the JSON loader.
pub mod db;
/// Why an object file is refused.
pub mod errors;
/// Reading an input file with bounds: a regular file, of limited size.
pub mod input;
/// The instruction set, declared once (ADR 0004).
pub mod isa;
/// The `.sto` object format and its CRC-32.
pub mod object;
/// The text form of values (constants, timestamps).
pub mod text;
/// The object format's encoding of each table.
pub mod wire;
/// Escaping text for the XML reports.
pub mod xml;

pub use code::Code;
pub use db::{Database, DbError, FieldDef, FieldType, Template};
pub use errors::LoadError;
pub use object::{ObjectFile, MAX_CHART_DEPTH};

/// Most bytes one string value may hold (a field, a constant, a value on
/// the VM's string stack): the database loader, the console and the VM
/// refuse longer ones.
pub const MAX_STRING: usize = 65_535;
