//! The constant folder against the VM. The compiler computes constant
//! numeric expressions itself (`lower::expr::constant`) and must get exactly
//! what the VM would: the same INT wrap-around, the same REAL rounding, the
//! same 16-bit logic, the same comparisons, and no folding where the VM
//! faults (division by zero, `**` outside its domain, a REAL overflow), so
//! the fault stays a located runtime error.
//!
//! Each generated program is compiled twice: as written, where the folder
//! computes every constant expression, and with every literal hidden behind
//! `MAX(x, x)` (the identity, which the folder does not look through), so
//! the VM computes everything. The two runs must leave the same values and
//! stop with the same fault at the same line.

use linc_compiler::st::lower::{self, Lines};
use linc_compiler::Context;
use linc_conformance::guide_db;
use linc_conformance::rng::Rng;
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Vm, DEFAULT_WATCHDOG};
use linc_runtime::Program;

#[derive(Clone, Copy, PartialEq)]
enum Ty {
    Int,
    Real,
}

/// One expression written two ways: plain, and with literals hidden.
struct Gen {
    plain: String,
    hidden: String,
    ty: Ty,
}

const INTS: &[&str] = &["0", "1", "2", "3", "7", "100", "255", "32767", "65535", "1000000", "2147483647"];
const REALS: &[&str] = &["0.0", "0.5", "1.5", "2.0", "10.0", "1.0E30", "3.4E38", "1.0E-30", "0.1", "1.0E10"];

fn leaf(rng: &mut Rng) -> Gen {
    let (text, ty) =
        if rng.one_in(2) { (INTS[rng.below(INTS.len())], Ty::Int) } else { (REALS[rng.below(REALS.len())], Ty::Real) };
    Gen { plain: text.to_string(), hidden: format!("MAX({text}, {text})"), ty }
}

fn expr(rng: &mut Rng, depth: u32) -> Gen {
    if depth == 0 || rng.one_in(4) {
        return leaf(rng);
    }
    if rng.one_in(6) {
        let a = expr(rng, depth - 1);
        return Gen { plain: format!("-({})", a.plain), hidden: format!("-({})", a.hidden), ty: a.ty };
    }
    let (a, b) = (expr(rng, depth - 1), expr(rng, depth - 1));
    let ints = a.ty == Ty::Int && b.ty == Ty::Int;
    let ops: &[&str] =
        if ints { &["+", "-", "*", "/", "MOD", "**", "AND", "OR", "XOR"] } else { &["+", "-", "*", "/", "**"] };
    let op = ops[rng.below(ops.len())];
    let ty = if op == "**" || !ints { Ty::Real } else { Ty::Int };
    Gen { plain: format!("({} {op} {})", a.plain, b.plain), hidden: format!("({} {op} {})", a.hidden, b.hidden), ty }
}

/// A program of a few statements, each storing a generated expression or
/// the outcome of a comparison, written plain and hidden.
fn program(rng: &mut Rng) -> (String, String) {
    let (mut plain, mut hidden) = (String::new(), String::new());
    for i in 0..4 {
        let e = expr(rng, 4);
        if rng.one_in(3) {
            let f = expr(rng, 3);
            let cmp = ["=", "<>", "<", ">", "<=", ">="][rng.below(6)];
            let stmt = |x: &str, y: &str| {
                format!("IF {x} {cmp} {y} THEN Recipe.N{} := 1; ELSE Recipe.N{} := 2; END_IF;\n", i + 1, i + 1)
            };
            plain.push_str(&stmt(&e.plain, &f.plain));
            hidden.push_str(&stmt(&e.hidden, &f.hidden));
        } else {
            let target = if e.ty == Ty::Real { format!("Recipe.A{i}") } else { format!("Recipe.N{i}") };
            plain.push_str(&format!("{target} := {};\n", e.plain));
            hidden.push_str(&format!("{target} := {};\n", e.hidden));
        }
    }
    (plain, hidden)
}

/// What a run left: every field of Recipe, and the fault's code and line.
type Outcome = (Vec<String>, Option<(&'static str, u32)>);

/// The outcome of compiling and running `src`; `None` if it does not compile.
fn outcome(src: &str) -> Option<Outcome> {
    let db = guide_db();
    let ctx = Context::of(Some(db));
    let checked = linc_compiler::check_source(src, "fold", ctx);
    let program = checked.program?;
    let obj = lower::lower_program(&program, "fold.st", &Lines::new(src)).ok()?;
    let verified = linc_runtime::load(&obj.to_bytes()).expect("a compiled program loads");
    let mut store = Store::new(db.clone());
    let linked = verified.link(&store, &[Program { unit: 0, own: None }]).expect("links");
    let mut vm = Vm::new(DEFAULT_WATCHDOG, Clock::new(1, 0));
    let mut act = Activation::new(&linked, 0, 0);
    let fault = vm.run(&linked, &mut act, &mut store, None).err().map(|e| (e.code.as_str(), e.line));
    let recipe = db.block("Recipe").expect("Recipe");
    let fields = db.block_template(recipe).fields.len() as u32;
    let first = store.cell_of(recipe, "A0").expect("A0");
    Some(((first..first + fields).map(|c| store.show(c)).collect(), fault))
}

#[test]
fn folded_constants_are_what_the_vm_computes() {
    let cases: u64 = std::env::var("FOLD_CASES").ok().and_then(|n| n.parse().ok()).unwrap_or(3_000);
    let (mut compared, mut faulted) = (0, 0);
    for seed in 0..cases {
        let mut rng = Rng::new(seed);
        let (plain, hidden) = program(&mut rng);
        let (folded, computed) = (outcome(&plain), outcome(&hidden));
        assert_eq!(folded.is_some(), computed.is_some(), "case {seed}: one compiles, the other not:\n{plain}");
        let (Some(folded), Some(computed)) = (folded, computed) else { continue };
        assert_eq!(folded, computed, "case {seed}: the folder and the VM disagree on\n{plain}");
        compared += 1;
        faulted += usize::from(folded.1.is_some());
    }
    // The generator must exercise both outcomes, or the test says little.
    assert!(compared as u64 > cases / 2, "only {compared} of {cases} programs compiled");
    assert!(faulted > 0 && faulted < compared, "{faulted} of {compared} programs faulted");
}
