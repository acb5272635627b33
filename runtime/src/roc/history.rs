//! History points and the FST commands that write and read them (Tables
//! B-16 and B-17, `docs/fst-history.md`).
//!
//! A history point is a block of template `HIST` named `HIST n`, n its
//! number 1–200. Each point has three archives of (stamp, value) entries:
//! periodic, daily and minute. FST points (FSTDATA, FSTSEC, FSTMIN) are
//! filled only by WDB and WTM at the index the FST gives; CURRENT points
//! only by the logger ([`History::sample`], in `logger.rs`).

use super::clock::{self, civil};
use super::real;
use crate::db::{Database, InitValue};
use linc_format::Code;
use serde_json::{json, Value};
use std::fmt;

/// History point numbers run from 1 to this.
pub const MAX_POINTS: u16 = 200;
/// The minute archive: one entry per minute of the hour.
pub const MINUTE_ENTRIES: usize = 60;
/// Periodic entries when PERIODIC is 0 (35 days of hours).
pub const DEFAULT_PERIODIC: usize = 840;
/// Daily entries when DAILY is 0.
pub const DEFAULT_DAILY: usize = 35;
/// The periodic interval in minutes when PERIOD is 0.
pub const DEFAULT_PERIOD: u32 = 60;
/// The most periodic entries a point may have (a leap year of hours):
/// archives are allocated whole when the database loads, so their size
/// is bounded.
pub const MAX_PERIODIC: usize = 8784;
/// The most daily entries a point may have (a leap year of days).
pub const MAX_DAILY: usize = 366;
/// The code of every [`HistError`]: the FST halts.
pub const HALT: Code = Code::R0011;

/// ARCHTYP: what fills a history point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArchiveType {
    /// Nothing: the archives stay empty.
    None,
    /// WDB/WTM; WTM stores seconds.
    FstData,
    /// WDB/WTM; WTM stores seconds.
    FstSec,
    /// WDB/WTM; WTM stores the time rounded down to the minute.
    FstMin,
    /// The logger samples ARCHPT.
    Current,
}

impl ArchiveType {
    /// As the HIST template's ARCHTYP enum spells it.
    pub const NAMES: [&'static str; 5] = ["NONE", "FSTDATA", "FSTSEC", "FSTMIN", "CURRENT"];
    const ALL: [ArchiveType; 5] =
        [ArchiveType::None, ArchiveType::FstData, ArchiveType::FstSec, ArchiveType::FstMin, ArchiveType::Current];

    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// By name, ignoring case.
    pub fn parse(s: &str) -> Option<ArchiveType> {
        Self::NAMES.iter().position(|n| n.eq_ignore_ascii_case(s.trim())).map(|i| Self::ALL[i])
    }

    /// Whether WDB, WTM and RDB may address the point.
    pub fn is_fst(self) -> bool {
        matches!(self, ArchiveType::FstData | ArchiveType::FstSec | ArchiveType::FstMin)
    }
}

pub use crate::isa::HistFn;

/// A history command the device halts on (the FST stops; the integrator
/// sets run flag 5). Always code [`HALT`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HistError {
    pub code: Code,
    pub message: String,
}

impl HistError {
    fn new(message: String) -> Self {
        HistError { code: HALT, message }
    }
}

impl fmt::Display for HistError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.code, self.message)
    }
}

impl std::error::Error for HistError {}

/// One archive entry. Never written: stamp 0 and value 0.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Entry {
    /// The device clock when it was written, POSIX seconds.
    pub stamp: i64,
    pub value: f32,
}

impl Entry {
    pub fn is_written(&self) -> bool {
        self.stamp != 0
    }
}

/// Which archive of a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Archive {
    Periodic,
    Daily,
    Minute,
}

impl Archive {
    fn name(self) -> &'static str {
        match self {
            Archive::Periodic => "periodic",
            Archive::Daily => "daily",
            Archive::Minute => "minute",
        }
    }
}

/// One history point: its configuration and its archives.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// 1–200.
    pub number: u16,
    /// The block's name as the database writes it.
    pub block: String,
    pub kind: ArchiveType,
    /// ARCHPT as configured, trimmed (`"SFP 1,DATA1"`); only CURRENT
    /// points use it.
    pub archpt: String,
    /// The periodic interval in minutes: a divisor of 1440.
    pub period: u32,
    pub(super) periodic: Vec<Entry>,
    pub(super) daily: Vec<Entry>,
    pub(super) minute: Vec<Entry>,
    /// Where the logger writes next in the periodic and daily archives.
    pub(super) next_periodic: usize,
    pub(super) next_daily: usize,
}

