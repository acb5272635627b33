//! One compile session: the files of one `linc check` or `linc compile`.
//!
//! The session owns the file map, decodes each file's bytes, checks its
//! actions one at a time as the parser reads them (a file is never held as
//! one big tree unless its tree is asked for), finds action names defined
//! twice across all files with one hashed look-up each, counts the limits of
//! the object file across files, and lowers the checked files into one
//! object, naming the right file in every diagnostic. `check` and `compile`
//! run the same checks, so they reject the same files (ADR 0007).

use crate::diag::files::{self, SourceFiles, SUBSTITUTE};
use crate::diag::span::{FileId, Span};
use crate::diag::{Capped, Diagnostic, Omitted, MAX_ERRORS};
use crate::source_kind::{self, SourceKind};
use crate::st::ast;
use crate::st::check::{CheckError, Checker, Context, FastHash, Limits};
use crate::st::errors::LexError;
use crate::st::hir;
use crate::st::lower::{self, Lines, Unit};
use crate::st::parse_support::Item;
use crate::st::parser::{self, ParseErrors};
use linc_format::Code;
use linc_format::ObjectFile;
use std::collections::hash_map::Entry;
use std::collections::HashMap;

/// What a file holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Input {
    /// Actions, with or without `ACTION` headers.
    #[default]
    Actions,
    /// One transition expression, which must be a truth value (§12.11).
    Transition,
    /// One expression of any type (`linc eval`).
    Expression,
}

/// How to check one file.
#[derive(Clone, Copy, Debug, Default)]
pub struct CheckOptions {
    pub input: Input,
    /// Keep the syntax tree, for `--tree` and the conformance snapshots.
    pub tree: bool,
}

/// A syntax tree kept for printing.
#[derive(Debug)]
pub enum Tree {
    Actions(ast::SourceFile),
    Expr(ast::Expr),
}

impl Tree {
    /// The S-expression view of [`crate::st::pretty`].
    pub fn pretty(&self) -> String {
        match self {
            Tree::Actions(f) => crate::st::pretty::file(f),
            Tree::Expr(e) => crate::st::pretty::expr(e) + "\n",
        }
    }
}

/// What checking one file gave.
#[derive(Debug)]
pub struct Checked {
    pub file: FileId,
    /// In source order.
    pub diagnostics: Vec<Diagnostic>,
    /// The tree, if asked for and the parser could build one.
    pub tree: Option<Tree>,
    /// The checked expression of a transition or expression input, when the
    /// file has no errors.
    pub expr: Option<hir::Expr>,
}

impl Checked {
    pub fn has_errors(&self) -> bool {
        self.diagnostics.iter().any(Diagnostic::is_error)
    }
}

/// Errors that only the session can see: across files, or about a file as
/// a whole.
#[derive(Clone, Debug, PartialEq)]
pub enum SessionError {
    DuplicateAction {
        span: Span,
        name: String,
        first: (FileId, Span),
        by_file: bool,
    },
    NotUtf8 {
        span: Span,
        byte: u8,
        more: usize,
    },
    ObjectFile {
        name: String,
    },
    /// Errors over the number kept per file ([`crate::diag::MAX_ERRORS`]).
    Omitted {
        span: Span,
        count: usize,
    },
}

impl SessionError {
    /// E0017 for the first of a file's bytes that were not UTF-8 (from
    /// [`files::decode`]), if any; every front end reports it the same way.
    pub fn not_utf8(invalid: &[(usize, u8)]) -> Option<SessionError> {
        let &(at, byte) = invalid.first()?;
        Some(SessionError::NotUtf8 { span: Span::new(at, at + 1), byte, more: invalid.len() - 1 })
    }

