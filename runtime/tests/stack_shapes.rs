//! The verifier records the numeric stack's types where paths meet (issue
//! 16): the compiling tier types its stack from these instead of analysing
//! the code again. Types that differ where paths meet are no error (both
//! are 32-bit words) but mark the shape unknown, and such a block stays on
//! the interpreter.

use linc_runtime::isa::{Kind, Op};
use linc_runtime::object::{CodeBlock, ObjectFile, Unit};
use linc_runtime::verify::Shape;
use linc_runtime::wire::Code;
use linc_runtime::{Database, Program, Store};

/// One unit of one block; label 0 is instruction `label`.
fn verified(ops: Vec<Op>, label: u32) -> linc_runtime::Verified {
    let block = CodeBlock { ops: Code(ops), labels: vec![label], ..CodeBlock::default() };
    let unit = Unit { name: "A".into(), blocks: vec![block], ..Unit::default() };
    let obj = ObjectFile { source: "x.st".into(), symbols: Vec::new(), strings: Vec::new(), units: vec![unit] };
    linc_runtime::verify::verify(obj).expect("verifies")
}

#[test]
fn the_types_at_a_label_are_recorded() {
    // A REAL under the condition, an INT or REAL pushed on each path.
    let mut ops = vec![Op::PushR { v: 2.5 }, Op::PushI { v: 1 }, Op::JumpIfFalse { to: 0 }, Op::NegR {}];
    ops.extend([Op::Return { kind: Kind::Real as u8 }]);
    let v = verified(ops, 4);
    assert_eq!(v.shapes(0, 0), [(4, Shape { depth: 1, reals: 0b1, known: true })]);
    // Paths that bring an INT and a REAL: known no more, still verified.
    let mut ops = vec![Op::PushI { v: 3 }, Op::PushI { v: 1 }, Op::JumpIfFalse { to: 0 }, Op::IToR {}];
    ops.extend([Op::Return { kind: Kind::Real as u8 }]);
    let v = verified(ops, 4);
    assert_eq!(v.shapes(0, 0), [(4, Shape { depth: 1, reals: 0, known: false })]);
}

#[test]
fn a_block_whose_paths_meet_with_other_types_runs_interpreted() {
    let store = Store::new(Database::builtin());
    let compiled = |ops: Vec<Op>| {
        let v = verified(ops, 4);
        let linked = v.link(&store, &[Program { unit: 0, own: None }]).expect("links");
        linc_runtime::jit::compile(&linked, &store, 0, 0).is_some()
    };
    let mut same = vec![Op::PushR { v: 2.5 }, Op::PushI { v: 1 }, Op::JumpIfFalse { to: 0 }, Op::NegR {}];
    same.push(Op::Return { kind: Kind::Real as u8 });
    assert!(compiled(same), "REAL on both paths: compiled");
    let mut mixed = vec![Op::PushI { v: 3 }, Op::PushI { v: 1 }, Op::JumpIfFalse { to: 0 }, Op::IToR {}];
    mixed.push(Op::Return { kind: Kind::Real as u8 });
    assert!(!compiled(mixed), "INT and REAL meeting: left to the interpreter");
}
