//! The plant on the wire: ROC Plus (over TCP and serial lines) and Modbus
//! TCP servers beside the monitor (docs/roc-protocol.md, docs/modbus.md).
//! The network side reads frames and hands each to the plant thread, which
//! answers between scans; a scan never waits for a client and a client
//! never sees a half-scan.

pub mod modbus;
pub(crate) mod modbus_server;
pub(crate) mod net;
pub mod roc;
mod roc_logs;
pub(crate) mod roc_server;
mod rocp;
mod rocp_history;
pub(crate) mod serial;

pub use net::{Limits, Log};

use linc_engines::console::fields::Addr;
use linc_engines::console::Console;
use linc_engines::strategy::trace::Trace;
use linc_format::db::FieldType;
use linc_format::Code;
use linc_runtime::store::Cell;

/// Why the console's rules refused a client's write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Refused {
    Forced,
    ReadOnly,
}

/// Writes `cells` for a client on the wire (`client` is `roc ADDR` or
/// `modbus ADDR`) through the console's `M` rules, all or none: each
/// write is logged and traced with the client's name, or the refusal is,
/// with the index of the cell refused and why.
pub(crate) fn commit(
    console: &mut Console,
    cells: &[(Addr, Cell)],
    client: &str,
    log: &mut Vec<String>,
    mut trace: Option<&mut Trace>,
) -> Result<(), (usize, Refused)> {
    let now = console.strategy.elapsed_us();
    if let Err((i, e)) = console.modify_all(cells) {
        let why = if e.code == Code::C0009 { Refused::Forced } else { Refused::ReadOnly };
        log.push(format!("{client}: write refused: {}", e.message));
        if let Some(t) = trace {
            let text = if why == Refused::Forced { "forced" } else { "read-only" };
            t.client_refused(&console.strategy.store, now, client, cells[i].0.cell, text);
        }
        return Err((i, why));
    }
    let store = &console.strategy.store;
    for (a, _) in cells {
        log.push(format!("{client}: wrote {} = {}", store.describe(a.cell), store.show(a.cell)));
        if let Some(t) = trace.as_deref_mut() {
            t.client_write(store, now, client, a.cell);
        }
    }
    Ok(())
}

/// A write refused for its value (the field can't hold what the client
/// sent: out of range, not finite, half a REAL), logged and traced like
/// the refusals [`commit`] makes, so every refused write leaves a line.
pub(crate) fn refuse_value(
    console: &Console,
    client: &str,
    cell: u32,
    sent: &str,
    log: &mut Vec<String>,
    trace: Option<&mut Trace>,
) {
    let store = &console.strategy.store;
    log.push(format!("{client}: write refused: {} can't hold {sent}", store.describe(cell)));
    if let Some(t) = trace {
        t.client_refused(store, console.strategy.elapsed_us(), client, cell, "value");
    }
}

/// The cell a whole number off the wire makes for a field of `ty`: an INT
/// within 32 bits, a BOOL 0 or 1, a BITS field within its width, an ENUM
/// one of its indices; `None` when the field can't hold it.
pub(crate) fn whole_cell(ty: &FieldType, v: i64) -> Option<Cell> {
    Some(match ty {
        FieldType::Int => Cell::Int(i32::try_from(v).ok()?),
        FieldType::Bool => Cell::Bool(match v {
            0 => false,
            1 => true,
            _ => return None,
        }),
        FieldType::Bits { width, .. } => {
            (0..1 << width).contains(&v).then_some(Cell::Bits { v: v as u16, width: *width })?
        }
        FieldType::Enum(names) => {
            let i = usize::try_from(v).ok().filter(|&i| i < names.len())?;
            Cell::Enum { idx: i as u16 }
        }
        _ => return None,
    })
}