    pub fn to_diagnostic(&self) -> Diagnostic {
        match self {
            SessionError::DuplicateAction { span, name, first, by_file } => {
                let d = Diagnostic::error(Code::E0117, format!("action `{name}` is defined twice"), *span)
                    .label(if *by_file {
                        "this file has no ACTION header, so its action is named after the file"
                    } else {
                        "second definition"
                    })
                    .with_in(first.0, first.1, "first defined here")
                    .help("action names ignore case, and are unique among the files compiled together");
                if *by_file {
                    d.help("rename one of the files, or give the actions ACTION headers with different names")
                } else {
                    d
                }
            }
            SessionError::NotUtf8 { span, byte, more } => {
                let d = Diagnostic::error(Code::E0017, format!("byte 0x{byte:02X} is not UTF-8"), *span)
                    .label("not valid UTF-8")
                    .help("linc reads source files as UTF-8; save the file as UTF-8 (in Latin-1, a degree sign is the byte 0xB0)");
                if *more > 0 {
                    d.help(format!(
                        "{more} more byte{} in this file {} not UTF-8",
                        plural(*more),
                        if *more == 1 { "is" } else { "are" }
                    ))
                } else {
                    d
                }
            }
            SessionError::Omitted { span, count } => Diagnostic::error(
                Code::E0023,
                format!("{count} more error{} in this file not shown", plural(*count)),
                *span,
            )
            .label("the first of them")
            .help(format!("linc keeps at most {MAX_ERRORS} errors of each kind per file; fix these and check again")),
            SessionError::ObjectFile { name } => Diagnostic::error(
                Code::E0018,
                format!("`{name}` is a linc object file, not ST source"),
                Span::default(),
            )
            .label("compiled object")
            .help(format!("to list its instructions, run `linc disasm {name}`; to run it, `linc run {name} --db DB`")),
        }
    }
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// The files of one run and what is known across them.
pub struct Session<'a> {
    ctx: Context<'a>,
    files: SourceFiles,
    /// Each file's kind ([`SourceKind`]), by file id.
    kinds: Vec<SourceKind>,
    /// The object of a sequence or FST table, made when it was checked.
    alone: Option<ObjectFile>,
    /// Action names seen so far, in upper case, with where each was first defined.
    actions: HashMap<String, (FileId, Span), FastHash>,
    limits: Option<Limits>,
    /// Checked programs kept whole (only in a [`Session::keeping`]).
    programs: Option<Vec<(FileId, hir::Program)>>,
    /// The object being lowered as files are checked (only when compiling).
    stream: Option<lower::Stream>,
    failed: bool,
}

