//! The layout of a sequence (`.sfc`): one step a line, with the
//! associations and `END_STEP` of neighbouring steps aligned, one
//! transition a line, actions as ST (or nested charts and rungs).

use super::ladder;
use super::printer::Printer;
use super::tokens::tokens;
use crate::st::token::Raw;

/// Where a step's line is in the output, for alignment.
struct StepLine {
    start: usize,
    header_end: usize,
    assocs_end: usize,
    end: usize,
}

pub(crate) fn format(src: &str) -> String {
    let lexed = tokens(src);
    let mut p = Printer::new(src, &lexed);
    p.brk = true;
    chart(&mut p, false);
    p.gap(lexed.tail, true);
    p.out.finish()
}

/// The items of a chart, up to the `END_ACTION` of a chart action.
fn chart(p: &mut Printer, nested: bool) {
    let mut steps = Vec::new();
    while p.pos < p.toks.len() {
        let i = p.pos;
        if p.word_at(i, "STEP") || p.word_at(i, "INITIAL_STEP") {
            steps.push(step(p));
        } else if p.word_at(i, "TRANSITION") {
            transition(p);
        } else if p.raw(i) == Some(Raw::Action) && !nested {
            action(p);
        } else if p.raw(i) == Some(Raw::EndAction) && nested {
            break;
        } else {
            p.emit(i, false);
        }
    }
    align(&mut p.out.buf, &steps);
}

fn step(p: &mut Printer) -> StepLine {
    p.line();
    p.emit_upper(p.pos, true);
    let start = p.out.buf.rfind('\n').map(|i| i + 1).unwrap_or(0);
    p.inline(p.pos + 1); // the name
    if p.raw(p.pos) == Some(Raw::Colon) {
        p.emit_spaced(p.pos, false, Some(false));
    }
    let header_end = p.out.buf.len();
    let mut qualifier = false;
    while p.pos < p.toks.len() && !p.word_at(p.pos, "END_STEP") {
        if qualifier && p.raw(p.pos) == Some(Raw::Name) {
            p.emit_upper(p.pos, false);
        } else {
            p.emit(p.pos, false);
        }
        qualifier = p.raw(p.pos - 1) == Some(Raw::LParen);
    }
    let assocs_end = p.out.buf.len();
    if p.pos < p.toks.len() {
        p.emit_upper(p.pos, false);
    }
    if p.raw(p.pos) == Some(Raw::Semi) {
        p.emit(p.pos, false);
    }
    p.line();
    StepLine { start, header_end, assocs_end, end: p.out.buf.len() }
}

fn transition(p: &mut Printer) {
    p.line();
    p.emit_upper(p.pos, true);
    let named = p.raw(p.pos) == Some(Raw::Name) && (!p.word_at(p.pos, "FROM") || p.word_at(p.pos + 1, "FROM"));
    if named {
        p.inline(p.pos + 1);
    }
    if p.raw(p.pos) == Some(Raw::LParen) {
        p.emit_spaced(p.pos, false, Some(true));
        p.emit_upper(p.pos, false); // PRIORITY
        while p.pos < p.toks.len() && p.raw(p.pos) != Some(Raw::RParen) {
            p.emit(p.pos, false);
        }
        p.inline(p.pos + 1);
    }
    if p.word_at(p.pos, "FROM") {
        p.emit_upper(p.pos, false);
    }
    while p.pos < p.toks.len() && !matches!(p.raw(p.pos), Some(Raw::Assign | Raw::Colon)) {
        let space = (p.raw(p.pos) == Some(Raw::LParen)).then_some(true);
        p.emit_spaced(p.pos, false, space);
    }
    let end = (p.pos..p.toks.len()).find(|&k| p.word_at(k, "END_TRANSITION")).unwrap_or(p.toks.len());
    if p.raw(p.pos) == Some(Raw::Colon) && p.word_at(p.pos + 1, "LADDER") {
        p.inline(p.pos + 1);
        p.emit_upper(p.pos, false);
        let from = p.toks[p.pos - 1].end;
        let to = p.toks.get(end).map(|t| t.start).unwrap_or(p.src.len());
        let rung = ladder::condition_rung(&p.src[from..to]);
        p.put(&rung);
        p.pos = end;
        if end < p.toks.len() {
            p.out.put(" ", false);
            let text = p.text(end).to_ascii_uppercase();
            p.out.buf.push_str(&text);
            p.pos = end + 1;
        }
    } else {
        while p.pos < end {
            p.emit(p.pos, false);
        }
        if end < p.toks.len() {
            p.emit_upper(end, false);
        }
    }
    if p.raw(p.pos) == Some(Raw::Semi) {
        p.emit(p.pos, false);
    }
    p.line();
}

