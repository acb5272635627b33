//! ABS, FLOAT, ROUND and TRUNC (§12.6, sub-category Convert). FORMAT, SCAN
//! and IS_VALID are in [`super::format`] and [`super::scan`].

use crate::value::round_to_i32;
use crate::Value;

/// ABS: REAL for a REAL argument, else INT. ABS(-2147483648) saturates to
/// 2147483647 (the guide is silent; INT has no +2147483648).
pub fn abs(v: &Value) -> Value {
    match v {
        Value::Real(r) => Value::Real(r.abs()),
        other => Value::Int(other.as_int().saturating_abs()),
    }
}

/// FLOAT: the value as a REAL (nearest f32 for large INTs).
pub fn float(v: &Value) -> Value {
    Value::Real(v.as_real())
}

/// ROUND: nearest INT, halves away from zero, saturating; NaN gives 0.
pub fn round(v: &Value) -> Value {
    match v {
        Value::Real(r) => Value::Int(round_to_i32(*r)),
        other => Value::Int(other.as_int()),
    }
}

/// TRUNC: toward zero, saturating at the INT limits; NaN gives 0.
pub fn trunc(v: &Value) -> Value {
    match v {
        // `as` truncates toward zero and saturates, NaN -> 0.
        Value::Real(r) => Value::Int(*r as i32),
        other => Value::Int(other.as_int()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn abs_keeps_the_kind() {
        assert_eq!(abs(&Value::Int(-5)), Value::Int(5));
        assert_eq!(abs(&Value::Int(i32::MIN)), Value::Int(i32::MAX));
        assert_eq!(abs(&Value::Real(-2.5)), Value::Real(2.5));
        assert_eq!(abs(&Value::Bool(true)), Value::Int(1));
    }

    #[test]
    fn float_round_trunc() {
        assert_eq!(float(&Value::Int(3)), Value::Real(3.0));
        assert_eq!(round(&Value::Real(2.5)), Value::Int(3));
        assert_eq!(round(&Value::Real(-2.5)), Value::Int(-3));
        assert_eq!(round(&Value::Real(-2.4)), Value::Int(-2));
        assert_eq!(round(&Value::Real(1e30)), Value::Int(i32::MAX));
        assert_eq!(round(&Value::Int(7)), Value::Int(7));
        assert_eq!(trunc(&Value::Real(2.9)), Value::Int(2));
        assert_eq!(trunc(&Value::Real(-2.9)), Value::Int(-2));
        assert_eq!(trunc(&Value::Real(-1e30)), Value::Int(i32::MIN));
        assert_eq!(trunc(&Value::Real(f32::NAN)), Value::Int(0));
        assert_eq!(trunc(&Value::Int(-7)), Value::Int(-7));
    }
}
