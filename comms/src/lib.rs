//! The plant on the wire (docs/roc-protocol.md, docs/modbus.md).
//!
//! The codecs here are pure: bytes in, values out, no sockets and no
//! plant. The server side (which answers from the running strategy) lives
//! in `linc-serve`; the host side (`linc roc poll`) is [`roc::host`], which
//! uses a plain blocking socket because a poll table runs one command at a
//! time.

pub mod error;
pub mod modbus;
pub mod roc;
