//! Per-surface accuracy of hierarchical radiosity: the built-in Cornell box with every face of
//! every object reported on its own, against the light model at 2·10⁸ photons (recorded in
//! `src/validate/cornell_per_face_light_model.json`, its three standard errors 0.2–0.6 % on the
//! dim block faces). At the default settings the dim block faces are 3–5 % too bright;
//! `surface_error` (importance-driven budgets per reported surface) brings them to the
//! reference. A live light-model run checks that the recording still describes the code.
//! The final gather at the reported surfaces (`surface_gather`) brings them there too, at a
//! stated standard error, for either hierarchical solver.
//! And measuring patches: small black quads reading the light of CIE 171's lit wall past an
//! occluder (case 5.7, `strahl validate`'s `meters`), against the closed form at the defaults.

use serde_json::Value;
use std::collections::HashMap;
use std::sync::Arc;
use strahl::color::LUMINOUS_EFFICACY;
use strahl::light_model::LightTraceSettings;
use strahl::method::{
    AccelKind, Cancel, FinalGatherSettings, Method, NoProgress, RadiosityImageSettings,
    RadiositySettings, SolverKind, SurfaceGather, World, run,
};
use strahl::report::Report;
use strahl::scene::builtin;
use strahl::validate::Quantity;

/// Surfaces below this share of the power all surfaces receive are not compared (the
/// issue's threshold: none of the Cornell faces is below it).
const NEGLIGIBLE_SHARE: f64 = 1e-4;

fn cornell_per_face() -> Arc<World> {
    let mut scene = builtin::load("cornell").unwrap().unwrap();
    for object in &mut scene.objects {
        object.per_face = true;
    }
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

/// Per face (`object#face`): incident power and its standard error, W per channel.
type Faces = HashMap<String, ([f64; 3], [f64; 3])>;

fn triple(v: &Value) -> [f64; 3] {
    std::array::from_fn(|c| v[c].as_f64().unwrap())
}

/// The entries under `key` of the recording `tests/data/{file}`.
fn recorded(file: &str, key: &str) -> Vec<Value> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(file);
    let json: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    json[key].as_array().unwrap().clone()
}

/// The recorded reference (`strahl validate`'s `cornell-faces` case checks against it too).
fn reference() -> Faces {
    strahl::validate::recorded::cornell_faces()
        .iter()
        .map(|f| {
            let name = format!("{}#{}", f.object, f.face);
            (name, (f.incident_power, f.incident_power_standard_error))
        })
        .collect()
}

/// The faces a method reports on `world`.
fn faces(world: &Arc<World>, method: &Method) -> Faces {
    let outcome = run(world, method, &NoProgress, &Cancel::new()).unwrap();
    let report = Report::new("cornell", outcome.measurement.as_ref().unwrap());
    report
        .objects
        .iter()
        .map(|o| {
            let name = format!("{}#{}", o.name, o.face.unwrap());
            let error = o
                .incident_power_standard_error
                .map_or([0.0; 3], |e| e.to_array());
            (name, (o.incident_power.to_array(), error))
        })
        .collect()
}

/// The largest relative deviation of `computed` from `reference` over the channels of the
/// faces that matter, and its root mean square over them.
fn deviation(computed: &Faces, reference: &Faces) -> (f64, f64, String) {
    let total: f64 = reference.values().map(|(p, _)| p.iter().sum::<f64>()).sum();
    let (mut worst, mut squares, mut count, mut name) = (0.0f64, 0.0, 0, String::new());
    for (face, (expected, _)) in reference {
        if expected.iter().sum::<f64>() < NEGLIGIBLE_SHARE * total {
            continue;
        }
        let (got, _) = computed[face];
        for c in 0..3 {
            let e = (got[c] - expected[c]) / expected[c];
            squares += e * e;
            count += 1;
            if e.abs() > worst {
                (worst, name) = (e.abs(), format!("{face} channel {c}: {:+.2} %", 100.0 * e));
            }
        }
    }
    (worst, (squares / f64::from(count)).sqrt(), name)
}

