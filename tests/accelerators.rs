//! The three accelerators answer every query identically on every built-in scene.

use strahl::accel::{AccelKind, Accelerator};
use strahl::geometry::Ray;
use strahl::sampling::warp::uniform_sphere;
use strahl::sampling::{Sampler, SequenceKind};
use strahl::scene::builtin;
use strahl::world::SceneGeometry;

fn random_rays(geometry: &SceneGeometry, count: usize, seed: u64) -> Vec<Ray> {
    let b = geometry.bounds();
    let mut s = Sampler::new(SequenceKind::Random, seed, 0, 0);
    (0..count)
        .map(|i| {
            let u = glam::Vec3::new(s.next_1d(), s.next_1d(), s.next_1d());
            // Half the rays start inside the bounds, half outside (enlarged by 50 %).
            let scale = if i % 2 == 0 { 1.0 } else { 2.0 };
            let origin = b.center() + (u - glam::Vec3::splat(0.5)) * b.extent() * scale;
            Ray::new(origin, uniform_sphere(s.next_2d()))
        })
        .collect()
}

fn check_scene(spec: &str) {
    let scene = builtin::load(spec).expect("built-in").expect("loads");
    let geometry = SceneGeometry::new(&scene).unwrap();
    let accels: Vec<(AccelKind, Box<dyn Accelerator<SceneGeometry>>)> =
        [AccelKind::Naive, AccelKind::Bvh, AccelKind::Octree]
            .into_iter()
            .map(|k| (k, k.build(&geometry)))
            .collect();
    let rays = random_rays(&geometry, 4000, 17);
    let mut hits = 0;
    for (i, ray) in rays.iter().enumerate() {
        let reference = accels[0].1.closest_hit(&geometry, ray, f32::INFINITY);
        hits += usize::from(reference.is_some());
        let limit = reference.map_or(f32::INFINITY, |h| h.t * 0.5);
        let any_reference = accels[0].1.any_hit(&geometry, ray, limit);
        for (kind, accel) in &accels[1..] {
            assert_eq!(
                accel.closest_hit(&geometry, ray, f32::INFINITY),
                reference,
                "{spec}: {kind:?} closest hit differs for ray {i} {ray:?}"
            );
            assert_eq!(
                accel.any_hit(&geometry, ray, limit),
                any_reference,
                "{spec}: {kind:?} any hit differs for ray {i}"
            );
        }
    }
    assert!(
        hits > 400,
        "{spec}: too few rays hit anything ({hits}) to test much"
    );
}

#[test]
fn accelerators_agree_on_cornell() {
    check_scene("cornell");
}

#[test]
fn accelerators_agree_on_cornell_textured() {
    check_scene("cornell-textured");
}

#[test]
fn accelerators_agree_on_spheres() {
    check_scene("spheres:1000");
}

#[test]
fn accelerators_agree_on_neon() {
    check_scene("neon");
}

#[test]
fn accelerators_agree_on_a_canopy_whose_hierarchy_is_built_on_several_threads() {
    // 20,000 triangles: the BVH builds the two subtrees of every node over 4,096 references
    // or more at once, here on three threads.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(3)
        .build()
        .unwrap();
    pool.install(|| check_scene("canopy:10000"));
}
