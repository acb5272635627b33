//! The ROC device, and ROC Plus's opcodes (the ROC protocol's are in
//! `rocp.rs`): frames answered from the running plant, on the
//! plant's thread between scans (docs/roc-protocol.md). Reads and writes go
//! through the console's rules, so a host can do what `M` can and no more.

use linc_comms::roc::ops::{self, code, Clock, RocError};
use linc_comms::roc::value::{self, Value};
use linc_comms::roc::{Address, Frame};
use linc_engines::console::fields::Addr;
use linc_engines::console::Console;
use linc_engines::strategy::trace::Trace;
use linc_format::db::{FieldType, RocType, Tlp, TlpFault};
use linc_runtime::store::{Cell, Store};

/// Which ROC dialect a device speaks: the database's family decides
/// (docs/roc-protocol.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dialect {
    /// ROC Plus, the ROC800's.
    RocPlus,
    /// The ROC protocol of the FloBoss 100- and ROC300-series.
    Roc,
}

impl Dialect {
    pub fn of(device: linc_format::db::Device) -> Dialect {
        match device {
            linc_format::db::Device::Roc800 => Dialect::RocPlus,
            linc_format::db::Device::Fb107 => Dialect::Roc,
        }
    }

    /// How the startup line names it.
    pub fn name(self) -> &'static str {
        match self {
            Dialect::RocPlus => "ROC Plus",
            Dialect::Roc => "ROC protocol",
        }
    }
}

/// What the device is.
#[derive(Clone, Copy, Debug)]
pub struct RocDevice {
    /// The unit and group it answers to.
    pub address: Address,
    /// Whether hosts may write (`--allow-writes`).
    pub allow_writes: bool,
    pub dialect: Dialect,
}

/// A reply and what to log about the request.
pub struct Answer {
    pub reply: Frame,
    pub log: Vec<String>,
    /// The connection's login after the request: the access level of the
    /// operator logged in, if one is.
    pub session: Option<u8>,
}

/// A parameter a TLP names: its cell, how it travels and its field's type.
pub(super) struct Param<'a> {
    pub cell: u32,
    pub wire: RocType,
    ty: &'a FieldType,
}

/// The parameter a TLP names; a field of a type with no ROC form is an
/// invalid parameter.
pub(super) fn resolve(store: &Store, tlp: Tlp) -> Result<Param<'_>, TlpFault> {
    let (block, field) = store.db.tlp_parts(tlp)?;
    field_param(store, block, field).ok_or(TlpFault::Parameter)
}

/// A block's field as a parameter, if it has a ROC form.
pub(super) fn field_param(store: &Store, block: usize, field: usize) -> Option<Param<'_>> {
    let wire = store.db.roc_type(block, field)?;
    let ty = &store.db.block_template(block).fields[field].ty;
    Some(Param { cell: store.first[block] + field as u32, wire, ty })
}

/// A parameter's value now, as the wire carries it.
pub(super) fn encode(store: &Store, p: &Param, out: &mut Vec<u8>) {
    value::encode(p.wire, &wire_value(&store.cells[p.cell as usize]), out);
}

/// Where a write goes and the bytes of its value, with the offsets its
/// errors point at: `at` (forced) and `param_at` (range, read-only).
pub(super) struct Put<'a> {
    pub target: Target,
    pub value: &'a [u8],
    pub at: usize,
    pub param_at: usize,
}

/// A parameter by TLP, or a block's field (an opcode table's location).
#[derive(Clone, Copy)]
pub(super) enum Target {
    Tlp(Tlp),
    Field(usize, usize),
}

/// A cell's value as the wire carries it.
fn wire_value(cell: &Cell) -> Value {
    match cell {
        Cell::Real(x) => Value::Real(*x),
        Cell::Int(i) => Value::Int(i64::from(*i)),
        Cell::Bool(b) => Value::Int(i64::from(*b)),
        Cell::Bits { v, .. } => Value::Int(i64::from(*v)),
        Cell::Enum { idx } => Value::Int(i64::from(*idx)),
        Cell::Text(t) | Cell::Bseq(t) | Cell::Wstr(t) => Value::Text(t.clone()),
        Cell::Alarms(_) => Value::Int(0),
    }
}

