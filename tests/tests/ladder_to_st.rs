//! `linc ladder to-st` prints ST that linc reads back as the same program:
//! for generated ladder that checks clean (long series, comparison
//! contacts with every operator, negative and based constants, REAL and
//! time constants, bracketed names, bits, function boxes, jumps, variable
//! outputs, ACTION headers), the printed ST checks clean and its tree is
//! the desugared tree (AND, OR and XOR chains compared flat: they are
//! associative, and a long series is printed with fewer brackets).

use linc_compiler::ladder::pretty::to_st;
use linc_compiler::st::ast::{Expr, ExprKind, SourceFile, Stmt, UnOp, Var};
use linc_compiler::Context;
use linc_conformance::rng::Rng;
use linc_runtime::Database;

fn db() -> Database {
    Database::from_json(include_str!("../../examples/ladder/plant.json")).expect("plant.json")
}

const DIGITAL: [&str; 6] = ["Dig_1a.In", "Dig_2b.In", "Dig_1b.Out", "Bits_1.Word.Bit3", "[Dig_3a].In", "dig_4A.IN"];
const REALS: [&str; 3] = ["Ana_7a.PV", "[Ana_8a.PV]", "RECIPE1.A0"];
const INTS: [&str; 2] = ["Ana_7a.Count", "Ana_8a.Count"];
const REAL_CONSTANTS: [&str; 6] = ["1.5", "1e30", "2.5E-7", "0.0", "T#1h30m", "T#0.25s"];
const INT_CONSTANTS: [&str; 5] = ["3", "16#FF", "2#1010", "2147483647", "0"];

fn pick<'a>(r: &mut Rng, from: &[&'a str]) -> &'a str {
    from[r.below(from.len())]
}

/// A numeric ST expression: REAL, or INT when `int` (MOD and the INT
/// fields need it), with every operator, prefix minus and brackets.
fn num(r: &mut Rng, int: bool, depth: usize) -> String {
    if depth > 3 || r.below(3) == 0 {
        let leaf = match (int, r.below(2)) {
            (true, 0) => pick(r, &INTS).to_string(),
            (true, _) => pick(r, &INT_CONSTANTS).to_string(),
            (false, 0) => pick(r, &REALS).to_string(),
            (false, _) => pick(r, &REAL_CONSTANTS).to_string(),
        };
        return if r.below(4) == 0 { format!("-{leaf}") } else { leaf };
    }
    let (a, b) = (num(r, int, depth + 1), num(r, int, depth + 1));
    let ops: &[&str] = if int { &["+", "-", "*", "MOD"] } else { &["+", "-", "*", "/", "**"] };
    let op = pick(r, ops);
    match r.below(4) {
        0 => format!("-({a} {op} {b})"),
        1 => format!("({a}) {op} ({b})"),
        2 => format!("{a} {op} - {b}"),
        _ => format!("{a} {op} {b}"),
    }
}

/// What stands between a contact's brackets.
fn contact(r: &mut Rng) -> String {
    let inner = match r.below(5) {
        0 | 1 => pick(r, &DIGITAL).to_string(),
        2 => {
            let int = r.below(2) == 0;
            format!("{} {} {}", num(r, int, 0), pick(r, &["<", ">", "<=", ">=", "=", "<>"]), num(r, int, 0))
        }
        3 => format!("NOT ({} {} {})", pick(r, &DIGITAL), pick(r, &["AND", "OR", "XOR"]), pick(r, &DIGITAL)),
        _ => format!("{} AND ({} OR {})", pick(r, &DIGITAL), pick(r, &DIGITAL), pick(r, &DIGITAL)),
    };
    format!("[{}{inner}]", if r.below(3) == 0 { "/" } else { "" })
}

fn cond(r: &mut Rng, depth: usize) -> String {
    if depth >= 3 || r.below(3) == 0 {
        // Now and then a long series: written flat it would be too deep.
        if r.below(10) == 0 {
            let n = 100 + r.below(200);
            return (0..n).map(|_| format!("[{}]", pick(r, &DIGITAL))).collect::<Vec<_>>().join(" ");
        }
        return (0..1 + r.below(3)).map(|_| contact(r)).collect::<Vec<_>>().join(" ");
    }
    let kids: Vec<String> = (0..2 + r.below(2)).map(|_| cond(r, depth + 1)).collect();
    match r.below(5) {
        0 => format!("({})", kids.join(" | ")),
        1 => format!("AND({})", kids.join(", ")),
        2 => format!("OR({})", kids.join(", ")),
        3 => format!("XOR({})", kids.join(", ")),
        _ => format!("NOT({})", kids[0]),
    }
}

