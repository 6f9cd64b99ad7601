//! Runs split into batches that run apart — other processes, a cluster's job array, Dask
//! workers — and merge into the outcome one run gives, bit for bit: the light model's photons
//! (its tallies are integers, so their sums do not depend on how the photons were split). A
//! path-traced image's batches are `render_batches.rs`'s.

use super::run::light_outcome;
use super::{Method, MethodError, Outcome};
use crate::choice::Choice;
use crate::light_model::{LightTracePartial, merge_light_batches, trace_light_batch};
use crate::progress::{Cancel, ProgressListener};
use crate::sampling::Batch;
use crate::world::World;

/// Batch `batch` of `method`'s run on `world` (the light model; other methods refuse, as do
/// scenes with wavelength bands): what [`merge_batches`] needs of it. `progress` hears the
/// batch's photons.
pub fn run_batch(
    world: &World,
    method: &Method,
    batch: Batch,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<LightTracePartial, MethodError> {
    method.check()?;
    let Method::LightTrace(settings) = method else {
        return Err(MethodError::NotInBatches(method.kind().name()));
    };
    if world.scene.spectral.is_some() {
        return Err(MethodError::BandsInBatches);
    }
    progress.phase("photons");
    Ok(trace_light_batch(world, settings, batch, progress, cancel)?)
}

/// The outcome of the whole run from the `partials` of all its batches, each once, traced on
/// this `world`'s scene with the same settings: the one run's outcome, but for the seconds
/// (the batches' sum).
pub fn merge_batches(
    world: &World,
    partials: &[LightTracePartial],
) -> Result<Outcome, MethodError> {
    Ok(light_outcome(merge_light_batches(world, partials)?))
}
