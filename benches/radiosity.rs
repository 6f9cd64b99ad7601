//! Form factors per second on the Cornell box meshed 16 × 16 per root patch: the analytic
//! form factor with visibility (adaptive rays), with and without shaft culling, over a fixed
//! set of facing leaf pairs; the whole Cornell box solved to 1 % on a 32 × 32 mesh; and
//! the Cornell box solved again by hierarchical radiosity after its light moved, with the
//! patch links kept from the solve before and from scratch.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use std::sync::Arc;
use std::time::{Duration, Instant};
use strahl::accel::AccelKind;
use strahl::method::{KeptLinks, Method, RadiositySettings, run_keeping, solve_radiosity};
use strahl::progress::Cancel;
use strahl::progress::NoProgress;
use strahl::radiosity::solve::SolverKind;
use strahl::radiosity::{
    Facing, FormFactorOptions, MeshOptions, MeshSize, PatchId, PatchMesh, Side, VisRays,
    Visibility, VisibilityOptions, facing, form_factor,
};
use strahl::scene::builtin;
use strahl::world::World;

/// Facing leaf pairs taken at a fixed stride through all pairs.
const PAIRS: usize = 2000;

fn facing_pairs(mesh: &PatchMesh) -> Vec<(PatchId, PatchId)> {
    let leaves = mesh.leaves();
    let n = leaves.len();
    let stride = 7919; // prime, so the pairs spread over all root combinations
    (0..)
        .map(|k: usize| {
            let flat = k * stride % (n * n);
            (leaves[flat / n], leaves[flat % n])
        })
        .filter(|&(i, j)| {
            i != j && facing(mesh.patch(i), Side::Front, mesh.patch(j), Side::Front) != Facing::Away
        })
        .take(PAIRS)
        .collect()
}

fn bench(c: &mut Criterion) {
    let scene = builtin::load("cornell")
        .expect("built-in scene")
        .expect("valid scene");
    let mesh = PatchMesh::from_scene(
        &scene,
        &MeshOptions {
            segments: 16,
            size: MeshSize::Levels(4),
            ..MeshOptions::default()
        },
    )
    .expect("mesh");
    let world = Arc::new(World::new(scene, AccelKind::Bvh).expect("world"));
    let pairs = facing_pairs(&mesh);
    let ff = FormFactorOptions::default();
    let mut group = c.benchmark_group("radiosity");
    group.throughput(Throughput::Elements(pairs.len() as u64));
    group.sample_size(10);
    for (rays, culling) in [
        (VisRays::Adaptive, true),
        (VisRays::Adaptive, false),
        (VisRays::Fixed(16), true),
        (VisRays::Fixed(16), false),
    ] {
        let vis = Visibility::new(
            &world,
            VisibilityOptions {
                rays,
                shaft_culling: culling,
                seed: 1,
            },
            16,
        )
        .expect("the Cornell box has no curved shapes to facet");
        let cull = if culling { "shaft" } else { "bvh_only" };
        let name = format!("analytic_ff_with_visibility_{rays}_rays_{cull}");
        group.bench_function(&name, |b| {
            b.iter(|| {
                pairs
                    .iter()
                    .map(|&(i, j)| {
                        let f = form_factor(
                            mesh.patch(i),
                            Side::Front,
                            mesh.patch(j),
                            Side::Front,
                            &ff,
                        );
                        f * vis.between(&mesh, i, j)
                    })
                    .sum::<f64>()
            })
        });
    }
    group.bench_function("analytic_ff_only", |b| {
        b.iter(|| {
            pairs
                .iter()
                .map(|&(i, j)| {
                    form_factor(
                        black_box(mesh.patch(i)),
                        Side::Front,
                        mesh.patch(j),
                        Side::Front,
                        &ff,
                    )
                })
                .sum::<f64>()
        })
    });
    group.finish();
}

/// The Cornell box solved by progressive refinement until the unshot power is 1 % of the
/// emitted power: meshing, light links, form factors with visibility and shooting, timed as
/// one run. 16 × 16 patches per root face (`levels:4`) by default; the 32 × 32 mesh
/// (`levels:5`, minutes per run, so ten runs take long) with `STRAHL_BENCH_FULL=1`.
fn solve_cornell(c: &mut Criterion) {
    let full = std::env::var_os("STRAHL_BENCH_FULL").is_some();
    let (levels, name) = if full {
        (5, "cornell_32x32_progressive_to_1_percent")
    } else {
        (4, "cornell_16x16_progressive_to_1_percent")
    };
    let scene = builtin::load("cornell")
        .expect("built-in scene")
        .expect("valid scene");
    let world = Arc::new(World::new(scene, AccelKind::Bvh).expect("world"));
    let mut settings = RadiositySettings::new(SolverKind::Progressive);
    settings.system.mesh.size = MeshSize::Levels(levels);
    settings.shooting.tolerance = 0.01;
    let mut group = c.benchmark_group("radiosity_solve");
    group.sample_size(10);
    group.bench_function(name, |b| {
        b.iter(|| {
            let solved =
                solve_radiosity(&world, &settings, &NoProgress, &Cancel::new()).expect("solve");
            assert!(solved.solution.converged);
            black_box(solved.solution.radiosity.len())
        })
    });
    group.finish();
}

/// The Cornell box at the defaults solved again after its light moved 5 cm back and forth,
/// by hierarchical radiosity and the matrix solver, each solve taking the links of the one
/// before (`links_kept`: patch links, or couplings and the solution to start from), or none
/// (`from_scratch`, the same links computed anew; the same solution bit for bit, or within
/// the matrix solver's tolerance). What is timed is the solve: the merge of the links kept
/// after it is not (the viewer merges them once the solution is shown).
fn solve_after_a_move(c: &mut Criterion) {
    let scene = builtin::load("cornell")
        .expect("built-in scene")
        .expect("valid scene");
    let mut moved = scene.clone();
    moved
        .move_named("light", glam::Vec3::new(0.0, 0.0, 0.05))
        .expect("a light");
    let worlds: Vec<Arc<World>> = [scene, moved]
        .into_iter()
        .map(|s| Arc::new(World::new(s, AccelKind::Bvh).expect("world")))
        .collect();
    let mut group = c.benchmark_group("radiosity_after_a_move");
    group.sample_size(10);
    for solver in [SolverKind::Hierarchical, SolverKind::Matrix] {
        let method = Method::Radiosity(RadiositySettings::new(solver));
        for keep in [true, false] {
            let mut kept = KeptLinks::new();
            let mut turn = 0;
            let name = if keep { "links_kept" } else { "from_scratch" };
            group.bench_function(format!("{solver}/{name}"), |b| {
                // The links kept are merged before the clock starts, as the viewer merges
                // them after showing the solution (`KeptLinks::settle`).
                b.iter_custom(|iterations| {
                    let mut spent = Duration::ZERO;
                    for _ in 0..iterations {
                        turn += 1;
                        if !keep {
                            kept = KeptLinks::new();
                        }
                        kept.settle();
                        let world = &worlds[turn % 2];
                        let start = Instant::now();
                        let outcome =
                            run_keeping(world, &method, &NoProgress, &Cancel::new(), &mut kept)
                                .expect("solve");
                        spent += start.elapsed();
                        black_box(outcome.measurement.is_some());
                    }
                    spent
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench, solve_cornell, solve_after_a_move);
criterion_main!(benches);
