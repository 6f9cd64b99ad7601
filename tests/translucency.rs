//! Diffuse transmission (translucency) in every method, against closed forms: a large
//! horizontal sheet of reflectance ρ = 0.3 and translucency τ = 0.5, alone under a sun of
//! irradiance E = 100 W·m⁻² straight from above. Its top sends out the radiance `ρ·E/π`, its
//! underside `τ·E/π`, and it absorbs `(1 − ρ − τ)·E` per unit area. The sensor cases (the
//! sheet over a black floor, read below and above) are `strahl validate`'s
//! `translucent-sheet`.

use glam::Vec3;
use std::sync::Arc;
use strahl::color::Rgb;
use strahl::method::{
    AccelKind, Cancel, Choice, FinalGatherSettings, ImageSize, LightTraceSettings, Method,
    NoProgress, Outcome, PathTraceSettings, RadiositySettings, RayTraceSettings, SolverKind, World,
    run,
};
use strahl::report::Report;
use strahl::scene::{Light, LightKind, Material, Scene, Shape};

const RHO: f32 = 0.3;
const TAU: f32 = 0.5;
const SUN: f32 = 100.0;
/// The sheet is 20 m × 20 m.
const SIDE: f32 = 20.0;

/// The sheet under the sun, with the camera 1 m below it looking up (or above it looking
/// down): every camera ray meets the sheet.
fn sheet(camera_below: bool) -> Arc<World> {
    let mut scene = Scene::empty("sheet");
    let m = scene.add_material(Material {
        translucency: Rgb::splat(TAU),
        ..Material::diffuse("leaf", Rgb::splat(RHO))
    });
    scene.add_object(
        "sheet",
        Shape::Parallelogram {
            origin: Vec3::new(-SIDE / 2.0, 0.0, SIDE / 2.0),
            edge_u: Vec3::X * SIDE,
            edge_v: Vec3::NEG_Z * SIDE,
        },
        m,
    );
    scene.lights.push(Light {
        name: None,
        kind: LightKind::Directional {
            direction: -Vec3::Y,
            irradiance: Rgb::splat(SUN),
        },
    });
    let y = if camera_below { -1.0 } else { 1.0 };
    scene.camera.position = Vec3::new(0.0, y, 0.0);
    scene.camera.look_at = Vec3::new(0.2, 0.0, 0.0);
    scene.camera.up = Vec3::Z;
    scene.camera.fov_degrees = 30.0;
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

fn outcome(world: &Arc<World>, method: &Method) -> Outcome {
    run(world, method, &NoProgress, &Cancel::new()).unwrap()
}

const SIZE: ImageSize = ImageSize {
    width: Some(16),
    height: Some(12),
};

/// Every pixel of the method's image, which must all be `expected` (W·sr⁻¹·m⁻²) within the
/// relative `tolerance`.
fn assert_image(world: &Arc<World>, method: &Method, expected: f32, tolerance: f32) {
    let image = outcome(world, method).image.unwrap();
    for (k, p) in image.pixels().iter().enumerate() {
        for c in 0..3 {
            let error = (p[c] - expected).abs() / expected;
            assert!(
                error <= tolerance,
                "{:?} pixel {k}: {} vs {expected}",
                method.kind(),
                p[c]
            );
        }
    }
}

/// The ray tracer, the path tracer and final gather show the underside at `τ·E/π` and the
/// top at `ρ·E/π` (exact: one surface, one sun, no shadows, nothing else to reflect).
#[test]
fn images_show_the_light_passed_through_and_reflected() {
    let ray_trace = Method::RayTrace(RayTraceSettings {
        size: SIZE,
        ..RayTraceSettings::default()
    });
    let path_trace = Method::PathTrace(PathTraceSettings {
        size: SIZE,
        samples_per_pixel: 4,
        ..PathTraceSettings::default()
    });
    let final_gather = Method::FinalGather(FinalGatherSettings {
        size: SIZE,
        gather_rays: 4,
        ..FinalGatherSettings::default()
    });
    for (below, weight) in [(true, TAU), (false, RHO)] {
        let world = sheet(below);
        let expected = weight * SUN / std::f32::consts::PI;
        for method in [&ray_trace, &path_trace, &final_gather] {
            assert_image(&world, method, expected, 1e-5);
        }
    }
}

/// The report of a method on `world`.
fn report(world: &Arc<World>, method: &Method) -> Report {
    Report::new(
        "sheet",
        outcome(world, method).measurement.as_ref().unwrap(),
    )
}

/// Every radiosity solver absorbs `(1 − ρ − τ)·E·A` and scatters `(ρ + τ)·E·A` exactly; the
/// light model within three standard errors.
#[test]
fn the_sheet_absorbs_what_it_neither_reflects_nor_passes_on() {
    let world = sheet(true);
    let incident = f64::from(SUN * SIDE * SIDE);
    let absorbed = incident * f64::from(1.0 - RHO - TAU);
    let scattered = incident * f64::from(RHO + TAU);
    for &(solver, _, _) in SolverKind::VALUES {
        let method = Method::Radiosity(RadiositySettings::new(solver));
        let report = report(&world, &method);
        let (a, s) = (
            report.objects[0].absorbed_power[1],
            report.objects[0].reflected_power[1],
        );
        assert!(
            (a - absorbed).abs() < 1e-9 * incident,
            "{solver:?}: {a} vs {absorbed}"
        );
        assert!(
            (s - scattered).abs() < 1e-9 * incident,
            "{solver:?}: {s} vs {scattered}"
        );
    }
    // The light model absorbs each photon that reaches the sheet with probability
    // 1 − ρ − τ: a binomial share of the photons that arrive.
    let photons = 200_000;
    let report = report(
        &world,
        &Method::LightTrace(LightTraceSettings {
            photons,
            ..LightTraceSettings::default()
        }),
    );
    let sheet = &report.objects[0];
    let arrived = photons as f64 * sheet.incident_power[1] / report.totals.emitted_power[1];
    let p = f64::from(1.0 - RHO - TAU);
    let sigma = (p * (1.0 - p) / arrived).sqrt();
    let share = sheet.absorbed_power[1] / sheet.incident_power[1];
    assert!((share - p).abs() < 4.0 * sigma, "{share} vs {p} ± {sigma}");
    let incident_error = sheet.incident_power_standard_error.unwrap()[1];
    assert!(
        (sheet.incident_power[1] - incident).abs() < 4.0 * incident_error,
        "{} vs {incident} ± {incident_error}",
        sheet.incident_power[1]
    );
}

/// A material built in code whose reflectance and translucency add up to more than 1 would
/// create light in every method: the world refuses it, naming it (scene files refuse it
/// with the file's place, `cli/tests/malformed_files.rs`).
#[test]
fn a_material_that_passes_on_more_than_it_receives_is_refused() {
    let mut scene = Scene::empty("bright");
    let m = scene.add_material(Material {
        translucency: Rgb::splat(0.5),
        ..Material::diffuse("glowing leaf", Rgb::splat(0.8))
    });
    scene.add_object(
        "sheet",
        Shape::Parallelogram {
            origin: Vec3::ZERO,
            edge_u: Vec3::X,
            edge_v: Vec3::NEG_Z,
        },
        m,
    );
    let error = World::new(scene, AccelKind::Bvh).err().unwrap().to_string();
    assert!(
        error.contains("glowing leaf") && error.contains("1.3"),
        "{error}"
    );
}
