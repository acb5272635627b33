//! Linking a verified object to a store: every program's symbols become
//! cells, jumps become instruction indices, and writes to read-only fields
//! are refused before anything runs.
//!
//! A *program* is one unit run by one block: the same unit may run on
//! several blocks (two ACTION blocks naming one `ACTION a : ACTION` action),
//! each with its own cells for the unit's own-block fields. Each program
//! gets its own copy of the code with symbols renumbered into a small dense
//! table, so the VM's look-ups stay O(1) whatever the size of the object.

use crate::errors::LoadError;
use crate::isa::Op;
use crate::object::{CodeBlock, ObjectFile, Sub, Symbol, Unit};
use crate::store::{class_of, Cell, Store};
use crate::verify::{Limits, Verified};
use std::collections::HashMap;

/// What to link: a unit, and the block that runs it (for the fields of an
/// `ACTION name : TYPE` action).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Program {
    pub unit: usize,
    pub own: Option<usize>,
}

/// A symbol bound to the live database.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Target {
    pub cell: u32,
    /// Last cell of the run `cell` starts (for offsets).
    pub run_end: u32,
    /// Alarm index for alarm symbols; `u16::MAX` for the block-wide suppression.
    pub alarm: u16,
}

/// One code block ready to run: jumps are instruction indices and symbols
/// index the program's target table. A block runs the object's
/// instructions, without a copy ([`Linked::ops`]), when it has neither or
/// when it was linked in place (see [`Verified::link_each`]): a copy of a
/// block of one-byte instructions took 8 bytes per byte.
#[derive(Clone, Debug)]
pub struct LinkedBlock {
    /// The linked instructions; `None` when they are the object's (as they
    /// were, or linked in place).
    ops: Option<Vec<Op>>,
    pub limits: Limits,
}

/// One linked program.
#[derive(Clone, Debug)]
pub struct LinkedProgram {
    pub unit: usize,
    pub own: Option<usize>,
    pub targets: Vec<Target>,
    /// The object's symbol behind each target, for messages.
    pub symbols: Vec<u16>,
    pub blocks: Vec<LinkedBlock>,
}

impl Target {
    /// What an FST table's reference to a missing point links to: touching
    /// it stops the table with run flag 5 (R0010) instead of refusing the
    /// whole strategy, as a ROC does when a point is removed.
    pub const ABSENT: Target = Target { cell: u32::MAX, run_end: 0, alarm: u16::MAX };

    pub fn is_absent(&self) -> bool {
        self.cell == u32::MAX
    }
}

/// A verified object linked to a store: what the VM runs.
#[derive(Clone, Debug)]
pub struct Linked {
    verified: Verified,
    programs: Vec<LinkedProgram>,
    /// Machine code of the blocks the compiling tier has translated.
    pub(crate) jit: crate::jit::Cache,
    /// Coverage counters, when a run collects coverage (shared by clones).
    cover: Option<std::sync::Arc<crate::cover::Counters>>,
}

impl Linked {
    /// Counts what runs from now on (`linc test --coverage`); without it,
    /// nothing is counted and runs cost what they always did.
    pub fn enable_coverage(&mut self) {
        if self.cover.is_none() {
            self.cover = Some(std::sync::Arc::new(crate::cover::Counters::new(self.object())));
        }
    }

    /// The coverage counters, when enabled.
    pub fn coverage(&self) -> Option<&crate::cover::Counters> {
        self.cover.as_deref()
    }

    /// The counters of block `block` of `program`'s unit, when enabled.
    pub(crate) fn cover_block(&self, program: usize, block: usize) -> Option<&crate::cover::BlockCounters> {
        let unit = self.programs.get(program)?.unit;
        self.cover.as_deref()?.block(unit, block)
    }

    /// Whether the compiling tier has compiled block `block` of `program` yet.
    pub fn is_compiled(&self, program: usize, block: usize) -> bool {
        self.jit.is_compiled((program, block))
    }

    /// Whether the compiling tier has compiled the traced variant of a block.
    pub fn is_compiled_traced(&self, program: usize, block: usize) -> bool {
        self.jit.is_compiled_traced((program, block))
    }

    /// Waits until the translations `--tier auto` queued for these programs
    /// have ended, so that a test knows which code the next run uses.
    pub fn settle_translations(&self) {
        self.jit.settle();
    }

    /// Runs of a block that began on the interpreter while its translation
    /// was pending (ADR 0023): each is a run that did not wait for one.
    pub fn runs_behind_translation(&self, program: usize, block: usize) -> u64 {
        self.jit.runs_behind((program, block))
    }

