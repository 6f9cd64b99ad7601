//! Statistical and end-to-end checks of the path tracer. Every test uses fixed seeds, so it is
//! deterministic; tolerances are a stated number of standard errors measured from the
//! per-pixel sample variance of the estimators themselves, and each test also asserts that
//! its tolerance is small compared with the effect it checks, so none passes vacuously.

use glam::Vec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;
use strahl::accel::AccelKind;
use strahl::color::Rgb;
use strahl::progress::{Cancel, NoProgress, ProgressListener};
use strahl::sampling::{Sampler, SequenceKind};
use strahl::scene::{Camera, Light, LightKind, Material, Scene, Shape, builtin};
use strahl::trace::{Integrator, PathTracer, StandardRayTracer};
use strahl::trace::{ProgressiveOutput, ProgressiveSettings, render_progressive};
use strahl::world::World;

/// Per-pixel luminance mean and squared standard error of that mean.
struct PixelStats {
    width: u32,
    mean: Vec<f64>,
    variance_of_mean: Vec<f64>,
}

impl PixelStats {
    /// Mean and squared standard error over the pixels of a rectangle (pixels are independent
    /// streams, so variances of their means add).
    fn region(&self, x0: u32, y0: u32, x1: u32, y1: u32) -> (f64, f64) {
        let mut sum = 0.0;
        let mut var = 0.0;
        let mut n = 0.0;
        for y in y0..y1 {
            for x in x0..x1 {
                let i = (y * self.width + x) as usize;
                sum += self.mean[i];
                var += self.variance_of_mean[i];
                n += 1.0;
            }
        }
        (sum / n, var / (n * n))
    }
}

/// Traces `spp` samples per pixel (pixel position from the first two sampler dimensions, as
/// the progressive renderer does) and measures each pixel's luminance statistics.
fn pixel_stats(
    world: &World,
    integrator: &dyn Integrator,
    width: u32,
    height: u32,
    spp: u32,
    sequence: SequenceKind,
) -> PixelStats {
    let camera = world
        .scene
        .camera
        .with_resolution(width, height)
        .rays()
        .unwrap();
    let per_pixel: Vec<(f64, f64)> = (0..width * height)
        .into_par_iter()
        .map(|i| {
            let (px, py) = (i % width, i / width);
            let mut sum = 0.0f64;
            let mut sum2 = 0.0f64;
            for k in 0..spp {
                let mut sampler = Sampler::new(sequence, 7, i as u64, k);
                let j = sampler.next_2d();
                let ray = camera.ray(px as f32 + j.x, py as f32 + j.y);
                let y = integrator.radiance(world, &ray, &mut sampler).luminance() as f64;
                sum += y;
                sum2 += y * y;
            }
            let n = spp as f64;
            let mean = sum / n;
            let variance = (sum2 / n - mean * mean).max(0.0) * n / (n - 1.0);
            (mean, variance / n)
        })
        .collect();
    PixelStats {
        width,
        mean: per_pixel.iter().map(|p| p.0).collect(),
        variance_of_mean: per_pixel.iter().map(|p| p.1).collect(),
    }
}

fn camera(position: Vec3, look_at: Vec3, fov_degrees: f32) -> Camera {
    Camera {
        position,
        look_at,
        up: Vec3::Y,
        fov_degrees,
        width: 32,
        height: 32,
    }
}

/// White furnace: inside a closed box whose walls all emit radiance `Le` (both sides) and
/// reflect diffusely with ρ = 0.5, the radiance is the same everywhere and direction:
/// L = Le + ρ·L, so L = Le/(1 − ρ) (with the exitance M = π·Le: L = M/(π(1 − ρ))).
#[test]
fn white_furnace_radiance_is_emission_over_one_minus_albedo() {
    let le = 0.8f32;
    let rho = 0.5f32;
    let mut scene = Scene::empty("furnace");
    let wall = scene.add_material(Material {
        two_sided: true,
        ..Material::emitter("wall", Rgb::splat(rho), Rgb::splat(le))
    });
    scene.add_object(
        "box",
        Shape::Box {
            min: Vec3::splat(-1.0),
            max: Vec3::splat(1.0),
        },
        wall,
    );
    scene.camera = camera(Vec3::new(0.2, -0.3, 0.5), Vec3::new(-0.5, 0.4, -1.0), 100.0);
    let world = World::new(scene, AccelKind::Bvh).unwrap();
    let tracer = PathTracer::new(&world, u32::MAX, 1);
    let stats = pixel_stats(&world, &tracer, 8, 8, 1024, SequenceKind::Sobol);
    let expected = (le / (1.0 - rho)) as f64;
    // Every pixel within 5 of its own standard errors (from its 1024 samples; Russian
    // roulette from bounce 5 makes single paths vary by about ±30 %).
    for (i, (&m, &v)) in stats.mean.iter().zip(&stats.variance_of_mean).enumerate() {
        let tolerance = 5.0 * v.sqrt();
        assert!(
            tolerance < 0.06 * expected,
            "pixel {i}: tolerance {tolerance} too loose"
        );
        assert!(
            (m - expected).abs() < tolerance,
            "pixel {i}: {m} vs {expected} ± {tolerance}"
        );
    }
    // The image mean within 4 standard errors of the mean over all pixels.
    let (mean, var) = stats.region(0, 0, 8, 8);
    let tolerance = 4.0 * var.sqrt();
    assert!(tolerance < 0.01 * expected, "image tolerance {tolerance}");
    assert!(
        (mean - expected).abs() < tolerance,
        "image mean {mean} vs {expected} ± {tolerance}"
    );
}

