//! What the name under the cursor is: a block, a field (of a named block,
//! an alias, or the action's own block), a function, a step, an action or
//! a label. Resolution reads the database and a light scan of the text, so
//! it works in code the parser could not read to the end.

use crate::server::{Doc, Lang, Server};
use crate::text::{parts, piece_at, pieces, Kind, Piece};
use crate::workspace::DbFile;
use linc_runtime::Database;
use linc_stdlib::Signature;

/// A name's meaning.
#[derive(Clone, Debug)]
pub enum Sym {
    Block(usize),
    /// A field of a block (`sub`: a bit, an alarm, `Suppress` after it).
    Field {
        block: Option<usize>,
        template: usize,
        field: usize,
        sub: Option<String>,
    },
    Alias(usize),
    Function(&'static Signature),
    Step(String),
    Action(String),
    Label(String),
}

/// One request's view of a document and its database.
pub struct Ctx<'a> {
    pub doc: &'a Doc,
    pub file: Option<&'a DbFile>,
    pub pieces: Vec<Piece>,
    /// The file's own names, read once per request however often asked.
    names: std::cell::OnceCell<LocalNames>,
}

impl<'a> Ctx<'a> {
    pub fn new(server: &'a Server, doc: &'a Doc) -> Ctx<'a> {
        let file = server.ws.db_for(&doc.path);
        let pieces = if doc.lang == Lang::Fst || doc.lang == Lang::Json { Vec::new() } else { pieces(&doc.text) };
        Ctx { doc, file, pieces, names: std::cell::OnceCell::new() }
    }

    pub fn db(&self) -> Option<&'a Database> {
        self.file.and_then(DbFile::database)
    }

    pub fn text(&self, p: (usize, usize)) -> &'a str {
        &self.doc.text[p.0..p.1]
    }

    /// The word under `offset`, its parts and the part the cursor is on.
    pub fn word_at(&self, offset: usize) -> Option<WordAt> {
        let w = piece_at(&self.pieces, offset).filter(|p| p.kind == Kind::Word)?;
        let (parts, at) = parts(&self.doc.text, w, offset);
        Some((w, parts, at))
    }

    /// The next non-blank character after byte `at`.
    pub fn next_char(&self, at: usize) -> Option<char> {
        self.doc.text[at..].chars().find(|c| !c.is_whitespace())
    }

    /// The block type of the `ACTION name : TYPE` the offset is in, if any.
    pub fn own_type(&self, offset: usize) -> Option<usize> {
        let i = self.pieces.partition_point(|p| p.start < offset);
        let words: Vec<&Piece> = self.pieces[..i].iter().filter(|p| p.kind != Kind::Comment).collect();
        for (k, p) in words.iter().enumerate().rev() {
            let t = &self.doc.text[p.start..p.end];
            if t.eq_ignore_ascii_case("END_ACTION") {
                return None;
            }
            let header = t.eq_ignore_ascii_case("ACTION")
                && !(k > 0 && &self.doc.text[words[k - 1].start..words[k - 1].end] == ":");
            if header {
                let colon = words.get(k + 2).filter(|c| &self.doc.text[c.start..c.end] == ":");
                let ty = colon.and(words.get(k + 3))?;
                return self.db()?.template(&self.doc.text[ty.start..ty.end]);
            }
        }
        None
    }

    /// The steps and actions of a sequence, and the labels of a ladder file.
    pub fn local_names(&self) -> &LocalNames {
        self.names.get_or_init(|| self.read_local_names())
    }

    fn read_local_names(&self) -> LocalNames {
        let mut names = LocalNames::default();
        match self.doc.lang {
            Lang::Sfc => {
                let (seq, _) = linc_compiler::sfc::parser::parse(&self.doc.text);
                collect_chart(&seq.chart, &mut names);
                for a in &seq.actions {
                    names.actions.push((a.name.text.to_string(), a.name.span.start, a.name.span.end));
                    if let linc_compiler::sfc::ast::ActionBody::Chart(c) = &a.body {
                        collect_chart(c, &mut names);
                    }
                }
            }
            Lang::Ladder => {
                let (file, _) = linc_compiler::ladder::parser::parse(&self.doc.text, "file");
                for r in file.actions.iter().flat_map(|a| &a.rungs) {
                    if let Some(l) = &r.label {
                        names.labels.push((l.text.to_string(), l.span.start, l.span.end));
                    }
                }
            }
            _ => {}
        }
        names
    }

    /// The meaning of the part of the word at `offset`, with its byte range.
    pub fn symbol_at(&self, offset: usize) -> Option<(Sym, usize, usize)> {
        let (word, parts, at) = self.word_at(offset)?;
        let text = |i: usize| self.text(parts[i]);
        let (s, e) = parts[at];
        let local = self.local_names();
        if at == 0 {
            let name = text(0);
            let call = self.next_char(word.end) == Some('(');
            let is = |list: &[(String, usize, usize)]| list.iter().any(|n| n.0.eq_ignore_ascii_case(name));
            if is(&local.actions) && (call || parts.len() == 1) {
                return Some((Sym::Action(name.to_string()), s, e));
            }
            // A step is named alone (declarations, transitions) or with `.X`
            // or `.T`; a block of the same name wins, as in the checker.
            let step_use = parts.len() == 1
                || (parts.len() == 2
                    && ["X", "T"].iter().any(|v| text(1).eq_ignore_ascii_case(v))
                    && self.db().is_none_or(|db| db.block(name).is_none()));
            if step_use && is(&local.steps) {
                return Some((Sym::Step(name.to_string()), s, e));
            }
            if is(&local.labels) {
                return Some((Sym::Label(name.to_string()), s, e));
            }
            if call {
                if let Some(sig) = linc_stdlib::lookup(name) {
                    return Some((Sym::Function(sig), s, e));
                }
            }
        }
        let db = self.db()?;
        let first = text(0);
        let (block, template, field_part) = if let Some(b) = db.block(first) {
            if at == 0 {
                return Some((Sym::Block(b), s, e));
            }
            (Some(b), db.blocks[b].template, 1)
        } else if let Some(a) = db.alias(first) {
            let i = db.aliases.iter().position(|x| std::ptr::eq(x, a))?;
            if at == 0 {
                return Some((Sym::Alias(i), s, e));
            }
            let b = db.block(a.target.first()?)?;
            return self.alias_field(db, b, &a.target, &parts[1..], at - 1).map(|sym| (sym, s, e));
        } else {
            let t = self.own_type(word.start)?;
            (None, t, 0)
        };
        let field = db.templates[template].field(text(field_part))?;
        let sub = (at > field_part).then(|| text(at).to_string());
        Some((Sym::Field { block, template, field, sub }, s, e))
    }

    fn alias_field(
        &self,
        db: &Database,
        b: usize,
        target: &[String],
        rest: &[(usize, usize)],
        at: usize,
    ) -> Option<Sym> {
        let template = db.blocks[b].template;
        let field_name = target.get(1).map(String::as_str).or_else(|| rest.first().map(|p| self.text(*p)))?;
        let field = db.templates[template].field(field_name)?;
        let sub = rest.get(at).map(|p| self.text(*p).to_string()).filter(|_| target.len() > 1 || at > 0);
        Some(Sym::Field { block: Some(b), template, field, sub })
    }
}

/// A word, the byte ranges of its dotted parts, and the part at the cursor.
pub type WordAt = (Piece, Vec<(usize, usize)>, usize);

/// Names defined in the file: (name, start, end).
#[derive(Default)]
pub struct LocalNames {
    pub steps: Vec<(String, usize, usize)>,
    pub actions: Vec<(String, usize, usize)>,
    pub transitions: Vec<(String, usize, usize)>,
    pub labels: Vec<(String, usize, usize)>,
}

fn collect_chart(c: &linc_compiler::sfc::ast::Chart, names: &mut LocalNames) {
    for s in &c.steps {
        names.steps.push((s.name.text.to_string(), s.name.span.start, s.name.span.end));
    }
    for t in &c.transitions {
        let span = t.name.as_ref().map_or(t.span, |n| n.span);
        names.transitions.push((t.display_name(), span.start, span.end));
    }
}
