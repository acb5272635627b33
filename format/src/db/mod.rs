//! The function-block database: templates (block types), blocks and aliases.
//!
//! A database is loaded from the JSON contract described in `docs/database.md`.
//! Every database starts from the built-in template library (`builtin.json`),
//! and a file may add templates or override built-in ones by name. Names are
//! case-insensitive everywhere, as in LIN.

mod fields;
mod json;
pub mod modbus;
mod names;
mod period;
pub mod programs;
mod roc;
pub mod roc_device;
mod schema;
pub mod tree;
pub mod users;

pub use json::{without_bom, DbError, MAX_CELLS};
pub use period::{duration_seconds, time_constant, MAX_PERIOD, MIN_PERIOD};
pub use roc::{same_point, Device, RocType, Tlp, TlpFault};
pub use schema::{Alias, Block, Database, FieldDef, FieldType, InitValue, Task, Template};
