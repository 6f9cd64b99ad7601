//! The standard ray tracer's direct light against closed forms: point, spot, directional,
//! sky and a rectangular area light over a Lambertian plane; and shadows on/off.

use glam::Vec3;
use std::f32::consts::PI;
use strahl::accel::AccelKind;
use strahl::color::Rgb;
use strahl::progress::Cancel;
use strahl::progress::NoProgress;
use strahl::scene::{Camera, Light, LightKind, Material, Scene, Shape};
use strahl::trace::AntialiasMode;
use strahl::trace::ShadowMode;
use strahl::trace::StandardRayTracer;
use strahl::trace::{RenderSettings, render};
use strahl::world::World;

const RHO: f32 = 0.5;

/// A large Lambertian floor (y = 0) seen straight from above by a narrow camera.
fn floor_scene() -> Scene {
    let mut s = Scene::empty("floor");
    let m = s.add_material(Material::diffuse("floor", Rgb::splat(RHO)));
    s.add_object(
        "floor",
        Shape::Parallelogram {
            origin: Vec3::new(-50.0, 0.0, 50.0),
            edge_u: Vec3::new(100.0, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 0.0, -100.0),
        },
        m,
    );
    s.camera = Camera {
        position: Vec3::new(0.0, 1.0, 0.0),
        look_at: Vec3::ZERO,
        up: Vec3::Z,
        fov_degrees: 1.0,
        width: 1,
        height: 1,
    };
    s
}

/// Radiance of the single pixel looking at the floor's origin.
fn centre_radiance(scene: Scene, light_samples: u32, shadows: ShadowMode) -> Rgb {
    let world = World::new(scene, AccelKind::Bvh).unwrap();
    let tracer = StandardRayTracer {
        max_depth: 0,
        light_samples,
        shadows,
    };
    let settings = RenderSettings {
        width: 1,
        height: 1,
        antialias: AntialiasMode::None,
        ..Default::default()
    };
    let out = render(&world, &tracer, &settings, &NoProgress, &Cancel::new()).unwrap();
    out.film.get(0, 0)
}

fn light(kind: LightKind) -> Light {
    Light { name: None, kind }
}

fn assert_rel(got: f32, want: f32, tol: f32, what: &str) {
    assert!((got / want - 1.0).abs() < tol, "{what}: {got} vs {want}");
}

#[test]
fn point_spot_and_directional_lights_follow_the_cosine_law() {
    // Point light of 10 W/sr at height 2, offset 1.5: E = I cosθ / d² with d = 2.5, cosθ = 0.8.
    let mut s = floor_scene();
    s.lights.push(light(LightKind::Point {
        position: Vec3::new(1.5, 2.0, 0.0),
        intensity: Rgb::splat(10.0),
    }));
    let e = 10.0 * 0.8 / 6.25;
    assert_rel(
        centre_radiance(s, 1, ShadowMode::On).g,
        RHO / PI * e,
        1e-4,
        "point",
    );

    // A spot aimed at the point is the same inside its inner cone, dark outside its outer cone.
    let mut s = floor_scene();
    let pos = Vec3::new(1.5, 2.0, 0.0);
    s.lights.push(light(LightKind::Spot {
        position: pos,
        direction: (-pos).normalize(),
        intensity: Rgb::splat(10.0),
        inner_degrees: 10.0,
        outer_degrees: 20.0,
    }));
    assert_rel(
        centre_radiance(s, 1, ShadowMode::On).g,
        RHO / PI * e,
        1e-4,
        "spot",
    );
    let mut s = floor_scene();
    s.lights.push(light(LightKind::Spot {
        position: pos,
        direction: -Vec3::Y,
        intensity: Rgb::splat(10.0),
        inner_degrees: 10.0,
        outer_degrees: 20.0,
    }));
    assert_eq!(
        centre_radiance(s, 1, ShadowMode::On),
        Rgb::BLACK,
        "outside the spot cone"
    );

    // Directional light of 3 W/m² arriving at 60° from the normal: E = 3 cos 60°.
    let mut s = floor_scene();
    let a = 60f32.to_radians();
    s.lights.push(light(LightKind::Directional {
        direction: Vec3::new(a.sin(), -a.cos(), 0.0),
        irradiance: Rgb::splat(3.0),
    }));
    assert_rel(
        centre_radiance(s, 1, ShadowMode::On).g,
        RHO / PI * 1.5,
        1e-4,
        "directional",
    );
}

