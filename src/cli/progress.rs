//! Progress bars on the terminal and Ctrl-C handling.

use indicatif::{ProgressBar, ProgressStyle};
use std::sync::OnceLock;
use strahl::progress::{Cancel, ProgressListener};

/// A progress bar on standard error (hidden with `--quiet`).
pub struct Bar {
    bar: ProgressBar,
}

impl Bar {
    /// A bar labelled `label`; hidden when `quiet`.
    pub fn new(label: &str, quiet: bool) -> Self {
        let bar = if quiet {
            ProgressBar::hidden()
        } else {
            ProgressBar::new(0)
        };
        bar.set_style(
            ProgressStyle::with_template(
                "{msg:12} [{bar:40}] {percent:>3}% {elapsed_precise} (eta {eta})",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
        );
        bar.set_message(label.to_string());
        Bar { bar }
    }
}

impl ProgressListener for Bar {
    fn start(&self, total: u64) {
        self.bar.set_length(total);
        self.bar.set_position(0);
    }
    fn advance(&self, units: u64) {
        self.bar.inc(units);
    }
    fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

/// The stop request Ctrl-C sets.
static CANCEL: Cancel = Cancel::new();

/// True when Ctrl-C stopped the work: the process then exits with 130 after writing what it
/// has.
pub fn interrupted() -> bool {
    CANCEL.is_requested()
}

/// The stop request set by Ctrl-C. The first Ctrl-C asks running work to stop and keep what
/// it has; a second one ends the process at once.
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
