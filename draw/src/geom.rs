//! What a picture is made of, as numbers: the boxes that must not overlap,
//! the wires drawn, and for each connection of the source the path that
//! joins its two ends. The SVG is written from this record, and the layout
//! tests check it, so what is tested is what is drawn.

use std::collections::HashMap;

/// A point in SVG user units (px).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct P {
    pub x: f64,
    pub y: f64,
}

pub fn p(x: f64, y: f64) -> P {
    P { x, y }
}

/// An axis-aligned rectangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    pub x: f64,
    pub y: f64,
    pub w: f64,
    pub h: f64,
}

impl Rect {
    pub fn new(x: f64, y: f64, w: f64, h: f64) -> Rect {
        Rect { x, y, w, h }
    }

    pub fn right(&self) -> f64 {
        self.x + self.w
    }

    pub fn bottom(&self) -> f64 {
        self.y + self.h
    }

    /// Whether the two share any area (touching edges do not count).
    pub fn overlaps(&self, o: &Rect) -> bool {
        const E: f64 = 1e-6;
        self.x < o.right() - E && o.x < self.right() - E && self.y < o.bottom() - E && o.y < self.bottom() - E
    }

    /// Whether `q` lies on the rectangle's outline.
    pub fn on_edge(&self, q: P) -> bool {
        const E: f64 = 1e-6;
        let within_x = q.x >= self.x - E && q.x <= self.right() + E;
        let within_y = q.y >= self.y - E && q.y <= self.bottom() + E;
        let on_x = (q.x - self.x).abs() < E || (q.x - self.right()).abs() < E;
        let on_y = (q.y - self.y).abs() < E || (q.y - self.bottom()).abs() < E;
        (within_x && on_y) || (within_y && on_x)
    }

    pub fn translate(&self, dx: f64, dy: f64) -> Rect {
        Rect { x: self.x + dx, y: self.y + dy, ..*self }
    }
}

/// A drawn thing that must not overlap another: a step or FST box, an
/// action block, a label's text.
#[derive(Clone, Debug, PartialEq)]
pub struct Solid {
    pub what: String,
    pub r: Rect,
}

/// One connection of the source (a transition's source or target step, an
/// FST branch) and the path drawn for it, from `from`'s outline to `to`'s.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    pub from: String,
    pub to: String,
    pub path: Vec<P>,
}

/// A simultaneous branch's double bar and the wires that belong to it (the
/// transition's stem and the wires to or from the branch's steps): any
/// other wire that meets the bar reads as if it led into the branch.
#[derive(Clone, Debug, PartialEq)]
pub struct Double {
    /// The bar: both lines, from its first branch to its last.
    pub r: Rect,
    pub own: Vec<(P, P)>,
}

/// The record of a picture's layout.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Geometry {
    pub solids: Vec<Solid>,
    /// Every node a link may start or end at, by id.
    pub nodes: Vec<(String, Rect)>,
    /// Every wire segment drawn.
    pub wires: Vec<(P, P)>,
    pub links: Vec<Link>,
    /// Named connectors: (connector id, the name it shows, the node it stands for).
    pub connectors: Vec<(String, String, String)>,
    /// The double bars of simultaneous branches.
    pub doubles: Vec<Double>,
}

impl Geometry {
    /// Moves everything by (dx, dy) and adds it to `self`.
    pub fn absorb(&mut self, other: Geometry, dx: f64, dy: f64) {
        let mv = |q: P| p(q.x + dx, q.y + dy);
        self.solids.extend(other.solids.into_iter().map(|s| Solid { what: s.what, r: s.r.translate(dx, dy) }));
        self.nodes.extend(other.nodes.into_iter().map(|(n, r)| (n, r.translate(dx, dy))));
        self.wires.extend(other.wires.into_iter().map(|(a, b)| (mv(a), mv(b))));
        self.links.extend(other.links.into_iter().map(|l| Link { path: l.path.into_iter().map(mv).collect(), ..l }));
        self.connectors.extend(other.connectors);
        self.doubles.extend(other.doubles.into_iter().map(|d| Double {
            r: d.r.translate(dx, dy),
            own: d.own.into_iter().map(|(a, b)| (mv(a), mv(b))).collect(),
        }));
    }

    /// The first wire that meets a double bar it does not belong to (touching
    /// counts: a wire that ends on the bar leads into it), with the bar.
    pub fn through_double(&self) -> Option<((P, P), Rect)> {
        const E: f64 = 1e-6;
        let same = |a: &(P, P), b: &(P, P)| (a.0 == b.0 && a.1 == b.1) || (a.0 == b.1 && a.1 == b.0);
        for d in &self.doubles {
            let r = d.r;
            for w in &self.wires {
                let (lx, hx) = (w.0.x.min(w.1.x), w.0.x.max(w.1.x));
                let (ly, hy) = (w.0.y.min(w.1.y), w.0.y.max(w.1.y));
                let meets = lx <= r.right() + E && hx >= r.x - E && ly <= r.bottom() + E && hy >= r.y - E;
                if meets && !d.own.iter().any(|o| same(o, w)) {
                    return Some((*w, r));
                }
            }
        }
        None
    }

