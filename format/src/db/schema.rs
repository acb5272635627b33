//! In-memory shape of a database.

use super::names::NameMap;

pub use super::roc::Device;

/// The type of one field of a block template.
#[derive(Clone, Debug, PartialEq)]
pub enum FieldType {
    Real,
    Int,
    Bool,
    /// A bitfield of 8 or 16 bits; `names` are optional aliases of `Bit0…`.
    Bits {
        width: u8,
        names: Vec<String>,
    },
    /// Named values, assigned by case-insensitive string.
    Enum(Vec<String>),
    String,
    Date,
    Time,
    Bseq,
    Wstr,
    /// The block's alarms: each readable as its In_Alarm state, each with a
    /// `.Suppress` timer, plus a block-wide `.Alarms.Suppress`.
    Alarms(Vec<String>),
}

impl FieldType {
    /// The keyword used for this type in database files and diagnostics.
    pub fn keyword(&self) -> &'static str {
        match self {
            FieldType::Real => "REAL",
            FieldType::Int => "INT",
            FieldType::Bool => "BOOL",
            FieldType::Bits { width: 8, .. } => "BITS8",
            FieldType::Bits { .. } => "BITS16",
            FieldType::Enum(_) => "ENUM",
            FieldType::String => "STRING",
            FieldType::Date => "DATE",
            FieldType::Time => "TIME",
            FieldType::Bseq => "BSEQ",
            FieldType::Wstr => "WSTR",
            FieldType::Alarms(_) => "ALARMS",
        }
    }

    /// Two fields belong to one offset run when their types are the same
    /// kind (enum value lists and bit names do not matter).
    pub fn same_kind(&self, other: &FieldType) -> bool {
        match (self, other) {
            (FieldType::Bits { width: a, .. }, FieldType::Bits { width: b, .. }) => a == b,
            _ => std::mem::discriminant(self) == std::mem::discriminant(other),
        }
    }

    /// Index of a bit sub-field (`Bit5` or a declared bit name).
    pub fn bit_index(&self, sub: &str) -> Option<u8> {
        let FieldType::Bits { width, names } = self else {
            return None;
        };
        if let Some(i) = names.iter().position(|n| n.eq_ignore_ascii_case(sub)) {
            return u8::try_from(i).ok();
        }
        let digits = sub.get(..3).filter(|p| p.eq_ignore_ascii_case("bit")).and(sub.get(3..))?;
        if digits.is_empty() || digits.len() > 2 || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let n: u8 = digits.parse().ok()?;
        (n < *width).then_some(n)
    }
}

/// One field of a template.
#[derive(Clone, Debug, PartialEq)]
pub struct FieldDef {
    pub name: String,
    pub ty: FieldType,
    /// Computed by the block itself; actions may read but not write it.
    pub readonly: bool,
    /// How ROC Plus carries it, when not [`RocType::default_for`] its type
    /// (`"wire": "AC30"` in the template).
    pub wire: Option<super::RocType>,
}

/// A block type: an ordered list of fields. Field order is the order that
/// offsets (`A0{3}`) walk.
#[derive(Clone, Debug, PartialEq)]
pub struct Template {
    pub name: String,
    pub doc: String,
    pub fields: Vec<FieldDef>,
    /// ROC point type numbers by device family (`"roc"` in the file): a
    /// template with them is a ROC point type, addressable by numeric TLP,
    /// whose parameter numbers are its field positions.
    pub roc: Vec<(Device, u16)>,
    index: NameMap,
}

impl Template {
    pub fn new(name: String, doc: String, fields: Vec<FieldDef>) -> Self {
        let index = fields.iter().enumerate().map(|(i, f)| (f.name.to_ascii_uppercase(), i)).collect();
        Template { name, doc, fields, roc: Vec::new(), index }
    }

    /// The ROC point type number of this template on `device`.
    pub fn point_type(&self, device: Device) -> Option<u16> {
        self.roc.iter().find(|(d, _)| *d == device).map(|&(_, t)| t)
    }

    /// Finds a field by case-insensitive name.
    pub fn field(&self, name: &str) -> Option<usize> {
        self.index.get(name)
    }
}

/// An initial value from the database file, already checked against its field.
#[derive(Clone, Debug, PartialEq)]
pub enum InitValue {
    Num(f64),
    Bool(bool),
    Text(String),
    /// Names of the alarms that are active (In_Alarm) at the start.
    Active(Vec<String>),
}

/// A block instance.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    pub name: String,
    pub template: usize,
    pub values: Vec<(usize, InitValue)>,
    /// The user task (1–4) the block runs in; 1 unless the file says otherwise.
    pub task: u8,
}

/// A LIN user task: blocks assigned to it run once every `period`.
#[derive(Clone, Debug, PartialEq)]
pub struct Task {
    /// 1 to 4.
    pub number: u8,
    /// Seconds, from 1 ms to 1 day.
    pub period: f64,
}

impl Task {
    /// Task 1 at 100 ms: the task every block runs in unless told otherwise.
    pub const DEFAULT: Task = Task { number: 1, period: 0.1 };
}

/// A tag-name alias for a database reference such as `REC1.A0`.
#[derive(Clone, Debug, PartialEq)]
pub struct Alias {
    pub name: String,
    /// The path the alias stands for, split at dots. An alias written in
    /// terms of another alias is stored expanded, so the first part is
    /// never an alias.
    pub target: Vec<String>,
}

