//! A sequence as IEC 61131-3 draws it (docs/pictures.md): steps and
//! transitions in rows, the links between neighbouring rows as wires with
//! selective (single line) and simultaneous (double line) branches, links
//! that skip rows or go back up along lanes on the right, and links longer
//! than [`LANE_SPAN`] rows as named jump connectors.
//!
//! Layout: rows are longest-path ranks of the chart with back links taken
//! out (steps on even rows, transitions on odd ones); each node takes a
//! column, nodes with one parent going under it; columns are as wide as
//! their widest node, rows as tall as their tallest, so no two nodes meet.
//! Horizontal wires between two rows get tracks of their own (interval
//! colouring), so no two run over each other.

use crate::geom::{p, tracks, Geometry, Link, Rect, Solid, P};
use crate::svg::{id, num, text_width, wrap, Svg, LINE_H};
use linc_compiler::sfc::ast::{ActionBody, Chart, Sequence, Step, Transition};
use std::collections::{HashMap, HashSet};

/// The wires of the nets and links, and the double bars' records.
#[path = "sfc_links.rs"]
mod links;
use links::wires;

/// Links spanning more rows than this are drawn as named connectors.
pub const LANE_SPAN: usize = 8;
const MARGIN: f64 = 12.0;
const COL_GAP: f64 = 28.0;
const TRACK: f64 = 8.0;
const LANE_GAP: f64 = 10.0;
const BAR_HALF: f64 = 12.0;

/// Chart actions nest at most this deep in a picture (the checker allows
/// fewer; this only bounds the recursion).
const MAX_DEPTH: usize = 64;

/// What a run left in a step, for a picture of the state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepState {
    pub active: bool,
    /// `.T` in µs.
    pub t_us: u64,
    pub held: bool,
}

/// The state of each step by name, when the picture shows a run.
pub type Look<'a> = Option<&'a dyn Fn(&str) -> Option<StepState>>;

/// A chart drawn: its SVG elements (at the origin), size and geometry.
pub struct Drawn {
    pub body: String,
    pub w: f64,
    pub h: f64,
    pub geometry: Geometry,
}

/// The whole sequence as an SVG document, with its geometry.
pub fn sequence(src: &str, seq: &Sequence, look: Look) -> (String, Geometry) {
    let mut state = Numbering::of(seq);
    let d = chart(&Ctx { src, seq, look }, &seq.chart, &mut state, 0);
    let mut svg = Svg::new();
    svg.raw(&format!("<g transform=\"translate({MARGIN},{MARGIN})\">\n{}</g>\n", d.body));
    let mut g = Geometry::default();
    g.absorb(d.geometry, MARGIN, MARGIN);
    (svg.finish("sfc", d.w + 2.0 * MARGIN, d.h + 2.0 * MARGIN), g)
}

struct Ctx<'a> {
    src: &'a str,
    seq: &'a Sequence,
    look: Look<'a>,
}

impl Ctx<'_> {
    fn box_h(&self) -> f64 {
        if self.look.is_some() {
            40.0
        } else {
            26.0
        }
    }
}

/// Ids that are unique across the whole picture.
#[derive(Default)]
struct Numbering {
    /// The number of each unnamed transition, by where it starts.
    unnamed: HashMap<usize, usize>,
    jumps: usize,
    /// Chart actions already drawn (a chart action is drawn once).
    drawn: HashSet<String>,
}

