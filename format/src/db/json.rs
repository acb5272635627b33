//! Loading a database from the JSON contract (`docs/database.md`).
//!
//! Errors carry a code and the byte range of the key or value at fault so
//! that the CLI can render them like any other diagnostic. The loader stops
//! at the first problem.

use super::fields::{field_spec, init_values};
use super::period::{check_period, time_constant};
use super::roc::Device;
use super::schema::{Alias, Block, Database, Task, Template};
use super::tree::{self, get, Json, Member, Node, Span};
use crate::code::Code;
use std::collections::HashSet;
use std::fmt;

/// Every code the loader emits, in one place (the code registry's test
/// reads this file to check that each one is registered).
pub mod code {
    use crate::code::Code;

    pub const NOT_JSON: Code = Code::E0800;
    pub const SHAPE: Code = Code::E0801;
    pub const FIELD_TYPE: Code = Code::E0802;
    pub const UNKNOWN_TEMPLATE: Code = Code::E0803;
    pub const INIT_VALUE: Code = Code::E0804;
    pub const ALIAS_TARGET: Code = Code::E0805;
    pub const TWICE: Code = Code::E0806;
    pub const DUPLICATE_KEY: Code = Code::E0807;
    pub const TASK_NUMBER: Code = Code::E0808;
    pub const TASK_PERIOD: Code = Code::E0809;
    pub const UNDEFINED_TASK: Code = Code::E0810;
    pub const EMPTY_NAME: Code = Code::E0811;
    pub const LONG_NAME: Code = Code::E0812;
    pub const ENUM_TOO_BIG: Code = Code::E0813;
    pub const READONLY: Code = Code::E0814;
    pub const OUT_OF_RANGE: Code = Code::E0815;
    pub const ALIAS_CYCLE: Code = Code::E0816;
    pub const ALIAS_TOO_BIG: Code = Code::E0817;
    pub const DEVICE: Code = Code::E0818;
    pub const TOO_MANY_CELLS: Code = Code::E0819;
    pub const MODBUS_SHAPE: Code = Code::E0850;
    pub const MODBUS_FIELD: Code = Code::E0851;
    pub const MODBUS_TYPE: Code = Code::E0852;
    pub const MODBUS_OVERLAP: Code = Code::E0853;
    pub const USERS: Code = Code::E0854;
    pub const OPCODE_TABLE: Code = Code::E0855;
    pub const FORWARD: Code = Code::E0856;
}

/// Longest name in bytes: the object file stores names with a u16 length.
pub const MAX_NAME: usize = 65_535;

/// Most fields all blocks together may have: each is a cell of the store
/// (about 40 bytes with its flags), so a few hundred kilobytes of blocks of a
/// template with many fields could otherwise declare hundreds of millions.
pub const MAX_CELLS: usize = 1 << 20;

/// Most text all alias expansions together may produce, so that aliases
/// of aliases cannot multiply a small file into an exhausted memory.
const MAX_EXPANDED: usize = 1 << 24;

/// Something wrong with a database file.
#[derive(Clone, Debug, PartialEq)]
pub struct DbError {
    pub code: Code,
    pub message: String,
    /// Byte range in the database text, when it can be located.
    pub span: Option<(usize, usize)>,
}

impl DbError {
    pub(super) fn at(code: Code, message: String, span: Span) -> DbError {
        DbError { code, message, span: Some(span) }
    }
}

impl fmt::Display for DbError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.code, self.message)
    }
}

impl std::error::Error for DbError {}

const BUILTIN: &str = include_str!("builtin.json");

impl Database {
    /// The built-in template library with no blocks.
    pub fn builtin() -> Database {
        let mut db = Database::default();
        // The built-in library is tested to load; an empty library is the
        // only possible fallback and keeps this path free of panics.
        let _ = Loader::new(&mut db).load(BUILTIN);
        db
    }

    /// The built-in library, built once: what a check without a database
    /// resolves block types against.
    pub fn builtin_shared() -> &'static Database {
        static BUILTIN_DB: std::sync::OnceLock<Database> = std::sync::OnceLock::new();
        BUILTIN_DB.get_or_init(Database::builtin)
    }

    /// Loads a database file over the built-in library.
    pub fn from_json(text: &str) -> Result<Database, DbError> {
        let mut db = Database::builtin();
        Loader::new(&mut db).load(text)?;
        Ok(db)
    }

    /// Loads a database file's text as every reader of a file does (the
    /// commands' `--db`, the language server): a leading byte order mark
    /// is read as white space, and the error of one that does not load is
    /// located in the file. One function, so the editor's diagnostics are
    /// `linc check`'s.
    pub fn from_file_text(text: &str) -> Result<Database, DbError> {
        Database::from_json(&without_bom(text))
    }
}

