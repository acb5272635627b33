//! The plant on the wire: ROC Plus and Modbus TCP servers beside the
//! monitor (docs/roc-protocol.md, docs/modbus.md). The network side reads
//! frames and hands each to the plant thread, which answers between scans;
//! a scan never waits for a client and a client never sees a half-scan.

pub mod modbus;
pub mod modbus_server;
pub mod net;
pub mod roc;
pub mod roc_logs;
pub mod roc_server;

pub use net::{Limits, Log};
