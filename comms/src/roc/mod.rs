//! ROC Plus: frames with CRC-16/ARC, TLP-addressed parameters and the
//! opcodes a host uses (docs/roc-protocol.md).

pub mod crc;
pub mod frame;
pub mod history;
pub mod host;
pub mod logs;
pub mod ops;
pub mod value;

pub use frame::{Address, Deframer, Frame};
