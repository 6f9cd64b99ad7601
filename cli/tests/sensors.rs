//! Point sensors: read from the scene file, reported by every solver, agreeing with a small
//! named patch at the same place, with standard errors that match the spread of independent
//! runs, the same for any thread count, and written to CSV.

mod common;

use common::{strahl, temp};
use glam::Vec3;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::light_model::{LightTraceSettings, trace_light};
use strahl::progress::{Cancel, NoProgress};
use strahl::radiosity::solve::SystemOptions;
use strahl::radiosity::solve::hierarchical::{HierarchicalSettings, solve_hierarchical};
use strahl::scene::{Material, Sensor, Shape, builtin, load_str};
use strahl::world::World;

/// Lux of a white irradiance figure: 683 × its luminance.
fn lux(e: strahl::color::Rgb64) -> f64 {
    683.0 * e.luminance()
}

const SENSOR_SCENE: &str = r#"
[materials.grey]
diffuse = 0.5

[materials.lamp]
emission = 10.0

[[objects]]
name = "floor"
type = "parallelogram"
material = "grey"
origin = [-1, 0, 1]
edge_u = [2, 0, 0]
edge_v = [0, 0, -2]

[[objects]]
name = "lamp"
type = "parallelogram"
material = "lamp"
origin = [-0.25, 1, -0.25]
edge_u = [0.5, 0, 0]
edge_v = [0, 0, 0.5]

[[sensors]]
name = "centre"
position = [0, 0, 0]

[[sensors]]
name = "desk"
position = [-0.5, 0.5, -0.5]
edge_u = [1, 0, 0]
edge_v = [0, 0, 1]
count = [2, 3]
normal = [0, 2, 0]
"#;

#[test]
fn sensors_and_grids_are_read_from_the_scene_file() {
    let scene = load_str(SENSOR_SCENE, "sensors.toml", std::path::Path::new(".")).unwrap();
    let names: Vec<&str> = scene.sensors.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "centre",
            "desk[0,0]",
            "desk[0,1]",
            "desk[0,2]",
            "desk[1,0]",
            "desk[1,1]",
            "desk[1,2]"
        ]
    );
    assert_eq!(scene.sensors[0].normal, Vec3::Y);
    assert_eq!(
        scene.sensors[6].position,
        Vec3::new(0.25, 0.5, 0.5 - 1.0 / 6.0)
    );
    assert_eq!(scene.sensors[6].normal, Vec3::Y);
    let broken = SENSOR_SCENE.replace("count = [2, 3]\n", "");
    let error = load_str(&broken, "sensors.toml", std::path::Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("sensors[1]") && error.contains("count"),
        "{error}"
    );
    let zero = SENSOR_SCENE.replace("normal = [0, 2, 0]", "normal = [0, 0, 0]");
    let error = load_str(&zero, "sensors.toml", std::path::Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("sensors[1].normal") && error.contains("zero"),
        "{error}"
    );
}

