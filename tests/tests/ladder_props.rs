//! Property tests of ladder (docs/ladder.md): random rungs (contacts,
//! series, branches, function boxes, the four coils, forward jumps that
//! nest and cross) compiled and run in the VM give what a direct Boolean
//! evaluation of the rungs, top to bottom, gives, and so does the ST that
//! `linc ladder to-st` prints for them; and no input text makes
//! the ladder front end panic or run away.

use linc_compiler::ladder::pretty::to_st;
use linc_compiler::st::lower::{self, Lines};
use linc_compiler::Context;
use linc_conformance::rng::Rng;
use linc_runtime::store::{Cell, Store};
use linc_runtime::vm::{Activation, Clock, Vm, DEFAULT_WATCHDOG};
use linc_runtime::{Database, Program};

fn db() -> Database {
    Database::from_json(include_str!("../../examples/ladder/plant.json")).expect("plant.json")
}

/// Variables 0..8 are inputs, 8..12 outputs (coils write outputs; contacts
/// read both, so a rung sees what an earlier one wrote).
const VARS: [&str; 12] = [
    "Dig_1a.In",
    "Dig_2a.In",
    "Dig_2b.In",
    "Dig_3a.In",
    "Dig_3b.In",
    "Dig_4a.In",
    "Dig_4b.In",
    "Dig_5a.In",
    "Dig_1b.Out",
    "Dig_2c.Out",
    "Dig_3c.Out",
    "Dig_4c.Out",
];

