//! The Modbus device: requests answered from the plant through the
//! database's register map, on the plant's thread between scans
//! (docs/modbus.md). Writes go through the console's rules, all or none.

use linc_comms::modbus::{Exception as ExceptionCode, Request, Response};
use linc_engines::console::fields::Addr;
use linc_engines::console::Console;
use linc_engines::strategy::trace::Trace;
use linc_format::db::modbus::{MbEntry, MbType, ModbusMap, Table};
use linc_runtime::store::{Cell, Store};

/// What the device is.
#[derive(Clone, Copy, Debug)]
pub struct ModbusDevice {
    pub allow_writes: bool,
}

/// A reply and what to log about the request.
pub struct MbAnswer {
    pub reply: Result<Response, ExceptionCode>,
    /// The request's function code, which the reply repeats.
    pub function: u8,
    pub log: Vec<String>,
}

fn cell_of(store: &Store, e: &MbEntry) -> u32 {
    store.first[e.block] + e.field as u32
}

/// A bit's value now.
fn bit(store: &Store, e: &MbEntry) -> bool {
    match (&store.cells[cell_of(store, e) as usize], e.bit) {
        (Cell::Bits { v, .. }, Some(b)) => (v >> b) & 1 == 1,
        (Cell::Bool(b), _) => *b,
        (Cell::Int(i), _) => *i != 0,
        _ => false,
    }
}

/// Register `off` of an entry now: a REAL's high word first unless the
/// map says low first; an INT held at the ends of a register's range.
fn register(store: &Store, e: &MbEntry, off: u32) -> u16 {
    match &store.cells[cell_of(store, e) as usize] {
        Cell::Real(x) => {
            let bits = x.to_bits();
            let high_half = (off == 0) != e.low_first;
            if high_half {
                (bits >> 16) as u16
            } else {
                bits as u16
            }
        }
        Cell::Int(i) => (*i).clamp(i32::from(i16::MIN), i32::from(i16::MAX)) as i16 as u16,
        Cell::Bits { v, .. } => *v,
        Cell::Enum { idx } => *idx,
        _ => 0,
    }
}

/// The entries covering `n` addresses from `start` of `table`, each with
/// the offset in it; exception 02 when one is unmapped.
fn span(map: &ModbusMap, table: Table, start: u16, n: u16) -> Result<Vec<(&MbEntry, u32)>, ExceptionCode> {
    (0..n)
        .map(|i| start.checked_add(i).and_then(|a| map.at(table, a)).ok_or(ExceptionCode::IllegalDataAddress))
        .collect()
}

/// The entries a write of `n` values from `start` of `table` covers.
fn mapped(store: &Store, table: Table, start: u16, n: usize) -> Result<Vec<(&MbEntry, u32)>, ExceptionCode> {
    let map = store.db.modbus.as_ref().ok_or(ExceptionCode::IllegalDataAddress)?;
    span(map, table, start, n.try_into().unwrap_or(u16::MAX))
}

impl ModbusDevice {
    /// The reply to a request; `peer` names the client in the log.
    pub fn answer(&self, console: &mut Console, req: &Request, peer: &str, trace: Option<&mut Trace>) -> MbAnswer {
        let mut log = Vec::new();
        let reply = self.reply(console, req, peer, &mut log, trace);
        MbAnswer { reply, function: req.function(), log }
    }

    /// The reply when answering failed inside linc (a bug): exception 04
    /// and a log line.
    pub fn internal_error(&self, req: &Request, peer: &str) -> MbAnswer {
        let log = vec![format!("modbus {peer}: internal error answering function {}: exception 04", req.function())];
        MbAnswer { reply: Err(ExceptionCode::ServerDeviceFailure), function: req.function(), log }
    }

    fn reply(
        &self,
        console: &mut Console,
        req: &Request,
        peer: &str,
        log: &mut Vec<String>,
        trace: Option<&mut Trace>,
    ) -> Result<Response, ExceptionCode> {
        let store = &console.strategy.store;
        let Some(map) = store.db.modbus.as_ref() else { return Err(ExceptionCode::IllegalDataAddress) };
        let bits = |table, a, n| -> Result<Vec<bool>, ExceptionCode> {
            Ok(span(map, table, a, n)?.into_iter().map(|(e, _)| bit(store, e)).collect())
        };
        let regs = |table, a, n| -> Result<Vec<u16>, ExceptionCode> {
            Ok(span(map, table, a, n)?.into_iter().map(|(e, off)| register(store, e, off)).collect())
        };
        // The decoder checked every count against the protocol's limits.
        let n16 = |n: usize| n as u16;
        match req {
            Request::ReadCoils(a, n) => bits(Table::Coil, *a, *n).map(Response::Bits),
            Request::ReadDiscreteInputs(a, n) => bits(Table::Discrete, *a, *n).map(Response::Bits),
            Request::ReadHoldingRegisters(a, n) => regs(Table::Holding, *a, *n).map(Response::Registers),
            Request::ReadInputRegisters(a, n) => regs(Table::Input, *a, *n).map(Response::Registers),
            Request::WriteSingleCoil(a, v) => self
                .write_bits(console, *a, &[*v], peer, log, trace)
                .map(|_| Response::Echo(*a, if *v { 0xFF00 } else { 0 })),
            Request::WriteMultipleCoils(a, vs) => {
                self.write_bits(console, *a, vs, peer, log, trace).map(|_| Response::Echo(*a, n16(vs.len())))
            }
            Request::WriteSingleRegister(a, v) => {
                self.write_regs(console, *a, &[*v], peer, log, trace).map(|_| Response::Echo(*a, *v))
            }
            Request::WriteMultipleRegisters(a, vs) => {
                self.write_regs(console, *a, vs, peer, log, trace).map(|_| Response::Echo(*a, n16(vs.len())))
            }
        }
    }

