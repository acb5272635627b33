//! Checking a table (ROCLINK 800 B.1, Table B-9): labels, END, and every
//! argument against its command and the database. Every error of the table
//! is reported; only a clean table with a database gives [`Checked`].

use super::commands::Kind;
use super::errors;
use super::lower::MAX_STEPS;
use super::tlp::{self, distance, Points, ResolveError, Syntax, SyntaxError};
use super::{Arg, Cell, Checked, Cmd, Param, Row, Step, Table};
use crate::diag::span::Span;
use crate::diag::{Diagnostic, MAX_ERRORS};
use linc_format::object::class_of;
use linc_format::object::Class;
use linc_format::Database;
use std::collections::HashMap;

/// Checks a table read by [`super::reader::read`]. An unknown command was
/// reported by the reader (E0403): its row is skipped here, and the table
/// gives no [`Checked`]. Without a database points are not looked up, and
/// nothing is returned to compile.
pub fn check(table: &Table, db: Option<&Database>) -> (Option<Checked>, Vec<Diagnostic>) {
    let points = db.map(Points::new);
    let mut c = Checker {
        db: points.as_ref(),
        labels: HashMap::new(),
        diags: Vec::new(),
        errors: 0,
        omitted: None,
        failed: false,
    };
    c.too_many_steps(table);
    c.define_labels(table);
    let mut steps = Vec::with_capacity(table.rows.len() + 1);
    let mut end: Option<Span> = None;
    for row in &table.rows {
        let Some(cmd) = Cmd::parse(&row.cmd.text) else {
            c.failed = true;
            continue;
        };
        if cmd == Cmd::End {
            match end {
                Some(first) => c.push(errors::second_end(row.cmd.span, first)),
                None => end = Some(row.cmd.span),
            }
        }
        let (k1, k2) = cmd.args();
        let arg1 = c.arg(row, cmd, 1, k1, row.arg1.as_ref());
        let arg2 = c.arg(row, cmd, 2, k2, row.arg2.as_ref());
        steps.push(Step { cmd, arg1, arg2, line: row.line, col: row.col });
    }
    // B.1: "If an END command is not present, the FST Editor automatically
    // adds the END command". A table with its one END earlier keeps it
    // there; its last step, when not a jump, ends the cycle (docs/fst.md).
    if end.is_none() {
        let (line, col) = (table.end_line, table.end_col);
        steps.push(Step { cmd: Cmd::End, arg1: Arg::None, arg2: Arg::None, line, col });
    }
    if let Some((span, count)) = c.omitted {
        c.diags.push(errors::omitted(span, count));
    }
    let clean = c.errors == 0 && !c.failed && db.is_some();
    (clean.then_some(Checked { steps }), c.diags)
}

/// A value argument as far as it could be read.
enum Operand {
    Const(f32),
    /// A database parameter (the block's index too, for its template).
    Param(Param, usize),
    /// A point, accepted without a database.
    Unresolved,
    /// Reported already.
    Bad,
}

struct Checker<'a> {
    db: Option<&'a Points<'a>>,
    /// Labels by upper-case name: the step and the label cell.
    labels: HashMap<String, (u32, Span)>,
    diags: Vec<Diagnostic>,
    errors: usize,
    /// Errors over the cap: where the first was and how many.
    omitted: Option<(Span, usize)>,
    failed: bool,
}

