//! A scene's wavelength bands through a method that measures (the light model, the
//! radiosity solvers, the sensor tracers): each band group's scene solved on the world
//! relit with it, and the groups' channels read back as bands. The light model traces one
//! set of photon paths for the scene and all its band groups at once.

use super::run::{check_periodic, light_outcome, run};
use super::{Method, MethodError, Outcome};
use crate::light_model::trace_light_groups;
use crate::measure::{BandMeasurement, GroupMeasurement};
use crate::progress::{Cancel, ProgressListener};
use crate::world::World;
use std::sync::Arc;
use std::time::Instant;

/// Runs `method` on `world` as [`run`] does and, for a scene with wavelength bands and a
/// method that measures surfaces or sensors, its bands' figures too. The light model traces
/// the scene and every band group along the same photon paths (each path traced once, its
/// tallies kept per group); the other methods solve each band group after the scene (three
/// bands to a run: n bands cost ⌈n/3⌉ more runs, up to ⌈2n/3⌉ where the lights' spectra differ
/// in µmol per joule). The bands are `None` without bands, for methods that only render
/// images, and when `cancel` stopped a method other than the light model (whose bands, like
/// its RGB figures, are then scaled to the photons asked for).
pub fn run_with_bands(
    world: &Arc<World>,
    method: &Method,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<(Outcome, Option<BandMeasurement>), MethodError> {
    let measures = matches!(
        method,
        Method::LightTrace(_) | Method::Radiosity(_) | Method::SensorTrace(_)
    );
    let Some(spectral) = world.scene.spectral.as_ref().filter(|_| measures) else {
        return Ok((run(world, method, progress, cancel)?, None));
    };
    method.check()?;
    check_periodic(world, method)?;
    let groups = world.scene.band_groups().map_err(Box::new)?;
    let mut channels = Vec::with_capacity(groups.len());
    let mut relit = Vec::with_capacity(groups.len());
    for group in groups {
        channels.push(group.channels);
        relit.push(world.relit(group.scene)?);
    }
    let (outcome, band_outcomes) = match method {
        Method::LightTrace(settings) => {
            let start = Instant::now();
            progress.phase("photons");
            let worlds: Vec<&World> = std::iter::once(world.as_ref())
                .chain(relit.iter())
                .collect();
            let mut outcomes: Vec<Outcome> =
                trace_light_groups(&worlds, settings, progress, cancel)?
                    .into_iter()
                    .map(light_outcome)
                    .collect();
            let bands = outcomes.split_off(1);
            let mut outcome = outcomes.remove(0);
            outcome.seconds = start.elapsed().as_secs_f64();
            (outcome, bands)
        }
        _ => {
            let outcome = run(world, method, progress, cancel)?;
            let mut bands = Vec::with_capacity(relit.len());
            for w in relit {
                let band = run(&Arc::new(w), method, progress, cancel)?;
                if !band.complete {
                    return Ok((outcome, None));
                }
                bands.push(band);
            }
            (outcome, bands)
        }
    };
    let measured: Vec<GroupMeasurement<'_>> = channels
        .iter()
        .zip(&band_outcomes)
        .map(|(channels, outcome)| GroupMeasurement {
            channels,
            power: outcome.measurement.as_ref().map(|m| &m.power),
            sensors: outcome.sensors(),
        })
        .collect();
    let bands = BandMeasurement::new(spectral, &measured);
    Ok((outcome, Some(bands)))
}