impl Point {
    /// The entries of one archive, by index.
    pub fn archive(&self, a: Archive) -> &[Entry] {
        match a {
            Archive::Periodic => &self.periodic,
            Archive::Daily => &self.daily,
            Archive::Minute => &self.minute,
        }
    }

    /// Where the logger writes next in the periodic or daily archive (a
    /// ROC host's "current index"); the minute archive is indexed by the
    /// minute of the hour, which the caller knows from the clock.
    pub fn next_index(&self, a: Archive) -> Option<usize> {
        match a {
            Archive::Periodic => Some(self.next_periodic),
            Archive::Daily => Some(self.next_daily),
            Archive::Minute => None,
        }
    }

    /// The entry at an index given as an FST value: a whole number from 0
    /// to the archive's size − 1, else the FST halts.
    fn entry(&self, a: Archive, idx: f32) -> Result<(usize, Entry), HistError> {
        let entries = self.archive(a);
        let i = whole(idx).filter(|&i| i >= 0 && (i as usize) < entries.len()).ok_or_else(|| {
            let message = format!(
                "invalid history index {idx} for the {} archive of history point {} ({} entries: 0 to {})",
                a.name(),
                self.number,
                entries.len(),
                entries.len().saturating_sub(1)
            );
            HistError::new(message)
        })? as usize;
        Ok((i, entries[i]))
    }

    /// DIS/PIS (`first`) or DIN/PIN: the entries whose stamp falls on
    /// `month_day` (MMDD), in any year. The start is the index of the
    /// earliest such stamp (the lowest index when stamps tie), so that
    /// counting forward from it follows the day even when the archive
    /// has wrapped. −1 when none (also for a value that is no date).
    fn find_day(&self, a: Archive, month_day: f32, first: bool) -> f32 {
        let Some(md) = whole(month_day).filter(|md| (101..=1231).contains(md)) else {
            return -1.0;
        };
        let on_day = self
            .archive(a)
            .iter()
            .enumerate()
            .filter(|(_, e)| e.is_written() && i64::from(civil(e.stamp).month_day()) == md);
        if first {
            on_day.min_by_key(|(i, e)| (e.stamp, *i)).map_or(-1.0, |(i, _)| i as f32)
        } else {
            match on_day.count() {
                0 => -1.0,
                n => n as f32,
            }
        }
    }

    fn to_json(&self) -> Value {
        let entries = |a: Archive| -> Vec<Value> {
            let list = self.archive(a).iter().enumerate().filter(|(_, e)| e.is_written());
            list.map(
                |(i, e)| json!({"index": i, "time": clock::iso(e.stamp), "stamp": e.stamp, "value": real(e.value)}),
            )
            .collect()
        };
        json!({
            "number": self.number,
            "block": self.block,
            "type": self.kind.name(),
            "archpt": self.archpt,
            "period": self.period,
            "sizes": {"periodic": self.periodic.len(), "daily": self.daily.len(), "minute": self.minute.len()},
            "periodic": entries(Archive::Periodic),
            "daily": entries(Archive::Daily),
            "minute": entries(Archive::Minute),
        })
    }
}

/// The integer an FST value stands for, if it is a whole number in the
/// `i64` range (NaN and infinities are not).
fn whole(x: f32) -> Option<i64> {
    (x.is_finite() && x.fract() == 0.0 && x.abs() < 9.0e18).then_some(x as i64)
}

/// Every history point of a database, with its archives.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct History {
    /// Sorted by number, one per number.
    pub(super) points: Vec<Point>,
    /// What [`History::from_db`] found wrong and how it went on.
    pub(super) notes: Vec<String>,
    /// The device clock at the logger's last call.
    pub(super) last: Option<i64>,
}

impl History {
    /// The history points of a database: the blocks of template `HIST`
    /// named `HIST n` (case and spaces ignored). Loading never fails: a
    /// configuration the archives cannot follow is noted in
    /// [`History::notes`] and replaced as the note says.
    pub fn from_db(db: &Database) -> History {
        let mut h = History::default();
        let Some(tpl) = db.template("HIST") else {
            return h;
        };
        for b in db.blocks.iter().filter(|b| b.template == tpl) {
            let Some(number) = point_number(&b.name) else {
                h.notes.push(format!(
                    "block `{}` of type HIST is not a history point: it must be named `HIST n`, n from 1 to {MAX_POINTS}",
                    b.name
                ));
                continue;
            };
            match h.points.binary_search_by_key(&number, |p| p.number) {
                Ok(i) => h.notes.push(format!(
                    "block `{}` is history point {number} again (after `{}`): only the first is used",
                    b.name, h.points[i].block
                )),
                Err(i) => {
                    let p = configure(db, tpl, b, number, &mut h.notes);
                    h.points.insert(i, p);
                }
            }
        }
        h
    }

