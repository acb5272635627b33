//! Helpers shared by the integration tests: call a library function by
//! name, with a fixed environment.

#![allow(dead_code)]

use linc_stdlib::{call, lookup, Env, FnError, Value, SIGNATURES};

/// A deterministic environment.
pub struct TestEnv {
    pub random: f64,
    pub local: i64,
    pub system: i64,
}

impl Default for TestEnv {
    fn default() -> Self {
        TestEnv {
            random: 0.5,
            // 2006-09-23 00:43:06 local, 2006-09-22 23:43:06 UTC.
            local: 1_158_972_186,
            system: 1_158_968_586,
        }
    }
}

impl Env for TestEnv {
    fn random(&mut self) -> f64 {
        self.random
    }
    fn local_time(&self) -> i64 {
        self.local
    }
    fn system_time(&self) -> i64 {
        self.system
    }
}

/// The table index of a function.
pub fn index(name: &str) -> usize {
    let sig = lookup(name).unwrap_or_else(|| panic!("no function {name}"));
    SIGNATURES.iter().position(|s| s.name == sig.name).unwrap_or_else(|| panic!("{name} not in SIGNATURES"))
}

/// Calls `name` with `args` in `env`.
pub fn try_call_in(env: &mut TestEnv, name: &str, args: &[Value]) -> Result<Value, FnError> {
    call(index(name), args, env)
}

/// Calls `name` with `args` in the default environment.
pub fn try_call(name: &str, args: &[Value]) -> Result<Value, FnError> {
    try_call_in(&mut TestEnv::default(), name, args)
}

/// Calls `name`, which must succeed.
pub fn f(name: &str, args: &[Value]) -> Value {
    try_call(name, args).unwrap_or_else(|e| panic!("{name}{args:?} failed: {e:?}"))
}

/// A byte-sequence argument.
pub fn s(text: &str) -> Value {
    Value::Bytes(text.as_bytes().to_vec())
}

/// A raw byte-sequence argument.
pub fn b(bytes: &[u8]) -> Value {
    Value::Bytes(bytes.to_vec())
}

pub fn i(v: i32) -> Value {
    Value::Int(v)
}

pub fn r(v: f32) -> Value {
    Value::Real(v)
}

/// The null sequence.
pub fn null() -> Value {
    Value::Bytes(Vec::new())
}
