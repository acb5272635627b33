//! The guide's Convert functions: the §12.6 table and every example of
//! §12.6.3 (conversion formats), called through `call`.

mod common;
use common::*;
use linc_stdlib::Value;

fn format(fmt: &str, v: Value) -> Value {
    f("FORMAT", &[s(fmt), v])
}

fn scan(fmt: &str, input: &str) -> Value {
    f("SCAN", &[s(fmt), s(input)])
}

fn valid(fmt: &str, input: &str) -> Value {
    f("IS_VALID", &[s(fmt), s(input)])
}

#[test]
fn abs_float_round_trunc() {
    assert_eq!(f("ABS", &[i(-3)]), i(3));
    assert_eq!(f("ABS", &[r(-3.5)]), r(3.5));
    assert_eq!(f("ABS", &[i(i32::MIN)]), i(i32::MAX));
    assert_eq!(f("FLOAT", &[i(7)]), r(7.0));
    assert_eq!(f("ROUND", &[r(2.5)]), i(3));
    assert_eq!(f("ROUND", &[r(-2.5)]), i(-3));
    assert_eq!(f("ROUND", &[r(2.49)]), i(2));
    assert_eq!(f("TRUNC", &[r(2.99)]), i(2));
    assert_eq!(f("TRUNC", &[r(-2.99)]), i(-2));
    assert_eq!(f("TRUNC", &[r(1e12)]), i(i32::MAX));
    assert_eq!(f("TRUNC", &[r(-1e12)]), i(i32::MIN));
}

#[test]
fn format_table_example_04x() {
    // Tx_Value = FORMAT("04X", Raw1.I2): a 4-digit hexadecimal string.
    assert_eq!(format("04X", i(453)), s("01C5"));
    assert_eq!(format("04X", i(0xABCD)), s("ABCD"));
}

#[test]
fn format_null_when_not_convertible() {
    assert_eq!(format("Q", i(1)), null());
    assert_eq!(format("", i(1)), null());
    assert_eq!(format("5.2I", i(1)), null());
    assert_eq!(format("C", i(256)), null());
    assert_eq!(format("C", i(-1)), null());
    assert_eq!(format("G", r(1.0)), null());
    assert_eq!(format("T", i(246000)), null());
    assert_eq!(format("D", i(20060931)), null());
    assert_eq!(format("F", r(f32::NAN)), null());
}

#[test]
fn scan_table_example_hex_in_a_telegram() {
    // Setpoint := SCAN("X", MID(Raw1.Rx_Value, 4, 10)) gives 453 from
    // '[M01G0DI*01C5E5$R'.
    let rx = b(b"[M01G0DI*01C5E5\r");
    let field = f("MID", &[rx, i(4), i(10)]);
    assert_eq!(field, s("01C5"));
    assert_eq!(f("SCAN", &[s("X"), field]), i(453));
}

#[test]
fn scan_invalid_start_gives_zero() {
    assert_eq!(scan("I", " A123"), i(0));
    assert_eq!(scan("F", "x1.5"), r(0.0));
    assert_eq!(scan("I", ""), i(0));
    assert_eq!(scan("I", "12AB"), i(12));
}

#[test]
fn is_valid_table_example() {
    assert_eq!(valid("U", " -4789"), Value::Bool(false));
}

#[test]
fn i_signed_decimal() {
    assert_eq!(format("5I", i(7412)), s(" 7412"));
    assert_eq!(format("05I", i(7412)), s("07412"));
    assert_eq!(format("05I", i(-123)), s("-0123"));
    assert_eq!(format("3I!", i(7412)), s("!!!"));
    assert_eq!(scan("I", "  4789"), i(4789));
    assert_eq!(scan("I", " -4789"), i(-4789));
    assert_eq!(scan("3I", "-4789"), i(-47));
    assert_eq!(valid("I", " -4789"), Value::Bool(true));
    assert_eq!(valid("I", " A123"), Value::Bool(false));
}

#[test]
fn u_unsigned_decimal() {
    assert_eq!(format("5U", i(7412)), s(" 7412"));
    assert_eq!(format("05U", i(7412)), s("07412"));
    assert_eq!(format("5U", i(0xFFFF)), s("65535"));
    assert_eq!(format("U", i(-1)), s("4294967295"));
    assert_eq!(scan("U", "4789"), i(4789));
    assert_eq!(scan("2U", "4789"), i(47));
    assert_eq!(scan("U", "-4789"), i(0));
    assert_eq!(valid("U", "-4789"), Value::Bool(false));
}

#[test]
fn x_hexadecimal() {
    assert_eq!(format("06x", i(32767)), s("007fff"));
    assert_eq!(format("X", i(65535)), s("FFFF"));
    assert_eq!(scan("X", "FF"), i(255));
    assert_eq!(format("X", i(-1)), s("FFFFFFFF"));
}

