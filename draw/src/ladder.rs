//! Ladder rungs between their rails (docs/pictures.md), as `linc ladder
//! show` draws them in text: contacts `| |` and `|/|` with their operand
//! above, series side by side, parallel branches one under the other
//! joined left and right, function boxes with their inputs, the four
//! coils, jumps and variable outputs at the right rail. With a run's
//! state, wires that carry power are drawn `on` (the editor's power flow)
//! and each contact shows its value; with the lines the run executed, a
//! rung that did not run (a taken jump skipped it) carries no power and
//! is drawn `skipped`, as CODESYS and TwinCAT grey out code that did not
//! run in the last cycle.

use crate::geom::{p, Geometry, Link, Rect, Solid, P};
use crate::svg::{id, num, text_width, Svg};
use linc_compiler::diag::span::Span;
use linc_compiler::ladder::ast::{Action, BoxOp, CoilKind, Cond, Output, Rung};

/// The truth of an element's operand (a contact's expression, a coil's
/// target) by its span, after a run.
pub type Look<'a> = Option<&'a dyn Fn(Span) -> Option<bool>>;

/// The source lines (1-based, sorted) on which a statement started in the
/// actions' last execution, as the runtime counted them: a rung ran when a
/// statement of one of its lines did. `None` when it is not known (no
/// run), and power flow is then worked out from the values alone.
pub type Ran<'a> = Option<&'a [u32]>;

/// Which rungs of a source ran, from [`Ran`]'s lines: shared by the SVG
/// and the text drawing (`linc ladder show --values`), so both tell the
/// same rungs apart.
pub struct RanRungs<'a> {
    lines: &'a [u32],
    /// The offset each line of the source starts at.
    line_starts: Vec<usize>,
}

impl<'a> RanRungs<'a> {
    pub fn new(src: &str, lines: &'a [u32]) -> RanRungs<'a> {
        let line_starts = std::iter::once(0).chain(src.match_indices('\n').map(|(i, _)| i + 1)).collect();
        RanRungs { lines, line_starts }
    }

    /// The 1-based line of byte `offset`.
    fn line(&self, offset: usize) -> u32 {
        self.line_starts.partition_point(|&s| s <= offset) as u32
    }

    /// Whether the rung at `span` ran: some statement started on one of
    /// its lines.
    pub fn ran(&self, span: Span) -> bool {
        let (first, last) = (self.line(span.start), self.line(span.end.saturating_sub(1).max(span.start)));
        let at = self.lines.partition_point(|&l| l < first);
        self.lines.get(at).is_some_and(|&l| l <= last)
    }
}

const RAIL: f64 = 16.0;
const JOIN: f64 = 12.0;
const WY: f64 = 26.0;

struct Ctx<'a> {
    src: &'a str,
    look: Look<'a>,
    ran: Option<RanRungs<'a>>,
}

impl Ctx<'_> {
    fn text(&self, span: Span) -> String {
        self.src.get(span.start..span.end).unwrap_or("?").split_whitespace().collect::<Vec<_>>().join(" ")
    }

    fn truth(&self, span: Span) -> Option<bool> {
        self.look.and_then(|f| f(span))
    }

    /// Whether the rung at `span` ran in the last execution (`None`: not
    /// known).
    fn executed(&self, span: Span) -> Option<bool> {
        self.ran.as_ref().map(|r| r.ran(span))
    }

    fn elem_h(&self) -> f64 {
        if self.look.is_some() {
            54.0
        } else {
            40.0
        }
    }
}

/// Width, height and the wire's height of a drawn condition.
#[derive(Clone, Copy)]
struct Size {
    w: f64,
    h: f64,
    wy: f64,
}