/// The Cornell box with a sensor facing up at `at` on the floor and, when `with_patch`, a
/// black 4 × 4 cm patch named `probe` just under it.
fn cornell_with_probe(at: Vec3, with_patch: bool) -> Arc<World> {
    let mut scene = builtin::load("cornell").unwrap().unwrap();
    scene.sensors.push(Sensor {
        name: "probe".to_string(),
        position: at,
        normal: Vec3::Y,
    });
    if with_patch {
        let black = scene.add_material(Material::diffuse("probe", strahl::color::Rgb::BLACK));
        let half = 0.02;
        scene.add_object(
            "probe",
            Shape::Parallelogram {
                origin: at + Vec3::new(-half, -0.0005, half),
                edge_u: Vec3::X * 2.0 * half,
                edge_v: Vec3::Z * -2.0 * half,
            },
            black,
        );
    }
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

#[test]
fn a_sensor_reads_what_a_small_patch_at_its_place_receives() {
    // On the open floor of the Cornell box, between the blocks and the left wall.
    let at = Vec3::new(0.12, 0.001, 0.35);
    let world = cornell_with_probe(at, true);
    let settings = LightTraceSettings {
        photons: 4_000_000,
        seed: 3,
        ..LightTraceSettings::default()
    };
    let out = trace_light(&world, &settings, &NoProgress, &Cancel::new()).unwrap();
    let table = out.power.table();
    let entry = (0..table.len())
        .find(|&e| table.surfaces()[e].name == "probe")
        .unwrap();
    let area = table.surfaces()[entry].area;
    let patch = lux(out.power.balance(entry).incident) / area;
    let patch_error = lux(out.power.standard_error(entry).unwrap()) / area;
    let sensor = lux(out.sensors[0].irradiance());
    let sensor_error = lux(out.sensors[0].standard_error.unwrap());
    // The patch averages 16 cm² where the sensor reads one point: allow 1 % for the slope of
    // the light over it, plus four standard errors of the two estimates.
    let bound = 0.01 * patch + 4.0 * (patch_error.powi(2) + sensor_error.powi(2)).sqrt();
    assert!(
        (patch - sensor).abs() < bound,
        "patch {patch} ± {patch_error} lx, sensor {sensor} ± {sensor_error} lx"
    );
    assert!(sensor_error < 0.01 * sensor, "{sensor_error} of {sensor}");

    // Hierarchical radiosity's sensor agrees with the light model's (without the patch).
    let world = cornell_with_probe(at, false);
    let (system, solution) = solve_hierarchical(
        &world,
        SystemOptions::default(),
        &HierarchicalSettings::default(),
        &NoProgress,
        &Cancel::new(),
    )
    .unwrap();
    let radiosity = lux(solution.measurement(&system).sensors[0].irradiance());
    assert!(
        (radiosity - sensor).abs() < 0.02 * sensor,
        "radiosity {radiosity} lx, light model {sensor} lx"
    );
}

#[test]
fn light_model_standard_errors_match_the_spread_of_independent_runs() {
    let scene = load_str(SENSOR_SCENE, "sensors.toml", std::path::Path::new(".")).unwrap();
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let runs: Vec<_> = (0..12)
        .map(|seed| {
            let settings = LightTraceSettings {
                photons: 20_000,
                seed,
                ..LightTraceSettings::default()
            };
            trace_light(&world, &settings, &NoProgress, &Cancel::new()).unwrap()
        })
        .collect();
    let spread = |values: &[f64]| {
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        let var =
            values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (values.len() - 1) as f64;
        var.sqrt()
    };
    // The floor-centre sensor and the floor's incident power.
    let sensor: Vec<f64> = runs.iter().map(|r| r.sensors[0].irradiance().g).collect();
    let sensor_se = runs
        .iter()
        .map(|r| r.sensors[0].standard_error.unwrap().g)
        .sum::<f64>()
        / 12.0;
    let floor: Vec<f64> = runs.iter().map(|r| r.power.balance(0).incident.g).collect();
    let floor_se = runs
        .iter()
        .map(|r| r.power.standard_error(0).unwrap().g)
        .sum::<f64>()
        / 12.0;
    // With 12 runs the spread itself is known to about ±21 % (1σ): allow 0.5 to 1.6 times.
    for (name, observed, reported) in [
        ("sensor", spread(&sensor), sensor_se),
        ("floor", spread(&floor), floor_se),
    ] {
        let ratio = observed / reported;
        assert!(
            (0.5..1.6).contains(&ratio),
            "{name}: spread {observed}, reported {reported}"
        );
    }
}

#[test]
fn sensor_reports_are_the_same_for_any_thread_count_and_reach_the_csv() {
    let scene = temp("sensors", "scene.toml");
    std::fs::write(&scene, SENSOR_SCENE).unwrap();
    for solver in ["light-trace", "hierarchical", "progressive"] {
        let reports: Vec<serde_json::Value> = ["1", "2"]
            .iter()
            .map(|threads| {
                let out = temp("sensors", &format!("{solver}-{threads}.json"));
                let run = strahl(&[
                    "solve",
                    scene.to_str().unwrap(),
                    "--solver",
                    solver,
                    "--photons",
                    "100000",
                    "--threads",
                    threads,
                    "-q",
                    "--report",
                    out.to_str().unwrap(),
                ]);
                assert!(
                    run.status.success(),
                    "{}",
                    String::from_utf8_lossy(&run.stderr)
                );
                let v: serde_json::Value =
                    serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
                v["sensors"].clone()
            })
            .collect();
        assert_eq!(reports[0], reports[1], "{solver}");
        let sensors = reports[0].as_array().unwrap();
        assert_eq!(sensors.len(), 7);
        let centre = &sensors[0];
        let total = centre["illuminance_lux"].as_f64().unwrap();
        let parts = centre["direct_illuminance_lux"].as_f64().unwrap()
            + centre["indirect_illuminance_lux"].as_f64().unwrap();
        assert!(
            total > 0.0 && (total - parts).abs() < 1e-9 * total,
            "{solver}: {centre}"
        );
        assert_eq!(
            centre.get("standard_error_lux").is_some(),
            solver == "light-trace",
            "{solver}"
        );
    }
    let csv = temp("sensors", "report.csv");
    let run = strahl(&[
        "solve",
        scene.to_str().unwrap(),
        "--photons",
        "10000",
        "-q",
        "--report",
        csv.to_str().unwrap(),
    ]);
    assert!(run.status.success());
    let rows = std::fs::read_to_string(temp("sensors", "report.sensors.csv")).unwrap();
    let lines: Vec<&str> = rows.lines().collect();
    assert_eq!(lines.len(), 8);
    assert!(lines[0].starts_with("name,x,y,z,nx,ny,nz,illuminance_lux"));
    assert!(
        lines[2].starts_with("\"desk[0,0]\",-0.25,0.5,"),
        "{}",
        lines[2]
    );
}

#[test]
fn a_sensor_at_the_coordinate_origin_on_a_floor_is_not_shadowed_by_the_floor() {
    // A 0.5 m square lamp of radiance 10 one metre above a sensor lying on the floor at
    // (0, 0, 0): E = π·L·F with F from the closed form. Shadow rays arriving there from the
    // lamp once hit the floor they end on (the end's offset is tiny at the origin).
    let text = SENSOR_SCENE.replace(
        "[[sensors]]\nname = \"desk\"",
        "[[unused]]\nname = \"desk\"",
    );
    let text = &text[..text.find("[[unused]]").unwrap()];
    let scene = load_str(text, "origin.toml", std::path::Path::new(".")).unwrap();
    assert_eq!(scene.sensors[0].position, Vec3::ZERO);
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let f = strahl::validate::closed_forms::parallel_rectangle((-0.25, 0.25), (-0.25, 0.25), 1.0);
    let expected = std::f64::consts::PI * 10.0 * f;
    let settings = LightTraceSettings {
        photons: 1_000_000,
        seed: 9,
        ..LightTraceSettings::default()
    };
    let light = trace_light(&world, &settings, &NoProgress, &Cancel::new()).unwrap();
    let reading = &light.sensors[0];
    let (direct, se) = (reading.direct.g, reading.standard_error.unwrap().g);
    assert!(
        (direct - expected).abs() < 4.0 * se + 1e-4 * expected,
        "{direct} ± {se} vs {expected}"
    );
    let traced = strahl::trace::sensor_readings(
        &world,
        None,
        &strahl::trace::SensorSettings {
            samples: 1 << 16,
            paths: 1,
            seed: 9,
        },
    );
    let (direct, se) = (traced[0].direct.g, traced[0].standard_error.unwrap().g);
    assert!(
        (direct - expected).abs() < 4.0 * se + 1e-4 * expected,
        "{direct} ± {se} vs {expected}"
    );
}
