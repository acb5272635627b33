//! An FST table as a flow (docs/pictures.md): a box a step with its
//! number, label, command and arguments, in table order; a step falls
//! through to the next unless it is GO or END; every branch to a label is
//! an arrow along a lane on the right, END's return to step 0 one on the
//! left. With a run's state the step the table goes on with is `current`
//! and RR and CF are shown.

use crate::geom::{p, tracks, Geometry, Link, Rect, Solid};
use crate::svg::{text_width, Svg};
use linc_compiler::fst::commands::Kind;
use linc_compiler::fst::{Cmd, Table};
use std::collections::HashMap;

/// What a run left in the table's FST block.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FstState {
    /// The step the table goes on with (from IP).
    pub current: Option<usize>,
    pub rr: String,
    pub cf: String,
    /// RUNFLG, as the database shows it.
    pub runflg: String,
    /// The registers R1–R10 (or as many as the block has), by name.
    pub registers: Vec<(String, String)>,
}

/// The state's lines above the table: RR, CF and RUNFLG, then the
/// registers five to a line.
fn state_lines(st: &FstState) -> Vec<String> {
    let mut lines = vec![format!("RR = {}   CF = {}   RUNFLG = {}", st.rr, st.cf, st.runflg)];
    for five in st.registers.chunks(5) {
        lines.push(five.iter().map(|(n, v)| format!("{n} = {v}")).collect::<Vec<_>>().join("   "));
    }
    lines
}

const BOX_H: f64 = 24.0;
const GAP: f64 = 16.0;
const LEFT: f64 = 40.0;
const LANE_GAP: f64 = 10.0;

struct Row {
    step: usize,
    label: String,
    text: String,
    comment: String,
    cmd: Option<Cmd>,
    /// The step a branch goes to.
    target: Option<usize>,
}

fn rows(table: &Table) -> Vec<Row> {
    let labels: HashMap<String, usize> = table
        .rows
        .iter()
        .enumerate()
        .filter_map(|(i, r)| Some((r.label.as_ref()?.text.as_str().to_ascii_uppercase(), i)))
        .collect();
    let mut out: Vec<Row> = table
        .rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let cmd = Cmd::parse(&r.cmd.text);
            let args: Vec<&str> =
                [&r.arg1, &r.arg2].iter().filter_map(|a| a.as_ref().map(|c| c.text.as_str())).collect();
            let target = cmd.and_then(|c| {
                let (k1, k2) = c.args();
                let cell = if k1 == Kind::Label {
                    &r.arg1
                } else if k2 == Kind::Label {
                    &r.arg2
                } else {
                    &None
                };
                cell.as_ref().and_then(|c| labels.get(&c.text.as_str().to_ascii_uppercase()).copied())
            });
            let text =
                if args.is_empty() { r.cmd.text.to_string() } else { format!("{} {}", r.cmd.text, args.join(", ")) };
            let label = r.label.as_ref().map(|l| l.text.to_string()).unwrap_or_default();
            Row { step: i, label, text, comment: r.comment.clone(), cmd, target }
        })
        .collect();
    if !out.iter().any(|r| r.cmd == Some(Cmd::End)) {
        let step = out.len();
        out.push(Row {
            step,
            label: String::new(),
            text: "END".into(),
            comment: "added".into(),
            cmd: Some(Cmd::End),
            target: None,
        });
    }
    out
}