impl Checker<'_> {
    fn push(&mut self, d: Diagnostic) {
        if d.is_error() {
            self.errors += 1;
            if self.errors > MAX_ERRORS {
                let o = self.omitted.get_or_insert((d.span, 0));
                o.1 += 1;
                return;
            }
        }
        self.diags.push(d);
    }

    /// Whether errors are over the cap: what is found now is only counted,
    /// so nothing that costs more than a look-up (a "did you mean" search)
    /// is worth doing for it.
    fn full(&self) -> bool {
        self.errors >= MAX_ERRORS
    }

    /// E0132 at the first step over [`MAX_STEPS`]: the END appended to a
    /// table without one counts, and is charged to the last row.
    fn too_many_steps(&mut self, table: &Table) {
        let has_end = table.rows.iter().any(|r| Cmd::parse(&r.cmd.text) == Some(Cmd::End));
        let steps = table.rows.len() + usize::from(!has_end);
        if steps <= MAX_STEPS {
            return;
        }
        let (row, appended) = match table.rows.get(MAX_STEPS) {
            Some(row) => (row, false),
            None => (&table.rows[table.rows.len() - 1], true),
        };
        self.push(errors::too_many_steps(row.cmd.span, MAX_STEPS, appended));
    }

    /// B.1.2: up to six letters and digits, no command names, unique.
    fn define_labels(&mut self, table: &Table) {
        for (i, row) in table.rows.iter().enumerate() {
            let Some(label) = &row.label else { continue };
            let text = &label.text;
            if !is_label(text) {
                self.push(errors::bad_label(label.span, text));
            } else if Cmd::is_command(text) {
                self.push(errors::label_is_command(label.span, text));
            }
            let key = text.to_ascii_uppercase();
            match self.labels.get(&key) {
                Some(&(_, first)) => self.push(errors::duplicate_label(label.span, text, first)),
                None => {
                    self.labels.insert(key, (u32::try_from(i).unwrap_or(u32::MAX), label.span));
                }
            }
        }
    }

    fn arg(&mut self, row: &Row, cmd: Cmd, which: u8, kind: Kind, cell: Option<&Cell>) -> Arg {
        let Some(cell) = cell else {
            let optional = kind == Kind::None || (which == 2 && matches!(cmd, Cmd::Msg | Cmd::Alm | Cmd::Evt));
            if !optional {
                self.push(errors::missing_argument(row.cmd.span, cmd.text(), which, describe(kind)));
            }
            return Arg::None;
        };
        match kind {
            Kind::None => {
                self.push(errors::unexpected_argument(cell.span, cmd.text(), which));
                Arg::None
            }
            Kind::Label => self.label_arg(cmd, cell),
            Kind::Text => self.text_arg(cmd, cell),
            Kind::In => self.in_arg(cmd, which, cell),
            Kind::Out | Kind::Index => self.out_arg(cmd, kind, cell),
            Kind::Hist => self.hist_arg(cmd, cell),
            Kind::Timer => self.timer_arg(cell),
            Kind::AoPoint => self.point_arg(cmd, cell, "AOU"),
            Kind::DoPoint => self.point_arg(cmd, cell, "DOU"),
        }
    }

    fn label_arg(&mut self, cmd: Cmd, cell: &Cell) -> Arg {
        if let Some(&(step, _)) = self.labels.get(&cell.text.as_str().to_ascii_uppercase()) {
            return Arg::Label(step);
        }
        if is_label(&cell.text) && tlp::parse(&cell.text).is_ok_and(|s| matches!(s, Syntax::Text { .. })) {
            let suggestion = if self.full() { None } else { self.suggest_label(&cell.text) };
            self.push(errors::unknown_label(cell.span, &cell.text, suggestion.as_deref()));
        } else {
            self.push(errors::value_for_label(cell.span, cmd.text(), &cell.text));
        }
        Arg::None
    }

    fn suggest_label(&self, text: &str) -> Option<String> {
        let upper = text.to_ascii_uppercase();
        let mut close: Vec<(usize, &String)> =
            self.labels.keys().map(|k| (distance(&upper, k), k)).filter(|(d, _)| *d <= 2).collect();
        close.sort();
        close.first().map(|(_, k)| (*k).clone())
    }

    /// MSG keeps 30 characters, ALM and EVT 10; more is cut with a warning.
    fn text_arg(&mut self, cmd: Cmd, cell: &Cell) -> Arg {
        let keep = if cmd == Cmd::Msg { 30 } else { 10 };
        if cell.text.chars().count() > keep {
            self.push(errors::text_truncated(cell.span, cmd.text(), keep));
        }
        Arg::Text(cell.text.chars().take(keep).collect())
    }

    fn in_arg(&mut self, cmd: Cmd, which: u8, cell: &Cell) -> Arg {
        match self.operand(cell) {
            Operand::Const(v) => {
                self.constant_range(cmd, which, v, cell);
                Arg::Const(v)
            }
            Operand::Param(p, _) => self.numeric(p, cell),
            Operand::Unresolved | Operand::Bad => Arg::None,
        }
    }

    /// SAV's target, or a history index WDB/WTM/RDB may advance.
    fn out_arg(&mut self, cmd: Cmd, kind: Kind, cell: &Cell) -> Arg {
        match self.operand(cell) {
            Operand::Const(v) if kind == Kind::Index => {
                if v < 0.0 || v.fract() != 0.0 {
                    self.push(errors::out_of_range(cell.span, cmd.text(), &cell.text, "a whole number, 0 or more"));
                }
                Arg::Const(v)
            }
            Operand::Const(_) => {
                self.push(errors::constant_for_param(cell.span, cmd.text(), "a parameter to write"));
                Arg::None
            }
            Operand::Param(p, _) => self.writable(cmd, p, cell),
            Operand::Unresolved | Operand::Bad => Arg::None,
        }
    }

    fn hist_arg(&mut self, cmd: Cmd, cell: &Cell) -> Arg {
        match self.operand(cell) {
            Operand::Const(v) => {
                if !(1.0..=200.0).contains(&v) || v.fract() != 0.0 {
                    self.push(errors::out_of_range(cell.span, cmd.text(), &cell.text, "a history point 1 to 200"));
                }
                Arg::Const(v)
            }
            Operand::Param(p, _) => self.numeric(p, cell),
            Operand::Unresolved | Operand::Bad => Arg::None,
        }
    }

    /// ST/CT: this FST's timer 1–4, or an FST point's TMR1–TMR4.
    fn timer_arg(&mut self, cell: &Cell) -> Arg {
        let written = cell.text.clone();
        match self.operand(cell) {
            Operand::Const(v) if (1.0..=4.0).contains(&v) && v.fract() == 0.0 => Arg::Param(Param {
                block: String::new(),
                field: format!("TMR{v}"),
                class: Class::Int,
                readonly: false,
                written,
            }),
            Operand::Param(p, block) if self.template_of(block) == Some("FST") && is_timer_field(&p.field) => {
                Arg::Param(p)
            }
            Operand::Const(_) | Operand::Param(..) => {
                self.push(errors::bad_timer(cell.span, &cell.text));
                Arg::None
            }
            // Without a database the point is unknown, but the parameter
            // name still says whether it is a timer.
            Operand::Unresolved => {
                if let Ok(Syntax::Text { param: Some(p), .. }) = tlp::parse(&cell.text) {
                    if !is_timer_field(p) {
                        self.push(errors::bad_timer(cell.span, &cell.text));
                    }
                }
                Arg::None
            }
            Operand::Bad => Arg::None,
        }
    }

    /// AO, DO, TDO: a point of one template (its default parameter if none).
    fn point_arg(&mut self, cmd: Cmd, cell: &Cell, template: &str) -> Arg {
        // The template decides before the parameter: `SFP 1` is the wrong
        // point, not a point that lacks a parameter.
        if let (Some(points), Ok(Syntax::Text { point, .. })) = (self.db, tlp::parse(&cell.text)) {
            if let Some(b) = points.point(point) {
                let found = points.db.block_template(b).name.as_str();
                if !found.eq_ignore_ascii_case(template) {
                    self.push(errors::wrong_point_type(cell.span, cmd.text(), point, found, template));
                    return Arg::None;
                }
            }
        }
        match self.operand(cell) {
            Operand::Const(_) => {
                self.push(errors::constant_for_param(cell.span, cmd.text(), &format!("an {template} point")));
                Arg::None
            }
            Operand::Param(p, block) => match self.template_of(block) {
                Some(found) if !found.eq_ignore_ascii_case(template) => {
                    let found = found.to_string();
                    self.push(errors::wrong_point_type(cell.span, cmd.text(), &cell.text, &found, template));
                    Arg::None
                }
                _ => self.writable(cmd, p, cell),
            },
            Operand::Unresolved | Operand::Bad => Arg::None,
        }
    }

    fn template_of(&self, block: usize) -> Option<&str> {
        self.db.map(|p| p.db.block_template(block).name.as_str())
    }

    fn numeric(&mut self, p: Param, cell: &Cell) -> Arg {
        if is_numeric(p.class) {
            Arg::Param(p)
        } else {
            self.push(errors::not_numeric(cell.span, &cell.text, class_name(p.class)));
            Arg::None
        }
    }

    fn writable(&mut self, cmd: Cmd, p: Param, cell: &Cell) -> Arg {
        if p.readonly && is_numeric(p.class) {
            self.push(errors::readonly(cell.span, &cell.text, cmd.text()));
            return Arg::None;
        }
        self.numeric(p, cell)
    }

    /// Reads a value cell: a number, a numeric TLP or a point.
    fn operand(&mut self, cell: &Cell) -> Operand {
        let syntax = match tlp::parse(&cell.text) {
            Ok(s) => s,
            Err(SyntaxError::NumberRange) => {
                self.push(errors::bad_number(cell.span, &cell.text));
                return Operand::Bad;
            }
            Err(SyntaxError::Malformed(why)) => {
                self.push(errors::bad_argument(cell.span, &cell.text, why));
                return Operand::Bad;
            }
        };
        if let Syntax::Number(v) = syntax {
            return Operand::Const(v);
        }
        let label = match &syntax {
            Syntax::Text { point, param: None } => self.labels.contains_key(&point.to_ascii_uppercase()),
            _ => false,
        };
        let Some(points) = self.db else {
            if label {
                self.push(errors::label_for_value(cell.span, &cell.text));
                return Operand::Bad;
            }
            return Operand::Unresolved;
        };
        match tlp::resolve(points, &syntax) {
            Ok((block, field)) => Operand::Param(param(points.db, block, field, &cell.text), block),
            Err(ResolveError::UnknownPoint) if label => {
                self.push(errors::label_for_value(cell.span, &cell.text));
                Operand::Bad
            }
            Err(e) => {
                let full = self.full();
                self.push(resolve_error(points.db, &syntax, e, cell.span, full));
                Operand::Bad
            }
        }
    }

    /// Table B-9's limits on constants.
    fn constant_range(&mut self, cmd: Cmd, which: u8, v: f32, cell: &Cell) {
        let whole = v.fract() == 0.0;
        let range = match (cmd, which) {
            (Cmd::Wt, 1) if !(0.1..=999_999.0).contains(&v) => "0.1 to 999,999 seconds",
            (Cmd::Brk, 1) if !(whole && (0.0..=65_535.0).contains(&v)) => "a whole number 0 to 65,535",
            (Cmd::Gte, 2) if !(whole && (0.0..=5.0).contains(&v)) => "an element 0 (month) to 5 (second)",
            (Cmd::And | Cmd::Or | Cmd::Xor, 1) if !(whole && (0.0..=255.0).contains(&v)) => "a whole number 0 to 255",
            (Cmd::Dis | Cmd::Din | Cmd::Pis | Cmd::Pin, 2) => {
                let (month, day) = ((v / 100.0).trunc(), v % 100.0);
                if !(whole && (1.0..=12.0).contains(&month) && (1.0..=31.0).contains(&day)) {
                    self.push(errors::bad_month_day(cell.span, &cell.text));
                }
                return;
            }
            _ => return,
        };
        self.push(errors::out_of_range(cell.span, cmd.text(), &cell.text, range));
    }
}

