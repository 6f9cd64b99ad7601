//! `strahl bench`: ray-query throughput of an accelerator on a defined ray set, printed as
//! one JSON line so it can be compared with other ray tracing kernels.
//!
//! Ray sets (reproducible by any kernel):
//! - `primary`: a pinhole image 1024 pixels wide (height by the camera's aspect) from the
//!   scene camera, one ray through each pixel centre; for a bare mesh file the camera sits at
//!   the centre of the mesh bounds looking along +x with a 90° vertical field of view. Rays
//!   are traced tile by tile (16 × 16 pixels), as the renderer does;
//! - `random`: 2²⁰ rays with origins uniform in the scene bounds and directions uniform on
//!   the sphere, from a fixed seed.

use super::choice::choice;
use super::{source, with_threads};
use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use rayon::prelude::*;
use serde::Serialize;
use std::time::Instant;
use strahl::accel::AccelKind;
use strahl::choice::Choice;
use strahl::geometry::Ray;
use strahl::sampling::warp::uniform_sphere;
use strahl::sampling::{Sampler, SequenceKind};
use strahl::world::World;

/// Width of the primary-ray image.
pub const PRIMARY_WIDTH: u32 = 1024;
/// Side of the square tiles primary rays are traced in.
const TILE: u32 = 16;
/// Number of random rays.
pub const RANDOM_RAYS: usize = 1 << 20;

/// Which rays to trace.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RaySet {
    /// Camera rays through pixel centres.
    Primary,
    /// Uniform random rays inside the scene bounds.
    Random,
}

/// Arguments of `strahl bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Scene: a built-in name, a .toml scene file or a mesh file.
    pub scene: String,
    /// Ray set.
    #[arg(long, value_enum, default_value_t = RaySet::Primary)]
    pub rays: RaySet,
    /// Accelerator.
    #[arg(long, value_parser = choice::<AccelKind>(), default_value_t = AccelKind::Bvh)]
    pub accel: AccelKind,
    /// Worker threads.
    #[arg(long, default_value_t = 1)]
    pub threads: usize,
    /// Repetitions of each query pass; the fastest is reported.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..))]
    pub repeat: u32,
}

#[derive(Serialize)]
struct QueryResult {
    seconds: f64,
    mrays_per_second: f64,
    hits: usize,
}

#[derive(Serialize)]
struct BenchResult<'a> {
    scene: &'a str,
    accel: &'static str,
    threads: usize,
    rays: RaySet,
    ray_count: usize,
    primitives: usize,
    build_seconds: f64,
    closest_hit: QueryResult,
    any_hit: QueryResult,
}

/// The rays of `set` for `world`.
pub fn ray_set(world: &World, set: RaySet) -> Result<Vec<Ray>> {
    Ok(match set {
        RaySet::Primary => {
            let cam = &world.scene.camera;
            let height = ((PRIMARY_WIDTH as f32 * cam.height as f32 / cam.width as f32).round()
                as u32)
                .max(1);
            let rays = cam
                .with_resolution(PRIMARY_WIDTH, height)
                .rays()
                .context("the camera is degenerate")?;
            let tiles_x = PRIMARY_WIDTH.div_ceil(TILE);
            (0..height.div_ceil(TILE) * tiles_x)
                .flat_map(|tile| {
                    let (x0, y0) = (tile % tiles_x * TILE, tile / tiles_x * TILE);
                    (y0..(y0 + TILE).min(height)).flat_map(move |y| {
                        (x0..(x0 + TILE).min(PRIMARY_WIDTH)).map(move |x| (x, y))
                    })
                })
                .map(|(x, y)| rays.ray(x as f32 + 0.5, y as f32 + 0.5))
                .collect()
        }
        RaySet::Random => {
            let b = world.geometry.bounds();
            if b.is_empty() {
                bail!("the scene has no bounded geometry");
            }
            let mut s = Sampler::new(SequenceKind::Random, 0x5eed, 0, 0);
            (0..RANDOM_RAYS)
                .map(|_| {
                    let u = glam::Vec3::new(s.next_1d(), s.next_1d(), s.next_1d());
                    let origin = b.min + u * b.extent();
                    Ray::new(origin, uniform_sphere(s.next_2d()))
                })
                .collect()
        }
    })
}

fn time_queries(rays: &[Ray], repeat: u32, query: impl Fn(&Ray) -> bool + Sync) -> QueryResult {
    let mut best = f64::INFINITY;
    let mut hits = 0;
    for _ in 0..repeat.max(1) {
        let start = Instant::now();
        hits = rays
            .par_chunks(4096)
            .map(|c| c.iter().filter(|r| query(r)).count())
            .sum();
        best = best.min(start.elapsed().as_secs_f64());
    }
    QueryResult {
        seconds: best,
        mrays_per_second: rays.len() as f64 / best / 1e6,
        hits,
    }
}

/// Runs `strahl bench`.
pub fn run(args: &BenchArgs) -> Result<()> {
    if args.threads == 0 {
        bail!("--threads must be at least 1");
    }
    let scene = source::load(&args.scene, &strahl::scene::LoadOptions::default())?;
    let world = World::new(scene, args.accel).with_context(|| format!("scene '{}'", args.scene))?;
    let rays = ray_set(&world, args.rays)?;
    let (closest, any) = with_threads(args.threads, || {
        let closest = time_queries(&rays, args.repeat, |r| {
            world.closest_hit(r, f32::INFINITY).is_some()
        });
        let any = time_queries(&rays, args.repeat, |r| world.occluded(r, f32::INFINITY));
        (closest, any)
    })?;
    let result = BenchResult {
        scene: &args.scene,
        accel: args.accel.name(),
        threads: args.threads,
        rays: args.rays,
        ray_count: rays.len(),
        primitives: world.accel_stats().primitives,
        build_seconds: world.build_seconds(),
        closest_hit: closest,
        any_hit: any,
    };
    println!("{}", serde_json::to_string(&result)?);
    Ok(())
}