#[test]
fn b_binary() {
    assert_eq!(format("08B", i(93)), s("01011101"));
    assert_eq!(scan("B", " 1111111111"), i(1023));
}

#[test]
fn o_octal() {
    assert_eq!(format("O", i(511)), s("777"));
    assert_eq!(format("4O", i(511)), s(" 777"));
    assert_eq!(format("04O", i(511)), s("0777"));
    assert_eq!(scan("O", "77"), i(63));
}

#[test]
fn f_real() {
    let v = r(1000.0 / 3.0);
    assert_eq!(format("6.2F", v.clone()), s("333.33"));
    assert_eq!(format("6.F", v.clone()), s("  333."));
    assert_eq!(format("6F", v.clone()), s("  333"));
    assert_eq!(format("F", v), s("333"));
    assert_eq!(scan("F", " -1.456E-2"), r(-1.456));
}

#[test]
fn e_scientific() {
    let v = r(1000.0 / 3.0);
    assert_eq!(format("10.2E", v.clone()), s("  3.33E+02"));
    assert_eq!(format("10.2e", v), s("  3.33e+02"));
    assert_eq!(format("E", r(1.0e-5)), s("1E-05"));
    assert_eq!(format(".3E", r(-1.5e30)), s("-1.500E+30"));
    // For FORMAT only.
    assert_eq!(scan("E", "1.5"), i(0));
    assert_eq!(valid("E", "1.5"), Value::Bool(false));
}

#[test]
fn g_general() {
    assert_eq!(scan("G", " -1.456E-2"), r(-0.01456));
    assert_eq!(valid("G", " -1.456E-2"), Value::Bool(true));
}

#[test]
fn c_single_character() {
    assert_eq!(format("C", i(65)), s("A"));
    assert_eq!(scan("C", "B"), i(66));
    assert_eq!(scan("C", " B"), i(32));
}

#[test]
fn t_iso8601_time() {
    assert_eq!(format("T", i(123306)), s("12:33:06"));
    assert_eq!(format("T.", i(123306)), s("12.33.06"));
    assert_eq!(scan("T", "14:27:30"), i(142730));
}

#[test]
fn tp_posix_time() {
    assert_eq!(format("TP", i(45186)), s("12:33:06"));
    assert_eq!(format("TP.", i(45186)), s("12.33.06"));
    assert_eq!(scan("TP", "00:01:30"), i(90));
    // Greater than 86399: modulo 86400.
    assert_eq!(format("TP", i(45186 + 3 * 86400)), s("12:33:06"));
}

#[test]
fn d_iso8601_date() {
    assert_eq!(format("D", i(20060923)), s("23/09/2006"));
    assert_eq!(scan("D", "04/07/2005"), i(20050704));
}

#[test]
fn dp_posix_date() {
    assert_eq!(format("DP", i(345600)), s("05/01/70"));
    assert_eq!(scan("DP", "15/01/70"), i(1209600));
}

#[test]
fn width_truncates_scanned_input() {
    // SCAN("6I", Buffer) is equivalent to SCAN("I", LEFT(Buffer, 6)).
    let buffer = s("  123456789");
    let left = f("LEFT", &[buffer.clone(), i(6)]);
    assert_eq!(f("SCAN", &[s("6I"), buffer]), f("SCAN", &[s("I"), left]));
    assert_eq!(scan("6I", "  123456789"), i(1234));
    // A shorter input is scanned whole.
    assert_eq!(scan("6I", "12"), i(12));
}

#[test]
fn override_character_fills_the_width() {
    assert_eq!(format("3I", i(7412)), s("***"));
    assert_eq!(format("4.2F#", r(123.0)), s("####"));
    assert_eq!(format("5T", i(123306)), s("*****"));
    assert_eq!(format("7T.?", i(123306)), s("???????"));
    assert_eq!(format("4X", i(0xFFFF)), s("FFFF"));
    assert_eq!(format("3X-", i(0xFFFF)), s("---"));
}

#[test]
fn scan_result_kind_follows_the_checker() {
    let sig = linc_stdlib::lookup("SCAN").expect("SCAN");
    for (fmt, input) in [("F", "1.5"), ("I", "7"), ("6.2F", "x"), ("X", "zz")] {
        let v = scan(fmt, input);
        let ty = sig.result(&[], Some(fmt.as_bytes()));
        let kind = match v {
            Value::Real(_) => linc_stdlib::Ty::Real,
            _ => linc_stdlib::Ty::Int,
        };
        assert_eq!(kind, ty, "{fmt}");
    }
}