/// The field `BLOCK.FIELD` (or an alias of one) names, as the table's
/// checker would see it, for a field given on the command line
/// (`linc fst to-sfc --exit`); `Err` says what is wrong with it: no such
/// field, a bit, a field that is read-only or not numeric.
pub fn field_param(db: &Database, path: &str) -> Result<Param, String> {
    let (block, field, bit) = db.field_path(path)?;
    if bit.is_some() {
        return Err(format!("`{path}` is a bit; name a whole numeric field"));
    }
    let p = param(db, block, field, path);
    if !matches!(p.class, Class::Real | Class::Int | Class::Bits8 | Class::Bits16) {
        return Err(format!("`{path}` is {}, not a number", class_name(p.class)));
    }
    if p.readonly {
        return Err(format!("`{path}` is read-only"));
    }
    Ok(p)
}

fn param(db: &Database, block: usize, field: usize, written: &str) -> Param {
    let template = db.block_template(block);
    let (name, class, readonly) = match template.fields.get(field) {
        Some(f) => (f.name.clone(), class_of(&f.ty), f.readonly),
        None => (String::new(), Class::String, true),
    };
    let block = db.blocks.get(block).map(|b| b.name.clone()).unwrap_or_default();
    Param { block, field: name, class, readonly, written: written.to_string() }
}