/// A diffuse floor and box lit by a one-sided area light (facing down) and a point light.
fn direct_light_scene() -> Scene {
    let mut scene = Scene::empty("direct");
    let grey = scene.add_material(Material::diffuse("grey", Rgb::new(0.7, 0.6, 0.5)));
    let lamp = scene.add_material(Material::emitter("lamp", Rgb::splat(0.5), Rgb::splat(12.0)));
    scene.add_object(
        "floor",
        Shape::Parallelogram {
            origin: Vec3::new(-2.0, 0.0, 2.0),
            edge_u: Vec3::new(4.0, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 0.0, -4.0),
        },
        grey,
    );
    scene.add_object(
        "block",
        Shape::Box {
            min: Vec3::new(-0.4, 0.0, -0.4),
            max: Vec3::new(0.3, 0.8, 0.2),
        },
        grey,
    );
    // Edges chosen so that edge_u × edge_v points down (−y): the lamp's front faces the floor.
    scene.add_object(
        "lamp",
        Shape::Parallelogram {
            origin: Vec3::new(-0.3, 2.0, -0.3),
            edge_u: Vec3::new(0.6, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 0.0, 0.6),
        },
        lamp,
    );
    scene.lights.push(Light {
        name: Some("point".into()),
        kind: LightKind::Point {
            position: Vec3::new(1.2, 1.5, 0.8),
            intensity: Rgb::splat(2.0),
        },
    });
    scene.camera = camera(Vec3::new(0.5, 2.5, 3.5), Vec3::new(0.0, 0.3, 0.0), 50.0);
    scene
}

/// With one scattering event the path tracer computes exactly the direct light that the
/// standard ray tracer (recursion depth 0) computes; both are compared per 8×8 block within
/// 5 standard errors of the difference, each side's error measured from its own samples.
#[test]
fn path_tracer_agrees_with_standard_tracer_on_direct_light() {
    let world = World::new(direct_light_scene(), AccelKind::Bvh).unwrap();
    let path = PathTracer::new(&world, 1, 1);
    let standard = StandardRayTracer {
        max_depth: 0,
        light_samples: 4,
        ..Default::default()
    };
    let (w, h) = (32, 32);
    let a = pixel_stats(&world, &path, w, h, 256, SequenceKind::Sobol);
    let b = pixel_stats(&world, &standard, w, h, 128, SequenceKind::Random);
    let (image_mean, _) = a.region(0, 0, w, h);
    assert!(
        image_mean > 0.05,
        "the test scene is too dark: {image_mean}"
    );
    for by in 0..h / 8 {
        for bx in 0..w / 8 {
            let (x0, y0) = (bx * 8, by * 8);
            let (ma, va) = a.region(x0, y0, x0 + 8, y0 + 8);
            let (mb, vb) = b.region(x0, y0, x0 + 8, y0 + 8);
            let tolerance = 5.0 * (va + vb).sqrt();
            assert!(
                tolerance < 0.1 * image_mean,
                "block ({bx}, {by}): tolerance {tolerance} too loose"
            );
            assert!(
                (ma - mb).abs() <= tolerance,
                "block ({bx}, {by}): path {ma} vs standard {mb} ± {tolerance}"
            );
        }
    }
}

fn render(world: &World, tracer: &PathTracer, settings: &ProgressiveSettings) -> ProgressiveOutput {
    render_progressive(world, tracer, settings, &NoProgress, &Cancel::new()).unwrap()
}