/// Rungs `0..n` of one action, labelled `R0…`, jumping only forwards.
fn rungs(r: &mut Rng, n: usize) -> String {
    let mut s = String::new();
    for i in 0..n {
        let c = if r.below(6) == 0 { String::new() } else { cond(r, 0) };
        let out = match r.below(6) {
            0 => format!(
                "JUMP {}",
                if i + 1 == n || r.below(3) == 0 { "_End".into() } else { format!("R{}", i + 1 + r.below(n - i - 1)) }
            ),
            1 => format!("Ana_7b.PV := {}", num(r, false, 0)),
            2 => format!("Ana_8c.Count := {}", num(r, true, 0)),
            k => format!(
                "({}{})",
                ["", "/", "S ", "R "][k - 2],
                pick(r, &["Dig_1b.Out", "Dig_2c.Out", "Bits_1.Word.Bit9"])
            ),
        };
        s.push_str(&format!("R{i}: {c} -> {out};\n"));
    }
    s
}

fn program(r: &mut Rng) -> String {
    if r.below(2) == 0 {
        let n = 1 + r.below(6);
        return rungs(r, n);
    }
    (0..1 + r.below(3))
        .map(|i| {
            let header = if r.below(2) == 0 { format!("ACTION Act{i}") } else { format!("ACTION a_{i} : ACTION") };
            let n = 1 + r.below(5);
            format!("{header}\n{}END_ACTION\n", rungs(r, n))
        })
        .collect()
}

/// The tree without spans, AND/OR/XOR chains flat and `-` folded into a
/// constant after it (as the parser folds `-5`).
fn norm(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Binary(op, ..) if matches!(op.symbol(), "AND" | "OR" | "XOR") => {
            fn chain<'e>(e: &'e Expr, sym: &str, out: &mut Vec<&'e Expr>) {
                match &e.kind {
                    ExprKind::Binary(o, a, b) if o.symbol() == sym => {
                        chain(a, sym, out);
                        chain(b, sym, out);
                    }
                    _ => out.push(e),
                }
            }
            let mut ops = Vec::new();
            chain(e, op.symbol(), &mut ops);
            format!("({} {})", op.symbol(), ops.iter().map(|o| norm(o)).collect::<Vec<_>>().join(" "))
        }
        ExprKind::Binary(op, a, b) => format!("({} {} {})", op.symbol(), norm(a), norm(b)),
        ExprKind::Unary(UnOp::Neg, a) => match &a.kind {
            ExprKind::Int(i) => format!("{}", -i),
            ExprKind::Real(x) => format!("{:?}", -x),
            _ => format!("(neg {})", norm(a)),
        },
        ExprKind::Unary(UnOp::Not, a) => format!("(not {})", norm(a)),
        ExprKind::Int(i) => format!("{i}"),
        ExprKind::Real(x) => format!("{x:?}"),
        ExprKind::Time(t) => format!("T{t}"),
        ExprKind::Bool(b) => format!("{b}"),
        ExprKind::Str(s) => format!("'{s}'"),
        ExprKind::Var(v) => var(v),
        ExprKind::Call { name, args } => {
            format!("({} {})", name.text, args.iter().map(norm).collect::<Vec<_>>().join(" "))
        }
        ExprKind::Error => "error".into(),
    }
}

fn var(v: &Var) -> String {
    let segs: Vec<String> = v
        .segs
        .iter()
        .map(|s| match &s.offset {
            Some(o) => format!("{}{{{}}}", s.name.text, norm(o)),
            None => s.name.text.to_string(),
        })
        .collect();
    segs.join(".")
}

fn stmts(list: &[Stmt]) -> String {
    list.iter()
        .map(|s| match s {
            Stmt::Assign { target, value, .. } => format!("{} := {};", var(target), norm(value)),
            Stmt::If { arms, otherwise, .. } => {
                let arms: Vec<String> = arms.iter().map(|(c, b)| format!("{} -> [{}]", norm(c), stmts(b))).collect();
                format!("if {} else [{}];", arms.join(" | "), otherwise.as_deref().map(stmts).unwrap_or_default())
            }
            other => format!("{other:?}"),
        })
        .collect()
}

