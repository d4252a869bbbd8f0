//! Progress inside the long solver phases (a factorization, block solves, an eigen iteration),
//! for whoever shows it: the command line installs one reporter for the process, the library
//! calls [`report`] at each step. Without a reporter a report costs one relaxed atomic load.
//!
//! A reporter is process-wide, like a logger: the phases it hears about sit several layers
//! below the pipeline (reduce → solve), and threading a callback through every signature
//! between them would change every caller for something only a terminal needs.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, RwLock};

/// One step of a long phase.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Event {
    /// A sparse Cholesky factorization starts: the dimension and the flop count of the analysis
    /// (Σ_j c_j², c_j = nnz(L[:, j])), and whether it runs in f32 (mixed precision).
    FactorStart {
        /// Matrix dimension.
        n: usize,
        /// Floating-point operations of the numeric factorization.
        flops: f64,
        /// An f32 factor (`--precision mixed`).
        single: bool,
    },
    /// The share of the factorization announced by the last `FactorStart` done so far: its
    /// dense kernels' flops against the analysis's count, below 1 until `FactorEnd` (a few
    /// times a second while it runs; only where the kernels count their work, x86-64).
    FactorProgress {
        /// Share done, 0 … 0.99.
        share: f64,
    },
    /// The factorization announced by the last `FactorStart` is done.
    FactorEnd,
    /// Solves with a factor for many right-hand sides (constraint modes, attachment modes).
    Solves {
        /// Right-hand sides.
        columns: usize,
    },
    /// One step of the eigen iteration: eigenpairs converged so far of those wanted (in band
    /// mode `wanted` grows when the band holds more modes than first asked for).
    Eigen {
        /// Converged eigenpairs.
        converged: usize,
        /// Eigenpairs wanted.
        wanted: usize,
    },
}

/// What receives the events (the command line's progress display).
pub type Reporter = Arc<dyn Fn(&Event) + Send + Sync>;

static ACTIVE: AtomicBool = AtomicBool::new(false);
static REPORTER: RwLock<Option<Reporter>> = RwLock::new(None);

/// Installs `reporter` for the whole process (`None` removes it).
pub fn set_reporter(reporter: Option<Reporter>) {
    let active = reporter.is_some();
    // A poisoned lock only means a reporter panicked; the slot itself is still a valid Option.
    let mut slot = REPORTER.write().unwrap_or_else(|e| e.into_inner());
    *slot = reporter;
    ACTIVE.store(active, Ordering::Release);
}

/// Whether a reporter is installed (a phase may skip work done only to report).
pub fn active() -> bool {
    ACTIVE.load(Ordering::Acquire)
}

/// Sends `event` to the reporter, if one is installed.
pub fn report(event: Event) {
    if !ACTIVE.load(Ordering::Acquire) {
        return;
    }
    let reporter = REPORTER.read().unwrap_or_else(|e| e.into_inner()).clone();
    if let Some(r) = reporter {
        r(&event);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicUsize;

    #[test]
    fn events_reach_the_installed_reporter_and_stop_when_it_is_removed() {
        // Other tests of this binary may solve (and report) meanwhile: count only this event.
        let mine = Event::Eigen {
            converged: 3,
            wanted: 987_654_321,
        };
        let seen = Arc::new(AtomicUsize::new(0));
        let sink = seen.clone();
        set_reporter(Some(Arc::new(move |e: &Event| {
            if *e == mine {
                sink.fetch_add(1, Ordering::SeqCst);
            }
        })));
        report(mine);
        set_reporter(None);
        report(mine);
        assert_eq!(seen.load(Ordering::SeqCst), 1);
    }
}
