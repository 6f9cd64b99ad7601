//! Per-surface accuracy of hierarchical radiosity: the built-in Cornell box with every face of
//! every object reported on its own, against the light model at 2·10⁸ photons (recorded in
//! `tests/data/cornell_per_face_light_model.json`, its three standard errors 0.2–0.6 % on the
//! dim block faces). At the default settings the dim block faces are 9–12 % too bright;
//! `surface_error` (importance-driven budgets per reported surface) brings them to the
//! reference. A live light-model run checks that the recording still describes the code.
//! And measuring patches: small black quads reading the light of CIE 171's lit wall past an
//! occluder (case 5.7), against the closed form.

use glam::Vec3;
use serde_json::Value;
use std::collections::HashMap;
use std::sync::Arc;
use strahl::color::Rgb;
use strahl::light_model::LightTraceSettings;
use strahl::method::{
    AccelKind, Cancel, Method, NoProgress, RadiositySettings, SolverKind, World, run,
};
use strahl::report::Report;
use strahl::scene::{Material, Shape, builtin};
use strahl::validate::closed_forms::perpendicular_rectangle;

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

/// The recorded reference.
fn reference() -> Faces {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data/cornell_per_face_light_model.json"),
    )
    .unwrap();
    let json: Value = serde_json::from_str(&text).unwrap();
    json["faces"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| {
            let name = format!("{}#{}", f["object"].as_str().unwrap(), f["face"]);
            let incident = triple(&f["incident_power"]);
            let error = triple(&f["incident_power_standard_error"]);
            (name, (incident, error))
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
        Method::Radiosity(settings)
    };
    // The defaults: whole objects within 1.3 % (tests/radiosity_vs_light_model.rs), single
    // faces up to 12 % off.
    let (worst, rms, name) = deviation(&faces(&world, &hierarchical(0.0)), &reference);
    assert!(
        worst > 0.08,
        "the defaults are better than recorded: {name}"
    );
    // With per-surface budgets every face is within 3 % and most within 1 % (measured:
    // largest 2.8 %, tall block face 1 green; RMS 0.84 %).
    let (worst, rms_budgeted, name) = deviation(&faces(&world, &hierarchical(0.003)), &reference);
    assert!(worst < 0.03, "{name}");
    assert!(
        rms_budgeted < 0.01 && rms_budgeted < rms / 4.0,
        "{rms_budgeted} vs {rms}"
    );
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

/// Distances from the lit wall of the measuring patches that see part of it past the box.
const METERS: [f64; 3] = [6.0, 8.0, 12.0];

/// Height of the measuring patches above the ground plane, m.
const METER_HEIGHT: f64 = 0.001;

/// Half the side of a measuring patch, m (2 × 2 cm).
const METER_HALF: f32 = 0.01;

/// `validate`'s occluder case (a 2 × 2 m wall of luminance 1000 cd/m² at x = 0 facing +x, a
/// black box 1 m high from x = 1.5 to 2.5 m) with black one-sided 2 × 2 cm patches facing up,
/// 1 mm above the ground, centred at the distances [`METERS`]; objects 2.. are the patches.
/// Returns the world and the wall's radiance, W·sr⁻¹·m⁻².
fn wall_past_a_box_with_meters() -> (Arc<World>, f64) {
    let case = strahl::validate::cases::all(true)
        .into_iter()
        .find(|c| c.name == "occluder")
        .unwrap();
    let mut scene = case.scene;
    assert_eq!(scene.objects.len(), 2, "the lit wall and the box");
    let radiance = f64::from(
        scene.materials[scene.objects[0].material as usize]
            .emission
            .g,
    );
    let meter = scene.add_material(Material {
        one_sided: true,
        ..Material::diffuse("meter", Rgb::BLACK)
    });
    for x in METERS {
        let h = METER_HALF;
        scene.add_object(
            &format!("meter x={x}"),
            Shape::Parallelogram {
                origin: Vec3::new(x as f32 - h, METER_HEIGHT as f32, h),
                edge_u: Vec3::X * 2.0 * h,
                edge_v: Vec3::NEG_Z * 2.0 * h,
            },
            meter,
        );
    }
    (
        Arc::new(World::new(scene, AccelKind::Bvh).unwrap()),
        radiance,
    )
}

/// The irradiance at the centre of the meter at distance `x`: `π·L·F` of the part of the wall
/// above the box's near top edge as seen from there, W·m⁻².
fn meter_irradiance(x: f64, radiance: f64) -> f64 {
    let (near, top, y) = (2.5, 1.0, METER_HEIGHT);
    let cut = y + (top - y) * x / (x - near);
    std::f64::consts::PI * radiance * perpendicular_rectangle((-1.0, 1.0), (cut - y, 2.0 - y), x)
}

#[test]
fn surface_error_reads_small_measuring_patches_right() {
    let (world, radiance) = wall_past_a_box_with_meters();
    let area = f64::from(4.0 * METER_HALF * METER_HALF);
    let errors = |surface_error: f64| -> Vec<f64> {
        let mut settings = RadiositySettings::new(SolverKind::Hierarchical);
        settings.hierarchical.surface_error = surface_error;
        let outcome = run(
            &world,
            &Method::Radiosity(settings),
            &NoProgress,
            &Cancel::new(),
        )
        .unwrap();
        let report = Report::new("meters", outcome.measurement.as_ref().unwrap());
        METERS
            .iter()
            .enumerate()
            .map(|(k, &x)| {
                let got = report.objects[2 + k].incident_power[1] / area;
                got / meter_irradiance(x, radiance) - 1.0
            })
            .collect()
    };
    // The defaults: the patches' share of the scene's power is far below the scene-wide
    // error, and light reaches them past the box only through a narrow gap (measured: two
    // of them read nothing, the third −53 %).
    let default = errors(0.0);
    assert!(default.iter().any(|e| e.abs() > 0.2), "{default:?}");
    // Held to their own power, every patch reads its closed form within 1 % (measured:
    // +0.1 %, +0.2 %, +0.8 %; the closed form at the centre differs from the patch's mean by
    // well under 0.1 %).
    let budgeted = errors(0.01);
    assert!(budgeted.iter().all(|e| e.abs() < 0.01), "{budgeted:?}");
}
