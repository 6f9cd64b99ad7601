//! Antialiasing (seed 002 §4.2): one value per pixel from the rays through its pixel pyramid.
//!
//! - `none`: the ray through the pixel centre;
//! - `stochastic`: jittered `n × n` subpixels, one ray each, averaged (§4.2.1);
//! - `adaptive`: corners and centre, recursively subdivided where they differ (§4.2.2), up to
//!   depth 4. Samples sit on a fixed grid of [`ADAPTIVE_GRID`] units per pixel side and are
//!   cached, so no grid point is traced twice — not across pixels, rows or threads.

use super::super::Integrator;
use crate::color::Rgb;
use crate::sampling::warp::stratified;
use crate::sampling::{Sampler, SequenceKind, hash64};
use crate::scene::CameraRays;
use crate::world::World;
use std::collections::HashMap;
use std::sync::Mutex;

/// Antialiasing method.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AntialiasMode {
    /// One ray through each pixel centre.
    None,
    /// Jittered supersampling.
    #[default]
    Stochastic,
    /// Adaptive supersampling.
    Adaptive,
}

crate::choice::named_values!(AntialiasMode {
    AntialiasMode::None = "none", "One ray through each pixel centre";
    AntialiasMode::Stochastic = "stochastic", "Jittered n×n subpixels, one ray each";
    AntialiasMode::Adaptive = "adaptive", "Corners and centre, subdivided where they differ (depth 4)";
});

/// Maximum subdivision depth of adaptive supersampling.
pub const ADAPTIVE_MAX_DEPTH: u32 = 4;
/// Grid units per pixel side: the squares of the deepest level (side 2) still have an
/// integer centre.
pub const ADAPTIVE_GRID: u32 = 1 << ADAPTIVE_MAX_DEPTH;

/// What the image loop needs to trace camera samples.
pub struct SampleContext<'a> {
    /// The scene.
    pub world: &'a World,
    /// The integrator.
    pub integrator: &'a dyn Integrator,
    /// Camera ray generator.
    pub camera: CameraRays,
    /// Image seed.
    pub seed: u64,
    /// Sequence used by samplers.
    pub sequence: SequenceKind,
}

impl SampleContext<'_> {
    /// Radiance through image position `(x, y)` with the random numbers of `stream`/`index`.
    pub fn trace(&self, x: f32, y: f32, stream: u64, index: u32) -> Rgb {
        let mut sampler = Sampler::new(self.sequence, self.seed, stream, index);
        let c = self
            .integrator
            .radiance(self.world, &self.camera.ray(x, y), &mut sampler);
        // A NaN or infinite sample would poison the pixel; drop it.
        if c.is_finite() { c } else { Rgb::BLACK }
    }

    /// Pixel value with no antialiasing.
    pub fn centre(&self, px: u32, py: u32, width: u32) -> Rgb {
        self.trace(
            px as f32 + 0.5,
            py as f32 + 0.5,
            pixel_stream(px, py, width),
            0,
        )
    }

    /// Pixel value from `samples` camera samples: jittered `n × n` strata (n = ⌈√samples⌉)
    /// with the `Random` sequence, Sobol points with the `Sobol` sequence.
    pub fn stochastic(&self, px: u32, py: u32, width: u32, samples: u32) -> Rgb {
        let stream = pixel_stream(px, py, width);
        let count = stochastic_count(samples, self.sequence);
        let n = match self.sequence {
            SequenceKind::Random => (count as f32).sqrt() as u32,
            SequenceKind::Sobol => 1,
        };
        let mut sum = Rgb::BLACK;
        for k in 0..count {
            let mut jitter = Sampler::new(self.sequence, self.seed ^ 0x5eed, stream, k);
            let u = stratified(k % (n * n), n, jitter.next_2d());
            sum += self.trace(px as f32 + u.x, py as f32 + u.y, stream, k);
        }
        sum / count as f32
    }
}

/// Camera samples per pixel that stochastic antialiasing traces for a requested count:
/// rounded up to a square (`n × n` strata) with the `Random` sequence, exact with `Sobol`.
pub fn stochastic_count(samples: u32, sequence: SequenceKind) -> u32 {
    match sequence {
        SequenceKind::Random => {
            let n = (samples.max(1) as f32).sqrt().ceil() as u32;
            n * n
        }
        SequenceKind::Sobol => samples.max(1),
    }
}