/// The neon scene has no light source but its emissive sign: the room must be lit by it.
#[test]
fn neon_room_is_lit_by_its_sign() {
    let world = World::new(builtin::load("neon").unwrap().unwrap(), AccelKind::Bvh).unwrap();
    assert!(world.lights.delta.is_empty() && world.lights.sky.is_none());
    let tracer = PathTracer::new(&world, u32::MAX, 1);
    let settings = ProgressiveSettings {
        width: 40,
        height: 30,
        samples_per_pixel: 16,
        seed: 3,
        time_limit: None,
    };
    let out = render(&world, &tracer, &settings);
    let lit = out
        .film
        .pixels()
        .iter()
        .filter(|p| p.luminance() > 1e-3)
        .count();
    // The sign covers a small part of the view; most pixels see walls lit by it.
    assert!(
        lit as f32 > 0.8 * out.film.pixels().len() as f32,
        "only {lit} lit pixels"
    );
}

/// A sphere above a floor under a small light; `glass` chooses a clear dielectric sphere or
/// an opaque grey one.
fn caustic_world(glass: bool) -> World {
    let mut scene = Scene::empty("caustic");
    let floor = scene.add_material(Material::diffuse("floor", Rgb::splat(0.8)));
    let ball = scene.add_material(if glass {
        Material {
            diffuse: Rgb::BLACK,
            transmission: Rgb::WHITE,
            ior: 1.5,
            ..Material::default()
        }
    } else {
        Material::diffuse("ball", Rgb::splat(0.5))
    });
    let lamp = scene.add_material(Material::emitter("lamp", Rgb::BLACK, Rgb::splat(400.0)));
    scene.add_object(
        "floor",
        Shape::Parallelogram {
            origin: Vec3::new(-3.0, 0.0, 3.0),
            edge_u: Vec3::new(6.0, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 0.0, -6.0),
        },
        floor,
    );
    scene.add_object(
        "ball",
        Shape::Sphere {
            center: Vec3::new(0.0, 1.0, 0.0),
            radius: 0.5,
        },
        ball,
    );
    scene.add_object(
        "lamp",
        Shape::Parallelogram {
            origin: Vec3::new(-0.15, 3.0, -0.15),
            edge_u: Vec3::new(0.3, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 0.0, 0.3),
        },
        lamp,
    );
    scene.camera = camera(Vec3::new(0.0, 3.0, 3.0), Vec3::ZERO, 30.0);
    World::new(scene, AccelKind::Bvh).unwrap()
}

/// Light focused by a glass sphere makes the floor under it brighter than the shadow of an
/// opaque sphere (and brighter than the open floor around it).
#[test]
fn glass_sphere_casts_a_caustic() {
    let (w, h) = (32, 32);
    let stats = |glass: bool| {
        let world = caustic_world(glass);
        let tracer = PathTracer::new(&world, u32::MAX, 1);
        pixel_stats(&world, &tracer, w, h, 256, SequenceKind::Sobol)
    };
    let glass = stats(true);
    let opaque = stats(false);
    // The camera looks at the floor point under the sphere: the centre 4×4 pixels.
    let (mg, vg) = glass.region(14, 14, 18, 18);
    let (mo, vo) = opaque.region(14, 14, 18, 18);
    let (open_floor, vf) = opaque.region(0, 28, 4, 32);
    assert!(
        mg > 2.0 * mo + 5.0 * (vg + 4.0 * vo).sqrt(),
        "caustic {mg} ± {} vs shadow {mo} ± {}",
        vg.sqrt(),
        vo.sqrt()
    );
    assert!(
        mg > open_floor + 5.0 * (vg + vf).sqrt(),
        "caustic {mg} vs open floor {open_floor}"
    );
}

fn cornell() -> World {
    World::new(builtin::load("cornell").unwrap().unwrap(), AccelKind::Bvh).unwrap()
}