impl<'a> Session<'a> {
    /// A session that checks only.
    pub fn new(ctx: Context<'a>) -> Session<'a> {
        Session {
            ctx,
            files: SourceFiles::new(),
            kinds: Vec::new(),
            alone: None,
            actions: HashMap::default(),
            limits: Some(Limits::default()),
            programs: None,
            stream: None,
            failed: false,
        }
    }

    /// A session that lowers what it checks as it goes, to
    /// [`Session::compile`] it; checked programs are not kept.
    pub fn compiling(ctx: Context<'a>) -> Session<'a> {
        Session { stream: Some(lower::Stream::default()), ..Session::new(ctx) }
    }

    /// A session that keeps each file's checked program whole, for
    /// [`Session::take_program`] (the API's one-file helpers) and
    /// [`Session::compile`].
    pub fn keeping(ctx: Context<'a>) -> Session<'a> {
        Session { programs: Some(Vec::new()), ..Session::new(ctx) }
    }

    /// The files, for rendering diagnostics.
    pub fn files(&self) -> &SourceFiles {
        &self.files
    }

    /// The files, given up when the session is done, for the problems
    /// that point into them.
    pub fn into_files(self) -> SourceFiles {
        self.files
    }

    /// True once any file had an error.
    pub fn has_errors(&self) -> bool {
        self.failed
    }

    /// Adds a file from its bytes. An object file is kept without its text;
    /// bytes that are not UTF-8 are replaced one for one and reported when
    /// the file is checked.
    pub fn add(&mut self, name: impl Into<String>, bytes: Vec<u8>) -> FileId {
        let name = name.into();
        let kind = SourceKind::of(&name, &bytes);
        let (text, invalid) =
            if kind == SourceKind::Object { (String::new(), Vec::new()) } else { files::decode(bytes) };
        self.kinds.push(kind);
        self.files.add_decoded(name, text, invalid)
    }

    /// The kind of a file added to the session.
    pub fn kind(&self, file: FileId) -> SourceKind {
        self.kinds.get(file.index()).copied().unwrap_or(SourceKind::Actions)
    }

    /// Checks a sequence or an FST table: each is a unit of its own, read
    /// once by its front end; a compiling session keeps the object it made.
    fn check_alone(&mut self, file: FileId, kind: SourceKind) -> Checked {
        let mut checked = Checked { file, diagnostics: Vec::new(), tree: None, expr: None };
        let Some(source) = self.files.file(file) else { return checked };
        let not_utf8 = SessionError::not_utf8(source.invalid_bytes()).map(|e| e.to_diagnostic().in_file(file));
        checked.diagnostics.extend(not_utf8);
        if checked.diagnostics.is_empty() {
            let lower = self.stream.is_some() || self.programs.is_some();
            let (found, object) = source_kind::read_alone(kind, (source.name(), source.text()), self.ctx, lower);
            checked.diagnostics.extend(found.into_iter().map(|d| d.in_file(file)));
            self.alone = object;
        }
        self.failed |= checked.has_errors();
        checked
    }

    /// The object of the session's one sequence or FST table, made when it
    /// was checked.
    fn compile_alone(&mut self, file: FileId, kind: SourceKind) -> Result<ObjectFile, Vec<Diagnostic>> {
        let name = self.files.file(file).map(|f| f.name().to_string()).unwrap_or_default();
        if self.kinds.len() > 1 {
            return Err(vec![source_kind::not_alone(kind, &name)]);
        }
        if self.failed {
            return Err(Vec::new());
        }
        self.alone.take().ok_or_else(|| {
            // Clean but not lowered: a table checked without its points.
            let no_points = kind == SourceKind::FstTable && !self.ctx.resolve_blocks;
            if no_points {
                vec![source_kind::needs_points(&name)]
            } else {
                Vec::new()
            }
        })
    }

    /// Checks one file.
    pub fn check(&mut self, file: FileId, options: CheckOptions) -> Checked {
        let mut checked = Checked { file, diagnostics: Vec::new(), tree: None, expr: None };
        let kind = self.kind(file);
        if kind.stands_alone() {
            return self.check_alone(file, kind);
        }
        let Some(source) = self.files.file(file) else { return checked };
        if kind == SourceKind::Object {
            let name = source.name().to_string();
            checked.diagnostics.push(SessionError::ObjectFile { name }.to_diagnostic().in_file(file));
            self.failed = true;
            return checked;
        }
        let mut session_errors = Capped::default();
        if let Some(e) = SessionError::not_utf8(source.invalid_bytes()) {
            session_errors.push(e);
        }
        let mut checker = Checker::new(self.ctx, self.limits.take().unwrap_or_default());
        if self.programs.is_none() && self.stream.is_none() {
            checker = checker.reporting_only();
        }
        if let Some(stream) = &mut self.stream {
            stream.begin_file(file.index(), source.name(), Lines::new(source.text()));
        }
        let mut ladder_errors = Vec::new();
        let (parse_errors, program) = match options.input {
            Input::Actions if crate::ladder::is_ladder(source.name()) => {
                let mut names = Names { map: &mut self.actions, file, errors: &mut session_errors };
                let sink = Sink { keep: self.programs.is_some(), stream: self.stream.as_mut() };
                let (program, tree, errors) =
                    check_ladder(source, self.ctx, &mut checker, &mut names, sink, options.tree);
                checked.tree = tree.map(Tree::Actions);
                ladder_errors = errors;
                (ParseErrors::default(), Some(program))
            }
            Input::Actions => {
                let mut names = Names { map: &mut self.actions, file, errors: &mut session_errors };
                let keep = self.programs.is_some();
                let sink = Sink { keep, stream: self.stream.as_mut() };
                let (errors, program, tree) = check_actions(source, &mut checker, &mut names, sink, options.tree);
                checked.tree = tree.map(Tree::Actions);
                (errors, Some(program))
            }
            Input::Transition | Input::Expression => {
                let (expr, errors) = parser::parse_expr(source.text());
                if let Some(e) = &expr {
                    checked.expr = Some(if options.input == Input::Transition {
                        checker.transition(e)
                    } else {
                        checker.expression(e)
                    });
                }
                checked.tree = expr.filter(|_| options.tree).map(Tree::Expr);
                (errors, None)
            }
        };
        let check_errors = checker.take_errors();
        let mut omitted = checker.omitted();
        self.limits = Some(checker.into_limits());
        let (session_errors, n, first) = session_errors.into_parts();
        omitted.add(n, first.map(|e| e.to_diagnostic().span));
        checked.diagnostics = collect(source, parse_errors, &check_errors, &session_errors, omitted, file);
        if !ladder_errors.is_empty() {
            checked.diagnostics.extend(ladder_errors.into_iter().map(|d| d.in_file(file)));
            checked.diagnostics.sort_by_key(|d| (d.span.start, d.span.end));
        }
        if checked.has_errors() {
            self.failed = true;
            checked.expr = None;
        } else if let (Some(programs), Some(p)) = (&mut self.programs, program) {
            programs.push((file, p));
        }
        checked
    }

    /// Takes the checked program of `file` (for the API's one-file helpers).
    pub fn take_program(&mut self, file: FileId) -> Option<hir::Program> {
        let programs = self.programs.as_mut()?;
        let i = programs.iter().position(|p| p.0 == file)?;
        Some(programs.remove(i).1)
    }

    /// Lowers every checked file into one object. `Err` holds the lowering
    /// errors, each in its own file; it is empty when a file already had
    /// errors (they were reported when it was checked) or nothing was kept.
    /// The programs are handed over: a second call gives an empty `Err`.
    pub fn compile(&mut self) -> Result<ObjectFile, Vec<Diagnostic>> {
        if let Some(i) = self.kinds.iter().position(|k| k.stands_alone()) {
            return self.compile_alone(FileId(i as u32), self.kinds[i]);
        }
        if let Some(stream) = self.stream.take() {
            if self.failed {
                return Err(Vec::new());
            }
            let in_file = |(i, e): (usize, lower::LowerError)| e.to_diagnostic().in_file(FileId(i as u32));
            return stream.finish().map_err(|errors| errors.into_iter().map(in_file).collect());
        }
        let Some(programs) = self.programs.take().filter(|_| !self.failed) else {
            return Err(Vec::new());
        };
        let names: Vec<(&str, Lines)> = programs
            .iter()
            .map(|(id, _)| {
                let f = self.files.file(*id);
                (f.map(|f| f.name()).unwrap_or(""), Lines::new(f.map(|f| f.text()).unwrap_or("")))
            })
            .collect();
        let units: Vec<Unit> =
            programs.iter().zip(&names).map(|((_, program), (file, lines))| Unit { program, file, lines }).collect();
        lower::lower_units(&units)
            .map_err(|errors| errors.into_iter().map(|(unit, e)| e.to_diagnostic().in_file(programs[unit].0)).collect())
    }
}

/// Action names across the files of a session.
struct Names<'n> {
    map: &'n mut HashMap<String, (FileId, Span), FastHash>,
    file: FileId,
    errors: &'n mut Capped<SessionError>,
}

impl Names<'_> {
    /// Records an action's name, reporting it if it is taken (one hashed
    /// look-up, whatever the number of actions).
    fn define(&mut self, name: &ast::Ident, by_file: bool) {
        match self.map.entry(name.text.as_str().to_ascii_uppercase()) {
            Entry::Occupied(e) => self.errors.push(SessionError::DuplicateAction {
                span: name.span,
                name: name.text.to_string(),
                first: *e.get(),
                by_file,
            }),
            Entry::Vacant(e) => {
                e.insert((self.file, name.span));
            }
        }
    }
}

/// Where checked actions go: kept whole, lowered at once, or both.
struct Sink<'s> {
    keep: bool,
    stream: Option<&'s mut lower::Stream>,
}

