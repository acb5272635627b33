//! Binary operators are bound by precedence while the parser reads a flat
//! chain (`parse_support::Climb`). Every pair of operators in `a op b op c`,
//! and chains of three, must group as the precedence table says (§12.6):
//! tighter first, equal levels to the left; prefix operators bind tightest.

use linc_compiler::st::parser::parse_expr;
use linc_compiler::st::pretty;

/// The operators, with their level (lower binds tighter).
const OPS: [(&str, u8); 15] = [
    ("**", 2),
    ("*", 3),
    ("/", 3),
    ("MOD", 3),
    ("+", 4),
    ("-", 4),
    ("=", 5),
    ("<>", 5),
    ("<", 5),
    (">", 5),
    ("<=", 5),
    (">=", 5),
    ("AND", 6),
    ("XOR", 7),
    ("OR", 8),
];

fn tree(src: &str) -> String {
    let (e, errors) = parse_expr(src);
    assert!(errors.syntax.is_empty() && errors.lex.is_empty(), "{src}: {errors:?}");
    pretty::expr(&e.expect("an expression"))
}

fn bin(op: &str, a: &str, b: &str) -> String {
    format!("({op} {a} {b})")
}

#[test]
fn every_pair_of_operators_groups_by_precedence() {
    for (p, lp) in OPS {
        for (q, lq) in OPS {
            let src = format!("a {p} b {q} c");
            let want = if lp <= lq { bin(q, &bin(p, "a", "b"), "c") } else { bin(p, "a", &bin(q, "b", "c")) };
            assert_eq!(tree(&src), want, "{src}");
        }
    }
}

#[test]
fn every_triple_of_levels_groups_by_precedence() {
    // One operator per level is enough: the grouping depends on levels only.
    let reps: Vec<(&str, u8)> = [0, 1, 4, 6, 12, 13, 14].iter().map(|&i| OPS[i]).collect();
    for &(p, lp) in &reps {
        for &(q, lq) in &reps {
            for &(r, lr) in &reps {
                let src = format!("a {p} b {q} c {r} d");
                assert_eq!(tree(&src), reference(&[("a", 0), ("b", lp), ("c", lq), ("d", lr)], &[p, q, r]), "{src}");
            }
        }
    }
}

/// An independent grouping by recursive splitting: the loosest operator
/// (the last one among equals, for left association) is the root.
fn reference(operands: &[(&str, u8)], ops: &[&str]) -> String {
    if ops.is_empty() {
        return operands[0].0.to_string();
    }
    let levels: Vec<u8> = operands[1..].iter().map(|o| o.1).collect();
    let loosest = *levels.iter().max().expect("an operator");
    let root = levels.iter().rposition(|&l| l == loosest).expect("found");
    let left = reference(&operands[..=root], &ops[..root]);
    let right = reference(&operands[root + 1..], &ops[root + 1..]);
    bin(ops[root], &left, &right)
}

#[test]
fn prefix_operators_bind_tighter_than_any_binary_operator() {
    assert_eq!(tree("-a ** 2"), "(** (neg a) 2)");
    assert_eq!(tree("NOT a AND b"), "(AND (NOT a) b)");
    assert_eq!(tree("a - -b * c"), "(- a (* (neg b) c))");
    assert_eq!(tree("a OR NOT b = c"), "(OR a (= (NOT b) c))");
    assert_eq!(tree("(a + b) * c"), "(* (+ a b) c)");
}
