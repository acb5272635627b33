//! The guide's String basics (§12.6), FIND (§12.6.2) and DELIMIT: every
//! example and every null-sequence rule, called through `call`.

mod common;
use common::*;
use linc_stdlib::Value;

const T: Value = Value::Bool(true);
const F: Value = Value::Bool(false);

#[test]
fn equal_is_strict() {
    assert_eq!(f("EQUAL", &[s("abc"), s("abc")]), T);
    assert_eq!(f("EQUAL", &[s("abc"), s("ABC")]), F);
    assert_eq!(f("EQUAL", &[s("abc"), s("abc ")]), F);
    assert_eq!(f("EQUAL", &[null(), null()]), T);
}

#[test]
fn len() {
    assert_eq!(f("LEN", &[s("abc")]), i(3));
    // A null sequence has length 0.
    assert_eq!(f("LEN", &[null()]), i(0));
}

#[test]
fn left_and_right() {
    assert_eq!(f("LEFT", &[s("abcdef"), i(3)]), s("abc"));
    assert_eq!(f("RIGHT", &[s("abcdef"), i(3)]), s("def"));
    assert_eq!(f("LEFT", &[s("abc"), i(3)]), s("abc"));
    // Fewer than L bytes: the null sequence.
    assert_eq!(f("LEFT", &[s("abc"), i(4)]), null());
    assert_eq!(f("RIGHT", &[s("abc"), i(4)]), null());
    // L zero or negative (decision): null.
    assert_eq!(f("LEFT", &[s("abc"), i(0)]), null());
    assert_eq!(f("RIGHT", &[s("abc"), i(-1)]), null());
}

#[test]
fn mid() {
    assert_eq!(f("MID", &[s("abcdef"), i(3), i(2)]), s("bcd"));
    assert_eq!(f("MID", &[s("abcdef"), i(1), i(6)]), s("f"));
    // Fewer than L+P-1 bytes.
    assert_eq!(f("MID", &[s("abcdef"), i(3), i(5)]), null());
    // P zero, negative or greater than the length.
    assert_eq!(f("MID", &[s("abcdef"), i(1), i(0)]), null());
    assert_eq!(f("MID", &[s("abcdef"), i(1), i(-2)]), null());
    assert_eq!(f("MID", &[s("abcdef"), i(0), i(7)]), null());
    // L zero or negative (decision).
    assert_eq!(f("MID", &[s("abcdef"), i(0), i(2)]), null());
    assert_eq!(f("MID", &[s("abcdef"), i(-1), i(2)]), null());
}

#[test]
fn concat() {
    assert_eq!(f("CONCAT", &[s("ab"), s("cd")]), s("abcd"));
    assert_eq!(f("CONCAT", &[null(), s("cd")]), s("cd"));
}

#[test]
fn insert() {
    assert_eq!(f("INSERT", &[s("abef"), s("cd"), i(3)]), s("abcdef"));
    assert_eq!(f("INSERT", &[s("abc"), s("X"), i(1)]), s("Xabc"));
    assert_eq!(f("INSERT", &[s("abc"), s("X"), i(4)]), s("abcX"));
    // P zero, negative, or greater than the length + 1.
    assert_eq!(f("INSERT", &[s("abc"), s("X"), i(0)]), null());
    assert_eq!(f("INSERT", &[s("abc"), s("X"), i(-1)]), null());
    assert_eq!(f("INSERT", &[s("abc"), s("X"), i(5)]), null());
}

#[test]
fn delete() {
    assert_eq!(f("DELETE", &[s("abcdef"), i(2), i(3)]), s("abef"));
    assert_eq!(f("DELETE", &[s("abcdef"), i(6), i(1)]), s(""));
    assert_eq!(f("DELETE", &[s("abcdef"), i(1), i(6)]), s("abcde"));
    // Fewer than L+P-1 bytes, or P zero or negative.
    assert_eq!(f("DELETE", &[s("abcdef"), i(2), i(6)]), null());
    assert_eq!(f("DELETE", &[s("abcdef"), i(1), i(0)]), null());
    assert_eq!(f("DELETE", &[s("abcdef"), i(1), i(-1)]), null());
    // L zero or negative (decision).
    assert_eq!(f("DELETE", &[s("abcdef"), i(0), i(1)]), null());
    assert_eq!(f("DELETE", &[s("abcdef"), i(-1), i(1)]), null());
}

