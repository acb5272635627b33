//! Names as the checker resolves them: what each block, alias, field,
//! function, step, action and label of a source denotes, by its span.
//!
//! There is one resolution, the checker's (`st/check/resolve.rs`: an alias,
//! a block, a field of the action's own block, a step variable, in that
//! order). A check given a [`Recorder`] in its [`Context`] records each name
//! it resolves; [`of_source`] checks a file so, and adds the names a
//! sequence or a ladder file declares (steps, actions, labels). A language
//! server answers hover, definition, references, completion and rename
//! from these, so it can never disagree with `linc check`.

use crate::diag::Span;
use crate::source_kind::SourceKind;
use crate::st::check::Context;
use linc_stdlib::Signature;
use std::sync::Mutex;

/// What a name denotes.
#[derive(Clone, Debug)]
pub enum Meaning {
    /// A block of the database, by index.
    Block(usize),
    /// An alias of the database, by index.
    Alias(usize),
    /// A field of `template`, of block `block` (`None`: the block that runs
    /// the action, `ACTION a : TYPE`); `sub` is a bit, an alarm or
    /// `Suppress` written after it.
    Field { block: Option<usize>, template: usize, field: usize, sub: Option<String> },
    /// A function of the library (§12.6).
    Function(&'static Signature),
    /// A step of the sequence, as declared.
    Step(String),
    /// An action of the sequence, as declared.
    Action(String),
    /// A rung label of the ladder file, as declared.
    Label(String),
}

impl PartialEq for Meaning {
    fn eq(&self, other: &Meaning) -> bool {
        use Meaning::*;
        match (self, other) {
            (Block(a), Block(b)) | (Alias(a), Alias(b)) => a == b,
            (Field { block, template, field, sub }, Field { block: b, template: t, field: f, sub: s }) => {
                (block, template, field, sub) == (b, t, f, s)
            }
            (Function(a), Function(b)) => a.name == b.name,
            (Step(a), Step(b)) | (Action(a), Action(b)) | (Label(a), Label(b)) => a.eq_ignore_ascii_case(b),
            _ => false,
        }
    }
}

/// A name and where it is.
#[derive(Clone, Debug, PartialEq)]
pub struct Name {
    pub span: Span,
    pub meaning: Meaning,
}

/// Where a check records the names it resolves ([`Context::recording`]).
#[derive(Debug, Default)]
pub struct Recorder(Mutex<Vec<Name>>);

impl Recorder {
    pub(crate) fn push(&self, span: Span, meaning: Meaning) {
        if let Ok(mut names) = self.0.lock() {
            names.push(Name { span, meaning });
        }
    }

    /// The names recorded, in source order, each place once.
    pub fn into_names(self) -> Names {
        let mut list = self.0.into_inner().unwrap_or_else(|e| e.into_inner());
        list.sort_by_key(|n| (n.span.start, n.span.end));
        list.dedup_by(|a, b| a.span == b.span);
        Names(list)
    }
}

/// The names of a source, in source order.
#[derive(Clone, Debug, Default)]
pub struct Names(Vec<Name>);

impl Names {
    /// The name at byte `offset` (a cursor touching its end counts).
    pub fn at(&self, offset: usize) -> Option<&Name> {
        let i = self.0.partition_point(|n| n.span.start <= offset);
        self.0[..i].iter().rev().find(|n| offset <= n.span.end)
    }

    pub fn iter(&self) -> std::slice::Iter<'_, Name> {
        self.0.iter()
    }