/// The text with a leading byte order mark replaced by three spaces (JSON
/// white space of the same length, so offsets stay those of the file).
pub fn without_bom(text: &str) -> std::borrow::Cow<'_, str> {
    match text.strip_prefix('\u{feff}') {
        Some(rest) => format!("   {rest}").into(),
        None => text.into(),
    }
}

/// The members of an object, or E0801 located at the value.
pub(super) fn object<'n>(node: &'n Node, what: &str) -> Result<&'n [Member], DbError> {
    node.as_object().ok_or_else(|| {
        DbError::at(code::SHAPE, format!("{what} must be a JSON object, not {}", node.kind()), node.span)
    })
}

/// E0801 for a key an object may not have.
fn only_keys(members: &[Member], allowed: &[&str], what: &str) -> Result<(), DbError> {
    match members.iter().find(|m| !allowed.contains(&m.key.as_str())) {
        Some(m) => Err(DbError::at(
            code::SHAPE,
            format!("unknown key `{}` in {what} (expected {})", m.key, allowed.join(", ")),
            m.key_span,
        )),
        None => Ok(()),
    }
}

/// Checks a declared name: not empty (E0811), at most 65,535 bytes (E0812).
pub(super) fn check_name(what: &str, name: &str, span: Span) -> Result<(), DbError> {
    if name.is_empty() {
        return Err(DbError::at(code::EMPTY_NAME, format!("{what} name is empty"), span));
    }
    if name.len() > MAX_NAME {
        let message = format!("{what} name is {} bytes long; names are at most {MAX_NAME} bytes", name.len());
        return Err(DbError::at(code::LONG_NAME, message, span));
    }
    Ok(())
}

struct Loader<'a> {
    db: &'a mut Database,
    /// Templates this file declares (upper case): a file may override a
    /// built-in template, but not declare one twice.
    declared: HashSet<String>,
    /// Fields of the blocks read so far: the cells of a store of them.
    cells: usize,
}

impl<'a> Loader<'a> {
    fn new(db: &'a mut Database) -> Self {
        Loader { db, declared: HashSet::new(), cells: 0 }
    }

    fn load(&mut self, text: &str) -> Result<(), DbError> {
        let root = tree::parse(text)?;
        let members = object(&root, "the database")?;
        // `roc` holds the logs and archives a run wrote with `--out`, which
        // describe a past run, not the database, so loading skips them; only
        // its `forward` links (store and forward) configure the device.
        only_keys(
            members,
            &["device", "templates", "blocks", "aliases", "tasks", "roc", "modbus", "users", "opcode_tables"],
            "the database",
        )?;
        if let Some(m) = get(members, "device") {
            self.device(&m.value)?;
        }
        // Tasks first: blocks name them, wherever the key is in the file.
        if let Some(m) = get(members, "tasks") {
            self.tasks(&m.value)?;
        }
        if let Some(m) = get(members, "templates") {
            for t in object(&m.value, "`templates`")? {
                self.template(t)?;
            }
        }
        if let Some(m) = get(members, "blocks") {
            for b in object(&m.value, "`blocks`")? {
                self.block(b)?;
            }
        }
        if let Some(m) = get(members, "aliases") {
            let aliases = object(&m.value, "`aliases`")?;
            for a in aliases {
                self.alias(a)?;
            }
            self.expand_aliases(aliases)?;
        }
        if let Some(m) = get(members, "users") {
            self.db.users = super::users::load(&m.value)?;
        }
        // The map names blocks and aliases, so it is read after them.
        if let Some(m) = get(members, "modbus") {
            self.db.modbus = Some(super::modbus::load(self.db, &m.value)?);
        }
        if let Some(m) = get(members, "opcode_tables") {
            self.db.opcode_tables = super::roc_device::opcode_tables(self.db, &m.value)?;
        }
        if let Some(m) = get(members, "roc") {
            self.db.roc_forward = super::roc_device::forward(&m.value)?;
        }
        Ok(())
    }