#[test]
fn surface_error_brings_every_face_of_the_cornell_box_to_the_light_model() {
    let world = cornell_per_face();
    let reference = reference();
    let hierarchical = |surface_error: f64| {
        let mut settings = RadiositySettings::new(SolverKind::Hierarchical);
        settings.hierarchical.surface_error = surface_error;
        settings.surface_gather = SurfaceGather::OFF;
        Method::Radiosity(settings)
    };
    // The solution alone: whole objects within 1.3 % (tests/radiosity_vs_light_model.rs),
    // single faces up to 5.5 % off (measured: short block face 3, red +5.5 %; RMS 1.59 %;
    // +4.8 % and 1.62 % while partial visibility was judged by the measuring rays, which
    // refined more links near the blocks; before the final gather over the emitters' pieces
    // +8.3 % and 2.66 %).
    let (worst, rms, name) = deviation(&faces(&world, &hierarchical(0.0)), &reference);
    assert!(worst < 0.06 && rms < 0.018, "{name}, RMS {rms}");
    assert!(
        worst > 0.03,
        "the defaults are better than recorded: {name}"
    );
    // With per-surface budgets every face is within 1.5 % and most within 0.5 % (measured:
    // largest 1.38 %, short block face 3 red; RMS 0.45 %).
    let (worst, rms_budgeted, name) = deviation(&faces(&world, &hierarchical(0.003)), &reference);
    assert!(worst < 0.015, "{name}");
    assert!(
        rms_budgeted < 0.005 && rms_budgeted < rms / 3.0,
        "{rms_budgeted} vs {rms}"
    );
}

#[test]
fn every_face_of_the_cornell_box_at_the_defaults() {
    // Both hierarchical solvers at their defaults: the faces with little light, most of it
    // reflected to them, measured anew by the final gather at the surfaces to a standard error
    // of 1 % of their light, the others the solution's. Measured over seeds 0–3 (worst face,
    // RMS): hierarchical 0.51–0.97 %, 0.22–0.33 % (seed 0: ceiling face 0, blue, −0.51 %);
    // hierarchical shooting 0.81–1.08 %, 0.31–0.40 % (seed 0: tall block face 1, green,
    // −0.94 %; seed 3 over 1 %; its solution's tall block face 1 is far off, which the
    // gather's second pass takes out);
    // progressive refinement on its default mesh worst 0.75 % (the matrix solver the same).
    let world = cornell_per_face();
    let reference = reference();
    for (solver, limit) in [
        (SolverKind::Hierarchical, 0.01),
        (SolverKind::Progressive, 0.01),
        (SolverKind::HierarchicalShooting, 0.01),
    ] {
        let computed = faces(&world, &Method::Radiosity(RadiositySettings::new(solver)));
        let (worst, rms, name) = deviation(&computed, &reference);
        assert!(
            worst < limit && rms < 0.006,
            "{solver:?}: {name}, RMS {rms}"
        );
        // The gathered faces state the error asked for, and it covers what is off: each
        // within three of it and three of the reference's. The dim block faces are among them.
        let mut gathered = Vec::new();
        for (face, (expected, reference_error)) in &reference {
            let (got, error) = computed[face];
            if error == [0.0; 3] {
                continue;
            }
            gathered.push(face.as_str());
            for c in 0..3 {
                assert!(error[c] <= 0.01 * got[c] * 1.0001, "{face} {c}");
                let bound = 3.0 * (error[c] + reference_error[c]);
                assert!(
                    (got[c] - expected[c]).abs() < bound,
                    "{solver:?} {face} {c}"
                );
            }
        }
        for dim in ["short_block#2", "short_block#3", "tall_block#1"] {
            assert!(gathered.contains(&dim), "{solver:?}: {dim} in {gathered:?}");
        }
    }
}

#[test]
fn the_gather_measures_again_over_the_solution_its_first_pass_corrects() {
    // Hierarchical shooting has the tall block's face toward the red wall 13 % high (green
    // and blue); that face sees itself over the floor, and gathered once over the solution it
    // came out +0.8 … +1.4 %. The first pass finds it off, the second reads the first's value.
    let world = cornell_per_face();
    let method = Method::Radiosity(RadiositySettings::new(SolverKind::HierarchicalShooting));
    let outcome = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
    let report = Report::new("cornell", outcome.measurement.as_ref().unwrap());
    let json = serde_json::to_value(&report).unwrap();
    assert_eq!(json["stats"]["surface_gather_corrected"], true);
    let (expected, reference_error) = reference()["tall_block#1"];
    let face = report
        .objects
        .iter()
        .find(|o| o.name == "tall_block" && o.face == Some(1))
        .unwrap();
    let error = face.incident_power_standard_error.unwrap().to_array();
    for (c, got) in face.incident_power.to_array().into_iter().enumerate() {
        let off = (got - expected[c]) / expected[c];
        assert!(off.abs() < 0.01, "channel {c}: {off}");
        assert!((got - expected[c]).abs() < 3.0 * (error[c] + reference_error[c]));
    }
}

