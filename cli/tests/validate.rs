//! `strahl validate --quick`: every analytic case passes through every method, as the
//! command line runs it, and the table and JSON report say so.

mod common;

use common::{strahl, temp};

#[test]
fn the_quick_validation_suite_passes_for_every_method() {
    let report = temp("validate", "table.json");
    let run = strahl(&["validate", "--quick", "--report", report.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(stdout.contains(" 0 failed"), "{stdout}");
    let rows: Vec<serde_json::Value> =
        serde_json::from_slice(&std::fs::read(&report).unwrap()).unwrap();
    assert!(rows.len() >= 380, "{} rows", rows.len());
    for method in [
        "direct",
        "pathtrace",
        "light-trace",
        "surface-trace",
        "matrix",
        "progressive",
        "hierarchical-shooting",
        "hierarchical",
    ] {
        let of_method: Vec<_> = rows.iter().filter(|r| r["method"] == method).collect();
        assert!(of_method.len() >= 20, "{method}: {} rows", of_method.len());
        for r in &of_method {
            let error = r["relative_error"].as_f64().unwrap();
            let tolerance = r["tolerance"].as_f64().unwrap();
            assert!(r["pass"] == true && error.abs() <= tolerance, "{r}");
            // 1 % of a closed form, or that and three standard errors of a recording.
            assert!(tolerance == 0.01 || r["case"] == "cornell-faces", "{r}");
        }
        // Every face of the Cornell box through every radiosity solver and the surface tracer.
        let faces = of_method.iter().filter(|r| r["case"] == "cornell-faces");
        let ray_tracer = ["direct", "pathtrace", "light-trace"].contains(&method);
        assert_eq!(faces.count(), if ray_tracer { 0 } else { 20 }, "{method}");
    }
}

#[test]
fn the_full_validation_suite_passes_with_every_monte_carlo_figure_proven_to_one_percent() {
    let report = temp("validate", "full.json");
    let run = strahl(&["validate", "--report", report.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let rows: Vec<serde_json::Value> =
        serde_json::from_slice(&std::fs::read(&report).unwrap()).unwrap();
    assert!(rows.len() >= 390, "{} rows", rows.len());
    assert!(rows.iter().any(|r| r["case"] == "cube ρ=0.95"));
    for r in &rows {
        assert!(r["pass"] == true, "{r}");
        // Three standard errors under 1 %: the run's own noise cannot hide a 1 % error. The
        // surface tracer states its errors with its Sobol points counted as independent,
        // which overstates them (the Cornell box's dim faces: stated 3σ 1.1–2.2 % at 2¹⁸
        // points, off by 0.01–0.25 %): held to 3 % stated, and to 1 % off like every row.
        if let Some(se) = r["standard_error"].as_f64() {
            let expected = r["expected"].as_f64().unwrap();
            if r["method"] == "surface-trace" {
                assert!(3.0 * se < 0.03 * expected.abs(), "{r}");
            } else {
                assert!(3.0 * se < 0.01 * expected.abs(), "{r}");
            }
        }
    }
}

#[test]
fn unknown_methods_are_refused() {
    let run = strahl(&["validate", "--quick", "--method", "nonsense"]);
    assert!(!run.status.success());
    assert!(String::from_utf8_lossy(&run.stderr).contains("nonsense"));
}

#[test]
fn the_quick_suite_passes_with_the_final_gather_at_the_surfaces() {
    // Every radiosity solver's report measured anew at the reported surfaces: the furnaces,
    // the translucent sheet, the measuring patches and the rest within 1 %.
    let report = temp("validate", "gather.json");
    let run = strahl(&[
        "validate",
        "--quick",
        "--method",
        "matrix,progressive,hierarchical-shooting,hierarchical",
        "--surface-gather",
        "0.01",
        "--report",
        report.to_str().unwrap(),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stdout)
    );
    let rows: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    std::fs::remove_file(&report).unwrap();
    assert!(rows.len() > 150, "{}", rows.len());
    assert!(rows.iter().all(|r| r["pass"] == true));
}