fn size(ctx: &Ctx, c: &Cond) -> Size {
    match c {
        Cond::Contact { expr, .. } => {
            Size { w: (text_width(&ctx.text(expr.span)) + 12.0).max(48.0), h: ctx.elem_h(), wy: WY }
        }
        Cond::Series(v) => {
            let sizes: Vec<Size> = v.iter().map(|x| size(ctx, x)).collect();
            let wy = sizes.iter().map(|s| s.wy).fold(0.0, f64::max);
            let h = sizes.iter().map(|s| wy - s.wy + s.h).fold(0.0, f64::max);
            Size { w: sizes.iter().map(|s| s.w).sum(), h, wy }
        }
        Cond::Parallel(v, _) if v.len() == 1 => size(ctx, &v[0]),
        Cond::Parallel(v, _) => {
            let sizes: Vec<Size> = v.iter().map(|x| size(ctx, x)).collect();
            let w = sizes.iter().map(|s| s.w).fold(0.0, f64::max) + 2.0 * JOIN;
            Size { w, h: sizes.iter().map(|s| s.h).sum(), wy: sizes.first().map_or(WY, |s| s.wy) }
        }
        Cond::Box { args, .. } => {
            let sizes: Vec<Size> = args.iter().map(|x| size(ctx, x)).collect();
            let w = sizes.iter().map(|s| s.w).fold(0.0, f64::max) + JOIN + 44.0 + JOIN;
            Size { w, h: sizes.iter().map(|s| s.h).sum::<f64>().max(40.0), wy: sizes.first().map_or(WY, |s| s.wy) }
        }
    }
}

/// Where the drawing goes.
struct Out<'a> {
    svg: &'a mut Svg,
    geo: &'a mut Geometry,
}

fn wire(o: &mut Out, a: P, b: P, on: Option<bool>) {
    o.svg.line(a, b, if on == Some(true) { "wire on" } else { "wire" });
    o.geo.wires.push((a, b));
}

/// Draws `c` with its top left at (x, y), power `pin` coming in; returns
/// the power going out (`None` when the state is not known).
fn cond(ctx: &Ctx, c: &Cond, x: f64, y: f64, pin: Option<bool>, o: &mut Out) -> Option<bool> {
    let s = size(ctx, c);
    match c {
        Cond::Contact { negated, expr, .. } => contact(ctx, (*negated, expr.span), x, y, s, pin, o),
        Cond::Series(v) => {
            let mut at = x;
            let mut power = pin;
            for item in v {
                let cs = size(ctx, item);
                power = cond(ctx, item, at, y + s.wy - cs.wy, power, o);
                at += cs.w;
            }
            power
        }
        Cond::Parallel(v, _) if v.len() == 1 => cond(ctx, &v[0], x, y, pin, o),
        Cond::Parallel(v, _) => {
            let (mut top, mut out) = (y, Some(false));
            let (first_y, mut last_y) = (y + s.wy, y + s.wy);
            for item in v {
                let cs = size(ctx, item);
                let wy = top + cs.wy;
                wire(o, p(x + if top == y { 0.0 } else { JOIN / 2.0 }, wy), p(x + JOIN, wy), pin);
                let branch = cond(ctx, item, x + JOIN, top, pin, o);
                wire(o, p(x + JOIN + cs.w, wy), p(x + s.w - JOIN / 2.0, wy), branch);
                out = or(out, branch);
                last_y = wy;
                top += cs.h;
            }
            wire(o, p(x + JOIN / 2.0, first_y), p(x + JOIN / 2.0, last_y), pin);
            wire(o, p(x + s.w - JOIN / 2.0, first_y), p(x + s.w - JOIN / 2.0, last_y), out);
            wire(o, p(x + s.w - JOIN / 2.0, first_y), p(x + s.w, first_y), out);
            out
        }
        Cond::Box { op, args, .. } => function_box(ctx, (*op, args), x, y, s, pin, o),
    }
}

fn or(a: Option<bool>, b: Option<bool>) -> Option<bool> {
    match (a, b) {
        (Some(true), _) | (_, Some(true)) => Some(true),
        (Some(false), Some(false)) => Some(false),
        _ => None,
    }
}