/// Templates, blocks, aliases and tasks, with case-insensitive lookup.
#[derive(Clone, Debug)]
pub struct Database {
    pub templates: Vec<Template>,
    pub blocks: Vec<Block>,
    pub aliases: Vec<Alias>,
    /// Sorted by number; always holds task 1 and every task a block uses.
    pub tasks: Vec<Task>,
    /// The ROC device family whose point type numbers numeric TLPs use.
    pub device: Device,
    /// The Modbus register map (`"modbus"`), if the database has one.
    pub modbus: Option<super::modbus::ModbusMap>,
    /// The ROC operators (`"users"`): when there are any, a ROC host must
    /// log in.
    pub users: Vec<super::users::RocUser>,
    /// The configurable opcode tables of a ROC-protocol device, by table
    /// number (`"opcode_tables"`).
    pub opcode_tables: Vec<(u8, super::roc_device::OpcodeTable)>,
    /// Where store and forward reaches each device (`"roc": {"forward"}`).
    pub roc_forward: Vec<(super::roc_device::UnitGroup, std::net::SocketAddr)>,
    template_index: NameMap,
    block_index: NameMap,
    alias_index: NameMap,
}

/// An empty database still has task 1, so every block has a task to run in.
impl Default for Database {
    fn default() -> Self {
        Database {
            templates: Vec::new(),
            blocks: Vec::new(),
            aliases: Vec::new(),
            tasks: vec![Task::DEFAULT],
            device: Device::default(),
            modbus: None,
            users: Vec::new(),
            opcode_tables: Vec::new(),
            roc_forward: Vec::new(),
            template_index: NameMap::default(),
            block_index: NameMap::default(),
            alias_index: NameMap::default(),
        }
    }
}

impl Database {
    /// Adds a template, replacing one of the same name.
    pub fn put_template(&mut self, t: Template) -> usize {
        if let Some(i) = self.template_index.get(&t.name) {
            self.templates[i] = t;
            i
        } else {
            self.template_index.insert(&t.name, self.templates.len());
            self.templates.push(t);
            self.templates.len() - 1
        }
    }

    /// Adds a block; returns false if the name is taken.
    pub fn add_block(&mut self, b: Block) -> bool {
        if self.block_index.contains(&b.name) {
            return false;
        }
        self.block_index.insert(&b.name, self.blocks.len());
        self.blocks.push(b);
        true
    }

    /// Adds an alias; returns false if the name is taken.
    pub fn add_alias(&mut self, a: Alias) -> bool {
        if self.alias_index.contains(&a.name) {
            return false;
        }
        self.alias_index.insert(&a.name, self.aliases.len());
        self.aliases.push(a);
        true
    }

    pub fn template(&self, name: &str) -> Option<usize> {
        self.template_index.get(name)
    }

    pub fn block(&self, name: &str) -> Option<usize> {
        self.block_index.get(name)
    }

    pub fn alias(&self, name: &str) -> Option<&Alias> {
        self.alias_position(name).map(|i| &self.aliases[i])
    }

    /// Index of an alias in `aliases`.
    pub(crate) fn alias_position(&self, name: &str) -> Option<usize> {
        self.alias_index.get(name)
    }

    /// The block, field and bit that `BLOCK.FIELD`, `BLOCK.FIELD.BitN`
    /// (or the bit's name) or an alias of one names, as people type them
    /// (the console, `--set`, a Modbus map); `Err` says what is wrong.
    /// A block name may hold spaces (`AIN 2-1.EU`).
    pub fn field_path(&self, path: &str) -> Result<(usize, usize, Option<u8>), String> {
        let mut parts: Vec<String> = path.split('.').map(|p| p.trim().to_string()).collect();
        if let Some(a) = parts.first().and_then(|p| self.alias(p)) {
            let mut expanded = a.target.clone();
            expanded.extend(parts.drain(1..));
            parts = expanded;
        }
        let (Some(b), Some(f)) = (parts.first(), parts.get(1)) else {
            return Err(format!("`{path}` is not BLOCK.FIELD"));
        };
        let block = self.block(b).ok_or_else(|| format!("the database has no block `{b}`"))?;
        let t = self.block_template(block);
        let field = t.field(f).ok_or_else(|| format!("`{b}` has no field `{f}`"))?;
        let bit = match parts.get(2) {
            None => None,
            Some(sub) => {
                Some(t.fields[field].ty.bit_index(sub).ok_or_else(|| format!("`{b}.{f}` has no bit `{sub}`"))?)
            }
        };
        if parts.len() > 3 {
            return Err(format!("`{path}` has too many parts"));
        }
        Ok((block, field, bit))
    }

    /// A user task by number.
    pub fn task(&self, number: u8) -> Option<&Task> {
        self.tasks.iter().find(|t| t.number == number)
    }

    /// Defines a task, replacing one of the same number, keeping `tasks` sorted.
    pub fn put_task(&mut self, task: Task) {
        match self.tasks.binary_search_by_key(&task.number, |t| t.number) {
            Ok(i) => self.tasks[i] = task,
            Err(i) => self.tasks.insert(i, task),
        }
    }

    /// The template of a block.
    pub fn block_template(&self, block: usize) -> &Template {
        &self.templates[self.blocks[block].template]
    }
}
