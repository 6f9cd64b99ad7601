//! What the file-reading targets share: a folder of their own to write the input into.

use std::path::PathBuf;

/// This process's scratch folder (created on first use): libFuzzer runs one input at a time
/// per process, so one folder per process keeps parallel jobs apart.
pub fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("strahl-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("cannot create the scratch folder");
    dir
}