    /// Code blocks of the linked programs: how many the compiling tier has
    /// compiled so far (for a traced run or not), and how many there are.
    pub fn compiled_blocks(&self) -> (usize, usize) {
        let all = self.programs.iter().map(|p| p.blocks.len()).sum();
        let compiled = (self.programs.iter().enumerate())
            .flat_map(|(p, prog)| (0..prog.blocks.len()).map(move |b| (p, b)))
            .filter(|&(p, b)| self.is_compiled(p, b) || self.is_compiled_traced(p, b))
            .count();
        (compiled, all)
    }

    /// The object. The code of a linked unit is as linked (jumps to
    /// instruction indices, symbols to a program's table), the form
    /// [`Linked::ops`] gives; its labels, tables and records are the file's.
    pub fn object(&self) -> &ObjectFile {
        self.verified.object()
    }

    pub fn programs(&self) -> &[LinkedProgram] {
        &self.programs
    }

    pub fn program(&self, i: usize) -> Option<&LinkedProgram> {
        self.programs.get(i)
    }

    /// The unit a program runs.
    pub fn unit(&self, program: usize) -> Option<&Unit> {
        self.programs.get(program).and_then(|p| self.object().units.get(p.unit))
    }

    /// The numeric stack's shape at each reached label of a block, as the
    /// verifier found it (the compiling tier types its stack from these).
    pub fn shapes(&self, program: usize, block: usize) -> &[(u32, crate::verify::Shape)] {
        self.programs.get(program).map_or(&[], |p| self.verified.shapes(p.unit, block))
    }

    /// The instructions block `block` of `program` runs.
    pub fn ops(&self, program: usize, block: usize) -> Option<&[Op]> {
        let linked = self.programs.get(program)?.blocks.get(block)?;
        let code = self.unit(program)?.blocks.get(block)?;
        Some(linked.ops_or(code))
    }
}

impl LinkedBlock {
    /// The instructions, given the object's block `code` this was linked from.
    pub(crate) fn ops_or<'a>(&'a self, code: &'a CodeBlock) -> &'a [Op] {
        self.ops.as_deref().unwrap_or(&code.ops)
    }
}

impl Verified {
    /// Links `programs` to `store`. The store's layout must not change
    /// afterwards (it does not: blocks are fixed when it is made).
    pub fn link(self, store: &Store, programs: &[Program]) -> Result<Linked, LoadError> {
        self.link_each(store, programs).map_err(|(_, e)| e)
    }

    /// As [`Verified::link`], naming the program that failed to link.
    ///
    /// The last program of each unit links the object's own instructions in
    /// place, and only the earlier ones (the same unit run by another
    /// block) link a copy: a copy of a block of one-byte instructions took
    /// 8 bytes per byte of the file, doubling what the load needs. No one
    /// reads the unlinked code of a unit once it is linked (the VM, the
    /// compiling tier and coverage read [`Linked::ops`] or what kind each
    /// instruction is, which linking keeps).
    pub fn link_each(mut self, store: &Store, programs: &[Program]) -> Result<Linked, (usize, LoadError)> {
        let units = self.object().units.len();
        let mut last = vec![usize::MAX; units];
        for (i, p) in programs.iter().enumerate() {
            if let Some(l) = last.get_mut(p.unit) {
                *l = i;
            }
        }
        let mut linked = Vec::with_capacity(programs.len());
        for (i, &p) in programs.iter().enumerate() {
            if p.unit >= units {
                let what = format!("no unit {} (the object has {units})", p.unit);
                return Err((i, LoadError::Malformed { what }));
            }
            linked.push(link_program(&mut self, p, last[p.unit] == i, store).map_err(|e| (i, e))?);
        }
        let jit = crate::jit::Cache::new(linked.iter().map(|p| p.blocks.len()));
        Ok(Linked { verified: self, programs: linked, jit, cover: None })
    }
}

/// What linking one program has bound so far: each object symbol it uses
/// with its index in the program's table.
struct Binder<'a> {
    symbols: &'a [Symbol],
    unit: (&'a str, &'a str),
    own: Option<usize>,
    fst: bool,
    store: &'a Store,
    local: HashMap<u16, u16>,
    targets: Vec<Target>,
    used: Vec<u16>,
}

