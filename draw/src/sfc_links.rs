//! The wires of a chart: each net's line (doubled for a simultaneous
//! branch) with the stems to its nodes, and each link's path along them or
//! along a lane; each double bar is recorded with the wires that belong to
//! it, so the layout tests can tell another branch's wire running into it.

use super::*;
use crate::geom::Double;

/// Where a link leaves node `u` and enters node `v`.
fn out_port(ctx: &Ctx, g: &Graph, pl: &Place, u: usize) -> P {
    let top = pl.row_top[g.nodes[u].rank];
    match g.nodes[u].kind {
        Kind::Step(_) => p(pl.spine[u], top + ctx.box_h()),
        Kind::Trans(_) => p(pl.spine[u], top + 14.0),
        Kind::Jump => p(pl.spine[u], top + 16.0),
    }
}

fn in_port(g: &Graph, pl: &Place, v: usize) -> P {
    let top = pl.row_top[g.nodes[v].rank];
    match g.nodes[v].kind {
        Kind::Trans(_) => p(pl.spine[v], top + 10.0),
        Kind::Step(_) | Kind::Jump => p(pl.spine[v], top),
    }
}

/// The wires of every net and link; each double bar is recorded with the
/// wires that belong to it (geom::Double), for the layout tests.
pub(super) fn wires(ctx: &Ctx, g: &Graph, pl: &Place, svg: &mut Svg, geo: &mut Geometry) {
    let mut own: Vec<Vec<(P, P)>> = vec![Vec::new(); pl.nets.len()];
    net_wires(g, pl, svg, geo, &mut own);
    link_wires(ctx, g, pl, svg, geo, &mut own);
    for (n, own) in pl.nets.iter().zip(own) {
        if n.double {
            geo.doubles.push(Double { r: Rect::new(n.lo, n.y, n.hi - n.lo, 3.0), own });
        }
    }
}

/// A wire of net `net` (if any).
fn net_wire(svg: &mut Svg, geo: &mut Geometry, own: Option<&mut Vec<(P, P)>>, a: P, b: P) {
    wire(svg, geo, a, b);
    if let Some(o) = own {
        o.push((a, b));
    }
}

fn net_wires(g: &Graph, pl: &Place, svg: &mut Svg, geo: &mut Geometry, own: &mut [Vec<(P, P)>]) {
    for (i, n) in pl.nets.iter().enumerate() {
        let o = &mut own[i];
        net_wire(svg, geo, Some(o), p(n.lo, n.y), p(n.hi, n.y));
        if n.double {
            svg.line(p(n.lo, n.y + 3.0), p(n.hi, n.y + 3.0), "wire double");
        }
        match n.kind {
            NetKind::Out(u) => net_wire(svg, geo, Some(o), p(pl.spine[u], row_bottom(g, pl, u)), p(pl.spine[u], n.y)),
            NetKind::In(v) => {
                net_wire(svg, geo, Some(o), p(pl.spine[v], n.y), p(pl.spine[v], pl.row_top[g.nodes[v].rank]))
            }
            NetKind::Plain(e) => {
                let (u, v) = (g.edges[e].from, g.edges[e].to);
                net_wire(svg, geo, Some(o), p(pl.spine[u], row_bottom(g, pl, u)), p(pl.spine[u], n.y));
                net_wire(svg, geo, Some(o), p(pl.spine[v], n.y), p(pl.spine[v], pl.row_top[g.nodes[v].rank]));
            }
        }
    }
}

fn link_wires(ctx: &Ctx, g: &Graph, pl: &Place, svg: &mut Svg, geo: &mut Geometry, own: &mut [Vec<(P, P)>]) {
    for (e, edge) in g.edges.iter().enumerate() {
        let (u, v) = (edge.from, edge.to);
        let [fo, fi, plain] = pl.edge_nets[e];
        let (xu, xv) = (pl.spine[u], pl.spine[v]);
        let (rb, rt) = (row_bottom(g, pl, u), pl.row_top[g.nodes[v].rank]);
        let mut path = vec![out_port(ctx, g, pl, u), p(xu, rb)];
        match (edge.lane, fo, fi, plain) {
            (Some(k), Some(o), Some(i), _) => {
                let (lx, yo, yi) = (pl.lane_x[k], pl.nets[o].y, pl.nets[i].y);
                net_wire(svg, geo, Some(&mut own[o]), p(lx, yo), p(lx, yi));
                own[i].push((p(lx, yo), p(lx, yi)));
                svg.arrow(p(lx, (yo + yi) / 2.0), 0.0, if yi < yo { -1.0 } else { 1.0 });
                path.extend([p(xu, yo), p(lx, yo), p(lx, yi), p(xv, yi)]);
            }
            _ => {
                if let Some(o) = fo {
                    let y = pl.nets[o].y;
                    let to = fi.map_or(rt, |i| pl.nets[i].y);
                    net_wire(svg, geo, Some(&mut own[o]), p(xv, y), p(xv, to));
                    if let Some(i) = fi {
                        own[i].push((p(xv, y), p(xv, to)));
                    }
                    path.extend([p(xu, y), p(xv, y)]);
                }
                if let Some(i) = fi {
                    let y = pl.nets[i].y;
                    let x0 = if fo.is_some() { xv } else { xu };
                    if fo.is_none() {
                        net_wire(svg, geo, Some(&mut own[i]), p(xu, rb), p(xu, y));
                    }
                    path.extend([p(x0, y), p(xv, y)]);
                }
                if let Some(pn) = plain {
                    let y = pl.nets[pn].y;
                    path.extend([p(xu, y), p(xv, y)]);
                }
            }
        }
        path.push(p(xv, rt));
        path.push(in_port(g, pl, v));
        if edge.lane.is_some() {
            svg.arrow(p(xv, rt), 0.0, 1.0);
        }
        path.dedup();
        geo.links.push(Link { from: g.nodes[u].id.clone(), to: g.nodes[v].id.clone(), path });
    }
}
