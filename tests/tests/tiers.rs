//! The compiling tier against the interpreter (ADR 0011): every program
//! the conformance suite writes that compiles against the guide database,
//! the guide's example actions, and generated numeric programs run on both
//! tiers, which must leave identical stores, retained slots and errors
//! (code, message, line, column). 2,400 generated cases by default (about
//! 2,000 compile); `TIER_CASES=100000` for a long run.

use linc_compiler::st::lower::{self, Lines};
use linc_compiler::Context;
use linc_conformance::gen::Gen;
use linc_conformance::guide_db;
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Vm};
use linc_runtime::{Linked, Program, RuntimeError};

/// Compiles `src` against the guide database, or `None` if it does not.
fn compile(src: &str) -> Option<Vec<u8>> {
    let ctx = Context::of(Some(guide_db()));
    let r = linc_compiler::check_source(src, "case", ctx);
    let program = r.program?;
    let obj = lower::lower_program(&program, "case.st", &Lines::new(src)).ok()?;
    Some(obj.to_bytes())
}

/// What one tier leaves behind after some cycles.
#[derive(Debug, PartialEq)]
struct Ending {
    cells: String,
    retained: Vec<u32>,
    ignored: u64,
    error: Option<RuntimeError>,
    /// The writes the run reported to its tracer: the cell, its value, and
    /// (for the first few) a digest of the whole store at that moment; past
    /// [`TRACED`] writes only their number.
    trace: Vec<(u32, String, u64)>,
    notes: u64,
    /// A covered run's counts at the instructions a report reads: (pc,
    /// runs, jumps taken).
    coverage: Vec<(usize, u64, u64)>,
}

/// Writes of a run whose values a traced case keeps, and of those the ones
/// with a digest of the store (formatting it is slow in a debug build).
const TRACED: usize = 2_000;
const DIGESTS: usize = 50;

fn digest(store: &Store) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    format!("{:?}", store.cells).hash(&mut h);
    h.finish()
}

struct Case {
    linked: Linked,
    watchdog: u64,
    force: Option<u32>,
    /// Bytes of strings a run may make, when not the default.
    strings: Option<usize>,
}

impl Case {
    fn new(src: &str, watchdog: u64, force: Option<u32>) -> Option<Case> {
        let verified = linc_runtime::load(&compile(src)?).ok()?;
        let store = Store::new(guide_db().clone());
        let linked = verified.link(&store, &[Program { unit: 0, own: None }]).ok()?;
        Some(Case { linked, watchdog, force, strings: None })
    }

    /// Whether the compiling tier translates the program at all.
    fn compiles(&self) -> bool {
        let store = Store::new(guide_db().clone());
        linc_runtime::jit::compile(&self.linked, &store, 0, 0).is_some()
    }

    /// A run; `traced` runs report every write (the trace is compared too).
    fn run_traced(&self, jit: bool, cycles: u32, traced: bool) -> Ending {
        self.run(jit, cycles, traced, false)
    }

    /// A run, traced or not, counting coverage or not.
    fn run(&self, jit: bool, cycles: u32, traced: bool, covered: bool) -> Ending {
        let mut linked = self.linked.clone();
        if covered {
            linked.enable_coverage();
        }
        let mut store = Store::new(guide_db().clone());
        store.now = 1_000_000.0;
        if let Some(c) = self.force {
            store.set_forced(c, true);
        }
        let mut vm = Vm::new(self.watchdog, Clock::new(1, 0));
        vm.jit = jit;
        vm.jit_after = 0;
        if let Some(budget) = self.strings {
            vm.string_budget = budget;
        }
        let mut act = Activation::new(&linked, 0, 0);
        let mut error = None;
        let (mut trace, mut notes) = (Vec::new(), 0);
        for _ in 0..cycles {
            let mut note = |s: &Store, c: u32| {
                notes += 1;
                if trace.len() < TRACED {
                    let d = if trace.len() < DIGESTS { digest(s) } else { 0 };
                    trace.push((c, s.show(c), d));
                }
            };
            let tracer: linc_runtime::vm::Tracer = if traced { Some(&mut note) } else { None };
            if let Err(e) = vm.run(&linked, &mut act, &mut store, tracer) {
                error = Some(e);
                break;
            }
            store.now += 1.0;
        }
        Ending {
            cells: format!("{:?}", store.cells),
            retained: act.retained.clone(),
            ignored: store.ignored_writes,
            error,
            trace,
            notes,
            coverage: coverage_points(&linked),
        }
    }

