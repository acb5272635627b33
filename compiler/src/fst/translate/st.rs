//! Each FST command as ST statements that do what its instructions do
//! (`super::super::lower`), value for value: the same single-precision
//! arithmetic, a math result that is no finite number leaving RR as it was
//! (`x * 0.0 = 0.0` holds exactly for the finite ones), `==` on the bits
//! (the sign of a zero told by `ATAN2(0.0, x)`, π for −0 and 0 for +0), and
//! stores converted as the table converts them.

use super::super::{Arg, Checked, Cmd, Param, Step, Table};
use super::Target;
use linc_format::object::Class;

/// Why a command has no faithful ST translation (`None`: it has one).
pub(super) fn refusal(step: &Step, in_one_run: bool) -> Option<&'static str> {
    Some(match step.cmd {
        Cmd::Wt if in_one_run => "WT waits for a time; one run of an action cannot (a sequence can: `linc fst to-sfc`)",
        Cmd::Wt if !matches!(step.arg1, Arg::Const(_)) => {
            "WT for a time read from a parameter: a transition tests a time written in the sequence"
        }
        Cmd::Brk => "BRK slows the table to one command a period; an action runs its statements at once",
        Cmd::Alm | Cmd::Evt => "ALM and EVT write the device's alarm and event logs, which ST cannot reach",
        Cmd::Dwk | Cmd::Mnd => "DWK and MND read the device clock, which ST has no function for",
        Cmd::Pow => "`**` with a result too large for a REAL leaves RR as it was; ST's `**` stops with R0005",
        Cmd::Msg if msg_text(step).is_some_and(|t| string(&t).is_none()) => {
            "the text holds both kinds of quote, or a `$` before one, which no ST string constant stores as written"
        }
        Cmd::Rdb
        | Cmd::Wdb
        | Cmd::Wtm
        | Cmd::Dhv
        | Cmd::Dht
        | Cmd::Phv
        | Cmd::Pht
        | Cmd::Mhv
        | Cmd::Dis
        | Cmd::Din
        | Cmd::Pis
        | Cmd::Pin
        | Cmd::Gte => "history commands use the device's archives, which ST cannot reach",
        _ => return None,
    })
}

/// The comment the translation starts with.
pub(super) fn header(t: &Target, steps: usize) -> String {
    format!(
        "(* `linc fst to-st`: {} steps of an FST table as one action. One run is\n   one cycle of the table on block {}, at most {} steps a cycle: run it in\n   the block's task with the block's FileName cleared. *)\n\n",
        steps, t.block, t.steps_per_cycle
    )
}

/// A REAL constant as ST reads it back to the same single-precision value.
fn real(c: f32) -> String {
    let mut text = format!("{}", c.abs());
    if !text.contains('.') {
        text.push_str(".0");
    }
    if (text.parse::<f64>().unwrap_or(f64::NAN) as f32).to_bits() != c.abs().to_bits() {
        text = format!("{:?}", f64::from(c.abs()));
    }
    if c.is_sign_negative() {
        format!("(-{text})")
    } else {
        text
    }
}

/// An ST string constant that a STRING field stores as `text`: a string
/// constant keeps its `$` sequences as written, so the text goes between
/// quotes it does not hold, as long as no `$` stands before that quote.
fn string(text: &str) -> Option<String> {
    ['\'', '"'].into_iter().find_map(|q| {
        let fits = !text.contains(q) && !text.ends_with('$') && !text.contains(&format!("${q}"));
        fits.then(|| format!("{q}{text}{q}"))
    })
}

/// MSG's text, as much of it as MSG1 takes.
fn msg_text(s: &Step) -> Option<String> {
    match &s.arg1 {
        Arg::Text(t) => Some(t.chars().take(30).collect()),
        _ => None,
    }
}

/// Writes the action's lines.
pub(super) struct Writer<'a> {
    block: &'a str,
    table: &'a Table,
    checked: &'a Checked,
    out: String,
}

