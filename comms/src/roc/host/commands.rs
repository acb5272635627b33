//! The host's command list (`003_…` §4.4.2 and §6.1): one row per
//! command, in the manual's columns
//! `PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD`.

use super::words::SIZE;
use crate::error::FileError;
use linc_format::Code;

/// The columns, as the manual heads them.
pub const COLUMNS: [&str; 10] =
    ["PORT", "SLV UNIT", "SLV GROUP", "OP CODE", "CNT", "SRC ADDR", "DEST ADDR", "TYPE", "POLL TIME", "STORE FWD"];

/// Most commands in a list (the module's 20 blocks of five).
pub const MAX_COMMANDS: usize = 100;

/// One command of the list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Command {
    /// 0 disabled; 1 or 2 continuous on that port; 9 or 10 control mode.
    pub port: u16,
    pub unit: u8,
    pub group: u8,
    /// 180 read parameters or 181 write parameters.
    pub opcode: u8,
    /// Parameters to read or write.
    pub count: u16,
    /// First word of the TLPs, three words each.
    pub src: u16,
    /// 180: where the values go; 181: where they are taken from.
    pub dest: u16,
    /// 180: 0 stores values only, 1 the TLP before each value. 181: bytes
    /// of each value, 4 (float), 2 (integer) or 1 (byte).
    pub ty: u16,
    /// Seconds between runs; 0 runs it on every pass of the list.
    pub poll: u16,
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

/// Reads a command list: the header row, then one command a row. Blank
/// lines are skipped.
pub fn parse(text: &str) -> Result<Vec<Command>, FileError> {
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
        rows.push(command(&cs, line_no)?);
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

fn command(cs: &[Cell], line: usize) -> Result<Command, FileError> {
    let n = |i: usize, max: u32| number(&cs[i], COLUMNS[i], max);
    let wrong = |i: usize, why: String| Err(FileError::at(Code::E0922, why, cs[i].span));
    let port = n(0, 65535)? as u16;
    if ![0, 1, 2, 9, 10].contains(&port) {
        return wrong(0, format!("PORT is 0 (disabled), 1 or 2 (continuous) or 9 or 10 (control), not {port}"));
    }
    let (unit, group) = (n(1, 255)? as u8, n(2, 255)? as u8);
    let opcode = n(3, 255)? as u8;
    if opcode != 180 && opcode != 181 {
        let why = format!("linc's host runs opcodes 180 (read parameters) and 181 (write parameters), not {opcode}");
        return Err(FileError::at(Code::E0923, why, cs[3].span));
    }
    let count = n(4, 255)? as u16;
    if count == 0 {
        return wrong(4, "CNT (the number of parameters) must be greater than 0".into());
    }
    let last = SIZE as u32 - 1;
    let (src, dest) = (n(5, last)? as u16, n(6, last)? as u16);
    if usize::from(src) + 3 * usize::from(count) > SIZE {
        return wrong(5, format!("the {count} TLPs from word {src} pass word {last}"));
    }
    let ty = n(7, 65535)? as u16;
    match opcode {
        180 if ty > 1 => return wrong(7, format!("TYPE of a 180 is 0 (values only) or 1 (TLP and value), not {ty}")),
        181 if ![1, 2, 4].contains(&ty) => {
            return wrong(7, format!("TYPE of a 181 is the bytes of each value: 4, 2 or 1, not {ty}"));
        }
        181 if usize::from(dest) + usize::from(count) * usize::from(ty.div_ceil(2)) > SIZE => {
            return wrong(6, format!("the {count} values from word {dest} pass word {last}"));
        }
        _ => {}
    }
    let poll = n(8, 65535)? as u16;
    if n(9, last)? != 0 {
        let why = "store and forward (opcode 24) is not supported by linc's host: STORE FWD must be 0".to_string();
        return Err(FileError::at(Code::E0923, why, cs[9].span));
    }
    Ok(Command { port, unit, group, opcode, count, src, dest, ty, poll, line })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The manual's §6.1.1 example.
    pub const EXAMPLE: &str = "PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD\n\
                               1,25,2,180,2,0,50,0,0,0\n\
                               1,25,2,181,2,0,100,2,0,0\n";

    #[test]
    fn the_manuals_example_reads() {
        let c = parse(EXAMPLE).unwrap();
        assert_eq!(c.len(), 2);
        let read =
            Command { port: 1, unit: 25, group: 2, opcode: 180, count: 2, src: 0, dest: 50, ty: 0, poll: 0, line: 2 };
        assert_eq!(c[0], read);
        assert_eq!(c[1], Command { opcode: 181, dest: 100, ty: 2, line: 3, ..read });
        // Header case and spacing, CRLF, blank lines and a BOM are forgiven.
        let loose = format!(
            "\u{feff}port, slv  unit,SLV GROUP,op code,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD\r\n\r\n{}",
            "1, 25 ,2,180,2,0,50,0,0,0\r\n"
        );
        assert_eq!(parse(&loose).unwrap()[0].unit, 25);
    }

    #[test]
    fn every_bad_cell_is_located_with_its_code() {
        let head = "PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD\n";
        for (row, code, cell) in [
            ("3,25,2,180,2,0,50,0,0,0", Code::E0922, "3"),
            ("1,256,2,180,2,0,50,0,0,0", Code::E0922, "256"),
            ("1,25,2,7,2,0,50,0,0,0", Code::E0923, "7"),
            ("1,25,2,180,0,0,50,0,0,0", Code::E0922, "0"),
            ("1,25,2,180,2,3995,50,0,0,0", Code::E0922, "3995"),
            ("1,25,2,180,2,0,50,2,0,0", Code::E0922, "2"),
            ("1,25,2,181,2,0,50,3,0,0", Code::E0922, "3"),
            ("1,25,2,181,2,0,3999,4,0,0", Code::E0922, "3999"),
            ("1,25,2,180,2,0,50,0,0,40", Code::E0923, "40"),
            ("1,25,2,180,2,0,5x,0,0,0", Code::E0922, "5x"),
        ] {
            let text = format!("{head}{row}\n");
            let e = parse(&text).unwrap_err();
            assert_eq!(e.code, code, "{row}: {}", e.message);
            let (s, t) = e.span.unwrap();
            assert_eq!(&text[s..t], cell, "{row}: {}", e.message);
        }
        assert_eq!(parse("PORT,SLV UNIT\n1,2\n").unwrap_err().code, Code::E0921);
        assert_eq!(parse(&format!("{head}1,25,2\n")).unwrap_err().code, Code::E0921);
        assert_eq!(parse("").unwrap_err().code, Code::E0921);
        let many = format!("{head}{}", "0,1,2,180,1,0,0,0,0,0\n".repeat(101));
        assert!(parse(&many).unwrap_err().message.contains("at most 100"));
    }
}