/// The sampler stream of pixel `(px, py)`.
pub fn pixel_stream(px: u32, py: u32, width: u32) -> u64 {
    py as u64 * width as u64 + px as u64
}

/// Cache of adaptive samples keyed by grid point. Points on the horizontal lines shared
/// between work strips go to one cache shared by all threads; all others stay in the strip's
/// own cache.
pub struct AdaptiveCache<'a> {
    local: HashMap<(u32, u32), Rgb>,
    shared: &'a Mutex<HashMap<(u32, u32), Rgb>>,
    /// Grid rows that are strip boundaries are multiples of this.
    boundary_every: u32,
    /// Number of samples this cache traced.
    pub traced: u64,
}

impl<'a> AdaptiveCache<'a> {
    /// A cache for one strip of `strip_rows` pixel rows.
    pub fn new(shared: &'a Mutex<HashMap<(u32, u32), Rgb>>, strip_rows: u32) -> Self {
        AdaptiveCache {
            local: HashMap::new(),
            shared,
            boundary_every: strip_rows * ADAPTIVE_GRID,
            traced: 0,
        }
    }

    fn sample(&mut self, ctx: &SampleContext, gx: u32, gy: u32) -> Rgb {
        let trace = |traced: &mut u64| {
            *traced += 1;
            let g = ADAPTIVE_GRID as f32;
            let stream = hash64(((gy as u64) << 32 | gx as u64) ^ 0xada9_71fe);
            ctx.trace(gx as f32 / g, gy as f32 / g, stream, 0)
        };
        if gy.is_multiple_of(self.boundary_every) {
            let mut shared = self.shared.lock().unwrap_or_else(|e| e.into_inner());
            if let Some(&c) = shared.get(&(gx, gy)) {
                return c;
            }
            let c = trace(&mut self.traced);
            shared.insert((gx, gy), c);
            c
        } else {
            if let Some(&c) = self.local.get(&(gx, gy)) {
                return c;
            }
            let c = trace(&mut self.traced);
            self.local.insert((gx, gy), c);
            c
        }
    }

    /// Pixel value by adaptive supersampling, and how many squares were subdivided.
    pub fn pixel(&mut self, ctx: &SampleContext, px: u32, py: u32, threshold: f32) -> (Rgb, u32) {
        let mut subdivisions = 0;
        let c = self.square(
            ctx,
            px * ADAPTIVE_GRID,
            py * ADAPTIVE_GRID,
            ADAPTIVE_GRID,
            0,
            threshold,
            &mut subdivisions,
        );
        (c, subdivisions)
    }

    /// Mean over the square at grid point `(x0, y0)` with side `side`: the average of its four
    /// quarters, each the mean of its outer corner and the centre, or subdivided further when
    /// those two differ by more than `threshold`.
    #[allow(clippy::too_many_arguments)]
    fn square(
        &mut self,
        ctx: &SampleContext,
        x0: u32,
        y0: u32,
        side: u32,
        depth: u32,
        threshold: f32,
        subdivisions: &mut u32,
    ) -> Rgb {
        let half = side / 2;
        let centre = self.sample(ctx, x0 + half, y0 + half);
        let mut sum = Rgb::BLACK;
        for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let corner = self.sample(ctx, x0 + dx * side, y0 + dy * side);
            if depth + 1 >= ADAPTIVE_MAX_DEPTH || difference(corner, centre) < threshold {
                sum += (corner + centre) * 0.5;
            } else {
                *subdivisions += 1;
                sum += self.square(
                    ctx,
                    x0 + dx * half,
                    y0 + dy * half,
                    half,
                    depth + 1,
                    threshold,
                    subdivisions,
                );
            }
        }
        sum * 0.25
    }
}

/// Perceptual difference of two radiances: largest channel difference after `v / (1 + v)`.
fn difference(a: Rgb, b: Rgb) -> f32 {
    let m = |v: f32| v / (1.0 + v);
    (a.map(m) - b.map(m)).map(f32::abs).max_channel()
}
