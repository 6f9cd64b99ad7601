//! Reports split each surface's incident light into direct and indirect alike in the light
//! model and the radiosity solvers that tell them apart.

mod common;

use common::{strahl, temp};

/// Per object of the Cornell box: (name, direct power, incident power, standard error of the
/// incident power) from `solve cornell` with `args`, green channel.
fn direct_parts(args: &[&str], out: &str) -> Vec<(String, f64, f64, f64)> {
    let path = temp("direct-split", out);
    let mut all = vec!["solve", "cornell", "-q", "--report", path.to_str().unwrap()];
    all.extend_from_slice(args);
    let run = strahl(&all);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    report["objects"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| {
            let g = |field: &str| o[field][1].as_f64().unwrap_or(0.0);
            (
                o["name"].as_str().unwrap().to_string(),
                g("direct_power"),
                g("incident_power"),
                g("incident_power_standard_error"),
            )
        })
        .collect()
}

#[test]
fn radiosity_and_the_light_model_agree_on_the_direct_light_of_every_object() {
    let reference = direct_parts(&["--photons", "4000000", "--seed", "7"], "light.json");
    let total: f64 = reference.iter().map(|r| r.1).sum();
    for solver in ["hierarchical", "matrix", "progressive"] {
        let got = direct_parts(&["--solver", solver], &format!("{solver}.json"));
        for ((name, direct, incident, _), (_, expected, _, se)) in got.iter().zip(&reference) {
            assert!(*direct <= incident * (1.0 + 1e-9), "{solver} {name}");
            // Per object within 2 % of the object (the flat solvers' coarse mesh), or of 0.2 %
            // of all direct light for the small ones, plus four standard errors.
            let bound = 0.02 * expected + 0.002 * total + 4.0 * se;
            assert!(
                (direct - expected).abs() < bound,
                "{solver} {name}: direct {direct} W, light model {expected} W ± {se}"
            );
        }
    }
}
