//! Work measured as the processor time it used, not the time on the wall:
//! a test that compares the cost of two sizes of input (to show growth is
//! linear) is then not decided by how busy the machine is — time the
//! process waits for a core is not counted. Work on one thread is measured
//! by [`thread_cpu`]; work on several (the front end parses long files on
//! a second thread, ADR 0018) by [`cpu`], the whole process, in a test
//! binary whose tests all hold [`crate::alloc::serial`], so that no other
//! test runs beside the measurement.

use std::time::Duration;

fn timespec(clock: libc::clockid_t) -> Duration {
    let mut t = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: `t` is a valid timespec for the call to fill.
    let ok = unsafe { libc::clock_gettime(clock, &mut t) } == 0;
    if ok {
        Duration::new(t.tv_sec as u64, t.tv_nsec as u32)
    } else {
        Duration::ZERO
    }
}

fn children() -> Duration {
    // SAFETY: `usage` is a valid rusage for the call to fill.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: as above.
    if unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut usage) } != 0 {
        return Duration::ZERO;
    }
    let tv = |t: libc::timeval| Duration::new(t.tv_sec as u64, t.tv_usec as u32 * 1000);
    tv(usage.ru_utime) + tv(usage.ru_stime)
}

/// What `f` returns, and the processor time this process used running it.
pub fn cpu<R>(f: impl FnOnce() -> R) -> (R, Duration) {
    let before = timespec(libc::CLOCK_PROCESS_CPUTIME_ID);
    let out = f();
    (out, timespec(libc::CLOCK_PROCESS_CPUTIME_ID).saturating_sub(before))
}

/// What `f` returns, and the processor time this thread used running it:
/// for work done on the calling thread, which other tests of the binary
/// running beside it do not add to.
pub fn thread_cpu<R>(f: impl FnOnce() -> R) -> (R, Duration) {
    let before = timespec(libc::CLOCK_THREAD_CPUTIME_ID);
    let out = f();
    (out, timespec(libc::CLOCK_THREAD_CPUTIME_ID).saturating_sub(before))
}

/// What `f` returns, and the processor time the child processes it waited
/// for used (a command run by the test).
pub fn children_cpu<R>(f: impl FnOnce() -> R) -> (R, Duration) {
    let before = children();
    let out = f();
    (out, children().saturating_sub(before))
}

/// How many times more the large input cost than the small one: each
/// measured three times, the least kept (`cost` gives the work of one
/// run, as [`cpu`] measures it).
pub fn growth(mut cost: impl FnMut(bool) -> Duration) -> f64 {
    let mut best = |large| (0..3).map(|_| cost(large)).min().unwrap_or_default();
    let small = best(false);
    let large = best(true);
    large.as_secs_f64() / small.as_secs_f64().max(1e-6)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn work_is_counted_and_sleeping_is_not() {
        let (sum, spun) = cpu(|| (0..20_000_000u64).fold(0u64, |a, i| std::hint::black_box(a.wrapping_add(i))));
        let ((), slept) = cpu(|| std::thread::sleep(Duration::from_millis(50)));
        assert!(sum > 0);
        assert!(spun > slept, "twenty million steps counted {spun:?}, 50 ms asleep {slept:?}");
    }
}
