//! A path-traced image split into batches of its samples per pixel that render apart —
//! other processes, a cluster's job array — and merge into the image one run gives, bit for
//! bit: every pixel's samples are summed in fixed point (`trace::PixelSums`), so the sums
//! of the batches added are the single run's sums.

use super::run::{check_periodic, empty, path_tracer};
use super::{Method, MethodError, Outcome, PathTraceSettings};
use crate::choice::Choice;
use crate::progress::{Cancel, ProgressListener};
use crate::sampling::{Batch, BatchPart, MergeError, check_batches};
use crate::trace::{PixelSums, render_samples};
use crate::world::World;
use std::time::Instant;

/// What the batches of one render must share besides the scene: the method and every
/// setting that changes a sample's value (not the time limit, which only stops a batch).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct RenderBatchSettings {
    /// The method, by the name the command line gives it (`pathtrace`).
    pub method: String,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Samples (paths) per pixel of the whole render, not of the batch.
    pub samples_per_pixel: u32,
    /// Seed of all random numbers.
    pub seed: u64,
    /// Most scattering events per path.
    pub max_depth: u32,
    /// Paths branching from the first hit of each camera ray.
    pub first_hit_paths: u32,
}

impl RenderBatchSettings {
    /// The settings of path tracing `s` at `width × height` pixels.
    fn path_trace(s: &PathTraceSettings, (width, height): (u32, u32)) -> Self {
        RenderBatchSettings {
            method: super::MethodKind::PathTrace.name().to_string(),
            width,
            height,
            samples_per_pixel: s.samples_per_pixel,
            seed: s.seed,
            max_depth: s.max_depth,
            first_hit_paths: s.first_hit_paths,
        }
    }
}

/// What a batch of a render leaves for the merge ([`run_render_batch`]): the scene's
/// digest, the settings, which batch, and the exact per-pixel sums of its samples.
/// Serializable (the sums as one string of packed integers, a few bytes per channel), so
/// that batches rendered elsewhere come back as files or bytes.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct RenderPartial {
    /// [`crate::scene::Scene::digest`] of the scene rendered, in hex.
    pub scene_digest: String,
    /// The render's settings.
    pub settings: RenderBatchSettings,
    /// Which batch.
    pub batch: Batch,
    /// Seconds the batch took.
    pub seconds: f64,
    sums: PixelSums,
}

impl RenderPartial {
    /// Samples per pixel the batch rendered (fewer than its share when it was stopped).
    pub fn samples_per_pixel(&self) -> u32 {
        self.sums.samples()
    }
}

/// Batch `batch` of the render `method` (path tracing; other methods refuse) of `world`:
/// samples `index·spp/count .. (index + 1)·spp/count` of every pixel, each exactly as
/// [`super::run`] renders it, summed for [`merge_render_batches`]. `progress` hears phase
/// `rendering` and the batch's samples; `cancel` or the method's time limit stop it after
/// the last finished pass (the merge then refuses it as cut short).
pub fn run_render_batch(
    world: &World,
    method: &Method,
    batch: Batch,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<RenderPartial, MethodError> {
    method.check()?;
    let Method::PathTrace(s) = method else {
        return Err(MethodError::NotInBatches(method.kind().name()));
    };
    check_periodic(world, method)?;
    let share = batch.share(u64::from(s.samples_per_pixel))?;
    // Within `0..samples_per_pixel`, so within `u32`.
    let samples = share.start as u32..share.end as u32;
    let start = Instant::now();
    let (integrator, settings) = path_tracer(world, s)?;
    progress.phase("rendering");
    let rendered = render_samples(world, &integrator, &settings, samples, progress, cancel)
        .ok_or(MethodError::DegenerateCamera)?;
    Ok(RenderPartial {
        scene_digest: format!("{:016x}", world.scene.digest()),
        settings: RenderBatchSettings::path_trace(s, (settings.width, settings.height)),
        batch,
        seconds: start.elapsed().as_secs_f64(),
        sums: rendered.sums,
    })
}

/// The image of the whole render from the `partials` of all its batches, each once and
/// whole, rendered on this `world`'s scene with the same settings: the image [`super::run`]
/// makes with those settings, bit for bit (linear radiance, W·sr⁻¹·m⁻²), its seconds the
/// batches' sum. Refuses partials that do not make one render ([`MergeError`]).
pub fn merge_render_batches(
    world: &World,
    partials: &[RenderPartial],
) -> Result<Outcome, MethodError> {
    let digest = format!("{:016x}", world.scene.digest());
    check_batches(
        &digest,
        partials.iter().map(|p| BatchPart {
            scene_digest: &p.scene_digest,
            settings: &p.settings,
            batch: p.batch,
            done: u64::from(p.sums.samples()),
            total: u64::from(p.settings.samples_per_pixel),
        }),
    )?;
    let first = &partials[0];
    let mut sums = PixelSums::new(first.settings.width, first.settings.height);
    for p in partials {
        if !sums.add(&p.sums) {
            return Err(MergeError::Damaged(p.batch).into());
        }
    }
    let film = sums.film().ok_or(MergeError::Damaged(first.batch))?;
    Ok(Outcome {
        image: Some(film),
        summary: format!(
            "{} paths per pixel in {} batches",
            sums.samples(),
            partials.len()
        ),
        seconds: partials.iter().map(|p| p.seconds).sum(),
        ..empty()
    })
}