/// The diagnostic of a TLP that names nothing; `full` (over the error cap,
/// only counted) leaves out the suggestion, which reads every block.
fn resolve_error(db: &Database, syntax: &Syntax<'_>, e: ResolveError, span: Span, full: bool) -> Diagnostic {
    let tname = |t: usize| db.templates.get(t).map(|t| t.name.clone()).unwrap_or_default();
    let block_name = |b: usize| db.blocks.get(b).map(|b| b.name.clone()).unwrap_or_default();
    let (point, param) = match syntax {
        Syntax::Text { point, param } => (*point, param.unwrap_or("")),
        _ => ("", ""),
    };
    match e {
        ResolveError::UnknownPoint => {
            let suggestion = if full { None } else { tlp::suggest(db, point) };
            errors::unknown_point(span, point, suggestion.as_deref())
        }
        ResolveError::UnknownParam { block } => {
            let template = db.block_template(block);
            let known: Vec<&str> = template.fields.iter().map(|f| f.name.as_str()).collect();
            errors::unknown_param(span, param, &block_name(block), &template.name, &known.join(", "))
        }
        ResolveError::NeedsParam { block } => {
            errors::needs_param(span, &block_name(block), &db.block_template(block).name)
        }
        ResolveError::NoType { t } => errors::tlp_no_type(span, t, db.device.name()),
        ResolveError::NoLogical { template, count } => {
            let l = if let Syntax::Numeric(tlp) = syntax { tlp.l } else { 0 };
            errors::tlp_no_logical(span, l, &tname(template), count)
        }
        ResolveError::NoParam { template } => {
            let p = if let Syntax::Numeric(tlp) = syntax { tlp.p } else { 0 };
            let count = db.templates.get(template).map_or(0, |t| t.fields.len());
            errors::tlp_no_param(span, p, &tname(template), count)
        }
    }
}

