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
