//! The light model on the built-in `canopy` scene (10,000 small tilted leaves under a sky and
//! a sun), 100,000 photons per iteration (photons per second is the figure to read).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::light_model::LightTraceSettings;
use strahl::method::{Method, run};
use strahl::progress::{Cancel, NoProgress};
use strahl::scene::builtin;
use strahl::world::World;

fn light_model(c: &mut Criterion) {
    let canopy = builtin::load("canopy").expect("built-in").expect("valid");
    let world = Arc::new(World::new(canopy, AccelKind::Bvh).expect("valid scene"));
    let settings = LightTraceSettings {
        photons: 100_000,
        seed: 1,
        max_bounces: 1000,
    };
    let mut group = c.benchmark_group("light_model");
    group.sample_size(10);
    group.throughput(Throughput::Elements(settings.photons));
    group.bench_function("canopy_10000_leaves", |b| {
        let method = Method::LightTrace(settings.clone());
        b.iter(|| run(&world, &method, &NoProgress, &Cancel::new()).expect("lights"))
    });
    group.finish();
}

criterion_group!(benches, light_model);
criterion_main!(benches);
