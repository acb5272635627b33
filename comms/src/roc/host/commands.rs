//! The host's command list (`003_…` §4.4.2 and §6.1): one row per
//! command, in the manual's columns
//! `PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD`.
//!
//! Every word range a command reads or surely writes is checked here, so
//! that running it cannot index past the table: what a reply may add
//! beyond that (the values of a 10, 130 or 180) is checked when it
//! arrives (status 2).

use super::layouts::{self, op, word_len};
use super::words::SIZE;
use crate::error::FileError;
use crate::roc::ops;
use linc_format::Code;

/// The columns, as the manual heads them.
pub const COLUMNS: [&str; 10] =
    ["PORT", "SLV UNIT", "SLV GROUP", "OP CODE", "CNT", "SRC ADDR", "DEST ADDR", "TYPE", "POLL TIME", "STORE FWD"];

/// Most commands in a list (the module's 20 blocks of five).
pub const MAX_COMMANDS: usize = 100;

/// Words of a store-and-forward communication path (§6.3): the host's
/// unit and group, then four destinations.
pub const PATH_WORDS: usize = 10;

/// The protocol the polled device speaks. The module's list is the ROC
/// protocol's (FloBoss 100-series, ROC300, FloBoss 407); a ROC Plus
/// device (ROC800) shares only the clock set and opcodes 180 and 181, and
/// has no store and forward, so the list is checked against it when read
/// rather than failing at the device.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Protocol {
    #[default]
    Roc,
    RocPlus,
}

/// One command of the list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Command {
    /// 0 disabled; 1 or 2 continuous on that port; 9 or 10 control mode.
    pub port: u16,
    pub unit: u8,
    pub group: u8,
    /// 8, 10, 120, 128, 130, 180 or 181 (docs/roc-host.md).
    pub opcode: u8,
    /// 180, 181: parameters; 8: bytes of the clock to send; 10, 128: 3;
    /// 130: 4; 120: 0.
    pub count: u16,
    /// First word of what the request sends (TLPs, three words each, for
    /// 180 and 181).
    pub src: u16,
    /// Where the reply goes; for a 181, where the values to write are
    /// taken from.
    pub dest: u16,
    /// 180: 0 stores values only, 1 the TLP before each value. 181: bytes
    /// of each value, 4 (float), 2 (integer) or 1 (byte). 10: the bytes of
    /// each value (1, 2, 4), or 0 for two bytes a word.
    pub ty: u16,
    /// Seconds between runs; 0 runs it on every pass of the list.
    pub poll: u16,
    /// The first of the ten words of the store-and-forward path; 0 sends
    /// the command directly.
    pub store_fwd: u16,
    /// The row's line in the file, from 1, for messages.
    pub line: usize,
}

impl Command {
    /// Whether it runs at all (PORT 0 disables it).
    pub fn enabled(&self) -> bool {
        self.port != 0
    }
}

/// One cell: its text and span in the file.
struct Cell<'a> {
    text: &'a str,
    span: (usize, usize),
}

/// The cells of a line starting at byte `base`, split on commas, trimmed.
fn cells(line: &str, base: usize) -> Vec<Cell<'_>> {
    let mut out = Vec::new();
    let mut at = 0;
    for part in line.split(',') {
        let lead = part.len() - part.trim_start().len();
        let text = part.trim();
        let start = base + at + lead;
        out.push(Cell { text, span: (start, start + text.len()) });
        at += part.len() + 1;
    }
    out
}

fn header_ok(cells: &[Cell]) -> bool {
    cells.len() == COLUMNS.len()
        && cells.iter().zip(COLUMNS).all(|(c, h)| {
            let squeeze = |s: &str| s.split_whitespace().collect::<Vec<_>>().join(" ").to_ascii_uppercase();
            squeeze(c.text) == h
        })
}

/// Reads a command list for a device speaking `protocol`: the header
/// row, then one command a row. Blank lines are skipped.
pub fn parse(text: &str, protocol: Protocol) -> Result<Vec<Command>, FileError> {
    let mut rows = Vec::new();
    let mut header = false;
    let mut base = 0;
    for (i, raw) in text.split('\n').enumerate() {
        let line = raw.strip_suffix('\r').unwrap_or(raw);
        let here = base;
        base += raw.len() + 1;
        let line_no = i + 1;
        let line = if i == 0 { line.strip_prefix('\u{feff}').unwrap_or(line) } else { line };
        let here = if i == 0 && raw.starts_with('\u{feff}') { here + 3 } else { here };
        if line.trim().is_empty() {
            continue;
        }
        let cs = cells(line, here);
        if !header {
            if !header_ok(&cs) {
                let message = format!("a command list starts with the header `{}`", COLUMNS.join(","));
                return Err(FileError::at(Code::E0921, message, (here, here + line.len())));
            }
            header = true;
            continue;
        }
        if cs.len() != COLUMNS.len() {
            let message =
                format!("this row has {} cells; a command has {}: {}", cs.len(), COLUMNS.len(), COLUMNS.join(","));
            return Err(FileError::at(Code::E0921, message, (here, here + line.len())));
        }
        if rows.len() == MAX_COMMANDS {
            let message = format!("a command list holds at most {MAX_COMMANDS} commands");
            return Err(FileError::at(Code::E0921, message, (here, here + line.len())));
        }
        rows.push(command(&cs, line_no, protocol)?);
    }
    if !header {
        let message = format!("the command list is empty: it starts with the header `{}`", COLUMNS.join(","));
        return Err(FileError { code: Code::E0921, message, span: None });
    }
    Ok(rows)
}

