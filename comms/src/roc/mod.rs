//! The two ROC dialects (docs/roc-protocol.md): ROC Plus, the ROC800's
//! (`ops`, `logs`, `history`), and the ROC protocol of the FloBoss 100- and
//! ROC300-series (`rocp`). Both frame with CRC-16/ARC and address
//! parameters by TLP; `host` is the communication module's master side.

pub mod crc;
pub mod frame;
pub mod history;
pub mod host;
pub mod logs;
pub mod ops;
pub mod rocp;
pub mod value;

pub use frame::{Address, Deframer, Frame};
