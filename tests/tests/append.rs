//! `X := CONCAT(X, e)` appends in place (`AppendS`): the same values,
//! forced-write refusals and string limits as the long form, which copies X
//! onto the string stack, concatenates and stores the result.
use linc_conformance::exec::{compile, run};
use linc_conformance::guide_db;
use linc_runtime::isa::Op;

/// The instructions of the first block of `src`.
fn ops(src: &str) -> Vec<Op> {
    let v = linc_runtime::load(&compile(src, guide_db())).expect("loads");
    v.object().units[0].blocks[0].ops.0.clone()
}

fn appends(src: &str) -> bool {
    ops(src).iter().any(|op| matches!(op, Op::AppendS { .. }))
}

#[test]
fn only_an_append_to_the_same_field_named_directly_is_in_place() {
    assert!(appends("RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer1, 'x');\n"));
    assert!(appends("RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer1, RAW_COM.Buffer1);\n"));
    assert!(appends("Raw1.Rx_Value := CONCAT(Raw1.Rx_Value, FORMAT('05I', Raw1.I1));\n"));
    assert!(!appends("RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer2, 'x');\n"));
    assert!(!appends("RAW_COM.Buffer1 := CONCAT('x', RAW_COM.Buffer1);\n"));
    assert!(!appends("RAW_COM.Buffer1 := CONCAT(Raw1.Buffer1, 'x');\n"), "another block");
    assert!(!appends("RAW_COM.FileName := CONCAT(RAW_COM.FileName, 'x');\n"), "a STRING is decoded on loading");
}

/// Runs `body` with Buffer1 filled first, in place and in the long form
/// (`CONCAT(LEFT(X, LEN(X)), e)` is the same value but no append).
fn both(fill: &str, tail: &str) -> (linc_conformance::exec::Run, linc_conformance::exec::Run) {
    let head = format!("RAW_COM.Buffer1 := {fill};\nRAW_COM.I1 := 7;\n");
    let short = format!("{head}RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer1, {tail});\n");
    let long = format!("{head}RAW_COM.Buffer1 := CONCAT(LEFT(RAW_COM.Buffer1, LEN(RAW_COM.Buffer1)), {tail});\n");
    assert!(appends(&short) && !appends(&long));
    (run(&short), run(&long))
}

#[test]
fn the_value_is_the_long_forms() {
    for (fill, tail) in [
        ("'ab'", "'c$41'"),
        ("''", "''"),
        ("'x'", "RAW_COM.Buffer1"),
        ("'n='", "FORMAT('05I', RAW_COM.I1)"),
        ("'$00$FF'", "RAW_COM.Mode"),
    ] {
        let (a, b) = both(fill, tail);
        assert_eq!(a.get("RAW_COM.Buffer1"), b.get("RAW_COM.Buffer1"), "{fill}, {tail}");
        assert_eq!(a.code(), None);
    }
    let (a, _) = both("'n='", "FORMAT('05I', RAW_COM.I1)");
    assert_eq!(a.get("RAW_COM.Buffer1"), "'n=00007'");
}

#[test]
fn past_the_string_limit_both_forms_stop_at_the_statement_and_keep_the_field() {
    let grow = "RAW_COM.Buffer1 := 'x';\nWHILE 1 DO\n  RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer1, RAW_COM.Buffer1);\nEND_WHILE;\n";
    let long = grow.replace("CONCAT(RAW_COM.Buffer1,", "CONCAT(LEFT(RAW_COM.Buffer1, LEN(RAW_COM.Buffer1)),");
    for src in [grow.to_string(), long] {
        let r = run(&src);
        let e = r.error.as_ref().expect("stops");
        assert_eq!((e.code.as_str(), e.line), ("R0007", 3), "{e}");
        assert!(e.message.contains("65536 bytes"), "{e}");
        assert_eq!(r.store.show(cell(&r, "Buffer1")).len(), 32_768 + 2, "the last good value stays (quoted)");
    }
}

fn cell(r: &linc_conformance::exec::Run, field: &str) -> u32 {
    r.store.cell_of(r.store.db.block("RAW_COM").expect("block"), field).expect("field")
}

#[test]
fn a_forced_field_keeps_its_value_and_the_refusal_is_counted_once() {
    use linc_runtime::store::Store;
    use linc_runtime::vm::{Activation, Clock, Vm};
    use linc_runtime::Program;
    let src = "RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer1, 'x');\n";
    let bytes = compile(src, guide_db());
    for jit in [false, true] {
        let v = linc_runtime::load(&bytes).expect("loads");
        let mut store = Store::new(guide_db().clone());
        let c = store.cell_of(store.db.block("RAW_COM").unwrap(), "Buffer1").unwrap();
        store.set_forced(c, true);
        let linked = v.link(&store, &[Program { unit: 0, own: None }]).expect("links");
        let mut vm = Vm::new(1000, Clock::new(1, 0));
        (vm.jit, vm.jit_after) = (jit, 0);
        let mut act = Activation::new(&linked, 0, 0);
        vm.run(&linked, &mut act, &mut store, None).expect("runs");
        assert_eq!((store.show(c).as_str(), store.ignored_writes), ("''", 1), "jit {jit}");
    }
}