/// Links unit `p.unit` of `v` for `p`: in the object's own code when
/// `in_place` (no later program links that unit), otherwise in a copy.
fn link_program(v: &mut Verified, p: Program, in_place: bool, store: &Store) -> Result<LinkedProgram, LoadError> {
    let limits: Vec<Limits> = (0..v.object().units[p.unit].blocks.len()).map(|b| v.limits(p.unit, b)).collect();
    let (units, symbols) = v.units_and_symbols();
    let Unit { name, block_type, kind, blocks: code, .. } = &mut units[p.unit];
    if let (Some(b), false) = (p.own, block_type.is_empty()) {
        let t = store.db.block_template(b);
        if !t.name.eq_ignore_ascii_case(block_type) {
            let name = &store.db.blocks[b].name;
            return Err(LoadError::Link {
                symbol: name.clone(),
                why: format!("the action runs on a {block_type} block, but `{name}` is a {} block", t.name),
            });
        }
    }
    let fst = *kind == crate::object::UnitKind::Fst;
    let mut binder = Binder {
        symbols,
        unit: (name, block_type),
        own: p.own,
        fst,
        store,
        local: HashMap::new(),
        targets: Vec::new(),
        used: Vec::new(),
    };
    let mut blocks = Vec::with_capacity(code.len());
    for (b, limits) in code.iter_mut().zip(limits) {
        let ops = if b.ops.iter().all(|op| op.target().is_none() && op.symbol().is_none()) {
            None
        } else if in_place {
            for op in b.ops.0.iter_mut() {
                *op = binder.link_op(*op, &b.labels)?;
            }
            None
        } else {
            Some(b.ops.iter().map(|&op| binder.link_op(op, &b.labels)).collect::<Result<Vec<Op>, _>>()?)
        };
        blocks.push(LinkedBlock { ops, limits });
    }
    let Binder { targets, used, .. } = binder;
    Ok(LinkedProgram { unit: p.unit, own: p.own, targets, symbols: used, blocks })
}

impl Binder<'_> {
    /// `op` linked: its jump to an instruction index, its symbol to the
    /// program's table (bound on first use).
    fn link_op(&mut self, op: Op, labels: &[u32]) -> Result<Op, LoadError> {
        let op = match op.target() {
            Some(label) => op.retarget(labels[label as usize]),
            None => op,
        };
        let Some(s) = op.symbol() else { return Ok(op) };
        let n = match self.local.get(&s) {
            Some(&n) => n,
            None => {
                let next = self.targets.len() as u16;
                let sym = &self.symbols[usize::from(s)];
                let target = match bind(sym, self.unit, self.own, self.store) {
                    Err(_) if self.fst && !sym.block.is_empty() => Target::ABSENT,
                    other => other?,
                };
                self.targets.push(target);
                self.used.push(s);
                self.local.insert(s, next);
                next
            }
        };
        let target = self.targets[usize::from(n)];
        if op.writes() && !target.is_absent() {
            check_writable(&self.symbols[usize::from(s)], target, self.store)?;
        }
        Ok(op.with_symbol(n))
    }
}

/// A direct write to a read-only field is refused at link time; writes
/// through offsets are checked when they happen.
fn check_writable(sym: &Symbol, t: Target, store: &Store) -> Result<(), LoadError> {
    if sym.sub == Sub::Field && store.is_readonly(t.cell) {
        return Err(LoadError::Link {
            symbol: sym.text(),
            why: "the field is read-only in this database, and the program writes it".into(),
        });
    }
    Ok(())
}

/// Binds one symbol to a cell of `store`, for the unit (name, block type).
fn bind(
    sym: &Symbol,
    (unit, block_type): (&str, &str),
    own: Option<usize>,
    store: &Store,
) -> Result<Target, LoadError> {
    let fail = |why: String| LoadError::Link { symbol: sym.text(), why };
    let block = if sym.block.is_empty() {
        own.ok_or_else(|| fail(format!("action `{unit}` runs on a {block_type} block; name one with --block")))?
    } else {
        store.db.block(&sym.block).ok_or_else(|| fail("the database has no such block".into()))?
    };
    let t = store.db.block_template(block);
    let fi = t.field(&sym.field).ok_or_else(|| fail(format!("block type {} has no such field", t.name)))?;
    let class = class_of(&t.fields[fi].ty);
    if class != sym.class {
        return Err(fail(format!(
            "the field is {class:?} in this database, but the program was compiled for {:?}",
            sym.class
        )));
    }
    let cell = store.first[block] + fi as u32;
    let alarm = match (&sym.sub, store.cells.get(cell as usize)) {
        (Sub::Field, _) | (Sub::Suppress(None), _) => u16::MAX,
        (Sub::Alarm(name) | Sub::Suppress(Some(name)), Some(Cell::Alarms(al))) => al
            .names
            .iter()
            .position(|n| n.eq_ignore_ascii_case(name))
            .map(|i| i as u16)
            .ok_or_else(|| fail("the block has no such alarm".into()))?,
        _ => return Err(fail("not an alarm field".into())),
    };
    Ok(Target { cell, run_end: store.run_end[cell as usize], alarm })
}
