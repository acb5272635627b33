//! Ladder diagrams as text (issue 9, guide chapter 11, docs/ladder.md):
//! snapshot cases for every rule, valid and invalid, and run tests of the
//! guide's eight rungs over every input combination. Each snapshot holds
//! the source, the ST it desugars into (ADR 0009) and the diagnostics.

use linc_compiler::diag::render::{self, Format, SourceFiles};
use linc_compiler::ladder::pretty::to_st;
use linc_compiler::st::lower::{self, Lines};
use linc_compiler::Context;
use linc_runtime::store::{Cell, Store};
use linc_runtime::vm::{Activation, Clock, Vm, DEFAULT_WATCHDOG};
use linc_runtime::{Database, Program};
use std::sync::OnceLock;

/// The database of the ladder example (`examples/ladder/plant.json`).
fn db() -> &'static Database {
    static DB: OnceLock<Database> = OnceLock::new();
    DB.get_or_init(|| Database::from_json(include_str!("../../examples/ladder/plant.json")).expect("plant.json"))
}

const INTERLOCK: &str = include_str!("../../examples/ladder/interlock.ld");

/// Checks `src` as `case.ld`; returns the codes and the snapshot text.
fn case(section: &str, src: &str) -> (Vec<&'static str>, String) {
    let ctx = Context::of(Some(db()));
    let r = linc_compiler::check_ladder(src, "case", ctx);
    let mut files = SourceFiles::new();
    let id = files.add("case.ld".to_string(), src.to_string());
    let mut s = format!("{section}\n--- source\n{src}\n--- st\n");
    s.push_str(&r.tree.as_ref().map_or("(none)\n".to_string(), to_st::file));
    s.push_str("--- diagnostics\n");
    if r.diagnostics.is_empty() {
        s.push_str("(none)\n");
    }
    for d in &r.diagnostics {
        s.push_str(&render::render(&files, &d.clone().in_file(id), Format::Human));
    }
    (r.diagnostics.iter().map(|d| d.code.as_str()).collect(), s)
}

macro_rules! valid {
    ($name:ident, $section:literal, $src:expr) => {
        #[test]
        fn $name() {
            let (codes, snapshot) = case($section, $src);
            insta::assert_snapshot!(stringify!($name), snapshot);
            assert!(codes.is_empty(), "expected no diagnostics, got {codes:?}");
            runs_as_its_st($src);
        }
    };
}

macro_rules! invalid {
    ($name:ident, $section:literal, $src:expr, [$($code:literal),+ $(,)?]) => {
        #[test]
        fn $name() {
            let (codes, snapshot) = case($section, $src);
            insta::assert_snapshot!(stringify!($name), snapshot);
            assert_eq!(codes, [$($code),+], "diagnostic codes");
        }
    };
}

