//! Evaluating one ST expression against a database (`linc eval`): checked,
//! lowered, verified, linked and run like any program, its problems
//! reported like any other.

use crate::database::load as load_db;
use crate::Reporter;
use linc_compiler::diag::render::SourceFiles;
use linc_compiler::session::{CheckOptions, Input, Session};
use linc_compiler::st::lower::{self, Lines};
use linc_compiler::Context;
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Vm, DEFAULT_WATCHDOG};
use linc_runtime::Database;
use linc_stdlib::value::decode_dollar;
use std::path::Path;

/// The value of `expr`; `Err` is the exit status (1 after a runtime error,
/// 2 for any other), the problem reported. A STRING comes back decoded, so
/// that its printed constant reads back to the same text.
pub fn evaluate(
    expr: &str,
    db: Option<&Path>,
    now: Option<&str>,
    seed: Option<u64>,
    r: &mut Reporter,
) -> Result<linc_stdlib::Value, u8> {
    let mut dbfiles = SourceFiles::new();
    let db = load_db(db, &mut dbfiles, r)?;
    let mut session = Session::new(Context::of(db.as_ref()));
    let id = session.add("<expr>", expr.as_bytes().to_vec());
    let checked = session.check(id, CheckOptions { input: Input::Expression, tree: false });
    r.emit_all(session.files(), &checked.diagnostics);
    let Some(program) = checked.expr else {
        return Err(2);
    };
    let is_text = program.ty == linc_stdlib::Ty::Text;
    let obj = match lower::lower_eval(&program, &Lines::new(expr)) {
        Ok(o) => o,
        Err(errors) => {
            for e in errors {
                r.emit(session.files(), &e.to_diagnostic().in_file(id));
            }
            return Err(2);
        }
    };
    let now = match crate::database::start_time(now) {
        Ok(s) => s,
        Err(msg) => return Err(crate::report::usage(r, msg)),
    };
    drop(session);
    let mut store = Store::new(db.unwrap_or_else(Database::builtin));
    store.now = now as f64;
    let program = linc_runtime::Program { unit: 0, own: None };
    let result = linc_runtime::verify::verify(obj).and_then(|v| v.link(&store, &[program])).map(|linked| {
        let mut vm = Vm::new(DEFAULT_WATCHDOG, Clock::new(seed.unwrap_or(now as u64), 0));
        let mut act = Activation::new(&linked, 0, 0);
        vm.run(&linked, &mut act, &mut store, None).map(|_| act.result.take())
    });
    match result {
        Ok(Ok(Some(v))) => Ok(match v {
            linc_stdlib::Value::Bytes(b) if is_text => linc_stdlib::Value::Bytes(decode_dollar(&b)),
            v => v,
        }),
        Ok(Ok(None)) => Err(2),
        Ok(Err(e)) => {
            r.runtime_in("<expr>", expr.to_string(), &e);
            Err(1)
        }
        Err(e) => {
            r.whole_file("<expr>", e.code(), e.to_string());
            Err(2)
        }
    }
}