    /// The first two solids that overlap (in the order drawn), found by
    /// bucketing the solids into a grid of cells so that only neighbours
    /// are compared: linear in the number of solids.
    pub fn overlap(&self) -> Option<(&Solid, &Solid)> {
        const CELL: f64 = 64.0;
        let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        let cells = |r: &Rect| {
            let span = |lo: f64, hi: f64| (lo / CELL).floor() as i64..=(hi / CELL).floor() as i64;
            let (xs, ys) = (span(r.x, r.right()), span(r.y, r.bottom()));
            xs.flat_map(move |x| ys.clone().map(move |y| (x, y)))
        };
        for (i, s) in self.solids.iter().enumerate() {
            for c in cells(&s.r) {
                let here = grid.entry(c).or_default();
                if let Some(&j) = here.iter().find(|&&j| self.solids[j].r.overlaps(&s.r)) {
                    return Some((&self.solids[j], s));
                }
                here.push(i);
            }
        }
        None
    }

    /// The first link that does not join its two ends with drawn wire: its
    /// ends off its nodes' outlines, a diagonal step, or a piece of its
    /// path that no wire covers.
    pub fn broken_link(&self) -> Option<&Link> {
        let nodes: HashMap<&str, Rect> = self.nodes.iter().map(|(n, r)| (n.as_str(), *r)).collect();
        let mut by_x: HashMap<i64, Vec<(f64, f64)>> = HashMap::new();
        let mut by_y: HashMap<i64, Vec<(f64, f64)>> = HashMap::new();
        let key = |v: f64| (v * 100.0).round() as i64;
        for (a, b) in &self.wires {
            if (a.x - b.x).abs() < 1e-6 {
                by_x.entry(key(a.x)).or_default().push((a.y.min(b.y), a.y.max(b.y)));
            }
            if (a.y - b.y).abs() < 1e-6 {
                by_y.entry(key(a.y)).or_default().push((a.x.min(b.x), a.x.max(b.x)));
            }
        }
        by_x.values_mut().chain(by_y.values_mut()).for_each(union);
        let covered = |lines: Option<&Vec<(f64, f64)>>, lo: f64, hi: f64| lines.is_some_and(|v| covers(v, lo, hi));
        self.links.iter().find(|l| {
            let node = |id: &String| nodes.get(id.as_str());
            let ends = match (node(&l.from), node(&l.to), l.path.first(), l.path.last()) {
                (Some(f), Some(t), Some(a), Some(b)) => f.on_edge(*a) && t.on_edge(*b),
                _ => false,
            };
            !ends
                || l.path.windows(2).any(|w| {
                    let (a, b) = (w[0], w[1]);
                    if (a.x - b.x).abs() < 1e-6 {
                        !covered(by_x.get(&key(a.x)), a.y.min(b.y), a.y.max(b.y))
                    } else if (a.y - b.y).abs() < 1e-6 {
                        !covered(by_y.get(&key(a.y)), a.x.min(b.x), a.x.max(b.x))
                    } else {
                        true
                    }
                })
        })
    }
}

/// Sorts the intervals and merges those that touch, so that coverage is
/// one binary search.
fn union(v: &mut Vec<(f64, f64)>) {
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(v.len());
    for &(a, b) in v.iter() {
        match out.last_mut() {
            Some(last) if a <= last.1 + 1e-6 => last.1 = last.1.max(b),
            _ => out.push((a, b)),
        }
    }
    *v = out;
}

/// Whether the merged, sorted intervals cover [lo, hi].
fn covers(merged: &[(f64, f64)], lo: f64, hi: f64) -> bool {
    let i = merged.partition_point(|&(a, _)| a <= lo + 1e-6);
    i > 0 && merged[i - 1].1 >= hi - 1e-6
}

/// Assigns each interval the lowest track free at its start: tracks for
/// horizontal wires that must not run over each other. Returns the track
/// of each interval (in input order) and how many tracks there are.
pub fn tracks(intervals: &[(f64, f64)], gap: f64) -> (Vec<usize>, usize) {
    let mut order: Vec<usize> = (0..intervals.len()).collect();
    order.sort_by(|&a, &b| intervals[a].0.total_cmp(&intervals[b].0).then(a.cmp(&b)));
    let mut ends: Vec<f64> = Vec::new();
    let mut out = vec![0; intervals.len()];
    for i in order {
        let (lo, hi) = intervals[i];
        let t = match ends.iter().position(|&e| e + gap <= lo) {
            Some(t) => t,
            None => {
                ends.push(f64::NEG_INFINITY);
                ends.len() - 1
            }
        };
        ends[t] = hi;
        out[i] = t;
    }
    (out, ends.len())
}