#[test]
fn the_final_gather_at_every_surface_holds_each_to_its_stated_error() {
    // Every face gathered (`below_share` 1) to 0.5 %. Measured (seed 0): worst +0.46 % (tall
    // block face 3), RMS 0.25 %, 2.6·10⁶ points; over 8 seeds each face's spread 0.25–0.84
    // of the stated error.
    let world = cornell_per_face();
    let reference = reference();
    let mut settings = RadiositySettings::new(SolverKind::Hierarchical);
    settings.surface_gather = SurfaceGather {
        error: 0.005,
        below_share: 1.0,
    };
    let computed = faces(&world, &Method::Radiosity(settings));
    let (worst, rms, name) = deviation(&computed, &reference);
    assert!(worst < 0.01 && rms < 0.004, "{name}, RMS {rms}");
    for (face, (expected, reference_error)) in &reference {
        let (got, error) = computed[face];
        for c in 0..3 {
            assert!(
                error[c] > 0.0 && error[c] <= 0.005 * got[c] * 1.0001,
                "{face} {c}"
            );
            let bound = 3.0 * (error[c] + reference_error[c]);
            assert!((got[c] - expected[c]).abs() < bound, "{face} {c}");
        }
    }
}

#[test]
fn the_final_gather_at_the_surfaces_does_not_depend_on_the_thread_count() {
    let world = cornell_per_face();
    let mut settings = RadiositySettings::new(SolverKind::Hierarchical);
    settings.surface_gather.error = 0.02;
    let method = Method::Radiosity(settings);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| faces(&world, &method))
    };
    assert_eq!(run(1), run(3));
}

#[test]
fn a_final_gather_cancelled_leaves_the_solution_s_values_and_says_so() {
    /// Asks to stop as soon as the gathering starts.
    struct StopAtGathering<'c>(&'c Cancel);
    impl strahl::progress::ProgressListener for StopAtGathering<'_> {
        fn phase(&self, name: &str) {
            if name == "gathering" {
                self.0.request();
            }
        }
        fn start(&self, _: u64) {}
        fn advance(&self, _: u64) {}
        fn finish(&self) {}
    }
    let world = cornell_per_face();
    let settings = RadiositySettings::new(SolverKind::Hierarchical);
    let cancel = Cancel::new();
    let method = Method::Radiosity(settings);
    let outcome = run(&world, &method, &StopAtGathering(&cancel), &cancel).unwrap();
    assert!(!outcome.complete);
    let measurement = outcome.measurement.unwrap();
    assert_eq!(measurement.stats.extra["surface_gather_interrupted"], true);
    let solution = outcome.radiosity.unwrap().measurement();
    let report = |m| Report::new("cornell", m).objects;
    assert_eq!(report(&measurement), report(&solution));
}

#[test]
fn the_image_methods_refuse_a_final_gather_at_the_surfaces() {
    // They make no report for it to measure: the setting would be ignored. Their defaults
    // take it off.
    assert!(
        Method::RadiosityImage(RadiosityImageSettings::default())
            .check()
            .is_ok()
    );
    assert!(
        Method::FinalGather(FinalGatherSettings::default())
            .check()
            .is_ok()
    );
    let radiosity = RadiositySettings::new(SolverKind::Hierarchical);
    assert!(radiosity.surface_gather.is_on());
    for method in [
        Method::RadiosityImage(RadiosityImageSettings {
            radiosity,
            ..RadiosityImageSettings::default()
        }),
        Method::FinalGather(FinalGatherSettings {
            radiosity,
            ..FinalGatherSettings::default()
        }),
    ] {
        let err = method.check().unwrap_err().to_string();
        assert!(err.contains("surface-gather"), "{err}");
    }
    assert!(Method::Radiosity(radiosity).check().is_ok());
}