#[test]
fn open_sky_gives_rho_times_l() {
    // Unoccluded uniform sky L: E = πL, so the reflected radiance is ρ·L (exact for cosine
    // sampling of a Lambertian surface).
    let mut s = floor_scene();
    s.lights.push(light(LightKind::Sky {
        radiance: Rgb::splat(2.0),
    }));
    assert_rel(
        centre_radiance(s, 16, ShadowMode::On).g,
        RHO * 2.0,
        1e-4,
        "sky",
    );
}

#[test]
fn rectangular_area_light_matches_the_analytic_form_factor() {
    // Emitter 0.6 × 0.4 facing down at height h = 0.5, centred above the point.
    // F(dA → rect) = (2/π)[a/√(1+a²)·atan(b/√(1+a²)) + b/√(1+b²)·atan(a/√(1+b²))],
    // a, b = half sides / h; E = π·L·F.
    let (w, d, h, l) = (0.6f32, 0.4f32, 0.5f32, 5.0f32);
    let mut s = floor_scene();
    let m = s.add_material(Material::emitter("lamp", Rgb::splat(0.0), Rgb::splat(l)));
    s.add_object(
        "lamp",
        Shape::Parallelogram {
            origin: Vec3::new(-w / 2.0, h, -d / 2.0),
            edge_u: Vec3::new(w, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 0.0, d),
        },
        m,
    );
    // The camera sits between floor and lamp (the lamp's front face points down).
    s.camera.position = Vec3::new(0.0, 0.2, 0.0);
    let (a, b) = (w / 2.0 / h, d / 2.0 / h);
    let f = 2.0 / PI
        * (a / (1.0 + a * a).sqrt() * (b / (1.0 + a * a).sqrt()).atan()
            + b / (1.0 + b * b).sqrt() * (a / (1.0 + b * b).sqrt()).atan());
    let expected = RHO / PI * PI * l * f;
    // 4096 stratified samples: the error of the estimate is far below 0.5 %.
    let got = centre_radiance(s, 4096, ShadowMode::On).g;
    assert_rel(got, expected, 5e-3, "area light");
}

#[test]
fn shadows_off_ignores_occluders_but_not_facing() {
    let mut s = floor_scene();
    s.lights.push(light(LightKind::Point {
        position: Vec3::new(0.0, 2.0, 0.0),
        intensity: Rgb::splat(4.0),
    }));
    let m = s.material_id("floor").unwrap();
    s.add_object(
        "blocker",
        Shape::Sphere {
            center: Vec3::new(0.0, 1.0, 0.0),
            radius: 0.2,
        },
        m,
    );
    s.camera.position = Vec3::new(0.0, 0.5, 0.01);
    assert_eq!(centre_radiance(s.clone(), 1, ShadowMode::On), Rgb::BLACK);
    let lit = centre_radiance(s.clone(), 1, ShadowMode::Off).g;
    assert_rel(lit, RHO / PI * 4.0 / 4.0, 1e-3, "shadows off");
    // A light below the floor stays dark even with shadows off (self-shadowing by facing).
    // The camera looks at the top side; the light is under it.
    let mut below = floor_scene();
    below.lights.push(light(LightKind::Point {
        position: Vec3::new(0.0, -2.0, 0.0),
        intensity: Rgb::splat(4.0),
    }));
    assert_eq!(centre_radiance(below, 1, ShadowMode::Off), Rgb::BLACK);
}