    /// Configuration problems found by [`History::from_db`], one sentence each.
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// The points, by number.
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// A point by number.
    pub fn point(&self, number: u16) -> Option<&Point> {
        self.points.binary_search_by_key(&number, |p| p.number).ok().map(|i| &self.points[i])
    }

    /// The point an FST value names: a whole number 1–200 with a `HIST n`
    /// block, else the FST halts.
    fn lookup(&self, hp: f32) -> Result<usize, HistError> {
        let n = whole(hp).filter(|n| (1..=i64::from(MAX_POINTS)).contains(n));
        let Some(n) = n else {
            return Err(HistError::new(format!(
                "invalid history point {hp}: history points are whole numbers from 1 to {MAX_POINTS}"
            )));
        };
        self.points
            .binary_search_by_key(&(n as u16), |p| p.number)
            .map_err(|_| HistError::new(format!("no history point {n}: the database has no block `HIST {n}`")))
    }

    /// An FST point, for WDB, WTM and RDB: those commands address the
    /// periodic archive by the FST's own index, which only FST points let
    /// the FST own.
    fn fst_point(&self, hp: f32, cmd: &str) -> Result<usize, HistError> {
        let i = self.lookup(hp)?;
        let p = &self.points[i];
        if p.kind.is_fst() {
            Ok(i)
        } else {
            Err(HistError::new(format!(
                "{cmd} needs an FST history point (ARCHTYP FSTDATA, FSTSEC or FSTMIN); history point {} is {}",
                p.number,
                p.kind.name()
            )))
        }
    }

    /// WDB (`value` is RR) or WTM (`value` is `None`: the time) into FST
    /// point `hp` at periodic index `idx`. The entry's stamp is `now`.
    /// WTM's value is `now` as an f32 (held to 128 s, as in the device's
    /// floating-point registers), on an FSTMIN point rounded down to the
    /// minute first. Returns the next index: `idx + 1`, 0 past the last.
    pub fn write(&mut self, hp: f32, idx: f32, value: Option<f32>, now: i64) -> Result<f32, HistError> {
        let cmd = if value.is_some() { "WDB" } else { "WTM" };
        let pi = self.fst_point(hp, cmd)?;
        let p = &mut self.points[pi];
        let (i, _) = p.entry(Archive::Periodic, idx)?;
        let value = value.unwrap_or(match p.kind {
            ArchiveType::FstMin => now.div_euclid(60).saturating_mul(60) as f32,
            _ => now as f32,
        });
        p.periodic[i] = Entry { stamp: now, value };
        Ok(if i + 1 >= p.periodic.len() { 0.0 } else { (i + 1) as f32 })
    }

    /// The read commands: `(RR, ARGUMENT2 after)`. Only RDB advances
    /// ARGUMENT2 (to `idx + 1`, 0 past the last); the others return it
    /// unchanged.
    pub fn read(&self, f: HistFn, arg1: f32, arg2: f32) -> Result<(f32, f32), HistError> {
        use Archive::{Daily, Minute, Periodic};
        let rr = match f {
            HistFn::Gte => gte(arg1, arg2)?,
            HistFn::Rdb => {
                let p = &self.points[self.fst_point(arg1, "RDB")?];
                let (i, e) = p.entry(Periodic, arg2)?;
                let next = if i + 1 >= p.periodic.len() { 0.0 } else { (i + 1) as f32 };
                return Ok((e.value, next));
            }
            HistFn::Dis | HistFn::Din | HistFn::Pis | HistFn::Pin => {
                let p = &self.points[self.lookup(arg1)?];
                let a = if matches!(f, HistFn::Dis | HistFn::Din) { Daily } else { Periodic };
                p.find_day(a, arg2, matches!(f, HistFn::Dis | HistFn::Pis))
            }
            HistFn::Dhv | HistFn::Dht | HistFn::Phv | HistFn::Pht | HistFn::Mhv => {
                let p = &self.points[self.lookup(arg1)?];
                let a = match f {
                    HistFn::Dhv | HistFn::Dht => Daily,
                    HistFn::Mhv => Minute,
                    _ => Periodic,
                };
                let e = p.entry(a, arg2)?.1;
                if matches!(f, HistFn::Dht | HistFn::Pht) {
                    e.stamp as f32
                } else {
                    e.value
                }
            }
        };
        Ok((rr, arg2))
    }

