//! Harness of the conformance suite.
//!
//! A case is a piece of ST, the guide section it covers, and what it should
//! give: the snapshot records the source, the syntax tree and the rendered
//! diagnostics together, and the case also asserts which codes appear, so a
//! changed snapshot can never hide a changed verdict.

use linc_compiler::diag::render::{self, Format, SourceFiles};
use linc_compiler::Context;
use linc_compiler::{st::pretty, Diagnostic};
use linc_runtime::Database;
use std::sync::OnceLock;

/// The database of the guide's examples (`examples/guide/plant.db.json`).
pub fn guide_db() -> &'static Database {
    static DB: OnceLock<Database> = OnceLock::new();
    DB.get_or_init(|| {
        let text = include_str!("../../examples/guide/plant.db.json");
        Database::from_json(text).unwrap_or_else(|e| panic!("guide database: {e}"))
    })
}

/// How a case is checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// An action file against the guide database.
    Action,
    /// An action in a sequence (step variables allowed).
    Sequence,
    /// A transition expression (sequence context).
    Transition,
    /// An action file with no database: only the action's own block type is known.
    NoDb,
}

/// The outcome of one case.
pub struct Outcome {
    pub codes: Vec<&'static str>,
    pub snapshot: String,
}

/// The error codes `linc check` and `linc compile` give for `src` against
/// the guide database: each in its own session, as the CLI runs them.
pub fn check_and_compile(src: &str) -> (Vec<&'static str>, Vec<&'static str>) {
    use linc_compiler::session::{CheckOptions, Session};
    let ctx = Context::of(Some(guide_db()));
    let errors = |d: &[Diagnostic]| d.iter().filter(|d| d.is_error()).map(|d| d.code.as_str()).collect::<Vec<_>>();
    let mut check = Session::new(ctx);
    let id = check.add("case.st", src.as_bytes().to_vec());
    let checked = errors(&check.check(id, CheckOptions::default()).diagnostics);
    let mut compile = Session::compiling(ctx);
    let id = compile.add("case.st", src.as_bytes().to_vec());
    let mut compiled = errors(&compile.check(id, CheckOptions::default()).diagnostics);
    if let Err(lowering) = compile.compile() {
        compiled.extend(errors(&lowering));
    }
    (checked, compiled)
}

/// Asserts that `linc check` rejects exactly what `linc compile` rejects.
pub fn assert_check_agrees_with_compile(src: &str) {
    let (checked, compiled) = check_and_compile(src);
    assert_eq!(checked, compiled, "check and compile disagree on {src:?}");
}

/// Asserts that `linc fmt` leaves `src` (a file named `name`, whose
/// extension gives its language) meaning the same: formatting twice gives
/// the same text, and the object compiled against `db` (or, when it does not
/// compile, the error codes) is the same before and after, except for source
/// positions. A text with syntax errors is not formatted, which is checked
/// too.
pub fn assert_format_preserves(src: &str, name: &str, db: &Database) {
    use linc_compiler::source_kind::SourceKind;
    let kind = SourceKind::of_name(name);
    let Ok(formatted) = linc_compiler::fmt::format(kind, src) else {
        return;
    };
    let again = linc_compiler::fmt::format(kind, &formatted);
    assert_eq!(again.as_deref().ok(), Some(formatted.as_str()), "formatting {name} twice differs; once:\n{formatted}");
    let (before, after) = (compiled(src, name, db), compiled(&formatted, name, db));
    assert_eq!(before, after, "formatting changed the meaning of {name}:\n{src}\n--- formatted:\n{formatted}");
}

/// The object `src` compiles to, without source positions, or its error codes.
pub fn compiled(src: &str, name: &str, db: &Database) -> Result<Vec<u8>, Vec<&'static str>> {
    use linc_compiler::session::{CheckOptions, Session};
    let mut s = Session::compiling(Context::of(Some(db)));
    let id = s.add(name, src.as_bytes().to_vec());
    let mut codes: Vec<&'static str> = s
        .check(id, CheckOptions::default())
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| d.code.as_str())
        .collect();
    match s.compile() {
        Ok(o) if codes.is_empty() => Ok(o.without_positions().to_bytes()),
        Ok(_) => Err(codes),
        Err(e) => {
            codes.extend(e.iter().filter(|d| d.is_error()).map(|d| d.code.as_str()));
            Err(codes)
        }
    }
}

pub fn run(section: &str, src: &str, mode: Mode) -> Outcome {
    // Every case, whatever its mode, is also checked and compiled as an
    // action file against the guide database: the two must agree, and
    // `linc fmt` must not change what it compiles to.
    assert_check_agrees_with_compile(src);
    assert_format_preserves(src, "case.st", guide_db());
    let builtin;
    let (db, resolve_blocks) = if mode == Mode::NoDb {
        builtin = Database::builtin();
        (&builtin, false)
    } else {
        (guide_db(), true)
    };
    let steps: &[String] = &[];
    let steps = matches!(mode, Mode::Sequence | Mode::Transition).then_some(steps);
    let ctx = Context { db, resolve_blocks, steps, steps_known: false, record: None };
    let (tree, diagnostics): (Option<String>, Vec<Diagnostic>) = if mode == Mode::Transition {
        let r = linc_compiler::check_transition(src, ctx);
        (r.tree.map(|e| pretty::expr(&e) + "\n"), r.diagnostics)
    } else {
        let r = linc_compiler::check_source(src, "case", ctx);
        (r.tree.map(|t| pretty::file(&t)), r.diagnostics)
    };
    let mut files = SourceFiles::new();
    let id = files.add("case.st".to_string(), src.to_string());
    let mut snapshot = format!("{section} ({mode:?})\n--- source\n{src}\n--- tree\n");
    snapshot.push_str(tree.as_deref().unwrap_or("(none)\n"));
    snapshot.push_str("--- diagnostics\n");
    if diagnostics.is_empty() {
        snapshot.push_str("(none)\n");
    }
    for d in &diagnostics {
        snapshot.push_str(&render::render(&files, &d.clone().in_file(id), Format::Human));
    }
    Outcome { codes: diagnostics.iter().map(|d| d.code.as_str()).collect(), snapshot }
}

