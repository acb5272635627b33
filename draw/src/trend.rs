//! A trend chart of a `--trace` file (docs/pictures.md): the fields asked
//! for over simulated time — numbers as step lines in one plot, BOOLs and
//! other values as strips — and a strip per sequence showing which steps
//! were active when. The trace is read a line at a time and each field is
//! thinned to what a pixel column can show, so a day's trace of gigabytes
//! draws in bounded memory.

use crate::geom::Rect;
use crate::svg::{num, text_width, Svg};
use linc_format::Code;
use std::collections::BTreeMap;

const PLOT_W: f64 = 800.0;
const PLOT_H: f64 = 240.0;
const LEFT: f64 = 90.0;
const STRIP_H: f64 = 26.0;

/// A trace that cannot be drawn: located at a line of it, or about a field.
#[derive(Clone, Debug, PartialEq)]
pub struct TrendError {
    pub code: Code,
    /// 1-based line of the trace, when the error is about one.
    pub line: Option<usize>,
    pub message: String,
}

/// The value of a field over time: (seconds, value as the trace shows it).
#[derive(Default)]
struct Series {
    name: String,
    /// The value before its first change in range.
    start: Option<String>,
    points: Vec<(f64, String)>,
}

/// A trend being read.
pub struct Trend {
    fields: Vec<Series>,
    from: f64,
    to: Option<f64>,
    last_time: f64,
    /// Active steps of each sequence (by program) as (time, step, active).
    steps: BTreeMap<String, Vec<(f64, String, bool)>>,
    lines: usize,
}

impl Trend {
    /// A trend of `fields` (BLOCK.FIELD, any case) between `from` and `to`
    /// seconds of the trace (the whole of it by default).
    pub fn new(fields: &[String], from: Option<f64>, to: Option<f64>) -> Trend {
        let fields = fields.iter().map(|f| Series { name: f.clone(), ..Series::default() }).collect();
        Trend { fields, from: from.unwrap_or(0.0), to, last_time: 0.0, steps: BTreeMap::new(), lines: 0 }
    }

    /// Reads the trace's next line.
    pub fn feed(&mut self, line: &str) -> Result<(), TrendError> {
        self.lines += 1;
        if line.trim().is_empty() {
            return Ok(());
        }
        let bad = |m: &str| TrendError { code: Code::E0910, line: Some(self.lines), message: m.to_string() };
        let v: serde_json::Value = serde_json::from_str(line).map_err(|e| bad(&format!("not JSON: {e}")))?;
        let time = v.get("time").and_then(serde_json::Value::as_f64).ok_or_else(|| bad("no \"time\""))?;
        if !time.is_finite() || time < self.last_time {
            return Err(bad("its time is not a number at or after the line before's"));
        }
        self.last_time = time;
        if let (Some(step), Some(active), Some(program)) = (
            v.get("step").and_then(|s| s.as_str()),
            v.get("active").and_then(|a| a.as_bool()),
            v.get("program").and_then(|a| a.as_str()),
        ) {
            self.steps.entry(program.to_string()).or_default().push((time, step.to_string(), active));
            return Ok(());
        }
        let Some(field) = v.get("field").and_then(|f| f.as_str()) else { return Ok(()) };
        let (Some(old), Some(new)) = (v.get("old").and_then(|s| s.as_str()), v.get("new").and_then(|s| s.as_str()))
        else {
            return Ok(());
        };
        let Some(s) = self.fields.iter_mut().find(|s| s.name.eq_ignore_ascii_case(field)) else { return Ok(()) };
        if time < self.from || self.to.is_some_and(|t| time > t) {
            if time < self.from {
                s.start = Some(new.to_string());
            }
            return Ok(());
        }
        if s.start.is_none() && s.points.is_empty() {
            s.start = Some(old.to_string());
        }
        s.points.push((time, new.to_string()));
        thin(&mut s.points, self.from, self.to.unwrap_or(time.max(self.from + 1.0)));
        Ok(())
    }