    /// `{"points": [...]}`: each point's number, block, type, ARCHPT,
    /// period, archive sizes and written entries (index, ISO time, stamp,
    /// value).
    pub fn to_json(&self) -> Value {
        json!({"points": self.points.iter().map(Point::to_json).collect::<Vec<_>>()})
    }
}

/// GTE with FST values: an element that is not a whole number 0–5, or a
/// time the calendar cannot place, halts.
fn gte(seconds: f32, element: f32) -> Result<f32, HistError> {
    let e = whole(element).filter(|e| (0..=5).contains(e)).ok_or_else(|| {
        HistError::new(format!(
            "invalid time element {element}: GTE takes 0 month, 1 day, 2 year, 3 hour, 4 minute or 5 second"
        ))
    })?;
    clock::gte(f64::from(seconds), e as i32).ok_or_else(|| {
        HistError::new(format!("invalid time {seconds}: GTE takes seconds since 1970 within years 1 to 9999"))
    })
}

/// The number of a block named `HIST n` (case and spaces ignored), n 1–200.
fn point_number(name: &str) -> Option<u16> {
    let squeezed: String = name.chars().filter(|c| !c.is_whitespace()).collect();
    let digits = squeezed.get(..4).filter(|p| p.eq_ignore_ascii_case("HIST")).and(squeezed.get(4..))?;
    if digits.is_empty() || digits.len() > 3 || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok().filter(|n| (1..=MAX_POINTS).contains(n))
}

/// A point's configuration from its block's initial values, with its
/// archives allocated.
fn configure(db: &Database, tpl: usize, b: &crate::db::Block, number: u16, notes: &mut Vec<String>) -> Point {
    let t = &db.templates[tpl];
    let init = |field: &str| t.field(field).and_then(|fi| b.values.iter().find(|(i, _)| *i == fi)).map(|(_, v)| v);
    let text = |field: &str| match init(field) {
        Some(InitValue::Text(s)) => s.trim().to_string(),
        _ => String::new(),
    };
    let num = |field: &str| match init(field) {
        Some(InitValue::Num(x)) => *x,
        _ => 0.0,
    };
    let kind = ArchiveType::parse(&text("ARCHTYP")).unwrap_or(ArchiveType::None);
    let mut size = |field: &str, default: usize, max: usize| {
        let x = num(field);
        if x == 0.0 {
            default
        } else if x < 0.0 || x.fract() != 0.0 {
            notes.push(format!("{}.{field} = {x} is not a number of entries: {default} are used", b.name));
            default
        } else if x > max as f64 {
            notes.push(format!("{}.{field} = {x} is more than the {max} entries linc allows: {max} are used", b.name));
            max
        } else {
            x as usize
        }
    };
    let periodic = size("PERIODIC", DEFAULT_PERIODIC, MAX_PERIODIC);
    let daily = size("DAILY", DEFAULT_DAILY, MAX_DAILY);
    let period = match num("PERIOD") {
        0.0 => DEFAULT_PERIOD,
        x if x > 0.0 && x <= 1440.0 && x.fract() == 0.0 && 1440 % (x as u32) == 0 => x as u32,
        x => {
            notes.push(format!(
                "{}.PERIOD = {x} does not divide a day into whole minutes: {DEFAULT_PERIOD} is used",
                b.name
            ));
            DEFAULT_PERIOD
        }
    };
    let archpt = text("ARCHPT");
    if kind == ArchiveType::Current && split_archpt(&archpt).is_none() {
        notes.push(format!("{}.ARCHPT `{archpt}` is not `BLOCK,PARAM`: the logger logs 0 for it", b.name));
    }
    Point {
        number,
        block: b.name.clone(),
        kind,
        archpt,
        period,
        periodic: vec![Entry::default(); periodic],
        daily: vec![Entry::default(); daily],
        minute: vec![Entry::default(); MINUTE_ENTRIES],
        next_periodic: 0,
        next_daily: 0,
    }
}

/// ARCHPT's block and parameter (`"SFP 1, DATA1"` → `("SFP 1", "DATA1")`),
/// both non-empty and trimmed.
pub fn split_archpt(archpt: &str) -> Option<(&str, &str)> {
    let (block, param) = archpt.split_once(',')?;
    let (block, param) = (block.trim(), param.trim());
    (!block.is_empty() && !param.is_empty() && !param.contains(',')).then_some((block, param))
}
