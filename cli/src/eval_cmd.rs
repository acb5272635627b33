//! `linc eval EXPR`: evaluate one expression and print its value.

use linc_compiler::check::Context;
use linc_compiler::lower::{self, Lines};
use linc_compiler::render::SourceFiles;
use linc_compiler::session::{CheckOptions, Input, Session};
use linc_driver::database::load as load_db;
use linc_driver::Reporter;
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Vm, DEFAULT_WATCHDOG};
use linc_runtime::{text, Database};
use linc_stdlib::value::decode_dollar;
use std::path::Path;

pub fn run(expr: &str, db: Option<&Path>, now: Option<&str>, seed: Option<u64>, r: &mut Reporter) -> u8 {
    let mut dbfiles = SourceFiles::new();
    let db = match load_db(db, &mut dbfiles, r) {
        Ok(db) => db,
        Err(status) => return status,
    };
    let resolve_blocks = db.is_some();
    let db = db.unwrap_or_else(Database::builtin);
    let mut session = Session::new(Context { db: &db, resolve_blocks, steps: None });
    let id = session.add("<expr>", expr.as_bytes().to_vec());
    let checked = session.check(id, CheckOptions { input: Input::Expression, tree: false });
    r.emit_all(session.files(), &checked.diagnostics);
    let Some(program) = checked.expr else {
        return 2;
    };
    let is_text = program.ty == linc_stdlib::Ty::Text;
    let obj = match lower::lower_eval(&program, &Lines::new(expr)) {
        Ok(o) => o,
        Err(errors) => {
            for e in errors {
                r.emit(session.files(), &e.to_diagnostic().in_file(id));
            }
            return 2;
        }
    };
    let now = match linc_driver::database::start_time(now) {
        Ok(s) => s,
        Err(msg) => return crate::report::usage(r, msg),
    };
    let mut store = Store::new(db);
    store.now = now as f64;
    let program = linc_runtime::Program { unit: 0, own: None };
    let result = linc_runtime::verify::verify(obj).and_then(|v| v.link(&store, &[program])).map(|linked| {
        let mut vm = Vm::new(DEFAULT_WATCHDOG, Clock::new(seed.unwrap_or(now as u64), 0));
        let mut act = Activation::new(&linked, 0, 0);
        vm.run(&linked, &mut act, &mut store, None).map(|_| act.result.take())
    });
    match result {
        Ok(Ok(Some(v))) => {
            // A STRING keeps its $-sequences as written; shown, it is decoded
            // so that the printed constant reads back to the same text.
            let v = match v {
                linc_stdlib::Value::Bytes(b) if is_text => linc_stdlib::Value::Bytes(decode_dollar(&b)),
                v => v,
            };
            crate::out::line(&text::format_value(&v));
            0
        }
        Ok(Ok(None)) => 2,
        Ok(Err(e)) => {
            r.runtime_in("<expr>", expr.to_string(), &e);
            1
        }
        Err(e) => {
            r.whole_file("<expr>", e.code(), e.to_string());
            2
        }
    }
}
