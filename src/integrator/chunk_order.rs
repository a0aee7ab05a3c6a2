//! The ordered hand-over of a light pass's chunks: workers take chunks of forward rays in
//! order and trace them without waiting for each other; a finished chunk's splats are added to
//! the pass buffer as soon as every earlier chunk's are, so the sums are formed in chunk order
//! whatever the thread count.

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Condvar, Mutex, MutexGuard, PoisonError};

use crate::film::{ChunkSplats, PassBuffer};

/// What the workers of one light pass share.
pub struct Shared<'b> {
    order: Mutex<Order<'b>>,
    /// Signalled whenever chunks were added (or the pass aborted).
    added: Condvar,
    next_chunk: AtomicU64,
    /// Set on an interrupt or a worker's panic: every worker stops.
    aborted: AtomicBool,
    chunks: u64,
    /// How far a worker may run ahead of the oldest unfinished chunk.
    window: u64,
}

impl<'b> Shared<'b> {
    /// The hand-over of `chunks` chunks into `buf`; workers run at most `window` chunks ahead
    /// of the oldest unfinished one.
    pub fn new(buf: &'b mut PassBuffer, chunks: u64, window: u64) -> Self {
        Shared {
            order: Mutex::new(Order {
                next_add: 0,
                finished: BTreeMap::new(),
                spare: Vec::new(),
                buf,
            }),
            added: Condvar::new(),
            next_chunk: AtomicU64::new(0),
            aborted: AtomicBool::new(false),
            chunks,
            window,
        }
    }

    pub fn chunks(&self) -> u64 {
        self.chunks
    }

    /// Whether the pass was abandoned (an interrupt or a worker's panic).
    pub fn aborted(&self) -> bool {
        self.aborted.load(Ordering::Relaxed)
    }

    /// The next chunk to trace and a splat log for it (a copy of `empty`), or None when all are taken or the pass
    /// is aborted (`stop` set).
    pub fn next(&self, stop: &AtomicBool, empty: &ChunkSplats) -> Option<(u64, ChunkSplats)> {
        if stop.load(Ordering::Relaxed) {
            self.abort();
            return None;
        }
        let c = self.next_chunk.fetch_add(1, Ordering::Relaxed);
        if c >= self.chunks {
            return None;
        }
        let mut o = lock(&self.order);
        while c >= o.next_add + self.window {
            if self.aborted.load(Ordering::Relaxed) {
                return None;
            }
            o = self.added.wait(o).unwrap_or_else(PoisonError::into_inner);
        }
        let sink = o.spare.pop().unwrap_or_else(|| empty.empty_like());
        Some((c, sink))
    }

    /// Hands chunk `c` over; it is added once every earlier chunk is.
    pub fn finish(&self, c: u64, sink: ChunkSplats) {
        let mut o = lock(&self.order);
        o.finished.insert(c, sink);
        o.add_ready();
        self.added.notify_all();
    }

    pub fn abort(&self) {
        // Under the lock, so no waiter can miss the flag between its check and its wait.
        let _o = lock(&self.order);
        self.aborted.store(true, Ordering::Relaxed);
        self.added.notify_all();
    }
}

/// The ordered hand-over of finished chunks into the pass buffer.
struct Order<'b> {
    next_add: u64,
    finished: BTreeMap<u64, ChunkSplats>,
    spare: Vec<ChunkSplats>,
    buf: &'b mut PassBuffer,
}

impl Order<'_> {
    fn add_ready(&mut self) {
        while let Some(mut sink) = self.finished.remove(&self.next_add) {
            sink.drain_into(self.buf);
            self.spare.push(sink);
            self.next_add += 1;
        }
    }
}

pub struct WakeOnPanic<'a, 'b>(pub &'a Shared<'b>);

impl Drop for WakeOnPanic<'_, '_> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.abort();
        }
    }
}

/// A poisoned lock only means another worker panicked; the panic reaches the caller through
/// the scope anyway, so the data is still fine to use here.
fn lock<'m, 'b>(m: &'m Mutex<Order<'b>>) -> MutexGuard<'m, Order<'b>> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}
