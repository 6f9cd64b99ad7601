//! The tile loop: the image split into tiles (strips with adaptive antialiasing) rendered on
//! all threads of the current rayon pool, progress reported per row, cancellation honoured
//! between tiles (what is done is kept).

use super::super::Integrator;
use super::antialias::{AdaptiveCache, AntialiasMode, SampleContext, stochastic_count};
use crate::color::Rgb;
use crate::measure::Film;
use crate::progress::{Cancel, ProgressListener};
use crate::sampling::SequenceKind;
use crate::world::World;
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

/// Side of the square tiles used without adaptive antialiasing.
const TILE: u32 = 32;
/// Pixel rows per strip with adaptive antialiasing (strips keep the row-to-row corner cache).
const ADAPTIVE_STRIP_ROWS: u32 = 8;

/// Settings of one image.
#[derive(Clone, Debug)]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Antialiasing method.
    pub antialias: AntialiasMode,
    /// Camera samples per pixel for stochastic antialiasing.
    pub samples_per_pixel: u32,
    /// Colour difference that makes adaptive antialiasing subdivide.
    pub adaptive_threshold: f32,
    /// Seed of all random numbers.
    pub seed: u64,
    /// Random sequence for samplers.
    pub sequence: SequenceKind,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            width: 512,
            height: 512,
            antialias: AntialiasMode::Stochastic,
            samples_per_pixel: 4,
            adaptive_threshold: 0.05,
            seed: 0,
            sequence: SequenceKind::Random,
        }
    }
}

/// A rendered image and what it took.
#[derive(Clone, Debug)]
pub struct RenderOutput {
    /// Linear radiance per pixel (black where cancelled before rendering).
    pub film: Film,
    /// Per pixel, how many squares adaptive antialiasing subdivided (all zero otherwise).
    pub subdivisions: Vec<u32>,
    /// Camera samples traced.
    pub samples_traced: u64,
    /// False when cancelled before every tile was done.
    pub complete: bool,
}

struct Tile {
    x0: u32,
    y0: u32,
    x1: u32,
    y1: u32,
}

struct TileResult {
    pixels: Vec<Rgb>,
    subdivisions: Vec<u32>,
}

/// Renders the camera view of `world` with `integrator`.
pub fn render(
    world: &World,
    integrator: &dyn Integrator,
    settings: &RenderSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Option<RenderOutput> {
    let camera = world
        .scene
        .camera
        .with_resolution(settings.width, settings.height)
        .rays()?;
    let ctx = SampleContext {
        world,
        integrator,
        camera,
        seed: settings.seed,
        sequence: settings.sequence,
    };
    let (w, h) = (settings.width, settings.height);
    let adaptive = settings.antialias == AntialiasMode::Adaptive;
    let tiles: Vec<Tile> = if adaptive {
        (0..h.div_ceil(ADAPTIVE_STRIP_ROWS))
            .map(|i| Tile {
                x0: 0,
                y0: i * ADAPTIVE_STRIP_ROWS,
                x1: w,
                y1: ((i + 1) * ADAPTIVE_STRIP_ROWS).min(h),
            })
            .collect()
    } else {
        (0..h.div_ceil(TILE))
            .flat_map(|ty| (0..w.div_ceil(TILE)).map(move |tx| (tx, ty)))
            .map(|(tx, ty)| Tile {
                x0: tx * TILE,
                y0: ty * TILE,
                x1: ((tx + 1) * TILE).min(w),
                y1: ((ty + 1) * TILE).min(h),
            })
            .collect()
    };
    let shared_cache = Mutex::new(HashMap::new());
    let traced = AtomicU64::new(0);
    progress.start(u64::from(w) * u64::from(h));
    let results: Vec<Option<TileResult>> = tiles
        .par_iter()
        .map(|tile| {
            if cancel.is_requested() {
                return None;
            }
            let n = ((tile.x1 - tile.x0) * (tile.y1 - tile.y0)) as usize;
            let mut out = TileResult {
                pixels: Vec::with_capacity(n),
                subdivisions: Vec::with_capacity(n),
            };
            let mut cache = AdaptiveCache::new(&shared_cache, ADAPTIVE_STRIP_ROWS);
            for py in tile.y0..tile.y1 {
                for px in tile.x0..tile.x1 {
                    // A pixel can take long at high sample counts: a stop request drops the
                    // unfinished tile rather than waiting for it.
                    if cancel.is_requested() {
                        return None;
                    }
                    let (c, subdivided) = match settings.antialias {
                        AntialiasMode::None => (ctx.centre(px, py, w), 0),
                        AntialiasMode::Stochastic => {
                            (ctx.stochastic(px, py, w, settings.samples_per_pixel), 0)
                        }
                        AntialiasMode::Adaptive => {
                            cache.pixel(&ctx, px, py, settings.adaptive_threshold)
                        }
                    };
                    out.pixels.push(c);
                    out.subdivisions.push(subdivided);
                }
                progress.advance(u64::from(tile.x1 - tile.x0));
            }
            let samples = match settings.antialias {
                AntialiasMode::None => n as u64,
                AntialiasMode::Stochastic => {
                    n as u64
                        * u64::from(stochastic_count(
                            settings.samples_per_pixel,
                            settings.sequence,
                        ))
                }
                AntialiasMode::Adaptive => cache.traced,
            };
            traced.fetch_add(samples, Ordering::Relaxed);
            Some(out)
        })
        .collect();
    progress.finish();
    let mut film = Film::new(w, h);
    let mut subdivisions = vec![0u32; w as usize * h as usize];
    let mut complete = true;
    for (tile, result) in tiles.iter().zip(results) {
        let Some(result) = result else {
            complete = false;
            continue;
        };
        let mut i = 0;
        for py in tile.y0..tile.y1 {
            for px in tile.x0..tile.x1 {
                film.set(px, py, result.pixels[i]);
                subdivisions[py as usize * w as usize + px as usize] = result.subdivisions[i];
                i += 1;
            }
        }
    }
    Some(RenderOutput {
        film,
        subdivisions,
        samples_traced: traced.into_inner(),
        complete,
    })
}