    fn tasks(&mut self, node: &Node) -> Result<(), DbError> {
        for m in object(node, "`tasks`")? {
            let number = match m.key.as_str() {
                "1" => 1,
                "2" => 2,
                "3" => 3,
                "4" => 4,
                _ => {
                    let message = format!("`{}` is not a task number; LIN user tasks are \"1\" to \"4\"", m.key);
                    return Err(DbError::at(code::TASK_NUMBER, message, m.key_span));
                }
            };
            let what = format!("task {number}");
            let spec = object(&m.value, &what)?;
            only_keys(spec, &["period"], &what)?;
            let p = get(spec, "period")
                .ok_or_else(|| DbError::at(code::SHAPE, format!("{what} has no `period`"), m.key_span))?;
            let period = match &p.value.v {
                Json::Str(s) => time_constant(s),
                Json::Num(x) => Ok(*x),
                _ => Err(format!(
                    "expected a time constant such as \"T#100ms\" or a number of seconds, not {}",
                    p.value.kind()
                )),
            }
            .and_then(check_period)
            .map_err(|why| DbError::at(code::TASK_PERIOD, format!("period of {what}: {why}"), p.value.span))?;
            self.db.put_task(Task { number, period });
        }
        Ok(())
    }

    /// `"device": "ROC800"`: the family whose point type numbers TLPs use.
    fn device(&mut self, node: &Node) -> Result<(), DbError> {
        let names = || Device::ALL.map(Device::name).join(", ");
        let name = node.as_str().ok_or_else(|| {
            DbError::at(
                code::SHAPE,
                format!("`device` must be a device family ({}), not {}", names(), node.kind()),
                node.span,
            )
        })?;
        self.db.device = Device::parse(name).ok_or_else(|| {
            DbError::at(code::DEVICE, format!("unknown device family `{name}` (expected {})", names()), node.span)
        })?;
        Ok(())
    }

    /// A template's `"roc": {"ROC800": 96, "FB107": 16}` point type numbers.
    fn roc_types(what: &str, node: &Node) -> Result<Vec<(Device, u16)>, DbError> {
        let mut out = Vec::new();
        for m in object(node, &format!("`roc` of {what}"))? {
            let device = Device::parse(&m.key).ok_or_else(|| {
                let names = Device::ALL.map(Device::name).join(", ");
                DbError::at(code::DEVICE, format!("unknown device family `{}` (expected {names})", m.key), m.key_span)
            })?;
            let t = match m.value.whole(0.0, 65_535.0) {
                Some(x) => x as u16,
                None => {
                    let message = format!("point type of {what} on {} must be a whole number from 0 to 65535", m.key);
                    return Err(DbError::at(code::OUT_OF_RANGE, message, m.value.span));
                }
            };
            out.push((device, t));
        }
        Ok(out)
    }

    fn template(&mut self, m: &Member) -> Result<(), DbError> {
        let name = &m.key;
        check_name("a template", name, m.key_span)?;
        if !self.declared.insert(name.to_ascii_uppercase()) {
            let message = format!("template `{name}` is declared twice in this file (names ignore case)");
            return Err(DbError::at(code::TWICE, message, m.key_span));
        }
        let what = format!("template `{name}`");
        let spec = object(&m.value, &what)?;
        only_keys(spec, &["doc", "fields", "roc"], &what)?;
        let doc =
            match get(spec, "doc") {
                None => String::new(),
                Some(d) => d.value.as_str().map(str::to_string).ok_or_else(|| {
                    DbError::at(code::SHAPE, format!("`doc` of {what} must be a string"), d.value.span)
                })?,
            };
        let mut fields = Vec::new();
        if let Some(fs) = get(spec, "fields") {
            let mut seen = HashSet::new();
            for f in object(&fs.value, &format!("`fields` of {what}"))? {
                check_name("a field", &f.key, f.key_span)?;
                if !seen.insert(f.key.to_ascii_uppercase()) {
                    let message = format!("template `{name}` declares field `{}` twice", f.key);
                    return Err(DbError::at(code::TWICE, message, f.key_span));
                }
                fields.push(field_spec(name, f)?);
            }
        }
        let mut template = Template::new(name.clone(), doc, fields);
        if let Some(r) = get(spec, "roc") {
            template.roc = Self::roc_types(&what, &r.value)?;
        }
        self.db.put_template(template);
        Ok(())
    }