/// Parses and checks an action file, one statement or action at a time as
/// the parser reads them. The statements of a file without headers are
/// checked as they come, as one action named after the file. Returns the
/// parse errors, the checked program (empty unless `keep`) and the tree (if
/// `tree` and the parser could build one).
fn check_actions(
    source: &files::SourceFile,
    checker: &mut Checker,
    names: &mut Names,
    mut sink: Sink,
    tree: bool,
) -> (ParseErrors, hir::Program, Option<ast::SourceFile>) {
    let keep = sink.keep;
    let (mut actions, mut trees) = (Vec::new(), Vec::new());
    let (mut body, mut body_tree, mut headers) = (Vec::new(), Vec::new(), 0usize);
    checker.begin_action(None);
    if let Some(stream) = sink.stream.as_deref_mut() {
        stream.begin_statements();
    }
    // What is not kept goes back to be freed where it was parsed.
    let (ok, errors) = parser::parse_actions_giving(source.text(), &mut |item| match item {
        Item::Stmt(s) => {
            let h = checker.statement(&s);
            if let Some(stream) = sink.stream.as_deref_mut() {
                stream.statement(&h);
            }
            if keep {
                body.push(h);
            }
            if tree {
                body_tree.push(s);
                return None;
            }
            Some(Item::Stmt(s))
        }
        Item::Action(a) => {
            headers += 1;
            names.define(&a.name, false);
            let h = checker.action(&a);
            if let Some(stream) = sink.stream.as_deref_mut() {
                stream.action(&h);
            }
            if keep {
                actions.push(h);
            }
            if tree {
                trees.push(a);
                return None;
            }
            Some(Item::Action(a))
        }
    });
    // Without headers, the statements read are the file's one action. (With
    // headers, statements outside an action are E0016 and nothing is kept.)
    if headers == 0 {
        let stem = std::path::Path::new(source.name()).file_stem().and_then(|s| s.to_str()).unwrap_or("action");
        let action = parser::headerless(source.text(), stem, body_tree);
        names.define(&action.name, true);
        if let Some(stream) = sink.stream.as_deref_mut() {
            stream.end_statements(&action.name.text);
        }
        if keep {
            actions.push(hir::Action { name: action.name.text.to_string(), block_type: None, body, span: action.span });
        }
        if tree {
            trees.push(action);
        }
    }
    let tree = (tree && ok).then_some(ast::SourceFile { actions: trees });
    (errors, hir::Program { actions }, tree)
}