#[test]
fn replace() {
    assert_eq!(f("REPLACE", &[s("abcdef"), s("XYZ"), i(2), i(3)]), s("abXYZef"));
    assert_eq!(f("REPLACE", &[s("abcdef"), s(""), i(2), i(3)]), s("abef"));
    assert_eq!(f("REPLACE", &[s("abc"), s("Z"), i(1), i(3)]), s("abZ"));
    // Fewer than L+P-1 bytes, or P zero or negative.
    assert_eq!(f("REPLACE", &[s("abc"), s("Z"), i(2), i(3)]), null());
    assert_eq!(f("REPLACE", &[s("abc"), s("Z"), i(1), i(0)]), null());
    assert_eq!(f("REPLACE", &[s("abc"), s("Z"), i(1), i(-4)]), null());
    // L zero or negative (decision).
    assert_eq!(f("REPLACE", &[s("abc"), s("Z"), i(0), i(1)]), null());
}

#[test]
fn find_examples_12_6_2() {
    assert_eq!(f("FIND", &[s("ABACA"), s("A"), i(2)]), i(3));
    assert_eq!(f("FIND", &[s("ABACABA"), s("AB"), i(2)]), i(5));
    assert_eq!(f("FIND", &[s("AAAAA"), s("AA"), i(-1)]), i(4));
    assert_eq!(f("FIND", &[s("AAAAA"), s("A"), i(-1)]), i(5));
    assert_eq!(f("FIND", &[s("AAAAA"), s(""), i(-1)]), i(6));
}

#[test]
fn find_rules() {
    // N omitted defaults to 1.
    assert_eq!(f("FIND", &[s("xxABxAB"), s("AB")]), i(3));
    // N zero, ByteSeq1 null, or no occurrence: 0.
    assert_eq!(f("FIND", &[s("ABC"), s("B"), i(0)]), i(0));
    assert_eq!(f("FIND", &[null(), s("B"), i(1)]), i(0));
    assert_eq!(f("FIND", &[s("ABC"), s("D"), i(1)]), i(0));
    assert_eq!(f("FIND", &[s("ABC"), s("B"), i(2)]), i(0));
    // ByteSeq2 null: 1 for positive N, length + 1 for negative N.
    assert_eq!(f("FIND", &[s("ABC"), null(), i(1)]), i(1));
    assert_eq!(f("FIND", &[s("ABC"), null(), i(3)]), i(1));
    assert_eq!(f("FIND", &[s("ABC"), null(), i(-2)]), i(4));
    // Non-overlapping.
    assert_eq!(f("FIND", &[s("AAAA"), s("AA"), i(2)]), i(3));
    assert_eq!(f("FIND", &[s("AAA"), s("AA"), i(2)]), i(0));
}

#[test]
fn delimit_examples() {
    let d = |a: &str, b: &str, n: i32| f("DELIMIT", &[s(a), s(b), i(n)]);
    assert_eq!(d("a+b+c", "+", 2), s("b"));
    assert_eq!(d("abc;;def;ghi", ";", 3), s("def"));
    assert_eq!(d("a::bb::ccc::dddd", "::", -2), s("ccc"));
    assert_eq!(d("A/B/C/", "/", -4), s("A"));
    assert_eq!(d("ABCDEFG", "BX", 1), s("ABCDEFG"));
    assert_eq!(d("ABCDEFG", "BX", 2), s(""));
    assert_eq!(d("ABC>>>DEF>>>G", ">>", 2), s(">DEF"));
}

#[test]
fn delimit_rules() {
    let d = |a: &str, b: &str, n: i32| f("DELIMIT", &[s(a), s(b), i(n)]);
    // ByteSeq1 null, ByteSeq2 null, N = 0: null.
    assert_eq!(d("", "+", 1), null());
    assert_eq!(d("a+b", "", 1), null());
    assert_eq!(d("a+b", "+", 0), null());
    // Fewer than |N|-1 delimiters: null; exactly |N|-1: the last field.
    assert_eq!(d("a+b", "+", 3), null());
    assert_eq!(d("a+b", "+", -3), null());
    assert_eq!(d("a+b", "+", 2), s("b"));
    assert_eq!(d("a+b", "+", -2), s("a"));
    // Empty fields between adjacent delimiters.
    assert_eq!(d("abc;;def;ghi", ";", 2), s(""));
    // Counted from the right, delimiters found from the right (decision).
    assert_eq!(d("ABC>>>DEF>>>G", ">>", -2), s("DEF>"));
}