/// The cell a value off the wire makes for a field of `ty`; `None` when the
/// field can't hold it (out of its range, not finite, not an enumeration
/// value).
fn field_value(ty: &FieldType, v: Value) -> Option<Cell> {
    match (ty, v) {
        (FieldType::Real, Value::Real(x)) if x.is_finite() => Some(Cell::Real(x)),
        (FieldType::Real, Value::Int(i)) => Some(Cell::Real(i as f32)),
        (FieldType::String, Value::Text(t)) => Some(Cell::Text(t)),
        (_, Value::Int(i)) => super::whole_cell(ty, i),
        _ => None,
    }
}

impl RocDevice {
    /// The reply to a request frame addressed to this device; `peer` names
    /// the client in the log.
    pub fn answer(
        &self,
        console: &mut Console,
        req: &Frame,
        peer: &str,
        session: Option<u8>,
        trace: Option<&mut Trace>,
    ) -> Answer {
        if self.dialect == Dialect::Roc {
            return super::rocp::answer(self, console, req, peer, session, trace);
        }
        let mut log = Vec::new();
        let mut session = session;
        let writes = req.opcode == ops::WRITE || req.opcode == ops::CLOCK_SET;
        let result = match security(&console.strategy.store, req.opcode, session, writes) {
            Err(e) => Err(vec![e]),
            Ok(()) => self.opcode(console, req, peer, &mut session, &mut log, trace),
        };
        let (opcode, data) = match result {
            Ok(data) => (req.opcode, data),
            Err(errors) => (ops::ERROR, ops::error_data(&errors)),
        };
        Answer { reply: Frame { dst: req.src, src: self.address, opcode, data }, log, session }
    }

    fn opcode(
        &self,
        console: &mut Console,
        req: &Frame,
        peer: &str,
        session: &mut Option<u8>,
        log: &mut Vec<String>,
        trace: Option<&mut Trace>,
    ) -> Result<Vec<u8>, Vec<RocError>> {
        match req.opcode {
            ops::LOGIN => login(&console.strategy.store, &req.data, peer, session, log),
            ops::READ => read(&console.strategy.store, &req.data),
            ops::WRITE => self.write(console, &req.data, peer, log, trace),
            ops::CLOCK_READ => clock_read(console, &req.data),
            ops::CLOCK_SET => self.clock_set(console, &req.data, peer, log),
            ops::CONFIG => config(&console.strategy.store, &req.data),
            ops::ALARMS | ops::EVENTS => {
                super::roc_logs::log(&console.strategy.store, &req.data, req.opcode == ops::ALARMS)
            }
            ops::HISTORY_POINT => {
                super::roc_logs::point(&console.strategy.store, &req.data, console.strategy.device_seconds())
            }
            ops::HISTORY_POINTS => {
                super::roc_logs::points(&console.strategy.store, &req.data, console.strategy.device_seconds())
            }
            _ => Err(vec![RocError { code: code::INVALID_OPCODE, offset: 4 }]),
        }
    }

    /// The reply when answering failed inside linc (a bug): error 50,
    /// general error, and a log line.
    pub fn internal_error(&self, req: &Frame, peer: &str) -> Answer {
        let e = RocError { code: code::GENERAL, offset: 4 };
        let data = match self.dialect {
            Dialect::RocPlus => ops::error_data(&[e]),
            Dialect::Roc => linc_comms::roc::rocp::error_data(e, req.opcode),
        };
        let log = vec![format!("roc {peer}: internal error answering opcode {}: refused with error 50", req.opcode)];
        Answer { reply: Frame { dst: req.src, src: self.address, opcode: ops::ERROR, data }, log, session: None }
    }

