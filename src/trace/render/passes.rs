//! Progressive rendering for Monte Carlo integrators: the whole image is rendered in passes
//! of a few samples per pixel, accumulated into the film. A time limit stops after the last
//! pass that fits, and cancellation (Ctrl-C) keeps every finished pass.
//!
//! Sample `k` of pixel `p` draws its numbers from the Owen-scrambled Sobol point `k` of the
//! pixel's stream (the first two dimensions place it in the pixel, the integrator uses the
//! rest), and each pixel's samples are summed exactly (`sums.rs`), so the image depends
//! neither on the thread count nor on how the samples were split into passes — nor into
//! batches rendered apart ([`render_samples`]) whose sums are added afterwards.

use super::super::Integrator;
use super::sums::{PixelSum, PixelSums};
use crate::color::Rgb;
use crate::geometry::Ray;
use crate::measure::Film;
use crate::progress::{Cancel, ProgressListener};
use crate::sampling::{Sampler, SequenceKind};
use crate::world::World;
use rayon::prelude::*;
use std::ops::Range;
use std::time::{Duration, Instant};

/// Pixel rows per parallel work item.
const STRIP_ROWS: usize = 4;
/// Camera samples handed to the integrator at once.
const BATCH: usize = 64;
/// Largest number of samples per pixel in one pass.
const MAX_PASS_SAMPLES: u32 = 8;

/// Settings of a progressive render.
#[derive(Clone, Debug)]
pub struct ProgressiveSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples (paths) per pixel to render when not stopped earlier.
    pub samples_per_pixel: u32,
    /// Seed of all random numbers.
    pub seed: u64,
    /// Wall-clock budget: no pass is started that is not expected to end within it, and a
    /// pass still running when it runs out is dropped (the first pass always completes).
    pub time_limit: Option<Duration>,
}

/// The result of a progressive render.
#[derive(Clone, Debug)]
pub struct ProgressiveOutput {
    /// Mean radiance per pixel over the finished passes (black when none finished).
    pub film: Film,
    /// Samples per pixel in `film`.
    pub samples_per_pixel: u32,
    /// Passes finished.
    pub passes: u32,
    /// True when all requested samples were rendered.
    pub complete: bool,
}

/// Samples of every pixel rendered in passes ([`render_samples`]).
#[derive(Clone, Debug)]
pub struct RenderedSamples {
    /// The radiance of the finished passes' samples summed per pixel.
    pub sums: PixelSums,
    /// Passes finished.
    pub passes: u32,
}

/// Samples per pixel of pass `index` (counted from 0): 1, 1, 2, 4, 8, 8, … so that a time
/// limit gets an image early and later passes amortise their overhead.
fn pass_samples(index: u32) -> u32 {
    match index {
        0 => 1,
        i => (1u32 << (i - 1).min(3)).min(MAX_PASS_SAMPLES),
    }
}

/// What tracing one camera sample needs.
struct SampleTracer<'a> {
    world: &'a World,
    integrator: &'a dyn Integrator,
    camera: crate::scene::CameraRays,
    seed: u64,
    width: u32,
}

impl SampleTracer<'_> {
    /// Adds samples `first..first + count` of every pixel of `pixels` (row-major from pixel
    /// index `start`) to its sum, tracing them [`BATCH`] at a time.
    fn add_samples(&self, pixels: &mut [PixelSum], start: usize, first: u32, count: u32) {
        let w = self.width as usize;
        let samples: Vec<(usize, u32)> = (0..pixels.len())
            .flat_map(|i| (first..first + count).map(move |k| (i, k)))
            .collect();
        let mut radiance = [Rgb::BLACK; BATCH];
        for batch in samples.chunks(BATCH) {
            let (rays, mut samplers): (Vec<Ray>, Vec<Sampler>) = batch
                .iter()
                .map(|&(i, k)| {
                    // A pixel's index in the image is its sampler stream.
                    let pixel = start + i;
                    let mut sampler = Sampler::new(SequenceKind::Sobol, self.seed, pixel as u64, k);
                    let jitter = sampler.next_2d();
                    let (px, py) = ((pixel % w) as f32, (pixel / w) as f32);
                    (self.camera.ray(px + jitter.x, py + jitter.y), sampler)
                })
                .unzip();
            let out = &mut radiance[..batch.len()];
            self.integrator
                .radiance_batch(self.world, &rays, &mut samplers, out);
            for (&(i, _), &c) in batch.iter().zip(out.iter()) {
                // A NaN or infinite sample would poison the pixel; drop it.
                if c.is_finite() {
                    pixels[i].add(c);
                }
            }
        }
    }
}

