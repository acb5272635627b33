//! The plant on the wire (docs/roc-protocol.md, docs/modbus.md).
//!
//! The codecs here are pure: bytes in, values out, no sockets and no
//! plant. The server side (which answers from the running strategy) lives
//! in `linc-serve`; the host side (`linc roc poll`) is [`roc::host`], which
//! uses a plain blocking socket (or serial port) because a poll table runs
//! one command at a time.

/// A comms file's error, located in the file.
pub mod error;
/// Modbus TCP framing and PDUs (ADR 0019).
pub mod modbus;
/// ROC Plus frames, opcodes and values, and the ROC host.
pub mod roc;
/// A serial line's settings (baud, data bits, parity, stop bits).
pub mod serial;