/// The recording agrees with the light model as it is now: 4·10⁶ photons within four
/// combined standard errors on every face.
#[test]
fn the_recorded_reference_is_the_light_model_of_this_code() {
    let world = cornell_per_face();
    let reference = reference();
    let live = faces(
        &world,
        &Method::LightTrace(LightTraceSettings {
            photons: 4_000_000,
            ..LightTraceSettings::default()
        }),
    );
    assert_eq!(live.len(), reference.len());
    for (face, (expected, expected_error)) in &reference {
        let (got, error) = live[face];
        for c in 0..3 {
            let sigma = (error[c] * error[c] + expected_error[c] * expected_error[c]).sqrt();
            assert!(
                sigma > 0.0 && (got[c] - expected[c]).abs() < 4.0 * sigma,
                "{face} channel {c}: {} vs {} ± {sigma}",
                got[c],
                expected[c]
            );
        }
    }
}

/// `validate`'s `meters` case: CIE 171 case 5.7's lit wall past a black box, read by black
/// one-sided 2 × 2 cm patches on the ground at 6, 8 and 12 m.
fn meters() -> strahl::validate::Case {
    strahl::validate::cases::all(true)
        .into_iter()
        .find(|c| c.name == "meters")
        .unwrap()
}

/// The report of `scene` solved by radiosity with `settings`.
fn solved(scene: strahl::scene::Scene, settings: RadiositySettings) -> Report {
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let method = Method::Radiosity(settings);
    let outcome = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
    Report::new("meters", outcome.measurement.as_ref().unwrap())
}

/// The `meters` case solved by hierarchical radiosity
/// by `solver` with clustering on or off: each patch's relative deviation from its closed
/// form.
fn meter_errors(solver: SolverKind, clustering: bool) -> Vec<f64> {
    let case = meters();
    let mut settings = RadiositySettings::new(solver);
    settings.hierarchical.clustering = clustering;
    let report = solved(case.scene, settings);
    case.checks
        .iter()
        .map(|check| {
            let Quantity::Surface(k) = check.quantity else {
                panic!("{}: not a surface", check.label)
            };
            let lux = LUMINOUS_EFFICACY * report.objects[k].incident_power[1]
                / report.objects[k].area.unwrap();
            lux / check.expected - 1.0
        })
        .collect()
}

#[test]
fn small_measuring_patches_read_their_closed_form_at_the_defaults() {
    // The patches hold about 10⁻⁷ of the scene's power each, far below the scene-wide error,
    // and light reaches them past the box only through a narrow gap: as measuring patches
    // (black, passing nothing) they are held to 1 % of their own light whatever
    // `--surface-error` says. Measured: +0.02 %, +0.23 %, +0.17 % (before that rule all three
    // read nothing); without clustering −0.34 %, +0.13 %, +0.49 % (before: −42 %, −5 %,
    // +24 %). Hierarchical shooting holds each shot's light onto a patch to 1 % of what the
    // patch has received or that shot brings it: +0.17 %, +0.13 %, +0.49 % (before: −42 %,
    // −5 %, +24 %); it keeps no direct part, so its patches are then measured anew by the
    // final gather at the surfaces: +0.09 %, −0.04 %, +0.01 %. (Hierarchical radiosity's
    // patches take their light straight from the emitting wall: not gathered.) The closed form at the centre differs from the patch's mean by well
    // under 0.1 %.
    for (solver, clustering) in [
        (SolverKind::Hierarchical, true),
        (SolverKind::Hierarchical, false),
        (SolverKind::HierarchicalShooting, true),
    ] {
        let errors = meter_errors(solver, clustering);
        assert!(
            errors.iter().all(|e| e.abs() < 0.01),
            "{solver:?}, clustering {clustering}: {errors:?}"
        );
    }
}

