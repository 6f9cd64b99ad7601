//! Ray-query throughput of a world's accelerator on a defined ray set, so that it can be
//! compared with other ray tracing kernels (`strahl bench`).
//!
//! Ray sets (reproducible by any kernel):
//! - `primary`: a pinhole image [`PRIMARY_WIDTH`] pixels wide (height by the camera's
//!   aspect) from the scene camera, one ray through each pixel centre, traced tile by tile
//!   (16 × 16 pixels) as the renderer does;
//! - `random`: [`RANDOM_RAYS`] rays with origins uniform in the scene bounds and directions
//!   uniform on the sphere, from a fixed seed.

use super::World;
use crate::geometry::Ray;
use crate::sampling::warp::uniform_sphere;
use crate::sampling::{Sampler, SequenceKind};
use glam::Vec3;
use rayon::prelude::*;
use serde::Serialize;
use std::time::Instant;

/// Width of the primary-ray image, pixels.
pub const PRIMARY_WIDTH: u32 = 1024;
/// Side of the square tiles primary rays are traced in, pixels.
const TILE: u32 = 16;
/// Number of random rays.
pub const RANDOM_RAYS: usize = 1 << 20;

/// Which rays to trace.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RaySet {
    /// Camera rays through pixel centres.
    Primary,
    /// Uniform random rays inside the scene bounds.
    Random,
}

crate::choice::named_values!(RaySet {
    RaySet::Primary = "primary", "Camera rays through pixel centres";
    RaySet::Random = "random", "Uniform random rays inside the scene bounds";
});

/// Why a ray set cannot be made.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RaySetError {
    /// The camera makes no rays.
    #[error("the camera is degenerate")]
    DegenerateCamera,
    /// There is nothing bounded to put random rays in.
    #[error("the scene has no bounded geometry")]
    Unbounded,
}

/// The timing of one kind of query over a ray set: the fastest of the repetitions.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct QueryTiming {
    /// Wall-clock seconds of the fastest pass.
    pub seconds: f64,
    /// Millions of rays per second in it.
    pub mrays_per_second: f64,
    /// Rays that hit something.
    pub hits: usize,
}

/// Closest-hit and any-hit throughput over one ray set.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RayBench {
    /// Rays in the set.
    pub ray_count: usize,
    /// Closest-hit queries.
    pub closest_hit: QueryTiming,
    /// Any-hit (occlusion) queries.
    pub any_hit: QueryTiming,
}

/// The rays of `set` for `world`.
pub fn ray_set(world: &World, set: RaySet) -> Result<Vec<Ray>, RaySetError> {
    Ok(match set {
        RaySet::Primary => {
            let cam = &world.scene.camera;
            let height = ((PRIMARY_WIDTH as f32 * cam.height as f32 / cam.width as f32).round()
                as u32)
                .max(1);
            let rays = cam
                .with_resolution(PRIMARY_WIDTH, height)
                .rays()
                .ok_or(RaySetError::DegenerateCamera)?;
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
                return Err(RaySetError::Unbounded);
            }
            let mut s = Sampler::new(SequenceKind::Random, 0x5eed, 0, 0);
            (0..RANDOM_RAYS)
                .map(|_| {
                    let u = Vec3::new(s.next_1d(), s.next_1d(), s.next_1d());
                    let origin = b.min + u * b.extent();
                    Ray::new(origin, uniform_sphere(s.next_2d()))
                })
                .collect()
        }
    })
}

/// Times closest-hit and any-hit queries of `world` over the rays of `set`, each the
/// fastest of `repeat` passes, in the current rayon pool.
pub fn bench_rays(world: &World, set: RaySet, repeat: u32) -> Result<RayBench, RaySetError> {
    let rays = ray_set(world, set)?;
    Ok(RayBench {
        ray_count: rays.len(),
        closest_hit: time_queries(&rays, repeat, |r| {
            world.closest_hit(r, f32::INFINITY).is_some()
        }),
        any_hit: time_queries(&rays, repeat, |r| world.occluded(r, f32::INFINITY)),
    })
}

/// The fastest of `repeat` passes of `query` over `rays`.
fn time_queries(rays: &[Ray], repeat: u32, query: impl Fn(&Ray) -> bool + Sync) -> QueryTiming {
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
    QueryTiming {
        seconds: best,
        mrays_per_second: rays.len() as f64 / best / 1e6,
        hits,
    }
}
