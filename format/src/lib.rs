//! What the compiler and the runtime share, beneath both: the instruction
//! set ([`isa`]), the `.sto` object format ([`object`], [`wire`]) and why
//! one is refused ([`errors`]), the function-block database schema and its
//! JSON ([`db`]), and the text form of values ([`text`]). The compiler
//! writes objects against a database with these and never needs the VM,
//! the verifier or the engines (ADR 0013).

pub mod code;
pub mod db;
pub mod errors;
pub mod isa;
pub mod object;
pub mod text;
pub mod wire;
pub mod xml;

pub use code::Code;
pub use db::{Database, DbError, FieldDef, FieldType, Template};
pub use errors::LoadError;
pub use object::{ObjectFile, MAX_CHART_DEPTH};

/// Most bytes one string value may hold (a field, a constant, a value on
/// the VM's string stack): the database loader, the console and the VM
/// refuse longer ones.
pub const MAX_STRING: usize = 65_535;