    pub fn len(&self) -> usize {
        self.0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// Every name of `src` (named `file_name`, which says its kind) as `linc
/// check` resolves it against `ctx`, and the steps, actions and labels it
/// declares.
pub fn of_source(src: &str, file_name: &str, ctx: Context) -> Names {
    let recorder = Recorder::default();
    let ctx = ctx.recording(&recorder);
    let stem = std::path::Path::new(file_name).file_stem().and_then(|s| s.to_str()).unwrap_or("file");
    match SourceKind::of_name(file_name) {
        SourceKind::Sequence => {
            if let Some(seq) = crate::check_sequence(src, ctx).tree {
                crate::sfc::declared(&seq, &recorder);
            }
        }
        SourceKind::Ladder => {
            crate::check_ladder(src, stem, ctx);
            crate::ladder::declared(src, stem, &recorder);
        }
        SourceKind::Actions => {
            crate::check_source(src, stem, ctx);
        }
        SourceKind::FstTable | SourceKind::Object => {}
    }
    recorder.into_names()
}

/// The meaning of the last part of `reference` (`TANK1`, `TANK1.Level`,
/// `Fill`), resolved as the checker resolves a reference in an action of
/// block type `own_type` (in a sequence when `steps` is given): what
/// completion after `reference.` offers members of.
pub fn of_reference(reference: &str, ctx: Context, own_type: Option<&str>) -> Option<Meaning> {
    let recorder = Recorder::default();
    let ctx = ctx.recording(&recorder);
    let text = match own_type {
        Some(t) => format!("ACTION x : {t}\n{reference} := {reference};\nEND_ACTION\n"),
        None => format!("{reference} := {reference};\n"),
    };
    crate::check_source(&text, "x", ctx);
    let names = recorder.into_names();
    let end = text.find(reference).map(|at| at + reference.len())?;
    names.iter().rev().find(|n| n.span.end <= end).map(|n| n.meaning.clone())
}

#[cfg(test)]
mod tests {
    use super::*;
    use linc_format::Database;

    fn db() -> Database {
        Database::from_json(
            r#"{ "aliases": { "Lvl": "TANK.PV" },
                 "templates": { "TANKT": { "fields": { "PV": "REAL", "Flags": "BITS8" } } },
                 "blocks": { "TANK": { "type": "TANKT" } } }"#,
        )
        .expect("database")
    }

    /// (text, meaning) of every name, in order.
    fn shown(src: &str, names: &Names) -> Vec<(String, Meaning)> {
        names.iter().map(|n| (src[n.span.start..n.span.end].to_string(), n.meaning.clone())).collect()
    }

    #[test]
    fn names_resolve_as_the_checker_resolves_them() {
        let db = db();
        let src = "ACTION a : TANKT\nTANK.Flags.Bit2 := Lvl > ABS(PV);\nNOPE.X := 1;\nEND_ACTION\n";
        let names = of_source(src, "a.stx", Context::of(Some(&db)));
        let abs = crate::functions::lookup("ABS").expect("ABS");
        let t = db.template("TANKT").expect("template");
        let field = |block, field, sub: Option<&str>| Meaning::Field {
            block,
            template: t,
            field,
            sub: sub.map(str::to_string),
        };
        assert_eq!(
            shown(src, &names),
            [
                ("TANK".to_string(), Meaning::Block(0)),
                ("Flags".to_string(), field(Some(0), 1, None)),
                ("Bit2".to_string(), field(Some(0), 1, Some("Bit2"))),
                ("Lvl".to_string(), Meaning::Alias(0)),
                ("ABS".to_string(), Meaning::Function(abs)),
                ("PV".to_string(), field(None, 0, None)),
            ]
        );
        // A cursor on a name, or touching its end; not on an unknown one.
        assert_eq!(names.at(src.find("Lvl").unwrap() + 3).map(|n| &n.meaning), Some(&Meaning::Alias(0)));
        assert!(names.at(src.find("NOPE").unwrap()).is_none());
        // A prefix typed before a `.`, resolved the same way.
        assert_eq!(of_reference("TANK", Context::of(Some(&db)), None), Some(Meaning::Block(0)));
        assert_eq!(of_reference("PV", Context::of(Some(&db)), Some("TANKT")), Some(field(None, 0, None)));
        assert_eq!(of_reference("NOPE", Context::of(Some(&db)), None), None);
    }

    #[test]
    fn a_sequence_names_its_steps_and_actions() {
        let db = db();
        let src = "INITIAL_STEP S1: A(N); END_STEP\nSTEP S2: END_STEP\n\
                   TRANSITION FROM S1 TO S2 := S1.T > 1.0; END_TRANSITION\n\
                   TRANSITION FROM S2 TO S1 := TRUE; END_TRANSITION\n\
                   ACTION A: TANK.PV := 1.0; END_ACTION\n";
        let names = of_source(src, "s.sfc", Context::of(Some(&db)));
        let steps: Vec<String> =
            shown(src, &names).into_iter().filter(|(_, m)| matches!(m, Meaning::Step(_))).map(|(t, _)| t).collect();
        assert_eq!(steps, ["S1", "S2", "S1", "S2", "S1", "S2", "S1"]);
        let actions = names.iter().filter(|n| n.meaning == Meaning::Action("a".into())).count();
        assert_eq!(actions, 2, "the association and the declaration");
    }
}