valid!(ld_guide_eight_rungs, "§11.2 the guide's eight example rungs", INTERLOCK);
valid!(ld_coil_normal, "§11.1.1 normally open coil", "[Dig_1a.In] -> (Dig_1b.Out);\n");
valid!(ld_coil_negated, "§11.1.1 normally closed coil", "[Dig_1a.In] -> (/Dig_1b.Out);\n");
valid!(ld_coil_set, "§11.1.1 set coil", "[Dig_1a.In] -> (S Dig_1b.Out);\n");
valid!(ld_coil_reset, "§11.1.1 reset coil", "[Dig_1a.In] -> (R Dig_1b.Out);\n");
valid!(ld_coil_without_condition, "§11.1.1 a coil on the left rail", "-> (S Dig_1b.Out);\n");
valid!(
    ld_nested_parallel,
    "§11.1 nested parallel branches",
    "([Dig_2a.In] ([Dig_2b.In] | [/Dig_3a.In]) | AND([Dig_3b.In], XOR([Dig_4a.In], [Dig_4b.In]))) -> (Dig_2c.Out);\n"
);
valid!(ld_comparison_contact, "§11.1 comparison contacts", "[Ana_7a.PV > 80.0] [/Ana_8a.Count = 3] -> (Dig_1b.Out);\n");
valid!(ld_bit_contact, "§11.1 a bit of an integer field", "[Bits_1.Word.Bit3] -> (Bits_1.Word.Bit4);\n");
valid!(
    ld_variable_outputs,
    "§11.2.7-9 variable outputs",
    "[Dig_6a.In] -> RECIPE1.A0 := 10;\n-> Ana_7b.PV := Ana_7a.PV * 2.0;\n-> Ana_8c.PV := MAX(Ana_8a.PV, 8.5);\n"
);
valid!(
    ld_forward_jumps,
    "§11.1.3 forward jumps, nested",
    "[Dig_1a.In] -> JUMP Outer;\n[Dig_2a.In] -> JUMP Inner;\n[Dig_3a.In] -> (Dig_3c.Out);\nInner: [Dig_4a.In] -> (Dig_4c.Out);\nOuter: [Dig_5a.In] -> (Dig_2c.Out);\n"
);
valid!(
    ld_crossing_jumps,
    "§11.1.3 forward jumps that cross",
    "[Dig_1a.In] -> JUMP A;\n[Dig_2a.In] -> JUMP B;\n[Dig_3a.In] -> (Dig_3c.Out);\nA: [Dig_4a.In] -> (Dig_4c.Out);\nB: [Dig_5a.In] -> (Dig_2c.Out);\n"
);
valid!(ld_label_16, "§20.8.1 a label of 16 characters", "[Dig_1a.In] -> JUMP SixteenCharLabel;\n[Dig_2a.In] -> (Dig_2c.Out);\nSixteenCharLabel: [Dig_3a.In] -> (Dig_3c.Out);\n");
valid!(
    ld_actions,
    "§10.2.1 ladder actions with headers",
    "ACTION Pump\n    [Dig_1a.In] -> (Dig_1b.Out);\nEND_ACTION\nACTION Valve\n    [/Dig_2a.In] -> (Dig_2c.Out);\nEND_ACTION\n"
);
invalid!(
    ld_label_17,
    "§20.8.1 a label of 17 characters",
    "Seventeen_CharLbl: [Dig_1a.In] -> (Dig_1b.Out);\n",
    ["E0302"]
);
invalid!(
    ld_duplicate_label,
    "§11.1.3 a label used twice",
    "[Dig_1a.In] -> JUMP L1;\nL1: [Dig_2a.In] -> (Dig_2c.Out);\nl1: [Dig_3a.In] -> (Dig_3c.Out);\n",
    ["E0303"]
);
invalid!(
    ld_end_label_defined,
    "§20.8.1 _End stands after the last rung",
    "_End: [Dig_1a.In] -> (Dig_1b.Out);\n",
    ["E0303"]
);
invalid!(
    ld_unresolved_jump,
    "§11.1.3 unresolved jump",
    "[Dig_1a.In] -> JUMP Nowhere;\n[Dig_2a.In] -> (Dig_2c.Out);\n",
    ["E0304"]
);
invalid!(
    ld_backward_jump,
    "§11.1.3 jumps go forwards only",
    "Top: [Dig_1a.In] -> (Dig_1b.Out);\n[Dig_2a.In] -> JUMP Top;\n",
    ["E0305"]
);
invalid!(ld_jump_to_own_rung, "§11.1.3 a jump to its own label", "Here: [Dig_1a.In] -> JUMP Here;\n", ["E0305"]);
invalid!(ld_integer_contact, "§11.1 an integer field is not a contact", "[Ana_8a.Count] -> (Dig_1b.Out);\n", ["E0306"]);
invalid!(ld_real_coil, "§11.1.1 a coil writes a digital variable", "[Dig_1a.In] -> (Ana_7b.PV);\n", ["E0307"]);
invalid!(
    ld_coil_expression,
    "§11.1.1 a coil writes a variable",
    "[Dig_1a.In] -> (Dig_1b.Out AND Dig_2c.Out);\n",
    ["E0308"]
);
invalid!(ld_unknown_contact, "ST names in contacts", "[Nothing.In] -> (Dig_1b.Out);\n", ["E0100"]);
invalid!(
    ld_rung_outside_action,
    "§10.2.1 rungs outside an action",
    "[Dig_1a.In] -> (Dig_1b.Out);\nACTION Pump\n    [Dig_2a.In] -> (Dig_2c.Out);\nEND_ACTION\n",
    ["E0309"]
);
invalid!(ld_not_box_arity, "§11.1 function boxes", "NOT([Dig_1a.In], [Dig_2a.In]) -> (Dig_1b.Out);\n", ["E0310"]);
invalid!(ld_empty_contact, "§11.1 contacts", "[] -> (Dig_1b.Out);\n", ["E0311"]);
invalid!(
    ld_unclosed_contact,
    "§11.1 contacts",
    "[Dig_1a.In -> (Dig_1b.Out);\n[Dig_2a.In] -> (Dig_2c.Out);\n",
    ["E0301"]
);
invalid!(
    ld_st_statement,
    "ladder actions hold rungs",
    "Dig_1b.Out := TRUE;\n[Dig_2a.In] -> (Dig_2c.Out);\n",
    ["E0300"]
);
invalid!(ld_missing_arrow, "a rung needs ->", "[Dig_1a.In] (Dig_1b.Out);\n[Dig_2a.In] -> (Dig_2c.Out);\n", ["E0300"]);
invalid!(ld_missing_semicolon, "every rung ends with ;", "[Dig_1a.In] -> (Dig_1b.Out)\n", ["E0300"]);
invalid!(
    ld_variable_output_type,
    "§11.2.7 variable outputs are ST assignments",
    "[Dig_1a.In] -> Ana_7b.PV := 'text';\n",
    ["E0103"]
);

