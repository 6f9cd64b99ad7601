//! Path tracing speed: the built-in Cornell box at 48×48 pixels, 4 paths per pixel, depth
//! unbounded with Russian roulette from bounce 5, on the default rayon pool. With
//! `STRAHL_BENCH_FULL=1` also at the setting of the comparison with Mitsuba 3 (256×256, 64
//! paths per pixel; seconds per run).

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::method::{ImageSize, Method, PathTraceSettings, run};
use strahl::progress::{Cancel, NoProgress};
use strahl::scene::builtin;
use strahl::world::World;

fn cornell(c: &mut Criterion) {
    let scene = builtin::load("cornell")
        .expect("cornell is built in")
        .expect("cornell builds");
    let world = Arc::new(World::new(scene, AccelKind::Bvh).expect("cornell flattens"));
    let mut sizes = vec![(48, 4)];
    if std::env::var_os("STRAHL_BENCH_FULL").is_some() {
        sizes.push((256, 64));
    }
    let cancel = Cancel::new();
    for (size, spp) in sizes {
        let method = Method::PathTrace(PathTraceSettings {
            size: ImageSize {
                width: Some(size),
                height: Some(size),
            },
            samples_per_pixel: spp,
            ..PathTraceSettings::default()
        });
        let name = format!("pathtrace cornell {size}x{size} {spp}spp");
        c.bench_function(&name, |b| {
            b.iter(|| black_box(run(&world, &method, &NoProgress, &cancel).expect("renders")))
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = cornell
}
criterion_main!(benches);