fn contact(
    ctx: &Ctx,
    (negated, span): (bool, Span),
    x: f64,
    y: f64,
    s: Size,
    pin: Option<bool>,
    o: &mut Out,
) -> Option<bool> {
    let text = ctx.text(span);
    let truth = ctx.truth(span);
    let passes = truth.map(|t| t != negated);
    let out = match (pin, passes) {
        (Some(false), _) | (_, Some(false)) => Some(false),
        (Some(true), Some(true)) => Some(true),
        _ => None,
    };
    let (cx, wy) = (x + s.w / 2.0, y + s.wy);
    let class = if out == Some(true) { "element on" } else { "element" };
    o.svg.open(None, class);
    wire(o, p(x, wy), p(cx - 5.0, wy), pin);
    wire(o, p(cx + 5.0, wy), p(x + s.w, wy), out);
    // The contact joins its two wires: the layout tests count it as wire.
    o.geo.wires.push((p(cx - 5.0, wy), p(cx + 5.0, wy)));
    o.svg.line(p(cx - 5.0, wy - 9.0), p(cx - 5.0, wy + 9.0), "contact");
    o.svg.line(p(cx + 5.0, wy - 9.0), p(cx + 5.0, wy + 9.0), "contact");
    if negated {
        o.svg.line(p(cx - 4.0, wy + 8.0), p(cx + 4.0, wy - 8.0), "contact");
    }
    o.svg.text(cx, y + 11.0, &text, "", "middle");
    if let Some(t) = truth {
        truth_label(o, cx, wy + 24.0, t);
    }
    o.svg.close();
    let tw = text_width(&text);
    o.geo.solids.push(Solid { what: format!("contact {text}"), r: Rect::new(cx - tw / 2.0, y, tw, s.h - 2.0) });
    out
}

/// A contact's or coil's value under it: `TRUE` in the energised colour,
/// `FALSE` dim (class `value true` / `value false`), so a glance tells the
/// state from the colour as well as the word.
fn truth_label(o: &mut Out, x: f64, y: f64, t: bool) {
    o.svg.text(x, y, if t { "TRUE" } else { "FALSE" }, if t { "value true" } else { "value false" }, "middle");
}

fn function_box(
    ctx: &Ctx,
    (op, args): (BoxOp, &[Cond]),
    x: f64,
    y: f64,
    s: Size,
    pin: Option<bool>,
    o: &mut Out,
) -> Option<bool> {
    let inner = s.w - JOIN - 44.0 - JOIN;
    let bx = x + inner + JOIN;
    let mut top = y;
    let mut ins = Vec::new();
    for a in args {
        let cs = size(ctx, a);
        let v = cond(ctx, a, x, top, pin, o);
        wire(o, p(x + cs.w, top + cs.wy), p(bx, top + cs.wy), v);
        ins.push(v);
        top += cs.h;
    }
    let known: Option<Vec<bool>> = ins.iter().copied().collect();
    let out = known.map(|v| match op {
        BoxOp::And => v.iter().all(|&b| b),
        BoxOp::Or => v.iter().any(|&b| b),
        BoxOp::Xor => v.iter().filter(|&&b| b).count() % 2 == 1,
        BoxOp::Not => !v.first().copied().unwrap_or(false),
    });
    let r = Rect::new(bx, y + 4.0, 44.0, s.h - 8.0);
    o.svg.open(None, if out == Some(true) { "function on" } else { "function" });
    o.svg.rect(r, "box");
    o.svg.text(bx + 22.0, y + 18.0, op.name(), "name", "middle");
    o.svg.close();
    o.geo.solids.push(Solid { what: format!("{} box", op.name()), r });
    o.geo.wires.push((p(bx, y + s.wy), p(bx + 44.0, y + s.wy)));
    wire(o, p(bx + 44.0, y + s.wy), p(x + s.w, y + s.wy), out);
    out
}

/// The output at the right rail: its width.
fn output_w(ctx: &Ctx, out: &Output) -> f64 {
    match out {
        Output::Coil { target, .. } => (text_width(&ctx.text(target.span)) + 12.0).max(48.0),
        Output::Jump { label, .. } => text_width(&label.text) + 30.0,
        Output::Assign(s) => text_width(&assign_text(ctx, s)) + 16.0,
    }
}

fn assign_text(ctx: &Ctx, s: &linc_compiler::st::ast::Stmt) -> String {
    match s {
        linc_compiler::st::ast::Stmt::Assign { span, .. } => ctx.text(*span).trim_end_matches(';').trim().to_string(),
        _ => String::new(),
    }
}

