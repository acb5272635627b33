//! The guide's Numeric, Random, Selector, Extract, Replace, Bit and
//! Checksum functions (§12.6, §12.6.1), called through `call`.

mod common;
use common::*;
use linc_stdlib::{power, FnError, Value};

const T: Value = Value::Bool(true);
const F: Value = Value::Bool(false);

fn real(v: Value) -> f32 {
    match v {
        Value::Real(x) => x,
        other => panic!("not a REAL: {other:?}"),
    }
}

#[test]
fn numeric_functions() {
    use std::f32::consts::PI;
    let close = |name: &str, a: Vec<Value>, want: f32| {
        let got = real(f(name, &a));
        assert!((got - want).abs() <= 1e-5 * want.abs().max(1.0), "{name}: {got} vs {want}");
    };
    close("ACOS", vec![r(0.0)], PI / 2.0);
    close("ASIN", vec![i(1)], PI / 2.0);
    close("ATAN2", vec![r(1.0), r(-1.0)], 3.0 * PI / 4.0);
    close("ATAN2", vec![i(-1), i(0)], -PI / 2.0);
    close("COS", vec![r(PI)], -1.0);
    close("DEG", vec![r(PI / 2.0)], 90.0);
    close("EXP", vec![i(2)], 7.389_056);
    close("LN", vec![r(std::f32::consts::E)], 1.0);
    close("LOG", vec![i(100)], 2.0);
    close("RAD", vec![i(90)], PI / 2.0);
    close("SIN", vec![r(PI / 2.0)], 1.0);
    close("SQRT", vec![i(2)], std::f32::consts::SQRT_2);
    close("TAN", vec![r(PI / 4.0)], 1.0);
}

#[test]
fn numeric_domain_errors() {
    for (name, args) in [
        ("SQRT", vec![i(-1)]),
        ("LN", vec![i(0)]),
        ("LOG", vec![r(-1.0)]),
        ("ACOS", vec![i(2)]),
        ("ASIN", vec![r(-1.01)]),
        ("EXP", vec![i(1000)]),
        ("DEG", vec![r(f32::MAX)]),
        ("ATAN2", vec![r(f32::NAN), i(1)]),
    ] {
        assert!(matches!(try_call(name, &args), Err(FnError::Domain(_))), "{name}{args:?}");
    }
    assert_eq!(power(2.0, 3.0), Ok(8.0));
    assert_eq!(power(0.0, 2.0), Ok(0.0));
    assert!(matches!(power(-8.0, 1.0 / 3.0), Err(FnError::Domain(_))));
    assert!(matches!(power(0.0, 0.0), Err(FnError::Domain(_))));
}

#[test]
fn random() {
    let mut env = TestEnv { random: 0.25, ..TestEnv::default() };
    assert_eq!(try_call_in(&mut env, "RANDOM", &[i(100)]), Ok(r(25.0)));
    assert_eq!(try_call_in(&mut env, "RANDOM", &[r(2.0)]), Ok(r(0.5)));
    env.random = 0.999_999_999_999;
    let top = real(try_call_in(&mut env, "RANDOM", &[i(1)]).expect("RANDOM"));
    assert!((0.0..1.0).contains(&top));
}

#[test]
fn selectors() {
    assert_eq!(f("AVG", &[i(1), i(2)]), r(1.5));
    assert_eq!(f("AVG", &[i(1), r(2.0), i(6)]), r(3.0));
    assert_eq!(f("MAX", &[i(1), i(7), i(3)]), i(7));
    assert_eq!(f("MAX", &[i(1), r(7.5), i(3)]), r(7.5));
    assert_eq!(f("MIN", &[i(1), i(-7), i(3)]), i(-7));
    assert_eq!(f("MIN", &[r(1.0), i(-7)]), r(-7.0));
    // SWITCH selects A when C = 0, else B.
    assert_eq!(f("SWITCH", &[i(10), i(20), i(0)]), i(10));
    assert_eq!(f("SWITCH", &[i(10), i(20), i(1)]), i(20));
    assert_eq!(f("SWITCH", &[i(10), i(20), i(-5)]), i(20));
    assert_eq!(f("SWITCH", &[i(10), r(20.0), i(0)]), r(10.0));
    // Two or more arguments.
    assert!(try_call("MAX", &[i(1)]).is_err());
    assert!(try_call("AVG", &[]).is_err());
}