impl Numbering {
    /// Unnamed transitions numbered in source order (by where each starts
    /// in the file), the root chart's and the chart actions' together.
    fn of(seq: &Sequence) -> Numbering {
        let mut n = Numbering::default();
        let charts = std::iter::once(&seq.chart).chain(seq.actions.iter().filter_map(|a| match &a.body {
            ActionBody::Chart(c) => Some(c),
            ActionBody::St(_) => None,
        }));
        let mut spans: Vec<usize> =
            charts.flat_map(|c| c.transitions.iter().filter(|t| t.name.is_none()).map(|t| t.span.start)).collect();
        spans.sort_unstable();
        for (i, s) in spans.into_iter().enumerate() {
            n.unnamed.insert(s, i + 1);
        }
        n
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Step(usize),
    Trans(usize),
    /// A jump connector standing for a long link.
    Jump,
}

struct Node {
    kind: Kind,
    id: String,
    rank: usize,
    col: usize,
    /// Extent left and right of the spine, and height.
    left: f64,
    right: f64,
    h: f64,
}

/// A link of the chart, node to node.
#[derive(Clone, Copy)]
struct Edge {
    from: usize,
    to: usize,
    /// Drawn along this lane (back links and links over rows).
    lane: Option<usize>,
}

fn slice(src: &str, lo: usize, hi: usize) -> String {
    src.get(lo..hi).unwrap_or("").split_whitespace().collect::<Vec<_>>().join(" ")
}

fn trans_lines(ctx: &Ctx, t: &Transition) -> Vec<String> {
    let mut lines = Vec::new();
    let head = match (&t.name, t.priority.as_deref()) {
        (Some(n), Some((p, _))) => Some(format!("{} ({p})", n.text)),
        (Some(n), None) => Some(n.text.to_string()),
        (None, Some((p, _))) => Some(format!("({p})")),
        (None, None) => None,
    };
    lines.extend(head);
    let cond = match (t.ladder.as_deref(), &t.cond) {
        (Some(span), _) => format!("LADDER {}", slice(ctx.src, span.start, span.end)),
        (None, Some(c)) => slice(ctx.src, c.span.start, c.span.end),
        (None, None) => "?".into(),
    };
    lines.extend(wrap(&cond, 36, 4));
    lines
}

/// The time a step has been active, as `T#…`.
pub fn step_time(us: u64) -> String {
    let ms = us / 1000;
    let (h, m, s, ms) = (ms / 3_600_000, ms / 60_000 % 60, ms / 1000 % 60, ms % 1000);
    let mut out = String::from("T#");
    if h > 0 {
        out.push_str(&format!("{h}h"));
    }
    if m > 0 {
        out.push_str(&format!("{m}m"));
    }
    if ms > 0 {
        out.push_str(&format!("{s}.{ms:03}s"));
    } else if s > 0 || (h == 0 && m == 0) {
        out.push_str(&format!("{s}s"));
    }
    out
}

/// The action blocks beside a step: qualifier and name a row, a chart
/// action's chart drawn under its row.
struct Blocks {
    rows: Vec<(String, String, Option<Drawn>)>,
    qw: f64,
    nw: f64,
}

const ROW: f64 = 20.0;

impl Blocks {
    fn width(&self) -> f64 {
        let sub = self.rows.iter().filter_map(|r| r.2.as_ref()).map(|d| d.w + 12.0).fold(0.0, f64::max);
        (self.qw + self.nw).max(sub)
    }

