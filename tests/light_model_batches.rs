//! The light model in batches: any split of a run's photons, traced apart (other processes,
//! other machines) and merged, gives the single run's report bit for bit (its tallies are
//! integers); merging refuses batches that do not belong together.

use glam::Vec3;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::light_model::{
    LightTraceError, LightTracePartial, LightTraceSettings, merge_light_batches, trace_light,
    trace_light_batch,
};
use strahl::progress::{Cancel, NoProgress};
use strahl::report::Report;
use strahl::sampling::{Batch, MergeError};
use strahl::world::World;

fn world(name: &str) -> Arc<World> {
    let scene = strahl::scene::open(name, &Default::default()).unwrap();
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

fn settings() -> LightTraceSettings {
    LightTraceSettings {
        photons: 60_001,
        seed: 7,
        ..LightTraceSettings::default()
    }
}

/// The report as JSON, without the seconds (which no two runs share).
fn report(world: &World, out: &strahl::light_model::LightTraceOutput) -> serde_json::Value {
    let mut value =
        serde_json::to_value(Report::new(&world.scene.name, &out.measurement())).unwrap();
    value["stats"].as_object_mut().unwrap().remove("seconds");
    value
}

/// Batch `index` of `count`, sent through JSON as it would travel between machines.
fn batch(world: &World, index: u32, count: u32, threads: usize) -> LightTracePartial {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let partial = pool.install(|| {
        trace_light_batch(
            world,
            &settings(),
            Batch { index, count },
            &NoProgress,
            &Cancel::new(),
        )
        .unwrap()
    });
    serde_json::from_str(&serde_json::to_string(&partial).unwrap()).unwrap()
}

#[test]
fn batches_merged_give_the_single_run_bit_for_bit() {
    let world = world("cornell");
    let single = trace_light(&world, &settings(), &NoProgress, &Cancel::new()).unwrap();
    let whole = report(&world, &single);
    for count in [1, 3, 7] {
        // Batches on one and on two threads, merged in reverse order.
        let mut partials: Vec<_> = (0..count)
            .map(|k| batch(&world, k, count, 1 + (k as usize % 2)))
            .collect();
        partials.reverse();
        let merged = merge_light_batches(&world, &partials).unwrap();
        assert_eq!(merged.photons_traced, settings().photons);
        assert_eq!(report(&world, &merged), whole, "{count} batches");
    }
}

#[test]
fn the_batches_cover_every_photon_once() {
    for photons in [1u64, 7, 60_001, u64::MAX / 3] {
        for count in [1u32, 2, 3, 1000] {
            let ranges: Vec<_> = (0..count)
                .map(|index| Batch { index, count }.share(photons).unwrap())
                .collect();
            assert_eq!(ranges[0].start, 0);
            assert_eq!(ranges.last().unwrap().end, photons);
            assert!(ranges.windows(2).all(|w| w[0].end == w[1].start));
        }
    }
}

#[test]
fn batches_that_do_not_belong_together_are_refused() {
    let world = world("cornell");
    let (a, b) = (batch(&world, 0, 2, 1), batch(&world, 1, 2, 1));
    let merge = |parts: &[LightTracePartial]| match merge_light_batches(&world, parts) {
        Ok(_) => Ok(()),
        Err(LightTraceError::Merge(refused)) => Err(refused),
        Err(other) => panic!("not a refusal to merge: {other}"),
    };
    assert_eq!(merge(&[]), Err(MergeError::Nothing));
    assert_eq!(
        merge(std::slice::from_ref(&a)),
        Err(MergeError::Missing(Batch { index: 1, count: 2 }))
    );
    assert_eq!(
        merge(&[a.clone(), a.clone(), b.clone()]),
        Err(MergeError::Twice(Batch { index: 0, count: 2 }))
    );
    let mut other_seed = b.clone();
    other_seed.settings.seed += 1;
    assert_eq!(
        merge(&[a.clone(), other_seed]),
        Err(MergeError::OtherSettings(Batch { index: 1, count: 2 }))
    );
    let third = batch(&world, 1, 3, 1);
    assert_eq!(
        merge(&[a.clone(), third]),
        Err(MergeError::OtherBatching(Batch { index: 1, count: 3 }, 2))
    );
    let mut cut = b.clone();
    cut.photons_traced -= 1;
    assert_eq!(
        merge(&[a.clone(), cut]),
        Err(MergeError::CutShort(Batch { index: 1, count: 2 }))
    );
    // The same batches against a scene with its light moved.
    let mut moved = strahl::scene::open("cornell", &Default::default()).unwrap();
    moved
        .move_named("light", Vec3::new(0.0, 0.0, 0.01))
        .unwrap();
    let moved = World::new(moved, AccelKind::Bvh).unwrap();
    assert_eq!(
        merge_light_batches(&moved, &[a, b]).map(|_| ()),
        Err(LightTraceError::Merge(MergeError::OtherScene(Batch {
            index: 0,
            count: 2
        })))
    );
}