    /// Opcode 181: every value is checked (the TLP, its size, the field's
    /// range, read-only, forced) before any is written: all or nothing.
    pub(super) fn write(
        &self,
        console: &mut Console,
        data: &[u8],
        peer: &str,
        log: &mut Vec<String>,
        trace: Option<&mut Trace>,
    ) -> Result<Vec<u8>, Vec<RocError>> {
        let store = &console.strategy.store;
        let writes = ops::parse_write(data, |t| resolve(store, t).map(|p| p.wire.size())).map_err(|e| vec![e])?;
        let puts: Vec<Put> = writes
            .iter()
            .map(|w| Put { target: Target::Tlp(w.tlp), value: w.value, at: w.at, param_at: w.at + 2 })
            .collect();
        self.put_all(console, &puts, peer, log, trace)
    }

    /// Writes every value or none: each is checked (where it goes, the
    /// field's range, read-only, forced) before any is written, and the
    /// first refused is the error, at the byte its [`Put`] names.
    pub(super) fn put_all(
        &self,
        console: &mut Console,
        puts: &[Put],
        peer: &str,
        log: &mut Vec<String>,
        trace: Option<&mut Trace>,
    ) -> Result<Vec<u8>, Vec<RocError>> {
        if !self.allow_writes {
            return Err(vec![RocError { code: code::SECURITY, offset: 4 }]);
        }
        let store = &console.strategy.store;
        let mut cells = Vec::with_capacity(puts.len());
        for put in puts {
            let p = match put.target {
                Target::Tlp(t) => resolve(store, t).map_err(|f| vec![ops::tlp_error(f, put.at)])?,
                Target::Field(b, f) => field_param(store, b, f)
                    .ok_or_else(|| vec![RocError::at_data(code::INVALID_PARAMETER, put.param_at)])?,
            };
            let Some(new) = value::decode(p.wire, put.value).and_then(|v| field_value(p.ty, v)) else {
                let sent = format!("the bytes {:02X?}", put.value);
                super::refuse_value(console, &format!("roc {peer}"), p.cell, &sent, log, trace);
                return Err(vec![RocError::at_data(code::PARAMETER_RANGE, put.param_at)]);
            };
            cells.push((Addr { cell: p.cell, bit: None }, new));
        }
        if let Err((i, why)) = super::commit(console, &cells, &format!("roc {peer}"), log, trace) {
            return Err(vec![match why {
                super::Refused::Forced => RocError::at_data(code::INVALID_STATE_FOR_WRITE, puts[i].at),
                super::Refused::ReadOnly => RocError::at_data(code::READ_ONLY, puts[i].param_at),
            }]);
        }
        Ok(Vec::new())
    }

    /// Opcode 8: the device clock set to the host's time.
    fn clock_set(
        &self,
        console: &mut Console,
        data: &[u8],
        peer: &str,
        log: &mut Vec<String>,
    ) -> Result<Vec<u8>, Vec<RocError>> {
        let c = Clock::parse_set(data).map_err(|e| vec![e])?;
        self.set_clock(console, c, peer, log)
    }

    /// Sets the device clock (opcode 8 in either dialect), if writes are on.
    pub(super) fn set_clock(
        &self,
        console: &mut Console,
        c: Clock,
        peer: &str,
        log: &mut Vec<String>,
    ) -> Result<Vec<u8>, Vec<RocError>> {
        if !self.allow_writes {
            return Err(vec![RocError { code: code::SECURITY, offset: 4 }]);
        }
        let days =
            linc_stdlib::functions::datetime::days_from_civil(i64::from(c.year), u32::from(c.month), u32::from(c.day));
        let local = days * 86_400 + i64::from(c.hour) * 3600 + i64::from(c.minute) * 60 + i64::from(c.second);
        console.strategy.set_device_seconds(local);
        log.push(format!("roc {peer}: set the clock to {}", console.strategy.now_text()));
        Ok(Vec::new())
    }
}

/// When the database names operators, a connection must log in (opcode
/// 17) before anything but the system configuration (6), and an operator
/// of access level 0 may only read: error 20 (security) otherwise.
pub(super) fn security(store: &Store, opcode: u8, session: Option<u8>, writes: bool) -> Result<(), RocError> {
    if store.db.users.is_empty() || opcode == ops::LOGIN || opcode == ops::CONFIG {
        return Ok(());
    }
    match session {
        Some(level) if level > 0 || !writes => Ok(()),
        _ => Err(RocError { code: code::SECURITY, offset: 4 }),
    }
}