    fn assert_tiers_agree(&self, what: &str) {
        // Coverage with a trace is the generated cases' (one in twelve).
        for (traced, covered) in [(false, false), (true, false), (false, true)] {
            let a = self.run(false, 3, traced, covered);
            let b = self.run(true, 3, traced, covered);
            assert_eq!(a, b, "tiers differ on {what} (traced: {traced}, covered: {covered})");
            assert!(covered || a.coverage.is_empty(), "{what}: counted though not covered");
        }
    }
}

/// The counts a report reads of block 0 of a covered run (empty when the
/// run was not covered).
fn coverage_points(linked: &Linked) -> Vec<(usize, u64, u64)> {
    let Some(counters) = linked.coverage() else { return Vec::new() };
    let counts = counters.counts();
    let block = &counts.units[0].blocks[0];
    let ops = linked.ops(0, 0).expect("block 0");
    let code = &linked.object().units[0].blocks[0];
    let points = linc_runtime::cover::points(ops, &code.lines);
    (0..ops.len()).filter(|&pc| points[pc]).map(|pc| (pc, block.hits[pc], block.taken[pc])).collect()
}

/// Every string literal of a Rust source (normal and raw), roughly: enough
/// to find the ST programs the test files write.
fn string_literals(text: &str) -> Vec<String> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'/' if b.get(i + 1) == Some(&b'/') => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            }
            b'\'' => {
                i += match (b.get(i + 1), b.get(i + 2)) {
                    (Some(b'\\'), _) => text[i + 2..].find('\'').map_or(1, |n| n + 3),
                    (Some(_), Some(b'\'')) => 3,
                    _ => 1,
                };
                continue;
            }
            b'r' if matches!(b.get(i + 1), Some(b'"' | b'#')) && (i == 0 || !b[i - 1].is_ascii_alphanumeric()) => {
                let hashes = b[i + 1..].iter().take_while(|&&c| c == b'#').count();
                let open = i + 1 + hashes;
                if b.get(open) == Some(&b'"') {
                    let close = format!("\"{}", "#".repeat(hashes));
                    if let Some(n) = text[open + 1..].find(&close) {
                        out.push(text[open + 1..open + 1 + n].to_string());
                        i = open + 1 + n + close.len();
                        continue;
                    }
                }
            }
            b'"' => {
                let (s, next) = normal_literal(text, i + 1);
                out.push(s);
                i = next;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    out
}

/// A `"..."` literal's value from just after its quote; returns the index
/// after the closing quote.
fn normal_literal(text: &str, start: usize) -> (String, usize) {
    let mut s = String::new();
    let mut chars = text[start..].char_indices();
    while let Some((k, c)) = chars.next() {
        match c {
            '"' => return (s, start + k + 1),
            '\\' => match chars.next().map(|(_, e)| e) {
                Some('n') => s.push('\n'),
                Some('t') => s.push('\t'),
                Some('r') => s.push('\r'),
                Some('0') => s.push('\0'),
                Some('\n') => {
                    // A line continuation: skip the next line's indentation.
                    let rest = chars.as_str();
                    let skip = rest.len() - rest.trim_start().len();
                    for _ in 0..rest[..skip].chars().count() {
                        chars.next();
                    }
                }
                Some(e) => s.push(e),
                None => break,
            },
            c => s.push(c),
        }
    }
    (s, text.len())
}