    /// Coils from `start`: each must be mapped, then written all or none.
    fn write_bits(
        &self,
        console: &mut Console,
        start: u16,
        values: &[bool],
        peer: &str,
        log: &mut Vec<String>,
        trace: Option<&mut Trace>,
    ) -> Result<(), ExceptionCode> {
        let store = &console.strategy.store;
        let entries = mapped(store, Table::Coil, start, values.len())?;
        let mut cells = Vec::with_capacity(values.len());
        for ((e, _), &on) in entries.iter().zip(values) {
            let cell = cell_of(store, e);
            let new = match (&store.cells[cell as usize], e.bit) {
                (Cell::Bits { v, width }, Some(b)) => {
                    Cell::Bits { v: if on { v | 1 << b } else { v & !(1 << b) }, width: *width }
                }
                (Cell::Int(_), _) => Cell::Int(i32::from(on)),
                _ => Cell::Bool(on),
            };
            cells.push((Addr { cell, bit: e.bit }, new));
        }
        self.commit(console, cells, peer, log, trace)
    }

    /// Holding registers from `start`: a REAL needs both its registers in
    /// the one request; a value must fit its field.
    fn write_regs(
        &self,
        console: &mut Console,
        start: u16,
        values: &[u16],
        peer: &str,
        log: &mut Vec<String>,
        trace: Option<&mut Trace>,
    ) -> Result<(), ExceptionCode> {
        let store = &console.strategy.store;
        let entries = mapped(store, Table::Holding, start, values.len())?;
        let mut cells = Vec::new();
        let mut i = 0;
        while i < entries.len() {
            let (e, off) = entries[i];
            let cell = cell_of(store, e);
            let ty = &store.db.block_template(e.block).fields[e.field].ty;
            let new = match e.ty {
                MbType::Real if off != 0 || i + 1 >= entries.len() => Err("half a REAL".to_string()),
                MbType::Real => {
                    let (first, second) = (u32::from(values[i]), u32::from(values[i + 1]));
                    let bits = if e.low_first { second << 16 | first } else { first << 16 | second };
                    i += 1;
                    let x = f32::from_bits(bits);
                    if x.is_finite() {
                        Ok(Cell::Real(x))
                    } else {
                        Err(format!("{x}"))
                    }
                }
                _ => int_cell(ty, values[i]).ok_or_else(|| format!("the register value {}", values[i])),
            };
            match new {
                Ok(new) => cells.push((Addr { cell, bit: None }, new)),
                Err(sent) => {
                    super::refuse_value(console, &format!("modbus {peer}"), cell, &sent, log, trace);
                    return Err(ExceptionCode::IllegalDataValue);
                }
            }
            i += 1;
        }
        self.commit(console, cells, peer, log, trace)
    }

    /// Writes the cells through the console's rules, all or none: writes
    /// off, a read-only or a forced field refuse the whole request
    /// (exception 04, the device can't do it).
    fn commit(
        &self,
        console: &mut Console,
        cells: Vec<(Addr, Cell)>,
        peer: &str,
        log: &mut Vec<String>,
        trace: Option<&mut Trace>,
    ) -> Result<(), ExceptionCode> {
        let client = format!("modbus {peer}");
        if !self.allow_writes {
            log.push(format!("{client}: write refused: this server is read-only (--allow-writes)"));
            return Err(ExceptionCode::IllegalFunction);
        }
        super::commit(console, &cells, &client, log, trace).map_err(|_| ExceptionCode::ServerDeviceFailure)
    }
}

/// A register written to a whole-number field: an INT takes it as a
/// signed 16-bit value, a BITS or ENUM field as unsigned; `None` when the
/// field can't hold it.
fn int_cell(ty: &linc_format::db::FieldType, w: u16) -> Option<Cell> {
    let v = if matches!(ty, linc_format::db::FieldType::Int) { i64::from(w as i16) } else { i64::from(w) };
    super::whole_cell(ty, v)
}