    /// The chart, or the first field the trace never wrote (E0911).
    pub fn finish(mut self) -> Result<String, TrendError> {
        if let Some(s) = self.fields.iter().find(|s| s.start.is_none() && s.points.is_empty()) {
            return Err(TrendError {
                code: Code::E0911,
                line: None,
                message: match self.to {
                    Some(to) => format!("the trace never writes `{}` up to {to} s (the end of --to)", s.name),
                    None => format!("the trace never writes `{}`", s.name),
                },
            });
        }
        let to = self.to.unwrap_or(self.last_time).max(self.from + 1e-6);
        let from = self.from;
        let x = |t: f64| LEFT + (t.clamp(from, to) - from) / (to - from) * PLOT_W;
        let mut svg = Svg::new();
        let (numeric, other): (Vec<&Series>, Vec<&Series>) = self.fields.iter().partition(|s| is_numeric(s));
        let mut y = 12.0;
        legend(&mut svg, &numeric, &mut y);
        if !numeric.is_empty() {
            plot(&mut svg, &numeric, &x, (from, to), y);
            y += PLOT_H + 12.0;
        }
        for s in &other {
            strip(&mut svg, &s.name, &segments(s, to), &x, y);
            y += STRIP_H + 6.0;
        }
        for (program, changes) in std::mem::take(&mut self.steps) {
            strip(&mut svg, &program, &active_sets(&changes, from, to), &x, y);
            y += STRIP_H + 6.0;
        }
        axis(&mut svg, &x, (from, to), y);
        Ok(svg.finish("trend", LEFT + PLOT_W + 20.0, y + 30.0))
    }
}

/// One field of a live trend: its name as shown, its value when the
/// window opens (`None` when not known), and its changes in the window as
/// (seconds, value), oldest first.
pub struct Recent {
    pub name: String,
    pub start: Option<String>,
    pub changes: Vec<(f64, String)>,
}

/// A trend of a running plant's recent past (`linc serve`'s page), from
/// `from` to `to` seconds of its clock: drawn as [`Trend::finish`] draws a
/// trace — the same plot, value scale, strips and time axis — so the live
/// page and `linc draw` show a trend alike. A field with neither a start
/// nor a change is left out.
pub fn recent(fields: Vec<Recent>, from: f64, to: f64) -> String {
    let to = to.max(from + 1e-6);
    let mut series: Vec<Series> = Vec::with_capacity(fields.len());
    for f in fields.into_iter().filter(|f| f.start.is_some() || !f.changes.is_empty()) {
        let mut points: Vec<(f64, String)> = f.changes.into_iter().filter(|(t, _)| *t >= from && *t <= to).collect();
        thin(&mut points, from, to);
        series.push(Series { name: f.name, start: f.start, points });
    }
    let t = Trend { fields: series, from, to: Some(to), last_time: to, steps: BTreeMap::new(), lines: 0 };
    t.finish().unwrap_or_default()
}

/// Keeps at most about four points per pixel column: first, lowest,
/// highest and last (values that are not numbers are all kept while few).
fn thin(points: &mut Vec<(f64, String)>, from: f64, to: f64) {
    if points.len() < 8 * PLOT_W as usize {
        return;
    }
    let col = |t: f64| (((t - from) / (to - from).max(1e-9)) * PLOT_W / 2.0) as i64;
    let mut out: Vec<(f64, String)> = Vec::with_capacity(points.len() / 2);
    let mut i = 0;
    while i < points.len() {
        let c = col(points[i].0);
        let mut j = i;
        while j < points.len() && col(points[j].0) == c {
            j += 1;
        }
        let group = &points[i..j];
        let val = |p: &(f64, String)| p.1.parse::<f64>().unwrap_or(0.0);
        let lo = group.iter().min_by(|a, b| val(a).total_cmp(&val(b)));
        let hi = group.iter().max_by(|a, b| val(a).total_cmp(&val(b)));
        let mut keep: Vec<&(f64, String)> = [group.first(), lo, hi, group.last()].into_iter().flatten().collect();
        keep.sort_by(|a, b| a.0.total_cmp(&b.0));
        keep.dedup_by(|a, b| a.0 == b.0 && a.1 == b.1);
        out.extend(keep.into_iter().cloned());
        i = j;
    }
    *points = out;
}

