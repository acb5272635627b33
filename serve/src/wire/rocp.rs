//! The ROC-protocol device (a FloBoss 107): each opcode of that dialect
//! answered from the running plant, with reads, writes, the clock and the
//! login going through the same rules as ROC Plus's (`roc.rs`), and errors
//! in this dialect's three-byte reply (docs/roc-protocol.md, "The ROC
//! protocol"). Store and forward that passes a frame on is the
//! connection's (`roc_server.rs`); a 24 that ends here is answered here.

use super::roc::{self, Answer, Put, RocDevice, Target};
use linc_comms::roc::ops::{code, RocError};
use linc_comms::roc::rocp::{self, clock, forward, params};
use linc_comms::roc::Frame;
use linc_engines::console::Console;
use linc_engines::strategy::trace::Trace;
use linc_format::db::{Tlp, TlpFault};
use linc_runtime::store::Store;

type Reply = Result<Vec<u8>, Vec<RocError>>;

/// One request, and what it needs to be answered.
struct Request<'a> {
    opcode: u8,
    data: &'a [u8],
    peer: &'a str,
}

/// The reply to a request frame for this device.
pub(super) fn answer(
    dev: &RocDevice,
    console: &mut Console,
    req: &Frame,
    peer: &str,
    session: Option<u8>,
    trace: Option<&mut Trace>,
) -> Answer {
    let mut log = Vec::new();
    let mut session = session;
    let (opcode, data) = if req.opcode == rocp::FORWARD {
        ends_here(dev, console, req, peer, &mut session, &mut log, trace)
    } else {
        let r = Request { opcode: req.opcode, data: &req.data, peer };
        reply_parts(req.opcode, one(dev, console, &r, &mut session, &mut log, trace))
    };
    Answer { reply: Frame { dst: req.src, src: dev.address, opcode, data }, log, session }
}

fn reply_parts(opcode: u8, r: Reply) -> (u8, Vec<u8>) {
    match r {
        Ok(data) => (opcode, data),
        Err(e) => (rocp::ERROR, rocp::error_data(e[0], opcode)),
    }
}

/// A store-and-forward request whose path ends at this device: the
/// wrapped request answered as if its host had sent it directly, and the
/// reply (or error) wrapped in the same path.
fn ends_here(
    dev: &RocDevice,
    console: &mut Console,
    req: &Frame,
    peer: &str,
    session: &mut Option<u8>,
    log: &mut Vec<String>,
    trace: Option<&mut Trace>,
) -> (u8, Vec<u8>) {
    let w = match forward::parse(&req.data) {
        Ok(w) => w,
        Err(e) => return reply_parts(rocp::FORWARD, Err(vec![e])),
    };
    let inner = if w.opcode == rocp::FORWARD {
        Err(vec![RocError::at_data(rocp::code::FORWARD_PATH, forward::PATH)])
    } else {
        let r = Request { opcode: w.opcode, data: w.data, peer };
        one(dev, console, &r, session, log, trace)
    };
    let (opcode, data) = reply_parts(w.opcode, inner);
    match forward::wrap(&w.path, opcode, &data) {
        Some(wrapped) => (rocp::FORWARD, wrapped),
        None => reply_parts(rocp::FORWARD, Err(vec![RocError::length(code::TOO_MANY_BYTES)])),
    }
}

/// Whether an opcode changes the device (refused without `--allow-writes`
/// or for a read-only operator).
fn writes(opcode: u8) -> bool {
    matches!(opcode, rocp::CLOCK_SET | rocp::TABLE_WRITE | rocp::WRITE_CONTIGUOUS | rocp::WRITE)
}

fn one(
    dev: &RocDevice,
    console: &mut Console,
    r: &Request,
    session: &mut Option<u8>,
    log: &mut Vec<String>,
    trace: Option<&mut Trace>,
) -> Reply {
    let store = &console.strategy.store;
    roc::security(store, r.opcode, *session, writes(r.opcode)).map_err(|e| vec![e])?;
    let now = console.strategy.device_seconds();
    match r.opcode {
        rocp::CONFIG => {
            rocp::exactly(r.data, 0).map_err(|e| vec![e])?;
            Ok(rocp::config_reply(!store.db.users.is_empty(), |t| roc::points_of_type(store, t)))
        }
        rocp::CLOCK_READ => {
            rocp::exactly(r.data, 0).map_err(|e| vec![e])?;
            Ok(clock::reply(&roc::clock_now(console)))
        }
        rocp::CLOCK_SET => {
            let c = clock::parse_set(r.data).map_err(|e| vec![e])?;
            dev.set_clock(console, c, r.peer, log)
        }
        rocp::LOGIN => login(store, r, session, log),
        rocp::TABLE_READ => table_read(store, r.data),
        rocp::TABLE_WRITE => table_write(dev, console, r, log, trace),
        rocp::READ_CONTIGUOUS => contiguous_read(store, r.data),
        rocp::WRITE_CONTIGUOUS => contiguous_write(dev, console, r, log, trace),
        rocp::READ => roc::read(store, r.data),
        rocp::WRITE => dev.write(console, r.data, r.peer, log, trace),
        rocp::FORWARD => Err(vec![RocError::at_data(rocp::code::FORWARD_PATH, forward::PATH)]),
        other => super::rocp_history::answer(store, other, r.data, now)
            .unwrap_or_else(|| Err(vec![RocError { code: code::INVALID_OPCODE, offset: 4 }])),
    }
}

