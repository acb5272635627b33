//! Hover: what a block, field, function, step, action, label, FST command
//! or TLP is, from the database and the function table.

use crate::resolve::{Ctx, Sym};
use crate::server::{Lang, Server};
use linc_compiler::fst::commands::Cmd;
use linc_compiler::fst::tlp;
use linc_format::db::InitValue;
use linc_format::{Database, FieldType};
use lsp_types::{Hover, HoverContents, HoverParams, MarkupContent, MarkupKind};

/// The functions page, for each function's one-line description.
const FUNCTIONS_PAGE: &str = include_str!("../../docs/functions.md");

pub fn hover(server: &Server, p: &HoverParams) -> Option<Hover> {
    let pos = &p.text_document_position_params;
    let doc = server.doc(&pos.text_document.uri)?;
    let offset = doc.index.offset(&doc.text, pos.position);
    let ctx = Ctx::new(server, doc);
    let (text, start, end) = match doc.lang {
        Lang::Fst => fst(&ctx, offset)?,
        Lang::Json | Lang::Other => return None,
        _ => source(&ctx, offset)?,
    };
    Some(Hover {
        contents: HoverContents::Markup(MarkupContent { kind: MarkupKind::Markdown, value: text }),
        range: Some(doc.index.range(&doc.text, start, end)),
    })
}

fn source(ctx: &Ctx, offset: usize) -> Option<(String, usize, usize)> {
    if let Some((sym, s, e)) = ctx.symbol_at(offset) {
        return Some((describe(ctx, &sym), s, e));
    }
    let (word, _, _) = ctx.word_at(offset)?;
    if ctx.db().is_none() && !is_keyword(ctx.text((word.start, word.end))) {
        let why = match ctx.file {
            Some(f) => format!("the database `{}` does not load", f.path.display()),
            None => "no strategy database in the workspace names this file".to_string(),
        };
        return Some((
            format!(
                "`{}`: {why}, so it is checked without one (as `linc check` without `--db`).",
                ctx.text((word.start, word.end))
            ),
            word.start,
            word.end,
        ));
    }
    None
}

fn is_keyword(w: &str) -> bool {
    crate::symbols::KEYWORDS.iter().any(|k| k.eq_ignore_ascii_case(w))
}

/// The Markdown shown for a symbol.
pub fn describe(ctx: &Ctx, sym: &Sym) -> String {
    let db = ctx.names_db();
    match sym {
        Sym::Block(b) => block(db, *b),
        Sym::Alias(i) => {
            let a = &db.aliases[*i];
            let target = a.target.join(".");
            let mut out = format!("**{}**: alias for `{target}`", a.name);
            if let Some(sym) = alias_target(db, &a.target) {
                out.push_str("\n\n");
                out.push_str(&describe(ctx, &sym));
            }
            out
        }
        Sym::Field { block, template, field, sub } => field_text(db, *block, *template, *field, sub.as_deref()),
        _ => local(ctx, sym),
    }
}

fn alias_target(db: &Database, target: &[String]) -> Option<Sym> {
    let b = db.block(target.first()?)?;
    let template = db.blocks[b].template;
    let field = db.templates[template].field(target.get(1)?)?;
    Some(Sym::Field { block: Some(b), template, field, sub: target.get(2).cloned() })
}

fn local(ctx: &Ctx, sym: &Sym) -> String {
    match sym {
        Sym::Function(sig) => format!("```\n{sig}\n```\n\n{}", function_line(sig.name)),
        Sym::Step(name) => step(ctx, name),
        Sym::Action(name) => format!("**ACTION {name}** (an action of this sequence)"),
        Sym::Label(name) => format!("**{name}:** a rung label (a `JUMP {name}` continues there)"),
        _ => String::new(),
    }
}

fn block(db: &Database, b: usize) -> String {
    let blk = &db.blocks[b];
    let t = db.block_template(b);
    let period = db.task(blk.task).map(|t| format!(" ({} s)", t.period)).unwrap_or_default();
    let mut out = format!("**{}**: block of type `{}`, task {}{period}", blk.name, t.name, blk.task);
    if !t.doc.is_empty() {
        out.push_str("\n\n");
        out.push_str(&t.doc);
    }
    out
}

fn field_text(db: &Database, block: Option<usize>, template: usize, field: usize, sub: Option<&str>) -> String {
    let t = &db.templates[template];
    let f = &t.fields[field];
    let owner = block.map_or_else(|| format!("(own block, {})", t.name), |b| db.blocks[b].name.clone());
    let mut out = format!("**{owner}.{}** : `{}`", f.name, f.ty.keyword());
    if f.readonly {
        out.push_str(" (read-only)");
    }
    out.push_str("\n\n");
    out.push_str(&range(&f.ty));
    if let Some(b) = block {
        let value = db.blocks[b].values.iter().find(|(i, _)| *i == field).map(|(_, v)| value(v));
        out.push_str(&format!("\n\nIn the database: {}", value.unwrap_or_else(|| "the type's default".into())));
    }
    if let Some(s) = sub {
        out.push_str(&format!("\n\n`.{s}`: {}", sub_text(&f.ty, s)));
    }
    out
}