/// The table as an SVG flow, with its geometry.
pub fn table(table: &Table, state: Option<&FstState>) -> (String, Geometry) {
    let rows = rows(table);
    let label_w = rows.iter().map(|r| text_width(&r.label)).fold(0.0, f64::max);
    let text_w = rows.iter().map(|r| text_width(&r.text)).fold(60.0, f64::max);
    let (num_w, lab_w) = (text_width(&rows.len().to_string()) + 12.0, if label_w > 0.0 { label_w + 12.0 } else { 0.0 });
    let box_w = num_w + lab_w + text_w + 16.0;
    let head = state.map(state_lines).unwrap_or_default();
    let top = if state.is_some() { 24.0 + 16.0 * head.len() as f64 } else { 12.0 };
    let y_of = |i: usize| top + i as f64 * (BOX_H + GAP);
    // Branch lanes on the right, by the steps they span.
    let branches: Vec<(usize, usize)> = rows.iter().filter_map(|r| Some((r.step, r.target?))).collect();
    let spans: Vec<(f64, f64)> = branches.iter().map(|&(a, b)| (a.min(b) as f64, a.max(b) as f64)).collect();
    let (lane, lanes) = tracks(&spans, 1.0);
    let right = LEFT + box_w;
    let comment_x = right + 24.0 + lanes as f64 * LANE_GAP;
    let comment_w = rows.iter().map(|r| text_width(&r.comment)).fold(0.0, f64::max);
    let mut svg = Svg::new();
    let mut geo = Geometry::default();
    for (i, line) in head.iter().enumerate() {
        let y = 10.0 + 16.0 * i as f64;
        svg.text(LEFT, y + 12.0, line, "value", "start");
        geo.solids.push(Solid { what: format!("state {i}"), r: Rect::new(LEFT, y, text_width(line), 16.0) });
    }
    for r in &rows {
        let y = y_of(r.step);
        let current = state.and_then(|s| s.current) == Some(r.step);
        let id = format!("fst-step-{}", r.step);
        svg.open(Some(&id), if current { "fst-step current" } else { "fst-step" });
        let b = Rect::new(LEFT, y, box_w, BOX_H);
        svg.rect(b, "box");
        svg.text(LEFT + 6.0, y + 16.0, &r.step.to_string(), "dim", "start");
        if !r.label.is_empty() {
            svg.text(LEFT + num_w, y + 16.0, &r.label, "name", "start");
        }
        svg.text(LEFT + num_w + lab_w + 8.0, y + 16.0, &r.text, "", "start");
        if !r.comment.is_empty() {
            svg.text(comment_x, y + 16.0, &r.comment, "dim", "start");
            geo.solids.push(Solid {
                what: format!("comment of {id}"),
                r: Rect::new(comment_x, y + 4.0, text_width(&r.comment), 16.0),
            });
        }
        svg.close();
        geo.nodes.push((id.clone(), b));
        geo.solids.push(Solid { what: id, r: b });
    }
    let wire = |svg: &mut Svg, geo: &mut Geometry, a, b| {
        svg.line(a, b, "wire");
        geo.wires.push((a, b));
    };
    let cx = LEFT + box_w / 2.0;
    for r in &rows {
        let falls = !matches!(r.cmd, Some(Cmd::Go) | Some(Cmd::End)) && r.step + 1 < rows.len();
        let (from, y) = (format!("fst-step-{}", r.step), y_of(r.step));
        if falls {
            let (a, b) = (p(cx, y + BOX_H), p(cx, y + BOX_H + GAP));
            wire(&mut svg, &mut geo, a, b);
            svg.arrow(b, 0.0, 1.0);
            geo.links.push(Link { from: from.clone(), to: format!("fst-step-{}", r.step + 1), path: vec![a, b] });
        }
        if r.cmd == Some(Cmd::End) && r.step > 0 {
            let (a, b, c, d) = (
                p(LEFT, y + BOX_H / 2.0),
                p(LEFT - 16.0, y + BOX_H / 2.0),
                p(LEFT - 16.0, y_of(0) + BOX_H / 2.0),
                p(LEFT, y_of(0) + BOX_H / 2.0),
            );
            for (s, e) in [(a, b), (b, c), (c, d)] {
                wire(&mut svg, &mut geo, s, e);
            }
            svg.arrow(d, 1.0, 0.0);
            geo.links.push(Link { from: from.clone(), to: "fst-step-0".into(), path: vec![a, b, c, d] });
        }
    }
    for (k, &(a, t)) in branches.iter().enumerate() {
        let lx = right + 12.0 + lane[k] as f64 * LANE_GAP;
        let (ya, yt) = (y_of(a) + BOX_H / 2.0 - 4.0, y_of(t) + BOX_H / 2.0 + 4.0);
        let path = vec![p(right, ya), p(lx, ya), p(lx, yt), p(right, yt)];
        for w in path.windows(2) {
            wire(&mut svg, &mut geo, w[0], w[1]);
        }
        svg.arrow(p(right, yt), -1.0, 0.0);
        geo.links.push(Link { from: format!("fst-step-{a}"), to: format!("fst-step-{t}"), path });
    }
    let head_w = head.iter().map(|l| LEFT + text_width(l)).fold(0.0, f64::max);
    let w = (comment_x + comment_w).max(head_w) + 12.0;
    let h = y_of(rows.len()) - GAP + 12.0;
    (svg.finish("fst", w, h), geo)
}