fn output(ctx: &Ctx, out: &Output, x: f64, y: f64, pin: Option<bool>, o: &mut Out) -> Rect {
    let w = output_w(ctx, out);
    let wy = y + WY;
    match out {
        Output::Coil { kind, target, .. } => {
            let cx = x + w / 2.0;
            let text = ctx.text(target.span);
            o.svg.open(None, if pin == Some(true) { "element output on" } else { "element output" });
            wire(o, p(x, wy), p(cx - 9.0, wy), pin);
            let d = format!(
                "M {} {} A 12 12 0 0 0 {} {} M {} {} A 12 12 0 0 1 {} {}",
                num(cx - 5.0),
                num(wy - 9.0),
                num(cx - 5.0),
                num(wy + 9.0),
                num(cx + 5.0),
                num(wy - 9.0),
                num(cx + 5.0),
                num(wy + 9.0)
            );
            o.svg.path(&d, "coil");
            let mark = match kind {
                CoilKind::Normal => "",
                CoilKind::Negated => "/",
                CoilKind::Set => "S",
                CoilKind::Reset => "R",
            };
            if !mark.is_empty() {
                o.svg.text(cx, wy + 4.0, mark, "name", "middle");
            }
            wire(o, p(cx + 9.0, wy), p(x + w, wy), pin);
            o.svg.text(cx, y + 11.0, &text, "", "middle");
            if let Some(t) = ctx.truth(target.span) {
                truth_label(o, cx, wy + 24.0, t);
            }
            o.svg.close();
            let tw = text_width(&text).max(24.0);
            Rect::new(cx - tw / 2.0, y, tw, ctx.elem_h() - 2.0)
        }
        Output::Jump { label, .. } => {
            o.svg.open(None, "jump");
            wire(o, p(x, wy), p(x + 14.0, wy), pin);
            o.svg.arrow(p(x + 22.0, wy), 1.0, 0.0);
            o.svg.text(x + 26.0, wy + 4.0, &label.text, "name", "start");
            o.svg.close();
            Rect::new(x + 14.0, wy - 8.0, w - 14.0, 16.0)
        }
        Output::Assign(s) => {
            let text = assign_text(ctx, s);
            o.svg.open(None, "assign");
            wire(o, p(x, wy), p(x + 4.0, wy), pin);
            let r = Rect::new(x + 4.0, wy - 10.0, w - 8.0, 20.0);
            o.svg.rect(r, "box");
            o.svg.text(x + 8.0, wy + 4.0, &text, "", "start");
            wire(o, p(x + w - 4.0, wy), p(x + w, wy), pin);
            o.svg.close();
            r
        }
    }
}

/// The truth of a condition from its contacts' values.
fn truth(ctx: &Ctx, c: &Cond) -> Option<bool> {
    match c {
        Cond::Contact { negated, expr, .. } => ctx.truth(expr.span).map(|t| t != *negated),
        Cond::Series(v) => v.iter().try_fold(true, |acc, x| Some(acc && truth(ctx, x)?)),
        Cond::Parallel(v, _) => v.iter().try_fold(false, |acc, x| Some(acc || truth(ctx, x)?)),
        Cond::Box { op, args, .. } => {
            let v: Option<Vec<bool>> = args.iter().map(|a| truth(ctx, a)).collect();
            let v = v?;
            Some(match op {
                BoxOp::And => v.iter().all(|&b| b),
                BoxOp::Or => v.iter().any(|&b| b),
                BoxOp::Xor => v.iter().filter(|&&b| b).count() % 2 == 1,
                BoxOp::Not => !v.first().copied().unwrap_or(false),
            })
        }
    }
}