fn number(text: &str) -> Option<f64> {
    text.trim().parse::<f64>().ok().filter(|v| v.is_finite())
}

fn is_numeric(s: &Series) -> bool {
    s.start.iter().chain(s.points.iter().map(|p| &p.1)).all(|v| number(v).is_some())
}

fn legend(svg: &mut Svg, numeric: &[&Series], y: &mut f64) {
    let mut x = LEFT;
    for (i, s) in numeric.iter().enumerate() {
        svg.line(crate::geom::p(x, *y + 6.0), crate::geom::p(x + 16.0, *y + 6.0), &format!("line c{}", i % 6));
        svg.text(x + 20.0, *y + 10.0, &s.name, "", "start");
        x += 40.0 + text_width(&s.name);
    }
    if !numeric.is_empty() {
        *y += 20.0;
    }
}

fn plot(svg: &mut Svg, numeric: &[&Series], x: &dyn Fn(f64) -> f64, (from, to): (f64, f64), top: f64) {
    let values =
        numeric.iter().flat_map(|s| s.start.iter().chain(s.points.iter().map(|p| &p.1))).filter_map(|v| number(v));
    let (mut lo, mut hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    if hi - lo < 1e-9 {
        lo -= 1.0;
        hi += 1.0;
    }
    let y = |v: f64| top + PLOT_H - (v - lo) / (hi - lo) * PLOT_H;
    svg.rect(Rect::new(LEFT, top, PLOT_W, PLOT_H), "frame");
    for k in 0..=4 {
        let v = lo + (hi - lo) * f64::from(k) / 4.0;
        svg.text(LEFT - 6.0, y(v) + 4.0, &num(v), "dim", "end");
    }
    for (i, s) in numeric.iter().enumerate() {
        let mut pts = Vec::new();
        let mut last = s.start.as_deref().and_then(number);
        if let Some(v) = last {
            pts.push(crate::geom::p(x(from), y(v)));
        }
        for (t, text) in &s.points {
            let Some(v) = number(text) else { continue };
            if let Some(prev) = last {
                pts.push(crate::geom::p(x(*t), y(prev)));
            }
            pts.push(crate::geom::p(x(*t), y(v)));
            last = Some(v);
        }
        if let Some(v) = last {
            pts.push(crate::geom::p(x(to), y(v)));
        }
        svg.open(Some(&crate::svg::id("trend-", &s.name)), "series");
        svg.title(&s.name);
        svg.polyline(&pts, &format!("line c{}", i % 6), "");
        svg.close();
    }
}

/// A field's values as (start, end, text) pieces.
fn segments(s: &Series, to: f64) -> Vec<(f64, f64, String)> {
    let mut out: Vec<(f64, f64, String)> = Vec::new();
    let mut cur = s.start.clone().map(|v| (f64::NEG_INFINITY, v));
    for (t, v) in &s.points {
        if let Some((a, text)) = cur.take() {
            out.push((a, *t, text));
        }
        cur = Some((*t, v.clone()));
    }
    if let Some((a, text)) = cur {
        out.push((a, to, text));
    }
    out
}

/// Which steps of a sequence were active when, as pieces.
fn active_sets(changes: &[(f64, String, bool)], from: f64, to: f64) -> Vec<(f64, f64, String)> {
    let mut active: Vec<String> = Vec::new();
    let mut out = Vec::new();
    let mut since = f64::NEG_INFINITY;
    let mut i = 0;
    while i < changes.len() {
        let t = changes[i].0;
        let before = active.join(" + ");
        while i < changes.len() && changes[i].0 == t {
            let (_, step, on) = &changes[i];
            active.retain(|s| s != step);
            if *on {
                active.push(step.clone());
            }
            i += 1;
        }
        if !before.is_empty() {
            out.push((since, t, before));
        }
        since = t;
    }
    if !active.is_empty() {
        out.push((since, to, active.join(" + ")));
    }
    out.retain(|(a, b, _)| *b >= from && *a <= to);
    out
}

fn strip(svg: &mut Svg, name: &str, pieces: &[(f64, f64, String)], x: &dyn Fn(f64) -> f64, y: f64) {
    svg.open(Some(&crate::svg::id("strip-", name)), "strip");
    svg.text(LEFT - 6.0, y + 17.0, name, "name", "end");
    svg.rect(Rect::new(LEFT, y, PLOT_W, STRIP_H), "frame");
    if !pieces.is_empty() && pieces.iter().all(|p| p.2 == "TRUE" || p.2 == "FALSE") {
        // A BOOL: a step line, high while TRUE.
        let level = |t: &str| if t == "TRUE" { y + 5.0 } else { y + STRIP_H - 5.0 };
        let mut pts = Vec::new();
        for (a, b, text) in pieces {
            pts.push(crate::geom::p(x(*a), level(text)));
            pts.push(crate::geom::p(x(*b), level(text)));
        }
        svg.polyline(&pts, "line c0", "");
        svg.close();
        return;
    }
    for (k, (a, b, text)) in pieces.iter().enumerate() {
        let (xa, xb) = (x(*a), x(*b));
        let class = match text.as_str() {
            "TRUE" => "piece on".to_string(),
            "FALSE" => "piece off".to_string(),
            _ => format!("piece p{}", k % 2),
        };
        svg.open(None, &class);
        svg.title(&format!("{text} from {}s to {}s", num(a.max(0.0)), num(*b)));
        svg.rect(Rect::new(xa, y + 3.0, (xb - xa).max(0.5), STRIP_H - 6.0), "box");
        if text_width(text) + 6.0 < xb - xa {
            svg.text(xa + 3.0, y + 17.0, text, "", "start");
        }
        svg.close();
    }
    svg.close();
}

/// The time axis: about eight ticks at round numbers of seconds.
fn axis(svg: &mut Svg, x: &dyn Fn(f64) -> f64, (from, to): (f64, f64), y: f64) {
    svg.line(crate::geom::p(LEFT, y), crate::geom::p(LEFT + PLOT_W, y), "wire");
    let span = to - from;
    let step = [0.1, 0.5, 1.0, 5.0, 10.0, 30.0, 60.0, 300.0, 600.0, 1800.0, 3600.0, 7200.0, 21600.0, 43200.0, 86400.0]
        .into_iter()
        .find(|s| span / s <= 8.0)
        .unwrap_or(span / 8.0);
    let mut t = (from / step).ceil() * step;
    let mut ticks = 0;
    while t <= to + 1e-9 && ticks < 64 {
        svg.line(crate::geom::p(x(t), y), crate::geom::p(x(t), y + 4.0), "wire");
        svg.text(x(t), y + 16.0, &clock(t), "dim", "middle");
        t += step;
        ticks += 1;
    }
}

/// Seconds since the start as `1h02m03s`, `4m05s` or `6.5s`.
fn clock(t: f64) -> String {
    let whole = t.floor() as u64;
    let (h, m, s) = (whole / 3600, whole / 60 % 60, whole % 60);
    match (h, m) {
        (0, 0) => format!("{}s", num(t)),
        (0, _) => format!("{m}m{s:02}s"),
        _ => format!("{h}h{m:02}m{s:02}s"),
    }
}
