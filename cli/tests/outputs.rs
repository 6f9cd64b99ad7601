//! Output files are written whole or not at all: every output goes to a temporary file beside
//! the target and replaces it only once completely written (`strahl::atomic_file`). A full
//! device is an error with a message, a finished run leaves nothing but its outputs, and one
//! file named by two outputs of a run is refused before any work.

mod common;

use common::{names, small_render, strahl};

#[test]
fn every_output_replaces_the_last_and_leaves_nothing_else() {
    let image = common::temp("outputs-ok", "cornell.png");
    let folder = image.parent().unwrap().to_path_buf();
    for name in [
        "cornell.png",
        "report.csv",
        "report.sensors.csv",
        "solution.ply",
    ] {
        std::fs::write(folder.join(name), "the last run's").unwrap();
    }
    let render = small_render(&image, &["-q"]);
    assert!(render.status.success(), "{render:?}");
    let report = folder.join("report.csv");
    let solution = folder.join("solution.ply");
    let solve = strahl(&[
        "solve",
        "cornell",
        "--solver",
        "hierarchical",
        "--error",
        "1e-2",
        "--report",
        report.to_str().unwrap(),
        "--export",
        solution.to_str().unwrap(),
        "-q",
    ]);
    assert!(solve.status.success(), "{solve:?}");
    for name in ["cornell.png", "report.csv", "solution.ply"] {
        let bytes = std::fs::read(folder.join(name)).unwrap();
        assert_ne!(bytes, b"the last run's", "{name} was not replaced");
    }
    // No temporary file is left (the sensor table of the last run stays: this one has none).
    assert_eq!(
        names(&folder),
        [
            "cornell.png",
            "report.csv",
            "report.sensors.csv",
            "solution.ply"
        ]
    );
    std::fs::remove_dir_all(folder).unwrap();
}

#[cfg(target_os = "linux")]
#[test]
fn a_full_device_fails_the_run_with_a_message() {
    // An image path that leads to /dev/full: every write is refused for want of space.
    let link = common::temp("outputs-full", "full.png");
    let _ = std::fs::remove_file(&link);
    std::os::unix::fs::symlink("/dev/full", &link).unwrap();
    let out = small_render(&link, &["-q"]);
    let message = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{message}");
    assert!(message.contains("No space left on device"), "{message}");
    std::fs::remove_dir_all(link.parent().unwrap()).unwrap();
}

#[test]
fn one_file_named_by_two_outputs_is_refused_before_any_work() {
    let image = common::temp("outputs-twice", "image.png");
    std::fs::write(&image, "the last run's").unwrap();
    let same = image.parent().unwrap().join(".").join("image.png");
    let out = strahl(&[
        "render",
        "cornell",
        "-o",
        image.to_str().unwrap(),
        "--aa",
        "adaptive",
        "--aa-map",
        same.to_str().unwrap(),
    ]);
    let message = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{message}");
    assert!(
        message.contains("--aa-map") && message.contains("-o writes too"),
        "{message}"
    );
    assert_eq!(std::fs::read(&image).unwrap(), b"the last run's");
    std::fs::remove_dir_all(image.parent().unwrap()).unwrap();
}

#[cfg(target_os = "linux")]
#[test]
fn an_output_that_cannot_be_written_is_refused_before_any_work() {
    use std::os::unix::fs::PermissionsExt;
    // A folder that does not exist, and a read-only one holding the last run's output; the
    // superuser writes into a read-only folder all the same, so there a folder of sysfs,
    // which takes no new file from anyone, stands in for it.
    let report = common::temp("outputs-read-only", "report.json");
    let folder = report.parent().unwrap().to_path_buf();
    std::fs::write(&report, "the last run's").unwrap();
    std::fs::set_permissions(&folder, std::fs::Permissions::from_mode(0o555)).unwrap();
    let probe = folder.join("probe");
    let read_only = if std::fs::write(&probe, "").is_ok() {
        std::fs::remove_file(&probe).unwrap();
        std::path::PathBuf::from("/sys/strahl-read-only-test.json")
    } else {
        report.clone()
    };
    let missing = folder.join("no such folder").join("image.png");
    let runs = [
        (
            "--report",
            read_only.clone(),
            strahl(&[
                "solve",
                "blocks:1000",
                "--solver",
                "hierarchical",
                "--report",
                read_only.to_str().unwrap(),
            ]),
        ),
        ("-o", missing.clone(), small_render(&missing, &["-q"])),
    ];
    for (flag, path, out) in runs {
        let message = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{message}");
        // The check's own words: the run stopped before its work (a solve of blocks:1000
        // would take a minute), naming the flag and the file.
        let expected = format!("{flag} {}: cannot write there", path.display());
        assert!(message.contains(&expected), "{message}");
    }
    assert_eq!(std::fs::read(&report).unwrap(), b"the last run's");
    std::fs::set_permissions(&folder, std::fs::Permissions::from_mode(0o755)).unwrap();
    std::fs::remove_dir_all(folder).unwrap();
}

#[test]
fn a_reader_that_stops_early_is_no_error() {
    // `strahl solve … | head -c 10`: the report goes to standard output and the reader
    // closes it after ten bytes.
    use std::io::Read;
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_strahl"))
        .args(["solve", "canopy:300", "--photons", "20000", "-q"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut start = [0u8; 10];
    child.stdout.take().unwrap().read_exact(&mut start).unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(&start[..1], b"{");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{:?}: {stderr}", out.status);
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn listings_to_a_reader_that_has_gone_are_no_error() {
    // `strahl info … | head -0`, `strahl scenes | head -0`: the reader is gone before the
    // first line is written.
    for args in [&["info", "cornell"][..], &["scenes"][..]] {
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_strahl"))
            .args(args)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{args:?}: {:?}: {stderr}", out.status);
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
}