/// The path tracer traces camera samples eight at a time, with SIMD lanes for Lambertian
/// vertices lit by uniform area lights and the one-path code for everything else; each
/// sample's radiance must be exactly what tracing it alone gives. The scenes cover both kinds
/// of vertex and their mixture: the Cornell box (all lanes), its textured variant, the neon
/// room (a textured emitter: one-path light sampling), a glass sphere (delta lobes) and
/// branching first hits.
#[test]
fn packets_give_every_sample_the_radiance_it_has_alone() {
    let worlds = [
        ("cornell", cornell(), 1),
        ("cornell, 3 first-hit paths", cornell(), 3),
        (
            "cornell-textured",
            World::new(
                builtin::load("cornell-textured").unwrap().unwrap(),
                AccelKind::Bvh,
            )
            .unwrap(),
            1,
        ),
        (
            "neon",
            World::new(builtin::load("neon").unwrap().unwrap(), AccelKind::Bvh).unwrap(),
            1,
        ),
        ("glass sphere", caustic_world(true), 1),
    ];
    for (name, world, first_hit_paths) in &worlds {
        let tracer = PathTracer::new(world, u32::MAX, *first_hit_paths);
        let (w, h, spp) = (16u32, 16u32, 3u32);
        let camera = world.scene.camera.with_resolution(w, h).rays().unwrap();
        let mut rays = Vec::new();
        let mut samplers = Vec::new();
        for py in 0..h {
            for px in 0..w {
                for k in 0..spp {
                    let stream = u64::from(py * w + px);
                    let mut sampler = Sampler::new(SequenceKind::Sobol, 7, stream, k);
                    let jitter = sampler.next_2d();
                    rays.push(camera.ray(px as f32 + jitter.x, py as f32 + jitter.y));
                    samplers.push(sampler);
                }
            }
        }
        let alone: Vec<Rgb> = rays
            .iter()
            .zip(samplers.clone())
            .map(|(ray, mut sampler)| tracer.radiance(world, ray, &mut sampler))
            .collect();
        let mut packed = vec![Rgb::BLACK; rays.len()];
        tracer.radiance_batch(world, &rays, &mut samplers, &mut packed);
        for (i, (a, p)) in alone.iter().zip(&packed).enumerate() {
            assert_eq!(a, p, "{name}: sample {i}");
        }
        let lit = alone.iter().filter(|c| c.max_channel() > 0.0).count();
        assert!(lit > rays.len() / 2, "{name}: only {lit} lit samples");
    }
}

#[test]
fn same_image_for_one_and_three_threads() {
    let world = cornell();
    let tracer = PathTracer::new(&world, u32::MAX, 2);
    let settings = ProgressiveSettings {
        width: 24,
        height: 20,
        samples_per_pixel: 5,
        seed: 11,
        time_limit: None,
    };
    let with = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| render(&world, &tracer, &settings))
    };
    let one = with(1);
    let three = with(3);
    assert!(one.complete && one.samples_per_pixel == 5);
    assert!(one.film.mean().luminance() > 0.01);
    assert_eq!(one.film.pixels(), three.film.pixels());
}

#[test]
fn time_limit_stops_early_with_a_valid_partial_image() {
    let world = cornell();
    let tracer = PathTracer::new(&world, u32::MAX, 1);
    let limit = Duration::from_millis(300);
    let settings = ProgressiveSettings {
        width: 32,
        height: 32,
        samples_per_pixel: 1 << 20,
        seed: 0,
        time_limit: Some(limit),
    };
    let out = render(&world, &tracer, &settings);
    // 2²⁰ paths per pixel would take minutes: stopping early is the only way to finish.
    assert!(!out.complete);
    assert!(out.samples_per_pixel >= 1 && out.samples_per_pixel < 1 << 20);
    assert!(out.film.pixels().iter().all(|p| p.is_finite()));
    assert!(out.film.mean().luminance() > 0.01);
}

/// Sets a cancel flag (like Ctrl-C) once `after` units of progress were reported.
struct CancelAfter<'a> {
    done: AtomicU64,
    after: u64,
    cancel: &'a Cancel,
}

impl ProgressListener for CancelAfter<'_> {
    fn start(&self, _total: u64) {}
    fn advance(&self, units: u64) {
        if self.done.fetch_add(units, Ordering::SeqCst) + units >= self.after {
            self.cancel.request();
        }
    }
    fn finish(&self) {}
}

#[test]
fn cancelling_keeps_the_finished_passes() {
    let world = cornell();
    let tracer = PathTracer::new(&world, u32::MAX, 1);
    let (w, h) = (24, 16);
    let settings = ProgressiveSettings {
        width: w,
        height: h,
        samples_per_pixel: 64,
        seed: 5,
        time_limit: None,
    };
    let cancel = Cancel::new();
    // Cancelled as the first pass (1 path per pixel) reports its last pixels.
    let listener = CancelAfter {
        done: AtomicU64::new(0),
        after: u64::from(w * h),
        cancel: &cancel,
    };
    let out = render_progressive(&world, &tracer, &settings, &listener, &cancel).unwrap();
    assert!(!out.complete);
    assert_eq!((out.passes, out.samples_per_pixel), (1, 1));
    // The kept image is exactly the one-pass render.
    let one = render(
        &world,
        &tracer,
        &ProgressiveSettings {
            samples_per_pixel: 1,
            ..settings
        },
    );
    assert_eq!(out.film.pixels(), one.film.pixels());
}
