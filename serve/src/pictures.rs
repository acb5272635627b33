//! The live pictures of a served plant: each sequence, ladder action and
//! FST table drawn by `linc-draw` with the state the plant is in now. A
//! picture is drawn again only when what it shows has changed (its key:
//! active steps and their whole seconds, powered elements and the rungs
//! the action's last execution ran, the current FST step with RR and CF),
//! so a monitor of a quiet plant costs nothing.

use crate::history::History;
use linc_compiler::Context;
use linc_compiler::{fst, ladder, sfc};
use linc_draw::trend::Recent;
use linc_driver::ladder::LiveElements;
use linc_engines::strategy::{Strategy, Want, WantKind};
use std::path::Path;

enum Live {
    Sequence { text: String, tree: sfc::ast::Sequence },
    Ladder { text: String, actions: Vec<ladder::ast::Action>, elements: LiveElements },
    Fst { table: fst::Table },
}

/// One program's picture and the state it was last drawn with.
pub struct Picture {
    pub block: usize,
    pub name: String,
    /// `sfc`, `ld` or `fst`.
    pub kind: &'static str,
    live: Live,
    key: Option<String>,
    pub svg: String,
}

/// The pictures of the programs `wants` name whose sources can be drawn:
/// sequences, ladder actions and FST tables (an ST action has none; its
/// values are in the block browser).
pub fn load(dir: &Path, wants: &[Want], s: &Strategy) -> Vec<Picture> {
    wants.iter().filter_map(|w| picture(dir, w, s)).collect()
}

fn picture(dir: &Path, w: &Want, s: &Strategy) -> Option<Picture> {
    let path = dir.join(&w.file);
    let lower = w.file.to_ascii_lowercase();
    let text = linc_driver::files::read_input_text(&path).ok()?;
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("program").to_string();
    let db = &s.store.db;
    let (kind, live) = match w.kind {
        WantKind::Sequence => {
            let tree = sfc::check_sequence(&text, Context::of(Some(db))).tree?;
            ("sfc", Live::Sequence { text, tree })
        }
        WantKind::Action if lower.ends_with(".ld") => {
            let (file, _) = ladder::parser::parse(&text, &stem);
            let actions: Vec<_> =
                file.actions.into_iter().filter(|a| a.name.text.eq_ignore_ascii_case(&w.action)).collect();
            if actions.is_empty() {
                return None;
            }
            let elements = LiveElements::new(&text, &stem, &s.store);
            ("ld", Live::Ladder { text, actions, elements })
        }
        WantKind::Fst => {
            let (table, _) = fst::reader::read(&text);
            ("fst", Live::Fst { table })
        }
        WantKind::Action => return None,
    };
    let name = db.blocks[w.block].name.clone();
    Some(Picture { block: w.block, name, kind, live, key: None, svg: String::new() })
}

impl Picture {
    /// Draws the picture again if the plant's state it shows has changed;
    /// `true` when it did.
    pub fn refresh(&mut self, s: &mut Strategy) -> bool {
        let block = self.block;
        match &self.live {
            Live::Sequence { text, tree } => {
                let Some(seq) = s.sequence(block) else { return false };
                let look = |name: &str| linc_driver::draw::step_state(seq, name);
                let mut key = seq.status.name().to_string();
                for n in seq.active_steps() {
                    let secs = seq.step(n).map_or(0, |(_, us)| us / 1_000_000);
                    key.push_str(&format!(" {n}:{secs}"));
                }
                let mut held: Vec<&String> = seq.monitor.held.iter().collect();
                held.sort();
                for h in held {
                    key.push_str(&format!(" held:{h}"));
                }
                if self.key.as_deref() == Some(key.as_str()) {
                    return false;
                }
                self.svg = linc_draw::sfc::sequence(text, tree, Some(&look)).0;
                self.key = Some(key);
            }
            Live::Ladder { text, actions, elements } => {
                // Watched from the first drawing, made before the first
                // scan: from then on the action's last execution is known.
                if s.lines_ran(block).is_none() {
                    s.watch_runs(block);
                }
                let ran = s.lines_ran(block).filter(|r| r.executions > 0).map(|r| r.lines.clone());
                let truths = elements.truths(&mut s.store);
                let mut known: Vec<_> = truths.iter().collect();
                known.sort();
                let key = format!("{known:?} {ran:?}");
                if self.key.as_deref() == Some(key.as_str()) {
                    return false;
                }
                let look = |span: linc_compiler::diag::span::Span| truths.get(&(span.start, span.end)).copied();
                self.svg = linc_draw::ladder::file(text, actions, Some(&look), ran.as_deref()).0;
                self.key = Some(key);
            }
            Live::Fst { table } => {
                let state = linc_driver::draw::fst_state(s, block);
                let key =
                    format!("{:?} {} {} {} {:?}", state.current, state.rr, state.cf, state.runflg, state.registers);
                if self.key.as_deref() == Some(key.as_str()) {
                    return false;
                }
                self.svg = linc_draw::fst::table(table, Some(&state)).0;
                self.key = Some(key);
            }
        }
        true
    }
}

/// How a trend is named in `GET /api/pictures/NAME`:
/// `trend:SECONDS:BLOCK.FIELD,BLOCK.FIELD…` — the page's trend, drawn by
/// `linc-draw` as `linc draw` draws a trace's, not a second drawing in the
/// page's script.
pub const TREND: &str = "trend:";

/// The most fields one trend draws.
const MAX_TREND_FIELDS: usize = 12;

/// The trend `spec` (a [`TREND`] name without its prefix) names: its
/// fields over the last SECONDS of simulated time (at most the history's
/// 15 minutes), from the changes the history kept. `None` when the window
/// is not a positive number of seconds or a field is not in the database.
pub fn trend(spec: &str, history: &History, s: &Strategy) -> Option<String> {
    let (secs, fields) = spec.split_once(':')?;
    let window = secs.parse::<f64>().ok().filter(|w| w.is_finite() && *w > 0.0)?;
    let window = window.min(crate::history::KEEP_US as f64 / 1e6);
    let seconds = |us: u64| us as f64 / 1e6;
    let now = seconds(s.elapsed_us());
    let from = (now - window).max(0.0);
    let store = &s.store;
    let mut out = Vec::new();
    for path in fields.split(',').filter(|p| !p.trim().is_empty()).take(MAX_TREND_FIELDS) {
        let cell = linc_engines::console::fields::address(store, path.trim()).ok()?.cell;
        let kept = history.of(cell);
        // The value when the window opens: the last change before it, or
        // the value now for a field that has not changed in the history.
        let before = kept.iter().rev().find(|(t, _)| seconds(*t) < from).map(|(_, v)| v.to_string());
        let start = before.or_else(|| kept.is_empty().then(|| store.show(cell)));
        let changes = kept.iter().map(|(t, v)| (seconds(*t), v.to_string())).collect();
        out.push(Recent { name: store.describe(cell), start, changes });
    }
    Some(linc_draw::trend::recent(out, from, now))
}
