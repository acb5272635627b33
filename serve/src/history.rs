//! Recent values of every field, as the plant published them, so that a
//! trend chosen on the page starts with the minutes before it was chosen,
//! as a trend on an HMI does. Bounded twice: by simulated time (the page's
//! longest window) and by the number of points kept (a plant whose every
//! field changes every scan keeps a shorter past, not more memory).

use std::collections::VecDeque;

/// How far back the history goes: the page's longest trend window.
pub const KEEP_US: u64 = 15 * 60 * 1_000_000;

/// The most points kept (about 40 MB at worst).
pub const MAX_POINTS: usize = 500_000;

#[derive(Default)]
pub struct History {
    points: VecDeque<(u64, u32, Box<str>)>,
}

impl History {
    /// A field's value from `now_us` on.
    pub fn record(&mut self, now_us: u64, cell: u32, value: &str) {
        self.points.push_back((now_us, cell, value.into()));
    }

    /// Drops what is older than the window or over the bound.
    pub fn trim(&mut self, now_us: u64) {
        let oldest = now_us.saturating_sub(KEEP_US);
        while self.points.front().is_some_and(|p| p.0 < oldest) || self.points.len() > MAX_POINTS {
            self.points.pop_front();
        }
    }

    /// A cell's changes still kept, oldest first: (µs, value).
    pub fn of(&self, cell: u32) -> Vec<(u64, &str)> {
        self.points.iter().filter(|p| p.1 == cell).map(|p| (p.0, &*p.2)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_past_is_bounded_by_time_and_by_size() {
        let mut h = History::default();
        h.record(0, 1, "1.0");
        h.record(10, 2, "TRUE");
        h.record(KEEP_US + 5, 1, "2.0");
        h.trim(KEEP_US + 5);
        assert_eq!(h.of(1), [(KEEP_US + 5, "2.0")], "older than the window: dropped");
        assert_eq!(h.of(2), [(10, "TRUE")]);
        for i in 0..MAX_POINTS as u64 + 10 {
            h.record(KEEP_US + 5, 3, if i % 2 == 0 { "0" } else { "1" });
        }
        h.trim(KEEP_US + 5);
        assert_eq!(h.points.len(), MAX_POINTS);
        assert!(h.of(2).is_empty(), "the oldest go first");
    }
}
