//! Progress of the shooting solvers: on a log scale from the first unshot fraction (1) down
//! to the tolerance, so each decade of convergence advances the bar by the same amount.

use crate::progress::ProgressListener;

/// Progress-bar units for the whole way.
const PROGRESS_UNITS: u64 = 1000;

/// A progress listener driven by the unshot fraction of the source power.
pub(crate) struct UnshotProgress<'a> {
    listener: &'a dyn ProgressListener,
    log_tolerance: f64,
    shown: u64,
}

impl<'a> UnshotProgress<'a> {
    /// Starts `listener` for a solve that stops at unshot fraction `tolerance`.
    pub(crate) fn start(listener: &'a dyn ProgressListener, tolerance: f64) -> Self {
        listener.start(PROGRESS_UNITS);
        UnshotProgress {
            listener,
            log_tolerance: tolerance.max(1e-300).ln(),
            shown: 0,
        }
    }

    /// Advances to unshot fraction `fraction` (never backwards).
    pub(crate) fn reach(&mut self, fraction: f64) {
        let reached = if fraction > 0.0 {
            ((fraction.ln() / self.log_tolerance).clamp(0.0, 1.0) * PROGRESS_UNITS as f64) as u64
        } else {
            PROGRESS_UNITS
        };
        if reached > self.shown {
            self.listener.advance(reached - self.shown);
            self.shown = reached;
        }
    }

    /// Ends the bar.
    pub(crate) fn finish(self) {
        self.listener.finish();
    }
}