    fn height(&self) -> f64 {
        self.rows.iter().map(|r| ROW + r.2.as_ref().map_or(0.0, |d| d.h + 12.0)).sum()
    }
}

fn blocks(ctx: &Ctx, step: &Step, numbering: &mut Numbering, depth: usize) -> Blocks {
    let mut rows = Vec::new();
    for a in &step.assocs {
        let q = match a.time {
            Some((t, _)) => format!("{} T#{}s", a.qualifier.text.as_str().to_ascii_uppercase(), num(t)),
            None => a.qualifier.text.as_str().to_ascii_uppercase(),
        };
        let action = ctx.seq.actions.iter().find(|x| x.name.text.eq_ignore_ascii_case(&a.action.text));
        let sub = match action.map(|x| (&x.body, x.name.text.as_str().to_ascii_uppercase())) {
            Some((ActionBody::Chart(c), key)) if depth < MAX_DEPTH && numbering.drawn.insert(key.clone()) => {
                Some(chart(ctx, c, numbering, depth + 1))
            }
            _ => None,
        };
        rows.push((q, a.action.text.to_string(), sub));
    }
    let qw = rows.iter().map(|r| text_width(&r.0) + 12.0).fold(28.0, f64::max);
    let nw = rows.iter().map(|r| text_width(&r.1) + 14.0).fold(40.0, f64::max);
    Blocks { rows, qw, nw }
}

/// Nodes, edges and ranks of one chart, before positions.
struct Graph {
    nodes: Vec<Node>,
    edges: Vec<Edge>,
    blocks: Vec<Blocks>,
    lines: Vec<Vec<String>>,
    connectors: Vec<(String, String, String)>,
    lanes: usize,
}

fn graph(ctx: &Ctx, c: &Chart, numbering: &mut Numbering, depth: usize) -> Graph {
    let box_h = ctx.box_h();
    let mut nodes = Vec::new();
    let mut all_blocks = Vec::new();
    for (i, s) in c.steps.iter().enumerate() {
        let b = blocks(ctx, s, numbering, depth);
        let w = (text_width(&s.name.text) + 24.0).max(72.0);
        let (right, h) = if b.rows.is_empty() {
            (w / 2.0, box_h)
        } else {
            (w / 2.0 + 16.0 + b.width(), box_h.max(box_h / 2.0 - ROW / 2.0 + b.height()))
        };
        let id = id("step-", &s.name.text);
        nodes.push(Node { kind: Kind::Step(i), id, rank: 0, col: 0, left: w / 2.0, right, h });
        all_blocks.push(b);
    }
    let mut lines = Vec::new();
    for (j, t) in c.transitions.iter().enumerate() {
        let l = trans_lines(ctx, t);
        let wide = l.iter().map(|x| text_width(x)).fold(0.0, f64::max);
        let h = (16.0 + l.len() as f64 * LINE_H).max(28.0);
        let id = match &t.name {
            Some(n) => id("trans-", &n.text),
            None => format!("trans-{}", numbering.unnamed.get(&t.span.start).copied().unwrap_or(0)),
        };
        nodes.push(Node { kind: Kind::Trans(j), id, rank: 0, col: 0, left: BAR_HALF, right: 18.0 + wide, h });
        lines.push(l);
    }
    let ns = c.steps.len();
    let by_name: HashMap<String, usize> =
        c.steps.iter().enumerate().map(|(i, s)| (s.name.text.as_str().to_ascii_uppercase(), i)).collect();
    let mut edges = Vec::new();
    for (j, t) in c.transitions.iter().enumerate() {
        for f in &t.from {
            if let Some(&s) = by_name.get(&f.text.as_str().to_ascii_uppercase()) {
                edges.push(Edge { from: s, to: ns + j, lane: None });
            }
        }
        for f in &t.to {
            if let Some(&s) = by_name.get(&f.text.as_str().to_ascii_uppercase()) {
                edges.push(Edge { from: ns + j, to: s, lane: None });
            }
        }
    }
    let initial: Vec<usize> = (0..ns).filter(|&i| c.steps[i].initial).collect();
    let back = back_edges(nodes.len(), &edges, &initial);
    rank(&mut nodes, &edges, &back);
    let mut g = Graph { nodes, edges, blocks: all_blocks, lines, connectors: Vec::new(), lanes: 0 };
    long_links(&mut g, c, numbering);
    g
}

/// The links that close a loop: found by a depth-first walk from the
/// initial steps, then the other steps, in source order (iterative, so a
/// long chart does not exhaust the stack).
fn back_edges(n: usize, edges: &[Edge], initial: &[usize]) -> Vec<bool> {
    let mut out: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (e, edge) in edges.iter().enumerate() {
        out[edge.from].push(e);
    }
    let mut colour = vec![0u8; n];
    let mut back = vec![false; edges.len()];
    let roots = initial.iter().copied().chain(0..n);
    for root in roots {
        if colour[root] != 0 {
            continue;
        }
        colour[root] = 1;
        let mut stack = vec![(root, 0usize)];
        while let Some((v, i)) = stack.last_mut() {
            let v = *v;
            if let Some(&e) = out[v].get(*i) {
                *i += 1;
                let w = edges[e].to;
                match colour[w] {
                    0 => {
                        colour[w] = 1;
                        stack.push((w, 0));
                    }
                    1 => back[e] = true,
                    _ => {}
                }
            } else {
                colour[v] = 2;
                stack.pop();
            }
        }
    }
    back
}

/// Longest-path ranks over the links that are not back links.
fn rank(nodes: &mut [Node], edges: &[Edge], back: &[bool]) {
    let n = nodes.len();
    let mut indeg = vec![0usize; n];
    let mut out: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (e, edge) in edges.iter().enumerate().filter(|(e, _)| !back[*e]) {
        indeg[edge.to] += 1;
        out[edge.from].push(e);
    }
    let mut ready: std::collections::VecDeque<usize> = (0..n).filter(|&v| indeg[v] == 0).collect();
    while let Some(v) = ready.pop_front() {
        for &e in &out[v] {
            let w = edges[e].to;
            nodes[w].rank = nodes[w].rank.max(nodes[v].rank + 1);
            indeg[w] -= 1;
            if indeg[w] == 0 {
                ready.push_back(w);
            }
        }
    }
}

/// Links between rows that are not neighbours: along a lane when short,
/// else through a jump connector in the row under the source.
fn long_links(g: &mut Graph, c: &Chart, numbering: &mut Numbering) {
    let mut lane_spans = Vec::new();
    let mut lane_edges = Vec::new();
    for e in 0..g.edges.len() {
        let Edge { from, to, .. } = g.edges[e];
        let (a, b) = (g.nodes[from].rank, g.nodes[to].rank);
        if b == a + 1 {
            continue;
        }
        if a.abs_diff(b) <= LANE_SPAN {
            lane_spans.push((a.min(b) as f64, a.max(b) as f64));
            lane_edges.push(e);
            continue;
        }
        numbering.jumps += 1;
        let name = match g.nodes[to].kind {
            Kind::Step(i) => c.steps[i].name.text.to_string(),
            Kind::Trans(j) => c.transitions[j].display_name(),
            Kind::Jump => String::new(),
        };
        let jid = format!("jump-{}", numbering.jumps);
        g.connectors.push((jid.clone(), name.clone(), g.nodes[to].id.clone()));
        let right = 14.0 + text_width(&name);
        g.nodes.push(Node { kind: Kind::Jump, id: jid, rank: a + 1, col: 0, left: 8.0, right, h: 24.0 });
        g.edges[e].to = g.nodes.len() - 1;
    }
    let (lanes, count) = tracks(&lane_spans, 1.0);
    for (k, e) in lane_edges.into_iter().enumerate() {
        g.edges[e].lane = Some(lanes[k]);
    }
    g.lanes = count;
}

/// Columns: row by row, a node under its first parent (its k-th child
/// k columns to the right), pushed right past the node before it.
fn columns(nodes: &mut [Node], edges: &[Edge]) -> usize {
    let rows = nodes.iter().map(|n| n.rank + 1).max().unwrap_or(0);
    let mut by_row: Vec<Vec<usize>> = vec![Vec::new(); rows];
    for (i, n) in nodes.iter().enumerate() {
        by_row[n.rank].push(i);
    }
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); nodes.len()];
    for e in edges.iter().filter(|e| e.lane.is_none() && nodes[e.to].rank == nodes[e.from].rank + 1) {
        children[e.from].push(e.to);
    }
    let mut desired = vec![usize::MAX; nodes.len()];
    let mut ncols = 0;
    for row in &mut by_row {
        row.sort_by_key(|&i| (if desired[i] == usize::MAX { 0 } else { desired[i] }, i));
        let mut next = 0;
        for &i in row.iter() {
            let want = if desired[i] == usize::MAX { 0 } else { desired[i] };
            nodes[i].col = want.max(next);
            next = nodes[i].col + 1;
        }
        ncols = ncols.max(next);
        for &i in row.iter() {
            for (k, &c) in children[i].iter().enumerate() {
                desired[c] = desired[c].min(nodes[i].col + k);
            }
        }
    }
    ncols
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum NetKind {
    /// A node's outgoing links (selective or simultaneous divergence).
    Out(usize),
    /// A node's incoming links (convergence).
    In(usize),
    /// One link between neighbours with no branch at either end.
    Plain(usize),
}

