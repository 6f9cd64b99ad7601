//! What the command-line tests share: running the built `strahl` binary and a scratch folder.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs the `strahl` binary with `args` and waits for it.
pub fn strahl(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_strahl"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// A small render of the Cornell box (16 × 12 pixels, one sample) to `image`, with `extra`
/// arguments after the others.
#[allow(
    dead_code,
    reason = "each test crate compiles this module; not all of them render"
)]
pub fn small_render(image: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "render",
        "cornell",
        "-o",
        image.to_str().unwrap(),
        "--width",
        "16",
        "--height",
        "12",
        "--spp",
        "1",
    ];
    args.extend_from_slice(extra);
    strahl(&args)
}

/// A path named `name` in this test process's scratch folder `strahl-{suite}-{pid}` under
/// cargo's folder for test data (`target/tmp`, gone with `cargo clean`; created if missing),
/// so that test runs leave nothing in the system's temporary folder.
pub fn temp(suite: &str, name: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("strahl-{suite}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// The sorted names of the files in `folder`.
#[allow(
    dead_code,
    reason = "each test crate compiles this module; not all of them list folders"
)]
pub fn names(folder: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(folder)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}