fn file(f: &SourceFile) -> String {
    f.actions
        .iter()
        .map(|a| {
            let t = a.block_type.as_ref().map(|t| t.text.as_str()).unwrap_or("");
            format!("{} {t} {{{}}}\n", a.name.text, stmts(&a.body))
        })
        .collect()
}

#[test]
fn the_st_of_any_valid_ladder_checks_clean_and_means_the_same() {
    let db = db();
    let ctx = Context::of(Some(&db));
    let mut clean = 0;
    for case in 0..200 {
        let mut r = Rng::new(case);
        let src = program(&mut r);
        let rep = linc_compiler::check_ladder(&src, "case", ctx);
        if rep.has_errors() {
            continue;
        }
        clean += 1;
        let tree = rep.tree.as_ref().expect("tree");
        let st = to_st::file(tree);
        let back = linc_compiler::check_source(&st, "case", ctx);
        assert!(!back.has_errors(), "case {case}:\n{src}\nprints\n{st}\nwhich has {:?}", back.diagnostics);
        assert_eq!(file(back.tree.as_ref().expect("tree")), file(tree), "case {case}:\n{src}\nprints\n{st}");
    }
    // The generator's ladder is valid nearly always, so the property is tested.
    assert!(clean > 150, "only {clean} of 200 generated files checked clean");
}

/// The cases found by the generator, each of which printed ST that linc
/// rejected or read differently.
#[test]
fn the_st_of_each_found_case_reads_back() {
    let db = db();
    let ctx = Context::of(Some(&db));
    let cases = [
        // A series longer than an expression may be deep, written flat.
        format!("{}-> (Dig_1b.Out);\n", "[Dig_1a.In] ".repeat(300)),
        // `-(a ** b)` was written `-a ** b`, which is `(-a) ** b`.
        "[-(Ana_7a.PV ** 2.0) > 1.0] -> (Dig_1b.Out);\n".to_string(),
        // A condition 199 deep under a negated coil: NOT made it 200 + 1.
        format!("[{}Dig_1a.In{}] -> (/Dig_1b.Out);\n", "NOT (".repeat(198), ")".repeat(198)),
    ];
    for src in &cases {
        let rep = linc_compiler::check_ladder(src, "case", ctx);
        assert!(!rep.has_errors(), "{src}: {:?}", rep.diagnostics);
        let tree = rep.tree.as_ref().expect("tree");
        let st = to_st::file(tree);
        let back = linc_compiler::check_source(&st, "case", ctx);
        assert!(!back.has_errors(), "{src}\nprints\n{st}\nwhich has {:?}", back.diagnostics);
        assert_eq!(file(back.tree.as_ref().expect("tree")), file(tree), "{src}\nprints\n{st}");
    }
    // A bracketed name with an offset: the offset went inside the brackets.
    let guide = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide db");
    let gctx = Context::of(Some(&guide));
    let src = "[[Block_5.Val1]{2} > 1.0] -> (Dig_A.Out.Bit0);\n";
    let rep = linc_compiler::check_ladder(src, "case", gctx);
    assert!(!rep.has_errors(), "{src}: {:?}", rep.diagnostics);
    let st = to_st::file(rep.tree.as_ref().expect("tree"));
    assert_eq!(
        st,
        "IF [Block_5.Val1]{2} > 1.0 THEN\n    Dig_A.Out.Bit0 := TRUE;\nELSE\n    Dig_A.Out.Bit0 := FALSE;\nEND_IF;\n"
    );
    assert!(!linc_compiler::check_source(&st, "case", gctx).has_errors());
    // A string with a `'` keeps its double quotes.
    let e = linc_compiler::st::parser::parse_expr("\"it's\" = 'a$'b'").0.expect("parses");
    assert_eq!(to_st::expr(&e), "\"it's\" = 'a$'b'");
    // One level deeper is refused by the ladder itself, and a keyword is no action name.
    let deep = format!("[{}Dig_1a.In{}] -> (/Dig_1b.Out);\n", "NOT (".repeat(199), ")".repeat(199));
    let codes: Vec<_> =
        linc_compiler::check_ladder(&deep, "case", ctx).diagnostics.iter().map(|d| d.code.as_str()).collect();
    assert_eq!(codes, ["E0022"]);
    let keyword = "ACTION END_FOR\n[Dig_1a.In] -> (Dig_1b.Out);\nEND_ACTION\n";
    let codes: Vec<_> =
        linc_compiler::check_ladder(keyword, "case", ctx).diagnostics.iter().map(|d| d.code.as_str()).collect();
    assert_eq!(codes, ["E0014"]);
}
