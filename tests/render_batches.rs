//! Path-traced images in batches: any split of a render's samples per pixel, rendered apart
//! (other processes, other machines) and merged, gives the single run's image bit for bit
//! (every pixel's samples are summed in fixed point); merging refuses batches that do not
//! belong together.

use glam::Vec3;
use std::sync::Arc;
use strahl::method::{
    AccelKind, Batch, Cancel, ImageSize, MergeError, Method, MethodError, NoProgress, NoSuchBatch,
    PathTraceSettings, RayTraceSettings, RenderPartial, World, merge_render_batches, run,
    run_render_batch,
};

fn world(name: &str) -> Arc<World> {
    let scene = strahl::scene::open(name, &Default::default()).unwrap();
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

/// A small path-traced render with a sample count that no split divides evenly.
fn path_trace(seed: u64) -> Method {
    Method::PathTrace(PathTraceSettings {
        size: ImageSize {
            width: Some(24),
            height: Some(18),
        },
        seed,
        samples_per_pixel: 13,
        ..PathTraceSettings::default()
    })
}

/// Batch `index` of `count` on `threads` threads, sent through JSON as it would travel
/// between machines.
fn batch(world: &World, method: &Method, index: u32, count: u32, threads: usize) -> RenderPartial {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let partial = pool.install(|| {
        run_render_batch(
            world,
            method,
            Batch { index, count },
            &NoProgress,
            &Cancel::new(),
        )
        .unwrap()
    });
    serde_json::from_str(&serde_json::to_string(&partial).unwrap()).unwrap()
}

/// The pixels' bits, for comparing images exactly.
fn bits(film: &strahl::measure::Film) -> Vec<[u32; 3]> {
    film.pixels()
        .iter()
        .map(|p| p.to_array().map(f32::to_bits))
        .collect()
}

#[test]
fn batches_merged_give_the_single_render_bit_for_bit() {
    let world = world("cornell");
    let method = path_trace(5);
    let single = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
    let whole = bits(single.image.as_ref().unwrap());
    assert!(
        whole.iter().flatten().any(|&b| f32::from_bits(b) > 0.0),
        "the image is not black"
    );
    for count in [1, 3, 7] {
        // Batches on one and on two threads, merged in reverse order.
        let mut partials: Vec<_> = (0..count)
            .map(|k| batch(&world, &method, k, count, 1 + (k as usize % 2)))
            .collect();
        let samples: u32 = partials.iter().map(|p| p.samples_per_pixel()).sum();
        assert_eq!(samples, 13);
        partials.reverse();
        let merged = merge_render_batches(&world, &partials).unwrap();
        assert!(merged.complete);
        assert_eq!(bits(&merged.image.unwrap()), whole, "{count} batches");
    }
}

/// The refusal of a merge, as the merge's own error.
fn refusal(world: &World, parts: &[RenderPartial]) -> Option<MergeError> {
    match merge_render_batches(world, parts) {
        Ok(_) => None,
        Err(MethodError::Merge(refused)) => Some(refused),
        Err(other) => panic!("not a refusal to merge: {other}"),
    }
}

#[test]
fn batches_that_do_not_belong_together_are_refused() {
    let world = world("cornell");
    let method = path_trace(5);
    let (a, b) = (
        batch(&world, &method, 0, 2, 1),
        batch(&world, &method, 1, 2, 1),
    );
    let of_two = |index| Batch { index, count: 2 };
    assert_eq!(refusal(&world, &[]), Some(MergeError::Nothing));
    assert_eq!(
        refusal(&world, std::slice::from_ref(&a)),
        Some(MergeError::Missing(of_two(1)))
    );
    assert_eq!(
        refusal(&world, &[a.clone(), a.clone(), b.clone()]),
        Some(MergeError::Twice(of_two(0)))
    );
    let other_seed = batch(&world, &path_trace(6), 1, 2, 1);
    assert_eq!(
        refusal(&world, &[a.clone(), other_seed]),
        Some(MergeError::OtherSettings(of_two(1)))
    );
    let third = batch(&world, &method, 1, 3, 1);
    assert_eq!(
        refusal(&world, &[a.clone(), third]),
        Some(MergeError::OtherBatching(Batch { index: 1, count: 3 }, 2))
    );
    // A batch stopped before its first pass.
    let cancel = Cancel::new();
    cancel.request();
    let stopped = run_render_batch(&world, &method, of_two(1), &NoProgress, &cancel).unwrap();
    assert_eq!(stopped.samples_per_pixel(), 0);
    assert_eq!(
        refusal(&world, &[a.clone(), stopped]),
        Some(MergeError::CutShort(of_two(1)))
    );
    // Sums of another size than the settings say, in a file altered consistently.
    let resized: Vec<RenderPartial> = [&a, &b]
        .iter()
        .map(|p| {
            let mut value = serde_json::to_value(p).unwrap();
            value["settings"]["width"] = 23.into();
            serde_json::from_value(value).unwrap()
        })
        .collect();
    assert_eq!(
        refusal(&world, &resized),
        Some(MergeError::Damaged(of_two(0)))
    );
    // The same batches against a scene with its light moved.
    let mut moved = strahl::scene::open("cornell", &Default::default()).unwrap();
    moved
        .move_named("light", Vec3::new(0.0, 0.0, 0.01))
        .unwrap();
    let moved = World::new(moved, AccelKind::Bvh).unwrap();
    assert_eq!(
        refusal(&moved, &[a, b]),
        Some(MergeError::OtherScene(of_two(0)))
    );
}

#[test]
fn damaged_sums_and_methods_without_batches_are_refused() {
    let world = world("cornell");
    let method = path_trace(5);
    let mut value = serde_json::to_value(batch(&world, &method, 0, 2, 1)).unwrap();
    value["sums"]["sums"] = "not base64!".into();
    let error = serde_json::from_value::<RenderPartial>(value.clone()).unwrap_err();
    assert!(error.to_string().contains("not packed integers"), "{error}");
    value["sums"]["sums"] = "AAEC".into();
    let error = serde_json::from_value::<RenderPartial>(value).unwrap_err();
    assert!(
        error.to_string().contains("3 sums for 24×18 pixels"),
        "{error}"
    );

    let ray_trace = Method::RayTrace(RayTraceSettings::default());
    let refused = run_render_batch(
        &world,
        &ray_trace,
        Batch { index: 0, count: 2 },
        &NoProgress,
        &Cancel::new(),
    );
    assert!(matches!(
        refused,
        Err(MethodError::NotInBatches("raytrace"))
    ));
    let beyond = Batch { index: 2, count: 2 };
    let refused = run_render_batch(&world, &method, beyond, &NoProgress, &Cancel::new());
    assert!(matches!(refused, Err(MethodError::NoSuchBatch(NoSuchBatch(b))) if b == beyond));
}

#[test]
fn more_batches_than_samples_leave_some_empty() {
    let world = world("cornell");
    let method = path_trace(5);
    let single = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
    let partials: Vec<_> = (0..20).map(|k| batch(&world, &method, k, 20, 2)).collect();
    assert_eq!(
        partials
            .iter()
            .filter(|p| p.samples_per_pixel() == 0)
            .count(),
        7
    );
    let merged = merge_render_batches(&world, &partials).unwrap();
    assert_eq!(bits(&merged.image.unwrap()), bits(&single.image.unwrap()));
}
