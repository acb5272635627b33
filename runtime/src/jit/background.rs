//! The translation thread of `--tier auto` (ADR 0023): a block due for
//! compilation is handed here and the interpreter goes on running it, so no
//! run, and no scan of a plant, waits for Cranelift. One thread for the
//! process, started by the first block due; the queue is bounded.

use super::{Prepared, SlotState};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::mpsc::{sync_channel, Receiver, SyncSender, TrySendError};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, OnceLock, PoisonError, Weak};

/// Jobs waiting at most. A job holds at most `MAX_BLOCK_OPS` instructions
/// and their cell layout (tens of kilobytes), so a full queue stays within
/// a few megabytes; a block that finds it full is offered again at a later
/// run.
const QUEUE: usize = 64;

/// One block variant to translate. The slot is weak: a program dropped
/// before its turn is not translated, and nothing here keeps it alive.
pub(super) struct Job {
    pub slot: Weak<SlotState>,
    pub variant: usize,
    pub work: Box<Prepared>,
}

/// Holds (the number of live [`Hold`]s) and the signal that a job ended or
/// a hold was released.
static HELD: Mutex<usize> = Mutex::new(0);
static CHANGED: Condvar = Condvar::new();

fn held() -> MutexGuard<'static, usize> {
    HELD.lock().unwrap_or_else(PoisonError::into_inner)
}

fn sender() -> Option<&'static SyncSender<Job>> {
    static SENDER: OnceLock<Option<SyncSender<Job>>> = OnceLock::new();
    let start = || {
        let (tx, rx) = sync_channel(QUEUE);
        std::thread::Builder::new().name("linc-jit".into()).spawn(move || work(rx)).ok()?;
        Some(tx)
    };
    SENDER.get_or_init(start).as_ref()
}

/// Queues a job; it comes back when the queue is full (try later) or there
/// is no thread to run it (`Disconnected`: translate on the caller's).
pub(super) fn submit(job: Job) -> Result<(), TrySendError<Job>> {
    match sender() {
        Some(tx) => tx.try_send(job),
        None => Err(TrySendError::Disconnected(job)),
    }
}

fn work(rx: Receiver<Job>) {
    for Job { slot, variant, work } in rx {
        drop(CHANGED.wait_while(held(), |n| *n > 0).unwrap_or_else(PoisonError::into_inner));
        if slot.strong_count() == 0 {
            continue;
        }
        // A panic in the code generator is a bug, but it must not take the
        // thread, and with it every later translation, down: the block
        // then stays on the interpreter.
        let code = catch_unwind(AssertUnwindSafe(|| work.compile())).ok().flatten();
        if let Some(slot) = slot.upgrade() {
            if let Some(cell) = slot.variants.get(variant) {
                // Only this job sets a queued variant.
                let _ = cell.set(code.map(Arc::new));
            }
        }
        let _wake = held();
        CHANGED.notify_all();
    }
}

/// Blocks until `pending` is false, rechecking after each job.
pub(super) fn settle(pending: impl Fn() -> bool) {
    drop(CHANGED.wait_while(held(), |_| pending()).unwrap_or_else(PoisonError::into_inner));
}

/// While one lives, queued translations wait (see [`hold`]).
#[must_use = "translations resume when the hold is dropped"]
pub struct Hold(());

/// Keeps the translation thread from starting any job until the returned
/// [`Hold`] is dropped: a test's proof that runs go on while their
/// translation is pending. It holds for the whole process, so a test that
/// uses it runs alone in its binary, and must not settle while holding.
#[doc(hidden)]
pub fn hold() -> Hold {
    *held() += 1;
    Hold(())
}

impl Drop for Hold {
    fn drop(&mut self) {
        let mut n = held();
        *n = n.saturating_sub(1);
        CHANGED.notify_all();
    }
}
