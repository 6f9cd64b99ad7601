//! One batch of a run split for job arrays (`solve --batch`, `render --batch`): run whole on
//! the threads asked for, with a progress bar, and its partial result written as a JSON file
//! for `strahl merge`.

use super::radiosity::method_error;
use anyhow::{Result, bail};
use serde::Serialize;
use std::path::Path;
use strahl::atomic_file::AtomicFile;
use strahl::method::{Cancel, MethodError, ProgressListener};

/// Runs one batch by `run` under a progress bar named
/// `phase` (none when `quiet`). A batch stopped by Ctrl-C is refused: cut short, it could not
/// be merged.
pub fn run_whole<P: Send>(
    phase: &str,
    quiet: bool,
    run: impl FnOnce(&dyn ProgressListener, &Cancel) -> Result<P, MethodError> + Send,
) -> Result<P> {
    let bar = super::progress::Bar::new(phase, quiet);
    let cancel = super::progress::cancel_flag();
    let partial = run(&bar, cancel).map_err(method_error)?;
    if super::progress::interrupted() {
        bail!("interrupted: a batch cut short cannot be merged, so nothing is written");
    }
    Ok(partial)
}

/// Writes `file` to `path` as JSON, whole or not at all.
pub fn write(path: &Path, file: &impl Serialize) -> Result<()> {
    let io = |e| anyhow::anyhow!("{}: {e}", path.display());
    let mut out = AtomicFile::create(path).map_err(io)?;
    serde_json::to_writer(&mut out, file)?;
    out.commit().map_err(io)?;
    Ok(())
}
