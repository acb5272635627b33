//! The ROC protocol's logs and history (opcodes 120, 121, 122, 126, 128,
//! 130), read from the ROC state the FST commands and the logger write
//! (docs/fst-history.md), with the decisions of docs/roc-protocol.md.

use super::roc_logs::{current_slot, records};
use linc_comms::roc::logs as plus_logs;
use linc_comms::roc::ops::RocError;
use linc_comms::roc::rocp::code::INVALID_HISTORY;
use linc_comms::roc::rocp::history::{self as hist, Day, DayRequest, When};
use linc_comms::roc::rocp::logs::{self, Pointers};
use linc_comms::roc::rocp::{self, exactly};
use linc_runtime::roc::{civil, Archive, ArchiveType, Point};
use linc_runtime::store::Store;

type Reply = Result<Vec<u8>, Vec<RocError>>;

/// The reply to a log or history opcode; `None` for another opcode.
pub(super) fn answer(store: &Store, opcode: u8, data: &[u8], now: i64) -> Option<Reply> {
    let one = |e: RocError| vec![e];
    Some(match opcode {
        rocp::POINTERS => exactly(data, 0).map_err(one).map(|()| logs::pointers_reply(&pointers(store))),
        rocp::ALARMS | rocp::EVENTS => log(store, data, opcode == rocp::ALARMS),
        rocp::LAST_HOUR => last_hour(store, data, now),
        rocp::DAY => day(store, data, now),
        rocp::FROM_POINTER => from_pointer(store, data),
        _ => return None,
    })
}

/// Error 14 (invalid history request) at a data byte.
fn no_history(at: usize) -> Vec<RocError> {
    vec![RocError::at_data(INVALID_HISTORY, at)]
}

/// The logger's point: the lowest-numbered CURRENT point, whose indexes
/// opcode 120 reports as the device's history pointers.
fn logger_point(store: &Store) -> Option<&Point> {
    store.roc.history.points().iter().find(|p| p.kind == ArchiveType::Current)
}

fn pointers(store: &Store) -> Pointers {
    let roc = &store.roc;
    let p = logger_point(store);
    let next = |a| p.and_then(|p| p.next_index(a)).unwrap_or(0);
    Pointers {
        alarm: current_slot(&roc.alarms),
        event: current_slot(&roc.events),
        hourly: next(Archive::Periodic) as u16,
        daily: next(Archive::Daily).min(255) as u8,
        max_alarms: roc.alarms.capacity().min(65535) as u16,
        max_events: roc.events.capacity().min(65535) as u16,
        days: p.map_or(0, |p| p.archive(Archive::Daily).len().min(255) as u8),
    }
}

/// Opcodes 121 (alarms) and 122 (events): ROC Plus's request and reply
/// around this dialect's 22-byte records.
fn log(store: &Store, data: &[u8], alarms: bool) -> Reply {
    let req = plus_logs::parse(data, alarms).map_err(|e| vec![e])?;
    let log = if alarms { &store.roc.alarms } else { &store.roc.events };
    Ok(records(store, log, req, logs::RECORD, |r, t| logs::record(alarms, r, t).to_vec()))
}

/// A history point with archives, by the number at data byte `at`.
fn point(store: &Store, number: u8, at: usize) -> Result<&Point, Vec<RocError>> {
    store
        .roc
        .history
        .point(u16::from(number))
        .filter(|p| !p.archive(Archive::Periodic).is_empty())
        .ok_or_else(|| no_history(at))
}

/// Opcode 126: the minute archive, index 0 minute 0.
fn last_hour(store: &Store, data: &[u8], now: i64) -> Reply {
    let n = hist::parse_last_hour(data).map_err(|e| vec![e])?;
    let p = point(store, n, 0)?;
    let mut values = [0.0f32; 60];
    for (v, e) in values.iter_mut().zip(p.archive(Archive::Minute)) {
        *v = e.value;
    }
    Ok(hist::last_hour_reply(n, civil(now).minute as u8, &values))
}

/// Opcode 128: a day's hourly values, its daily value and its extremes.
fn day(store: &Store, data: &[u8], now: i64) -> Reply {
    let request = hist::parse_day(data).map_err(|e| vec![e])?;
    let p = point(store, request.point, 0)?;
    let on_day = |stamp: i64| {
        let c = civil(stamp);
        stamp != 0 && c.month == u32::from(request.month) && c.day == u32::from(request.day)
    };
    let mut hours = [0.0f32; 24];
    let mut newest = [0i64; 24];
    let mut first: Option<(i64, usize)> = None;
    for (i, e) in p.archive(Archive::Periodic).iter().enumerate().filter(|(_, e)| on_day(e.stamp)) {
        if first.is_none_or(|(s, _)| e.stamp < s) {
            first = Some((e.stamp, i));
        }
        let c = civil(e.stamp);
        let h = c.hour as usize;
        if c.minute == 0 && c.second == 0 && e.stamp > newest[h] {
            (hours[h], newest[h]) = (e.value, e.stamp);
        }
    }
    let daily = p.archive(Archive::Daily).iter().filter(|e| on_day(e.stamp)).max_by_key(|e| e.stamp);
    let c = civil(now);
    Ok(hist::day_reply(&Day {
        request,
        hour: c.hour as u8,
        minute: c.minute as u8,
        first_index: first.map_or(u16::MAX, |(_, i)| i.min(65534) as u16),
        hours,
        daily: daily.map_or(0.0, |e| e.value),
        least: extreme(&request, &hours, &newest, |a, b| a < b),
        greatest: extreme(&request, &hours, &newest, |a, b| a > b),
        point_type: archived_type(store, p),
    }))
}

/// The hour whose value beats every other by `better`, and when; zeros
/// when no hour was logged.
fn extreme(r: &DayRequest, hours: &[f32; 24], logged: &[i64; 24], better: fn(f32, f32) -> bool) -> (f32, When) {
    let mut best: Option<usize> = None;
    for h in (0..24).filter(|&h| logged[h] != 0) {
        if best.is_none_or(|b| better(hours[h], hours[b])) {
            best = Some(h);
        }
    }
    best.map_or((0.0, [0; 5]), |h| (hours[h], [0, 0, h as u8, r.day, r.month]))
}

/// The point type of the block a CURRENT point samples (0 for none).
fn archived_type(store: &Store, p: &Point) -> u8 {
    let db = &store.db;
    linc_runtime::roc::split_archpt(&p.archpt)
        .and_then(|(block, _)| db.block(block))
        .and_then(|b| db.block_template(b).point_type(db.device))
        .map_or(0, |t| t.min(255) as u8)
}

/// Opcode 130: values (or, for point 254, the logger's time stamps) from
/// an index, wrapping at the archive's end as the archive does.
fn from_pointer(store: &Store, data: &[u8]) -> Reply {
    let r = hist::parse_from_pointer(data).map_err(|e| vec![e])?;
    let a = if r.kind == hist::DAILY { Archive::Daily } else { Archive::Periodic };
    let p = if r.point == hist::STAMPS {
        logger_point(store).ok_or_else(|| no_history(1))?
    } else {
        point(store, r.point, 1)?
    };
    let entries = p.archive(a);
    if entries.is_empty() {
        return Err(no_history(1));
    }
    let values: Vec<[u8; 4]> = (0..usize::from(r.count))
        .map(|j| {
            let e = entries[(usize::from(r.start) + j) % entries.len()];
            if r.point == hist::STAMPS {
                hist::short_stamp(e.stamp)
            } else {
                e.value.to_le_bytes()
            }
        })
        .collect();
    Ok(hist::from_pointer_reply(&r, &values))
}
