//! Harness of the conformance suite.
//!
//! A case is a piece of ST, the guide section it covers, and what it should
//! give: the snapshot records the source, the syntax tree and the rendered
//! diagnostics together, and the case also asserts which codes appear, so a
//! changed snapshot can never hide a changed verdict.

use linc_compiler::check::Context;
use linc_compiler::render::{self, Format, SourceFiles};
use linc_compiler::{pretty, Diagnostic};
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

pub fn run(section: &str, src: &str, mode: Mode) -> Outcome {
    let builtin;
    let (db, resolve_blocks) = if mode == Mode::NoDb {
        builtin = Database::builtin();
        (&builtin, false)
    } else {
        (guide_db(), true)
    };
    let steps: &[String] = &[];
    let steps = matches!(mode, Mode::Sequence | Mode::Transition).then_some(steps);
    let ctx = Context {
        db,
        resolve_blocks,
        steps,
    };
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
        snapshot.push_str(&render::render(&files, id, d, Format::Human));
    }
    Outcome {
        codes: diagnostics.iter().map(|d| d.code).collect(),
        snapshot,
    }
}

/// A case that must check clean (warnings allowed only when listed).
#[macro_export]
macro_rules! valid {
    ($name:ident, $section:literal, $mode:ident, $src:expr) => {
        #[test]
        fn $name() {
            let o = $crate::run($section, $src, $crate::Mode::$mode);
            insta::assert_snapshot!(stringify!($name), o.snapshot);
            assert!(
                o.codes.is_empty(),
                "expected no diagnostics, got {:?}",
                o.codes
            );
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
