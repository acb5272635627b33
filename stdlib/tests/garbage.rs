//! Every function index with garbage argument lists: wrong kinds, wrong
//! counts, extreme numbers. Nothing may panic; results keep their promises.

mod common;
use common::TestEnv;
use linc_stdlib::{call, FnError, Returns, Ty, Value, SIGNATURES};
use proptest::prelude::*;

/// Values at the edges of every kind.
fn extremes() -> Vec<Value> {
    vec![
        Value::Int(i32::MIN),
        Value::Int(-1),
        Value::Int(0),
        Value::Int(1),
        Value::Int(3),
        Value::Int(i32::MAX),
        Value::Real(f32::NAN),
        Value::Real(f32::NEG_INFINITY),
        Value::Real(-0.0),
        Value::Real(0.5),
        Value::Real(3e38),
        Value::Bool(true),
        Value::Bytes(Vec::new()),
        Value::Bytes(b"05.2F".to_vec()),
        Value::Bytes(vec![0xFF; 9]),
    ]
}

/// Checks what every successful result must satisfy.
fn check(index: usize, args: &[Value], out: &Result<Value, FnError>) {
    let sig = &SIGNATURES[index];
    let Ok(v) = out else {
        return;
    };
    if let Value::Bytes(bytes) = v {
        let input: usize = args.iter().map(|a| a.as_bytes().len()).sum();
        assert!(bytes.len() <= input + 1020, "{} made {} bytes", sig.name, bytes.len());
    }
    let kind_ok = match sig.returns {
        Returns::Fixed(Ty::Int) => matches!(v, Value::Int(_)),
        Returns::Fixed(Ty::Real) => matches!(v, Value::Real(_)),
        Returns::Fixed(Ty::Bool) => matches!(v, Value::Bool(_)),
        Returns::Fixed(_) | Returns::BytesOrWStr => matches!(v, Value::Bytes(_)),
        Returns::NumericOfArgs | Returns::ScanValue => {
            matches!(v, Value::Int(_) | Value::Real(_))
        }
    };
    assert!(kind_ok, "{}{args:?} returned {v:?}", sig.name);
}

#[test]
fn every_function_with_every_extreme_up_to_three_arguments() {
    let mut env = TestEnv::default();
    let values = extremes();
    let n = values.len();
    for index in 0..SIGNATURES.len() + 2 {
        let mut args = Vec::new();
        let out = call(index, &args, &mut env);
        if index < SIGNATURES.len() {
            check(index, &args, &out);
        } else {
            assert!(out.is_err());
        }
        for a in 0..n * n * n + n * n + n {
            args.clear();
            let mut k = a;
            loop {
                args.push(values[k % n].clone());
                if k < n {
                    break;
                }
                k = k / n - 1;
            }
            let out = call(index, &args, &mut env);
            if index < SIGNATURES.len() {
                check(index, &args, &out);
            }
        }
    }
}

#[test]
fn wrong_counts_are_errors() {
    let mut env = TestEnv::default();
    for (index, sig) in SIGNATURES.iter().enumerate() {
        for count in 0..7 {
            let args = vec![Value::Int(1); count];
            let out = call(index, &args, &mut env);
            if !sig.arity_ok(count) {
                assert!(matches!(out, Err(FnError::Domain(_))), "{} {count}", sig.name);
            }
        }
    }
}

fn any_value() -> impl Strategy<Value = Value> {
    prop_oneof![
        any::<i32>().prop_map(Value::Int),
        prop_oneof![Just(i32::MIN), Just(i32::MAX), -3..1100_i32].prop_map(Value::Int),
        any::<f32>().prop_map(Value::Real),
        any::<bool>().prop_map(Value::Bool),
        proptest::collection::vec(any::<u8>(), 0..24).prop_map(Value::Bytes),
        "[0-9 .+-]{0,4}[IUxXBOFeEGCTDPiuf]{0,3}[.:!*]{0,2}".prop_map(|t| Value::Bytes(t.into_bytes())),
        "[ 0-9A-Fa-f+.:/eE-]{0,14}".prop_map(|t| Value::Bytes(t.into_bytes())),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn random_argument_lists_never_panic(
        index in 0..SIGNATURES.len() + 3,
        args in proptest::collection::vec(any_value(), 0..6),
        random in prop_oneof![0.0..1.0_f64, Just(1.0), Just(-1.0), Just(f64::NAN)],
        clock in prop_oneof![any::<i64>(), -1_000_000_000_i64..5_000_000_000],
    ) {
        let mut env = TestEnv { random, local: clock, system: clock.wrapping_neg() };
        let out = call(index, &args, &mut env);
        if index < SIGNATURES.len() {
            check(index, &args, &out);
        } else {
            prop_assert!(out.is_err());
        }
    }

    #[test]
    fn format_scan_is_valid_never_panic(
        fmt in "[0-9 .]{0,5}[IUxXBOFeEGCTDPiufgtdpc]{0,3}.{0,2}",
        v in prop_oneof![any::<i32>().prop_map(Value::Int), any::<f32>().prop_map(Value::Real)],
        input in "[ 0-9A-Fa-f+.:/eE-]{0,20}",
    ) {
        let mut env = TestEnv::default();
        let idx = |name: &str| SIGNATURES.iter().position(|s| s.name == name).unwrap_or(0);
        let out = call(idx("FORMAT"), &[Value::Bytes(fmt.clone().into_bytes()), v], &mut env);
        prop_assert!(matches!(out, Ok(Value::Bytes(ref b)) if b.len() <= 1020));
        let args = [Value::Bytes(fmt.clone().into_bytes()), Value::Bytes(input.into_bytes())];
        let scanned = call(idx("SCAN"), &args, &mut env);
        // SCAN gives the kind the checker predicts from the format text.
        let ty = SIGNATURES[idx("SCAN")].result(&[], Some(fmt.as_bytes()));
        let kind = match scanned {
            Ok(Value::Real(_)) => Ty::Real,
            Ok(Value::Int(_)) => Ty::Int,
            _ => Ty::Any,
        };
        prop_assert_eq!(kind, ty);
        let valid = call(idx("IS_VALID"), &args, &mut env);
        prop_assert!(matches!(valid, Ok(Value::Bool(_))));
    }
}