#[test]
fn literal_scanner_reads_escapes_and_raw_strings() {
    let src = "let a = \"x := 1;\\nY\"; let c = '\"'; let b = r#\"q \"z\"\"#; // \"no\"\n";
    assert_eq!(string_literals(src), ["x := 1;\nY", "q \"z\""]);
}

#[test]
fn conformance_programs_agree_on_both_tiers() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests");
    let mut sources: Vec<String> = Vec::new();
    let mut files: Vec<_> = std::fs::read_dir(dir).expect("tests dir").flatten().map(|e| e.path()).collect();
    files.sort();
    for path in files.iter().filter(|p| p.extension().is_some_and(|e| e == "rs")) {
        let text = std::fs::read_to_string(path).expect("test file reads");
        sources.extend(string_literals(&text));
    }
    let guide = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/guide");
    for name in ["shift.st", "broken.st"] {
        sources.push(std::fs::read_to_string(format!("{guide}/{name}")).expect("example reads"));
    }
    sources.sort();
    sources.dedup();
    let (mut ran, mut compiled) = (0, 0);
    for src in &sources {
        for watchdog in [10_000_000, 57] {
            let Some(case) = Case::new(src, watchdog, None) else { break };
            ran += 1;
            compiled += usize::from(case.compiles());
            case.assert_tiers_agree(src);
        }
    }
    eprintln!("{ran} conformance runs (programs × 2 watchdogs), {compiled} on compiled code");
    assert!(ran >= 100, "only {ran} conformance programs compiled");
    assert!(compiled >= 40, "only {compiled} conformance programs use the compiling tier");
}

/// A random program and a watchdog budget for case `seed`.
fn generated(seed: u64) -> (String, u64, Option<u32>) {
    let mut g = Gen::new(seed);
    let n = 1 + g.rng.below(5);
    let src = g.stmts(n);
    let watchdog = match g.rng.below(3) {
        0 => 1 + g.rng.below(300) as u64,
        _ => 20_000,
    };
    let store = Store::new(guide_db().clone());
    let force = g.rng.one_in(20).then(|| {
        let (block, field) = if g.rng.one_in(2) { ("Recipe", "N1") } else { ("RAW_COM", "Buffer1") };
        let b = guide_db().block(block).unwrap_or(0);
        store.cell_of(b, field).unwrap_or(0)
    });
    (src, watchdog, force)
}

