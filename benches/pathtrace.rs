//! Path tracing speed: the built-in Cornell box at 48×48 pixels, 4 paths per pixel, depth
//! unbounded with Russian roulette from bounce 5, on the default rayon pool.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::sync::atomic::AtomicBool;
use strahl::accel::AccelKind;
use strahl::scene::builtin;
use strahl::trace::progressive::{ProgressiveSettings, render_progressive};
use strahl::trace::render::NoProgress;
use strahl::trace::{PathTracer, World};

fn cornell(c: &mut Criterion) {
    let scene = builtin::load("cornell")
        .expect("cornell is built in")
        .expect("cornell builds");
    let world = World::new(scene, AccelKind::Bvh).expect("cornell flattens");
    let tracer = PathTracer::new(&world, u32::MAX, 1);
    let settings = ProgressiveSettings {
        width: 48,
        height: 48,
        samples_per_pixel: 4,
        seed: 0,
        time_limit: None,
    };
    let cancel = AtomicBool::new(false);
    c.bench_function("pathtrace cornell 48x48 4spp", |b| {
        b.iter(|| {
            black_box(render_progressive(
                &world,
                &tracer,
                &settings,
                &NoProgress,
                &cancel,
            ))
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = cornell
}
criterion_main!(benches);