/// Opcode 17: a login checks the operator ID and password (error 21) and
/// the access level asked for against the operator's (error 63); a logout
/// needs the ID, the password and the text `LOGOUT` (error 77). A database
/// with no operators takes any login.
pub(super) fn login(
    store: &Store,
    data: &[u8],
    peer: &str,
    session: &mut Option<u8>,
    log: &mut Vec<String>,
) -> Result<Vec<u8>, Vec<RocError>> {
    let login = ops::Login::parse(data).map_err(|e| vec![e])?;
    let (id, password) = match login {
        ops::Login::In { id, password, .. } | ops::Login::Out { id, password, .. } => (id, password),
    };
    let user = store
        .db
        .users
        .iter()
        .find(|u| u.id.as_bytes().iter().copied().eq(id.iter().copied().take_while(|&b| b != b' ' && b != 0)));
    let users = !store.db.users.is_empty();
    if users && user.is_none_or(|u| u.password != password) {
        log.push(format!("roc {peer}: login refused for `{}`", String::from_utf8_lossy(&id).trim_end()));
        return Err(vec![RocError::at_data(code::INVALID_LOGON, 0)]);
    }
    match login {
        ops::Login::In { level, .. } => {
            if user.is_some_and(|u| level > u.level) {
                return Err(vec![RocError::at_data(code::ACCESS_LEVEL, 5)]);
            }
            *session = Some(level);
            log.push(format!("roc {peer}: `{}` logged in at level {level}", String::from_utf8_lossy(&id).trim_end()));
        }
        ops::Login::Out { text, .. } => {
            if &text != ops::LOGOUT {
                return Err(vec![RocError::at_data(code::INVALID_LOGOFF, 5)]);
            }
            *session = None;
        }
    }
    Ok(Vec::new())
}

/// Opcode 180: each TLP's value; the first TLP that names nothing is the
/// error.
pub(super) fn read(store: &Store, data: &[u8]) -> Result<Vec<u8>, Vec<RocError>> {
    let tlps = ops::parse_read(data).map_err(|e| vec![e])?;
    let mut values = Vec::with_capacity(tlps.len());
    for (i, t) in tlps.iter().enumerate() {
        let p = resolve(store, *t).map_err(|f| vec![ops::tlp_error(f, 1 + 3 * i)])?;
        let mut bytes = Vec::with_capacity(p.wire.size());
        encode(store, &p, &mut bytes);
        values.push((*t, bytes));
    }
    ops::read_reply(values.iter().map(|(t, b)| (*t, b.as_slice()))).map_err(|e| vec![e])
}

/// Opcode 7: the device clock.
fn clock_read(console: &Console, data: &[u8]) -> Result<Vec<u8>, Vec<RocError>> {
    if !data.is_empty() {
        return Err(vec![RocError::length(code::TOO_MANY_BYTES)]);
    }
    Ok(clock_now(console).reply())
}

/// The device clock as opcodes 7 carry it.
pub(super) fn clock_now(console: &Console) -> Clock {
    let now = console.strategy.device_seconds();
    let c = linc_runtime::roc::civil(now);
    let weekday = linc_runtime::roc::day_of_week(now) as u8;
    Clock {
        second: c.second as u8,
        minute: c.minute as u8,
        hour: c.hour as u8,
        day: c.day as u8,
        month: c.month as u8,
        year: u16::try_from(c.year).unwrap_or(0),
        weekday,
    }
}

/// Opcode 6: the system configuration, with the number of points of each
/// point type the database's device family numbers from 60.
fn config(store: &Store, data: &[u8]) -> Result<Vec<u8>, Vec<RocError>> {
    if !data.is_empty() {
        return Err(vec![RocError::length(code::TOO_MANY_BYTES)]);
    }
    Ok(ops::config_reply(0, |t| points_of_type(store, t)))
}

/// How many points of a type the database has (at most 255).
pub(super) fn points_of_type(store: &Store, t: u8) -> u8 {
    let db = &store.db;
    match db.point_template(u16::from(t)) {
        Some(tp) => db.blocks.iter().filter(|b| b.template == tp).count().min(255) as u8,
        None => 0,
    }
}
