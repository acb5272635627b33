//! Which database a file is checked against. A strategy database (a JSON
//! file with `blocks`) names the files its blocks run (`FileName`); the
//! server finds every such database under the workspace folders and checks
//! a file against the one that names it, as `linc run` would. A workspace
//! may instead name one database in `linc.toml` (`database = "plant.json"`)
//! or the client's initialization options (`{"database": "…"}`). A file no
//! database names is checked without one, as `linc check` does.

use linc_format::input::{read_text, MAX_INPUT_BYTES};
use linc_format::{Database, DbError};
use std::path::{Path, PathBuf};

/// The text of a file on disk, read by the same rules as the commands'
/// inputs (`linc_format::input`): a regular file of at most 256 MiB, read
/// with that bound, so a name that leads to `/dev/zero`, a FIFO or a file
/// that keeps growing costs nothing and hangs nothing. Whatever is refused
/// or unreadable reads as no file.
pub fn read(path: &Path) -> Option<String> {
    read_text(path, MAX_INPUT_BYTES).ok()
}

/// How deep the search for databases goes below a workspace folder.
const MAX_DEPTH: usize = 6;
/// At most this many JSON files are read while searching.
const MAX_JSON_FILES: usize = 2_000;

/// A database file: its text (the editor's, when it is open) and what it
/// loads to.
pub struct DbFile {
    pub path: PathBuf,
    /// `path` with links resolved, to compare with other spellings.
    key: PathBuf,
    pub text: String,
    pub db: Result<Database, DbError>,
    /// The files its blocks name, resolved against its directory, with the
    /// block and the action (`ActName`, empty for a sequence or table).
    pub named: Vec<Named>,
}

#[derive(Clone, Debug)]
pub struct Named {
    pub file: PathBuf,
    key: PathBuf,
    pub block: String,
    pub action: String,
}

impl DbFile {
    pub fn load(path: PathBuf, text: String) -> DbFile {
        let db = Database::from_file_text(&text);
        let named = db.as_ref().map(|db| named_files(&path, db)).unwrap_or_default();
        DbFile { key: key(&path), path, text, db, named }
    }

    pub fn database(&self) -> Option<&Database> {
        self.db.as_ref().ok()
    }

    /// Whether the database's blocks name the file whose [`key`] is `file`.
    fn names(&self, file: &Path) -> bool {
        self.named.iter().any(|n| n.key == file)
    }
}

fn named_files(db_path: &Path, db: &Database) -> Vec<Named> {
    let dir = db_path.parent().unwrap_or(Path::new("."));
    db.programs()
        .into_iter()
        .filter(|w| !w.file.is_empty())
        .map(|w| {
            let file = dir.join(&w.file);
            Named { key: key(&file), file, block: db.blocks[w.block].name.clone(), action: w.action }
        })
        .collect()
}

