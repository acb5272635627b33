//! `linc check` needs memory in proportion to the largest action, not to the
//! file: actions are checked as they are parsed and then dropped. A counting
//! allocator measures the peak of live heap bytes while a session checks a
//! generated file of realistic actions.

mod workload;

use linc_compiler::check::Context;
use linc_compiler::session::{CheckOptions, Session};
use linc_runtime::Database;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let live = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
        PEAK.fetch_max(live, Ordering::Relaxed);
        // SAFETY: forwarded unchanged to the system allocator.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        // SAFETY: `ptr` was allocated by `alloc` above with this layout.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

#[test]
fn checking_needs_less_than_twice_the_size_of_the_file() {
    let db = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide db");
    let before = LIVE.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    let src = workload::actions(2 << 20).into_bytes();
    let size = src.len();
    let mut s = Session::new(Context { db: &db, resolve_blocks: true, steps: None });
    let id = s.add("workload.st", src);
    let checked = s.check(id, CheckOptions::default());
    assert!(checked.diagnostics.is_empty(), "{:?}", checked.diagnostics.first());
    let peak = PEAK.load(Ordering::Relaxed) - before;
    // The text itself is 1x (the session keeps it, for the diagnostics);
    // the README's target for the whole process is 10x.
    assert!(peak < size * 2, "peak heap {peak} bytes for a {size}-byte file");
}