/// Desugars a ladder file into ST actions (ADR 0009) and checks them like
/// the actions of an ST file, one action at a time. Returns the checked
/// program (empty unless kept), the desugared tree (if `tree`) and the
/// ladder front end's own diagnostics.
fn check_ladder(
    source: &files::SourceFile,
    ctx: Context,
    checker: &mut Checker,
    names: &mut Names,
    mut sink: Sink,
    tree: bool,
) -> (hir::Program, Option<ast::SourceFile>, Vec<Diagnostic>) {
    let stem = std::path::Path::new(source.name()).file_stem().and_then(|s| s.to_str()).unwrap_or("action");
    let (mut actions, mut trees) = (Vec::new(), Vec::new());
    let diagnostics = crate::ladder::desugar_each(source.text(), stem, ctx, &mut |a| {
        names.define(&a.name, a.header.is_none());
        let h = checker.action(&a);
        if let Some(stream) = sink.stream.as_deref_mut() {
            stream.action(&h);
        }
        if sink.keep {
            actions.push(h);
        }
        if tree {
            trees.push(a);
        }
    });
    (hir::Program { actions }, tree.then_some(ast::SourceFile { actions: trees }), diagnostics)
}

/// Every diagnostic of one file, in source order. Lexer errors at bytes
/// that were not UTF-8 are dropped: E0017 already points there.
fn collect(
    source: &files::SourceFile,
    errors: ParseErrors,
    checked: &[CheckError],
    session: &[SessionError],
    mut omitted: Omitted,
    file: FileId,
) -> Vec<Diagnostic> {
    let invalid = source.invalid_bytes();
    let substituted = |e: &LexError| match e {
        LexError::UnexpectedChar { span, ch: SUBSTITUTE } => {
            let n = invalid.partition_point(|p| p.0 < span.end) - invalid.partition_point(|p| p.0 < span.start);
            n == span.end - span.start
        }
        _ => false,
    };
    omitted.add(errors.omitted.count, errors.omitted.first);
    let mut out: Vec<Diagnostic> = errors.lex.iter().filter(|e| !substituted(e)).map(LexError::to_diagnostic).collect();
    out.extend(errors.syntax.iter().map(crate::st::errors::SyntaxError::to_diagnostic));
    out.extend(checked.iter().map(CheckError::to_diagnostic));
    out.extend(session.iter().map(SessionError::to_diagnostic));
    if let (n @ 1.., Some(first)) = (omitted.count, omitted.first) {
        out.push(SessionError::Omitted { span: first, count: n }.to_diagnostic());
    }
    for d in &mut out {
        d.file = file;
    }
    out.sort_by_key(|d| (d.span.start, d.span.end));
    out
}