    fn block(&mut self, m: &Member) -> Result<(), DbError> {
        let name = &m.key;
        check_name("a block", name, m.key_span)?;
        let what = format!("block `{name}`");
        let spec = object(&m.value, &what)?;
        only_keys(spec, &["type", "values", "task"], &what)?;
        let ty =
            get(spec, "type").ok_or_else(|| DbError::at(code::SHAPE, format!("{what} has no `type`"), m.key_span))?;
        let tname = ty.value.as_str().ok_or_else(|| {
            DbError::at(code::SHAPE, format!("`type` of {what} must be a template name"), ty.value.span)
        })?;
        let template = self.db.template(tname).ok_or_else(|| {
            DbError::at(code::UNKNOWN_TEMPLATE, format!("block `{name}` has unknown type `{tname}`"), ty.value.span)
        })?;
        let fields = self.db.templates[template].fields.len();
        self.cells += fields;
        if self.cells > MAX_CELLS {
            let message = format!(
                "block `{name}` brings the database to {} fields; a database has at most {MAX_CELLS}",
                self.cells
            );
            return Err(DbError::at(code::TOO_MANY_CELLS, message, m.key_span));
        }
        let task = match get(spec, "task") {
            Some(t) => self.task_of(name, &t.value)?,
            None => Task::DEFAULT.number,
        };
        let values = match get(spec, "values") {
            Some(vs) => init_values(name, &self.db.templates[template], &vs.value)?,
            None => Vec::new(),
        };
        if !self.db.add_block(Block { name: name.clone(), template, values, task }) {
            let message = format!("block `{name}` is declared twice (names ignore case)");
            return Err(DbError::at(code::TWICE, message, m.key_span));
        }
        Ok(())
    }

    /// A block's `"task": N`, which must be a task the database defines.
    fn task_of(&self, block: &str, node: &Node) -> Result<u8, DbError> {
        let number = match node.v {
            Json::Num(x) if [1.0, 2.0, 3.0, 4.0].contains(&x) => x as u8,
            _ => {
                let message = format!("`task` of block `{block}` must be a LIN user task number 1 to 4");
                return Err(DbError::at(code::TASK_NUMBER, message, node.span));
            }
        };
        if self.db.task(number).is_none() {
            let message = format!(
                "block `{block}` runs in task {number}, which `tasks` does not define (only task 1 is implicit)"
            );
            return Err(DbError::at(code::UNDEFINED_TASK, message, node.span));
        }
        Ok(number)
    }

    fn alias(&mut self, m: &Member) -> Result<(), DbError> {
        let name = &m.key;
        check_name("an alias", name, m.key_span)?;
        let t = m.value.as_str().filter(|t| t.split('.').all(|s| !s.is_empty())).ok_or_else(|| {
            let message = format!("alias `{name}` must name a reference like \"BLOCK.FIELD\"");
            DbError::at(code::ALIAS_TARGET, message, m.value.span)
        })?;
        if let Some(b) = self.db.block(name) {
            let message =
                format!("alias `{name}` has the same name as block `{}` (names ignore case)", self.db.blocks[b].name);
            return Err(DbError::at(code::TWICE, message, m.key_span));
        }
        let alias = Alias { name: name.clone(), target: t.split('.').map(str::to_string).collect() };
        if !self.db.add_alias(alias) {
            let message = format!("alias `{name}` is declared twice (names ignore case)");
            return Err(DbError::at(code::TWICE, message, m.key_span));
        }
        Ok(())
    }