fn action(p: &mut Printer) {
    p.line();
    p.emit(p.pos, true);
    p.inline(p.pos + 1); // the name
    let mut kind = String::new();
    if p.raw(p.pos) == Some(Raw::Colon) {
        p.inline(p.pos + 1);
        kind = p.text(p.pos).to_ascii_uppercase();
        if kind == "CHART" || kind == "LADDER" {
            p.emit_upper(p.pos, false);
        } else {
            p.emit(p.pos, false);
        }
    }
    p.level += 1;
    p.line();
    let end = (p.pos..p.toks.len()).find(|&k| p.raw(k) == Some(Raw::EndAction)).unwrap_or(p.toks.len());
    match kind.as_str() {
        "CHART" => chart(p, true),
        "LADDER" => {
            let from = p.toks[p.pos - 1].end;
            let to = p.toks.get(end).map(|t| t.start).unwrap_or(p.src.len());
            p.out.newline();
            p.out.buf.push_str(&ladder::rungs(&p.src[from..to], p.indent_cols()));
            p.pos = end;
        }
        _ => p.statements(&|p: &Printer| p.raw(p.pos) == Some(Raw::EndAction)),
    }
    p.level -= 1;
    p.line();
    if p.pos < p.toks.len() {
        if kind == "LADDER" {
            p.out.newline();
            p.emit_without_gap(p.pos);
        } else {
            p.emit(p.pos, true);
        }
    }
    if p.raw(p.pos) == Some(Raw::Semi) {
        p.emit(p.pos, false);
    }
    p.line();
}

/// Two step lines follow each other: only a line break, or a comment at
/// the end of the first line, stands between them.
fn neighbours(buf: &str, a: &StepLine, b: &StepLine) -> bool {
    let between = buf.get(a.end..b.start).unwrap_or("\n\n");
    between.ends_with('\n') && between.matches('\n').count() == 1 && {
        let t = between.trim();
        t.is_empty() || (t.starts_with("(*") && t.ends_with("*)"))
    }
}

/// Pads the steps of each run of neighbouring one-line steps so that their
/// associations and their `END_STEP`s start in one column.
fn align(buf: &mut String, steps: &[StepLine]) {
    let one_line: Vec<&StepLine> = steps.iter().filter(|s| !buf[s.start..s.end].contains('\n')).collect();
    let mut runs: Vec<Vec<&StepLine>> = Vec::new();
    for s in one_line {
        match runs.last_mut() {
            Some(run) if run.last().is_some_and(|l| neighbours(buf, l, s)) => run.push(s),
            _ => runs.push(vec![s]),
        }
    }
    let width = |a: usize, b: usize| buf[a..b].trim().chars().count();
    let mut edits = Vec::new();
    for run in runs {
        let header = run.iter().map(|s| buf[s.start..s.header_end].trim_end().chars().count()).max().unwrap_or(0) + 1;
        let assocs = run.iter().map(|s| width(s.header_end, s.assocs_end)).max().unwrap_or(0) + 1;
        for s in run {
            let h = buf[s.start..s.header_end].trim_end().chars().count();
            let a = width(s.header_end, s.assocs_end);
            let assoc_text = buf[s.header_end..s.assocs_end].trim().to_string();
            let mut line = buf[s.start..s.header_end].trim_end().to_string();
            line.extend(std::iter::repeat_n(' ', header - h));
            line.push_str(&assoc_text);
            line.extend(std::iter::repeat_n(' ', assocs - a));
            line.push_str(buf[s.assocs_end..s.end].trim());
            edits.push((s.start, s.end, line));
        }
    }
    // One pass over the text from the first step on: replacing each line
    // in place would move the rest of the text once per step, and a
    // nested chart's steps are near the end of what is written so far.
    edits.sort_by_key(|e| e.0);
    let Some(first) = edits.first().map(|e| e.0) else { return };
    let tail = buf.split_off(first);
    let mut at = 0;
    for (a, b, line) in edits {
        let (a, b) = (a - first, b - first);
        buf.push_str(&tail[at..a]);
        buf.push_str(&line);
        if tail[a..b].ends_with('\n') {
            buf.push('\n');
        }
        at = b;
    }
    buf.push_str(&tail[at..]);
}