#[test]
fn generated_programs_agree_on_both_tiers() {
    let cases: u64 = std::env::var("TIER_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(2_400);
    let (mut ran, mut compiled, mut failed) = (0u64, 0u64, 0u64);
    for seed in 0..cases {
        let (src, watchdog, force) = generated(seed);
        let Some(case) = Case::new(&src, watchdog, force) else { continue };
        ran += 1;
        compiled += u64::from(case.compiles());
        // One case in four is traced: every write and the store at it; one
        // in three counts coverage.
        let (traced, covered) = (seed % 4 == 0, seed % 3 == 0);
        let a = case.run(false, 2, traced, covered);
        let b = case.run(true, 2, traced, covered);
        failed += u64::from(a.error.is_some());
        assert_eq!(a, b, "tiers differ on case {seed}:\n{src}");
    }
    eprintln!("{ran} generated programs ran, {compiled} on compiled code, {failed} stopped by an error");
    assert!(ran * 10 >= cases * 7, "only {ran} of {cases} generated programs compiled");
    assert!(compiled * 10 >= ran * 9, "only {compiled} of {ran} use the compiling tier");
    assert!(failed * 10 >= ran, "too few faults to exercise the bail-outs: {failed}");
}

/// Offsets whose range and kinds the compiling tier knows at translation
/// (a `RefOff` and its load or store in one basic block: the range check
/// is done once and the kind check left out) and loops whose watchdog is
/// checked only at their headers, against the longest way round: under
/// every watchdog from 1 to 400 instructions both tiers stop at the same
/// instruction with the same store, and an offset past the run faults at
/// the same place, as does a non-finite value computed from REAL cells
/// (values only moved from cell to cell are known to be finite).
#[test]
fn known_offsets_and_loop_headers_agree_under_every_watchdog() {
    let shift = "FOR Counters.N1 := 1 TO 4 DO
    FOR Counters.N0 := 7 TO 1 BY -1 DO
        Block_5.Val1{Counters.N0} := Block_5.Val1{Counters.N0 - 1};
        Recipe.N0{Counters.N0} := Recipe.N0{Counters.N0 - 1} + Counters.N1;
    END_FOR;
    IF Counters.N1 MOD 2 = 0 THEN
        Block_5.Val1 := Block_5.Val8 * 0.5 + 1.0;
    ELSE
        Recipe.A0{Counters.N1} := Recipe.A0{Counters.N1 + 1} - 2.0;
    END_IF;
END_FOR;
";
    let past = "FOR Counters.N0 := 0 TO 9 DO
    Recipe.N0{Counters.N0} := Counters.N0;
END_FOR;
";
    // A value computed from REAL cells is checked when stored (it overflows
    // at the third turn); one only read from a cell and stored again is
    // finite and is not.
    let overflow = "FOR Counters.N0 := 1 TO 7 DO
    Recipe.A1 := Recipe.A0;
    Recipe.A0{Counters.N0} := Recipe.A0{Counters.N0 - 1} * 1.0E30 + 1.0E30;
END_FOR;
";
    let cases =
        [("the shift register", shift, false), ("an offset past the run", past, true), ("an overflow", overflow, true)];
    for (what, src, faults) in cases {
        for watchdog in 1..=400 {
            let case = Case::new(src, watchdog, None).expect("compiles");
            assert!(case.compiles(), "{what} is compiled");
            let a = case.run(false, 2, false, false);
            let b = case.run(true, 2, false, false);
            assert_eq!(a, b, "tiers differ on {what} under a watchdog of {watchdog}");
        }
        let case = Case::new(src, 100_000, None).expect("compiles");
        case.assert_tiers_agree(what);
        let ending = case.run(true, 1, false, false);
        assert_eq!(ending.error.is_some(), faults, "{what}: {:?}", ending.error);
    }
}

/// A constant first in a REAL sum or product, which the compiling tier
/// puts second (x64 then reads it from memory): the values, and the fault
/// where a product overflows to infinity and then meets a zero (a NaN),
/// are the interpreter's under every watchdog.
#[test]
fn constants_first_in_real_sums_and_products_agree_on_both_tiers() {
    let src = "FOR Counters.N0 := 1 TO 12 DO
    Recipe.A1 := 1.5 * Recipe.A0 + 2.0 * Recipe.A1 - 0.25;
    Recipe.A2 := 0.5 + 3.0 * (1.0E30 * Recipe.A0);
    Recipe.A0 := 0.0 * (1.0E30 * (1.0E30 * Recipe.A2)) + 1.0E3 * Recipe.A0 + 1.0;
END_FOR;
";
    for watchdog in (1..=120).chain([100_000]) {
        let case = Case::new(src, watchdog, None).expect("compiles");
        assert!(case.compiles());
        assert_eq!(case.run(false, 2, false, false), case.run(true, 2, false, false), "watchdog {watchdog}");
    }
    let ending = Case::new(src, 100_000, None).expect("compiles").run(true, 1, false, false);
    let error = format!("{:?}", ending.error);
    assert!(ending.error.is_some(), "the product overflows: {error}");
}

/// LEN, LEFT, RIGHT, MID and CONCAT run in place on both tiers (the
/// compiling tier calls them directly with their INT arguments): every
/// edge of their arguments gives the same strings, and a loop that builds
/// a string past the run's string budget faults at the same instruction.
#[test]
fn string_functions_in_place_agree_on_both_tiers() {
    let edges = "FOR Counters.N0 := -2 TO 20 DO
    RAW_COM.Buffer1 := CONCAT(LEFT(Raw1.Rx_Value, Counters.N0), RIGHT(Raw1.Rx_Value, Counters.N0 - 3));
    Raw1.Tx_Value := MID(RAW_COM.Buffer1, Counters.N0 MOD 5, Counters.N0 - 1);
    Counters.N1 := Counters.N1 + LEN(RAW_COM.Buffer1) + LEN(Raw1.Tx_Value);
END_FOR;
";
    let budget = "FOR Counters.N0 := 1 TO 100000 DO
    RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer1, CONCAT(LEFT('abcdefgh', 6), 'xy'));
END_FOR;
";
    for (what, src, faults) in [("the edges", edges, false), ("a string past the budget", budget, true)] {
        let case = Case::new(src, 10_000_000, None).expect("compiles");
        assert!(case.compiles(), "{what} is compiled");
        case.assert_tiers_agree(what);
        let ending = case.run(true, 1, false, false);
        assert_eq!(ending.error.is_some(), faults, "{what}: {:?}", ending.error);
    }
}

