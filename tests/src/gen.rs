//! Random numeric, string and library-call ST over the guide database, for
//! the differential tests (two tiers; `linc fmt` before and after).

use crate::rng::Rng;

/// Random numeric ST over the RECIPE fields of the guide database.
pub struct Gen {
    pub rng: Rng,
    depth: u32,
}

const BLOCKS: [&str; 2] = ["Recipe", "Counters"];

impl Gen {
    pub fn new(seed: u64) -> Gen {
        Gen { rng: Rng::new(seed), depth: 0 }
    }

    fn pick<'a>(&mut self, xs: &[&'a str]) -> &'a str {
        xs[self.rng.below(xs.len())]
    }

    fn int_var(&mut self) -> String {
        let b = self.pick(&BLOCKS);
        if self.rng.one_in(6) {
            let i = self.offset();
            return format!("{b}.N0{{{i}}}");
        }
        format!("{b}.N{}", self.rng.below(8))
    }

    fn real_var(&mut self) -> String {
        let b = self.pick(&BLOCKS);
        if self.rng.one_in(6) {
            let i = self.offset();
            return format!("{b}.A0{{{i}}}");
        }
        format!("{b}.A{}", self.rng.below(8))
    }

    /// An offset: mostly a field, so that it is checked when the program
    /// runs (a constant out of the run is refused when compiling).
    fn offset(&mut self) -> String {
        match self.rng.below(3) {
            0 => format!("{} + 1", self.int_var()),
            1 => self.int_expr(1),
            _ => format!("{}.N{}", self.pick(&BLOCKS), self.rng.below(8)),
        }
    }

    /// A REAL field that starts a run of eight, for offsets.
    fn real_var_base(&mut self) -> String {
        format!("{}.A0", self.pick(&BLOCKS))
    }

    fn int_expr(&mut self, d: u32) -> String {
        if d == 0 || self.rng.one_in(3) {
            return match self.rng.below(4) {
                0 => format!("{}", self.rng.below(10) as i32 - 2),
                1 => ["2147483647", "-2147483647", "65535", "40000"][self.rng.below(4)].to_string(),
                _ => self.int_var(),
            };
        }
        let a = self.int_expr(d - 1);
        let b = self.int_expr(d - 1);
        match self.rng.below(9) {
            0 => format!("({a} + {b})"),
            1 => format!("({a} - {b})"),
            2 => format!("({a} * {b})"),
            3 => format!("({a} / {b})"),
            4 => format!("({a} MOD {b})"),
            5 => format!("(-{a})"),
            6 => format!("({a} AND {b})"),
            7 => format!("({a} XOR {b})"),
            _ => format!("({a} OR {b})"),
        }
    }

    fn real_expr(&mut self, d: u32) -> String {
        if d == 0 || self.rng.one_in(3) {
            return match self.rng.below(5) {
                0 => ["0.0", "1.5", "-2.25", "1.0E30", "0.001"][self.rng.below(5)].to_string(),
                1 => self.int_expr(0),
                _ => self.real_var(),
            };
        }
        let a = self.real_expr(d - 1);
        let b = self.real_expr(d - 1);
        match self.rng.below(5) {
            0 => format!("({a} + {b})"),
            1 => format!("({a} - {b})"),
            2 => format!("({a} * {b})"),
            3 => format!("({a} / {b})"),
            _ => format!("(-{a})"),
        }
    }

    fn cond(&mut self, d: u32) -> String {
        let c = match self.rng.below(6) {
            0 => format!("{} < {}", self.real_expr(d), self.real_expr(d)),
            1 => format!("{} >= {}", self.real_expr(d), self.real_expr(d)),
            2 => format!("{} = {}", self.int_expr(d), self.int_expr(d)),
            3 => format!("{} <> {}", self.int_expr(d), self.int_expr(d)),
            4 => format!("{} > {}", self.int_expr(d), self.int_expr(d)),
            _ => format!("{} <= {}", self.int_expr(d), self.int_expr(d)),
        };
        match self.rng.below(5) {
            0 => format!("NOT ({c})"),
            1 => format!("({c}) AND ({})", self.cond(0)),
            2 => format!("({c}) OR ({})", self.cond(0)),
            _ => c,
        }
    }

    /// A byte-sequence field, or a STRING or enumerated one read as text.
    fn str_var(&mut self) -> String {
        ["RAW_COM.Buffer1", "RAW_COM.Buffer2", "RAW_COM.Tx_Value", "Raw1.Rx_Value", "RAW_COM.Mode"][self.rng.below(5)]
            .to_string()
    }

    fn str_expr(&mut self, d: u32) -> String {
        if d == 0 || self.rng.one_in(3) {
            return match self.rng.below(3) {
                0 => ["''", "'ab'", "'A$42c'", "'$$x'", "'x$Ly'", "'AUTO'"][self.rng.below(6)].to_string(),
                _ => self.str_var(),
            };
        }
        let a = self.str_expr(d - 1);
        match self.rng.below(7) {
            0 | 1 => format!("CONCAT({a}, {})", self.str_expr(d - 1)),
            2 => {
                let f = ["'05I'", "'X'", "'6.2F'", "'B'", "'3F'", "'10E'"][self.rng.below(6)];
                let v = if self.rng.one_in(2) { self.int_expr(1) } else { self.real_expr(1) };
                format!("FORMAT({f}, {v})")
            }
            3 => format!("LEFT({a}, {})", self.int_expr(1)),
            4 => format!("MID({a}, {}, {})", self.int_expr(0), self.int_expr(0)),
            5 => format!("UCASE({a})"),
            _ => format!("REPLACE_INT16({a}, {}, {}, 1)", self.int_expr(0), self.int_expr(1)),
        }
    }

    /// A statement with strings or library calls, which compiled code
    /// hands to the runtime's services.
    fn service_stmt(&mut self) -> String {
        match self.rng.below(7) {
            0 | 1 => format!("{} := {};\n", ["RAW_COM.Buffer1", "RAW_COM.Buffer2"][self.rng.below(2)], self.str_expr(2)),
            2 => {
                let f = ["SQRT", "LN", "ABS", "EXP", "RANDOM"][self.rng.below(5)];
                format!("{} := {f}({});\n", self.real_var(), self.real_expr(1))
            }
            3 => format!("{} := LEN({}) + FIND({}, 'b', 1);\n", self.int_var(), self.str_expr(1), self.str_expr(1)),
            4 => format!("RAW_COM.Mode := {};\n", ["'AUTO'", "'manual'", "'BAD'", "RAW_COM.Buffer1"][self.rng.below(4)]),
            5 => {
                let (a, b) = (self.str_expr(1), self.str_expr(1));
                let op = ["=", "<>", "<", ">", "<=", ">="][self.rng.below(6)];
                format!("IF {a} {op} {b} THEN\n{}END_IF;\n", self.stmts(1))
            }
            // Past the string limit (R0007), or the watchdog if it stays empty.
            _ if self.rng.one_in(4) => {
                "WHILE LEN(RAW_COM.Buffer2) < 70000 DO\n  RAW_COM.Buffer2 := CONCAT(RAW_COM.Buffer2, RAW_COM.Buffer2);\nEND_WHILE;\n"
                    .to_string()
            }
            _ => "FOR RAW_COM.I1 := 1 TO 20 DO\n  RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer1, FORMAT('05I', RAW_COM.I1));\nEND_FOR;\n"
                .to_string(),
        }
    }

    pub fn stmts(&mut self, n: usize) -> String {
        (0..n).map(|_| self.stmt()).collect()
    }

    fn stmt(&mut self) -> String {
        let nested = self.depth < 3;
        let kind = if nested { self.rng.below(10) } else { self.rng.below(4) };
        self.depth += 1;
        let s = match kind {
            0 | 1 => format!("{} := {};\n", self.int_var(), self.int_expr(2)),
            2 | 3 => format!("{} := {};\n", self.real_var(), self.real_expr(2)),
            4 | 5 => {
                let (c, t) = (self.cond(1), self.stmts(2));
                let e = if self.rng.one_in(2) { format!("ELSE\n{}", self.stmts(1)) } else { String::new() };
                format!("IF {c} THEN\n{t}{e}END_IF;\n")
            }
            6 | 7 => {
                let v = format!("{}.N{}", self.pick(&BLOCKS), self.rng.below(8));
                let hi = self.rng.below(9);
                let by =
                    if self.rng.one_in(3) { format!(" BY {}", [1, 2, -1][self.rng.below(3)]) } else { String::new() };
                let body = format!("{}{{{v}}} := {};\n{}", self.real_var_base(), self.real_expr(1), self.stmts(1));
                format!("FOR {v} := 0 TO {hi}{by} DO\n{body}END_FOR;\n")
            }
            8 => format!("WHILE {} DO\n{}END_WHILE;\n", self.cond(1), self.stmts(2)),
            _ if self.rng.one_in(3) => self.service_stmt(),
            _ if self.rng.one_in(2) => format!("{} := {};\n", self.real_var(), self.int_expr(1)),
            _ => format!("{} := {};\n", self.int_var(), self.real_expr(1)),
        };
        self.depth -= 1;
        s
    }
}