/// A compiled ladder action, ready to run against fresh copies of `db`.
fn compile(src: &str) -> Vec<u8> {
    let ctx = Context::of(Some(db()));
    let r = linc_compiler::check_ladder(src, "case", ctx);
    let program = r.program.unwrap_or_else(|| panic!("does not compile: {:?}", r.diagnostics));
    lower::lower_program(&program, "case.ld", &Lines::new(src)).expect("lowers").to_bytes()
}

/// The ladder and the ST `linc ladder to-st` prints for it run to the same
/// database, for 32 settings of the digital inputs (each action in turn).
fn runs_as_its_st(src: &str) {
    let ctx = Context::of(Some(db()));
    let r = linc_compiler::check_ladder(src, "case", ctx);
    let st = to_st::file(r.tree.as_ref().expect("tree"));
    let st_r = linc_compiler::check_source(&st, "case", ctx);
    let st_program = st_r.program.unwrap_or_else(|| panic!("{st}: {:?}", st_r.diagnostics));
    let st_bytes = lower::lower_program(&st_program, "case.st", &Lines::new(&st)).expect("lowers").to_bytes();
    let ld_bytes = compile(src);
    let inputs =
        ["Dig_1a.In", "Dig_2a.In", "Dig_2b.In", "Dig_3a.In", "Dig_3b.In", "Dig_4a.In", "Dig_5a.In", "Dig_6a.In"];
    for unit in 0..st_program.actions.len() {
        for m in 0..32u32 {
            let bits = m.wrapping_mul(0x9E37_79B9) >> 8;
            let set: Vec<(&str, bool)> = inputs.iter().enumerate().map(|(i, p)| (*p, bits >> i & 1 == 1)).collect();
            let (a, b) = (run_unit(&ld_bytes, &set, unit), run_unit(&st_bytes, &set, unit));
            assert_eq!(a.cells, b.cells, "unit {unit}, inputs {set:?}\nST:\n{st}");
        }
    }
}

/// Runs `bytes` once after setting the BOOL fields `set`; gives the store.
fn run(bytes: &[u8], set: &[(&str, bool)]) -> Store {
    run_unit(bytes, set, 0)
}

/// [`run`] for action `unit` of the object.
fn run_unit(bytes: &[u8], set: &[(&str, bool)], unit: usize) -> Store {
    let verified = linc_runtime::load(bytes).expect("verifies");
    let mut store = Store::new(db().clone());
    for (path, v) in set {
        *cell(&mut store, path) = Cell::Bool(*v);
    }
    let linked = verified.link(&store, &[Program { unit, own: None }]).expect("links");
    let mut vm = Vm::new(DEFAULT_WATCHDOG, Clock::new(1, 0));
    let mut act = Activation::new(&linked, 0, 0);
    vm.run(&linked, &mut act, &mut store, None).expect("runs");
    store
}

fn cell<'s>(store: &'s mut Store, path: &str) -> &'s mut Cell {
    let (b, f) = path.split_once('.').expect("Block.Field");
    let block = store.db.block(b).unwrap_or_else(|| panic!("no block {b}"));
    let i = store.cell_of(block, f).unwrap_or_else(|| panic!("no field {path}"));
    &mut store.cells[i as usize]
}

fn get(store: &mut Store, path: &str) -> Cell {
    cell(store, path).clone()
}