/// B.1.2: one to six letters and digits.
fn is_label(text: &str) -> bool {
    (1..=6).contains(&text.len()) && text.bytes().all(|b| b.is_ascii_alphanumeric())
}

fn is_timer_field(field: &str) -> bool {
    ["TMR1", "TMR2", "TMR3", "TMR4"].iter().any(|t| t.eq_ignore_ascii_case(field))
}

fn is_numeric(class: Class) -> bool {
    matches!(class, Class::Real | Class::Int | Class::Bool | Class::Bits8 | Class::Bits16)
}

fn class_name(class: Class) -> &'static str {
    match class {
        Class::Enum => "an enumeration",
        Class::String | Class::Wstr => "text",
        Class::Date => "a date",
        Class::Time => "a time",
        Class::Bseq => "a byte sequence",
        Class::Alarms => "alarms",
        Class::Bool => "a BOOL",
        _ => "a number",
    }
}

/// What an argument of this kind is, for "needs ARGUMENTn" messages.
fn describe(kind: Kind) -> &'static str {
    match kind {
        Kind::None => "unused",
        Kind::In => "a number or a parameter",
        Kind::Out => "the parameter to write",
        Kind::Label => "the label of the step to go to",
        Kind::Text => "the message text",
        Kind::Timer => "a timer, 1 to 4",
        Kind::Hist => "a history point, 1 to 200",
        Kind::Index => "a history index",
        Kind::AoPoint => "an analog output point (AOU)",
        Kind::DoPoint => "a discrete output point (DOU)",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fst::reader::read;

    const DB: &str = r#"{"device": "ROC800", "blocks": {"FST 1": {"type": "FST"}, "SFP 1": {"type": "SFP"},
        "AIN 3-1": {"type": "AIN"}, "DOU 4-1": {"type": "DOU"}, "DOU 4-2": {"type": "DOU"},
        "AOU 5-1": {"type": "AOU"}, "HIST 9": {"type": "HIST", "values": {"ARCHTYP": "FSTDATA"}}}}"#;

    fn db() -> Database {
        Database::from_json(DB).unwrap()
    }

    /// Checks rows written without the STEP column (added here).
    fn run(rows: &[&str], db: Option<&Database>) -> (Option<Checked>, Vec<Diagnostic>, String) {
        let mut src = String::from("STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\n");
        for (i, r) in rows.iter().enumerate() {
            src.push_str(&format!("{i},{r}\n"));
        }
        let (table, read_diags) = read(&src);
        assert!(read_diags.is_empty(), "{read_diags:?}");
        let (checked, diags) = check(&table, db);
        (checked, diags, src)
    }

    fn codes(rows: &[&str]) -> Vec<&'static str> {
        run(rows, Some(&db())).1.iter().map(|d| d.code.as_str()).collect()
    }

    fn steps(rows: &[&str]) -> Vec<Step> {
        let (checked, diags, _) = run(rows, Some(&db()));
        assert!(diags.iter().all(|d| !d.is_error()), "{diags:?}");
        checked.expect("checked").steps
    }

    fn param(block: &str, field: &str, class: Class, written: &str) -> Arg {
        Arg::Param(Param { block: block.into(), field: field.into(), class, readonly: false, written: written.into() })
    }

    #[test]
    fn table_b4_branches_to_step_2_and_gets_an_end() {
        let s = steps(&[",GO,PMPOFF,", "PUMPON,DO,DOU 4-1,1", "PMPOFF,DO,DOU 4-2,0"]);
        assert_eq!(s.len(), 4);
        assert_eq!(s[0].arg1, Arg::Label(2));
        assert_eq!((s[0].line, s[0].col), (2, 4));
        assert_eq!(s[2].arg1, param("DOU 4-2", "STATUS", Class::Int, "DOU 4-2"));
        assert_eq!(s[2].arg2, Arg::Const(0.0));
        assert_eq!((s[3].cmd, s[3].line, s[3].col), (Cmd::End, 4, 22));
    }

    #[test]
    fn text_tlps_resolve_to_real_names() {
        let s = steps(&["CKHIAL,VAL,\"ain3-1,hial\",", ",>=,\"AIN 3-1\",CKHIAL", ",SAV,\"sfp 1,data1\",", ",END,,"]);
        assert_eq!(s[0].arg1, param("AIN 3-1", "HIAL", Class::Real, "ain3-1,hial"));
        assert_eq!(s[1].arg1, param("AIN 3-1", "EU", Class::Real, "AIN 3-1"));
        assert_eq!(s[1].arg2, Arg::Label(0));
        assert_eq!(s[2].arg1, param("SFP 1", "DATA1", Class::Real, "sfp 1,data1"));
        assert_eq!(s.len(), 4, "an END that is there is not added");
        let s = steps(&[",VAL,\"98,0,3\",", ",ST,2,50", ",ST,\"FST 1,TMR4\",1"]);
        assert_eq!(s[0].arg1, param("SFP 1", "DATA2", Class::Real, "98,0,3"));
        assert_eq!(s[1].arg1, param("", "TMR2", Class::Int, "2"));
        assert_eq!(s[2].arg1, param("FST 1", "TMR4", Class::Int, "FST 1,TMR4"));
    }

    #[test]
    fn labels() {
        assert_eq!(codes(&["TOOLONG1,VAL,1,", "A-B,VAL,1,", "END,VAL,1,"]), ["E0404", "E0404", "E0405"]);
        let (_, d, src) = run(&["L1,VAL,1,", "l1,VAL,2,", ",GO,L2,"], Some(&db()));
        assert_eq!(d.iter().map(|d| d.code).collect::<Vec<_>>(), ["E0406", "E0407"]);
        assert_eq!(&src[d[0].span.start..d[0].span.end], "l1");
        assert_eq!(&src[d[0].secondary[0].span.start..d[0].secondary[0].span.end], "L1");
        assert_eq!(d[1].help, ["did you mean `L1`?"]);
        assert_eq!(codes(&[",GO,3,", ",GO,\"SFP 1,DATA1\","]), ["E0411", "E0411"]);
        assert_eq!(codes(&["TOP,VAL,TOP,"]), ["E0412"]);
    }

    #[test]
    fn one_end_only() {
        let (_, d, src) = run(&[",END,,", ",END,,"], Some(&db()));
        assert_eq!(d.iter().map(|d| d.code).collect::<Vec<_>>(), ["E0408"]);
        assert_eq!(d[0].span.start, src.rfind("END").unwrap());
    }

    #[test]
    fn argument_counts() {
        assert_eq!(codes(&[",ABS,1,", ",VAL,,2", ",SAV,,", ",MSG,hello,"]), ["E0409", "E0410", "E0409", "E0410"]);
        let (_, d, src) = run(&[",SAV,,"], Some(&db()));
        assert_eq!(&src[d[0].span.start..d[0].span.end], "SAV", "a missing argument is shown at its command");
    }

    #[test]
    fn message_text_is_cut_with_a_warning() {
        let s =
            steps(&[",MSG,\"Pump 1 started, flow rate is now normal\",", ",ALM,High level,\"AIN 3-1\"", ",EVT,short,"]);
        assert_eq!(s[0].arg1, Arg::Text("Pump 1 started, flow rate is n".into()));
        assert_eq!(s[1].arg1, Arg::Text("High level".into()));
        assert_eq!(s[2].arg2, Arg::None);
        assert_eq!(
            codes(&[",MSG,\"Pump 1 started, flow rate is now normal\",", ",ALM,High level!,"]),
            ["W0401", "W0401"]
        );
    }

    #[test]
    fn parameter_kinds() {
        assert_eq!(codes(&[",VAL,\"AIN 3-1,UNITS\",", ",VAL,\"FST 1,CMPFLG\","]), ["E0414"]);
        assert_eq!(codes(&[",SAV,\"AIN 3-1,ALARM\",", ",SAV,3,"]), ["E0415", "E0413"]);
        assert_eq!(
            codes(&[",WDB,9,\"FST 1,IP\"", ",WDB,9,-1", ",RDB,9,2.5", ",WTM,10,\"FST 1,R4\""]),
            ["E0415", "E0417", "E0417"]
        );
        assert_eq!(
            codes(&[",WDB,0,1", ",WDB,201,1", ",RDB,\"FST 1,R1\",1", ",WDB,\"HIST 9,ARCHTYP\",1"]),
            ["E0417", "E0417", "E0414"]
        );
    }

    #[test]
    fn timers_and_output_points() {
        assert_eq!(
            codes(&[",ST,5,10", ",CT,0,X", "X,ST,\"SFP 1,DATA1\",1", ",ST,1.5,1"]),
            ["E0416", "E0416", "E0416", "E0416"]
        );
        assert_eq!(
            codes(&[",AO,\"AOU 5-1\",50", ",DO,\"AOU 5-1\",1", ",AO,\"SFP 1\",1", ",TDO,2,3"]),
            ["E0427", "E0427", "E0413"]
        );
        let s = steps(&[",AO,AOU5-1,50", ",TDO,\"DOU 4-1,TDOON\",3"]);
        assert_eq!(s[0].arg1, param("AOU 5-1", "EU", Class::Real, "AOU5-1"));
        assert_eq!(s[1].arg1, param("DOU 4-1", "TDOON", Class::Real, "DOU 4-1,TDOON"));
        assert_eq!(codes(&[",DO,\"DOU 4-1,ALARM\",1"]), ["E0415"]);
    }

    #[test]
    fn constant_ranges() {
        assert_eq!(codes(&[",WT,0.1,", ",WT,999999,", ",WT,0.05,", ",WT,1000000,"]), ["E0417", "E0417"]);
        assert_eq!(codes(&[",BRK,65535,", ",BRK,65536,", ",BRK,1.5,"]), ["E0417", "E0417"]);
        assert_eq!(codes(&[",GTE,\"SFP 1,DATA1\",5", ",GTE,0,6"]), ["E0417"]);
        assert_eq!(codes(&[",AND,255,", ",OR,256,", ",XOR,-1,", ",AND,\"FST 1,MISC1\","]), ["E0417", "E0417"]);
        assert_eq!(
            codes(&[",DIS,9,1123", ",DIN,9,1301", ",PIS,9,1232", ",PIN,9,0001", ",DIS,9,100"]),
            ["E0418", "E0418", "E0418", "E0418"]
        );
        assert_eq!(codes(&[",VAL,1e39,", ",VAL,12abc,"]), ["E0419", "E0420"]);
    }

    #[test]
    fn unknown_points_and_parameters() {
        assert_eq!(
            codes(&[",VAL,\"SFP 2,DATA1\",", ",VAL,\"SFP 1,DATA21\",", ",VAL,\"SFP 1\","]),
            ["E0421", "E0422", "E0423"]
        );
        let (_, d, _) = run(&[",VAL,\"16,0,2\",", ",VAL,\"98,1,2\",", ",VAL,\"98,0,22\","], Some(&db()));
        assert_eq!(d.iter().map(|d| d.code).collect::<Vec<_>>(), ["E0424", "E0425", "E0426"]);
        assert!(d[0].message.contains("ROC800"), "{}", d[0].message);
        assert!(d[1].message.contains("SFP"), "{}", d[1].message);
    }

    #[test]
    fn without_a_database_points_are_accepted_and_nothing_is_checked_out() {
        let (checked, d, _) = run(&[",VAL,\"XYZ 1,FOO\",", ",SAV,\"98,7,7\",", ",GO,NOWHR,"], None);
        assert_eq!(d.iter().map(|d| d.code).collect::<Vec<_>>(), ["E0407"]);
        assert!(checked.is_none());
        let (checked, d, _) = run(&[",VAL,1,"], None);
        assert!(checked.is_none() && d.is_empty());
        let (_, d, _) = run(&[",ST,\"FST 2,TMR3\",10", ",ST,\"FST 2,R1\",10", ",ST,7,10", ",WT,0,", "X,VAL,X,"], None);
        assert_eq!(d.iter().map(|d| d.code).collect::<Vec<_>>(), ["E0416", "E0416", "E0417", "E0412"]);
    }

    #[test]
    fn unknown_commands_stop_the_table_from_compiling_without_a_second_error() {
        let (table, read_diags) = read("STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\n0,,VALL,1,\n");
        assert_eq!(read_diags.len(), 1);
        let (checked, d) = check(&table, Some(&db()));
        assert!(checked.is_none() && d.is_empty());
    }

    #[test]
    fn too_many_steps_is_located_at_the_first_step_over_the_limit() {
        let mut rows = vec![",VAL,1,"; MAX_STEPS - 1];
        rows.push(",END,,");
        let (checked, d, _) = run(&rows, Some(&db()));
        assert!(d.is_empty() && checked.is_some(), "{MAX_STEPS} steps with their END fit: {d:?}");
        rows.insert(0, ",VAL,1,");
        let (_, d, src) = run(&rows, Some(&db()));
        assert_eq!(d.iter().map(|d| d.code).collect::<Vec<_>>(), ["E0132"]);
        let line = src[..d[0].span.start].matches('\n').count() + 1;
        assert_eq!((line, &src[d[0].span.start..d[0].span.end]), (MAX_STEPS + 2, "END"), "step {MAX_STEPS}");
        let rows = vec![",VAL,1,"; MAX_STEPS];
        let (_, d, src) = run(&rows, Some(&db()));
        let line = src[..d[0].span.start].matches('\n').count() + 1;
        assert_eq!((d[0].code.as_str(), line), ("E0132", MAX_STEPS + 1), "the appended END is charged to the last row");
        assert!(d[0].label.contains("END appended"), "{:?}", d[0]);
    }

    #[test]
    fn errors_are_capped() {
        let rows = vec![",ABS,1,"; MAX_ERRORS + 5];
        let (_, d, _) = run(&rows, Some(&db()));
        assert_eq!(d.len(), MAX_ERRORS + 1);
        assert_eq!(d[MAX_ERRORS].code, "E0023");
        assert!(d[MAX_ERRORS].message.starts_with("5 more"));
    }
}
