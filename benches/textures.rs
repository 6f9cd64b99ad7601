//! Texture averages under a deep quadtree: a 4096 × 4096 texture (268 MB of linear RGBA) on
//! one unit square split uniformly 8 levels deep (87,381 nodes, 65,536 leaves), and the exact
//! mean, smallest and largest texel under every node's UV polygon, as the hierarchical
//! solvers compute them when nodes are created. The averages need no memory beyond the
//! texture; each level reads every texel once, so the whole tree costs about nine passes
//! over the texture.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use std::hint::black_box;
use strahl::color::Rgb;
use strahl::radiosity::{MeshOptions, MeshSize, PatchMesh};
use strahl::scene::{Material, Scene, Shape, Texture};

/// Texels per side.
const SIZE: u32 = 4096;
/// Quadtree depth below the root.
const DEPTH: u32 = 8;

fn bench(c: &mut Criterion) {
    let texture = Texture::from_fn("noise", SIZE, SIZE, |x, y| {
        let v = ((x.wrapping_mul(2_654_435_761) ^ y.wrapping_mul(40_503)) % 1000) as f32 / 1000.0;
        [v, 1.0 - v, 0.5, 1.0]
    });
    let mut scene = Scene::empty("square");
    let m = scene.add_material(Material::diffuse("grey", Rgb::splat(0.5)));
    scene.add_object(
        "square",
        Shape::Parallelogram {
            origin: Vec3::ZERO,
            edge_u: Vec3::X,
            edge_v: Vec3::Z,
        },
        m,
    );
    let mut mesh = PatchMesh::from_scene(&scene, &MeshOptions::default()).unwrap();
    let root = mesh.roots[0];
    mesh.subdivide_uniformly(root, MeshSize::Levels(DEPTH));
    let polygons: Vec<Vec<glam::DVec2>> = mesh.patches.iter().map(|p| p.uvs().to_vec()).collect();
    let mut group = c.benchmark_group("texture averages");
    group.sample_size(10);
    group.throughput(Throughput::Elements(polygons.len() as u64));
    group.bench_function("4096² texture, every node of a depth-8 quadtree", |b| {
        b.iter(|| {
            for uv in &polygons {
                black_box(texture.polygon_stats(black_box(uv)));
            }
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
