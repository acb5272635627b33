//! `linc ladder show`: each rung drawn in text as a diagram between two
//! rails, as the LINtools ladder editor shows it (its SVG twin is
//! [`crate::ladder`]; both lay rungs out from the compiler's ladder tree). Contacts `--[ x ]--` / `--[/x]--`,
//! parallel branches joined by `+` and `|`, function boxes as a labelled
//! branch group, coils `( x )` `(/x)` `(S x)` `(R x)`, jumps `>> L`,
//! variable outputs `{ t := v }`. Element text is the source as written.

use crate::ladder::{Ran, RanRungs};
use linc_compiler::diag::{Diagnostic, Span};
use linc_compiler::ladder::ast::{Action, CoilKind, Cond, Output, Rung};
use linc_compiler::ladder::parser;
use linc_format::Code;

/// The most characters one rung's drawing may have. A drawing is as wide as
/// its widest branch on every row, so a few long contacts in many parallel
/// branches draw far larger than their text; a rung over this is refused
/// (E0314) instead of drawn.
pub const MAX_DRAWN: usize = 1 << 20;

/// Rungs up to this wide share the action's right rail; a wider one (a very
/// long series) keeps its own, so that it does not widen every other rung.
const ALIGN: usize = 200;

/// `text` padded with `fill` to `width` characters (`format!`'s width is
/// limited to 65 535, which a long series exceeds).
fn pad(text: &str, width: usize, fill: char) -> String {
    let n = width.saturating_sub(text.chars().count());
    let mut out = String::with_capacity(text.len() + n);
    out.push_str(text);
    out.extend(std::iter::repeat_n(fill, n));
    out
}

/// The state of an element after a run (`linc ladder show --values`): the
/// value of the ST expression at `span` (a contact's operand, a coil's
/// target), or `None` when it is not known.
pub type Values<'v> = &'v dyn Fn(Span) -> Option<bool>;

/// How an element is drawn with its state: a powered contact or coil gets
/// `=` wires (the editor's highlight), an unpowered one keeps `-`, and one
/// whose state is unknown is drawn plain.
fn wire(powered: Option<bool>) -> &'static str {
    match powered {
        Some(true) => "==",
        _ => "--",
    }
}

/// A drawn element: rows of equal width; the wire runs along row 0.
struct Cell {
    rows: Vec<String>,
    width: usize,
}

impl Cell {
    fn one(text: String) -> Cell {
        let width = text.chars().count();
        Cell { rows: vec![text], width }
    }

    /// Row `i`, padded to the cell's width with `fill` (the wire on row 0).
    fn row(&self, i: usize) -> String {
        let (text, fill) = match self.rows.get(i) {
            Some(r) => (r.as_str(), if i == 0 { '-' } else { ' ' }),
            None => ("", ' '),
        };
        pad(text, self.width, fill)
    }
}

