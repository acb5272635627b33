//! Generic sequences (guide §9.1): a sequence written with generic names
//! that a map file turns into database names, at block (`Kiln` → `TIC015`),
//! block.field (`TempHiFlag` → `DGOUT_01.Out`) or block.field.subfield
//! level.
//!
//! A map entry behaves like a database alias that exists for this sequence
//! only: [`bind`] returns a copy of the database with one alias per entry,
//! so the ST resolver needs no change and every span stays that of the
//! `.sfc` file. [`specialise`] and [`generalise`] rewrite the text through
//! the map, replacing only the name parts of references so that comments
//! and layout stay.

use super::ast::Sequence;
use super::refs::references;
use crate::diag::span::Span;
use crate::diag::Diagnostic;
use linc_format::db::tree::{self, Json};
use linc_format::db::Alias;
use linc_format::Code;
use linc_format::Database;
use std::collections::HashMap;

/// Generic names are at most this long (guide §9.1).
pub const MAX_GENERIC: usize = 16;

/// A map file: generic name → database name, in file order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Map {
    entries: Vec<Entry>,
    /// Entry by upper-case name: a map is looked up for every reference and
    /// every step, and a search through the entries made that quadratic.
    index: HashMap<String, usize>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    pub name: String,
    pub name_span: Span,
    /// The target split at dots; empty while the entry is not filled in
    /// (as `linc sfc map-template` writes it).
    pub target: Vec<String>,
    pub target_span: Span,
}

impl Map {
    /// The entry called `name` (names ignore case).
    pub fn get(&self, name: &str) -> Option<&Entry> {
        self.index.get(&name.to_ascii_uppercase()).and_then(|&i| self.entries.get(i))
    }

    /// The entries in file order.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    /// Adds an entry; false (and nothing added) if the map has its name.
    pub fn push(&mut self, e: Entry) -> bool {
        match self.index.entry(e.name.to_ascii_uppercase()) {
            std::collections::hash_map::Entry::Occupied(_) => false,
            std::collections::hash_map::Entry::Vacant(v) => {
                v.insert(self.entries.len());
                self.entries.push(e);
                true
            }
        }
    }
}

/// A map with the name of its file, for messages.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Named {
    pub map: Map,
    pub file: String,
}

/// A step with the name of a map entry: `Fill.T` would resolve through the
/// map (an alias comes before a step), so the step's variables could not be
/// read (E0255, at the step).
pub fn step_collisions(seq: &Sequence, map: &Named) -> Vec<Diagnostic> {
    let charts = std::iter::once(&seq.chart).chain(seq.actions.iter().filter_map(|a| match &a.body {
        super::ast::ActionBody::Chart(c) => Some(c),
        super::ast::ActionBody::St(_) => None,
    }));
    charts
        .flat_map(|c| &c.steps)
        .filter(|s| map.map.get(&s.name.text).is_some())
        .map(|s| {
            let name = &s.name.text;
            Diagnostic::error(
                Code::E0255,
                format!("step `{name}` has the name of a generic name of `{}`", map.file),
                s.name.span,
            )
            .label("this step")
            .help(format!("`{name}.X` and `{name}.T` would mean the map's target: rename the step or the map entry"))
        })
        .collect()
}

/// What is wrong with a map file (E0251–E0254, located in the map file).
#[derive(Clone, Debug, PartialEq)]
pub enum MapError {
    /// Not JSON, or not an object whose values are strings.
    Shape { span: Span, message: String },
    /// A target whose block the database does not have.
    UnknownBlock { span: Span, block: String },
    /// A generic name that is not a name, too long, or a database name.
    BadName { span: Span, name: String, why: String },
    /// A target that is not `block[.field[.subfield]]`.
    BadTarget { span: Span, target: String },
}

