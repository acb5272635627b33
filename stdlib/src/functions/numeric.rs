//! Numeric functions (§12.6, sub-category Numeric) and the `**` operator.
//!
//! REAL is f32. Each function computes in f64 and rounds the result to f32;
//! an argument outside the mathematical domain, or a result that is NaN or
//! infinite as an f32 (EXP(100), DEG(3E38)), is a [`FnError::Domain`].
//! ATAN2(0, 0) is 0, as in C (the guide is silent).

use crate::FnError;

/// The result as a finite REAL, or a domain error naming the call.
fn finite(name: &str, args: &[f32], x: f64) -> Result<f32, FnError> {
    let r = x as f32;
    if r.is_finite() {
        Ok(r)
    } else {
        let shown: Vec<String> = args.iter().map(|a| a.to_string()).collect();
        Err(FnError::Domain(format!("{name}({}) is not a finite REAL", shown.join(", "))))
    }
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
        _ => f64::NAN,
    };
    finite(name, &[a], y)
}

/// ATAN2(A, B): the angle whose tangent is A/B, in (-π, π].
pub fn atan2(a: f32, b: f32) -> Result<f32, FnError> {
    finite("ATAN2", &[a, b], f64::from(a).atan2(f64::from(b)))
}

/// `A ** B`. Defined for A > 0, and for A = 0 with B > 0 (the result is 0);
/// anything else, or a result that is not a finite REAL, is a domain error.
pub fn power(a: f32, b: f32) -> Result<f32, FnError> {
    let domain = || FnError::Domain(format!("{a} ** {b} is undefined"));
    if a == 0.0 && b > 0.0 {
        return Ok(0.0);
    }
    if a.is_nan() || a <= 0.0 {
        return Err(domain());
    }
    let r = f64::from(a).powf(f64::from(b)) as f32;
    if r.is_finite() {
        Ok(r)
    } else {
        Err(FnError::Domain(format!("{a} ** {b} is not a finite REAL")))
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

    #[test]
    fn domain_errors() {
        for (name, a) in [
            ("SQRT", -1.0),
            ("LN", 0.0),
            ("LN", -1.0),
            ("LOG", 0.0),
            ("LOG", -5.0),
            ("ACOS", 2.0),
            ("ASIN", -1.5),
            ("EXP", 100.0),
            ("DEG", 3e38),
            ("SIN", f32::INFINITY),
            ("COS", f32::NAN),
            ("NOPE", 1.0),
        ] {
            assert!(matches!(unary(name, a), Err(FnError::Domain(_))), "{name}({a})");
        }
        assert!(atan2(f32::NAN, 1.0).is_err());
    }

    #[test]
    fn powers() {
        assert_eq!(power(2.0, 10.0), Ok(1024.0));
        assert_eq!(power(4.0, 0.5), Ok(2.0));
        assert_eq!(power(2.0, -1.0), Ok(0.5));
        assert_eq!(power(0.0, 3.0), Ok(0.0));
        assert!(power(0.0, 0.0).is_err());
        assert!(power(0.0, -1.0).is_err());
        assert!(power(-2.0, 2.0).is_err());
        assert!(power(f32::NAN, 1.0).is_err());
        assert!(power(10.0, 100.0).is_err());
        assert!(power(2.0, f32::NAN).is_err());
    }
}
