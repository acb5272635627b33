//! Lowering of a checked sequence: one unit of kind `Sequence` whose code
//! blocks are its transition conditions and its code actions, and whose
//! chart tables (built by the caller from the sequence's tree) name them.
//! Step variables read the step's retained slots (`.X` at `2 × slot`, `.T`
//! at `2 × slot + 1`), in the order the steps are given.

use super::{Lines, LowerError, Lowerer};
use crate::st::hir;
use linc_format::isa::{Kind, Op};
use linc_format::object::{ChartRec, ObjectFile, Unit, UnitKind};
use linc_stdlib::Ty;

/// Builds one sequence unit, block by block.
pub struct SequenceBuilder {
    l: Lowerer,
    blocks: Vec<linc_format::object::CodeBlock>,
    slots: usize,
}

impl SequenceBuilder {
    /// `steps` are every step of the sequence, nested charts included, in
    /// slot order (names are unique in a sequence).
    pub fn new(file: &str, lines: Lines, steps: &[String]) -> SequenceBuilder {
        let mut l = Lowerer { lines, file: file.to_string(), ..Lowerer::default() };
        l.steps = steps.iter().enumerate().map(|(i, s)| (s.to_ascii_uppercase(), i as u16)).collect();
        SequenceBuilder { l, blocks: Vec::new(), slots: steps.len() }
    }

    /// The source line `span` starts on.
    pub fn line_of(&self, span: crate::diag::span::Span) -> u32 {
        self.l.lines.at(span.start).0
    }

    /// The number the next block gets, or E0132 at `span` (once) when the
    /// unit is full: the number would not fit the 16 bits it is stored in.
    fn next(&mut self, span: crate::diag::span::Span) -> u16 {
        match u16::try_from(self.blocks.len()) {
            Ok(n) if usize::from(n) < crate::sfc::lower::MAX_BLOCKS => n,
            _ => {
                if self.blocks.len() == crate::sfc::lower::MAX_BLOCKS {
                    let what = "code blocks (transition conditions and actions)";
                    self.l.errors.push(super::LowerError::TooMany { span, what });
                }
                0
            }
        }
    }

    /// A transition condition: the block computes it and returns a truth value.
    pub fn condition(&mut self, name: &str, cond: &hir::Expr) -> u16 {
        self.l.mark(cond.span);
        self.l.expr_as(cond, Ty::Bool);
        self.l.emit(Op::Return { kind: Kind::Bool as u8 });
        let at = self.next(cond.span);
        self.blocks.push(self.l.take_block(name.to_string()));
        at
    }

    /// A code action: its statements, ending with `Ret`.
    pub fn action(&mut self, name: &str, body: &[hir::Stmt], span: crate::diag::span::Span) -> u16 {
        self.l.stmts(body);
        self.l.emit(Op::Ret {});
        let at = self.next(span);
        self.blocks.push(self.l.take_block(name.to_string()));
        at
    }

    /// The object holding the sequence `name` with its charts (ROOT first).
    pub fn finish(mut self, name: &str, charts: Vec<ChartRec>) -> Result<ObjectFile, Vec<LowerError>> {
        // A unit holds code; a chart without transitions or ST actions
        // (`INITIAL_STEP S0: END_STEP`) gets one block that nothing runs.
        if self.blocks.is_empty() {
            self.l.emit(Op::Ret {});
            self.blocks.push(self.l.take_block(String::new()));
        }
        let retained = u16::try_from(2 * self.slots).unwrap_or(u16::MAX);
        let unit = Unit {
            kind: UnitKind::Sequence,
            name: name.to_string(),
            file: self.l.file.clone(),
            block_type: String::new(),
            retained,
            blocks: self.blocks,
            charts,
            steps: Vec::new(),
        };
        let source = self.l.file.clone();
        self.l.finish(&source, vec![unit])
    }
}
