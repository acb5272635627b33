//! The device's alarm and event logs (opcodes 118, 119) and history
//! archives (135, 136), read from the ROC state the FST commands write.

use linc_comms::roc::history::{self as hist, Kind};
use linc_comms::roc::logs::{self, LogRequest, Record};
use linc_comms::roc::ops::RocError;
use linc_runtime::roc::{Archive, Log, LogEntry};
use linc_runtime::store::Store;

/// The FST number of a log entry's source: its FST point's logical
/// number plus one, as ROCLINK numbers FSTs from 1 (0 if unknown).
fn fst_number(store: &Store, e: &LogEntry) -> u8 {
    let db = &store.db;
    db.block(&e.source).and_then(|b| db.logical(b)).map_or(0, |l| (l + 1).min(255) as u8)
}

/// The log as the device keeps it: a ring of `capacity` slots where entry
/// number k (counting every entry ever logged from 0) sits at slot
/// k mod capacity; the current index is the slot the next one takes. Each
/// held entry becomes a record by `build` (its record and time); an empty
/// slot is `size` zeros.
pub(super) fn records(
    store: &Store,
    log: &Log,
    req: LogRequest,
    size: usize,
    build: impl Fn(&Record, i64) -> Vec<u8>,
) -> Vec<u8> {
    let cap = log.capacity().max(1) as u64;
    let total = log.total();
    let first = total - log.len() as u64; // the oldest entry's number
    let mut out = Vec::with_capacity(usize::from(req.count));
    for j in 0..u64::from(req.count) {
        let slot = (u64::from(req.start) + j) % cap;
        // The newest entry at this slot, if one is held.
        let newest = total.checked_sub(1).and_then(|last| last.checked_sub((last + cap - slot) % cap));
        let entry = newest.filter(|&k| k >= first && k < total).and_then(|k| log.get((k - first) as usize));
        out.push(match entry {
            None => vec![0; size],
            Some(e) => {
                let r = Record {
                    time: u32::try_from(e.time).unwrap_or(0),
                    fst: fst_number(store, e),
                    text: e.text.as_bytes().to_vec(),
                    value: e.value,
                };
                build(&r, e.time)
            }
        });
    }
    logs::reply(req, current_slot(log), &out)
}

/// The slot a log's next entry takes.
pub(super) fn current_slot(log: &Log) -> u16 {
    (log.total() % log.capacity().max(1) as u64) as u16
}

/// Opcodes 118 (alarms) and 119 (events).
pub fn log(store: &Store, data: &[u8], alarms: bool) -> Result<Vec<u8>, Vec<RocError>> {
    let req = logs::parse(data, alarms).map_err(|e| vec![e])?;
    let log = if alarms { &store.roc.alarms } else { &store.roc.events };
    Ok(if alarms {
        records(store, log, req, logs::ALARM_RECORD, |r, _| logs::alarm(r).to_vec())
    } else {
        records(store, log, req, logs::EVENT_RECORD, |r, _| logs::event(r).to_vec())
    })
}

fn archive(kind: Kind) -> (Archive, bool) {
    match kind {
        Kind::Minute => (Archive::Minute, false),
        Kind::Periodic => (Archive::Periodic, false),
        Kind::Daily => (Archive::Daily, false),
        Kind::PeriodicStamps => (Archive::Periodic, true),
        Kind::DailyStamps => (Archive::Daily, true),
    }
}

/// The current index of a point's archive: where the logger writes next,
/// or for the minute archive the minute of the hour now.
fn current(p: &linc_runtime::roc::Point, a: Archive, device_now: i64) -> u16 {
    p.next_index(a).map_or((device_now.rem_euclid(3600) / 60) as u16, |i| i as u16)
}

/// Error 30 (invalid history point) at a data byte.
fn no_point(at: usize) -> Vec<RocError> {
    vec![RocError::at_data(30, at)]
}

/// Opcode 135: values or time stamps of one point from an index (an
/// index past the archive's end wraps, as the archive does).
pub fn point(store: &Store, data: &[u8], device_now: i64) -> Result<Vec<u8>, Vec<RocError>> {
    let req = hist::parse_point(data).map_err(|e| vec![e])?;
    let p = store.roc.history.point(u16::from(req.point)).ok_or_else(|| no_point(1))?;
    let (a, stamps) = archive(req.kind);
    let entries = p.archive(a);
    if entries.is_empty() {
        return Err(no_point(1));
    }
    let values: Vec<[u8; 4]> = (0..usize::from(req.count))
        .map(|j| {
            let e = entries[(usize::from(req.start) + j) % entries.len()];
            if stamps {
                u32::try_from(e.stamp).unwrap_or(0).to_le_bytes()
            } else {
                e.value.to_le_bytes()
            }
        })
        .collect();
    Ok(hist::point_reply(&req, current(p, a, device_now), &values))
}

/// Opcode 136: several points' values per period, each period stamped
/// with the first point's time stamp for that index.
pub fn points(store: &Store, data: &[u8], device_now: i64) -> Result<Vec<u8>, Vec<RocError>> {
    let req = hist::parse_points(data).map_err(|e| vec![e])?;
    let (a, _) = archive(req.kind);
    let h = &store.roc.history;
    let pts: Vec<_> = (0..req.points)
        .map(|i| h.point(u16::from(req.first_point) + u16::from(i)).filter(|p| !p.archive(a).is_empty()))
        .collect::<Option<_>>()
        .ok_or_else(|| no_point(4))?;
    let periods: Vec<(u32, Vec<f32>)> = (0..usize::from(req.periods))
        .map(|j| {
            let at = |p: &linc_runtime::roc::Point| p.archive(a)[(usize::from(req.start) + j) % p.archive(a).len()];
            let stamp = u32::try_from(at(pts[0]).stamp).unwrap_or(0);
            (stamp, pts.iter().map(|p| at(p).value).collect())
        })
        .collect();
    Ok(hist::points_reply(&req, current(pts[0], a, device_now), &periods))
}