impl MapError {
    pub fn to_diagnostic(&self) -> Diagnostic {
        match self {
            MapError::Shape { span, message } => Diagnostic::error(Code::E0251, message.clone(), *span)
                .label("here")
                .help(r#"a map is one JSON object of strings: { "KilnController": "TIC015" }"#),
            MapError::UnknownBlock { span, block } => {
                Diagnostic::error(Code::E0252, format!("the database has no block `{block}`"), *span)
                    .label("target of this map entry")
                    .help("a target starts with a block (or alias) of the database given with --db")
            }
            MapError::BadName { span, name, why } => {
                Diagnostic::error(Code::E0253, format!("`{name}` can't be a generic name: {why}"), *span)
                    .label("generic name")
            }
            MapError::BadTarget { span, target } => {
                Diagnostic::error(Code::E0254, format!("`{target}` is not a database name"), *span)
                    .label("target of this map entry")
                    .help("write BLOCK, BLOCK.FIELD or BLOCK.FIELD.SUBFIELD, or \"\" while it is not known")
            }
        }
    }
}

fn is_name(s: &str) -> bool {
    let mut c = s.chars();
    c.next().is_some_and(|f| f.is_ascii_alphabetic() || f == '_') && c.all(|x| x.is_ascii_alphanumeric() || x == '_')
}

/// Reads a map file. Entries with errors are left out; the rest are kept.
pub fn parse_map(text: &str) -> (Map, Vec<MapError>) {
    let mut errors = Vec::new();
    let root = match tree::parse_named(text, "the map file") {
        Ok(n) => n,
        Err(e) => {
            let (s, t) = e.span.unwrap_or((0, 0));
            return (Map::default(), vec![MapError::Shape { span: Span::new(s, t), message: e.message }]);
        }
    };
    let Json::Obj(members) = &root.v else {
        let message = format!("a map must be a JSON object, not {}", root.kind());
        return (Map::default(), vec![MapError::Shape { span: Span::new(root.span.0, root.span.1), message }]);
    };
    let mut map = Map::default();
    for m in members {
        let name_span = Span::new(m.key_span.0, m.key_span.1);
        let target_span = Span::new(m.value.span.0, m.value.span.1);
        let Some(target) = m.value.as_str() else {
            let message = format!("the target of `{}` must be a string, not {}", m.key, m.value.kind());
            errors.push(MapError::Shape { span: target_span, message });
            continue;
        };
        let why = if !is_name(&m.key) {
            Some("a name starts with a letter or `_` and holds letters, digits and `_`".to_string())
        } else if m.key.len() > MAX_GENERIC {
            Some(format!("it is {} characters long; generic names are at most {MAX_GENERIC}", m.key.len()))
        } else if map.get(&m.key).is_some() {
            // JSON keys are unique already (the reader refuses a repeated
            // one); these differ in case only.
            Some("it is in the map twice (names ignore case)".to_string())
        } else {
            None
        };
        if let Some(why) = why {
            errors.push(MapError::BadName { span: name_span, name: m.key.clone(), why });
            continue;
        }
        let parts: Vec<String> =
            if target.is_empty() { Vec::new() } else { target.split('.').map(String::from).collect() };
        if parts.len() > 3 || !parts.iter().all(|p| is_name(p)) {
            errors.push(MapError::BadTarget { span: target_span, target: target.to_string() });
            continue;
        }
        map.push(Entry { name: m.key.clone(), name_span, target: parts, target_span });
    }
    (map, errors)
}

/// A copy of `db` where every filled-in entry of the map is an alias.
/// `resolve_blocks` (a database was given) checks that targets name its
/// blocks and that generic names are not its names.
pub fn bind(map: &Map, db: &Database, resolve_blocks: bool) -> (Database, Vec<MapError>) {
    let mut bound = db.clone();
    let mut errors = Vec::new();
    for e in map.entries() {
        if db.block(&e.name).is_some() || db.alias(&e.name).is_some() {
            let why = "the database already has a block or alias of this name".to_string();
            errors.push(MapError::BadName { span: e.name_span, name: e.name.clone(), why });
            continue;
        }
        let Some(first) = e.target.first() else { continue };
        let mut target = e.target.clone();
        if let Some(a) = db.alias(first) {
            target.splice(0..1, a.target.iter().cloned());
        } else if resolve_blocks && db.block(first).is_none() {
            errors.push(MapError::UnknownBlock { span: e.target_span, block: first.clone() });
            continue;
        }
        bound.add_alias(Alias { name: e.name.clone(), target });
    }
    (bound, errors)
}

/// A sequence's diagnostics as seen with a map: an unknown name (E0100)
/// is a generic name the map lacks, E0250, or W0250 when unmapped names are
/// allowed for now.
pub fn with_map(diagnostics: Vec<Diagnostic>, src: &str, map_file: &str, allow: bool) -> Vec<Diagnostic> {
    diagnostics
        .into_iter()
        .map(|d| {
            if d.code != Code::E0100 {
                return d;
            }
            let name = src.get(d.span.start..d.span.end).unwrap_or("?").to_string();
            unmapped(&d, &name, map_file, allow)
        })
        .collect()
}

/// A generic name may have 16 characters where an ST name has 8 (E0005,
/// which leaves the reference unresolved): for the first name of a
/// reference whose only syntax error that is, the error goes and the
/// reference is resolved (through the map, or it is E0250).
pub fn lift_long_names(seq: &mut Sequence, diagnostics: Vec<Diagnostic>) -> Vec<Diagnostic> {
    let mut lifted = std::collections::HashSet::new();
    // The errors by where they start, so that a reference finds the ones
    // inside it without reading them all (which made this quadratic).
    let mut errors: Vec<&Diagnostic> = diagnostics.iter().filter(|d| d.is_error()).collect();
    errors.sort_by_key(|d| d.span.start);
    super::refs::for_each_mut(seq, &mut |v| {
        let first = &v.segs[0].name;
        let long = first.text.chars().count();
        if !v.malformed || long <= 8 || long > MAX_GENERIC {
            return;
        }
        let from = errors.partition_point(|d| d.span.start < v.span.start);
        let starting = errors[from..].iter().take_while(|d| d.span.start <= v.span.end);
        let mut inside = starting.filter(|d| d.span.end <= v.span.end);
        let only = inside.all(|d| d.code == Code::E0005 && d.span == first.span);
        if only {
            v.malformed = false;
            lifted.insert((first.span.start, first.span.end));
        }
    });
    diagnostics
        .into_iter()
        .filter(|d| !(d.code == Code::E0005 && lifted.contains(&(d.span.start, d.span.end))))
        .collect()
}

/// E0250 or W0250 for an unknown name, keeping a "did you mean" of E0100.
fn unmapped(d: &Diagnostic, name: &str, map_file: &str, allow: bool) -> Diagnostic {
    let message = format!("can't find `{name}` in the database or in the map `{map_file}`");
    let made = if allow {
        Diagnostic::warning(Code::W0250, message, d.span)
    } else {
        Diagnostic::error(Code::E0250, message, d.span)
    };
    let mut made = made.label("a generic name with no target");
    for h in d.help.iter().filter(|h| h.starts_with("did you mean")) {
        made = made.help(h.clone());
    }
    made.help(format!(
        "add it to `{map_file}`, e.g. \"{name}\": \"BLOCK.FIELD\" (or check with --allow-unmapped while the map is incomplete)"
    ))
}

/// Drops E0005 (a name longer than 8 characters) for names of at most 16:
/// in a text being rewritten, such a name may be a generic name.
pub fn allow_long_names(diagnostics: Vec<Diagnostic>, src: &str) -> Vec<Diagnostic> {
    diagnostics
        .into_iter()
        .filter(|d| {
            let len = src.get(d.span.start..d.span.end).map_or(usize::MAX, |n| n.chars().count());
            !(d.code == Code::E0005 && len <= MAX_GENERIC)
        })
        .collect()
}

/// The specific sequence: every generic name the map gives a target is
/// replaced by it. Unmapped names stay as they are.
pub fn specialise(src: &str, seq: &Sequence, map: &Map) -> String {
    let mut edits = Vec::new();
    for v in references(seq) {
        let first = &v.segs[0].name;
        if let Some(e) = map.get(&first.text).filter(|e| !e.target.is_empty()) {
            edits.push((first.span, e.target.join(".")));
        }
    }
    apply(src, edits)
}

/// The generic sequence: every reference that starts with a map entry's
/// target is written with its generic name, the longest target first
/// (`R1.Temp` → `TempPV` before `R1` → `Reactor`). When two entries have
/// the same target, the first in the map wins.
pub fn generalise(src: &str, seq: &Sequence, map: &Map) -> String {
    let mut by_target: HashMap<String, &str> = HashMap::new();
    for e in map.entries().iter().rev().filter(|e| !e.target.is_empty()) {
        by_target.insert(e.target.join(".").to_ascii_uppercase(), &e.name);
    }
    let mut edits = Vec::new();
    for v in references(seq) {
        let most = v.segs.len().min(3);
        for k in (1..=most).rev() {
            if v.segs[..k - 1].iter().any(|s| s.offset.is_some()) {
                continue;
            }
            let path: Vec<&str> = v.segs[..k].iter().map(|s| s.name.text.as_str()).collect();
            if let Some(name) = by_target.get(&path.join(".").to_ascii_uppercase()) {
                edits.push((v.segs[0].name.span.to(v.segs[k - 1].name.span), name.to_string()));
                break;
            }
        }
    }
    apply(src, edits)
}

/// Replaces spans (sorted, not overlapping: each is inside one reference).
fn apply(src: &str, mut edits: Vec<(Span, String)>) -> String {
    edits.sort_by_key(|(s, _)| s.start);
    let mut out = String::with_capacity(src.len());
    let mut at = 0;
    for (span, text) in edits {
        if span.start < at || span.end > src.len() {
            continue;
        }
        out.push_str(&src[at..span.start]);
        out.push_str(&text);
        at = span.end;
    }
    out.push_str(&src[at..]);
    out
}

/// The generic names of a sequence: first names of references that are
/// not a block or alias of `db` nor a step of the sequence, each once (by
/// first use), as written there.
pub fn generic_names(seq: &Sequence, db: &Database) -> Vec<String> {
    let steps = super::steps_of(seq);
    let mut seen = std::collections::HashSet::new();
    let mut out = Vec::new();
    for v in references(seq) {
        let name = &v.segs[0].name.text;
        let known =
            db.block(name).is_some() || db.alias(name).is_some() || steps.contains(name.to_ascii_uppercase().as_str());
        if !known && seen.insert(name.to_ascii_uppercase()) {
            out.push(name.to_string());
        }
    }
    out
}

/// A map with every generic name and an empty target, as JSON text.
pub fn map_template(names: &[String]) -> String {
    if names.is_empty() {
        return "{}\n".to_string();
    }
    let lines: Vec<String> =
        names.iter().map(|n| format!("  {}: \"\"", serde_json::Value::String(n.clone()))).collect();
    format!("{{\n{}\n}}\n", lines.join(",\n"))
}
