//! The linc runtime: the function-block database the compiler resolves names
//! against and (later) the instruction set, object format and VM that run
//! compiled actions against it.

pub mod db;

pub use db::{Database, DbError, FieldDef, FieldType, Template};
