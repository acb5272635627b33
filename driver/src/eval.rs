//! Evaluating one ST expression against a database (`linc eval`): checked,
//! lowered, verified, linked and run like any program, its problems
//! returned like any other.

use linc_compiler::diag::Problems;
use linc_compiler::session::{CheckOptions, Input, Session};
use linc_compiler::st::lower::{self, Lines};
use linc_compiler::Context;
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Vm, DEFAULT_WATCHDOG};
use linc_runtime::Database;
use linc_stdlib::value::decode_dollar;
use std::path::Path;

/// A value as `linc eval` prints it: its ST constant.
pub fn text(v: &linc_stdlib::Value) -> String {
    linc_runtime::text::format_value(v)
}

/// The value of `expr` at `now` (POSIX seconds; the system's time without
/// it), with its warnings. A STRING comes back decoded, so that its
/// printed constant reads back to the same text. An expression that does
/// not compile is a refused request; one that faults, an error found.
pub fn evaluate(
    expr: &str,
    db: Option<&Path>,
    now: Option<i64>,
    seed: Option<u64>,
) -> Result<(linc_stdlib::Value, Problems), Problems> {
    let db = crate::database::load_opt(db)?.map(|d| d.db);
    let mut session = Session::new(Context::of(db.as_ref()));
    let id = session.add("<expr>", expr.as_bytes().to_vec());
    let checked = session.check(id, CheckOptions { input: Input::Expression, tree: false });
    let Some(program) = checked.expr else {
        return Err(Problems::of(session.into_files(), checked.diagnostics).refused());
    };
    let is_text = program.ty == linc_stdlib::Ty::Text;
    let obj = match lower::lower_eval(&program, &Lines::new(expr)) {
        Ok(o) => o,
        Err(errors) => {
            let mut all = checked.diagnostics;
            all.extend(errors.iter().map(|e| e.to_diagnostic().in_file(id)));
            return Err(Problems::of(session.into_files(), all).refused());
        }
    };
    let warnings = Problems::of(session.into_files(), checked.diagnostics);
    let now = match now {
        Some(t) => t,
        None => crate::database::start_time(None)?,
    };
    let mut store = Store::new(db.unwrap_or_else(Database::builtin));
    store.now = now as f64;
    let program = linc_runtime::Program { unit: 0, own: None };
    let result = linc_runtime::verify::verify(obj).and_then(|v| v.link(&store, &[program])).map(|linked| {
        let mut vm = Vm::new(DEFAULT_WATCHDOG, Clock::new(seed.unwrap_or(now as u64), 0));
        let mut act = Activation::new(&linked, 0, 0);
        vm.run(&linked, &mut act, &mut store, None).map(|_| act.result.take())
    });
    let mut problems = warnings;
    match result {
        Ok(Ok(Some(v))) => Ok((
            match v {
                linc_stdlib::Value::Bytes(b) if is_text => linc_stdlib::Value::Bytes(decode_dollar(&b)),
                v => v,
            },
            problems,
        )),
        Ok(Ok(None)) => Err(problems.refused()),
        Ok(Err(e)) => {
            problems.append(crate::run::fault_in("<expr>", expr.to_string(), &e));
            Err(problems)
        }
        Err(e) => {
            problems.append(Problems::whole_file("<expr>", e.code(), e.to_string()));
            Err(problems)
        }
    }
}
