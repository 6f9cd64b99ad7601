//! End-to-end rendering with the standard ray tracer: a stored reference image, identical
//! images for every accelerator and every thread count, and adaptive antialiasing that never
//! traces a grid point twice.

use strahl::accel::AccelKind;
use strahl::image;
use strahl::measure::Film;
use strahl::progress::Cancel;
use strahl::progress::NoProgress;
use strahl::scene::builtin;
use strahl::trace::AntialiasMode;
use strahl::trace::StandardRayTracer;
use strahl::trace::{RenderOutput, RenderSettings, render};
use strahl::world::World;

fn world(spec: &str, accel: AccelKind) -> World {
    World::new(builtin::load(spec).unwrap().unwrap(), accel).unwrap()
}

fn settings(width: u32, height: u32, antialias: AntialiasMode) -> RenderSettings {
    RenderSettings {
        width,
        height,
        antialias,
        samples_per_pixel: 4,
        seed: 1,
        ..Default::default()
    }
}

fn render_with(world: &World, settings: &RenderSettings, threads: usize) -> RenderOutput {
    render_with_tracer(world, settings, threads, &StandardRayTracer::default())
}

fn render_with_tracer(
    world: &World,
    settings: &RenderSettings,
    threads: usize,
    tracer: &StandardRayTracer,
) -> RenderOutput {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| render(world, tracer, settings, &NoProgress, &Cancel::new()).unwrap())
}

/// Regenerate with `STRAHL_WRITE_REFERENCE=1 cargo test --release --test render` after a
/// deliberate change of the standard ray tracer's output, and say why in the commit.
#[test]
fn cornell_matches_stored_reference_for_every_accelerator() {
    let reference_path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cornell_standard_48.pfm");
    // Many shadow rays per pixel keep the soft shadows' noise well below the tolerance, so
    // the comparison measures the renderer rather than its random numbers.
    let tracer = StandardRayTracer {
        light_samples: 256,
        ..Default::default()
    };
    let s = settings(48, 48, AntialiasMode::None);
    if std::env::var_os("STRAHL_WRITE_REFERENCE").is_some() {
        let out = render_with_tracer(&world("cornell", AccelKind::Bvh), &s, 2, &tracer);
        image::save(&out.film, &reference_path, &Default::default()).unwrap();
    }
    let reference = image::load(&reference_path).unwrap();
    let mean = reference.mean().luminance() as f64;
    assert!(mean > 0.01, "the reference image is black");
    // The noise floor: the same render with another seed differs by this much.
    let other_seed = RenderSettings {
        seed: 99,
        ..s.clone()
    };
    let noise = render_with_tracer(&world("cornell", AccelKind::Bvh), &other_seed, 2, &tracer)
        .film
        .rms_difference(&reference)
        .unwrap()
        / mean;
    assert!(noise < 0.01, "noise floor {noise}");
    for accel in [AccelKind::Bvh, AccelKind::Octree, AccelKind::Naive] {
        let out = render_with_tracer(&world("cornell", accel), &s, 2, &tracer);
        assert!(out.complete);
        let rms = out.film.rms_difference(&reference).unwrap() / mean;
        // Deterministic, so normally 0; a change in sampling order may move it up to the
        // noise floor, a real change of geometry or lighting far beyond 2 %.
        assert!(rms < 0.02, "{accel:?}: relative RMS {rms}");
    }
}

fn assert_same(a: &Film, b: &Film, what: &str) {
    assert_eq!(a.pixels(), b.pixels(), "{what}");
}

#[test]
fn every_accelerator_gives_the_same_image() {
    for spec in ["cornell-textured", "spheres:300", "neon"] {
        let s = settings(40, 30, AntialiasMode::Stochastic);
        let reference = render_with(&world(spec, AccelKind::Naive), &s, 2).film;
        for accel in [AccelKind::Bvh, AccelKind::Octree] {
            let film = render_with(&world(spec, accel), &s, 2).film;
            assert_same(&film, &reference, &format!("{spec} with {accel:?}"));
        }
    }
}

#[test]
fn the_image_does_not_depend_on_the_thread_count() {
    let w = world("cornell", AccelKind::Bvh);
    for aa in [AntialiasMode::Stochastic, AntialiasMode::Adaptive] {
        let s = settings(37, 29, aa);
        let one = render_with(&w, &s, 1);
        for threads in [2, 3] {
            let many = render_with(&w, &s, threads);
            assert_same(
                &many.film,
                &one.film,
                &format!("{aa:?} with {threads} threads"),
            );
            assert_eq!(many.samples_traced, one.samples_traced);
        }
    }
}

#[test]
fn adaptive_antialiasing_traces_each_grid_point_once() {
    let w = world("cornell", AccelKind::Bvh);
    let (width, height) = (21u64, 19u64);
    // Never subdividing: the pixel corners and centres, each once.
    let mut s = settings(width as u32, height as u32, AntialiasMode::Adaptive);
    s.adaptive_threshold = f32::INFINITY;
    let out = render_with(&w, &s, 2);
    assert_eq!(
        out.samples_traced,
        (width + 1) * (height + 1) + width * height
    );
    assert!(out.subdivisions.iter().all(|&c| c == 0));
    // Always subdividing to depth 4: squares of side 2 on a grid of 16 per pixel, so every
    // even grid point and every odd-odd centre, each once.
    s.adaptive_threshold = -1.0;
    let out = render_with(&w, &s, 2);
    let even = (8 * width + 1) * (8 * height + 1);
    let centres = 8 * width * 8 * height;
    assert_eq!(out.samples_traced, even + centres);
    // Levels of side 16, 8, 4 and 2 grid units: 4 + 16 + 64 squares subdivided per pixel.
    assert!(out.subdivisions.iter().all(|&c| c == 4 + 16 + 64));
}

#[test]
fn adaptive_antialiasing_subdivides_only_at_edges() {
    let w = world("cornell", AccelKind::Bvh);
    let out = render_with(&w, &settings(64, 64, AntialiasMode::Adaptive), 2);
    let subdivided = out.subdivisions.iter().filter(|&&c| c > 0).count();
    // Edges of walls, blocks and the light: a minority of pixels, but not none.
    assert!(
        subdivided > 64 && subdivided < 64 * 64 / 2,
        "{subdivided} pixels subdivided"
    );
}
