//! The `strahl` binary as a user runs it: outputs, exit codes and one-line errors.

use std::path::PathBuf;
use std::process::Output;

mod common;

use common::strahl;

fn temp(name: &str) -> PathBuf {
    common::temp("cli", name)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn scenes_lists_the_built_ins() {
    let o = strahl(&["scenes"]);
    assert!(o.status.success());
    let out = String::from_utf8_lossy(&o.stdout);
    for name in ["cornell", "cornell-textured", "spheres", "neon"] {
        assert!(
            out.lines().any(|l| l.starts_with(name)),
            "{name} missing in {out}"
        );
    }
}

#[test]
fn render_writes_png_exr_and_pfm() {
    for ext in ["png", "exr", "pfm"] {
        let path = temp(&format!("cornell.{ext}"));
        let o = strahl(&[
            "render",
            "cornell",
            "-o",
            path.to_str().unwrap(),
            "--width",
            "24",
            "--height",
            "16",
            "--quiet",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let film = strahl::image::load(&path).unwrap();
        assert_eq!((film.width(), film.height()), (24, 16));
        assert!(film.mean().luminance() > 0.0);
    }
}

#[test]
fn adaptive_antialiasing_writes_its_subdivision_map() {
    let (img, map) = (temp("a.png"), temp("a-map.png"));
    let o = strahl(&[
        "render",
        "cornell",
        "-o",
        img.to_str().unwrap(),
        "--width",
        "32",
        "--height",
        "32",
        "--aa",
        "adaptive",
        "--aa-map",
        map.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let m = strahl::image::load(&map).unwrap();
    let max = m.pixels().iter().map(|c| c.r).fold(0.0, f32::max);
    assert!(max > 0.9, "the most subdivided pixel is white");
}

#[test]
fn bad_input_gives_one_line_error_and_failure() {
    let out = temp("x.png");
    let cases: Vec<Vec<&str>> = vec![
        vec!["render", "no-such-scene", "-o", out.to_str().unwrap()],
        vec!["render", "cornell", "-o", "image.bmp"],
        vec!["render", "spheres:zero", "-o", out.to_str().unwrap()],
        vec![
            "render",
            "cornell",
            "-o",
            out.to_str().unwrap(),
            "--width",
            "100000",
            "--height",
            "100000",
        ],
        vec!["info", "/nonexistent/scene.toml"],
    ];
    for args in cases {
        let o = strahl(&args);
        assert!(!o.status.success(), "{args:?} should fail");
        let e = stderr(&o);
        assert_eq!(e.trim_end().lines().count(), 1, "{args:?}: {e}");
        assert!(e.starts_with("error: "), "{args:?}: {e}");
    }
}

#[test]
fn scene_file_errors_name_file_line_and_field() {
    let path = temp("broken.toml");
    std::fs::write(
        &path,
        "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\nfov = 40\n\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 1, 0]\nradius = -1\n",
    )
    .unwrap();
    let o = strahl(&["info", path.to_str().unwrap()]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(e.contains("broken.toml:9:"), "{e}");
    assert!(e.contains("radius"), "{e}");
}

#[test]
fn info_and_bench_report_statistics() {
    let o = strahl(&["info", "spheres:50"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("50 sphere") && out.contains("5 point"),
        "{out}"
    );
    let o = strahl(&["bench", "cornell", "--rays", "random", "--repeat", "1"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(json["ray_count"], 1 << 20);
    assert!(json["closest_hit"]["mrays_per_second"].as_f64().unwrap() > 0.0);
    assert!(json["any_hit"]["hits"].as_u64().unwrap() > 0);
}

#[test]
fn a_periodic_field_is_solved_by_the_light_model_and_radiosity_and_rendered_by_radiosity() {
    let o = strahl(&["info", "field:100"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("periodic    plot x [0.0, 0.5]"), "{out}");
    let report = temp("field.json");
    let args = ["solve", "field:100", "--photons", "20000", "-q", "--report"];
    let o = strahl(&[&args[..], &[report.to_str().unwrap()]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["objects"].as_array().unwrap().len(), 101);
    // Rays from every leaf: each with its standard error, none non-finite.
    let args = [
        "solve",
        "field:100",
        "--solver",
        "surface-trace",
        "--points",
        "16",
        "-q",
    ];
    let o = strahl(&[&args[..], &["--report", report.to_str().unwrap()]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["solver"], "surface-trace");
    for object in json["objects"].as_array().unwrap() {
        let sigma = object["incident_power_standard_error"][1].as_f64().unwrap();
        assert!(object["absorbed_power"][1].as_f64().unwrap() > 0.0 && sigma.is_finite());
    }
    // Hierarchical radiosity reports the plot's leaves and ground, not the copies around it.
    let o = strahl(&[
        "solve",
        "field:100",
        "--solver",
        "hierarchical",
        "-q",
        "--report",
        report.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["objects"].as_array().unwrap().len(), 101);
    let image = temp("field.png");
    let _ = std::fs::remove_file(&image);
    let o = strahl(&[
        "render",
        "field:100",
        "--method",
        "radiosity",
        "-o",
        image.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(image.exists());
}

#[test]
fn the_placed_plants_example_reports_every_copy() {
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/placed-plants/plants.toml"
    );
    let o = strahl(&["info", scene]);
    assert!(o.status.success(), "{}", stderr(&o));
    let info = String::from_utf8_lossy(&o.stdout);
    assert!(
        info.contains("placed      200 copies of shared meshes, 24 triangles kept once"),
        "{info}"
    );
    let report = temp("plants.json");
    let args = ["solve", scene, "--photons", "50000", "-q", "--report"];
    let o = strahl(&[&args[..], &[report.to_str().unwrap()]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let objects = json["objects"].as_array().unwrap();
    assert_eq!(objects.len(), 201);
    // Every copy its own row, with its light: the sun and sky reach every plant on the plot.
    for (i, plant) in objects[1..].iter().enumerate() {
        assert_eq!(plant["name"], format!("plant[{i}]"));
        let absorbed = plant["absorbed_power"][1].as_f64().unwrap();
        assert!(absorbed > 0.0 && absorbed.is_finite(), "{plant}");
    }
}

#[test]
fn the_plant_example_reports_its_bands_in_json_and_csv() {
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/plant-bands/plant.toml"
    );
    let json_path = temp("plant.json");
    let args = ["solve", scene, "--photons", "50000", "-q", "--report"];
    let o = strahl(&[&args[..], &[json_path.to_str().unwrap()]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json_path).unwrap()).unwrap();
    let bands = json["bands"].as_array().unwrap();
    let names: Vec<&str> = bands.iter().map(|b| b["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["PAR", "red", "far-red", "NIR"]);
    // Every leaf absorbs most of its PAR and little of its near infrared, as its spectra say.
    for (par, nir) in bands[0]["objects"].as_array().unwrap()[1..]
        .iter()
        .zip(&bands[3]["objects"].as_array().unwrap()[1..])
    {
        let share = |o: &serde_json::Value| {
            o["absorbed_power"].as_f64().unwrap() / o["incident_power"].as_f64().unwrap()
        };
        assert!(share(par) > 0.8 && share(nir) < 0.3, "{par} {nir}");
        assert!(par["photon_irradiance_umol_m2_s"].as_f64().unwrap() > 0.0);
    }
    assert_eq!(json["red_far_red"]["objects"].as_array().unwrap().len(), 10);
    let csv_path = temp("plant.csv");
    let args = ["solve", scene, "--photons", "50000", "-q", "--report"];
    let o = strahl(&[&args[..], &[csv_path.to_str().unwrap()]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(&csv_path).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(
        header.contains("PAR_photon_irradiance_umol_m2_s") && header.ends_with("red_far_red"),
        "{header}"
    );
    let o = strahl(&[
        "solve",
        scene,
        "--batch",
        "1/2",
        "--partial",
        "p.json",
        "-q",
    ]);
    assert!(!o.status.success() && stderr(&o).contains("not split into batches"));
}

#[test]
fn a_day_reports_each_state_alone() {
    let scene = temp("day.toml");
    std::fs::write(
        &scene,
        r#"
[materials.black]
diffuse = 0

[[objects]]
type = "quad"
name = "plate"
material = "black"
vertices = [[0, 0, 1], [1, 0, 1], [1, 0, 0], [0, 0, 0]]

[[sensors]]
name = "meter"
position = [0.5, 0.001, 0.5]
normal = [0, 1, 0]

[[lights]]
type = "day"
sky_type = 12
date = "2026-06-21"
utc_offset_hours = 2
latitude_deg = 52.52
longitude_deg = 13.40
states = [
  { time = "09:00", direct_normal = 500, diffuse_horizontal = 100 },
  { time = "13:15", direct_normal = 800, diffuse_horizontal = 150 },
]
"#,
    )
    .unwrap();
    let report = temp("day.json");
    let args = [
        "solve",
        scene.to_str().unwrap(),
        "--solver",
        "matrix",
        "-q",
        "--report",
    ];
    let o = strahl(&[&args[..], &[report.to_str().unwrap()]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let states = json["states"].as_array().unwrap();
    assert_eq!(states.len(), 2);
    let plate = |v: &serde_json::Value| v["objects"][0]["incident_power"][1].as_f64().unwrap();
    let mean = json["objects"][0]["incident_power"][1].as_f64().unwrap();
    assert_eq!(states[1]["time"], "13:15");
    // The run's seconds hold the states' solves (matrix radiosity solves each after the day).
    let stats = &json["stats"];
    let parts = stats["seconds_parts"].as_f64().unwrap();
    assert!(
        parts > 0.0 && stats["seconds"].as_f64().unwrap() > parts,
        "{stats}"
    );
    assert!(((plate(&states[0]) + plate(&states[1])) / 2.0 / mean - 1.0).abs() < 1e-6);
    // The CSV form holds every state's figures too, the same numbers as the JSON.
    let csv = temp("day.csv");
    let o = strahl(&[&args[..], &[csv.to_str().unwrap()]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header.len(), row.len());
    for (k, time) in ["09:00", "13:15"].iter().enumerate() {
        let column = format!("state_{time}_incident_power_g");
        let at = header.iter().position(|h| *h == column).unwrap();
        assert_eq!(
            row[at].parse::<f64>().unwrap(),
            plate(&states[k]),
            "{column}"
        );
        let lux = format!("state_{time}_illuminance_lux");
        assert!(header.contains(&lux.as_str()), "{lux}");
    }
    let sensors = std::fs::read_to_string(csv.with_file_name("day.sensors.csv")).unwrap();
    let header: Vec<&str> = sensors.lines().next().unwrap().split(',').collect();
    let row: Vec<&str> = sensors.lines().nth(1).unwrap().split(',').collect();
    let at = header
        .iter()
        .position(|h| *h == "state_13:15_illuminance_lux")
        .unwrap();
    let lux = json["states"][1]["sensors"][0]["illuminance_lux"].as_f64();
    assert_eq!(row[at].parse::<f64>().ok(), lux);
}

#[test]
fn per_face_reports_every_face_and_the_faces_add_up_to_their_object() {
    // The same photons, told apart by face or not: the faces of each object add up to it.
    let solve = |name: &str, extra: &[&str]| {
        let report = temp(name);
        let mut args = vec!["solve", "cornell", "--photons", "20000", "-q", "--report"];
        args.push(report.to_str().unwrap());
        args.extend_from_slice(extra);
        let o = strahl(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
        json["objects"].as_array().unwrap().clone()
    };
    let objects = solve("objects.json", &[]);
    let faces = solve("faces.json", &["--per-face"]);
    // The built-in box: the ceiling in four pieces around the lamp, the red wall in two, five
    // faces per block, one for everything else.
    assert_eq!((objects.len(), faces.len()), (8, 20));
    for object in &objects {
        let name = object["name"].as_str().unwrap();
        assert!(object["face"].is_null(), "{object}");
        let of_it: Vec<_> = faces.iter().filter(|f| f["name"] == name).collect();
        assert!(of_it.iter().all(|f| f["face"].is_u64()), "{name}");
        for key in ["area", "incident_power"] {
            let whole = serde_json::to_string(&object[key]).unwrap();
            let sum = |c: usize| -> f64 {
                of_it
                    .iter()
                    .map(|f| f[key].get(c).unwrap_or(&f[key]).as_f64().unwrap())
                    .sum()
            };
            let want =
                |c: usize| -> f64 { object[key].get(c).unwrap_or(&object[key]).as_f64().unwrap() };
            for c in 0..3 {
                let (got, want) = (sum(c), want(c));
                assert!(
                    (got - want).abs() <= 1e-9 * want.abs(),
                    "{name} {key}: faces {got}, object {whole}"
                );
            }
        }
    }
}

#[test]
fn radiosity_warns_about_light_it_does_not_follow() {
    // Glass and mirrors: radiosity counts the light they reflect specularly or refract as
    // absorbed, and names them; translucent leaves it follows, and does not warn about.
    let o = strahl(&[
        "solve",
        "../tests/data/lobes.toml",
        "--solver",
        "hierarchical",
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("warning") && err.contains("glass") && err.contains("mirror"),
        "{err}"
    );
    // With the lobes radiosity does not model dropped, there is nothing to warn about, and
    // the light model solves that scene: the glass and the mirror absorb what they would
    // have sent on, so the objects absorb more than in the scene as it is.
    let o = strahl(&[
        "solve",
        "../tests/data/lobes.toml",
        "--solver",
        "hierarchical",
        "--diffuse-only",
        "--quiet",
    ]);
    assert!(
        o.status.success() && !stderr(&o).contains("warning"),
        "{}",
        stderr(&o)
    );
    let absorbed = |extra: &[&str]| {
        let report = temp(&format!("lobes{}.json", extra.len()));
        let mut args = vec![
            "solve",
            "../tests/data/lobes.toml",
            "--photons",
            "20000",
            "-q",
        ];
        args.extend_from_slice(&["--report", report.to_str().unwrap()]);
        args.extend_from_slice(extra);
        assert!(strahl(&args).status.success());
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
        json["totals"]["absorbed_power"][1].as_f64().unwrap()
    };
    let (as_it_is, diffuse_only) = (absorbed(&[]), absorbed(&["--diffuse-only"]));
    assert!(diffuse_only > as_it_is, "{diffuse_only} vs {as_it_is}");
    let o = strahl(&["solve", "canopy:4", "--solver", "hierarchical", "--quiet"]);
    assert!(o.status.success());
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
    let o = strahl(&[
        "solve",
        "cornell",
        "--solver",
        "hierarchical",
        "--error",
        "1e-3",
        "-q",
    ]);
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
}