impl Net {
    /// The net's place among the nets of its boundary, top to bottom:
    /// selective divergences, plain links, simultaneous divergences,
    /// convergences. A simultaneous divergence's double bar goes under the
    /// selective and plain wires so that none of them runs down through it
    /// (which would read as leading into the parallel branch): their stems
    /// from the row above end on their own lines above the bar.
    fn group(&self) -> usize {
        match self.kind {
            NetKind::Out(_) if self.double => 2,
            NetKind::Out(_) => 0,
            NetKind::Plain(_) => 1,
            NetKind::In(_) => 3,
        }
    }
}

/// The wires between two rows that one horizontal line joins.
struct Net {
    kind: NetKind,
    boundary: usize,
    lo: f64,
    hi: f64,
    double: bool,
    y: f64,
}

/// Where everything is.
struct Place {
    spine: Vec<f64>,
    row_top: Vec<f64>,
    row_h: Vec<f64>,
    lane_x: Vec<f64>,
    nets: Vec<Net>,
    /// Per edge: its Out, In and Plain nets.
    edge_nets: Vec<[Option<usize>; 3]>,
    w: f64,
    h: f64,
}

fn place(g: &mut Graph) -> Place {
    let ncols = columns(&mut g.nodes, &g.edges);
    let (mut left, mut right) = (vec![0.0f64; ncols], vec![0.0f64; ncols]);
    for n in &g.nodes {
        left[n.col] = left[n.col].max(n.left);
        right[n.col] = right[n.col].max(n.right);
    }
    let mut col_spine = Vec::with_capacity(ncols);
    let mut x = 0.0;
    for c in 0..ncols {
        col_spine.push(x + left[c]);
        x += left[c] + right[c] + COL_GAP;
    }
    let spine: Vec<f64> = g.nodes.iter().map(|n| col_spine[n.col]).collect();
    let content_w = (x - COL_GAP).max(0.0);
    let lane_x: Vec<f64> = (0..g.lanes).map(|k| content_w + 16.0 + k as f64 * LANE_GAP).collect();
    let rows = g.nodes.iter().map(|n| n.rank + 1).max().unwrap_or(0);
    let mut row_h = vec![0.0f64; rows];
    for n in &g.nodes {
        row_h[n.rank] = row_h[n.rank].max(n.h);
    }
    let (nets, edge_nets) = nets(g, &spine, &lane_x);
    let mut p = Place {
        spine,
        row_top: vec![0.0; rows],
        row_h,
        lane_x,
        nets,
        edge_nets,
        w: content_w + if g.lanes > 0 { 16.0 + g.lanes as f64 * LANE_GAP } else { 0.0 },
        h: 0.0,
    };
    tracks_and_rows(&mut p, rows);
    p
}

