//! Acceleration-structure benchmarks: BVH build time and closest-hit / any-hit throughput for
//! camera rays, on `spheres:10000` and on a generated room of about 300,000 triangles that
//! stands in for the conference room (set `STRAHL_CONFERENCE_OBJ` to a copy of the real
//! `conference.obj` to measure it too; `strahl bench FILE` gives the full 1024-wide figure).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use std::hint::black_box;
use std::sync::Arc;
use strahl::accel::{Accelerator, Bvh, BvhOptions};
use strahl::geometry::Ray;
use strahl::scene::{Material, Object, PolygonMesh, Scene, Shape, builtin};
use strahl::world::SceneGeometry;

/// A room (20 × 4 × 12) furnished with rows of tessellated chairs and tables: about 300,000
/// triangles in many small pieces, like the conference room; camera in the middle looking +x.
fn furnished_room() -> Scene {
    let mut scene = Scene::empty("furnished-room");
    let m = scene.add_material(Material::diffuse("grey", strahl::color::Rgb::splat(0.6)));
    let mut add = |shape: Shape, segments: u32| {
        let mesh: PolygonMesh = shape.to_mesh(segments).expect("finite shape").into_owned();
        scene.objects.push(Object {
            name: None,
            shape: Shape::Mesh(Arc::new(mesh)),
            transform: Default::default(),
            material: m,
            per_face: false,
        });
    };
    add(
        Shape::Box {
            min: Vec3::new(-10.0, -0.1, -6.0),
            max: Vec3::new(10.0, 0.0, 6.0),
        },
        4,
    );
    for i in 0..40 {
        for j in 0..24 {
            let base = Vec3::new(-9.5 + i as f32 * 0.5, 0.0, -5.75 + j as f32 * 0.5);
            for (dx, dz) in [(0.1, 0.1), (0.3, 0.1), (0.1, 0.3), (0.3, 0.3)] {
                let leg = base + Vec3::new(dx, 0.0, dz);
                add(
                    Shape::Cylinder {
                        base: leg,
                        top: leg + Vec3::Y * 0.45,
                        radius: 0.02,
                        caps: false,
                    },
                    16,
                );
            }
            add(
                Shape::Box {
                    min: base + Vec3::new(0.05, 0.45, 0.05),
                    max: base + Vec3::new(0.35, 0.5, 0.35),
                },
                4,
            );
            add(
                Shape::Sphere {
                    center: base + Vec3::new(0.2, 0.8, 0.2),
                    radius: 0.12,
                },
                22,
            );
        }
    }
    scene.camera.position = Vec3::new(0.0, 2.0, 0.0);
    scene.camera.look_at = Vec3::new(1.0, 2.0, 0.0);
    scene.camera.fov_degrees = 90.0;
    scene
}

fn camera_rays(scene: &Scene, width: u32) -> Vec<Ray> {
    let rays = scene
        .camera
        .with_resolution(width, width)
        .rays()
        .expect("valid camera");
    (0..width * width)
        .map(|i| rays.ray((i % width) as f32 + 0.5, (i / width) as f32 + 0.5))
        .collect()
}

fn bench_scene(c: &mut Criterion, name: &str, scene: &Scene) {
    let geometry = SceneGeometry::new(scene).expect("valid scene");
    let mut group = c.benchmark_group(name);
    group.sample_size(10);
    group.bench_function("bvh_build", |b| {
        b.iter(|| Bvh::build(black_box(&geometry), &BvhOptions::default()))
    });
    let bvh = Bvh::build(&geometry, &BvhOptions::default());
    let rays = camera_rays(scene, 256);
    group.throughput(Throughput::Elements(rays.len() as u64));
    group.bench_function("closest_hit_primary", |b| {
        b.iter(|| {
            rays.iter()
                .filter(|r| bvh.closest_hit(&geometry, r, f32::INFINITY).is_some())
                .count()
        })
    });
    group.bench_function("any_hit_primary", |b| {
        b.iter(|| {
            rays.iter()
                .filter(|r| bvh.any_hit(&geometry, r, f32::INFINITY))
                .count()
        })
    });
    group.finish();
}

fn accelerators(c: &mut Criterion) {
    let spheres = builtin::load("spheres:10000")
        .expect("built-in")
        .expect("loads");
    bench_scene(c, "spheres_10000", &spheres);
    let room = furnished_room();
    bench_scene(c, "furnished_room", &room);
    if let Some(path) = std::env::var_os("STRAHL_CONFERENCE_OBJ") {
        let text = format!(
            "[camera]\nposition = [0, 0, 0]\nlook_at = [1, 0, 0]\nfov = 90\n\n[[objects]]\ntype = \"mesh\"\nfile = {}\n",
            toml::Value::String(path.to_string_lossy().into_owned())
        );
        let mut scene = strahl::scene::load_str(&text, "conference", std::path::Path::new("."))
            .expect("conference.obj loads");
        let centre = SceneGeometry::new(&scene).expect("valid").bounds().center();
        scene.camera.position = centre;
        scene.camera.look_at = centre + Vec3::X;
        bench_scene(c, "conference", &scene);
    }
}

criterion_group!(benches, accelerators);
criterion_main!(benches);