#[test]
fn the_gather_leaves_surfaces_under_the_contract_s_floor_but_not_measuring_patches() {
    // `meters` by hierarchical shooting, which keeps no direct part apart: every surface
    // under 2 % of the light is a candidate. Its three patches hold about 10⁻⁷ of the light
    // each: black, they are measuring patches and gathered; grey, they are ordinary surfaces
    // under `LEAST_SHARE` (10⁻⁴) and keep the solution's values, as a field's 160,000 leaves
    // do (before the floor they were gathered: 25 minutes on the Helios field).
    let case = meters();
    let patches: Vec<usize> = case
        .checks
        .iter()
        .map(|check| match check.quantity {
            Quantity::Surface(k) => k,
            _ => panic!("{}: not a surface", check.label),
        })
        .collect();
    let gathered = |scene| {
        let report = solved(
            scene,
            RadiositySettings::new(SolverKind::HierarchicalShooting),
        );
        let count = report.stats.extra["surface_gather_surfaces"]
            .as_u64()
            .unwrap();
        let stated: Vec<bool> = patches
            .iter()
            .map(|&k| report.objects[k].incident_power_standard_error.is_some())
            .collect();
        (count, stated)
    };
    let (black, black_stated) = gathered(case.scene.clone());
    assert_eq!(black_stated, [true; 3]);
    let mut grey = case.scene;
    let material = grey.add_material(strahl::scene::Material::diffuse(
        "grey",
        strahl::color::Rgb::splat(0.5),
    ));
    for &k in &patches {
        grey.objects[k].material = material;
    }
    let (without, grey_stated) = gathered(grey);
    assert_eq!(grey_stated, [false; 3]);
    assert_eq!(black - without, 3, "{black} gathered black, {without} grey");
}

/// Per leaf: absorbed power, W per channel, and the reference's relative standard error.
type Leaves = HashMap<String, ([f64; 3], [f64; 3])>;

/// The recorded light model of `canopy:300` at 10⁹ photons (three standard errors 0.27–0.42 %
/// per leaf).
fn canopy_reference() -> Leaves {
    recorded("canopy300_per_leaf_light_model.json", "leaves")
        .iter()
        .map(|leaf| {
            let incident = triple(&leaf["incident_power"]);
            let error = triple(&leaf["incident_power_standard_error"]);
            let relative = std::array::from_fn(|c| error[c] / incident[c]);
            let name = leaf["name"].as_str().unwrap().to_string();
            (name, (triple(&leaf["absorbed_power"]), relative))
        })
        .collect()
}

#[test]
fn every_leaf_of_the_canopy_absorbs_what_the_light_model_says() {
    // canopy:300 (translucent leaves under sky and sun) at the defaults of both hierarchical
    // solvers, leaf by leaf against the recording: each leaf within 1 % plus three of the
    // reference's standard errors, the RMS over leaves and channels under 0.5 %. Measured:
    // hierarchical radiosity worst −1.06 % (leaf 12-5, green; its reference's 3σ 0.27 %), RMS
    // 0.25 %, the sun's light links exact (+1.13 % on leaf 8-10 when they were measured at
    // points) — the leaves' light from each other over cluster links, within 0.98 % without
    // clustering; no leaf is gathered (1–16 % of their light is indirect). Hierarchical
    // shooting, every leaf gathered (it keeps no direct part): worst −1.20 % (leaf 13-17,
    // green), RMS 0.30 %; its solution alone was worst +0.98 %, RMS 0.24 %. Before the light links
    // looked for shadows at the leaves' edges, two leaves a sliver in another's shadow read
    // +1.56 % and +1.43 %.
    let reference = canopy_reference();
    let world = Arc::new(
        World::new(
            builtin::load("canopy:300").unwrap().unwrap(),
            AccelKind::Bvh,
        )
        .unwrap(),
    );
    for solver in [SolverKind::Hierarchical, SolverKind::HierarchicalShooting] {
        let method = Method::Radiosity(RadiositySettings::new(solver));
        let outcome = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
        let report = Report::new("canopy", outcome.measurement.as_ref().unwrap());
        let (mut squares, mut count) = (0.0, 0);
        for leaf in &report.objects {
            let (expected, sigma) = reference[&leaf.name];
            for c in 0..3 {
                let e = leaf.absorbed_power.to_array()[c] / expected[c] - 1.0;
                assert!(
                    e.abs() < 0.01 + 3.0 * sigma[c],
                    "{solver:?} {} channel {c}: {:+.2} %",
                    leaf.name,
                    100.0 * e
                );
                squares += e * e;
                count += 1;
            }
        }
        let rms = (squares / f64::from(count)).sqrt();
        assert!(rms < 0.005, "{solver:?}: RMS {rms}");
    }
}