fn nets(g: &Graph, spine: &[f64], lane_x: &[f64]) -> (Vec<Net>, Vec<[Option<usize>; 3]>) {
    let (mut outs, mut ins) = (vec![0usize; g.nodes.len()], vec![0usize; g.nodes.len()]);
    for e in &g.edges {
        outs[e.from] += 1;
        ins[e.to] += 1;
    }
    let is_trans = |v: usize| matches!(g.nodes[v].kind, Kind::Trans(_));
    let mut nets: Vec<Net> = Vec::new();
    let mut index: HashMap<NetKind, usize> = HashMap::new();
    let mut net = |kind: NetKind, boundary: usize, xs: &[f64]| {
        let i = *index.entry(kind).or_insert_with(|| {
            let double = match kind {
                NetKind::Out(u) => is_trans(u) && outs[u] > 1,
                NetKind::In(v) => is_trans(v) && ins[v] > 1,
                NetKind::Plain(_) => false,
            };
            nets.push(Net { kind, boundary, lo: f64::INFINITY, hi: f64::NEG_INFINITY, double, y: 0.0 });
            nets.len() - 1
        });
        for &x in xs {
            nets[i].lo = nets[i].lo.min(x);
            nets[i].hi = nets[i].hi.max(x);
        }
        i
    };
    let mut edge_nets = Vec::with_capacity(g.edges.len());
    for (e, edge) in g.edges.iter().enumerate() {
        let (u, v) = (edge.from, edge.to);
        let (xu, xv) = (spine[u], spine[v]);
        let (ru, rv) = (g.nodes[u].rank, g.nodes[v].rank);
        let mut on = [None; 3];
        if let Some(k) = edge.lane {
            on[0] = Some(net(NetKind::Out(u), ru + 1, &[xu, lane_x[k]]));
            on[1] = Some(net(NetKind::In(v), rv, &[xv, lane_x[k]]));
        } else {
            let (fo, fi) = (outs[u] > 1, ins[v] > 1);
            if fo {
                on[0] = Some(net(NetKind::Out(u), rv, &[xu, xv]));
            }
            if fi {
                on[1] = Some(net(NetKind::In(v), rv, &[xv, if fo { xv } else { xu }]));
            }
            if !fo && !fi {
                on[2] = Some(net(NetKind::Plain(e), rv, &[xu, xv]));
            }
        }
        edge_nets.push(on);
    }
    (nets, edge_nets)
}

