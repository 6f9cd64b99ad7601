//! What the command-line tests share: running the built `strahl` binary and a scratch folder.

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs the `strahl` binary with `args` and waits for it.
pub fn strahl(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_strahl"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// A path named `name` in this test process's scratch folder `strahl-{suite}-{pid}` under the
/// system's temporary folder (created if missing).
pub fn temp(suite: &str, name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("strahl-{suite}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}
