//! The light model on a plant-like scene: 10,000 small tilted leaves under a sky and a sun,
//! 100,000 photons per iteration (photons per second is the figure to read).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use std::sync::atomic::AtomicBool;
use strahl::accel::AccelKind;
use strahl::color::Rgb;
use strahl::scene::{Light, LightKind, Material, Scene, Shape};
use strahl::trace::World;
use strahl::trace::lighttracer::{LightTraceSettings, trace_light};
use strahl::trace::render::NoProgress;

/// 100 × 100 leaves of 6 × 6 cm, at varying heights and tilts, in a 10 m × 10 m canopy.
fn canopy() -> Scene {
    let mut scene = Scene::empty("canopy");
    let leaf = scene.add_material(Material {
        transmission: Rgb::splat(0.1),
        ior: 1.0,
        ..Material::diffuse("leaf", Rgb::new(0.1, 0.4, 0.1))
    });
    for i in 0..100 {
        for j in 0..100 {
            let origin = Vec3::new(
                i as f32 * 0.1,
                ((i * 7 + j * 13) % 10) as f32 * 0.05,
                j as f32 * 0.1,
            );
            let tilt = Vec3::new(0.02 * ((i + j) % 3) as f32, 0.03, 0.0);
            scene.add_object(
                &format!("leaf-{i}-{j}"),
                Shape::Parallelogram {
                    origin,
                    edge_u: Vec3::X * 0.06 + tilt,
                    edge_v: Vec3::NEG_Z * 0.06,
                },
                leaf,
            );
        }
    }
    scene.lights.push(Light {
        name: None,
        kind: LightKind::Sky {
            radiance: Rgb::splat(0.2),
        },
    });
    scene.lights.push(Light {
        name: Some("sun".into()),
        kind: LightKind::Directional {
            direction: Vec3::new(0.3, -1.0, 0.2),
            irradiance: Rgb::splat(500.0),
        },
    });
    scene
}

fn light_model(c: &mut Criterion) {
    let world = World::new(canopy(), AccelKind::Bvh).expect("valid scene");
    let settings = LightTraceSettings {
        photons: 100_000,
        seed: 1,
        max_bounces: 1000,
    };
    let mut group = c.benchmark_group("light_model");
    group.sample_size(10);
    group.throughput(Throughput::Elements(settings.photons));
    group.bench_function("canopy_10000_leaves", |b| {
        b.iter(|| {
            trace_light(&world, &settings, &NoProgress, &AtomicBool::new(false)).expect("lights")
        })
    });
    group.finish();
}

criterion_group!(benches, light_model);
criterion_main!(benches);
