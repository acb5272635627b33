//! Name resolution: what a variable reference denotes in the database.
//!
//! A reference is tried, in order, as an alias (its target replaces the first
//! name), a block, a field of the action's own block type, and (in sequences)
//! a step variable. Names ignore case throughout.

use super::errors::CheckError;
use super::limits::SymbolKey;
use super::Checker;
use crate::diag::span::Span;
use crate::names::Meaning;
use crate::st::ast::{Expr, Name, Var};
use crate::st::hir::{self, Place, Target};
use linc_format::object::class_of;
use linc_format::object::Class;
use linc_format::{FieldType, Template};
use linc_stdlib::Ty;
use smallvec::SmallVec;

/// What a reference denotes: the place, and whether it may be written.
#[derive(Clone, Debug, PartialEq)]
pub struct Resolved {
    pub place: Place,
    pub writable: bool,
    /// Why it is not writable, for the diagnostic.
    pub why_readonly: &'static str,
    /// The object file symbol this becomes, for counting (see `limits.rs`).
    symbol: Option<SymbolKey>,
}

impl Resolved {
    fn new(v: &Var, ty: Ty, target: Target) -> Resolved {
        // Only messages about step variables and unknown names (from
        // lowering) and about enumerated fields read the path: other
        // references skip building it (one allocation each).
        let path = match target {
            Target::Step { .. } | Target::Unknown => v.path(),
            _ => String::new(),
        };
        let place = Place { ty, class: None, target, enum_values: None, path, span: v.span };
        Resolved { place, writable: true, why_readonly: "", symbol: None }
    }

    /// Sets the storage class and the symbol: `block` and `field` are
    /// indices, `sub` tells a field from its alarms and suppression.
    fn stored(mut self, class: Class, (block, field, sub): (u32, usize, u32)) -> Resolved {
        self.place.class = Some(class);
        self.symbol = Some((block, field as u32, sub, class as u8));
        self
    }

    fn read_only(mut self, why: &'static str) -> Resolved {
        self.writable = false;
        self.why_readonly = why;
        self
    }

    pub fn ty(&self) -> Ty {
        self.place.ty
    }
}

/// One name part with its span and optional offset (as written and as
/// checked); alias targets borrow the span of the alias.
struct Part<'a> {
    name: &'a str,
    span: Span,
    offset: Option<&'a Expr>,
    checked: Option<hir::Expr>,
    /// Part of an alias's target: the name written is the alias's.
    from_alias: bool,
}