/// Gives each net a track in its boundary (in the order of
/// [`Net::group`]), then sets the rows' tops.
fn tracks_and_rows(p: &mut Place, rows: usize) {
    let mut per: Vec<Vec<Vec<usize>>> = vec![vec![Vec::new(); 4]; rows + 1];
    for (i, n) in p.nets.iter().enumerate() {
        per[n.boundary][n.group()].push(i);
    }
    let mut y = 0.0;
    for (b, groups) in per.iter().enumerate() {
        let top = y;
        let mut used = 0;
        for group in groups {
            let spans: Vec<(f64, f64)> = group.iter().map(|&i| (p.nets[i].lo, p.nets[i].hi)).collect();
            let (t, count) = tracks(&spans, 6.0);
            for (k, &i) in group.iter().enumerate() {
                p.nets[i].y = top + TRACK * (used + t[k] + 1) as f64;
            }
            used += count;
        }
        y += if used == 0 { 14.0 } else { TRACK * (used + 1) as f64 };
        if b < rows {
            p.row_top[b] = y;
            y += p.row_h[b];
        }
    }
    p.h = y;
}

fn chart(ctx: &Ctx, c: &Chart, numbering: &mut Numbering, depth: usize) -> Drawn {
    let mut g = graph(ctx, c, numbering, depth);
    let pl = place(&mut g);
    let mut svg = Svg::new();
    let mut geo = Geometry::default();
    let has_out: HashSet<usize> = g.edges.iter().map(|e| e.from).collect();
    let has_in: HashSet<usize> = g.edges.iter().map(|e| e.to).collect();
    let mut subs: Vec<Vec<Option<Drawn>>> =
        g.blocks.iter_mut().map(|b| b.rows.iter_mut().map(|r| r.2.take()).collect()).collect();
    let mut nested = Vec::new();
    let mut out = Out { svg: &mut svg, geo: &mut geo, nested: &mut nested };
    for i in 0..g.nodes.len() {
        let links = (has_out.contains(&i), has_in.contains(&i));
        match g.nodes[i].kind {
            Kind::Step(s) => step(ctx, c, &g, &pl, i, links, std::mem::take(&mut subs[s]), &mut out),
            _ => other(&g, &pl, i, links, &mut out),
        }
    }
    svg.open(None, "links");
    wires(ctx, &g, &pl, &mut svg, &mut geo);
    svg.close();
    for (x, y, d) in nested {
        svg.raw(&format!("<g transform=\"translate({},{})\">\n{}</g>\n", num(x), num(y), d.body));
        geo.absorb(d.geometry, x, y);
    }
    geo.connectors.extend(g.connectors.iter().cloned());
    Drawn { body: svg.into_body(), w: pl.w, h: pl.h, geometry: geo }
}

fn wire(svg: &mut Svg, geo: &mut Geometry, a: P, b: P) {
    svg.line(a, b, "wire");
    geo.wires.push((a, b));
}

fn row_bottom(g: &Graph, pl: &Place, u: usize) -> f64 {
    let r = g.nodes[u].rank;
    pl.row_top[r] + pl.row_h[r]
}

/// Where a node's drawing goes.
struct Out<'a> {
    svg: &'a mut Svg,
    geo: &'a mut Geometry,
    /// Chart actions' charts, with where they go.
    nested: &'a mut Vec<(f64, f64, Drawn)>,
}

