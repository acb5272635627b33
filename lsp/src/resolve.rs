//! What the name under the cursor is: the compiler's own resolution
//! (`linc_compiler::names`), the one `linc check` uses — a block, an alias,
//! a field (of a named block, an alias, or the action's own block), a
//! function, a step, an action or a label. Where the parser gave up (a
//! statement being typed), the dotted name under the cursor is resolved by
//! the same function on its own.

use crate::server::{Doc, Lang, Server};
use crate::text::{parts, piece_at, pieces, Kind, Piece};
use crate::workspace::DbFile;
use linc_compiler::names::{self, Names};
use linc_compiler::Context;
use linc_format::Database;

/// A name's meaning: the compiler's.
pub use linc_compiler::names::Meaning as Sym;

/// One request's view of a document and its database.
pub struct Ctx<'a> {
    pub doc: &'a Doc,
    pub file: Option<&'a DbFile>,
    pub pieces: Vec<Piece>,
    /// The file's own declarations, read once per request however often asked.
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

    /// What names are checked against: the database, or without one the
    /// built-in block types with block names unresolved (as `linc check`).
    pub fn context(&self) -> Context<'a> {
        Context::of(self.db())
    }

    /// The database the file's names resolve in (the built-in one without
    /// a database), for what they denote.
    pub fn names_db(&self) -> &'a Database {
        self.context().db
    }

    /// Every name of the file as `linc check` resolves it, kept with the
    /// document until its text or a database changes.
    pub fn resolved(&self) -> &'a Names {
        let doc = self.doc;
        doc.names.get_or_init(|| names::of_source(&doc.text, &doc.lang.file_name(&doc.path), self.context()))
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

    /// The block type of the `ACTION name : TYPE` the offset is in, if any
    /// (a scan of the text: completion asks where nothing parses yet).
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
                return self.names_db().template(&self.doc.text[ty.start..ty.end]);
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

    /// The meaning of the name at `offset`, with its byte range: as the
    /// checker resolved it, or where the parser gave up, the dotted name
    /// under the cursor resolved on its own by the same function.
    pub fn symbol_at(&self, offset: usize) -> Option<(Sym, usize, usize)> {
        if let Some(n) = self.resolved().at(offset) {
            return Some((n.meaning.clone(), n.span.start, n.span.end));
        }
        let (word, parts, at) = self.word_at(offset)?;
        if self.covered(word) {
            return None;
        }
        let (s, e) = parts[at];
        if at == 0 && parts.len() == 1 && self.next_char(word.end) == Some('(') {
            let sig = linc_compiler::functions::lookup(self.text((s, e)))?;
            return Some((Sym::Function(sig), s, e));
        }
        let reference = &self.doc.text[parts[0].0..e];
        let own = self.own_type(word.start).map(|t| self.names_db().templates[t].name.clone());
        Some((self.reference(reference, own.as_deref())?, s, e))
    }

    /// Whether the checker saw the word (a name in it resolved): then what
    /// it did not resolve is unknown, not to be guessed.
    fn covered(&self, word: Piece) -> bool {
        self.resolved().iter().any(|n| word.start <= n.span.start && n.span.end <= word.end)
    }

    /// What `reference` (a dotted name) denotes, as the checker would
    /// resolve it in an action of block type `own`.
    pub fn reference(&self, reference: &str, own: Option<&str>) -> Option<Sym> {
        names::of_reference(reference, self.context(), own)
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
