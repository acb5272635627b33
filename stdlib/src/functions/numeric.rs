//! Numeric functions (§12.6, sub-category Numeric) and the `**` operator.
//!
//! REAL is f32. Each function computes in f64 and rounds the result to f32;
//! an argument outside the mathematical domain, or a result that is NaN or
//! infinite as an f32 (EXP(100), DEG(3E38)), is a [`FnError::Domain`]
//! whose message gives the reason: which argument is out of its domain, or
//! that the result overflows the largest REAL. ATAN2(0, 0) is 0, as in C
//! (the guide is silent).

use crate::FnError;

/// The largest REAL, as messages name it.
const MAX_REAL: &str = "3.4028235E38";

/// A REAL as a message shows it: shortest decimal, with an exponent when
/// very large or small (`3E38`, not 39 digits).
fn number(a: f32) -> String {
    let m = a.abs();
    if m.is_finite() && m != 0.0 && !(1e-5..1e7).contains(&m) {
        format!("{a:E}")
    } else {
        a.to_string()
    }
}

/// An operand of `**` as a message shows it: a negative one in brackets,
/// so that `(-2) ** 2` does not read as `-(2 ** 2)`.
fn shown(a: f32) -> String {
    if a.is_sign_negative() && !a.is_nan() {
        format!("({})", number(a))
    } else {
        number(a)
    }
}

/// Why a function of a finite argument gave no finite REAL for its exact
/// result `y`: the argument was outside the function's domain, or `y` is a
/// number too large for a REAL.
fn reason(name: &str, y: f64) -> String {
    match name {
        "LN" | "LOG" => "is undefined: the argument must exceed zero".to_string(),
        "SQRT" => "is undefined: the argument must not be negative".to_string(),
        "ACOS" | "ASIN" => "is undefined: the argument must lie between -1 and 1".to_string(),
        _ if !y.is_nan() => format!("overflows: the result is beyond the largest REAL ({MAX_REAL})"),
        _ => "is not a finite REAL".to_string(),
    }
}

/// The result as a finite REAL, or a domain error naming the call and why.
fn finite(name: &str, args: &[f32], x: f64) -> Result<f32, FnError> {
    let r = x as f32;
    if r.is_finite() {
        return Ok(r);
    }
    let list: Vec<String> = args.iter().map(|&a| number(a)).collect();
    let call = format!("{name}({})", list.join(", "));
    let why = if let Some(bad) = args.iter().find(|a| !a.is_finite()) {
        let what = if bad.is_nan() { "not a number" } else { "infinite" };
        format!("is undefined: an argument is {what}")
    } else {
        reason(name, x)
    };
    Err(FnError::Domain(format!("{call} {why}")))
}

/// Applies a one-argument function by name. Names: ACOS, ASIN, COS, DEG,
/// EXP, LN, LOG, RAD, SIN, SQRT, TAN (unknown names are a domain error).
pub fn unary(name: &str, a: f32) -> Result<f32, FnError> {
    let x = f64::from(a);
    let y = match name {
        "ACOS" => x.acos(),
        "ASIN" => x.asin(),
        "COS" => x.cos(),
        "DEG" => x.to_degrees(),
        "EXP" => x.exp(),
        // ln and log10 of 0 are -inf, of a negative number NaN.
        "LN" => x.ln(),
        "LOG" => x.log10(),
        "RAD" => x.to_radians(),
        "SIN" => x.sin(),
        "SQRT" => x.sqrt(),
        "TAN" => x.tan(),
        _ => return Err(FnError::Domain(format!("{name} is not a numeric function"))),
    };
    finite(name, &[a], y)
}

/// ATAN2(A, B): the angle whose tangent is A/B, in (-π, π].
pub fn atan2(a: f32, b: f32) -> Result<f32, FnError> {
    finite("ATAN2", &[a, b], f64::from(a).atan2(f64::from(b)))
}