/// Renders the camera view of `world` with `integrator` progressively. `None` when the
/// camera is degenerate.
pub fn render_progressive(
    world: &World,
    integrator: &dyn Integrator,
    settings: &ProgressiveSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Option<ProgressiveOutput> {
    let target = settings.samples_per_pixel.max(1);
    let rendered = render_samples(world, integrator, settings, 0..target, progress, cancel)?;
    let done = rendered.sums.samples();
    Some(ProgressiveOutput {
        film: rendered.sums.film()?,
        samples_per_pixel: done,
        passes: rendered.passes,
        complete: done == target,
    })
}

/// Renders samples `samples` (sample indices, the same for every pixel) of the camera view
/// of `world` with `integrator` in passes, each sample exactly as [`render_progressive`]
/// renders it, and keeps their sums: the sums of any split of `0..N` into ranges, added,
/// are those of `0..N` bit for bit. `settings` gives the size, seed and time limit (its
/// `samples_per_pixel` is not read). Progress is counted in samples; cancelling or the time
/// limit keeps the finished passes. `None` when the camera is degenerate.
pub fn render_samples(
    world: &World,
    integrator: &dyn Integrator,
    settings: &ProgressiveSettings,
    samples: Range<u32>,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Option<RenderedSamples> {
    let camera = world
        .scene
        .camera
        .with_resolution(settings.width, settings.height)
        .rays()?;
    let (w, h) = (settings.width, settings.height);
    let tracer = SampleTracer {
        world,
        integrator,
        camera,
        seed: settings.seed,
        width: w,
    };
    let start = Instant::now();
    let deadline = settings
        .time_limit
        .and_then(|limit| start.checked_add(limit));
    let target = samples.end.saturating_sub(samples.start);
    // The sums of the finished passes, and those with the current pass: a pass cut short
    // is dropped. Each strip copies its sums before adding the pass, while they are in cache.
    let mut sums = vec![PixelSum::default(); w as usize * h as usize];
    let mut next = sums.clone();
    let strip = w as usize * STRIP_ROWS;
    let mut done = 0u32;
    let mut passes = 0u32;
    let mut last_pass_seconds_per_sample = 0.0f64;
    progress.start(u64::from(w) * u64::from(h) * u64::from(target));
    while done < target && !cancel.is_requested() {
        let count = pass_samples(passes).min(target - done);
        if let Some(deadline) = deadline {
            let expected = Duration::from_secs_f64(last_pass_seconds_per_sample * count as f64);
            if passes > 0 && Instant::now() + expected > deadline {
                break;
            }
        }
        let pass_start = Instant::now();
        let first = passes == 0;
        let stop =
            |now: Instant| cancel.is_requested() || (!first && deadline.is_some_and(|d| now > d));
        let finished = next
            .par_chunks_mut(strip)
            .zip(sums.par_chunks(strip))
            .enumerate()
            .all(|(index, (pixels, before))| {
                if stop(Instant::now()) {
                    return false;
                }
                pixels.copy_from_slice(before);
                tracer.add_samples(pixels, index * strip, samples.start + done, count);
                progress.advance(pixels.len() as u64 * u64::from(count));
                true
            });
        if !finished {
            break;
        }
        std::mem::swap(&mut sums, &mut next);
        done += count;
        passes += 1;
        last_pass_seconds_per_sample = pass_start.elapsed().as_secs_f64() / count as f64;
    }
    progress.finish();
    Some(RenderedSamples {
        sums: PixelSums::from_sums(w, h, done, sums)?,
        passes,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pass_sizes_grow_to_the_cap() {
        let sizes: Vec<u32> = (0..7).map(pass_samples).collect();
        assert_eq!(sizes, [1, 1, 2, 4, 8, 8, 8]);
    }
}
