//! `strahl bench`: ray-query throughput of an accelerator on a defined ray set (camera rays
//! through pixel centres, or random rays in the scene bounds: `strahl::method::RaySet`),
//! printed as one JSON line so it can be compared with other ray tracing kernels. For a bare
//! mesh file the camera sits at the centre of the mesh bounds looking along +x with a 90°
//! vertical field of view.

use super::choice::choice;
use anyhow::{Context, Result, bail};
use clap::Args;
use serde::Serialize;
use strahl::method::{AccelKind, Choice, QueryTiming, RaySet, World, bench_rays};

/// Arguments of `strahl bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Scene: a built-in name, a .toml scene file or a mesh file.
    pub scene: String,
    /// Ray set.
    #[arg(long, value_parser = choice::<RaySet>(), default_value_t = RaySet::Primary)]
    pub rays: RaySet,
    /// Accelerator.
    #[arg(long, value_parser = choice::<AccelKind>(), default_value_t = AccelKind::Bvh)]
    pub accel: AccelKind,
    /// Worker threads.
    #[arg(long, default_value_t = 1)]
    pub threads: usize,
    /// Repetitions of each query pass; the fastest is reported (at most 1000).
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=i64::from(super::limits::MAX_REPEATS)))]
    pub repeat: u32,
    /// The memory bound.
    #[command(flatten)]
    pub memory: super::limits::MemoryArgs,
}

/// The JSON line `strahl bench` prints.
#[derive(Serialize)]
struct BenchResult<'a> {
    scene: &'a str,
    accel: &'static str,
    threads: usize,
    rays: &'static str,
    ray_count: usize,
    primitives: usize,
    build_seconds: f64,
    closest_hit: QueryTiming,
    any_hit: QueryTiming,
}

/// Runs `strahl bench`.
pub fn run(args: &BenchArgs) -> Result<()> {
    if args.threads == 0 {
        bail!("--threads must be at least 1");
    }
    let scene = strahl::scene::open(&args.scene, &strahl::scene::LoadOptions::default())?;
    let world = World::new(scene, args.accel).with_context(|| format!("scene '{}'", args.scene))?;
    let threads = rayon::current_num_threads();
    let bench = bench_rays(&world, args.rays, args.repeat)?;
    let result = BenchResult {
        scene: &args.scene,
        accel: args.accel.name(),
        threads,
        rays: args.rays.name(),
        ray_count: bench.ray_count,
        primitives: world.accel_stats().primitives,
        build_seconds: world.build_seconds(),
        closest_hit: bench.closest_hit,
        any_hit: bench.any_hit,
    };
    println!("{}", serde_json::to_string(&result)?);
    Ok(())
}