#[test]
fn extract_values() {
    let buf = b(&[0x01, 0x80, 0xFF, 0x7F, 0x00, 0x00, 0xC0, 0x3F]);
    let x = |name: &str, p: i32, o: i32| f(name, &[buf.clone(), i(p), i(o)]);
    assert_eq!(x("EXTRACT_BOOL", 1, 0), T);
    assert_eq!(x("EXTRACT_BOOL", 1, 1), F);
    assert_eq!(x("EXTRACT_BOOL", 2, 7), T);
    assert_eq!(f("EXTRACT_INT8", &[buf.clone(), i(2)]), i(-128));
    assert_eq!(f("EXTRACT_UINT8", &[buf.clone(), i(2)]), i(128));
    assert_eq!(x("EXTRACT_INT16", 3, 0), i(0x7FFF));
    assert_eq!(x("EXTRACT_INT16", 3, 1), i(-129));
    assert_eq!(x("EXTRACT_UINT16", 3, 1), i(0xFF7F));
    assert_eq!(x("EXTRACT_INT32", 1, 0), i(0x7FFF_8001));
    assert_eq!(x("EXTRACT_INT32", 1, 1), i(0x0180_FF7F));
    assert_eq!(x("EXTRACT_REAL", 5, 0), r(1.5));
    assert_eq!(x("EXTRACT_REAL", 5, 3), r(f32::from_bits(0xC03F_0000)));
}

#[test]
fn extract_beyond_the_end_is_zero() {
    let buf = b(&[1, 2, 3]);
    let x = |name: &str, p: i32| f(name, &[buf.clone(), i(p), i(0)]);
    assert_eq!(x("EXTRACT_BOOL", 4), F);
    assert_eq!(f("EXTRACT_INT8", &[buf.clone(), i(4)]), i(0));
    assert_eq!(f("EXTRACT_UINT8", &[buf.clone(), i(0)]), i(0));
    assert_eq!(x("EXTRACT_INT16", 3), i(0));
    assert_eq!(x("EXTRACT_UINT16", -1), i(0));
    assert_eq!(x("EXTRACT_INT32", 1), i(0));
    assert_eq!(x("EXTRACT_REAL", 1), r(0.0));
    // Bit outside 0-7.
    assert_eq!(f("EXTRACT_BOOL", &[b(&[0xFF]), i(1), i(8)]), F);
}

#[test]
fn replace_values() {
    let buf = b(&[0; 4]);
    assert_eq!(f("REPLACE_BOOL", &[buf.clone(), i(2), i(1), T]), b(&[0, 2, 0, 0]));
    assert_eq!(f("REPLACE_BOOL", &[b(&[0xFF]), i(1), i(7), i(0)]), b(&[0x7F]));
    assert_eq!(f("REPLACE_INT8", &[buf.clone(), i(4), i(-1)]), b(&[0, 0, 0, 0xFF]));
    assert_eq!(f("REPLACE_UINT8", &[buf.clone(), i(1), i(200)]), b(&[200, 0, 0, 0]));
    let v16 = |name: &str, o: i32| f(name, &[buf.clone(), i(2), i(0x1234), i(o)]);
    assert_eq!(v16("REPLACE_INT16", 0), b(&[0, 0x34, 0x12, 0]));
    assert_eq!(v16("REPLACE_UINT16", 1), b(&[0, 0x12, 0x34, 0]));
    let v32 = |o: i32| f("REPLACE_INT32", &[buf.clone(), i(1), i(0x0A0B_0C0D), i(o)]);
    assert_eq!(v32(0), b(&[0x0D, 0x0C, 0x0B, 0x0A]));
    assert_eq!(v32(1), b(&[0x0A, 0x0B, 0x0C, 0x0D]));
    // 2: MS word LS byte, MS word MS byte, LS word LS byte, LS word MS byte.
    assert_eq!(v32(2), b(&[0x0B, 0x0A, 0x0D, 0x0C]));
    // 3: LS word MS byte, LS word LS byte, MS word MS byte, MS word LS byte.
    assert_eq!(v32(3), b(&[0x0C, 0x0D, 0x0A, 0x0B]));
    let real = f("REPLACE_REAL", &[buf.clone(), i(1), r(1.5), i(1)]);
    assert_eq!(real, b(&[0x3F, 0xC0, 0, 0]));
    let from_int = f("REPLACE_REAL", &[buf, i(1), i(2), i(0)]);
    assert_eq!(from_int, b(&2.0f32.to_le_bytes()));
}