/// `A ** B`. Defined for A > 0, and for A = 0 with B > 0 (the result is 0);
/// anything else is a domain error saying which rule it breaks, and a
/// result too large for a REAL is one saying that it overflows.
pub fn power(a: f32, b: f32) -> Result<f32, FnError> {
    let err = |why: &str| Err(FnError::Domain(format!("{} ** {} {why}", shown(a), shown(b))));
    if a.is_nan() || b.is_nan() {
        return err("is undefined: an operand is not a number");
    }
    if a == 0.0 && b > 0.0 {
        return Ok(0.0);
    }
    if a == 0.0 {
        return err("is undefined: 0 may only be raised to a power above zero");
    }
    if a < 0.0 {
        return err("is undefined: A must exceed zero (the guide's rule for **)");
    }
    let r = f64::from(a).powf(f64::from(b)) as f32;
    if r.is_finite() {
        Ok(r)
    } else if a.is_infinite() || b.is_infinite() {
        err("is not a finite REAL: an operand is infinite")
    } else {
        err(&format!("overflows: the result is beyond the largest REAL ({MAX_REAL})"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f32::consts::PI;

    fn ok(name: &str, a: f32) -> f32 {
        unary(name, a).unwrap_or(f32::NAN)
    }

    #[test]
    fn values() {
        assert_eq!(ok("SQRT", 16.0), 4.0);
        assert_eq!(ok("ACOS", 1.0), 0.0);
        assert!((ok("ASIN", 1.0) - PI / 2.0).abs() < 1e-6);
        assert_eq!(ok("COS", 0.0), 1.0);
        assert!((ok("DEG", PI) - 180.0).abs() < 1e-4);
        assert!((ok("RAD", 180.0) - PI).abs() < 1e-6);
        assert!((ok("EXP", 1.0) - std::f32::consts::E).abs() < 1e-6);
        assert_eq!(ok("LN", 1.0), 0.0);
        assert_eq!(ok("LOG", 1000.0), 3.0);
        assert_eq!(ok("SIN", 0.0), 0.0);
        assert!((ok("TAN", PI / 4.0) - 1.0).abs() < 1e-6);
        assert!((atan2(1.0, 1.0).unwrap_or(0.0) - PI / 4.0).abs() < 1e-6);
        assert!((atan2(1.0, -1.0).unwrap_or(0.0) - 3.0 * PI / 4.0).abs() < 1e-6);
        assert_eq!(atan2(0.0, 0.0), Ok(0.0));
        assert_eq!(ok("SQRT", -0.0), 0.0);
    }

    fn why(r: Result<f32, FnError>) -> String {
        match r {
            Err(FnError::Domain(m)) => m,
            Ok(v) => format!("no error: {v}"),
        }
    }

    #[test]
    fn domain_errors_say_why() {
        for (name, a, message) in [
            ("SQRT", -1.0, "SQRT(-1) is undefined: the argument must not be negative"),
            ("LN", 0.0, "LN(0) is undefined: the argument must exceed zero"),
            ("LN", -1.0, "LN(-1) is undefined: the argument must exceed zero"),
            ("LOG", 0.0, "LOG(0) is undefined: the argument must exceed zero"),
            ("LOG", -5.0, "LOG(-5) is undefined: the argument must exceed zero"),
            ("ACOS", 2.0, "ACOS(2) is undefined: the argument must lie between -1 and 1"),
            ("ASIN", -1.5, "ASIN(-1.5) is undefined: the argument must lie between -1 and 1"),
            ("EXP", 100.0, "EXP(100) overflows: the result is beyond the largest REAL (3.4028235E38)"),
            ("DEG", 3e38, "DEG(3E38) overflows: the result is beyond the largest REAL (3.4028235E38)"),
            ("SIN", f32::INFINITY, "SIN(inf) is undefined: an argument is infinite"),
            ("COS", f32::NAN, "COS(NaN) is undefined: an argument is not a number"),
            ("NOPE", 1.0, "NOPE is not a numeric function"),
        ] {
            assert_eq!(why(unary(name, a)), message, "{name}({a})");
        }
        assert_eq!(why(atan2(f32::NAN, 1.0)), "ATAN2(NaN, 1) is undefined: an argument is not a number");
    }

    #[test]
    fn powers() {
        assert_eq!(power(2.0, 10.0), Ok(1024.0));
        assert_eq!(power(4.0, 0.5), Ok(2.0));
        assert_eq!(power(2.0, -1.0), Ok(0.5));
        assert_eq!(power(0.0, 3.0), Ok(0.0));
        assert_eq!(power(2.0, -1000.0), Ok(0.0), "an underflow is 0, not an error");
    }

    #[test]
    fn power_errors_say_why() {
        let overflow = "overflows: the result is beyond the largest REAL (3.4028235E38)";
        for (a, b, message) in [
            (2.0, 1000.0, format!("2 ** 1000 {overflow}")),
            (10.0, 100.0, format!("10 ** 100 {overflow}")),
            (0.5, -200.0, format!("0.5 ** (-200) {overflow}")),
            (1e30, 2.0, format!("1E30 ** 2 {overflow}")),
            (0.0, 0.0, "0 ** 0 is undefined: 0 may only be raised to a power above zero".into()),
            (0.0, -1.0, "0 ** (-1) is undefined: 0 may only be raised to a power above zero".into()),
            (-2.0, 2.0, "(-2) ** 2 is undefined: A must exceed zero (the guide's rule for **)".into()),
            (-8.0, 1.0 / 3.0, "(-8) ** 0.33333334 is undefined: A must exceed zero (the guide's rule for **)".into()),
            (f32::NAN, 1.0, "NaN ** 1 is undefined: an operand is not a number".into()),
            (2.0, f32::NAN, "2 ** NaN is undefined: an operand is not a number".into()),
            (f32::INFINITY, 2.0, "inf ** 2 is not a finite REAL: an operand is infinite".into()),
        ] {
            assert_eq!(why(power(a, b)), message, "{a} ** {b}");
        }
    }
}
