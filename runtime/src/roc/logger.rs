//! The history logger: CURRENT points sample their ARCHPT value at the
//! boundaries of the device clock (each minute, every PERIOD minutes,
//! each midnight), whenever the caller says the clock has moved.

use super::clock::DAY;
use super::history::{ArchiveType, Entry, History, MINUTE_ENTRIES};

/// The last `keep` multiples of `step` in `(after, upto]`, oldest first.
/// A clock that jumps ahead passes many boundaries; only the last `keep`
/// can survive in an archive of `keep` entries, so only they are made,
/// which bounds the work by the archive's size whatever the jump.
fn boundaries(after: i64, upto: i64, step: i64, keep: usize) -> impl Iterator<Item = i64> {
    let step128 = i128::from(step);
    let first = (i128::from(after).div_euclid(step128) + 1) * step128;
    let last = i128::from(upto).div_euclid(step128) * step128;
    let count = if step <= 0 || last < first { 0 } else { (last - first) / step128 + 1 };
    let k = count.min(keep as i128);
    // Every boundary made lies in (after, upto], so it fits in an i64.
    let start = last - (k - 1) * step128;
    (0..k).map(move |j| (start + j * step128) as i64)
}

impl History {
    /// Logs every boundary the device clock passed since the last call,
    /// into every CURRENT point: the minute archive at each minute (index
    /// = minute of the hour), the periodic archive every PERIOD minutes
    /// counted from midnight, the daily archive at each midnight (the
    /// latter two circular, from index 0). Each entry's stamp is its
    /// boundary; its value is ARCHPT as `value_of` reads it now (0 when
    /// it cannot be read). The first call only sets the logger's clock;
    /// a clock that stands still or goes back logs nothing and restarts
    /// from the new time.
    pub fn sample(&mut self, now: i64, value_of: &mut dyn FnMut(&str) -> Option<f32>) {
        let last = self.last.replace(now);
        let Some(last) = last.filter(|&l| l < now) else {
            return;
        };
        for p in self.points.iter_mut().filter(|p| p.kind == ArchiveType::Current) {
            let minutes = boundaries(last, now, 60, MINUTE_ENTRIES);
            let periods = boundaries(last, now, i64::from(p.period) * 60, p.periodic.len());
            let days = boundaries(last, now, DAY, p.daily.len());
            let mut value = None;
            let mut read = |archpt: &str| *value.get_or_insert_with(|| value_of(archpt).unwrap_or(0.0));
            for t in minutes {
                let e = Entry { stamp: t, value: read(&p.archpt) };
                if let Some(slot) = p.minute.get_mut((t.rem_euclid(3600) / 60) as usize) {
                    *slot = e;
                }
            }
            for t in periods {
                let e = Entry { stamp: t, value: read(&p.archpt) };
                if let Some(slot) = p.periodic.get_mut(p.next_periodic) {
                    *slot = e;
                    p.next_periodic = (p.next_periodic + 1) % p.periodic.len();
                }
            }
            for t in days {
                let e = Entry { stamp: t, value: read(&p.archpt) };
                if let Some(slot) = p.daily.get_mut(p.next_daily) {
                    *slot = e;
                    p.next_daily = (p.next_daily + 1) % p.daily.len();
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boundaries_keep_the_last_ones_in_order() {
        let b: Vec<i64> = boundaries(0, 300, 60, 10).collect();
        assert_eq!(b, [60, 120, 180, 240, 300], "after excluded, upto included");
        let b: Vec<i64> = boundaries(59, 61, 60, 10).collect();
        assert_eq!(b, [60]);
        let b: Vec<i64> = boundaries(60, 119, 60, 10).collect();
        assert!(b.is_empty());
        let b: Vec<i64> = boundaries(0, 1_000_000_000 * 60, 60, 3).collect();
        assert_eq!(b, [59_999_999_880, 59_999_999_940, 60_000_000_000], "only the last three are made");
        let b: Vec<i64> = boundaries(-61, -1, 60, 10).collect();
        assert_eq!(b, [-60]);
        assert_eq!(boundaries(0, 600, 60, 0).count(), 0);
        let b: Vec<i64> = boundaries(i64::MAX - 10, i64::MAX, 60, 5).collect();
        assert_eq!(b, [9_223_372_036_854_775_800], "no overflow at the end of time");
        assert_eq!(boundaries(i64::MIN, i64::MIN + 120, 60, 5).count(), 2);
    }
}