/// A case that must check clean (warnings allowed only when listed).
#[macro_export]
macro_rules! valid {
    ($name:ident, $section:literal, $mode:ident, $src:expr) => {
        #[test]
        fn $name() {
            let o = $crate::run($section, $src, $crate::Mode::$mode);
            insta::assert_snapshot!(stringify!($name), o.snapshot);
            assert!(o.codes.is_empty(), "expected no diagnostics, got {:?}", o.codes);
        }
    };
}

/// A case that must give exactly these codes, in source order.
#[macro_export]
macro_rules! invalid {
    ($name:ident, $section:literal, $mode:ident, $src:expr, [$($code:literal),+ $(,)?]) => {
        #[test]
        fn $name() {
            let o = $crate::run($section, $src, $crate::Mode::$mode);
            insta::assert_snapshot!(stringify!($name), o.snapshot);
            assert_eq!(o.codes, [$($code),+], "diagnostic codes");
        }
    };
}

/// Running compiled ST against a database, for the runtime semantics tests.
pub mod fst;
pub mod gen;

pub mod exec {
    use linc_compiler::st::lower::{self, Lines};
    use linc_compiler::Context;
    use linc_runtime::store::Store;
    use linc_runtime::vm::{Activation, Clock, Vm, DEFAULT_WATCHDOG};
    use linc_runtime::{Database, Program, RuntimeError};

    /// Compiles `src` against `db` into object bytes; panics with the
    /// diagnostics if it does not compile (a test bug, not a finding).
    pub fn compile(src: &str, db: &Database) -> Vec<u8> {
        let ctx = Context::of(Some(db));
        let r = linc_compiler::check_source(src, "test", ctx);
        let program = r.program.unwrap_or_else(|| panic!("does not compile: {:?}", r.diagnostics));
        let obj =
            lower::lower_program(&program, "test.st", &Lines::new(src)).unwrap_or_else(|e| panic!("lowering: {e:?}"));
        obj.to_bytes()
    }

    /// A strategy of the database `db` (JSON) whose action-type blocks all
    /// name actions of the one action file `actions`, its clock at 10^6 s.
    pub fn strategy(db: &str, actions: &str) -> linc_engines::strategy::Strategy {
        let db = Database::from_json(db).unwrap_or_else(|e| panic!("db: {e}"));
        let object = linc_runtime::load(&compile(actions, &db)).expect("loads");
        let store = Store::new(db);
        let wants: Vec<_> = linc_engines::strategy::wanted(&store).into_iter().map(|w| (w, 0)).collect();
        let vm = Vm::new(100_000, Clock::new(1, 0));
        linc_engines::strategy::Strategy::build(store, vec![object], &wants, vm, 1_000_000.0)
            .unwrap_or_else(|e| panic!("build: {e}"))
    }

    /// The outcome of running an action for some cycles.
    pub struct Run {
        pub store: Store,
        pub error: Option<RuntimeError>,
    }

    impl Run {
        /// A field's value as `linc run --show` prints it.
        pub fn get(&self, path: &str) -> String {
            let (b, f) = path.split_once('.').unwrap_or((path, ""));
            let block = self.store.db.block(b).unwrap_or_else(|| panic!("no block {b}"));
            let (field, bit) = f.split_once('.').map(|(f, s)| (f, Some(s))).unwrap_or((f, None));
            let cell = self.store.cell_of(block, field).unwrap_or_else(|| panic!("no field {path}"));
            match bit {
                Some(sub) => {
                    let t = self.store.db.block_template(block);
                    let n = t.fields[t.field(field).unwrap_or(0)].ty.bit_index(sub).unwrap_or(0);
                    match &self.store.cells[cell as usize] {
                        linc_runtime::store::Cell::Bits { v, .. } => ((v >> n) & 1).to_string(),
                        other => format!("{other:?}"),
                    }
                }
                None => self.store.show(cell),
            }
        }

        pub fn code(&self) -> Option<&'static str> {
            self.error.as_ref().map(|e| e.code.as_str())
        }
    }

    /// Runs the first action of `src` for `cycles` cycles of `period` seconds.
    pub fn run_in(db: &Database, src: &str, cycles: u32, period: f64) -> Run {
        let bytes = compile(src, db);
        let verified = linc_runtime::load(&bytes).unwrap_or_else(|e| panic!("load: {e}"));
        let mut store = Store::new(db.clone());
        store.now = 1_000_000.0;
        let program = Program { unit: 0, own: None };
        let linked = verified.link(&store, &[program]).unwrap_or_else(|e| panic!("link: {e}"));
        let mut vm = Vm::new(DEFAULT_WATCHDOG, Clock::new(1, 0));
        let mut act = Activation::new(&linked, 0, 0);
        let mut error = None;
        for _ in 0..cycles {
            match vm.run(&linked, &mut act, &mut store, None) {
                Ok(_) => {}
                Err(e) => {
                    error = Some(e);
                    break;
                }
            }
            store.now += period;
        }
        Run { store, error }
    }

    /// Runs `src` once against the guide database.
    pub fn run(src: &str) -> Run {
        run_in(crate::guide_db(), src, 1, 1.0)
    }
}

/// The tests' deterministic random numbers, shared by every suite.
pub use linc_test_support::rng;
