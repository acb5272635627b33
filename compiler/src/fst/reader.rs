//! Reading an FST table saved as CSV by ROCLINK's FST Editor (or written
//! by hand): the header row, then one row per step. The `csv` crate does
//! the quoting (RFC 4180); a small scan beside it finds each cell's bytes,
//! so that diagnostics underline the cell.

use super::errors;
use super::tlp::distance;
use super::{Cell, Cmd, Row, Table};
use crate::diag::span::Span;
use crate::diag::{Diagnostic, MAX_ERRORS};

/// The header's columns, as compared: upper case, spaces removed.
const COLUMNS: [&str; 6] = ["STEP", "LABEL", "CMD", "ARGUMENT1", "ARGUMENT2", "COMMENT"];

/// The cell separator of a table: `;` when its first line has more `;`
/// than `,` (a table saved where `,` is the decimal comma), else `,`. The
/// formatter and the language server split cells by the same rule.
pub fn delimiter(text: &str) -> u8 {
    let first_line = text.split(['\n', '\r']).next().unwrap_or("");
    if first_line.matches(';').count() > first_line.matches(',').count() {
        b';'
    } else {
        b','
    }
}

/// Whether header cells (blanks removed, upper case) name the columns.
fn is_header(names: &[String]) -> bool {
    (names.len() == 5 || names.len() == 6) && names.iter().zip(COLUMNS).all(|(a, b)| a == b)
}

/// Whether a text starts with a table's header as [`read`] accepts it: how
/// `linc fmt` tells FST tables from other CSV files in a directory.
pub fn starts_with_header(text: &str) -> bool {
    let body = text.strip_prefix('\u{feff}').unwrap_or(text);
    let line = body.split(['\n', '\r']).next().unwrap_or("");
    let names: Vec<String> = line
        .split(char::from(delimiter(body)))
        .map(|c| c.chars().filter(|c| !c.is_whitespace() && *c != '"').collect::<String>().to_ascii_uppercase())
        .collect();
    is_header(&names)
}

/// Reads a table. Rows after the first blank command are not part of it.
pub fn read(text: &str) -> (Table, Vec<Diagnostic>) {
    let base = if text.starts_with('\u{feff}') { '\u{feff}'.len_utf8() } else { 0 };
    let body = text.get(base..).unwrap_or("");
    let delim = delimiter(body);
    let mut reader =
        Reader { text, base, body, delim, columns: 0, next_step: 0, table: Table::default(), diags: Vec::new() };
    reader.run();
    (reader.table, reader.diags)
}

enum Header {
    Ok,
    /// No header: the first row is a step.
    Data,
    Bad,
}

struct Reader<'a> {
    text: &'a str,
    base: usize,
    body: &'a str,
    delim: u8,
    /// How many columns the header has (5 or 6); 0 before it is read.
    columns: usize,
    /// What the next STEP cell should say. After a wrong one, counting goes
    /// on from it, so that one gap is one error.
    next_step: usize,
    table: Table,
    diags: Vec<Diagnostic>,
}

/// One CSV record: its cells (trimmed) and their spans in the whole text.
struct Record {
    line: u32,
    cells: Vec<(String, Span)>,
    span: Span,
    /// The first cell with a line break inside its quotes.
    line_break: Option<Span>,
}

impl Record {
    fn cell(&self, i: usize) -> Option<Cell> {
        let (text, span) = self.cells.get(i)?;
        (!text.is_empty()).then(|| Cell { text: text.clone(), span: *span })
    }

    fn blank(&self, i: usize) -> bool {
        self.cells.get(i).filter(|(t, _)| !t.is_empty()).is_none()
    }
}

