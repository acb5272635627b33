//! The host side of the ROC protocol and ROC Plus, as the communication
//! module's master runs it (`003_…` §4.4 and §6): a command list polled
//! against a device, with a module database of 16-bit words holding what
//! each command sends and what its reply brought (docs/roc-host.md).

pub mod commands;
mod exchange;
pub mod layouts;
pub mod poll;
pub mod serial;
pub mod tcp;
pub mod words;

#[cfg(test)]
mod tests;

pub use commands::{Command, Protocol};
pub use poll::{status_text, Host, Link};
pub use serial::SerialLink;
pub use tcp::TcpLink;
pub use words::Words;