#[test]
fn justify() {
    assert_eq!(f("JUSTIFY_LEFT", &[s("ab"), i(5)]), s("ab   "));
    assert_eq!(f("JUSTIFY_RIGHT", &[s("ab"), i(5)]), s("   ab"));
    assert_eq!(f("JUSTIFY_CENTRE", &[s("ab"), i(6)]), s("  ab  "));
    // Cannot be centred exactly: biased to the left.
    assert_eq!(f("JUSTIFY_CENTRE", &[s("ab"), i(5)]), s(" ab  "));
    assert_eq!(f("JUSTIFY_CENTRE", &[s("abc"), i(4)]), s("abc "));
    assert_eq!(f("JUSTIFY_LEFT", &[s("ab"), i(2)]), s("ab"));
    // Longer than the field: null.
    for name in ["JUSTIFY_LEFT", "JUSTIFY_RIGHT", "JUSTIFY_CENTRE"] {
        assert_eq!(f(name, &[s("abc"), i(2)]), null(), "{name}");
        assert_eq!(f(name, &[s("abc"), i(-1)]), null(), "{name}");
        assert_eq!(f(name, &[null(), i(0)]), null(), "{name}");
    }
}

#[test]
fn trims() {
    assert_eq!(f("LTRIM", &[s("  a b  ")]), s("a b  "));
    assert_eq!(f("RTRIM", &[s("  a b  ")]), s("  a b"));
    assert_eq!(f("TRIM", &[s("  a b  ")]), s("a b"));
    assert_eq!(f("TRIM", &[s("    ")]), null());
}

#[test]
fn cases_are_ascii_only() {
    assert_eq!(f("UCASE", &[b(b"abc-xyz\xe9")]), b(b"ABC-XYZ\xe9"));
    assert_eq!(f("LCASE", &[b(b"ABC-XYZ\xc9")]), b(b"abc-xyz\xc9"));
}

#[test]
fn string_and_space() {
    assert_eq!(f("STRING", &[i(3), s("xyz")]), s("xxx"));
    assert_eq!(f("SPACE", &[i(4)]), s("    "));
    // Greater than 1020: clipped to 1020.
    assert_eq!(f("STRING", &[i(5000), s("x")]), s(&"x".repeat(1020)));
    assert_eq!(f("SPACE", &[i(1021)]), s(&" ".repeat(1020)));
    assert_eq!(f("SPACE", &[i(1020)]), s(&" ".repeat(1020)));
    // Zero or negative, or no first byte (decision): null.
    assert_eq!(f("STRING", &[i(0), s("x")]), null());
    assert_eq!(f("STRING", &[i(3), null()]), null());
    assert_eq!(f("SPACE", &[i(-1)]), null());
}

#[test]
fn strcomp() {
    assert_eq!(f("STRCOMP", &[s("aa"), s("ab")]), i(-1));
    assert_eq!(f("STRCOMP", &[s("aa"), s("aaa")]), i(-1));
    assert_eq!(f("STRCOMP", &[s("ab"), s("aa")]), i(1));
    assert_eq!(f("STRCOMP", &[s("aa"), s("aa")]), i(0));
    assert_eq!(f("STRCOMP", &[s("a"), s("A")]), i(1));
}

#[test]
fn purge() {
    assert_eq!(f("PURGE", &[s("abcdabcde"), s("bd")]), s("acace"));
    assert_eq!(f("PURGE", &[s("abc"), null()]), s("abc"));
}

#[test]
fn date_and_time_now() {
    assert_eq!(f("DATEANDTIMENOW", &[]), s("23/09/2006 00:43:06"));
    assert_eq!(f("DATEANDTIMENOW", &[i(0)]), s("23/09/2006 00:43:06"));
    assert_eq!(f("DATEANDTIMENOW", &[i(1)]), s("22/09/2006 23:43:06"));
    assert_eq!(f("DATEANDTIMENOW", &[i(2)]), null());
    // The guide's mm/dd/yy example.
    let buffer1 = f("DATEANDTIMENOW", &[]);
    let mm = f("MID", &[buffer1.clone(), i(3), i(4)]);
    let dd = f("LEFT", &[buffer1.clone(), i(3)]);
    let yy = f("MID", &[buffer1, i(2), i(9)]);
    let front = f("CONCAT", &[mm, dd]);
    assert_eq!(f("CONCAT", &[front, yy]), s("09/23/06"));
}