impl Reader<'_> {
    fn run(&mut self) {
        let mut csv = csv::ReaderBuilder::new()
            .has_headers(false)
            .flexible(true)
            .delimiter(self.delim)
            .from_reader(self.body.as_bytes());
        let mut ended: Option<u32> = None;
        let mut warned = false;
        let mut last_end = self.base;
        for result in csv.records() {
            if self.diags.len() >= MAX_ERRORS {
                break;
            }
            let rec = match result.map_err(|e| (last_end, e.to_string())).and_then(|r| self.record(&r)) {
                Ok(rec) => rec,
                Err((start, why)) => {
                    let rest = self.text.get(start..).unwrap_or("");
                    let end = rest.find(['\n', '\r']).map_or(self.text.len(), |i| start + i);
                    self.diags.push(errors::malformed_row(Span::new(start, end), why));
                    break;
                }
            };
            if self.columns == 0 {
                match self.header(&rec) {
                    Header::Ok => {
                        last_end = rec.span.end;
                        continue;
                    }
                    Header::Data => self.columns = COLUMNS.len(),
                    Header::Bad => break,
                }
            }
            if let Some(blank_line) = ended {
                if !warned {
                    warned = self.ignored(&rec, blank_line);
                }
                continue;
            }
            if let Some(span) = rec.line_break {
                self.diags.push(errors::line_break_in_cell(span));
                self.next_step += 1;
                continue;
            }
            if rec.blank(2) {
                ended = Some(rec.line);
                warned = self.ignored(&rec, rec.line);
                continue;
            }
            if rec.cells.len() > self.columns || rec.cells.len() < 5 {
                let why = format!("{} cells where the header has {}", rec.cells.len(), self.columns);
                let d = errors::malformed_row(rec.span, why)
                    .help("quote a cell that holds the delimiter: \"AIN 3-1,EU\"".to_string());
                self.diags.push(d);
                self.next_step += 1;
                continue;
            }
            last_end = rec.span.end;
            self.row(rec);
        }
        if self.columns == 0 && self.diags.is_empty() {
            // No record at all: an empty file, or only blank lines.
            self.diags.push(errors::bad_header(Span::new(self.base, self.base), ""));
        }
        let (line, col) = line_col(self.text, last_end);
        self.table.end_line = line;
        self.table.end_col = col;
    }

    /// Splits one record into trimmed cells with their spans.
    fn record(&self, r: &csv::StringRecord) -> Result<Record, (usize, String)> {
        let pos = r.position().ok_or((self.base, "record without a position".to_string()))?;
        let mut start = usize::try_from(pos.byte()).map_err(|e| (self.base, e.to_string()))?;
        let mut line = u32::try_from(pos.line()).unwrap_or(u32::MAX);
        // After a CR LF, csv places the next record at the LF.
        while let Some(&c) = self.body.as_bytes().get(start).filter(|c| matches!(c, b'\r' | b'\n')) {
            start += 1;
            line = line.saturating_add(u32::from(c == b'\n'));
        }
        let (spans, end) = cell_spans(self.body.as_bytes(), start, self.delim).map_err(|_| {
            (start + self.base, "a quoted cell is not closed: the rest of the file is inside its quotes".to_string())
        })?;
        let shift = |s: Span| Span::new(s.start + self.base, s.end + self.base);
        let whole = shift(Span::new(start, end));
        let mut line_break = None;
        let cells = r
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let span = spans.get(i).map(|s| shift(trim_span(self.body.as_bytes(), *s))).unwrap_or(whole);
                if t.contains(['\n', '\r']) {
                    line_break.get_or_insert(span);
                }
                (t.trim().to_string(), span)
            })
            .collect();
        Ok(Record { line, cells, span: whole, line_break })
    }

    /// Takes the header row, or reports E0400.
    fn header(&mut self, rec: &Record) -> Header {
        let names: Vec<String> = rec
            .cells
            .iter()
            .map(|(t, _)| t.chars().filter(|c| !c.is_whitespace()).collect::<String>().to_ascii_uppercase())
            .collect();
        if is_header(&names) {
            self.columns = names.len();
            return Header::Ok;
        }
        let line = self.body.split(['\n', '\r']).next().unwrap_or("");
        let span = Span::new(self.base, self.base + line.len());
        self.diags.push(errors::bad_header(span, line.trim()));
        // A first row that is a step is read as one, in the usual columns;
        // anything else leaves the columns unknown.
        match rec.cells.first().is_some_and(|(t, _)| t.parse::<u32>().is_ok()) {
            true => Header::Data,
            false => Header::Bad,
        }
    }

    /// W0400 for content after the end, at its command (or first cell).
    fn ignored(&mut self, rec: &Record, blank_line: u32) -> bool {
        let at = rec.cell(2).or_else(|| [1, 3, 4].into_iter().find_map(|i| rec.cell(i)));
        match at {
            Some(cell) => {
                self.diags.push(errors::rows_after_end(cell.span, blank_line));
                true
            }
            None => false,
        }
    }

    fn row(&mut self, rec: Record) {
        let written = rec.cell(0).and_then(|c| c.text.parse::<usize>().ok());
        if written != Some(self.next_step) {
            let (found, span) = rec.cells.first().cloned().unwrap_or_default();
            self.diags.push(errors::bad_step(span, &found, self.next_step));
        }
        self.next_step = written.unwrap_or(self.next_step).saturating_add(1);
        let step = self.table.rows.len();
        let Some(cmd) = rec.cell(2) else { return };
        if Cmd::parse(&cmd.text).is_none() {
            self.diags.push(errors::unknown_command(cmd.span, &cmd.text, suggest_command(&cmd.text)));
        }
        // A row is one line (cells with line breaks are refused), so the
        // column counts from the row's start: counting from the start of
        // the file for every row made reading quadratic.
        let before = self.text.get(rec.span.start..cmd.span.start).unwrap_or("");
        let col = u32::try_from(before.chars().count() + 1).unwrap_or(u32::MAX);
        let comment = rec.cell(5).map(|c| c.text).unwrap_or_default();
        self.table.rows.push(Row {
            step: u32::try_from(step).unwrap_or(u32::MAX),
            line: rec.line,
            col,
            label: rec.cell(1),
            cmd,
            arg1: rec.cell(3),
            arg2: rec.cell(4),
            comment,
        });
    }
}