/// Runs of string instructions, which the compiling tier hands over as
/// fused steps in one call (a field read only to be cut or measured copies
/// only what is kept, a value stored and read straight back stays on the
/// stack, the constants of LEFT, RIGHT and MID are folded in): under every
/// string budget from none to more than the run makes, with no field forced
/// or with a string field forced, both tiers stop at the same statement
/// with the same fault and the same store. The statements store to an
/// enumerated field (the name read back is the field's own spelling, and a
/// name it does not have faults), cut a value that is no field, append,
/// compare and measure.
#[test]
fn string_runs_agree_under_every_string_budget() {
    let src = "RAW_COM.Buffer1 := CONCAT(LEFT(Raw1.Rx_Value, 4), 'ab');
Raw1.Rx_Value := CONCAT(RAW_COM.Buffer1, RIGHT(RAW_COM.Buffer1, 2));
Counters.N2 := Counters.N2 + LEN(Raw1.Rx_Value);
Raw1.Tx_Value := MID(CONCAT(Raw1.Rx_Value, 'xyz'), 3, 2);
TIC_100.Mode := 'manual';
RAW_COM.Buffer1 := TIC_100.Mode;
IF RAW_COM.Buffer1 = 'MANUAL' THEN
    Counters.N1 := LEN(LEFT(RAW_COM.Buffer1, 3)) + LEN(RAW_COM.Buffer1);
END_IF;
RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer1, Raw1.Tx_Value);
Raw1.Tx_Value := RAW_COM.Buffer1;
Counters.N0 := LEN(Raw1.Tx_Value);
TIC_100.Mode := CONCAT(LEFT(Raw1.Tx_Value, 2), 'X');
";
    let store = Store::new(guide_db().clone());
    let raw = guide_db().block("Raw1").expect("Raw1");
    let forced = [None, store.cell_of(raw, "Rx_Value"), store.cell_of(raw, "Tx_Value")];
    let mut endings = std::collections::BTreeSet::new();
    for force in forced {
        for budget in (0..=160).chain([100_000]) {
            let mut case = Case::new(src, 100_000, force).expect("compiles");
            case.strings = Some(budget);
            assert!(case.compiles(), "the string runs are compiled");
            let a = case.run(false, 2, false, false);
            let b = case.run(true, 2, false, false);
            assert_eq!(a, b, "tiers differ under a string budget of {budget} (forced: {force:?})");
            endings.insert(a.error.map(|e| (e.line, e.message)));
        }
        let case = Case::new(src, 100_000, force).expect("compiles");
        case.assert_tiers_agree("the string runs");
    }
    // The budget runs out at every statement that makes a string, and
    // with enough of it the last statement stores a name the enumerated
    // field does not have.
    let lines: std::collections::BTreeSet<u32> = endings.iter().flatten().map(|e| e.0).collect();
    assert!(lines.is_superset(&[1, 2, 3, 4, 5, 6, 8, 10, 11, 12, 13].into()), "{endings:?}");
    assert!(endings.iter().flatten().any(|(_, m)| m.contains("is not a value of")), "{endings:?}");
}

