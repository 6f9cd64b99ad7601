//! Progress and cancellation of long work (seed 002 §5.1, `RTProgressListener`): every long
//! computation reports units of work done to a [`ProgressListener`] and looks at a [`Cancel`]
//! between units, stopping within one unit and keeping what it has.

use crate::measure::RoundSolution;
use std::sync::atomic::{AtomicBool, Ordering};

/// Receives progress of long work. Calls may come from several threads at once.
pub trait ProgressListener: Sync {
    /// The next work to start is the phase `name` (`"refining"`, `"rendering"`, …), for
    /// listeners that show one bar per phase; ignored by default.
    fn phase(&self, _name: &str) {}
    /// Work of `total` units starts (0: how much is not known).
    fn start(&self, total: u64);
    /// The work started is now estimated at `total` units in all, the units done so far
    /// included (for work whose end is known only as it goes); ignored by default.
    fn estimate(&self, _total: u64) {}
    /// `units` more units are done.
    fn advance(&self, units: u64);
    /// The work ended (completed or cancelled).
    fn finish(&self);
    /// Whether this listener shows the solution of the round just ended: solvers that refine
    /// in rounds ask after each round and then hand its solution to
    /// [`ProgressListener::round`] (making it costs time, so only when asked). False by
    /// default.
    fn wants_rounds(&self) -> bool {
        false
    }
    /// The solution after a round (hierarchical radiosity: after each round's gathers,
    /// before the next refinement); ignored by default.
    fn round(&self, _solution: &RoundSolution) {}
}

/// A listener that ignores everything.
pub struct NoProgress;

impl ProgressListener for NoProgress {
    fn start(&self, _total: u64) {}
    fn advance(&self, _units: u64) {}
    fn finish(&self) {}
}

/// A request to stop long work early, shared between whoever asks (a Ctrl-C handler, a test)
/// and the work, which checks it between units and keeps what is done.
#[derive(Debug, Default)]
pub struct Cancel(AtomicBool);

impl Cancel {
    /// No stop requested yet.
    pub const fn new() -> Self {
        Cancel(AtomicBool::new(false))
    }

    /// Asks the work to stop; returns true when a stop had been asked before.
    pub fn request(&self) -> bool {
        self.0.swap(true, Ordering::SeqCst)
    }

    /// True once a stop has been asked.
    #[inline]
    pub fn is_requested(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}