/// One loop around `n` statements of the kinds that make translation slow
/// and make exits: REAL stores (checked for non-finite values), INT
/// division and MOD, and IFs (basic blocks) — for the tests of the
/// compiling tier's limits and of translating in the background.
pub fn slow_to_translate(n: usize) -> String {
    let fields = ["PV", "SL", "TrimSP", "OP", "HR", "LR", "XP", "TI", "TD"];
    let pids = ["TIC_100", "HEAT_PID", "PIC_004", "PIC_005", "pid1"];
    let real = |i: usize| format!("{}.{}", pids[i % pids.len()], fields[i / pids.len() % fields.len()]);
    let mut s = String::from("FOR Counters.N0 := 1 TO 3 DO\n");
    for i in 0..n {
        s.push_str(&match i % 3 {
            0 => format!("  {} := {} * 0.5 - {} * 0.25 + {}.25;\n", real(i), real(i + 7), real(i + 11), i % 97),
            1 => format!("  Counters.N1 := Counters.N1 + Counters.N0 * {} / {} MOD 7;\n", i % 89, i % 13 + 1),
            _ => {
                format!("  IF {} > {}.5 THEN {} := {} + 1.0; END_IF;\n", real(i + 3), i % 89, real(i + 5), real(i + 5))
            }
        });
    }
    s.push_str("END_FOR;\n");
    s
}