/// The actions of a ladder file, drawn one under the other with the same
/// rails; rungs numbered from 1 through the file.
pub fn file(src: &str, actions: &[Action], look: Look, ran: Ran) -> (String, Geometry) {
    let ctx = Ctx { src, look, ran: ran.map(|lines| RanRungs::new(src, lines)) };
    let body_w = actions
        .iter()
        .flat_map(|a| &a.rungs)
        .map(|r| r.cond.as_ref().map_or(0.0, |c| size(&ctx, c).w) + output_w(&ctx, &r.output) + 32.0)
        .fold(200.0, f64::max);
    let (left, right) = (RAIL, RAIL + body_w);
    let mut svg = Svg::new();
    let mut geo = Geometry::default();
    let mut y = 8.0;
    let mut number = 0;
    for a in actions {
        svg.open(Some(&id("action-", &a.name.text)), "action");
        svg.text(left, y + 12.0, &format!("ACTION {}", a.name.text), "name", "start");
        geo.solids.push(Solid {
            what: format!("title {}", a.name.text),
            r: Rect::new(left, y, text_width(&a.name.text) + 50.0, 16.0),
        });
        y += 22.0;
        let top = y;
        for r in &a.rungs {
            number += 1;
            y = rung(&ctx, r, number, (left, right, y), &mut Out { svg: &mut svg, geo: &mut geo });
        }
        svg.line(p(left, top), p(left, y), "rail");
        svg.line(p(right, top), p(right, y), "rail");
        geo.nodes.push((format!("rail-left-{}", a.name.text), Rect::new(left, top, 0.0, y - top)));
        geo.nodes.push((format!("rail-right-{}", a.name.text), Rect::new(right, top, 0.0, y - top)));
        for l in geo.links.iter_mut().filter(|l| l.from.is_empty()) {
            l.from = format!("rail-left-{}", a.name.text);
        }
        svg.close();
        y += 12.0;
    }
    (svg.finish("ld", right + RAIL, y), geo)
}

/// One rung at `y`; returns the y under it. A rung that did not run gets
/// no power from the left rail, so nothing in it is drawn `on`.
fn rung(ctx: &Ctx, r: &Rung, number: usize, (left, right, mut y): (f64, f64, f64), o: &mut Out) -> f64 {
    let executed = ctx.executed(r.span);
    let powered = match (&r.cond, executed) {
        (_, Some(false)) => Some(false),
        (Some(c), _) => truth(ctx, c),
        (None, _) => ctx.look.map(|_| true),
    };
    let class = match (powered, executed) {
        (_, Some(false)) => "rung skipped",
        (Some(true), _) => "rung powered",
        _ => "rung",
    };
    o.svg.open(Some(&format!("rung-{number}")), class);
    if executed == Some(false) {
        o.svg.title(&format!("rung {number} did not run in the last scan (a jump skipped it)"));
    }
    if let Some(l) = &r.label {
        o.svg.text(left + 6.0, y + 12.0, &format!("{}:", l.text), "name", "start");
        o.geo.solids.push(Solid {
            what: format!("label {}", l.text),
            r: Rect::new(left + 6.0, y, text_width(&l.text) + 8.0, 16.0),
        });
        y += 16.0;
    }
    let cs = r.cond.as_ref().map_or(Size { w: 0.0, h: ctx.elem_h(), wy: WY }, |c| size(ctx, c));
    let wy = y + cs.wy.max(WY);
    let cy = wy - cs.wy;
    let pin = match executed {
        Some(false) => Some(false),
        _ => ctx.look.map(|_| true),
    };
    let pout = match &r.cond {
        Some(c) => cond(ctx, c, left, cy, pin, o),
        None => pin,
    };
    let ow = output_w(ctx, &r.output);
    let ox = right - ow;
    wire(o, p(left + cs.w, wy), p(ox, wy), pout);
    let orect = output(ctx, &r.output, ox, wy - WY, pout, o);
    o.geo.solids.push(Solid { what: format!("output of rung-{number}"), r: orect });
    // The rung's wire from the left rail to its output, for the layout tests.
    let out_id = format!("rung-{number}-out");
    o.geo.nodes.push((out_id.clone(), Rect::new(ox, wy - 10.0, ow, 20.0)));
    o.geo.links.push(Link { from: String::new(), to: out_id, path: vec![p(left, wy), p(ox, wy)] });
    o.svg.close();
    y + cs.h.max(ctx.elem_h()) + 10.0
}