#[test]
fn replace_beyond_the_end_is_null() {
    let buf = b(&[1, 2, 3]);
    assert_eq!(f("REPLACE_BOOL", &[buf.clone(), i(4), i(0), T]), null());
    assert_eq!(f("REPLACE_BOOL", &[buf.clone(), i(1), i(8), T]), null());
    assert_eq!(f("REPLACE_INT8", &[buf.clone(), i(0), i(1)]), null());
    assert_eq!(f("REPLACE_UINT8", &[buf.clone(), i(4), i(1)]), null());
    assert_eq!(f("REPLACE_INT16", &[buf.clone(), i(3), i(1), i(0)]), null());
    assert_eq!(f("REPLACE_UINT16", &[buf.clone(), i(-1), i(1), i(0)]), null());
    assert_eq!(f("REPLACE_INT32", &[buf.clone(), i(1), i(1), i(0)]), null());
    assert_eq!(f("REPLACE_REAL", &[buf.clone(), i(1), r(1.0), i(0)]), null());
    // REPLACE cannot initialise a buffer.
    assert_eq!(f("REPLACE_INT8", &[null(), i(1), i(1)]), null());
    // Order outside 0-3 (decision).
    assert_eq!(f("REPLACE_INT16", &[buf, i(1), i(1), i(4)]), null());
}

#[test]
fn bit_functions() {
    let g = |name: &str, v: i32, n: i32| f(name, &[i(v), i(n)]);
    assert_eq!(f("BIT_INVERT", &[i(0)]), i(-1));
    assert_eq!(f("BIT_INVERT", &[i(0x00FF)]), i(!0x00FF));
    assert_eq!(g("SHL8", 0xFF, 4), i(0xF0));
    assert_eq!(g("SHL16", 0xFFFF, 4), i(0xFFF0));
    assert_eq!(g("SHL32", -1, 4), i(-16));
    assert_eq!(g("SHR8", 0xF0, 4), i(0x0F));
    assert_eq!(g("SHR16", 0xF000, 4), i(0x0F00));
    assert_eq!(g("SHR32", -16, 4), i(0x0FFF_FFFF));
    assert_eq!(g("ROL8", 0x81, 1), i(0x03));
    assert_eq!(g("ROL16", 0x8001, 1), i(0x0003));
    assert_eq!(g("ROL32", i32::MIN + 1, 1), i(3));
    assert_eq!(g("ROR8", 0x81, 1), i(0xC0));
    assert_eq!(g("ROR16", 0x8001, 1), i(0xC000));
    assert_eq!(g("ROR32", 3, 1), i(i32::MIN + 1));
    // 8- and 16-bit results are unsigned, inputs masked first.
    assert_eq!(g("SHL8", -1, 0), i(0xFF));
    assert_eq!(g("ROL16", -1, 3), i(0xFFFF));
    // Shifts by the width or more give 0; negative counts leave the value.
    assert_eq!(g("SHL8", 1, 8), i(0));
    assert_eq!(g("SHR32", -1, 32), i(0));
    assert_eq!(g("SHL16", 5, -2), i(5));
    // Rotation counts are taken modulo the width.
    assert_eq!(g("ROL8", 0x81, 9), i(0x03));
    assert_eq!(g("ROR32", 1, -1), i(2));
}

#[test]
fn bcc() {
    let data = b(&[0x02, 0x31, 0x32, 0x03]);
    assert_eq!(f("BCC", &[data.clone(), i(0), i(0)]), i(0x02 ^ 0x31 ^ 0x32 ^ 0x03));
    assert_eq!(f("BCC", &[data.clone(), i(1), i(0)]), i(0x68));
    assert_eq!(f("BCC", &[b(&[0xFF; 3]), i(1), i(0)]), i(0xFD));
    assert_eq!(f("BCC", &[b(&[0xFF; 3]), i(2), i(0)]), i(765));
    assert_eq!(f("BCC", &[data.clone(), i(0), i(0x55)]), i(0x55 ^ 0x02 ^ 0x31 ^ 0x32 ^ 0x03));
    assert_eq!(f("BCC", &[data, i(9), i(0)]), i(0));
}

#[test]
fn crc_example_12_6_1() {
    // CRC('123456789',1,16#8005,16#FFFF) returns 16#4B37 (MODBUS).
    assert_eq!(f("CRC", &[s("123456789"), i(1), i(0x8005), i(0xFFFF)]), i(0x4B37));
    // CRC16 (8005) non-reversed, seed 0: CRC-16/UMTS (BUYPASS).
    assert_eq!(f("CRC", &[s("123456789"), i(0), i(0x8005), i(0)]), i(0xFEE8));
    // Other modes (decision): 0.
    assert_eq!(f("CRC", &[s("123456789"), i(2), i(0x8005), i(0)]), i(0));
}