enum C {
    Contact(usize, bool),
    Series(Vec<C>),
    Parallel(Vec<C>),
    Box(&'static str, Vec<C>),
}

enum Out {
    Coil(&'static str, usize),
    Jump(usize),
}

struct Rung {
    cond: Option<C>,
    out: Out,
}

fn gen_cond(r: &mut Rng, depth: usize) -> C {
    let leaf = depth >= 3 || r.below(3) == 0;
    if leaf {
        return C::Contact(r.below(VARS.len()), r.below(2) == 0);
    }
    let n = 2 + r.below(2);
    let kind = r.below(5);
    let kids: Vec<C> = (0..if kind == 4 { 1 } else { n }).map(|_| gen_cond(r, depth + 1)).collect();
    match kind {
        0 => C::Series(kids),
        1 => C::Parallel(kids),
        2 => C::Box("AND", kids),
        3 => C::Box(["OR", "XOR"][(depth + n) % 2], kids),
        _ => C::Box("NOT", kids),
    }
}

fn text(c: &C) -> String {
    let list = |v: &[C], sep: &str| v.iter().map(text).collect::<Vec<_>>().join(sep);
    match c {
        C::Contact(v, neg) => format!("[{}{}]", if *neg { "/" } else { "" }, VARS[*v]),
        C::Series(v) => list(v, " "),
        C::Parallel(v) => format!("({})", list(v, " | ")),
        C::Box(op, v) => format!("{op}({})", list(v, ", ")),
    }
}

fn eval(c: &C, s: &[bool]) -> bool {
    match c {
        C::Contact(v, neg) => s[*v] != *neg,
        C::Series(v) | C::Box("AND", v) => v.iter().all(|c| eval(c, s)),
        C::Parallel(v) | C::Box("OR", v) => v.iter().any(|c| eval(c, s)),
        C::Box("XOR", v) => v.iter().fold(false, |a, c| a ^ eval(c, s)),
        C::Box(_, v) => !eval(&v[0], s),
    }
}

fn gen_program(r: &mut Rng) -> Vec<Rung> {
    let n = 1 + r.below(6);
    (0..n)
        .map(|i| {
            let cond = (r.below(6) != 0).then(|| gen_cond(r, 0));
            let out = if r.below(4) == 0 {
                Out::Jump(i + 1 + r.below(n - i))
            } else {
                Out::Coil(["", "/", "S ", "R "][r.below(4)], 8 + r.below(4))
            };
            Rung { cond, out }
        })
        .collect()
}

fn source(p: &[Rung]) -> String {
    let mut s = String::new();
    for (i, rung) in p.iter().enumerate() {
        let cond = rung.cond.as_ref().map(text).unwrap_or_default();
        let out = match &rung.out {
            Out::Coil(k, v) => format!("({k}{})", VARS[*v]),
            Out::Jump(t) if *t == p.len() => "JUMP _End".to_string(),
            Out::Jump(t) => format!("JUMP R{t}"),
        };
        s.push_str(&format!("R{i}: {cond} -> {out};\n"));
    }
    s
}

/// The rungs run directly: top to bottom, jumps forwards.
fn model(p: &[Rung], s: &mut [bool]) {
    let mut i = 0;
    while i < p.len() {
        let c = p[i].cond.as_ref().is_none_or(|c| eval(c, s));
        match p[i].out {
            Out::Jump(t) if c => {
                i = t;
                continue;
            }
            Out::Jump(_) => {}
            Out::Coil("", v) => s[v] = c,
            Out::Coil("/", v) => s[v] = !c,
            Out::Coil("S ", v) if c => s[v] = true,
            Out::Coil("R ", v) if c => s[v] = false,
            Out::Coil(..) => {}
        }
        i += 1;
    }
}

#[test]
fn random_rungs_run_as_their_boolean_evaluation() {
    let db = db();
    let ctx = Context::of(Some(&db));
    let mut r = Rng(0x1AD_DE12_5EED);
    for _ in 0..300 {
        let p = gen_program(&mut r);
        let src = source(&p);
        let rep = linc_compiler::check_ladder(&src, "case", ctx);
        let program = rep.program.unwrap_or_else(|| panic!("{src}: {:?}", rep.diagnostics));
        let bytes = lower::lower_program(&program, "case.ld", &Lines::new(&src)).expect("lowers").to_bytes();
        // The ST that `linc ladder to-st` prints runs the same.
        let st = to_st::file(rep.tree.as_ref().expect("tree"));
        let st_rep = linc_compiler::check_source(&st, "case", ctx);
        let st_program = st_rep.program.unwrap_or_else(|| panic!("{st}: {:?}", st_rep.diagnostics));
        let st_bytes = lower::lower_program(&st_program, "case.st", &Lines::new(&st)).expect("lowers").to_bytes();
        for k in 0..12 {
            let verified = linc_runtime::load(if k % 2 == 0 { &bytes } else { &st_bytes }).expect("verifies");
            let mut state: Vec<bool> = (0..VARS.len()).map(|_| r.below(2) == 1).collect();
            let mut store = Store::new(db.clone());
            let cells: Vec<usize> = VARS
                .iter()
                .map(|p| {
                    let (b, f) = p.split_once('.').expect("dot");
                    store.cell_of(store.db.block(b).expect("block"), f).expect("field") as usize
                })
                .collect();
            for (c, v) in cells.iter().zip(&state) {
                store.cells[*c] = Cell::Bool(*v);
            }
            let linked = verified.link(&store, &[Program { unit: 0, own: None }]).expect("links");
            let mut act = Activation::new(&linked, 0, 0);
            Vm::new(DEFAULT_WATCHDOG, Clock::new(1, 0)).run(&linked, &mut act, &mut store, None).expect("runs");
            let before = state.clone();
            model(&p, &mut state);
            let got: Vec<bool> = cells.iter().map(|c| store.cells[*c] == Cell::Bool(true)).collect();
            assert_eq!(got, state, "program (run {k}):\n{src}as ST:\n{st}inputs {before:?}");
        }
    }
}

/// Random text from ladder-ish pieces: the front end reports, never panics,
/// and every diagnostic points inside the text.
#[test]
fn no_text_makes_the_ladder_front_end_panic() {
    const PIECES: [&str; 34] = [
        "[",
        "]",
        "(",
        ")",
        "|",
        "/",
        "->",
        ";",
        ":",
        ":=",
        "AND",
        "NOT(",
        "OR (",
        "JUMP ",
        "_End",
        "Dig_1a.In",
        "(S ",
        "(R ",
        "(* ",
        "*)",
        "'",
        "é",
        " ",
        "\n",
        "ACTION A ",
        "END_ACTION",
        "L1:",
        "x",
        "1.5",
        ",",
        "[[",
        "]]",
        "$",
        "Ana_7a.PV > 1.0",
    ];
    let db = db();
    let ctx = Context::of(Some(&db));
    let mut r = Rng(7);
    for _ in 0..20_000 {
        let n = 1 + r.below(40);
        let src: String = (0..n).map(|_| PIECES[r.below(PIECES.len())]).collect();
        let rep = linc_compiler::check_ladder(&src, "case", ctx);
        for d in &rep.diagnostics {
            assert!(d.span.end <= src.len() && d.span.start <= d.span.end, "{src:?}: {d:?}");
        }
    }
}

/// Deep nesting and crossing jumps are refused with an error, quickly.
#[test]
fn deep_branches_and_crossing_jumps_are_bounded() {
    let db = db();
    let ctx = Context::of(Some(&db));
    let deep = format!("{}[Dig_1a.In]{} -> (Dig_1b.Out);\n", "(".repeat(100_000), ")".repeat(100_000));
    let rep = linc_compiler::check_ladder(&deep, "case", ctx);
    assert_eq!(rep.diagnostics.iter().map(|d| d.code.as_str()).collect::<Vec<_>>(), ["E0300"]);
    // A long series is a balanced tree: as many contacts as an action may
    // hold elements (the coil is one) check and compile; one more is E0313,
    // at the element over the limit, and the rest of the action is skipped.
    let max = linc_compiler::ladder::parser::MAX_ELEMENTS;
    let long = format!("{} -> (Dig_1b.Out);\n", "[Dig_1a.In] ".repeat(max - 1));
    let rep = linc_compiler::check_ladder(&long, "case", ctx);
    assert!(rep.diagnostics.is_empty() && rep.program.is_some(), "{:?}", rep.diagnostics);
    let over = format!("{} -> (Dig_1b.Out);\n[Dig_1a.In] [x -> ;\n", "[Dig_1a.In] ".repeat(max + 5));
    let rep = linc_compiler::check_ladder(&over, "case", ctx);
    let found: Vec<_> = rep.diagnostics.iter().map(|d| (d.code.as_str(), d.span.start)).collect();
    assert_eq!(found, [("E0313", "[Dig_1a.In] ".len() * max)]);
    // Boxes around a contact that is nearly as deep as ST allows: too deep.
    let inner = format!("{}Dig_1a.In{}", "NOT (".repeat(190), ")".repeat(190));
    let boxed = format!("{}[{inner}]{} -> (Dig_1b.Out);\n", "NOT(".repeat(30), ")".repeat(30));
    let rep = linc_compiler::check_ladder(&boxed, "case", ctx);
    assert_eq!(rep.diagnostics.iter().map(|d| d.code.as_str()).collect::<Vec<_>>(), ["E0022"]);
    // Each jump crosses the next one's label: written out, rungs would repeat 2^n times.
    let mut src = String::new();
    for i in 0..60 {
        src.push_str(&format!("L{i}: [Dig_1a.In] -> JUMP L{};\n", i + 2));
    }
    src.push_str("L60: -> (Dig_1b.Out);\nL61: -> (Dig_2c.Out);\n");
    let start = std::time::Instant::now();
    let rep = linc_compiler::check_ladder(&src, "case", ctx);
    assert_eq!(rep.diagnostics.iter().map(|d| d.code.as_str()).collect::<Vec<_>>(), ["E0312"]);
    assert!(start.elapsed().as_secs() < 20, "took {:?}", start.elapsed());
}