    /// Replaces each alias whose target starts with another alias by the
    /// full path, so users of [`Database::alias`] see the final target. A
    /// chain that comes back to itself is E0816. `members` are the file's
    /// aliases, the last `members.len()` of `db.aliases`.
    fn expand_aliases(&mut self, members: &[Member]) -> Result<(), DbError> {
        #[derive(Clone, Copy, PartialEq)]
        enum State {
            Todo,
            Walking,
            Done,
        }
        let base = self.db.aliases.len() - members.len();
        let next_of: Vec<Option<usize>> =
            self.db.aliases.iter().map(|a| self.db.alias_position(&a.target[0])).collect();
        let aliases = &mut self.db.aliases;
        let mut state: Vec<State> =
            (0..aliases.len()).map(|i| if i < base { State::Done } else { State::Todo }).collect();
        let mut budget = MAX_EXPANDED;
        for start in base..aliases.len() {
            // Follow the chain of first parts until a non-alias or an
            // alias already expanded; then expand the chain backwards.
            let mut chain = Vec::new();
            let mut i = start;
            while state[i] == State::Todo {
                state[i] = State::Walking;
                chain.push(i);
                match next_of[i] {
                    Some(next) if state[next] == State::Walking => {
                        let from = chain.iter().position(|&c| c == next).unwrap_or(0);
                        let names: Vec<&str> = chain[from..].iter().map(|&c| aliases[c].name.as_str()).collect();
                        let message = format!("aliases form a cycle: {} -> {}", names.join(" -> "), aliases[next].name);
                        return Err(DbError::at(code::ALIAS_CYCLE, message, members[i - base].value.span));
                    }
                    Some(next) => i = next,
                    None => {
                        state[i] = State::Done;
                        chain.pop();
                    }
                }
            }
            while let Some(k) = chain.pop() {
                let Some(next) = next_of[k] else { continue };
                let expanded: Vec<String> =
                    aliases[next].target.iter().chain(&aliases[k].target[1..]).cloned().collect();
                let size: usize = expanded.iter().map(|p| p.len() + 1).sum();
                budget = budget.checked_sub(size).ok_or_else(|| {
                    let message = format!(
                        "alias `{}` expands to more text than all aliases together may ({MAX_EXPANDED} bytes)",
                        aliases[k].name
                    );
                    DbError::at(code::ALIAS_TOO_BIG, message, members[k - base].value.span)
                })?;
                aliases[k].target = expanded;
                state[k] = State::Done;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::db::FieldType;

    #[test]
    fn builtin_library_loads() {
        let mut db = Database::default();
        let r = Loader::new(&mut db).load(BUILTIN);
        assert_eq!(r, Ok(()));
        for t in ["ACTION", "DIGACT", "SFC_CON", "RAW_COM", "PID", "AN_CONN", "DG_CONN"] {
            assert!(db.template(t).is_some(), "{t}");
        }
        assert_eq!(db.tasks, [Task { number: 1, period: 0.1 }]);
    }

    #[test]
    fn contract_example_loads() {
        let text = r#"{ "templates": { "RECIPE": { "fields": { "A0": "REAL", "N0": "INT", "Flags": "BITS16",
            "Mode": { "ENUM": ["MANUAL", "AUTO"] }, "Alarms": { "ALARMS": ["HighAbs", "LowAbs"] } } } },
            "blocks": { "REC1": { "type": "RECIPE", "values": { "A0": 12.5, "Mode": "AUTO" } } },
            "aliases": { "avg": "REC1.A0" } }"#;
        let db = Database::from_json(text).expect("loads");
        let b = db.block("rec1").expect("block");
        let t = db.block_template(b);
        assert_eq!(
            t.fields.iter().map(|f| f.name.as_str()).collect::<Vec<_>>(),
            ["A0", "N0", "Flags", "Mode", "Alarms"]
        );
        assert_eq!(db.alias("AVG").map(|a| a.target.clone()), Some(vec!["REC1".to_string(), "A0".to_string()]));
    }

    #[test]
    fn errors_are_coded_and_located() {
        let e = Database::from_json("{ \"blocks\": { \"B\": { \"type\": \"NOPE\" } } }").expect_err("fails");
        assert_eq!(e.code, "E0803");
        assert_eq!(e.span, Some((29, 35)));
        let e = Database::from_json("{ \"blocks\": ").expect_err("fails");
        assert_eq!(e.code, "E0800");
        let e = Database::from_json(
            r#"{"templates":{"T":{"fields":{"M":{"ENUM":["A"]}}}},"blocks":{"B":{"type":"T","values":{"M":"Z"}}}}"#,
        )
        .expect_err("fails");
        assert_eq!(e.code, "E0804");
    }

    #[test]
    fn bit_names() {
        let t = FieldType::Bits { width: 8, names: vec!["Run".into()] };
        assert_eq!(t.bit_index("BIT7"), Some(7));
        assert_eq!(t.bit_index("Bit8"), None);
        assert_eq!(t.bit_index("run"), Some(0));
        assert_eq!(t.bit_index("Bitx"), None);
    }
}