/// A path with its links resolved (as it is when it does not exist), so
/// that two spellings of one file compare equal. Databases and the files
/// they name get theirs when loaded; a request resolves only its own file.
fn key(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

#[derive(Default)]
pub struct Workspace {
    pub roots: Vec<PathBuf>,
    pub dbs: Vec<DbFile>,
    /// The database named by `linc.toml` or the client, used for every file.
    pub chosen: Option<PathBuf>,
}

impl Workspace {
    /// Finds the databases under `roots`; `chosen` (from the client) wins
    /// over a `linc.toml` in a root.
    pub fn new(roots: Vec<PathBuf>, chosen: Option<PathBuf>) -> Workspace {
        let chosen = chosen.or_else(|| roots.iter().find_map(|r| linc_toml(r)));
        let mut ws = Workspace { roots, dbs: Vec::new(), chosen };
        let mut found = Vec::new();
        for r in &ws.roots {
            search(r, 0, &mut found);
        }
        if let Some(c) = &ws.chosen {
            if !found.iter().any(|f| key(f) == key(c)) {
                found.push(c.clone());
            }
        }
        for path in found {
            if let Some(text) = read(&path) {
                if has_blocks(&text) || ws.chosen.as_ref().is_some_and(|c| key(c) == key(&path)) {
                    ws.dbs.push(DbFile::load(path, text));
                }
            }
        }
        ws
    }

    /// The database `file` is checked against.
    pub fn db_for(&self, file: &Path) -> Option<&DbFile> {
        if let Some(c) = &self.chosen {
            return self.db_at(c);
        }
        let file = key(file);
        self.dbs.iter().find(|d| d.names(&file))
    }

    pub fn db_at(&self, path: &Path) -> Option<&DbFile> {
        let path = key(path);
        self.dbs.iter().find(|d| d.key == path)
    }

    /// A database file's text changed (in the editor); a JSON file that
    /// gains `blocks` becomes a database.
    pub fn update(&mut self, path: &Path, text: &str) -> bool {
        let k = key(path);
        let known = self.dbs.iter().position(|d| d.key == k);
        let is_db = has_blocks(text) || self.chosen.as_ref().is_some_and(|c| key(c) == k);
        match known {
            Some(i) if self.dbs[i].text == text => false,
            Some(i) => {
                self.dbs[i] = DbFile::load(path.to_path_buf(), text.to_string());
                true
            }
            None if is_db => {
                self.dbs.push(DbFile::load(path.to_path_buf(), text.to_string()));
                true
            }
            None => false,
        }
    }

    /// Every file some database names, once.
    pub fn source_files(&self) -> Vec<PathBuf> {
        let mut out: Vec<PathBuf> = Vec::new();
        let mut seen = std::collections::HashSet::new();
        for n in self.dbs.iter().flat_map(|d| &d.named) {
            if seen.insert(&n.key) {
                out.push(n.file.clone());
            }
        }
        out
    }
}

/// A strategy database: a JSON object with a `blocks` member at the top;
/// or a text that names `"blocks"` but is not JSON a database can be (a
/// key twice in an object, a syntax error): a database that does not load,
/// which the editor shows with the error `linc check --db` gives it.
fn has_blocks(text: &str) -> bool {
    text.contains("\"blocks\"")
        && linc_format::db::tree::parse(&linc_format::db::without_bom(text))
            .map_or(true, |n| n.as_object().is_some_and(|m| m.iter().any(|m| m.key == "blocks")))
}

/// What linc reads of a workspace's `linc.toml`.
#[derive(serde::Deserialize)]
struct LincToml {
    /// The database every file is checked against, relative to the root.
    database: Option<String>,
}

/// The most bytes of a `linc.toml` read (it holds a line or two).
const MAX_TOML: u64 = 64 << 10;

/// `database = "…"` in `root/linc.toml`, relative to the root; a file
/// that is not a regular file of at most 64 KiB, or not TOML, names none.
fn linc_toml(root: &Path) -> Option<PathBuf> {
    let text = read_text(&root.join("linc.toml"), MAX_TOML).ok()?;
    let toml: LincToml = toml::from_str(&text).ok()?;
    toml.database.map(|d| root.join(d))
}

fn search(dir: &Path, depth: usize, found: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    let mut entries: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        if found.len() >= MAX_JSON_FILES {
            return;
        }
        let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
        let Ok(meta) = std::fs::symlink_metadata(&p) else { continue };
        if meta.is_dir() {
            if depth < MAX_DEPTH && !name.starts_with('.') && name != "target" && name != "node_modules" {
                search(&p, depth + 1, found);
            }
        } else if meta.is_file() && name.ends_with(".json") && meta.len() < 64 << 20 {
            found.push(p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linc_toml_is_read_as_toml() {
        let root = linc_test_support::fresh_dir("lsp-linc-toml");
        let toml = "# the plant of this folder\ndatabase = 'plant.db.json' # as the guide's\n\n[editor]\nx = 1\n";
        std::fs::write(root.join("linc.toml"), toml).unwrap();
        assert_eq!(linc_toml(&root), Some(root.join("plant.db.json")));
        std::fs::write(root.join("linc.toml"), "database = \"a\\u0062.json\"\n").unwrap();
        assert_eq!(linc_toml(&root), Some(root.join("ab.json")), "escapes are TOML's");
        std::fs::write(root.join("linc.toml"), "database = \n").unwrap();
        assert_eq!(linc_toml(&root), None, "not TOML");
        std::fs::write(root.join("linc.toml"), "x".repeat(MAX_TOML as usize + 1)).unwrap();
        assert_eq!(linc_toml(&root), None, "too large");
    }
}
