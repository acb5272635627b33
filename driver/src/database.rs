//! The database a command runs against: loaded with located errors,
//! changed by `--set`, read by `--show`, written back by `--out`; and the
//! clock options every run shares (`--now`, `--for`).

use linc_compiler::diag::{Diagnostic, Problems, SourceFiles, Span};
use linc_engines::console::fields::{address, set, Addr};
use linc_format::Code;
use linc_runtime::{text, Database, Store};
use std::path::Path;

/// A database as read from its file: what it describes, and its text (to
/// locate a problem of what it configures, and to write it back).
#[derive(Clone, Debug)]
pub struct DbFile {
    pub db: Database,
    /// The file's name as given.
    pub name: String,
    pub text: String,
}

impl DbFile {
    /// Problems holding `d`, which points into this file (file 0).
    pub fn problems(&self, d: Diagnostic) -> Problems {
        let mut files = SourceFiles::new();
        files.add(self.name.clone(), self.text.clone());
        Problems::of(files, vec![d])
    }
}

/// Loads a database (`--db`, a strategy), its errors located in the file;
/// a database that does not load is a refused request.
pub fn load(path: &Path) -> Result<DbFile, Problems> {
    let text = crate::files::read_input_text(path).map_err(|e| Problems::unreadable(path, &e))?;
    let name = path.display().to_string();
    // A byte order mark is ignored, as in sources (the language server
    // loads a database by the same function).
    match Database::from_file_text(&text) {
        Ok(db) => Ok(DbFile { db, name, text }),
        Err(e) => {
            let span = e.span.map(|(s, e)| Span::new(s, e)).unwrap_or_default();
            let d = Diagnostic::error(e.code, e.message, span).label("here");
            let file = DbFile { db: Database::default(), name, text };
            Err(file.problems(d).refused())
        }
    }
}

/// [`load`] for an optional `--db`.
pub fn load_opt(path: Option<&Path>) -> Result<Option<DbFile>, Problems> {
    path.map(load).transpose()
}

pub(crate) use linc_format::db::without_bom;

/// Applies every `--set` (the first problem is a refused request, E0903).
pub fn apply_sets(store: &mut Store, sets: &[String]) -> Result<(), Problems> {
    for s in sets {
        set(store, s).map_err(|msg| usage(format!("--set {s}: {msg}")))?;
    }
    Ok(())
}

/// Resolves every `--show` (the first problem is a refused request, E0903).
pub fn shows(store: &Store, shows: &[String]) -> Result<Vec<(String, Addr)>, Problems> {
    shows
        .iter()
        .map(|p| address(store, p).map(|a| (p.clone(), a)).map_err(|m| usage(format!("--show {p}: {m}"))))
        .collect()
}

/// A refused option (E0903).
pub fn usage(message: impl Into<String>) -> Problems {
    Problems::usage(Code::E0903, message)
}

/// `YYYY-MM-DDTHH:MM:SS` (UTC) in POSIX seconds, if it is a real date and
/// time (no 29 February 2023, no 24:00:00).
pub fn timestamp(text: &str) -> Option<i64> {
    text::parse_timestamp(text)
}

/// The clock's start in POSIX seconds: `--now`, or the system time.
pub fn start_time(now: Option<&str>) -> Result<i64, Problems> {
    match now {
        Some(t) => text::parse_timestamp(t)
            .ok_or_else(|| usage(format!("--now `{t}` is not a real date and time YYYY-MM-DDTHH:MM:SS"))),
        None => Ok(std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_secs() as i64)
            .unwrap_or(0)),
    }
}

/// A duration given to the option `flag` (`--for`, `--client-timeout`), as
/// an ST time constant with or without `T#` (`10m`, `T#1h30m`), in
/// microseconds: at least one, at most 366 days.
pub fn duration(flag: &str, text: &str) -> Result<u64, Problems> {
    let secs = linc_runtime::db::duration_seconds(text)
        .map_err(|why| usage(format!("{flag} `{text}` is not a duration like 10m, 1h30m or T#2.5s: {why}")))?;
    if !secs.is_finite() || !(1e-6..=366.0 * 86_400.0).contains(&secs) {
        return Err(usage(format!(
            "{flag} `{text}`: the duration must be at least the clock's microsecond (0.000001s) and at most 366 days"
        )));
    }
    Ok(linc_engines::strategy::micros(secs))
}

/// Writes the database with the store's values, in the input's JSON shape.
pub fn write_db(out: &Path, original: &str, store: &Store) -> Result<(), Problems> {
    let json_error =
        |e: serde_json::Error| Problems::usage(Code::E0900, format!("can't write `{}`: {e}", out.display()));
    let mut root: serde_json::Value = serde_json::from_str(&without_bom(original)).map_err(json_error)?;
    let values = store.values_json();
    if let Some(blocks) = root.get_mut("blocks").and_then(|b| b.as_object_mut()) {
        for (name, block) in blocks.iter_mut() {
            if let (Some(obj), Some(v)) = (block.as_object_mut(), values.get(name)) {
                obj.insert("values".to_string(), v.clone());
            }
        }
    }
    // The ROC device's logs and archives, when the database has history
    // points or a table logged something (the loader skips them), beside
    // the store-and-forward links the input configured (which it reads).
    let roc = &store.roc;
    if !roc.history.points().is_empty() || !roc.alarms.is_empty() || !roc.events.is_empty() {
        let mut state = roc.to_json();
        if let (Some(s), Some(links)) = (state.as_object_mut(), root.get("roc").and_then(|r| r.get("forward"))) {
            s.insert("forward".to_string(), links.clone());
        }
        if let Some(obj) = root.as_object_mut() {
            obj.insert("roc".to_string(), state);
        }
    }
    let text = serde_json::to_string_pretty(&root).map_err(json_error)? + "\n";
    Ok(crate::files::write_atomic(out, text.as_bytes())?)
}