/// A cell's whole number, at most `max`.
fn number(c: &Cell, column: &str, max: u32) -> Result<u32, FileError> {
    c.text.parse::<u32>().ok().filter(|&n| n <= max).ok_or_else(|| {
        FileError::at(Code::E0922, format!("{column} is a whole number from 0 to {max}, not `{}`", c.text), c.span)
    })
}

fn command(cs: &[Cell], line: usize, protocol: Protocol) -> Result<Command, FileError> {
    let n = |i: usize, max: u32| number(&cs[i], COLUMNS[i], max);
    let port = n(0, 65535)? as u16;
    if ![0, 1, 2, 9, 10].contains(&port) {
        let why = format!("PORT is 0 (disabled), 1 or 2 (continuous) or 9 or 10 (control), not {port}");
        return Err(FileError::at(Code::E0922, why, cs[0].span));
    }
    let (unit, group) = (n(1, 255)? as u8, n(2, 255)? as u8);
    let opcode = n(3, 255)? as u8;
    supported(opcode, protocol).map_err(|why| FileError::at(Code::E0923, why, cs[3].span))?;
    let count = n(4, 255)? as u16;
    let last = SIZE as u32 - 1;
    let (src, dest) = (n(5, last)? as u16, n(6, last)? as u16);
    let ty = n(7, 65535)? as u16;
    let poll = n(8, 65535)? as u16;
    let store_fwd = n(9, last)? as u16;
    let c = Command { port, unit, group, opcode, count, src, dest, ty, poll, store_fwd, line };
    check(&c, protocol).map_err(|(i, code, why)| FileError::at(code, why, cs[i].span))
}

/// Whether the host runs `opcode` against a device speaking `protocol`:
/// the reason it doesn't when not.
fn supported(opcode: u8, protocol: Protocol) -> Result<(), String> {
    let roc_only = [op::TABLE, op::LOG_POINTERS, op::DAY_HOURS, op::HISTORY];
    match (opcode, protocol) {
        (ops::CLOCK_SET | ops::READ | ops::WRITE, _) => Ok(()),
        (o, Protocol::Roc) if roc_only.contains(&o) => Ok(()),
        (o, Protocol::RocPlus) if roc_only.contains(&o) => Err(format!(
            "opcode {o} is the ROC protocol's; against a ROC Plus device (--protocol rocplus) the host runs 8, 180 and 181"
        )),
        (o, Protocol::Roc) => Err(format!("linc's host runs the module's opcodes 8, 10, 120, 128, 130, 180 and 181, not {o}")),
        (o, Protocol::RocPlus) => Err(format!("linc's host runs opcodes 8, 180 and 181 against a ROC Plus device, not {o}")),
    }
}

/// A column's rule broken: its index, the code and why.
type Broken = (usize, Code, String);

/// The rules of CNT and TYPE for the command's opcode, then every word
/// range it reads or surely writes (the table has 4,000 words).
fn check(c: &Command, protocol: Protocol) -> Result<Command, Broken> {
    let wrong = |i: usize, why: String| Err((i, Code::E0922, why));
    let (o, count, ty) = (c.opcode, c.count, c.ty);
    match o {
        ops::CLOCK_SET if !(6..=9).contains(&count) => {
            return wrong(4, format!("CNT of an 8 is the bytes of the clock to send, 6 to 9, not {count}"));
        }
        op::TABLE | op::DAY_HOURS if count != 3 => {
            let what = if o == op::TABLE { "table, first location, locations" } else { "history point, day, month" };
            return wrong(4, format!("CNT of a {o} is 3 ({what}), not {count}"));
        }
        op::LOG_POINTERS if count != 0 => {
            return wrong(4, format!("CNT of a 120 is 0 (it sends nothing), not {count}"))
        }
        op::HISTORY if count != 4 => {
            let why = format!("CNT of a 130 is 4 (history type, history point, values, starting pointer), not {count}");
            return wrong(4, why);
        }
        ops::READ | ops::WRITE if count == 0 => {
            return wrong(4, "CNT (the number of parameters) must be greater than 0".into());
        }
        ops::READ if ty > 1 => {
            return wrong(7, format!("TYPE of a 180 is 0 (values only) or 1 (TLP and value), not {ty}"))
        }
        ops::WRITE if ![1, 2, 4].contains(&ty) => {
            return wrong(7, format!("TYPE of a 181 is the bytes of each value: 4, 2 or 1, not {ty}"));
        }
        op::TABLE if ![0, 1, 2, 4].contains(&ty) => {
            return wrong(
                7,
                format!("TYPE of a 10 is the bytes of each value, 1, 2 or 4, or 0 (two bytes a word), not {ty}"),
            );
        }
        _ => {}
    }
    ranges(c, protocol)?;
    Ok(*c)
}

