//! Faults injected around the work: writes cut short (a file-size limit, as a full disk
//! would), SIGINT and SIGTERM at moments spread over a render and a solve with an export, and
//! runs writing one output at the same time. After each, every output is either the last
//! run's, byte for byte, or a complete new one, and nothing else is left beside it.
#![cfg(target_os = "linux")]

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::Duration;

mod common;

use common::names;

/// What every output holds before a run.
const LAST_RUN: &[u8] = b"the last run's";

/// A scratch folder of its own for `test`, with the last run's version of each of `names`.
fn folder_with_last_run(test: &str, names: &[&str]) -> PathBuf {
    let folder = common::temp("faults", test).join("out");
    let _ = std::fs::remove_dir_all(&folder);
    std::fs::create_dir_all(&folder).unwrap();
    for name in names {
        std::fs::write(folder.join(name), LAST_RUN).unwrap();
    }
    folder
}

/// Whether `path` holds a complete output of its kind: a PNG up to its end chunk, JSON that
/// parses, an ASCII PLY with as many lines as its header announces.
fn complete(path: &Path) -> bool {
    let bytes = std::fs::read(path).unwrap();
    match path.extension().and_then(|e| e.to_str()) {
        Some("png") => {
            const END: [u8; 8] = [0x49, 0x45, 0x4E, 0x44, 0xAE, 0x42, 0x60, 0x82];
            bytes.starts_with(b"\x89PNG\r\n\x1a\n") && bytes.ends_with(&END)
        }
        Some("json") => serde_json::from_slice::<serde_json::Value>(&bytes).is_ok(),
        Some("ply") => {
            let text = String::from_utf8_lossy(&bytes);
            let Some((header, body)) = text.split_once("end_header\n") else {
                return false;
            };
            let announced: usize = header
                .lines()
                .filter_map(|l| l.strip_prefix("element "))
                .filter_map(|l| l.split_whitespace().nth(1)?.parse::<usize>().ok())
                .sum();
            body.lines().count() == announced && text.ends_with('\n')
        }
        other => panic!("no completeness check for {other:?}"),
    }
}

/// Each of `outputs` in `folder` is the last run's or complete, and nothing else is there.
fn assert_whole(folder: &Path, outputs: &[&str], case: &str) {
    assert_eq!(
        names(folder),
        outputs,
        "{case}: files left beside the outputs"
    );
    for name in outputs {
        let path = folder.join(name);
        let old = std::fs::read(&path).unwrap() == LAST_RUN;
        assert!(old || complete(&path), "{case}: {name} is truncated");
    }
}

/// Runs `strahl args` with writes limited to `kib` KiB per file (`ulimit -f`, the signal it
/// raises ignored, so a write past it fails as on a full disk).
fn with_file_size_limit(kib: u32, args: &[&str]) -> Output {
    Command::new("bash")
        .args(["-c", r#"trap '' XFSZ; ulimit -f "$0" && exec "$@""#])
        .arg(kib.to_string())
        .arg(env!("CARGO_BIN_EXE_strahl"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn a_write_cut_short_keeps_the_last_output() {
    let outputs = ["image.png", "report.json", "solution.ply"];
    let folder = folder_with_last_run("cut-short", &outputs);
    let path = |name: &str| folder.join(name).to_str().unwrap().to_owned();
    let runs: [Vec<String>; 3] = [
        ["render", "cornell", "-o", &path("image.png")]
            .iter()
            .chain(&["--width", "96", "--height", "72", "--spp", "4", "-q"])
            .map(|s| s.to_string())
            .collect(),
        ["solve", "cornell", "--photons", "100000", "--report"]
            .iter()
            .chain(&[path("report.json").as_str(), "-q"])
            .map(|s| s.to_string())
            .collect(),
        ["solve", "cornell", "--solver", "hierarchical", "--export"]
            .iter()
            .chain(&[path("solution.ply").as_str(), "-q"])
            .map(|s| s.to_string())
            .collect(),
    ];
    for args in &runs {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let run = with_file_size_limit(1, &args);
        let message = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success(), "{args:?}: {message}");
        assert!(message.contains("File too large"), "{args:?}: {message}");
    }
    for name in outputs {
        assert_eq!(
            std::fs::read(folder.join(name)).unwrap(),
            LAST_RUN,
            "{name}"
        );
    }
    assert_eq!(names(&folder), outputs);
}

/// Starts `strahl args` quietly.
fn start(args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_strahl"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap()
}

/// Sends `signal` to `child` after `after` and waits for it; its exit code, `None` where the
/// signal ended it before its handler was in place.
fn signal_after(mut child: Child, signal: &str, after: Duration) -> Option<i32> {
    std::thread::sleep(after);
    let sent = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    child.wait().unwrap().code()
}

#[test]
fn sigint_and_sigterm_at_any_moment_leave_whole_outputs() {
    // Runs far longer than the last signal comes: the image at 4096 samples per pixel, the
    // solve of a thousand blocks with its report and export.
    let moments = [10, 120, 400, 900].map(Duration::from_millis);
    for signal in ["INT", "TERM"] {
        for (k, &after) in moments.iter().enumerate() {
            let outputs = ["image.png", "report.json", "solution.ply"];
            let folder = folder_with_last_run(&format!("signal-{signal}-{k}"), &outputs);
            let path = |name: &str| folder.join(name).to_str().unwrap().to_owned();
            let render = start(&[
                "render",
                "cornell",
                "-o",
                &path("image.png"),
                "--width",
                "64",
                "--height",
                "48",
                "--spp",
                "4096",
                "-q",
            ]);
            let code = signal_after(render, signal, after);
            let case = format!("render, SIG{signal} after {after:?}");
            assert!(matches!(code, None | Some(130)), "{case}: exit {code:?}");
            let solve = start(&[
                "solve",
                "blocks:1000",
                "--solver",
                "hierarchical",
                "--report",
                &path("report.json"),
                "--export",
                &path("solution.ply"),
                "-q",
            ]);
            let code = signal_after(solve, signal, after);
            let case = format!("{case}; solve: exit {code:?}");
            assert!(matches!(code, None | Some(130)), "{case}");
            assert_whole(&folder, &outputs, &case);
        }
    }
}

#[test]
fn runs_writing_one_output_at_once_leave_one_whole_file() {
    let outputs = ["image.png", "report.json"];
    let folder = folder_with_last_run("at-once", &outputs);
    let path = |name: &str| folder.join(name).to_str().unwrap().to_owned();
    let seeds = ["1", "2", "3"];
    let renders: Vec<Child> = seeds
        .iter()
        .map(|seed| {
            start(&[
                "render",
                "cornell",
                "-o",
                &path("image.png"),
                "--width",
                "48",
                "--height",
                "36",
                "--spp",
                "16",
                "--seed",
                seed,
                "-q",
            ])
        })
        .collect();
    let solves: Vec<Child> = seeds
        .iter()
        .map(|seed| {
            start(&[
                "solve",
                "cornell",
                "--photons",
                "200000",
                "--seed",
                seed,
                "--report",
                &path("report.json"),
                "-q",
            ])
        })
        .collect();
    for mut child in renders.into_iter().chain(solves) {
        assert!(child.wait().unwrap().success());
    }
    assert_whole(&folder, &outputs, "three runs at once");
    for name in outputs {
        assert_ne!(
            std::fs::read(folder.join(name)).unwrap(),
            LAST_RUN,
            "{name}"
        );
    }
}
