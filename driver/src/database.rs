//! The database a command runs against: loaded with located errors,
//! changed by `--set`, read by `--show`, written back by `--out`; and the
//! clock options every run shares (`--now`, `--for`).

use crate::report::usage;
use crate::Reporter;
use linc_compiler::diag::render::SourceFiles;
use linc_compiler::Diagnostic;
use linc_engines::console::fields::{address, set, Addr};
use linc_format::Code;
use linc_runtime::{text, Database, Store};
use std::path::Path;

/// Loads a database (`--db`, a strategy), reporting its errors located in
/// the file. `Err` carries the exit status.
pub fn load(path: Option<&Path>, files: &mut SourceFiles, r: &mut Reporter) -> Result<Option<Database>, u8> {
    let Some(path) = path else { return Ok(None) };
    let text = crate::files::read_input_text(path).map_err(|e| {
        r.unreadable(path, &e);
        2u8
    })?;
    // A byte order mark is ignored, as in sources: three spaces keep every
    // offset that of the file.
    let loaded = Database::from_json(&without_bom(&text));
    let id = files.add(path.display().to_string(), text);
    loaded.map(Some).map_err(|e| {
        let span = e.span.map(|(s, e)| linc_compiler::Span::new(s, e)).unwrap_or_default();
        let d = Diagnostic::error(e.code, e.message, span).label("here").in_file(id);
        r.emit(files, &d);
        2u8
    })
}

/// The text with a leading byte order mark replaced by three spaces (JSON
/// white space of the same length, so offsets stay those of the file).
pub(crate) fn without_bom(text: &str) -> std::borrow::Cow<'_, str> {
    match text.strip_prefix('\u{feff}') {
        Some(rest) => format!("   {rest}").into(),
        None => text.into(),
    }
}

/// Applies every `--set` and resolves every `--show` (reporting the first
/// problem, E0903; `Err` is the exit status).
pub fn set_and_show(
    store: &mut Store,
    sets: &[String],
    shows: &[String],
    r: &mut Reporter,
) -> Result<Vec<(String, Addr)>, u8> {
    for s in sets {
        set(store, s).map_err(|msg| usage(r, format_args!("--set {s}: {msg}")))?;
    }
    let mut out = Vec::with_capacity(shows.len());
    for p in shows {
        let a = address(store, p).map_err(|msg| usage(r, format_args!("--show {p}: {msg}")))?;
        out.push((p.clone(), a));
    }
    Ok(out)
}

/// The clock's start in POSIX seconds: `--now`, or the system time.
pub fn start_time(now: Option<&str>) -> Result<i64, String> {
    match now {
        Some(t) => text::parse_timestamp(t)
            .ok_or_else(|| format!("--now `{t}` is not a real date and time YYYY-MM-DDTHH:MM:SS")),
        None => Ok(std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_secs() as i64)
            .unwrap_or(0)),
    }
}

/// A duration as an ST time constant, with or without `T#` (`10m`, `T#1h30m`).
pub fn duration(text: &str) -> Result<u64, String> {
    let secs = linc_runtime::db::duration_seconds(text)
        .map_err(|why| format!("--for `{text}` is not a duration like 10m, 1h30m or T#2.5s: {why}"))?;
    if !secs.is_finite() || !(1e-6..=366.0 * 86_400.0).contains(&secs) {
        return Err(format!(
            "--for `{text}`: the duration must be at least the clock's microsecond (1us) and at most 366 days"
        ));
    }
    Ok(linc_engines::strategy::micros(secs))
}

/// Writes the database with the store's values, in the input's JSON shape.
pub fn write_db(out: &std::path::Path, original: &str, store: &Store) -> Result<(), crate::files::Refused> {
    let json_error = |e: serde_json::Error| crate::files::Refused {
        code: Code::E0900,
        message: format!("can't write `{}`: {e}", out.display()),
    };
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
    // points or a table logged something (the loader skips this key).
    let roc = &store.roc;
    if !roc.history.points().is_empty() || !roc.alarms.is_empty() || !roc.events.is_empty() {
        if let Some(obj) = root.as_object_mut() {
            obj.insert("roc".to_string(), roc.to_json());
        }
    }
    let text = serde_json::to_string_pretty(&root).map_err(json_error)? + "\n";
    crate::files::write_atomic(out, text.as_bytes())
}
