//! The host side of ROC Plus, as the communication module's master runs it
//! (`003_…` §4.4 and §6): a command list polled against a device, with a
//! module database of 16-bit words holding the TLPs, the values read and
//! the values to write (docs/roc-host.md).

pub mod commands;
pub mod poll;
pub mod serial;
pub mod tcp;
pub mod words;

pub use commands::Command;
pub use poll::{status_text, Host, Link};
pub use serial::SerialLink;
pub use tcp::TcpLink;
pub use words::Words;