#[test]
fn the_gather_at_the_surfaces_counts_the_light_of_glossy_lobes_as_absorbed_as_the_solution_does() {
    // Radiosity reflects diffusely only and counts the rest as absorbed. The final gather at
    // the dim faces traces rays: it must count it so too, or its first hits add the glossy
    // surfaces' highlights to a solution that has none (RenderPark's corridor scene, with
    // glossy floor and walls: +12 … +21 % on every gathered object against the light model on
    // the same scene made diffuse). So a glossy box reports what its diffuse part alone does.
    let glossy = {
        let mut scene = builtin::load("cornell").unwrap().unwrap();
        for object in &mut scene.objects {
            object.per_face = true;
        }
        let white = scene.material_id("white").unwrap() as usize;
        scene.materials[white].specular = strahl::color::Rgb::splat(0.2);
        scene.materials[white].shininess = 20.0;
        scene
    };
    let mut diffuse = glossy.clone();
    diffuse.keep_diffuse_lobes();
    let world = |scene| Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let method = Method::Radiosity(RadiositySettings::new(SolverKind::Hierarchical));
    let (glossy, diffuse) = (
        faces(&world(glossy), &method),
        faces(&world(diffuse), &method),
    );
    assert_eq!(glossy, diffuse);
}

#[test]
fn a_small_surface_lit_straight_by_an_emitting_surface_is_gathered() {
    // Light from emitting surfaces comes over links held to the scene-wide threshold like
    // reflected light (RenderPark's louvred luminaire: its vanes, lit straight by the tube
    // lamps, −6.8 … +3.6 % in the solution), not over the light links of point lights and
    // the sky, measured on grids of points. A 10 cm tile beside a 4 m² floor under a square
    // lamp, all of the tile's light straight from the lamp, is measured anew and says how
    // well; the floor, with most of the light, keeps the solution's value.
    use strahl::color::Rgb;
    use strahl::scene::{Material, Scene, Shape};
    let mut scene = Scene::empty("tile");
    let grey = scene.add_material(Material::diffuse("grey", Rgb::splat(0.5)));
    let lamp = scene.add_material(Material {
        emission: Rgb::splat(1.0),
        ..Material::diffuse("lamp", Rgb::BLACK)
    });
    let square = |origin: [f32; 3], side: f32, down: bool| {
        let (u, v) = (glam::Vec3::X * side, glam::Vec3::Z * side);
        let (edge_u, edge_v) = if down { (u, v) } else { (v, u) };
        Shape::Parallelogram {
            origin: origin.into(),
            edge_u,
            edge_v,
        }
    };
    scene.add_object("floor", square([-2.0, 0.0, -1.0], 2.0, false), grey);
    scene.add_object("tile", square([0.5, 0.0, 0.5], 0.1, false), grey);
    scene.add_object("lamp", square([-0.5, 1.0, -0.5], 1.0, true), lamp);
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let method = Method::Radiosity(RadiositySettings::new(SolverKind::Hierarchical));
    let outcome = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
    let report = Report::new("tile", outcome.measurement.as_ref().unwrap());
    let object = |name: &str| report.objects.iter().find(|o| o.name == name).unwrap();
    let (tile, floor) = (object("tile"), object("floor"));
    assert!(tile.incident_power.g < 0.02 * floor.incident_power.g);
    assert!(tile.direct_power.unwrap().g > 0.99 * tile.incident_power.g);
    assert!(floor.incident_power_standard_error.is_none());
    // Against the closed form: the form factor from a point to a parallel rectangle 1 m
    // above (by its corners, each term odd in both extents), irradiance π·L·F, averaged
    // over the tile on a 40 × 40 grid.
    let corner = |a: f64, b: f64| {
        let (sa, sb) = ((1.0 + a * a).sqrt(), (1.0 + b * b).sqrt());
        (a / sa * (b / sa).atan() + b / sb * (a / sb).atan()) / (2.0 * std::f64::consts::PI)
    };
    let n = 40;
    let mut exact = 0.0;
    for i in 0..n {
        for j in 0..n {
            let (x, z) = (
                0.5 + 0.1 * (i as f64 + 0.5) / n as f64,
                0.5 + 0.1 * (j as f64 + 0.5) / n as f64,
            );
            let f =
                corner(0.5 - x, 0.5 - z) - corner(-0.5 - x, 0.5 - z) - corner(0.5 - x, -0.5 - z)
                    + corner(-0.5 - x, -0.5 - z);
            exact += std::f64::consts::PI * f * 0.01 / (n * n) as f64;
        }
    }
    let error = tile.incident_power_standard_error.unwrap().g;
    let off = tile.incident_power.g - exact;
    assert!(
        off.abs() < 3.0 * error && error < 0.01 * exact,
        "{} ± {error} vs {exact}",
        tile.incident_power.g
    );
}
