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
/// index the program's target table. A block with neither runs the
/// object's instructions as they are, without a copy ([`Linked::ops`]): a
/// copy of a block of one-byte instructions took 8 bytes per byte.
#[derive(Clone, Debug)]
pub struct LinkedBlock {
    /// The linked instructions; `None` when they are the object's.
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
    pub fn link_each(self, store: &Store, programs: &[Program]) -> Result<Linked, (usize, LoadError)> {
        let mut linked = Vec::with_capacity(programs.len());
        for (i, &p) in programs.iter().enumerate() {
            let unit = self.object().units.get(p.unit).ok_or_else(|| {
                let what = format!("no unit {} (the object has {})", p.unit, self.object().units.len());
                (i, LoadError::Malformed { what })
            })?;
            linked.push(link_program(&self, unit, p, store).map_err(|e| (i, e))?);
        }
        let jit = crate::jit::Cache::new(linked.iter().map(|p| p.blocks.len()));
        Ok(Linked { verified: self, programs: linked, jit, cover: None })
    }
}

fn link_program(v: &Verified, unit: &Unit, p: Program, store: &Store) -> Result<LinkedProgram, LoadError> {
    if let (Some(b), false) = (p.own, unit.block_type.is_empty()) {
        let t = store.db.block_template(b);
        if !t.name.eq_ignore_ascii_case(&unit.block_type) {
            let name = &store.db.blocks[b].name;
            return Err(LoadError::Link {
                symbol: unit.name.clone(),
                why: format!("the action runs on a {} block, but `{name}` is a {} block", unit.block_type, t.name),
            });
        }
    }
    let mut local: HashMap<u16, u16> = HashMap::new();
    let mut targets = Vec::new();
    let mut symbols = Vec::new();
    let fst = unit.kind == crate::object::UnitKind::Fst;
    let mut blocks = Vec::with_capacity(unit.blocks.len());
    for (bi, b) in unit.blocks.iter().enumerate() {
        if b.ops.iter().all(|op| op.target().is_none() && op.symbol().is_none()) {
            blocks.push(LinkedBlock { ops: None, limits: v.limits(p.unit, bi) });
            continue;
        }
        let mut ops = Vec::with_capacity(b.ops.len());
        for op in b.ops.iter() {
            let mut op = match op.target() {
                Some(label) => op.retarget(b.labels[label as usize]),
                None => *op,
            };
            if let Some(s) = op.symbol() {
                let next = targets.len() as u16;
                let n = match local.get(&s) {
                    Some(&n) => n,
                    None => {
                        let sym = &v.object().symbols[usize::from(s)];
                        let target = match bind(sym, unit, p.own, store) {
                            Err(_) if fst && !sym.block.is_empty() => Target::ABSENT,
                            other => other?,
                        };
                        targets.push(target);
                        symbols.push(s);
                        local.insert(s, next);
                        next
                    }
                };
                if op.writes() && !targets[usize::from(n)].is_absent() {
                    check_writable(&v.object().symbols[usize::from(s)], targets[usize::from(n)], store)?;
                }
                op = op.with_symbol(n);
            }
            ops.push(op);
        }
        blocks.push(LinkedBlock { ops: Some(ops), limits: v.limits(p.unit, bi) });
    }
    Ok(LinkedProgram { unit: p.unit, own: p.own, targets, symbols, blocks })
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

/// Binds one symbol to a cell of `store`.
fn bind(sym: &Symbol, unit: &Unit, own: Option<usize>, store: &Store) -> Result<Target, LoadError> {
    let fail = |why: String| LoadError::Link { symbol: sym.text(), why };
    let block = if sym.block.is_empty() {
        own.ok_or_else(|| {
            fail(format!("action `{}` runs on a {} block; name one with --block", unit.name, unit.block_type))
        })?
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