impl Checker<'_> {
    /// Resolves a variable, reporting what is wrong with it. `None` means an
    /// error was reported and the caller should treat the value as `Any`.
    pub(super) fn resolve(&mut self, v: &Var) -> Option<Resolved> {
        let checked = self.offsets(v);
        self.resolve_checked(v, checked)
    }

    /// Resolves a variable whose offsets are checked.
    pub(super) fn resolve_checked(&mut self, v: &Var, checked: Vec<Option<hir::Expr>>) -> Option<Resolved> {
        if v.malformed {
            return None;
        }
        let r = self.resolve_parts(v, checked)?;
        if let Some(key) = r.symbol {
            self.count_reference(key, v.span);
        }
        Some(r)
    }

    /// Checks the offsets of every part (this is where the walk recurses).
    /// Most references have no offset: then the list is empty (no
    /// allocation) and every part reads as having none.
    pub(super) fn offsets(&mut self, v: &Var) -> Vec<Option<hir::Expr>> {
        if v.segs.iter().all(|s| s.offset.is_none()) {
            return Vec::new();
        }
        let mut checked: Vec<Option<hir::Expr>> = Vec::with_capacity(v.segs.len());
        for seg in &v.segs {
            match &seg.offset {
                Some(o) => {
                    let e = self.expr(o);
                    if !e.ty.is_numeric() {
                        self.offset_not_number(o.span, e.ty);
                    }
                    checked.push(Some(e));
                }
                None => checked.push(None),
            }
        }
        checked
    }

    #[cold]
    fn offset_not_number(&mut self, span: Span, found: Ty) {
        self.errors.push(CheckError::OffsetNotNumber { span, found: found.name().into() });
    }

    fn resolve_parts(&mut self, v: &Var, checked: Vec<Option<hir::Expr>>) -> Option<Resolved> {
        let db = self.ctx.db;
        let mut checked = checked.into_iter();
        let first = &v.segs[0];
        let first_checked = checked.next().flatten();
        // On the stack: a reference has rarely more than four parts.
        let mut parts: SmallVec<[Part; 4]> = SmallVec::new();
        if let Some(alias) = db.alias(&first.name.text) {
            self.ctx.note(first.name.span, || {
                Meaning::Alias(db.aliases.iter().position(|a| std::ptr::eq(a, alias)).unwrap_or_default())
            });
            let n = alias.target.len();
            let mut first_checked = Some(first_checked);
            for (i, t) in alias.target.iter().enumerate() {
                let last = i + 1 == n;
                let offset = if last { first.offset.as_deref() } else { None };
                let checked = if last { first_checked.take().flatten() } else { None };
                parts.push(Part { name: t, span: first.name.span, offset, checked, from_alias: true });
            }
        } else {
            let offset = first.offset.as_deref();
            let checked = first_checked;
            parts.push(Part { name: &first.name.text, span: first.name.span, offset, checked, from_alias: false });
        }
        for s in &v.segs[1..] {
            let checked = checked.next().flatten();
            let offset = s.offset.as_deref();
            parts.push(Part { name: &s.name.text, span: s.name.span, offset, checked, from_alias: false });
        }

        if let Some(b) = db.block(parts[0].name) {
            if !parts[0].from_alias {
                self.ctx.note(parts[0].span, || Meaning::Block(b));
            }
            if parts[0].offset.is_some() {
                self.errors.push(CheckError::BadOffsetBase {
                    span: parts[0].span,
                    base: parts[0].name.to_string(),
                    why: "a block name can't be offset".into(),
                });
                return None;
            }
            if parts.len() < 2 {
                self.errors.push(CheckError::NotAValue { span: v.span, what: v.path() });
                return None;
            }
            let block = &db.blocks[b].name;
            return self.field_path(db.block_template(b), (block, b as u32 + 1), &mut parts[1..], v);
        }
        if let Some(t) = self.self_template {
            let tpl = &db.templates[t];
            if tpl.field(parts[0].name).is_some() {
                return self.field_path(tpl, ("", 0), &mut parts, v);
            }
        }
        let step_like =
            parts.len() == 2 && (parts[1].name.eq_ignore_ascii_case("X") || parts[1].name.eq_ignore_ascii_case("T"));
        if step_like && self.ctx.steps.is_some() {
            return self.step_variable(&parts, v);
        }
        // Without a database any block may exist at run time; a lone name in
        // an action bound to a block type can only be one of its fields.
        let lone_field = self.self_template.is_some() && parts.len() == 1;
        if !self.ctx.resolve_blocks && !lone_field {
            return Some(Resolved::new(v, Ty::Any, Target::Unknown));
        }
        // `PIC_04.T` is more likely a misspelt block than a step variable
        // when a block of a close name exists.
        let suggestion = self.suggest_block(parts[0].name);
        if step_like && suggestion.is_none() {
            return self.step_variable(&parts, v);
        }
        self.errors.push(CheckError::UnknownName { span: parts[0].span, name: parts[0].name.to_string(), suggestion });
        None
    }

    /// The block or alias whose name is closest to `name`, if close enough.
    fn suggest_block(&mut self, name: &str) -> Option<String> {
        if let Some(s) = self.suggestions.get(name) {
            return s.clone();
        }
        let db = self.ctx.db;
        let upper = name.to_ascii_uppercase();
        let names = db.blocks.iter().map(|b| b.name.as_str()).chain(db.aliases.iter().map(|a| a.name.as_str()));
        let best = names
            .filter(|n| n.len().abs_diff(upper.len()) <= 2)
            .map(|n| (super::expr::distance(&upper, &n.to_ascii_uppercase()), n))
            .filter(|(d, n)| *d <= 2.min(n.len() / 3).max(1))
            .min_by_key(|(d, _)| *d)
            .map(|(_, n)| n.to_string());
        self.suggestions.insert(name.to_string(), best.clone());
        best
    }

    fn step_variable(&mut self, parts: &[Part], v: &Var) -> Option<Resolved> {
        let Some(steps) = self.ctx.steps else {
            self.errors.push(CheckError::StepOutsideSequence { span: v.span, name: v.path() });
            return None;
        };
        let index = self
            .step_index
            .get_or_insert_with(|| steps.iter().enumerate().rev().map(|(i, s)| (s.to_ascii_uppercase(), i)).collect());
        let declared = index.get(&parts[0].name.to_ascii_uppercase()).copied();
        if (self.ctx.steps_known || !steps.is_empty()) && declared.is_none() {
            self.errors.push(CheckError::UnknownStep { span: parts[0].span, name: parts[0].name.to_string() });
            return None;
        }
        if let Some(i) = declared {
            self.ctx.note(parts[0].span, || Meaning::Step(steps[i].clone()));
        }
        let x = parts[1].name.eq_ignore_ascii_case("X");
        let ty = if x { Ty::Bool } else { Ty::Real };
        let target = Target::Step { step: parts[0].name.into(), x };
        Some(Resolved::new(v, ty, target).read_only("step variables are maintained by the sequence"))
    }

    /// Resolves `field[.sub[.sub]]` within a template. `block` is the block's
    /// name, or empty for the block that runs the action.
    fn field_path(&mut self, tpl: &Template, block: (&str, u32), parts: &mut [Part], v: &Var) -> Option<Resolved> {
        let (block, block_id) = block;
        let fpart = &parts[0];
        let Some(fi) = tpl.field(fpart.name) else {
            return self.unknown_field(tpl, block, fpart);
        };
        if let Some(o) = fpart.offset {
            self.check_field_offset(tpl, fi, o, fpart)?;
        }
        self.note_field(block_id, fi, parts);
        let base_name = Name::from(tpl.fields[fi].name.as_str());
        // A constant offset names its field exactly: `PV{1}` is as writable as
        // the field it lands on. Variable offsets are checked at run time.
        let landed = match fpart.offset.and_then(|o| o.int_value()) {
            Some(n) => fi + n as usize,
            None => fi,
        };
        let field = &tpl.fields[landed];
        let offset = parts[0].checked.take().map(Box::new);
        let readonly = |r: Resolved| {
            if field.readonly {
                r.read_only("this field is computed by its block (read-only)")
            } else {
                r
            }
        };
        let class = class_of(&field.ty);
        let (b, f) = (Name::from(block), base_name);
        let rest = &mut parts[1..];
        match (&field.ty, rest) {
            (FieldType::Alarms(_), []) => {
                self.errors.push(CheckError::NotAValue { span: v.span, what: v.path() });
                None
            }
            (ty, []) => {
                let (t, enum_values) = value_type(ty);
                let mut r =
                    Resolved::new(v, t, Target::Field { block: b, field: f, offset }).stored(class, (block_id, fi, 0));
                if enum_values.is_some() {
                    r.place.path = v.path();
                }
                r.place.enum_values = enum_values;
                Some(readonly(r))
            }
            (FieldType::Bits { width, .. }, [bit]) => {
                let Some(n) = field.ty.bit_index(bit.name) else {
                    return self.no_sub(bit, &field.name, &field.ty);
                };
                self.check_bit_offset(bit, n, *width)?;
                let bit_offset = bit.checked.take().map(Box::new);
                let target = Target::Bit { block: b, field: f, offset, bit: n, bit_offset };
                let r = Resolved::new(v, Ty::Bool, target).stored(class, (block_id, fi, 0));
                Some(readonly(r))
            }
            (FieldType::Alarms(names), [sub, more @ ..]) => {
                let suppress = |alarm: Option<Name>, sub: u32| {
                    Resolved::new(v, Ty::Int, Target::Suppress { block: b.clone(), field: f.clone(), alarm })
                        .stored(class, (block_id, fi, sub))
                };
                if sub.name.eq_ignore_ascii_case("Suppress") && more.is_empty() {
                    return Some(suppress(None, 1));
                }
                let Some(ai) = names.iter().position(|n| n.eq_ignore_ascii_case(sub.name)) else {
                    return self.no_sub(sub, &field.name, &field.ty);
                };
                let alarm = Name::from(names[ai].as_str());
                match more {
                    [] => {
                        let r = Resolved::new(v, Ty::Bool, Target::Alarm { block: b.clone(), field: f.clone(), alarm })
                            .stored(class, (block_id, fi, 2 + 2 * ai as u32));
                        Some(r.read_only("an alarm's state is set by its block; write its .Suppress instead"))
                    }
                    [s] if s.name.eq_ignore_ascii_case("Suppress") => Some(suppress(Some(alarm), 3 + 2 * ai as u32)),
                    [s, ..] => {
                        let s = Part { name: s.name, span: s.span, offset: None, checked: None, from_alias: false };
                        self.no_sub(&s, &alarm, &FieldType::Bool)
                    }
                }
            }
            (_, [sub, ..]) => {
                let sub = Part { name: sub.name, span: sub.span, offset: None, checked: None, from_alias: false };
                let owner_ty = field.ty.clone();
                let name = field.name.clone();
                self.no_sub(&sub, &name, &owner_ty)
            }
        }
    }

    fn unknown_field(&mut self, tpl: &Template, block: &str, part: &Part) -> Option<Resolved> {
        let known =
            if tpl.fields.len() <= 16 { tpl.fields.iter().map(|f| f.name.clone()).collect() } else { Vec::new() };
        let owner = if block.is_empty() { "this action's block".to_string() } else { block.to_string() };
        self.errors.push(CheckError::UnknownField {
            span: part.span,
            field: part.name.to_string(),
            owner,
            template: tpl.name.clone(),
            known,
        });
        None
    }

    /// Records what each written part of a field path names, for the
    /// language server; parts an alias supplied have no place in the text.
    fn note_field(&self, block_id: u32, fi: usize, parts: &[Part]) {
        let template =
            if block_id == 0 { self.self_template } else { Some(self.ctx.db.blocks[block_id as usize - 1].template) };
        let Some(template) = template else { return };
        let owner = (block_id != 0).then(|| block_id as usize - 1);
        for (i, part) in parts.iter().enumerate().filter(|(_, p)| !p.from_alias) {
            let sub = (i > 0).then(|| part.name.to_string());
            self.ctx.note(part.span, || Meaning::Field { block: owner, template, field: fi, sub });
        }
    }

    /// A bit with an offset must leave room for it: `Bit3{k}` stays inside
    /// the field when k is a constant, and is checked at run time otherwise.
    fn check_bit_offset(&mut self, bit: &Part, n: u8, width: u8) -> Option<()> {
        let Some(o) = bit.offset else { return Some(()) };
        let span = bit.span.to(o.span);
        let why = if n + 1 >= width {
            format!("Bit{n} is the last bit of a {width}-bit field")
        } else {
            match o.int_value() {
                Some(k) if k < 0 => format!("Bit{n}{{{k}}} counts back from its base; offsets count forward"),
                Some(k) if i64::from(n) + i64::from(k) >= i64::from(width) => {
                    format!("Bit{n}{{{k}}} is beyond the last bit, Bit{}", width - 1)
                }
                _ => return Some(()),
            }
        };
        self.errors.push(CheckError::BadOffsetBase { span, base: bit.name.to_string(), why });
        None
    }

    fn no_sub(&mut self, part: &Part, field: &str, ty: &FieldType) -> Option<Resolved> {
        let field_type = if field.eq_ignore_ascii_case("") { "" } else { ty.keyword() };
        self.errors.push(CheckError::UnknownSubField {
            span: part.span,
            sub: part.name.to_string(),
            field: field.to_string(),
            field_type,
        });
        None
    }

    /// §12.12: the base must start a run of same-typed fields, and a
    /// constant offset must stay inside it.
    fn check_field_offset(&mut self, tpl: &Template, fi: usize, o: &Expr, part: &Part) -> Option<()> {
        let kind = &tpl.fields[fi].ty;
        let run = tpl.fields[fi..].iter().take_while(|f| f.ty.same_kind(kind)).count();
        let span = part.span.to(o.span);
        let base = part.name.to_string();
        if run < 2 {
            let why = match tpl.fields.get(fi + 1) {
                Some(next) => {
                    format!("the next field, {}, is {} but this is {}", next.name, next.ty.keyword(), kind.keyword())
                }
                None => "it is the last field of its block".to_string(),
            };
            self.errors.push(CheckError::BadOffsetBase { span, base, why });
            return None;
        }
        if let Some(n) = o.int_value() {
            if n < 0 || n as usize >= run {
                let why = format!(
                    "offset {n} leaves the run of {} {} fields that starts here ({} to {})",
                    run,
                    kind.keyword(),
                    tpl.fields[fi].name,
                    tpl.fields[fi + run - 1].name
                );
                self.errors.push(CheckError::BadOffsetBase { span, base, why });
                return None;
            }
        }
        Some(())
    }
}

/// The value type of a whole field, and an ENUM field's values.
fn value_type(ty: &FieldType) -> (Ty, Option<Vec<String>>) {
    match ty {
        FieldType::Real => (Ty::Real, None),
        FieldType::Int | FieldType::Bits { .. } => (Ty::Int, None),
        FieldType::Bool => (Ty::Bool, None),
        FieldType::Enum(v) => (Ty::Text, Some(v.clone())),
        FieldType::String | FieldType::Date | FieldType::Time => (Ty::Text, None),
        FieldType::Bseq => (Ty::Bytes, None),
        FieldType::Wstr => (Ty::WStr, None),
        FieldType::Alarms(_) => (Ty::Any, None),
    }
}