fn range(ty: &FieldType) -> String {
    match ty {
        FieldType::Real => "REAL: a single-precision number".into(),
        FieldType::Int => "INT: -2147483648 … 2147483647".into(),
        FieldType::Bool => "BOOL: FALSE or TRUE".into(),
        FieldType::Bits { width, names } => {
            let max = (1u32 << width) - 1;
            let named = if names.is_empty() { String::new() } else { format!("; bits named {}", names.join(", ")) };
            format!("{width} bits: 0 … {max}, bits Bit0 … Bit{}{named}", width - 1)
        }
        FieldType::Enum(values) => format!("one of: {}", values.join(", ")),
        FieldType::Alarms(names) => format!("alarms: {}", names.join(", ")),
        other => format!("{}: a string of at most 65,535 bytes", other.keyword()),
    }
}

fn sub_text(ty: &FieldType, sub: &str) -> String {
    match ty {
        FieldType::Bits { .. } => match ty.bit_index(sub) {
            Some(i) => format!("bit {i}"),
            None => "not a bit of this field".into(),
        },
        FieldType::Alarms(_) => "an alarm (TRUE while in alarm; `.Suppress` is its suppression timer)".into(),
        _ => "not a sub-field".into(),
    }
}

fn value(v: &InitValue) -> String {
    match v {
        InitValue::Num(n) => format!("`{n}`"),
        InitValue::Bool(b) => format!("`{}`", if *b { "TRUE" } else { "FALSE" }),
        InitValue::Text(t) => format!("`\"{t}\"`"),
        InitValue::Active(a) => format!("active alarms {}", a.join(", ")),
    }
}

/// The first line the functions page gives a function: its table row's
/// description, or the sentence of the paragraph that names it.
pub fn function_line(name: &str) -> String {
    let call = format!("`{name}(");
    for line in FUNCTIONS_PAGE.lines() {
        if let Some(rest) = line.strip_prefix("| ").filter(|l| l.starts_with(&call)) {
            return rest.rsplit(" | ").next().unwrap_or("").trim_end_matches(" |").trim().to_string();
        }
    }
    FUNCTIONS_PAGE
        .lines()
        .find(|l| l.contains(&call))
        .map(|l| l.trim().to_string())
        .unwrap_or_else(|| "See docs/functions.md.".into())
}

fn step(ctx: &Ctx, name: &str) -> String {
    let (seq, _) = linc_compiler::sfc::parser::parse(&ctx.doc.text);
    let mut charts = vec![&seq.chart];
    for a in &seq.actions {
        if let linc_compiler::sfc::ast::ActionBody::Chart(c) = &a.body {
            charts.push(c);
        }
    }
    for s in charts.iter().flat_map(|c| &c.steps) {
        if s.name.text.eq_ignore_ascii_case(name) {
            let kind = if s.initial { "INITIAL_STEP" } else { "STEP" };
            let assocs: Vec<String> = s
                .assocs
                .iter()
                .map(|a| match &a.time {
                    Some((t, _)) => format!("{}({}, {t} s)", a.action.text, a.qualifier.text),
                    None => format!("{}({})", a.action.text, a.qualifier.text),
                })
                .collect();
            let list = if assocs.is_empty() { "no actions".to_string() } else { assocs.join("; ") };
            return format!(
                "**{kind} {}**: {list}\n\n`{0}.X` is TRUE while it is active; `{0}.T` its time active (s).",
                s.name.text
            );
        }
    }
    format!("**STEP {name}**")
}

/// FST: the command of a CMD cell, or the point parameter of an argument.
fn fst(ctx: &Ctx, offset: usize) -> Option<(String, usize, usize)> {
    let (col, s, e) = crate::text::fst_cell(&ctx.doc.text, offset)?;
    let cell = ctx.doc.text[s..e].trim().trim_matches('"').trim();
    let range = (s, e);
    match col {
        2 => {
            let cmd = Cmd::parse(cell)?;
            Some((format!("**{}** ({}): {}", cmd.text(), cmd.category(), cmd.doc()), range.0, range.1))
        }
        3 | 4 => {
            let db = ctx.db()?;
            let syntax = tlp::parse(cell).ok()?;
            if let tlp::Syntax::Number(n) = syntax {
                return Some((format!("the constant `{n}`"), range.0, range.1));
            }
            let points = tlp::Points::new(db);
            let (block, field) = tlp::resolve(&points, &syntax).ok()?;
            Some((tlp_text(db, block, field), range.0, range.1))
        }
        _ => None,
    }
}

fn tlp_text(db: &Database, block: usize, field: usize) -> String {
    let t = db.block_template(block);
    let logical = db.blocks[..block].iter().filter(|b| b.template == db.blocks[block].template).count();
    let f = &t.fields[field];
    let number = t.point_type(db.device).map_or_else(|| "-".to_string(), |n| n.to_string());
    let mut out = format!(
        "**{},{}**: point type {number} ({}), logical {logical}, parameter {field}: `{}`",
        db.blocks[block].name,
        f.name,
        t.name,
        f.ty.keyword()
    );
    if f.readonly {
        out.push_str(" (read-only)");
    }
    out
}
