//! When an action-type block runs its action: the block's `Trigger` plays
//! the part of a step's activity and its qualifier decides (guide §10.2.3,
//! with the sequence qualifiers of §20.5.5). The rules are in
//! `docs/strategies.md`; this is the one place they are computed.

/// LIN's action qualifiers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Qualifier {
    /// Non-stored: every scan while triggered.
    N,
    /// Pulse: once, in the scan the trigger rises.
    P,
    /// Time-limited: every scan while triggered for less than the time.
    L,
    /// Delayed: every scan while triggered for at least the time.
    D,
    /// Once, in the first scan triggered for at least the time.
    E,
    /// Once, in the scan the trigger falls.
    F,
    /// Stored at the rising trigger: every scan until reset.
    S,
    /// Reset: a rising trigger stops a stored action.
    R,
}

impl Qualifier {
    /// From an ENUM value name (`"N"`, `"P"`, ...), ignoring case.
    pub fn parse(name: &str) -> Option<Qualifier> {
        // Read once per block and scan: no allocation.
        let [letter] = name.as_bytes() else { return None };
        Some(match letter.to_ascii_uppercase() {
            b'N' => Qualifier::N,
            b'P' => Qualifier::P,
            b'L' => Qualifier::L,
            b'D' => Qualifier::D,
            b'E' => Qualifier::E,
            b'F' => Qualifier::F,
            b'S' => Qualifier::S,
            b'R' => Qualifier::R,
            _ => return None,
        })
    }
}

/// What a block remembers between scans (its edge memory and timer).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QualState {
    /// The trigger at the last scan.
    pub was: bool,
    /// When the trigger last rose, in microseconds of simulated time
    /// (integers, so that 0.1 s periods add up exactly).
    pub since: u64,
    /// E has fired since the trigger rose.
    pub fired: bool,
    /// S has stored the action (until an R).
    pub stored: bool,
}

impl QualState {
    /// One scan at time `now` (µs): whether the action runs in it. `time`
    /// is the qualifier's time in µs (L, D, E).
    pub fn scan(&mut self, q: Qualifier, time: u64, trigger: bool, now: u64) -> bool {
        let rising = trigger && !self.was;
        let falling = !trigger && self.was;
        self.was = trigger;
        if rising {
            self.since = now;
            self.fired = false;
        }
        let elapsed = now.saturating_sub(self.since);
        match q {
            Qualifier::N => trigger,
            Qualifier::P => rising,
            Qualifier::L => trigger && elapsed < time,
            Qualifier::D => trigger && elapsed >= time,
            Qualifier::E => {
                let run = trigger && elapsed >= time && !self.fired;
                self.fired |= run;
                run
            }
            Qualifier::F => falling,
            Qualifier::S | Qualifier::R => {
                if rising {
                    self.stored = q == Qualifier::S;
                }
                self.stored
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs a qualifier over a trigger pattern, one scan per `period`.
    fn runs(q: Qualifier, time: f64, period: f64, trigger: &[u8]) -> String {
        let mut s = QualState::default();
        let us = |x: f64| (x * 1e6).round() as u64;
        trigger
            .iter()
            .enumerate()
            .map(|(i, &t)| if s.scan(q, us(time), t == b'1', i as u64 * us(period)) { '1' } else { '.' })
            .collect()
    }

    #[test]
    fn each_qualifier_over_one_trigger_pulse() {
        let t = b"0111111000";
        assert_eq!(runs(Qualifier::N, 0.0, 1.0, t), ".111111...");
        assert_eq!(runs(Qualifier::P, 0.0, 1.0, t), ".1........");
        assert_eq!(runs(Qualifier::L, 2.0, 1.0, t), ".11.......");
        assert_eq!(runs(Qualifier::D, 2.0, 1.0, t), "...1111...");
        assert_eq!(runs(Qualifier::E, 2.0, 1.0, t), "...1......");
        assert_eq!(runs(Qualifier::F, 0.0, 1.0, t), ".......1..");
        assert_eq!(runs(Qualifier::S, 0.0, 1.0, t), ".111111111");
        assert_eq!(runs(Qualifier::R, 0.0, 1.0, t), "..........");
    }

    #[test]
    fn timed_qualifiers_count_time_not_scans() {
        let t = b"0111111111111111111111";
        // At 0.1 s per scan, 0.5 s is five scans.
        assert_eq!(runs(Qualifier::L, 0.5, 0.1, t), ".11111................");
        assert_eq!(runs(Qualifier::D, 0.5, 0.1, t), "......1111111111111111");
        assert_eq!(runs(Qualifier::E, 0.5, 0.1, t), "......1...............");
    }

    #[test]
    fn a_new_rising_edge_restarts_the_timer_and_e() {
        assert_eq!(runs(Qualifier::E, 1.0, 1.0, b"011100111"), "..1....1.");
        assert_eq!(runs(Qualifier::L, 1.0, 1.0, b"0110011"), ".1...1.");
    }

    #[test]
    fn r_stops_what_s_stored() {
        let mut s = QualState::default();
        let mut at = 0;
        let mut step = |q, t| {
            at += 1_000_000;
            s.scan(q, 0, t, at)
        };
        assert!(step(Qualifier::S, true));
        assert!(step(Qualifier::S, false), "stored runs without its trigger");
        assert!(step(Qualifier::R, false), "R acts on its rising trigger only");
        assert!(!step(Qualifier::R, true), "R stops it and it does not run that scan");
        assert!(!step(Qualifier::S, false));
    }
}