/// Opcode 17: the ROC protocol's login is the operator ID and password,
/// optionally followed by the access level asked for (without it, the
/// operator's own); the logout form is ROC Plus's.
fn login(store: &Store, r: &Request, session: &mut Option<u8>, log: &mut Vec<String>) -> Reply {
    let mut data = r.data.to_vec();
    if data.len() == 5 {
        let id = &data[..3];
        let level = store
            .db
            .users
            .iter()
            .find(|u| u.id.as_bytes().iter().copied().eq(id.iter().copied().take_while(|&b| b != b' ' && b != 0)))
            .map_or(linc_format::db::users::MAX_LEVEL, |u| u.level);
        data.push(level);
    }
    roc::login(store, &data, r.peer, session, log)
}

/// The opcode 255 error for parameter `p` of a contiguous request.
fn contiguous_error(fault: TlpFault) -> RocError {
    let at = match fault {
        TlpFault::PointType => params::AT_TYPE,
        TlpFault::Logical => params::AT_LOGICAL,
        TlpFault::Parameter => params::AT_FIRST,
    };
    let c = match fault {
        TlpFault::PointType => code::INVALID_POINT_TYPE,
        TlpFault::Logical => code::INVALID_LOGICAL,
        TlpFault::Parameter => code::INVALID_PARAMETER,
    };
    RocError::at_data(c, at)
}

fn contiguous_tlps(c: &params::Contiguous) -> impl Iterator<Item = Tlp> + '_ {
    (0..u16::from(c.count)).map(|i| Tlp { t: u16::from(c.t), l: u16::from(c.l), p: u16::from(c.first) + i })
}

/// Opcode 167: parameters `first ..` of one point, each at its size.
fn contiguous_read(store: &Store, data: &[u8]) -> Reply {
    let c = params::parse_read(data).map_err(|e| vec![e])?;
    let mut values = Vec::new();
    for tlp in contiguous_tlps(&c) {
        let p = roc::resolve(store, tlp).map_err(|f| vec![contiguous_error(f)])?;
        roc::encode(store, &p, &mut values);
    }
    params::read_reply(&c, &values).map_err(|e| vec![e])
}

/// Opcode 166: parameters `first ..` of one point written, all or none.
fn contiguous_write(
    dev: &RocDevice,
    console: &mut Console,
    r: &Request,
    log: &mut Vec<String>,
    trace: Option<&mut Trace>,
) -> Reply {
    let (c, bytes) = params::parse_write(r.data).map_err(|e| vec![e])?;
    let store = &console.strategy.store;
    let mut sizes = Vec::with_capacity(usize::from(c.count));
    for tlp in contiguous_tlps(&c) {
        sizes.push(roc::resolve(store, tlp).map_err(|f| vec![contiguous_error(f)])?.wire.size());
    }
    let values = rocp::split_values(bytes, &sizes).map_err(|e| vec![e])?;
    let puts: Vec<Put> = contiguous_tlps(&c)
        .zip(values)
        .map(|(t, value)| Put { target: Target::Tlp(t), value, at: params::AT_TYPE, param_at: params::AT_FIRST })
        .collect();
    dev.put_all(console, &puts, r.peer, log, trace)
}

/// A table's version and the block and field of each location asked for.
type TableFields = (f32, Vec<(usize, usize)>);

/// The fields of locations `first ..` of an opcode table; a location the
/// table does not map is error 13 at the first-location byte.
fn table_fields(store: &Store, t: &params::TableRequest) -> Result<TableFields, Vec<RocError>> {
    let unmapped = || vec![RocError::at_data(rocp::code::OUTSIDE_RANGE, 1)];
    let table = store.db.opcode_tables.iter().find(|(n, _)| *n == t.table).map(|(_, tb)| tb).ok_or_else(unmapped)?;
    let slots = &table.slots[usize::from(t.first)..usize::from(t.first) + usize::from(t.count)];
    let fields = slots.iter().map(|s| s.ok_or_else(unmapped)).collect::<Result<_, _>>()?;
    Ok((table.version, fields))
}

/// Opcode 10: a configurable opcode table's values.
fn table_read(store: &Store, data: &[u8]) -> Reply {
    let t = params::parse_table_read(data).map_err(|e| vec![e])?;
    let (version, fields) = table_fields(store, &t)?;
    let mut values = Vec::new();
    for (b, f) in fields {
        let p = roc::field_param(store, b, f).ok_or_else(|| vec![RocError::at_data(code::INVALID_PARAMETER, 1)])?;
        roc::encode(store, &p, &mut values);
    }
    params::table_reply(&t, version, &values).map_err(|e| vec![e])
}

/// Opcode 11: a configurable opcode table's locations written, all or none.
fn table_write(
    dev: &RocDevice,
    console: &mut Console,
    r: &Request,
    log: &mut Vec<String>,
    trace: Option<&mut Trace>,
) -> Reply {
    let (t, bytes) = params::parse_table_write(r.data).map_err(|e| vec![e])?;
    let store = &console.strategy.store;
    let (_, fields) = table_fields(store, &t)?;
    let sizes: Vec<usize> =
        fields.iter().map(|&(b, f)| roc::field_param(store, b, f).map_or(0, |p| p.wire.size())).collect();
    let values = rocp::split_values(bytes, &sizes).map_err(|e| vec![e])?;
    let puts: Vec<Put> = fields
        .iter()
        .zip(values)
        .map(|(&(b, f), value)| Put { target: Target::Field(b, f), value, at: 1, param_at: 1 })
        .collect();
    dev.put_all(console, &puts, r.peer, log, trace)
}