/// The command closest to a misspelt one.
fn suggest_command(text: &str) -> Option<&'static str> {
    if text.len() > 16 {
        return None;
    }
    let upper = text.to_ascii_uppercase();
    Cmd::ALL
        .iter()
        .map(|c| (distance(&upper, c.text()), c.text()))
        .filter(|(d, t)| *d <= if t.len() >= 3 { 2 } else { 1 } && *d < upper.len())
        .min_by_key(|(d, _)| *d)
        .map(|(_, t)| t)
}

/// The byte spans of the cells of the record at `start`, split as RFC 4180
/// splits them, and where the record ends; `Err` if a quote is not closed.
fn cell_spans(b: &[u8], start: usize, delim: u8) -> Result<(Vec<Span>, usize), ()> {
    let mut spans = Vec::new();
    let mut i = start;
    loop {
        let s = i;
        if b.get(i) == Some(&b'"') {
            i += 1;
            loop {
                match b.get(i) {
                    None => return Err(()),
                    Some(b'"') if b.get(i + 1) == Some(&b'"') => i += 2,
                    Some(b'"') => {
                        i += 1;
                        break;
                    }
                    Some(_) => i += 1,
                }
            }
        }
        while let Some(&c) = b.get(i) {
            if c == delim || c == b'\n' || c == b'\r' {
                break;
            }
            i += 1;
        }
        spans.push(Span::new(s, i));
        match b.get(i) {
            Some(&c) if c == delim => i += 1,
            _ => return Ok((spans, i)),
        }
    }
}

