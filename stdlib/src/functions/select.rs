//! RANDOM (§12.6, sub-category Random) and the selectors AVG, MAX, MIN and
//! SWITCH.

use crate::{Env, FnError, Value};

/// RANDOM(A): a REAL uniformly distributed in `[0, A)` from
/// [`Env::random`].
///
/// Decisions: a negative A gives a value in `(A, 0]`, A = 0 gives 0; the
/// product is kept strictly inside the interval after rounding to f32; a
/// generator value outside `[0, 1)` is taken as 0; a non-finite A is a
/// domain error.
pub fn random(a: f32, env: &mut dyn Env) -> Result<f32, FnError> {
    if !a.is_finite() {
        return Err(FnError::Domain(format!("RANDOM({a}) has no finite range")));
    }
    let r = env.random();
    let r = if (0.0..1.0).contains(&r) { r } else { 0.0 };
    let x = (f64::from(a) * r) as f32;
    // For a non-zero f32, the bit pattern minus one is the neighbour nearer
    // to zero.
    let inside = if a != 0.0 && x.abs() >= a.abs() { f32::from_bits(a.to_bits() - 1) } else { x };
    Ok(inside)
}

/// AVG: the arithmetic mean as a REAL (computed in f64). A non-finite mean
/// (only possible with non-finite REAL arguments) is a domain error; no
/// arguments give 0.0.
pub fn avg(args: &[Value]) -> Result<f32, FnError> {
    if args.is_empty() {
        return Ok(0.0);
    }
    let sum: f64 = args
        .iter()
        .map(|v| match v {
            Value::Int(i) => f64::from(*i),
            other => f64::from(other.as_real()),
        })
        .sum();
    let mean = (sum / args.len() as f64) as f32;
    if mean.is_finite() {
        Ok(mean)
    } else {
        Err(FnError::Domain("AVG is not a finite REAL".to_string()))
    }
}

/// MAX (`max` true) or MIN: a REAL if any argument is REAL, else an INT.
/// A NaN argument is ignored unless all arguments are NaN.
pub fn extreme(args: &[Value], max: bool) -> Value {
    if args.iter().any(|v| matches!(v, Value::Real(_))) {
        let pick = if max { f32::max } else { f32::min };
        Value::Real(args.iter().map(Value::as_real).reduce(pick).unwrap_or(0.0))
    } else {
        let ints = args.iter().map(Value::as_int);
        Value::Int(if max { ints.max() } else { ints.min() }.unwrap_or(0))
    }
}

/// SWITCH(A, B, C): A when C = 0, else B; REAL if A or B is REAL.
pub fn switch(a: Option<&Value>, b: Option<&Value>, c: i32) -> Value {
    let real = [a, b].iter().any(|v| matches!(v, Some(Value::Real(_))));
    let chosen = if c == 0 { a } else { b };
    if real {
        Value::Real(chosen.map_or(0.0, Value::as_real))
    } else {
        Value::Int(chosen.map_or(0, Value::as_int))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Fixed(f64);
    impl Env for Fixed {
        fn random(&mut self) -> f64 {
            self.0
        }
        fn local_time(&self) -> i64 {
            0
        }
        fn system_time(&self) -> i64 {
            0
        }
    }

    #[test]
    fn random_stays_in_range() {
        assert_eq!(random(10.0, &mut Fixed(0.25)), Ok(2.5));
        assert_eq!(random(10.0, &mut Fixed(0.0)), Ok(0.0));
        let top = random(1.0, &mut Fixed(0.999_999_999_9)).unwrap_or(1.0);
        assert!((0.0..1.0).contains(&top));
        let neg = random(-1.0, &mut Fixed(0.999_999_999_9)).unwrap_or(-1.0);
        assert!(neg > -1.0 && neg <= 0.0);
        assert_eq!(random(0.0, &mut Fixed(0.5)), Ok(0.0));
        assert_eq!(random(4.0, &mut Fixed(7.0)), Ok(0.0));
        assert_eq!(random(4.0, &mut Fixed(f64::NAN)), Ok(0.0));
        assert!(random(f32::INFINITY, &mut Fixed(0.5)).is_err());
        let tiny = f32::from_bits(1);
        assert_eq!(random(tiny, &mut Fixed(0.9)), Ok(0.0));
    }

    #[test]
    fn selectors() {
        let ints = [Value::Int(3), Value::Int(-7), Value::Int(5)];
        assert_eq!(avg(&ints), Ok(1.0 / 3.0));
        assert_eq!(extreme(&ints, true), Value::Int(5));
        assert_eq!(extreme(&ints, false), Value::Int(-7));
        let mixed = [Value::Int(3), Value::Real(4.5), Value::Bool(true)];
        assert_eq!(extreme(&mixed, true), Value::Real(4.5));
        assert_eq!(extreme(&mixed, false), Value::Real(1.0));
        assert_eq!(avg(&[Value::Int(i32::MAX), Value::Int(i32::MAX)]), Ok(2_147_483_647.0));
        assert!(avg(&[Value::Real(f32::INFINITY), Value::Int(1)]).is_err());
        assert_eq!(avg(&[]), Ok(0.0));
        assert_eq!(extreme(&[], true), Value::Int(0));
        let (a, b) = (Value::Int(1), Value::Real(2.0));
        assert_eq!(switch(Some(&a), Some(&b), 0), Value::Real(1.0));
        assert_eq!(switch(Some(&a), Some(&b), -3), Value::Real(2.0));
        assert_eq!(switch(Some(&a), Some(&Value::Int(9)), 1), Value::Int(9));
        assert_eq!(switch(None, None, 0), Value::Int(0));
    }
}
