//! Progress bars on the terminal, Ctrl-C handling and the memory watch.

use indicatif::{ProgressBar, ProgressStyle};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::Duration;
use strahl::method::{Cancel, ProgressListener, resident_bytes};

/// A phase whose length is known: a bar, the share done, the time taken and the estimate of
/// the time left.
const BAR_TEMPLATE: &str = "{msg:16} [{bar:40}] {percent:>3}% {elapsed_precise} (eta {eta})";
/// A phase whose length is not known: a spinner and the time taken.
const SPINNER_TEMPLATE: &str = "{msg:16} {spinner} {elapsed_precise}";

/// A progress bar on standard error (hidden with `--quiet`), a new one for each phase of
/// the work.
pub struct Bar {
    bar: Mutex<ProgressBar>,
    quiet: bool,
}

impl Bar {
    /// A bar labelled `label` until a phase names itself; hidden when `quiet`.
    pub fn new(label: &str, quiet: bool) -> Self {
        Bar {
            bar: Mutex::new(Self::labelled(label, quiet)),
            quiet,
        }
    }

    /// A fresh bar labelled `label`, a spinner until its length is known.
    fn labelled(label: &str, quiet: bool) -> ProgressBar {
        let bar = if quiet {
            ProgressBar::hidden()
        } else {
            ProgressBar::new(0)
        };
        bar.set_style(Self::style(SPINNER_TEMPLATE));
        bar.set_message(label.to_string());
        bar
    }

    /// The style of `template`, or indicatif's default bar should it not parse.
    fn style(template: &str) -> ProgressStyle {
        ProgressStyle::with_template(template)
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> ")
    }

    /// The bar of the current phase.
    fn current(&self) -> ProgressBar {
        match self.bar.lock() {
            Ok(bar) => bar.clone(),
            Err(poisoned) => poisoned.into_inner().clone(),
        }
    }
}

impl ProgressListener for Bar {
    fn phase(&self, name: &str) {
        let fresh = Self::labelled(name, self.quiet);
        let mut bar = match self.bar.lock() {
            Ok(bar) => bar,
            Err(poisoned) => poisoned.into_inner(),
        };
        bar.finish_and_clear();
        *bar = fresh;
    }
    fn start(&self, total: u64) {
        let bar = self.current();
        if total == 0 {
            bar.set_style(Self::style(SPINNER_TEMPLATE));
            bar.enable_steady_tick(Duration::from_millis(200));
        } else {
            bar.set_style(Self::style(BAR_TEMPLATE));
            bar.disable_steady_tick();
        }
        bar.set_length(total);
        bar.set_position(0);
    }
    fn estimate(&self, total: u64) {
        self.current().set_length(total);
    }
    fn advance(&self, units: u64) {
        self.current().inc(units);
    }
    fn finish(&self) {
        self.current().finish_and_clear();
    }
}

/// The stop request Ctrl-C sets.
static CANCEL: Cancel = Cancel::new();

/// Resident memory seen over the bound by [`watch_memory`], bytes (0 while under it).
static OVER_MEMORY: AtomicU64 = AtomicU64::new(0);

/// True when Ctrl-C stopped the work: the process then exits with 130 after writing what it
/// has.
pub fn interrupted() -> bool {
    CANCEL.is_requested() && over_memory().is_none()
}

/// The resident memory, bytes, at which [`watch_memory`] stopped the work, if it did.
pub fn over_memory() -> Option<u64> {
    Some(OVER_MEMORY.load(Ordering::SeqCst)).filter(|&b| b > 0)
}

/// Prints why the run stopped at `bytes` of resident memory; `partial`: what was done has
/// been written.
pub fn report_over_memory(bytes: u64, partial: bool) {
    eprintln!(
        "error: stopped at {} MiB of memory, over the bound (--max-memory, default three \
         quarters of the machine's memory){}: raise --max-memory, or ask for less (a larger \
         --error or --min-area, a coarser --mesh-size, a smaller image or scene)",
        bytes >> 20,
        if partial {
            "; what was done is written, marked partial"
        } else {
            ""
        }
    );
}

/// Watches the process's resident memory from a background thread (every 20 ms) and stops
/// the work as Ctrl-C does when it exceeds `bound` bytes, so that the run ends with a
/// message (see [`over_memory`]) instead of being killed by the system. Work that cannot be
/// stopped (building a scene or its acceleration structure) and goes on growing, a quarter
/// of the bound (at least 64 MiB) past it, ends the process there with the same message.
pub fn watch_memory(bound: Option<u64>) {
    let Some(bound) = bound else {
        return;
    };
    let cancel = cancel_flag();
    let last_resort = bound.saturating_add((bound / 4).max(64 << 20));
    let spawned = std::thread::Builder::new()
        .name("memory watch".into())
        .spawn(move || {
            loop {
                match resident_bytes() {
                    Some(bytes) if bytes > last_resort => {
                        report_over_memory(bytes, false);
                        std::process::exit(1);
                    }
                    Some(bytes) if bytes > bound && OVER_MEMORY.load(Ordering::SeqCst) == 0 => {
                        OVER_MEMORY.store(bytes, Ordering::SeqCst);
                        cancel.request();
                    }
                    Some(_) => std::thread::sleep(Duration::from_millis(20)),
                    None => return,
                }
            }
        });
    if let Err(e) = spawned {
        eprintln!("warning: memory will not be watched: {e}");
    }
}

/// The stop request set by Ctrl-C, SIGTERM or SIGHUP. The first asks running work to stop and
/// keep what it has; a second one ends the process at once.
pub fn cancel_flag() -> &'static Cancel {
    static HANDLER: OnceLock<()> = OnceLock::new();
    HANDLER.get_or_init(|| {
        let installed = ctrlc::set_handler(|| {
            if CANCEL.request() {
                std::process::exit(130);
            }
            eprintln!("\ninterrupted: finishing the current work unit and keeping what is done");
        });
        if let Err(e) = installed {
            eprintln!("warning: Ctrl-C will not stop cleanly: {e}");
        }
    });
    &CANCEL
}
