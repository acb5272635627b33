//! Task periods: LIN time constants (`T#100ms`, `T#4m13.0s`) read without
//! the compiler, which the runtime must not depend on.

/// Shortest task period, in seconds.
pub const MIN_PERIOD: f64 = 0.001;
/// Longest task period, in seconds (one day).
pub const MAX_PERIOD: f64 = 86_400.0;

/// Units from largest to smallest; a constant lists them in this order.
const UNITS: [(&str, f64); 5] = [("d", 86_400.0), ("h", 3_600.0), ("m", 60.0), ("s", 1.0), ("ms", 0.001)];

/// Seconds in a duration written on a command line, console or scenario
/// line: a time constant with or without its `T#` (`10m`, `T#1h30m`),
/// around spaces ignored. Bounds are the caller's.
pub fn duration_seconds(text: &str) -> Result<f64, String> {
    let t = text.trim();
    let prefixed = t.get(..2).is_some_and(|p| p.eq_ignore_ascii_case("t#"));
    if prefixed {
        time_constant(t)
    } else {
        time_constant(&format!("T#{t}"))
    }
}

/// Seconds in a time constant `T#…` (or `t#…`): one or more parts
/// `<number><unit>`, units `d h m s ms` (any case) each at most once and
/// from largest to smallest, numbers with an optional decimal part. As in
/// ST, a `_` or `.` may separate parts (`T#1h_30m`, `T#1d.12.2h`).
pub fn time_constant(text: &str) -> Result<f64, String> {
    let body = text
        .strip_prefix("T#")
        .or_else(|| text.strip_prefix("t#"))
        .ok_or_else(|| format!("`{text}` is not a time constant (it should start with T#)"))?;
    let bad = |why: &str| format!("`{text}` is not a time constant: {why}");
    let mut rest = body;
    let mut next_unit = 0;
    let mut total = 0.0;
    if rest.is_empty() {
        return Err(bad("it has no value after T#"));
    }
    while !rest.is_empty() {
        let digits = rest.bytes().take_while(|b| b.is_ascii_digit() || *b == b'.').count();
        let (number, after) = rest.split_at(digits);
        if number.is_empty() || number.starts_with('.') || number.ends_with('.') || number.matches('.').count() > 1 {
            return Err(bad("expected a number such as 4 or 13.5"));
        }
        let letters = after.bytes().take_while(u8::is_ascii_alphabetic).count();
        let (unit, after) = after.split_at(letters);
        let Some(u) = UNITS.iter().position(|(name, _)| name.eq_ignore_ascii_case(unit)) else {
            return Err(bad("expected a unit d, h, m, s or ms after each number"));
        };
        if u < next_unit {
            return Err(bad("units must go from largest to smallest, each at most once"));
        }
        next_unit = u + 1;
        let value: f64 = number.parse().map_err(|_| bad("expected a number such as 4 or 13.5"))?;
        // Dividing keeps `T#100ms` exactly 0.1 (0.001 itself is inexact).
        total += if UNITS[u].0 == "ms" { value / 1000.0 } else { value * UNITS[u].1 };
        rest = after;
        if let Some(r) = rest.strip_prefix(['_', '.']).filter(|r| !r.is_empty()) {
            rest = r;
        }
    }
    Ok(total)
}

/// Checks that a period in seconds is one a task can run at.
pub fn check_period(seconds: f64) -> Result<f64, String> {
    if seconds.is_finite() && (MIN_PERIOD..=MAX_PERIOD).contains(&seconds) {
        Ok(seconds)
    } else {
        Err(format!("a task period must be from 1 ms to 1 day (86400 s); this one is {seconds} s"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_take_the_prefix_or_not_and_never_split_a_character() {
        assert_eq!(duration_seconds(" 1h30m "), Ok(5_400.0));
        assert_eq!(duration_seconds("t#2.5s"), Ok(2.5));
        assert!(duration_seconds("€5s").is_err(), "a multi-byte first character is an error, not a panic");
        assert!(duration_seconds("T").is_err());
    }

    #[test]
    fn guide_forms_and_milliseconds() {
        let cases = [
            ("T#100ms", 0.1),
            ("T#1s", 1.0),
            ("T#1s500ms", 1.5),
            ("T#1.5s", 1.5),
            ("T#4m13.0s", 253.0),
            ("t#4M13.0S", 253.0),
            ("T#1d12.2h", 86_400.0 + 12.2 * 3_600.0),
            ("T#1d.12.2h", 86_400.0 + 12.2 * 3_600.0),
            ("T#1h_30m", 5_400.0),
            ("T#1ms", 0.001),
            ("T#3ms", 0.003),
            ("T#700ms", 0.7),
        ];
        for (text, seconds) in cases {
            assert_eq!(time_constant(text), Ok(seconds), "{text}");
        }
    }

    #[test]
    fn malformed_constants_are_refused() {
        for text in
            ["100ms", "T#", "T#ms", "T#1", "T#1x", "T#1s1s", "T#1s1m", "T#-1s", "T#1..5s", "T#.5s", "T#1s_", "T# 1s"]
        {
            assert!(time_constant(text).is_err(), "{text}");
        }
    }

    #[test]
    fn period_bounds() {
        assert_eq!(check_period(0.001), Ok(0.001));
        assert_eq!(check_period(86_400.0), Ok(86_400.0));
        for bad in [0.0, -1.0, 0.000_999, 86_400.5, f64::INFINITY] {
            assert!(check_period(bad).is_err(), "{bad}");
        }
    }
}