/// Every combination of `n` inputs.
fn combinations(n: usize) -> impl Iterator<Item = Vec<bool>> {
    (0..1u32 << n).map(move |m| (0..n).map(|i| m >> i & 1 == 1).collect())
}

/// Rungs 1-4 of the guide: each coil's truth table, with the coil's old
/// value both FALSE and TRUE (set and reset coils keep it).
#[test]
fn the_guide_coils_follow_their_truth_tables() {
    let bytes = compile(INTERLOCK);
    for v in combinations(3) {
        let (a, b, old) = (v[0], v[1], v[2]);
        let set = |n: u8| {
            vec![
                (format!("Dig_{n}a.In"), a),
                (format!("Dig_{n}b.In"), b),
                (format!("Dig_{n}c.Out"), old),
                ("Dig_5a.In".to_string(), true),
            ]
        };
        let mut all: Vec<(String, bool)> = vec![("Dig_1a.In".into(), a), ("Dig_1b.Out".into(), old)];
        for n in 2..=4 {
            all.extend(set(n));
        }
        let refs: Vec<(&str, bool)> = all.iter().map(|(p, v)| (p.as_str(), *v)).collect();
        let mut s = run(&bytes, &refs);
        assert_eq!(get(&mut s, "Dig_1b.Out"), Cell::Bool(a), "rung 1, a={a}");
        assert_eq!(get(&mut s, "Dig_2c.Out"), Cell::Bool(!a || b), "rung 2: NOT (a AND NOT b), a={a} b={b}");
        assert_eq!(get(&mut s, "Dig_3c.Out"), Cell::Bool(if a && !b { true } else { old }), "rung 3 {v:?}");
        assert_eq!(get(&mut s, "Dig_4c.Out"), Cell::Bool(if a || !b { false } else { old }), "rung 4 {v:?}");
    }
}

/// Rungs 5-8: the jump to `_End` skips the variable outputs exactly when
/// `Dig_5a.In OR NOT Dig_5b.In`; rung 6 writes only when `Dig_6a.In`.
#[test]
fn the_guide_jump_and_variable_outputs_follow_their_truth_tables() {
    let bytes = compile(INTERLOCK);
    for v in combinations(3) {
        let (a5, b5, a6) = (v[0], v[1], v[2]);
        let mut s = run(&bytes, &[("Dig_5a.In", a5), ("Dig_5b.In", b5), ("Dig_6a.In", a6)]);
        let jumped = a5 || !b5;
        let a0 = if !jumped && a6 { 10.0 } else { 0.0 };
        assert_eq!(get(&mut s, "RECIPE1.A0"), Cell::Real(a0), "rung 6 {v:?}");
        assert_eq!(get(&mut s, "Ana_7b.PV"), Cell::Real(if jumped { 0.0 } else { 42.5 }), "rung 7 {v:?}");
        assert_eq!(get(&mut s, "Ana_8c.PV"), Cell::Real(if jumped { 0.0 } else { 8.5 }), "rung 8 {v:?}");
    }
}

/// A later rung sees what an earlier one wrote, in the same execution.
#[test]
fn rungs_run_top_to_bottom() {
    let bytes = compile("[Dig_1a.In] -> (Dig_1b.Out);\n[Dig_1b.Out] -> (Dig_2c.Out);\n");
    for a in [false, true] {
        let mut s = run(&bytes, &[("Dig_1a.In", a)]);
        assert_eq!(get(&mut s, "Dig_2c.Out"), Cell::Bool(a));
    }
}

/// Crossing jumps: each rung runs exactly when no taken jump skips it.
#[test]
fn crossing_jumps_skip_exactly_their_rungs() {
    let src = "[Dig_1a.In] -> JUMP A;\n[Dig_2a.In] -> JUMP B;\n-> (S Dig_3c.Out);\nA: -> (S Dig_4c.Out);\nB: -> (S Dig_2c.Out);\n";
    let bytes = compile(src);
    for v in combinations(2) {
        let (j1, j2) = (v[0], v[1]);
        let mut s = run(&bytes, &[("Dig_1a.In", j1), ("Dig_2a.In", j2)]);
        assert_eq!(get(&mut s, "Dig_3c.Out"), Cell::Bool(!j1 && !j2), "{v:?}");
        assert_eq!(get(&mut s, "Dig_4c.Out"), Cell::Bool(j1 || !j2), "{v:?}");
        assert_eq!(get(&mut s, "Dig_2c.Out"), Cell::Bool(true), "{v:?}");
    }
}
