//! Name resolution: what a variable reference denotes in the database.
//!
//! A reference is tried, in order, as an alias (its target replaces the first
//! name), a block, a field of the action's own block type, and (in sequences)
//! a step variable. Names ignore case throughout.

use super::errors::CheckError;
use super::Checker;
use crate::ast::{Expr, Var};
use crate::span::Span;
use linc_runtime::{FieldType, Template};
use linc_stdlib::Ty;

/// What a reference denotes, as far as the checker needs to know.
#[derive(Clone, Debug, PartialEq)]
pub struct Resolved {
    pub ty: Ty,
    pub writable: bool,
    /// Why it is not writable, for the diagnostic.
    pub why_readonly: &'static str,
    /// Allowed values of an ENUM field.
    pub enum_values: Option<Vec<String>>,
}

impl Resolved {
    fn any() -> Resolved {
        Resolved {
            ty: Ty::Any,
            writable: true,
            why_readonly: "",
            enum_values: None,
        }
    }
}

/// One name part with its span and optional offset; alias targets borrow
/// the span of the alias.
struct Part<'a> {
    name: &'a str,
    span: Span,
    offset: Option<&'a Expr>,
}

impl Checker<'_> {
    /// Resolves a variable, reporting what is wrong with it. `None` means an
    /// error was reported and the caller should treat the value as `Any`.
    pub(super) fn resolve(&mut self, v: &Var) -> Option<Resolved> {
        for seg in &v.segs {
            if let Some(o) = &seg.offset {
                let t = self.expr(o);
                if !t.is_numeric() {
                    self.errors.push(CheckError::OffsetNotNumber {
                        span: o.span,
                        found: t.name().into(),
                    });
                }
            }
        }
        if v.malformed {
            return None;
        }
        let db = self.ctx.db;
        let first = &v.segs[0];
        let mut parts: Vec<Part> = Vec::with_capacity(v.segs.len() + 2);
        if let Some(alias) = db.alias(&first.name.text) {
            let n = alias.target.len();
            for (i, t) in alias.target.iter().enumerate() {
                let offset = if i + 1 == n {
                    first.offset.as_deref()
                } else {
                    None
                };
                parts.push(Part {
                    name: t,
                    span: first.name.span,
                    offset,
                });
            }
        } else {
            parts.push(Part {
                name: &first.name.text,
                span: first.name.span,
                offset: first.offset.as_deref(),
            });
        }
        parts.extend(v.segs[1..].iter().map(|s| Part {
            name: &s.name.text,
            span: s.name.span,
            offset: s.offset.as_deref(),
        }));

        if let Some(b) = db.block(parts[0].name) {
            if parts[0].offset.is_some() {
                self.errors.push(CheckError::BadOffsetBase {
                    span: parts[0].span,
                    base: parts[0].name.to_string(),
                    why: "a block name can't be offset".into(),
                });
                return None;
            }
            let Some(field) = parts.get(1) else {
                self.errors.push(CheckError::NotAValue {
                    span: v.span,
                    what: v.path(),
                });
                return None;
            };
            let _ = field;
            return self.field_path(db.block_template(b), parts[0].name, &parts[1..], v);
        }
        if let Some(t) = self.self_template {
            let tpl = &db.templates[t];
            if tpl.field(parts[0].name).is_some() {
                return self.field_path(tpl, "this action's block", &parts, v);
            }
        }
        let step_like = parts.len() == 2
            && (parts[1].name.eq_ignore_ascii_case("X") || parts[1].name.eq_ignore_ascii_case("T"));
        if step_like && self.ctx.steps.is_some() {
            return self.step_variable(&parts, v);
        }
        // Without a database any block may exist at run time; a lone name in
        // an action bound to a block type can only be one of its fields.
        let lone_field = self.self_template.is_some() && parts.len() == 1;
        if !self.ctx.resolve_blocks && !lone_field {
            return Some(Resolved::any());
        }
        if step_like {
            return self.step_variable(&parts, v);
        }
        self.errors.push(CheckError::UnknownName {
            span: parts[0].span,
            name: parts[0].name.to_string(),
        });
        None
    }

    fn step_variable(&mut self, parts: &[Part], v: &Var) -> Option<Resolved> {
        let Some(steps) = self.ctx.steps else {
            self.errors.push(CheckError::StepOutsideSequence {
                span: v.span,
                name: v.path(),
            });
            return None;
        };
        if !steps.is_empty() && !steps.iter().any(|s| s.eq_ignore_ascii_case(parts[0].name)) {
            self.errors.push(CheckError::UnknownStep {
                span: parts[0].span,
                name: parts[0].name.to_string(),
            });
            return None;
        }
        let ty = if parts[1].name.eq_ignore_ascii_case("X") {
            Ty::Bool
        } else {
            Ty::Real
        };
        Some(Resolved {
            ty,
            writable: false,
            why_readonly: "step variables are maintained by the sequence",
            enum_values: None,
        })
    }

    /// Resolves `field[.sub[.sub]]` within a template.
    fn field_path(
        &mut self,
        tpl: &Template,
        owner: &str,
        parts: &[Part],
        v: &Var,
    ) -> Option<Resolved> {
        let fpart = &parts[0];
        let Some(fi) = tpl.field(fpart.name) else {
            let known = if tpl.fields.len() <= 16 {
                tpl.fields.iter().map(|f| f.name.clone()).collect()
            } else {
                Vec::new()
            };
            self.errors.push(CheckError::UnknownField {
                span: fpart.span,
                field: fpart.name.to_string(),
                owner: owner.to_string(),
                template: tpl.name.clone(),
                known,
            });
            return None;
        };
        if let Some(o) = fpart.offset {
            self.check_field_offset(tpl, fi, o, fpart)?;
        }
        // A constant offset names its field exactly: `PV{1}` is as writable as
        // the field it lands on. Variable offsets are checked at run time.
        let fi = match fpart.offset.and_then(|o| o.int_value()) {
            Some(n) => fi + n as usize,
            None => fi,
        };
        let field = &tpl.fields[fi];
        let readonly = |r: Resolved| {
            if field.readonly {
                Resolved {
                    writable: false,
                    why_readonly: "this field is computed by its block (read-only)",
                    ..r
                }
            } else {
                r
            }
        };
        let rest = &parts[1..];
        match (&field.ty, rest) {
            (FieldType::Alarms(_), []) => {
                self.errors.push(CheckError::NotAValue {
                    span: v.span,
                    what: v.path(),
                });
                None
            }
            (ty, []) => Some(readonly(value_of(ty))),
            (FieldType::Bits { width, .. }, [bit]) => {
                let Some(b) = field.ty.bit_index(bit.name) else {
                    return self.no_sub(bit, field.name.as_str(), &field.ty);
                };
                if let Some(o) = bit.offset {
                    let span = bit.span.to(o.span);
                    if b + 1 >= *width {
                        let why = format!("Bit{b} is the last bit of a {}-bit field", width);
                        self.errors.push(CheckError::BadOffsetBase {
                            span,
                            base: bit.name.to_string(),
                            why,
                        });
                        return None;
                    }
                    if let Some(n) = o.int_value() {
                        if n < 0 || i64::from(b) + i64::from(n) >= i64::from(*width) {
                            let why =
                                format!("Bit{b}{{{n}}} is beyond the last bit, Bit{}", width - 1);
                            self.errors.push(CheckError::BadOffsetBase {
                                span,
                                base: bit.name.to_string(),
                                why,
                            });
                            return None;
                        }
                    }
                }
                Some(readonly(Resolved {
                    ty: Ty::Bool,
                    writable: true,
                    why_readonly: "",
                    enum_values: None,
                }))
            }
            (FieldType::Alarms(names), [sub, more @ ..]) => {
                let suppress = Resolved {
                    ty: Ty::Int,
                    writable: true,
                    why_readonly: "",
                    enum_values: None,
                };
                if sub.name.eq_ignore_ascii_case("Suppress") && more.is_empty() {
                    return Some(suppress);
                }
                let Some(_) = names.iter().position(|n| n.eq_ignore_ascii_case(sub.name)) else {
                    return self.no_sub(sub, field.name.as_str(), &field.ty);
                };
                match more {
                    [] => Some(Resolved {
                        ty: Ty::Bool,
                        writable: false,
                        why_readonly:
                            "an alarm's state is set by its block; write its .Suppress instead",
                        enum_values: None,
                    }),
                    [s] if s.name.eq_ignore_ascii_case("Suppress") => Some(suppress),
                    [s, ..] => self.no_sub(s, sub.name, &FieldType::Bool),
                }
            }
            (_, [sub, ..]) => {
                let owner_ty = field.ty.clone();
                self.no_sub(sub, field.name.as_str(), &owner_ty)
            }
        }
    }

    fn no_sub(&mut self, part: &Part, field: &str, ty: &FieldType) -> Option<Resolved> {
        let field_type = if field.eq_ignore_ascii_case("") {
            ""
        } else {
            ty.keyword()
        };
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
    fn check_field_offset(
        &mut self,
        tpl: &Template,
        fi: usize,
        o: &Expr,
        part: &Part,
    ) -> Option<()> {
        let kind = &tpl.fields[fi].ty;
        let run = tpl.fields[fi..]
            .iter()
            .take_while(|f| f.ty.same_kind(kind))
            .count();
        let span = part.span.to(o.span);
        let base = part.name.to_string();
        if run < 2 {
            let why = match tpl.fields.get(fi + 1) {
                Some(next) => format!(
                    "the next field, {}, is {} but this is {}",
                    next.name,
                    next.ty.keyword(),
                    kind.keyword()
                ),
                None => "it is the last field of its block".to_string(),
            };
            self.errors
                .push(CheckError::BadOffsetBase { span, base, why });
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
                self.errors
                    .push(CheckError::BadOffsetBase { span, base, why });
                return None;
            }
        }
        Some(())
    }
}

/// The value type of a whole field.
fn value_of(ty: &FieldType) -> Resolved {
    let (ty, enum_values) = match ty {
        FieldType::Real => (Ty::Real, None),
        FieldType::Int | FieldType::Bits { .. } => (Ty::Int, None),
        FieldType::Bool => (Ty::Bool, None),
        FieldType::Enum(v) => (Ty::Text, Some(v.clone())),
        FieldType::String | FieldType::Date | FieldType::Time => (Ty::Text, None),
        FieldType::Bseq => (Ty::Bytes, None),
        FieldType::Wstr => (Ty::WStr, None),
        FieldType::Alarms(_) => (Ty::Any, None),
    };
    Resolved {
        ty,
        writable: true,
        why_readonly: "",
        enum_values,
    }
}