#[test]
fn what_compiles_and_what_is_left_to_the_interpreter() {
    let numeric = Case::new("Recipe.A1 := Recipe.A0 * 2.0;\n", 1000, None).expect("compiles");
    assert!(numeric.compiles());
    let strings = Case::new("RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer1, 'x');\n", 1000, None).expect("compiles");
    assert!(strings.compiles(), "strings are runtime services");
    let call = Case::new("Recipe.A1 := SQRT(Recipe.A0);\n", 1000, None).expect("compiles");
    assert!(call.compiles(), "a library call is a runtime service");
    let bits = Case::new("RAW_COM.Flags.Bit3 := TRUE;\n", 1000, None).expect("compiles");
    assert!(!bits.compiles(), "a bit field is left to the interpreter");
}

#[test]
fn a_traced_run_is_compiled_and_reports_every_write() {
    // Traced code keeps cells in memory and reports each write after
    // copying the cells out, so a tracer sees the store as the interpreter
    // leaves it at that write, intermediate values included.
    let src = "Recipe.N1 := 1;\nRecipe.N1 := 2;\nRecipe.A0{Recipe.N1} := 1.5;\nRAW_COM.Buffer1 := 'x';\n";
    let case = Case::new(src, 1000, None).expect("compiles");
    let a = case.run_traced(false, 1, true);
    let b = case.run_traced(true, 1, true);
    assert_eq!(a, b);
    let values: Vec<&str> = a.trace.iter().map(|(_, v, _)| v.as_str()).collect();
    assert_eq!(values, ["1", "2", "1.5", "'x'"]);
    assert_eq!(a.trace[0].0, a.trace[1].0, "the same cell twice");
    let store = Store::new(guide_db().clone());
    let mut vm = Vm::new(1000, Clock::new(1, 0));
    (vm.jit, vm.jit_after) = (true, 0);
    let mut act = Activation::new(&case.linked, 0, 0);
    let mut store = store;
    let mut note = |_: &Store, _: u32| {};
    vm.run(&case.linked, &mut act, &mut store, Some(&mut note)).expect("runs");
    assert!(case.linked.is_compiled_traced(0, 0), "the traced run used compiled code");
}

#[test]
fn a_block_is_compiled_once_it_has_run_about_as_long_as_compiling_takes() {
    // A block with a loop is due at its first run, which queues it and
    // runs on the interpreter; once translated, the next run is compiled.
    let looping = Case::new("FOR Counters.N0 := 1 TO 10 DO\n  Recipe.A1 := Recipe.A1 + 1.0;\nEND_FOR;\n", 1000, None)
        .expect("compiles");
    let mut store = Store::new(guide_db().clone());
    let mut vm = Vm::new(1_000_000, Clock::new(1, 0));
    let mut act = Activation::new(&looping.linked, 0, 0);
    vm.run(&looping.linked, &mut act, &mut store, None).expect("runs");
    assert_eq!(looping.linked.runs_behind_translation(0, 0), 1, "the first run did not wait");
    looping.linked.settle_translations();
    assert!(looping.linked.is_compiled(0, 0), "a loop is due at once");
    // A straight block of ten statements (about 40 instructions a run) waits
    // for the default threshold (1,000,000 instructions): some 25,000 runs.
    let straight: String = (0..10).map(|_| "Recipe.A1 := Recipe.A1 + 1.0;\n").collect();
    let case = Case::new(&straight, 1000, None).expect("compiles");
    assert!(case.compiles());
    let mut store = Store::new(guide_db().clone());
    assert!(vm.jit, "the tier is on by default");
    let mut act = Activation::new(&case.linked, 0, 0);
    let mut runs = 0;
    while !case.linked.is_compiled(0, 0) {
        vm.run(&case.linked, &mut act, &mut store, None).expect("runs");
        // Counted in runs, not time: each run finds the code ready if it
        // was queued by the one before.
        case.linked.settle_translations();
        runs += 1;
        assert!(runs < 100_000, "never compiled");
    }
    assert!((15_000..40_000).contains(&runs), "compiled after {runs} runs");
    // Compiled or not, the runs add up the same.
    vm.run(&case.linked, &mut act, &mut store, None).expect("runs");
    let a1 = store.cell_of(store.db.block("Recipe").unwrap(), "A1").unwrap();
    assert_eq!(store.cells[a1 as usize], linc_runtime::store::Cell::Real(10.0 * (runs + 1) as f32));
}

