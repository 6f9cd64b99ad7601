//! A fixed seed gives the same output bytes run after run and whatever the thread count, for
//! every rendering method and every solver (the report's timing and memory fields aside).

mod common;

use common::{strahl, temp};

/// Runs `args` writing to `out` (appended as the last argument) and returns the bytes.
fn output_of(args: &[&str], out: &std::path::Path) -> Vec<u8> {
    let mut all: Vec<&str> = args.to_vec();
    all.push(out.to_str().unwrap());
    let run = strahl(&all);
    assert!(
        run.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    std::fs::read(out).unwrap()
}

/// The report at `bytes` without the fields that measure the machine (time, memory).
fn without_timing(bytes: &[u8]) -> serde_json::Value {
    fn strip(v: &mut serde_json::Value) {
        match v {
            serde_json::Value::Object(map) => {
                map.retain(|k, _| !k.starts_with("seconds") && !k.contains("memory"));
                map.values_mut().for_each(strip);
            }
            serde_json::Value::Array(items) => items.iter_mut().for_each(strip),
            _ => {}
        }
    }
    let mut v: serde_json::Value = serde_json::from_slice(bytes).unwrap();
    strip(&mut v);
    v
}

#[test]
fn every_rendering_method_gives_the_same_image_for_any_thread_count() {
    let methods: [&[&str]; 5] = [
        &["--method", "raytrace", "--spp", "4"],
        &["--method", "raytrace", "--aa", "adaptive"],
        &["--method", "pathtrace", "--spp", "8"],
        &["--method", "radiosity"],
        &["--method", "final-gather", "--gather-rays", "4"],
    ];
    for method in methods {
        let images: Vec<Vec<u8>> = ["1", "2", "2"]
            .iter()
            .enumerate()
            .map(|(run, threads)| {
                let mut args = vec!["render", "cornell", "--width", "48", "--height", "48"];
                args.extend_from_slice(method);
                args.extend(["--seed", "5", "--threads", threads, "-q", "-o"]);
                output_of(&args, &temp("determinism", &format!("image-{run}.pfm")))
            })
            .collect();
        assert!(images[0].len() > 48 * 48 * 12);
        assert!(
            images[0] == images[1] && images[1] == images[2],
            "{method:?}: the images differ"
        );
    }
}

#[test]
fn every_solver_gives_the_same_report_for_any_thread_count() {
    let solvers: [&[&str]; 6] = [
        &["--solver", "light-trace", "--photons", "20000"],
        &["--solver", "surface-trace", "--points", "64"],
        &["--solver", "matrix", "--mesh-size", "levels:2"],
        &["--solver", "progressive", "--mesh-size", "levels:2"],
        &["--solver", "hierarchical", "--error", "1e-3"],
        &["--solver", "hierarchical-shooting", "--error", "1e-3"],
    ];
    for solver in solvers {
        let reports: Vec<serde_json::Value> = ["1", "2", "2"]
            .iter()
            .enumerate()
            .map(|(run, threads)| {
                let mut args = vec!["solve", "cornell"];
                args.extend_from_slice(solver);
                args.extend(["--seed", "5", "--threads", threads, "-q", "--report"]);
                let out = temp("determinism", &format!("report-{run}.json"));
                without_timing(&output_of(&args, &out))
            })
            .collect();
        assert!(reports[0]["objects"].as_array().unwrap().len() >= 8);
        assert!(
            reports[0] == reports[1] && reports[1] == reports[2],
            "{solver:?}: the reports differ"
        );
    }
}
