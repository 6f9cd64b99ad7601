//! Directional and sky photons aimed at what they can meet: in a scene whose bounding sphere
//! is mostly empty (a 1 m² quad 40 m from a sphere of radius 3 m), the quad still receives
//! its analytic power, now with most photons meeting something, a standard error several
//! times smaller than with uniform points over the bounding sphere's cross-section, exact
//! bookkeeping (emitted = absorbed + escaped, emitted = the light's defined power) and the
//! same report for any thread count.
//!
//! Standard errors are measured: the first-hit power each photon of the light brings to the
//! quad (its power times the fraction it carries, when the quad is the first thing it
//! meets), photon by photon, gives the per-photon spread of the light model's estimate.

use glam::Vec3;
use std::f64::consts::PI;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::color::Rgb;
use strahl::light_model::sources::PhotonSources;
use strahl::light_model::{LightTraceOutput, LightTraceSettings, trace_light};
use strahl::progress::{Cancel, NoProgress};
use strahl::report::Report;
use strahl::sampling::{Sampler, SequenceKind};
use strahl::scene::{Light, LightKind, Material, Scene, Shape};
use strahl::world::World;

/// The quad's object index.
const QUAD: u32 = 0;
/// Sun irradiance, W·m⁻².
const IRRADIANCE: f32 = 2.0;
/// Sky radiance, W·sr⁻¹·m⁻².
const RADIANCE: f32 = 0.5;

/// Sun direction, 30° from the vertical.
fn sun_direction() -> Vec3 {
    Vec3::new(30f32.to_radians().sin(), -30f32.to_radians().cos(), 0.0)
}

fn sun() -> LightKind {
    LightKind::Directional {
        direction: sun_direction(),
        irradiance: Rgb::splat(IRRADIANCE),
    }
}

fn sky() -> LightKind {
    LightKind::Sky {
        radiance: Rgb::splat(RADIANCE),
    }
}

/// An upward-facing 1 m² quad at the origin and a sphere of radius 3 m (a mesh, 32 segments)
/// 40 m away at the same height, both reflecting `rho`, under `lights`.
fn quad_and_far_sphere(rho: f32, lights: &[LightKind]) -> Scene {
    let mut scene = Scene::empty("quad and far sphere");
    let m = scene.add_material(Material::diffuse("grey", Rgb::splat(rho)));
    scene.add_object(
        "quad",
        Shape::Parallelogram {
            origin: Vec3::new(-0.5, 0.0, 0.5),
            edge_u: Vec3::X,
            edge_v: Vec3::NEG_Z,
        },
        m,
    );
    let sphere = Shape::Sphere {
        center: Vec3::new(40.0, 0.0, 0.0),
        radius: 3.0,
    };
    let mesh = sphere.to_mesh(32).unwrap().into_owned();
    scene.add_object("sphere", Shape::Mesh(Arc::new(mesh)), m);
    for kind in lights {
        scene.lights.push(Light {
            name: None,
            kind: kind.clone(),
        });
    }
    scene
}

fn compile(scene: Scene) -> World {
    World::new(scene, AccelKind::Bvh).unwrap()
}

fn trace(world: &World, photons: u64, seed: u64) -> LightTraceOutput {
    let settings = LightTraceSettings {
        photons,
        seed,
        ..LightTraceSettings::default()
    };
    let out = trace_light(world, &settings, &NoProgress, &Cancel::new()).unwrap();
    assert!(out.complete());
    out
}

/// What the photons of a world's only light bring on their first hit.
struct FirstHits {
    /// Mean power on the quad per photon, W (green channel).
    mean: f64,
    /// Standard deviation of one photon's power on the quad, W.
    deviation: f64,
    /// Fraction of the photons that meet something.
    hit_fraction: f64,
    /// Fraction of the light's power that meets something (what uniform points would hit).
    power_fraction: f64,
}

fn first_hits(world: &World, photons: u64, seed: u64) -> FirstHits {
    let sources = PhotonSources::new(world);
    assert_eq!(sources.sources.len(), 1);
    let power = f64::from(sources.sources[0].power.g);
    let (mut sum, mut squares, mut hits, mut hit_power) = (0.0, 0.0, 0u64, 0.0);
    for i in 0..photons {
        let mut sampler = Sampler::new(SequenceKind::Random, seed, i, 0);
        let photon = sources.emit(world, 0, &mut sampler);
        let brought = power * photon.carried;
        let Some(hit) = world.intersect(&photon.ray).filter(|_| brought > 0.0) else {
            continue;
        };
        hits += 1;
        hit_power += brought;
        if hit.object == QUAD {
            sum += brought;
            squares += brought * brought;
        }
    }
    let n = photons as f64;
    let mean = sum / n;
    FirstHits {
        mean,
        deviation: (squares / n - mean * mean).max(0.0).sqrt(),
        hit_fraction: hits as f64 / n,
        power_fraction: hit_power / n / power,
    }
}