#[test]
fn a_tracer_that_panics_in_compiled_code_is_an_internal_error_not_an_abort() {
    // Unwinding through machine code would abort the process; the service
    // catches the panic and the run ends with R0099 at the write.
    let case = Case::new("Recipe.N1 := 1;\n", 1000, None).expect("compiles");
    let mut store = Store::new(guide_db().clone());
    let mut vm = Vm::new(1000, Clock::new(1, 0));
    (vm.jit, vm.jit_after) = (true, 0);
    let mut act = Activation::new(&case.linked, 0, 0);
    let mut note = |_: &Store, _: u32| panic!("a broken tracer");
    let e = vm.run(&case.linked, &mut act, &mut store, Some(&mut note)).expect_err("stops");
    assert_eq!((e.code.as_str(), e.line), ("R0099", 1), "{e}");
    assert!(case.linked.is_compiled_traced(0, 0));
}

/// Counts by source line of a covered run: (line, runs of its first
/// statement), and each decision's (line, evaluations, jumps taken).
type LineCounts = (Vec<(u32, u64)>, Vec<(u32, u64, u64)>);

fn by_line(linked: &Linked) -> LineCounts {
    let counts = linked.coverage().expect("covered").counts();
    let (block, code) = (&counts.units[0].blocks[0], &linked.object().units[0].blocks[0]);
    let mut lines: Vec<(u32, u64)> = Vec::new();
    for l in &code.lines {
        if lines.last().is_none_or(|&(line, _)| line != l.line) {
            lines.push((l.line, block.hits[l.op as usize]));
        }
    }
    let line_of = |pc: usize| code.lines.iter().take_while(|l| l.op as usize <= pc).last().map_or(0, |l| l.line);
    let ops = linked.ops(0, 0).expect("block 0");
    let decisions = (0..ops.len())
        .filter(|&pc| linc_runtime::cover::is_decision(&ops[pc]))
        .map(|pc| (line_of(pc), block.hits[pc], block.taken[pc]))
        .collect();
    (lines, decisions)
}

#[test]
fn coverage_counts_statements_and_decisions_alike_on_both_tiers() {
    let src = "Recipe.N1 := 0;\nFOR Counters.N0 := 1 TO 3 DO\n  IF Counters.N0 > 1 THEN\n    Recipe.N1 := Recipe.N1 + 1;\n  END_IF;\nEND_FOR;\n";
    let case = Case::new(src, 1_000_000, None).expect("compiles");
    for jit in [false, true] {
        let mut linked = case.linked.clone();
        linked.enable_coverage();
        let mut store = Store::new(guide_db().clone());
        let mut vm = Vm::new(1_000_000, Clock::new(1, 0));
        (vm.jit, vm.jit_after) = (jit, 0);
        let mut act = Activation::new(&linked, 0, 0);
        for _ in 0..2 {
            vm.run(&linked, &mut act, &mut store, None).expect("runs");
        }
        assert_eq!(linked.is_compiled(0, 0), jit);
        let (lines, decisions) = by_line(&linked);
        // Two runs: the FOR statement twice, its body three times a run,
        // the increment on two of the three passes.
        assert_eq!(lines, [(1, 2), (2, 2), (3, 6), (4, 4)], "jit: {jit}");
        // The loop's test leaves the loop once a run; the IF skips its arm
        // once a run.
        let mut d = decisions.clone();
        d.sort();
        assert_eq!(d, [(2, 8, 2), (3, 6, 2)], "jit: {jit}");
    }
}