#[allow(clippy::too_many_arguments)]
fn step(
    ctx: &Ctx,
    c: &Chart,
    g: &Graph,
    pl: &Place,
    i: usize,
    (out, _): (bool, bool),
    mut subs: Vec<Option<Drawn>>,
    o: &mut Out,
) {
    let n = &g.nodes[i];
    let Kind::Step(s) = n.kind else { return };
    let step = &c.steps[s];
    let (x, top) = (pl.spine[i], pl.row_top[n.rank]);
    let st = ctx.look.and_then(|f| f(&step.name.text));
    let mut class = String::from("step");
    if st.is_some_and(|s| s.active) {
        class.push_str(" active");
    }
    if st.is_some_and(|s| s.held) {
        class.push_str(" held");
    }
    o.svg.open(Some(&n.id), &class);
    let (w, bh) = (n.left * 2.0, ctx.box_h());
    let r = Rect::new(x - w / 2.0, top, w, bh);
    o.svg.rect(r, "box");
    if step.initial {
        o.svg.rect(Rect::new(r.x + 3.0, r.y + 3.0, r.w - 6.0, r.h - 6.0), "box inner");
    }
    o.svg.text(x, top + if ctx.look.is_some() { 16.0 } else { 17.0 }, &step.name.text, "name", "middle");
    if let Some(st) = st.filter(|s| s.active) {
        o.svg.text(x, top + 32.0, &step_time(st.t_us), "value time", "middle");
    }
    if out {
        wire(o.svg, o.geo, p(x, top + bh), p(x, row_bottom(g, pl, i)));
    }
    o.geo.nodes.push((n.id.clone(), r));
    o.geo.solids.push(Solid { what: n.id.clone(), r });
    let b = &g.blocks[s];
    if !b.rows.is_empty() {
        let x0 = x + w / 2.0 + 16.0;
        let mut y = top + bh / 2.0 - ROW / 2.0;
        o.svg.line(p(x + w / 2.0, top + bh / 2.0), p(x0, top + bh / 2.0), "wire");
        for (k, (q, name, _)) in b.rows.iter().enumerate() {
            o.svg.open(None, "action");
            o.svg.rect(Rect::new(x0, y, b.qw, ROW), "box");
            o.svg.rect(Rect::new(x0 + b.qw, y, b.nw, ROW), "box");
            o.svg.text(x0 + b.qw / 2.0, y + 14.0, q, "qualifier", "middle");
            o.svg.text(x0 + b.qw + 7.0, y + 14.0, name, "", "start");
            o.svg.close();
            o.geo.solids.push(Solid { what: format!("{name} in {}", n.id), r: Rect::new(x0, y, b.qw + b.nw, ROW) });
            y += ROW;
            if let Some(d) = subs.get_mut(k).and_then(Option::take) {
                o.svg.rect(Rect::new(x0, y, d.w + 12.0, d.h + 12.0), "frame");
                let h = d.h;
                o.nested.push((x0 + 6.0, y + 6.0, d));
                y += h + 12.0;
            }
        }
    }
    o.svg.close();
}

/// A transition (bar and label) or a jump connector (arrow and name).
fn other(g: &Graph, pl: &Place, i: usize, (out, inn): (bool, bool), o: &mut Out) {
    let n = &g.nodes[i];
    let (x, top) = (pl.spine[i], pl.row_top[n.rank]);
    match n.kind {
        Kind::Trans(t) => {
            o.svg.open(Some(&n.id), "transition");
            let yb = top + 12.0;
            if inn {
                wire(o.svg, o.geo, p(x, top), p(x, yb - 2.0));
            }
            if out {
                wire(o.svg, o.geo, p(x, yb + 2.0), p(x, row_bottom(g, pl, i)));
            }
            o.svg.line(p(x - BAR_HALF, yb), p(x + BAR_HALF, yb), "bar");
            let bar = Rect::new(x - BAR_HALF, yb - 2.0, 2.0 * BAR_HALF, 4.0);
            o.geo.nodes.push((n.id.clone(), bar));
            o.geo.solids.push(Solid { what: n.id.clone(), r: bar });
            let lines = &g.lines[t];
            for (k, l) in lines.iter().enumerate() {
                o.svg.text(x + 18.0, yb + 4.0 + k as f64 * LINE_H, l, "", "start");
            }
            let wide = lines.iter().map(|l| text_width(l)).fold(0.0, f64::max);
            let label = Rect::new(x + 18.0, yb - 8.0, wide, lines.len() as f64 * LINE_H);
            o.geo.solids.push(Solid { what: format!("label of {}", n.id), r: label });
            o.svg.close();
        }
        Kind::Jump => {
            let name = g.connectors.iter().find(|c| c.0 == n.id).map(|c| c.1.as_str()).unwrap_or("");
            o.svg.open(Some(&n.id), "jump");
            o.svg.line(p(x, top), p(x, top + 9.0), "wire");
            o.svg.arrow(p(x, top + 16.0), 0.0, 1.0);
            o.svg.text(x + 10.0, top + 14.0, name, "name", "start");
            o.svg.close();
            o.geo.nodes.push((n.id.clone(), Rect::new(x - 6.0, top, 12.0, 16.0)));
            let label = Rect::new(x + 10.0, top + 2.0, text_width(name), 14.0);
            o.geo.solids.push(Solid { what: format!("label of {}", n.id), r: label });
        }
        Kind::Step(_) => {}
    }
}