/// Checks the quad's power under `light` against `expected` (W) and the standard errors of
/// aimed against uniform points.
fn quad_receives(light: LightKind, expected: f64) {
    let world = compile(quad_and_far_sphere(0.0, &[light]));
    let n = 200_000u64;
    let aimed = first_hits(&world, n, 1);
    let out = trace(&world, n, 2);
    let report = Report::new("aimed", &out.measurement());
    let quad = report.objects.iter().find(|o| o.name == "quad").unwrap();
    let got = quad.incident_power[1];
    let error = aimed.deviation / (n as f64).sqrt();
    assert!(
        (aimed.mean - expected).abs() < 4.0 * error,
        "first hits: {} vs {expected} ± {error}",
        aimed.mean
    );
    assert!(
        (got - expected).abs() < 4.0 * error,
        "{got} vs {expected} ± {error}"
    );
    // Uniform points: each photon brings Φ/N with probability p = P/Φ, or nothing.
    let phi = report.totals.emitted_power[1];
    let p = expected / phi;
    let uniform_error = expected * ((1.0 - p) / (n as f64 * p)).sqrt();
    assert!(
        error < uniform_error / 5.0,
        "aimed {error} vs uniform {uniform_error}"
    );
    assert!(aimed.hit_fraction > 0.5, "{}", aimed.hit_fraction);
    assert!(aimed.power_fraction < 0.05, "{}", aimed.power_fraction);
    // Black surfaces: every photon that meets something ends there.
    let missed = out.escaped_photons as f64 / n as f64;
    assert!((1.0 - missed - aimed.hit_fraction).abs() < 0.01, "{missed}");
}

#[test]
fn aimed_sun_gives_the_quad_e_a_cos_theta() {
    quad_receives(sun(), f64::from(IRRADIANCE) * 30f64.to_radians().cos());
}

#[test]
fn aimed_sky_gives_each_side_of_the_quad_pi_l_a() {
    // π·L·A on each side; the sphere hides under 10⁻⁴ of the quad's sky, at the horizon.
    quad_receives(sky(), 2.0 * PI * f64::from(RADIANCE));
}

#[test]
fn aimed_photons_conserve_power_and_emit_the_lights_power() {
    for lights in [vec![sun()], vec![sky()], vec![sun(), sky()]] {
        let world = compile(quad_and_far_sphere(0.6, &lights));
        let report = Report::new("conservation", &trace(&world, 50_000, 3).measurement());
        let t = &report.totals;
        let defined: Rgb = lights.iter().map(|l| world.light_power(l)).sum();
        for c in 0..3 {
            let (emitted, absorbed, escaped) =
                (t.emitted_power[c], t.absorbed_power[c], t.escaped_power[c]);
            assert!(
                (absorbed + escaped - emitted).abs() < 1e-9 * emitted,
                "{lights:?}: {absorbed} + {escaped} vs {emitted}"
            );
            let defined = f64::from(defined.to_array()[c]);
            assert!(
                (emitted - defined).abs() < 1e-6 * defined,
                "{emitted} vs {defined}"
            );
        }
    }
}

#[test]
fn aimed_photons_give_the_same_report_for_any_thread_count() {
    let world = compile(quad_and_far_sphere(0.6, &[sun(), sky()]));
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let out = pool.install(|| trace(&world, 30_000, 5));
        Report::new("threads", &out.measurement())
    };
    let (a, b) = (run(1), run(2));
    assert_eq!(a.objects, b.objects);
    assert_eq!(a.totals, b.totals);
}

#[test]
fn an_infinite_plane_still_receives_every_photon_that_misses_the_rest() {
    // Unbounded geometry turns aiming off: under a vertical sun a black ground plane below
    // the quad and the sphere receives all that they do not, E·πR² in all.
    let vertical_sun = LightKind::Directional {
        direction: Vec3::NEG_Y,
        irradiance: Rgb::splat(IRRADIANCE),
    };
    let mut scene = quad_and_far_sphere(0.0, &[vertical_sun]);
    let black = scene.add_material(Material::diffuse("black", Rgb::BLACK));
    scene.add_object(
        "ground",
        Shape::Plane {
            point: Vec3::new(0.0, -5.0, 0.0),
            normal: Vec3::Y,
        },
        black,
    );
    let report = Report::new("ground", &trace(&compile(scene), 20_000, 4).measurement());
    let t = &report.totals;
    let incident: f64 = report.objects.iter().map(|o| o.incident_power[1]).sum();
    assert!((incident - t.emitted_power[1]).abs() < 1e-9 * t.emitted_power[1]);
    assert_eq!(t.escaped_power[1], 0.0);
}