/// A span without the spaces around the cell.
fn trim_span(b: &[u8], s: Span) -> Span {
    let Some(bytes) = b.get(s.start..s.end) else { return s };
    let lead = bytes.iter().take_while(|c| c.is_ascii_whitespace()).count();
    let trail = bytes[lead..].iter().rev().take_while(|c| c.is_ascii_whitespace()).count();
    Span::new(s.start + lead, s.end - trail)
}

/// 1-based line and column (in characters) of a byte offset.
pub fn line_col(text: &str, offset: usize) -> (u32, u32) {
    let before = text.get(..offset).unwrap_or(text);
    let line = before.bytes().filter(|&c| c == b'\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    let col = before.get(start..).map_or(0, |s| s.chars().count()) + 1;
    (u32::try_from(line).unwrap_or(u32::MAX), u32::try_from(col).unwrap_or(u32::MAX))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn codes(d: &[Diagnostic]) -> Vec<&'static str> {
        d.iter().map(|d| d.code.as_str()).collect()
    }

    fn at(text: &str, span: Span) -> &str {
        &text[span.start..span.end]
    }

    const B4: &str = "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2,COMMENT\n0,,GO,PMPOFF,,\n1,PUMPON,DO,DOU 4-1,1,\n2,PMPOFF,DO,DOU 4-2,0,pump off\n";

    #[test]
    fn reads_the_manuals_table_b4() {
        let (t, d) = read(B4);
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(t.rows.len(), 3);
        let r = &t.rows[2];
        assert_eq!((r.step, r.line, r.col), (2, 4, 10));
        assert_eq!(r.label.as_ref().map(|c| c.text.as_str()), Some("PMPOFF"));
        assert_eq!(at(B4, r.cmd.span), "DO");
        assert_eq!(r.arg1.as_ref().map(|c| at(B4, c.span)), Some("DOU 4-2"));
        assert_eq!(r.arg2.as_ref().map(|c| c.text.as_str()), Some("0"));
        assert_eq!(r.comment, "pump off");
        assert_eq!(t.rows[0].label, None);
        assert_eq!(t.rows[0].arg2, None);
        assert_eq!((t.end_line, t.end_col), (4, 31));
    }

    #[test]
    fn quoted_cells_keep_their_commas_and_spans_cover_the_quotes() {
        let src = "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\n0, CKHIAL ,VAL,\"AIN 3-1,EU\",\n1,,MSG,\"say \"\"hi\"\"\",\n";
        let (t, d) = read(src);
        assert!(d.is_empty(), "{d:?}");
        let a = t.rows[0].arg1.as_ref().unwrap();
        assert_eq!(a.text, "AIN 3-1,EU");
        assert_eq!(at(src, a.span), "\"AIN 3-1,EU\"");
        assert_eq!(at(src, t.rows[0].label.as_ref().unwrap().span), "CKHIAL");
        assert_eq!(t.rows[1].arg1.as_ref().unwrap().text, "say \"hi\"");
    }

    #[test]
    fn semicolons_bom_and_header_spelling() {
        let src = "\u{feff} step ; Label;cmd;ARGUMENT 1;Argument 2\r\n0;;VAL;AIN 3-1,EU;\r\n1;;END;;\r\n\r\n\r\n";
        let (t, d) = read(src);
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(t.rows.len(), 2);
        assert_eq!(t.rows[0].arg1.as_ref().unwrap().text, "AIN 3-1,EU");
        assert_eq!(at(src, t.rows[1].cmd.span), "END", "{:?}", t.rows[1]);
        assert_eq!((t.rows[1].line, t.rows[1].col), (3, 4));
    }

    #[test]
    fn a_blank_command_ends_the_program_and_later_rows_warn_once() {
        let src = "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\n0,,VAL,1,\n1,,,,\n2,,SAV,SFP 1,DATA1\n3,,END,,\n";
        let (t, d) = read(src);
        assert_eq!(t.rows.len(), 1);
        assert_eq!(codes(&d), ["W0400"]);
        assert_eq!(at(src, d[0].span), "SAV");
        let (t, d) = read("STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\n0,,END,,\n1,,,,\n2,,,,\n,,,,\n");
        assert_eq!((t.rows.len(), d.len()), (1, 0), "blank rows after the program are fine");
    }

    #[test]
    fn step_numbers_count_up_without_gaps() {
        let src = "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\n0,,VAL,1,\n2,,VAL,2,\n3,,VAL,3,\nx,,VAL,4,\n5,,END,,\n";
        let (t, d) = read(src);
        assert_eq!(codes(&d), ["E0402", "E0402"], "one error a gap, counting on from it");
        assert_eq!(at(src, d[0].span), "2");
        assert_eq!(at(src, d[1].span), "x");
        assert_eq!(d[1].label, "expected 4");
        assert_eq!(t.rows.iter().map(|r| r.step).collect::<Vec<_>>(), [0, 1, 2, 3, 4]);
    }

    #[test]
    fn header_missing_or_wrong() {
        let (t, d) = read("0,,VAL,1,\n1,,END,,\n");
        assert_eq!(codes(&d), ["E0400"]);
        assert_eq!((d[0].span.start, t.rows.len()), (0, 2), "data without a header is still read");
        let (t, d) = read("STEP,CMD,ARG\n0,VAL,1\n");
        assert_eq!(codes(&d), ["E0400"]);
        assert!(t.rows.is_empty());
    }

    #[test]
    fn an_empty_file_is_refused_at_its_start() {
        for (text, start) in [("", 0), ("\n\r\n\n", 0), ("\u{feff}", 3)] {
            let (t, d) = read(text);
            assert_eq!(codes(&d), ["E0400"], "{text:?}");
            assert_eq!(d[0].label, "expected the header here");
            assert_eq!(d[0].span, Span::new(start, start), "{text:?}");
            assert!(t.rows.is_empty());
        }
        let (t, d) = read("STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\n");
        assert!(d.is_empty() && t.rows.is_empty(), "a header alone is a table without steps: {d:?}");
    }

    #[test]
    fn a_line_break_in_a_cell_is_refused_and_later_rows_keep_their_lines() {
        let src =
            "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2,COMMENT\n0,,VAL,1,,\"two\nlines\"\n1,,\"\nVAL\",1,,\n2,,VALL,1,,\n";
        let (t, d) = read(src);
        assert_eq!(codes(&d), ["E0401", "E0401", "E0403"]);
        assert_eq!(at(src, d[0].span), "\"two\nlines\"");
        assert_eq!(at(src, d[1].span), "\"\nVAL\"");
        assert!(d[0].label.contains("line break"), "{:?}", d[0]);
        assert_eq!(at(src, d[2].span), "VALL");
        assert_eq!(t.rows.len(), 1, "only the row without a line break is read");
        assert_eq!((t.rows[0].step, t.rows[0].line, t.rows[0].col), (0, 6, 4));
    }

    #[test]
    fn columns_count_from_the_rows_start() {
        let src = "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\r\n0,ÉTAPE,VAL,1,\r\n1,,  END,,\r\n";
        let (t, _) = read(src);
        assert_eq!((t.rows[0].line, t.rows[0].col), (2, 9), "characters, not bytes");
        assert_eq!((t.rows[1].line, t.rows[1].col), (3, 6));
    }

    #[test]
    fn unknown_commands_and_malformed_rows() {
        let src = "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\n0,,VALL,1,\n1,,VAL,AIN 3-1,EU,x\n2,,MSG,\"open\n";
        let (_, d) = read(src);
        assert_eq!(codes(&d), ["E0403", "E0401", "E0401"]);
        assert_eq!(at(src, d[0].span), "VALL");
        assert_eq!(d[0].help, ["did you mean `VAL`?"]);
        assert_eq!(at(src, d[1].span), "1,,VAL,AIN 3-1,EU,x");
        assert!(d[2].label.contains("not closed"), "{:?}", d[2]);
    }
}