impl<'a> Writer<'a> {
    pub(super) fn new(block: &'a str, table: &'a Table, checked: &'a Checked) -> Writer<'a> {
        Writer { block, table, checked, out: String::new() }
    }

    pub(super) fn line(&mut self, depth: usize, text: &str) {
        self.out.push_str(&"    ".repeat(depth));
        self.out.push_str(text);
        self.out.push('\n');
    }

    pub(super) fn finish(self) -> String {
        self.out
    }

    /// A field of the FST block.
    pub(super) fn field(&self, name: &str) -> String {
        format!("[{}.{name}]", self.block)
    }

    fn param(&self, p: &Param) -> String {
        let block = if p.block.is_empty() { self.block } else { &p.block };
        format!("[{block}.{}]", p.field)
    }

    /// An argument's value as a REAL expression.
    fn value(&self, a: &Arg) -> String {
        match a {
            Arg::Const(c) => real(*c),
            Arg::Param(p) if p.class == Class::Real => self.param(p),
            Arg::Param(p) => format!("FLOAT({})", self.param(p)),
            _ => "0.0".to_string(),
        }
    }

    /// `value(a) OP 0.0`, with a whole-number parameter compared as one;
    /// `None` for a constant, whose answer is known (`Some` of it then).
    fn against_zero(&self, a: &Arg, op: &str) -> Result<String, bool> {
        let holds = |x: f32| match op {
            "=" => x == 0.0,
            "<>" => x != 0.0,
            _ => x > 0.0,
        };
        match a {
            Arg::Const(c) => Err(holds(*c)),
            Arg::Param(p) if p.class != Class::Real => Ok(format!("{} {op} 0", self.param(p))),
            _ => Ok(format!("{} {op} 0.0", self.value(a))),
        }
    }

    /// `p := 1` when `test` holds, else `p := 0` (as truth values).
    fn truth_by(&self, p: &Param, test: Result<String, bool>) -> Vec<String> {
        match test {
            Err(on) => vec![self.store_truth(p, on)],
            Ok(t) => vec![
                format!("IF {t} THEN"),
                format!("    {}", self.store_truth(p, true)),
                "ELSE".into(),
                format!("    {}", self.store_truth(p, false)),
                "END_IF;".into(),
            ],
        }
    }

    /// `p := e` (a REAL expression), converted as the table stores.
    fn store(&self, p: &Param, e: &str) -> String {
        let target = self.param(p);
        match p.class {
            Class::Real => format!("{target} := {e};"),
            Class::Bits8 => format!("{target} := MAX(0, MIN(ROUND({e}), 255));"),
            Class::Bits16 => format!("{target} := MAX(0, MIN(ROUND({e}), 65535));"),
            Class::Bool => format!("{target} := ROUND({e}) <> 0;"),
            _ => format!("{target} := ROUND({e});"),
        }
    }

    /// `p := 0` or `1`, as the table stores a truth value.
    fn store_truth(&self, p: &Param, on: bool) -> String {
        match p.class {
            Class::Real => format!("{} := {};", self.param(p), if on { "1.0" } else { "0.0" }),
            Class::Bool => format!("{} := {};", self.param(p), if on { "TRUE" } else { "FALSE" }),
            _ => format!("{} := {};", self.param(p), u8::from(on)),
        }
    }

    /// The comment naming step `n`, then its statements.
    pub(super) fn step(&mut self, n: usize, depth: usize) {
        let s = &self.checked.steps[n];
        let mut what = super::super::lower::describe(s.cmd, &s.arg1, &s.arg2);
        if let Some(c) = self.table.rows.get(n).map(|r| r.comment.trim()).filter(|c| !c.is_empty()) {
            what = format!("{what}: {c}");
        }
        self.line(depth, &format!("(* {n}: {} *)", what.replace("(*", "( *").replace("*)", "* )")));
        for line in self.statements(s) {
            self.line(depth, &line);
        }
    }

    /// What step `s` does besides deciding where to go.
    fn statements(&self, s: &Step) -> Vec<String> {
        let (rr, v) = (self.field("RR"), self.value(&s.arg1));
        let keep =
            |e: String| vec![format!("IF ({e}) * 0.0 = 0.0 THEN"), format!("    {rr} := {e};"), "END_IF;".into()];
        let guarded = |test: String, f: &str| {
            vec![format!("IF {test} THEN"), format!("    {rr} := {f}({rr});"), "END_IF;".into()]
        };
        match s.cmd {
            Cmd::Add => keep(format!("{rr} + {v}")),
            Cmd::Sub => keep(format!("{rr} - {v}")),
            Cmd::Mul => keep(format!("{rr} * {v}")),
            Cmd::Div => {
                let mut out = vec![format!("IF {v} <> 0.0 THEN")];
                out.extend(keep(format!("{rr} / {v}")).into_iter().map(|l| format!("    {l}")));
                out.push("END_IF;".into());
                out
            }
            Cmd::Abs => vec![format!("IF {rr} < 0.0 THEN"), format!("    {rr} := -{rr};"), "END_IF;".into()],
            Cmd::Exp => guarded(format!("{rr} <= 88.72"), "EXP"),
            Cmd::Log => guarded(format!("{rr} > 0.0"), "LOG"),
            Cmd::Ln => guarded(format!("{rr} > 0.0"), "LN"),
            Cmd::Sqr => guarded(format!("{rr} >= 0.0"), "SQRT"),
            // Toward zero, keeping the sign of a zero; from 2**23 on every
            // REAL is whole already.
            Cmd::Int => vec![
                format!("IF ABS({rr}) < 1.0 THEN"),
                format!("    {rr} := {rr} * 0.0;"),
                format!("ELSIF ABS({rr}) < 8388608.0 THEN"),
                format!("    {rr} := FLOAT(TRUNC({rr}));"),
                "END_IF;".into(),
            ],
            Cmd::P3 => {
                let r = |k: u8| self.field(&format!("R{k}"));
                keep(format!("(({} * {rr} + {}) * {rr} + {}) * {rr} + {}", r(1), r(2), r(3), r(4)))
            }
            Cmd::Not => {
                let cf = self.field("CMPFLG");
                vec![
                    format!("IF {cf} = 0 THEN"),
                    format!("    {cf} := 1;"),
                    "ELSE".into(),
                    format!("    {cf} := 0;"),
                    "END_IF;".into(),
                ]
            }
            Cmd::And | Cmd::Or | Cmd::Xor => {
                let cf = self.field("CMPFLG");
                vec![format!("{cf} := {cf} {} MAX(0, MIN(ROUND({v}), 255));", s.cmd.text())]
            }
            Cmd::St => match &s.arg1 {
                Arg::Param(t) if t.class == Class::Int => {
                    vec![format!("{} := MAX(0, ROUND({}));", self.param(t), self.value(&s.arg2))]
                }
                Arg::Param(t) => vec![self.store(t, &format!("FLOAT(MAX(0, ROUND({})))", self.value(&s.arg2)))],
                _ => Vec::new(),
            },
            Cmd::Val => vec![format!("{rr} := {v};")],
            Cmd::Sav => match &s.arg1 {
                Arg::Param(p) => vec![self.store(p, &rr)],
                _ => Vec::new(),
            },
            Cmd::Msg => {
                let mut out = Vec::new();
                if let Some(text) = msg_text(s).and_then(|t| string(&t)) {
                    out.push(format!("{} := {text};", self.field("MSG1")));
                }
                out.push(format!("{} := {};", self.field("MSGDAT"), self.value(&s.arg2)));
                out
            }
            Cmd::Ao | Cmd::Do | Cmd::Tdo => self.output(s),
            _ => Vec::new(),
        }
    }

    /// AO, DO and TDO: nothing is sent to a point in manual (MODE not 0).
    fn output(&self, s: &Step) -> Vec<String> {
        let Arg::Param(p) = &s.arg1 else { return Vec::new() };
        let at = |field: &str, class| Param { field: field.to_string(), class, ..p.clone() };
        let v = self.value(&s.arg2);
        let mode = self.against_zero(&Arg::Param(at("MODE", Class::Int)), "=").unwrap_or_default();
        let mut body = match s.cmd {
            Cmd::Ao => vec![self.store(p, &v)],
            Cmd::Do => self.truth_by(p, self.against_zero(&s.arg2, "<>")),
            _ => {
                let mut out =
                    vec![self.store(&at("TDOON", Class::Real), &v), self.store(&at("TDOREM", Class::Real), &v)];
                out.extend(self.truth_by(&at("STATUS", Class::Int), self.against_zero(&s.arg2, ">")));
                out
            }
        };
        body.iter_mut().for_each(|l| l.insert_str(0, "    "));
        let mut out = vec![format!("IF {mode} THEN")];
        out.append(&mut body);
        out.push("END_IF;".into());
        out
    }

    /// The condition under which step `n` branches to its label.
    pub(super) fn condition(&self, n: usize) -> String {
        let s = &self.checked.steps[n];
        let (rr, v) = (self.field("RR"), self.value(&s.arg1));
        match s.cmd {
            Cmd::Lt => format!("{rr} < {v}"),
            Cmd::Le => format!("{rr} <= {v}"),
            Cmd::Gt => format!("{rr} > {v}"),
            Cmd::Ge => format!("{rr} >= {v}"),
            Cmd::Eq => self.same_bits(&rr, &s.arg1),
            Cmd::Ne => format!("NOT ({})", self.same_bits(&rr, &s.arg1)),
            Cmd::Ct => format!("{v} > 0.0"),
            _ => "TRUE".into(),
        }
    }

    /// `rr` and the argument have the same single-precision bits: equal,
    /// and, when zero, of the same sign (neither is ever NaN: RR and the
    /// database hold finite numbers only).
    fn same_bits(&self, rr: &str, a: &Arg) -> String {
        let negative = |x: &str| format!("ATAN2(0.0, {x}) > 1.0");
        match a {
            Arg::Const(c) if *c != 0.0 => format!("{rr} = {}", real(*c)),
            Arg::Const(c) if c.is_sign_negative() => format!("{rr} = 0.0 AND {}", negative(rr)),
            Arg::Const(_) => format!("{rr} = 0.0 AND NOT ({})", negative(rr)),
            _ => {
                let v = self.value(a);
                format!("{rr} = {v} AND ({}) = ({})", negative(rr), negative(&v))
            }
        }
    }
}