/// The words from SRC ADDR the request sends, those from DEST ADDR the
/// reply surely fills (or a 181 sends), and the path at STORE FWD must
/// lie below word 4000.
fn ranges(c: &Command, protocol: Protocol) -> Result<(), Broken> {
    let last = SIZE - 1;
    let past = |at: u16, n: usize| usize::from(at) + n > SIZE;
    let wrong = |i: usize, why: String| Err((i, Code::E0922, why));
    let sent = word_len(&layouts::request_layout(c.opcode, c.count));
    if past(c.src, sent) {
        if matches!(c.opcode, ops::READ | ops::WRITE) {
            return wrong(5, format!("the {} TLPs from word {} pass word {last}", c.count, c.src));
        }
        return wrong(5, format!("the {sent} words a {} sends from word {} pass word {last}", c.opcode, c.src));
    }
    let got = layouts::dest_words(c.opcode, c.count, c.ty);
    if past(c.dest, got) {
        if c.opcode == ops::WRITE {
            return wrong(6, format!("the {} values from word {} pass word {last}", c.count, c.dest));
        }
        return wrong(6, format!("the {got} words of a {} reply from word {} pass word {last}", c.opcode, c.dest));
    }
    match c.store_fwd {
        0 => Ok(()),
        _ if protocol == Protocol::RocPlus => {
            let why = "store and forward (opcode 24) is the ROC protocol's: against a ROC Plus device \
                       (--protocol rocplus) STORE FWD must be 0";
            Err((9, Code::E0923, why.into()))
        }
        at if past(at, PATH_WORDS) => {
            wrong(9, format!("the {PATH_WORDS} words of the store-and-forward path from word {at} pass word {last}"))
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEAD: &str = "PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD\n";

    /// The manual's §6.1.1 example.
    pub const EXAMPLE: &str = "PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD\n\
                               1,25,2,180,2,0,50,0,0,0\n\
                               1,25,2,181,2,0,100,2,0,0\n";

    #[test]
    fn the_manuals_example_reads() {
        for protocol in [Protocol::Roc, Protocol::RocPlus] {
            let c = parse(EXAMPLE, protocol).unwrap();
            assert_eq!(c.len(), 2);
            let read = Command {
                port: 1,
                unit: 25,
                group: 2,
                opcode: 180,
                count: 2,
                src: 0,
                dest: 50,
                ty: 0,
                poll: 0,
                store_fwd: 0,
                line: 2,
            };
            assert_eq!(c[0], read);
            assert_eq!(c[1], Command { opcode: 181, dest: 100, ty: 2, line: 3, ..read });
        }
        // Header case and spacing, CRLF, blank lines and a BOM are forgiven.
        let loose = format!(
            "\u{feff}port, slv  unit,SLV GROUP,op code,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD\r\n\r\n{}",
            "1, 25 ,2,180,2,0,50,0,0,0\r\n"
        );
        assert_eq!(parse(&loose, Protocol::Roc).unwrap()[0].unit, 25);
    }

    #[test]
    fn the_modules_whole_list_reads_at_the_edges_of_the_table() {
        let rows = "1,1,2,8,6,0,0,0,0,0\n1,1,2,8,9,3991,0,7,0,0\n\
                    1,1,2,10,3,3997,3995,0,0,0\n1,1,2,10,3,0,0,4,0,0\n\
                    1,1,2,120,0,3999,3982,0,0,0\n\
                    1,1,2,128,3,3997,3925,0,0,0\n\
                    1,1,2,130,4,3996,3997,0,0,3990\n";
        let list = parse(&format!("{HEAD}{rows}"), Protocol::Roc).unwrap();
        let ops: Vec<u8> = list.iter().map(|c| c.opcode).collect();
        assert_eq!(ops, [8, 8, 10, 10, 120, 128, 130]);
        assert_eq!(list[6].store_fwd, 3990);
        // TYPE is unused but for 10, 180 and 181: any number is taken.
        assert_eq!(list[1].ty, 7);
    }

    #[test]
    fn every_bad_cell_is_located_with_its_code() {
        for (row, code, cell) in [
            ("3,25,2,180,2,0,50,0,0,0", Code::E0922, "3"),
            ("1,256,2,180,2,0,50,0,0,0", Code::E0922, "256"),
            ("1,25,2,7,2,0,50,0,0,0", Code::E0923, "7"),
            ("1,25,2,24,2,0,50,0,0,0", Code::E0923, "24"),
            ("1,25,2,180,0,0,50,0,0,0", Code::E0922, "0"),
            ("1,25,2,180,2,3995,50,0,0,0", Code::E0922, "3995"),
            ("1,25,2,180,2,0,50,2,0,0", Code::E0922, "2"),
            ("1,25,2,181,2,0,50,3,0,0", Code::E0922, "3"),
            ("1,25,2,181,2,0,3999,4,0,0", Code::E0922, "3999"),
            ("1,25,2,180,2,0,50,0,0,3991", Code::E0922, "3991"),
            ("1,25,2,180,2,0,5x,0,0,0", Code::E0922, "5x"),
            // CNT of each ROC-protocol opcode, and 10's TYPE.
            ("1,25,2,8,5,0,0,0,0,0", Code::E0922, "5"),
            ("1,25,2,8,10,0,0,0,0,0", Code::E0922, "10"),
            ("1,25,2,10,4,0,0,0,0,0", Code::E0922, "4"),
            ("1,25,2,10,3,0,0,3,0,0", Code::E0922, "3"),
            ("1,25,2,120,1,0,0,0,0,0", Code::E0922, "1"),
            ("1,25,2,128,2,0,0,0,0,0", Code::E0922, "2"),
            ("1,25,2,130,3,0,0,0,0,0", Code::E0922, "3"),
            // What each sends from SRC ADDR and surely receives at DEST ADDR.
            ("1,25,2,8,9,3992,0,0,0,0", Code::E0922, "3992"),
            ("1,25,2,10,3,3998,0,0,0,0", Code::E0922, "3998"),
            ("1,25,2,10,3,0,3996,0,0,0", Code::E0922, "3996"),
            ("1,25,2,120,0,0,3983,0,0,0", Code::E0922, "3983"),
            ("1,25,2,128,3,0,3926,0,0,0", Code::E0922, "3926"),
            ("1,25,2,130,4,3997,0,0,0,0", Code::E0922, "3997"),
            ("1,25,2,130,4,0,3998,0,0,0", Code::E0922, "3998"),
        ] {
            let text = format!("{HEAD}{row}\n");
            let e = parse(&text, Protocol::Roc).unwrap_err();
            assert_eq!(e.code, code, "{row}: {}", e.message);
            let (s, t) = e.span.unwrap();
            assert_eq!(&text[s..t], cell, "{row}: {}", e.message);
        }
        assert_eq!(parse("PORT,SLV UNIT\n1,2\n", Protocol::Roc).unwrap_err().code, Code::E0921);
        assert_eq!(parse(&format!("{HEAD}1,25,2\n"), Protocol::Roc).unwrap_err().code, Code::E0921);
        assert_eq!(parse("", Protocol::Roc).unwrap_err().code, Code::E0921);
        let many = format!("{HEAD}{}", "0,1,2,180,1,0,0,0,0,0\n".repeat(101));
        assert!(parse(&many, Protocol::Roc).unwrap_err().message.contains("at most 100"));
    }

    #[test]
    fn a_roc_plus_device_refuses_the_roc_protocols_opcodes_and_store_and_forward() {
        for (row, cell) in [
            ("1,25,2,10,3,0,0,0,0,0", "10"),
            ("1,25,2,120,0,0,0,0,0,0", "120"),
            ("1,25,2,128,3,0,0,0,0,0", "128"),
            ("1,25,2,130,4,0,0,0,0,0", "130"),
            ("1,25,2,180,2,0,50,0,0,40", "40"),
        ] {
            let text = format!("{HEAD}{row}\n");
            assert!(parse(&text, Protocol::Roc).is_ok(), "{row}");
            let e = parse(&text, Protocol::RocPlus).unwrap_err();
            assert_eq!(e.code, Code::E0923, "{row}: {}", e.message);
            let (s, t) = e.span.unwrap();
            assert_eq!(&text[s..t], cell, "{row}: {}", e.message);
            assert!(e.message.contains("rocplus"), "{}", e.message);
        }
        // The clock set is both protocols' (ROC Plus's is 7 bytes).
        assert!(parse(&format!("{HEAD}1,25,2,8,7,0,0,0,0,0\n"), Protocol::RocPlus).is_ok());
    }
}