fn slice(src: &str, span: Span) -> String {
    let text = src.get(span.start..span.end).unwrap_or("?");
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Elements side by side, aligned on the wire.
fn series(cells: Vec<Cell>) -> Cell {
    let height = cells.iter().map(|c| c.rows.len()).max().unwrap_or(1);
    let rows = (0..height).map(|i| cells.iter().map(|c| c.row(i)).collect::<String>()).collect();
    Cell { rows, width: cells.iter().map(|c| c.width).sum() }
}

/// Branches one under the other, joined left and right.
fn parallel(cells: Vec<Cell>) -> Cell {
    let width = cells.iter().map(|c| c.width).max().unwrap_or(0);
    let last_wire: usize = cells.iter().take(cells.len().saturating_sub(1)).map(|c| c.rows.len()).sum();
    let mut rows = Vec::new();
    for c in &cells {
        for i in 0..c.rows.len() {
            let at = rows.len();
            let body = pad(&c.row(i), width, if i == 0 { '-' } else { ' ' });
            let joint = if i == 0 {
                '+'
            } else if at < last_wire {
                '|'
            } else {
                ' '
            };
            let lead = if at == 0 { "--" } else { "  " };
            let wire = if i == 0 { '-' } else { ' ' };
            rows.push(format!("{lead}{joint}{wire}{body}{wire}{joint}"));
        }
    }
    Cell { rows, width: width + 6 }
}

fn cond(src: &str, c: &Cond, values: Values) -> Cell {
    match c {
        Cond::Contact { negated, expr, .. } => {
            let inner = slice(src, expr.span);
            // A contact passes power when its operand is TRUE ([x]) or FALSE ([/x]).
            let w = wire(values(expr.span).map(|v| v != *negated));
            Cell::one(if *negated { format!("{w}[/{inner}]{w}") } else { format!("{w}[ {inner} ]{w}") })
        }
        Cond::Series(v) => series(v.iter().map(|x| cond(src, x, values)).collect()),
        Cond::Parallel(v, _) if v.len() == 1 => cond(src, &v[0], values),
        Cond::Parallel(v, _) => parallel(v.iter().map(|x| cond(src, x, values)).collect()),
        Cond::Box { op, args, .. } => {
            let inputs = if args.len() == 1 {
                cond(src, &args[0], values)
            } else {
                parallel(args.iter().map(|x| cond(src, x, values)).collect())
            };
            series(vec![inputs, Cell::one(format!("--[{}]", op.name()))])
        }
    }
}

fn output(src: &str, o: &Output, values: Values) -> Cell {
    match o {
        Output::Coil { kind, target, .. } => {
            let t = slice(src, target.span);
            let coil = match kind {
                CoilKind::Normal => format!("( {t} )"),
                CoilKind::Negated => format!("(/{t})"),
                CoilKind::Set => format!("(S {t})"),
                CoilKind::Reset => format!("(R {t})"),
            };
            Cell::one(format!("{}{coil}", wire(values(target.span))))
        }
        Output::Jump { label, .. } => Cell::one(format!("-->> {}", label.text)),
        Output::Assign(s) => Cell::one(format!("--{{ {} }}", slice(src, stmt_span(s)).trim_end_matches(';'))),
    }
}

fn stmt_span(s: &linc_compiler::st::ast::Stmt) -> Span {
    match s {
        linc_compiler::st::ast::Stmt::Assign { span, .. } => *span,
        _ => Span::default(),
    }
}

/// An upper bound of the width and height of `c`'s drawing, found without
/// drawing it.
fn size(c: &Cond) -> (usize, usize) {
    let many =
        |v: &[Cond]| v.iter().map(size).fold((0usize, 0usize), |(w, h), (cw, ch)| (w.max(cw), h.saturating_add(ch)));
    match c {
        Cond::Contact { expr, .. } => (expr.span.end - expr.span.start + 8, 1),
        Cond::Series(v) => {
            v.iter().map(size).fold((0usize, 1usize), |(w, h), (cw, ch)| (w.saturating_add(cw), h.max(ch)))
        }
        Cond::Parallel(v, _) if v.len() == 1 => size(&v[0]),
        Cond::Parallel(v, _) => {
            let (w, h) = many(v);
            (w + 6, h)
        }
        Cond::Box { args, .. } if args.len() == 1 => {
            let (w, h) = size(&args[0]);
            (w + 8, h)
        }
        Cond::Box { args, .. } => {
            let (w, h) = many(args);
            (w + 14, h)
        }
    }
}

/// An upper bound of the width and height of a rung's drawing.
fn rung_size(src: &str, r: &Rung) -> (usize, usize) {
    let (w, h) = r.cond.as_ref().map_or((2, 1), size);
    let out = match &r.output {
        Output::Coil { target, .. } => target.span.end - target.span.start + 6,
        Output::Jump { label, .. } => label.text.len() + 4,
        Output::Assign(s) => slice(src, stmt_span(s)).len() + 6,
    };
    (w + out + 4, h)
}

/// One rung between the rails, its label on the line above. A rung that
/// did not run (a taken jump skipped it) is drawn with no element passing
/// power and says so under it.
fn rung(src: &str, r: &Rung, width: usize, (values, ran): (Values, Option<&RanRungs>), out: &mut String) {
    if let Some(l) = &r.label {
        out.push_str(&format!("{}:\n", l.text));
    }
    let skipped = ran.is_some_and(|ran| !ran.ran(r.span));
    let values: Values = if skipped { &|_| None } else { values };
    let left = r.cond.as_ref().map_or_else(|| Cell::one("--".into()), |c| cond(src, c, values));
    let body = series(vec![left, output(src, &r.output, values)]);
    for i in 0..body.rows.len() {
        let line = if i == 0 { pad(&body.row(0), width, '-') + "--" } else { pad(&body.row(i), width, ' ') + "  " };
        out.push_str(&format!("  |{line}|\n"));
    }
    out.push_str(if skipped { "  |  (not run: a jump skipped it)\n" } else { "  |\n" });
}

/// The rungs of `a` too large to draw (E0314), each located at its rung.
fn too_large(src: &str, a: &Action) -> Vec<Diagnostic> {
    let mut errors = Vec::new();
    for r in &a.rungs {
        let (w, h) = rung_size(src, r);
        if w.saturating_mul(h) > MAX_DRAWN {
            errors.push(
                Diagnostic::error(Code::E0314, "rung too large to draw", r.span)
                    .label(format!("its drawing would be about {w} characters wide and {h} rows high"))
                    .help(format!(
                        "`linc ladder show` draws rungs of up to {MAX_DRAWN} characters; split the rung, or read it with `linc ladder to-st`"
                    )),
            );
        }
    }
    errors
}

/// Draws one action, elements in the state `values` gives them; `Err` with
/// the rungs too large to draw, and nothing drawn, if it has any.
fn action(src: &str, a: &Action, shown: (Values, Option<&RanRungs>), out: &mut String) -> Result<(), Vec<Diagnostic>> {
    let values = shown.0;
    let errors = too_large(src, a);
    if !errors.is_empty() {
        return Err(errors);
    }
    out.push_str(&format!("(* {} *)\n", a.name.text));
    let width = a
        .rungs
        .iter()
        .map(|r| {
            let left = r.cond.as_ref().map_or(2, |c| cond(src, c, values).width);
            left + output(src, &r.output, values).width
        })
        .filter(|&w| w <= ALIGN)
        .max()
        .unwrap_or(0);
    for r in &a.rungs {
        rung(src, r, width, shown, out);
    }
    out.push_str("  |_End\n");
    Ok(())
}

/// Adds every span of `a` whose value `--values` shows to `out`: contacts'
/// operands and coils' targets.
fn element_spans_of(a: &Action, out: &mut Vec<Span>) {
    fn walk(c: &Cond, out: &mut Vec<Span>) {
        match c {
            Cond::Contact { expr, .. } => out.push(expr.span),
            Cond::Series(v) | Cond::Parallel(v, _) | Cond::Box { args: v, .. } => v.iter().for_each(|x| walk(x, out)),
        }
    }
    for r in &a.rungs {
        if let Some(c) = &r.cond {
            walk(c, out);
        }
        if let Output::Coil { target, .. } = &r.output {
            out.push(target.span);
        }
    }
}

/// The diagram of a ladder file (`linc ladder show`), or its syntax errors
/// and the rungs too large to draw; `values` gives the state of each
/// element (contact operands and coil targets, by span), for `--values`,
/// and `ran` the lines the last cycle ran ([`crate::ladder::Ran`]).
pub fn draw(src: &str, stem: &str, values: Values, ran: Ran) -> Result<String, Vec<Diagnostic>> {
    let mut out = String::new();
    draw_to(src, stem, (values, ran), &mut |s| out.push_str(s))?;
    Ok(out)
}

/// [`draw`], handing the drawing to `write` one action at a time. The file
/// is read twice, for the errors and then for the drawing, so that only one
/// action is held and nothing is drawn when there are errors.
pub fn draw_to(
    src: &str,
    stem: &str,
    (values, ran): (Values, Ran),
    write: &mut dyn FnMut(&str),
) -> Result<(), Vec<Diagnostic>> {
    let ran = ran.map(|lines| RanRungs::new(src, lines));
    let mut oversized = Vec::new();
    let mut diagnostics = parser::parse_each(src, stem, &mut |a| oversized.extend(too_large(src, &a)));
    diagnostics.extend(oversized);
    if diagnostics.iter().any(Diagnostic::is_error) {
        diagnostics.sort_by_key(|d| (d.span.start, d.span.end));
        return Err(diagnostics);
    }
    let mut first = true;
    parser::parse_each(src, stem, &mut |a| {
        let mut out = String::new();
        if !std::mem::take(&mut first) {
            out.push('\n');
        }
        if let Err(e) = action(src, &a, (values, ran.as_ref()), &mut out) {
            diagnostics.extend(e);
        }
        write(&out);
    });
    if diagnostics.iter().any(Diagnostic::is_error) {
        return Err(diagnostics);
    }
    Ok(())
}

/// The spans of the elements `--values` shows, for the caller to evaluate.
pub fn element_spans(src: &str, stem: &str) -> Vec<Span> {
    let mut out = Vec::new();
    parser::parse_each(src, stem, &mut |a| element_spans_of(&a, &mut out));
    out
}
