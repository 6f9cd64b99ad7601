//! A run's parts: for a scene with wavelength bands, each band group's scene solved on the
//! world relit with it and the groups' channels read back as bands; for a scene with a day of
//! sun and sky states, each state's scene solved the same way. The light model traces one set
//! of photon paths for the scene and all its parts at once; the other methods that measure
//! (the radiosity solvers, the sensor tracers) solve each part after the scene.

use super::run::{check_periodic, light_outcome, run};
use super::{Method, MethodError, Outcome};
use crate::light_model::trace_light_groups;
use crate::measure::{BandMeasurement, ChannelErrors, GroupMeasurement, StateMeasurement};
use crate::progress::{Cancel, ProgressListener};
use crate::world::World;
use std::sync::Arc;
use std::time::Instant;

/// What a run measured of its scene's parts.
#[derive(Clone, Debug, Default)]
pub struct Parts {
    /// The figures of the scene's wavelength bands (`None` without bands).
    pub bands: Option<BandMeasurement>,
    /// The figures of each state of the scene's day, in order (empty without a day).
    pub states: Vec<StateMeasurement>,
}

/// Runs `method` on `world` as [`run`] does and, for a method that measures surfaces or
/// sensors, the scene's parts: its wavelength bands' figures (three band channels to a band
/// group, up to ⌈2n/3⌉ groups where the lights' spectra differ in µmol per joule) and each state of
/// its day alone. The light model traces the scene and every part along the same photon
/// paths (each path traced once, its tallies kept per part) unless a part has emitting
/// surfaces; the other methods solve each part after the scene. The parts are empty for
/// methods that only render images, and when `cancel` stopped a method other than the light
/// model (whose parts, like its own figures, are then scaled to the photons asked for).
pub fn run_with_parts(
    world: &Arc<World>,
    method: &Method,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<(Outcome, Parts), MethodError> {
    let measures = matches!(
        method,
        Method::LightTrace(_)
            | Method::SurfaceTrace(_)
            | Method::Radiosity(_)
            | Method::SensorTrace(_)
    );
    let scene = &world.scene;
    let spectral = scene.spectral.as_ref().filter(|_| measures);
    let day = scene.day.as_ref().filter(|_| measures);
    if spectral.is_none() && day.is_none() {
        return Ok((run(world, method, progress, cancel)?, Parts::default()));
    }
    method.check()?;
    check_periodic(world, method)?;
    let mut channels = Vec::new();
    let mut relit = Vec::new();
    if spectral.is_some() {
        for group in scene.band_groups().map_err(Box::new)? {
            channels.push(group.channels);
            relit.push(world.relit(group.scene)?);
        }
    }
    let states = day.map_or(&[][..], |d| &d.states[..]);
    for state in 0..states.len() {
        if let Some(state_scene) = scene.state_scene(state) {
            relit.push(world.relit(state_scene)?);
        }
    }
    // The light model traces every part along the same photon paths unless a part has
    // emitting surfaces (whose photons' power is not their source's times one number).
    let together = matches!(method, Method::LightTrace(_))
        && std::iter::once(world.as_ref())
            .chain(&relit)
            .all(|w| w.lights.area.is_empty());
    let (outcome, parts) = run_parts(world, method, relit, together, progress, cancel)?;
    let Some(parts) = parts else {
        return Ok((outcome, Parts::default()));
    };
    let (band_outcomes, state_outcomes) = parts.split_at(channels.len());
    let bands = spectral.map(|spectral| {
        let measured: Vec<GroupMeasurement<'_>> = channels
            .iter()
            .zip(band_outcomes)
            .map(|(channels, outcome)| GroupMeasurement {
                channels,
                power: outcome.measurement.as_ref().map(|m| &m.power),
                sensors: outcome.sensors(),
            })
            .collect();
        let errors = if together {
            ChannelErrors::Independent
        } else {
            ChannelErrors::Correlated
        };
        BandMeasurement::new(spectral, &measured, errors)
    });
    let states = states
        .iter()
        .zip(state_outcomes)
        .map(|(state, outcome)| StateMeasurement {
            time: state.time.clone(),
            power: outcome.measurement.as_ref().map(|m| m.power.clone()),
            sensors: outcome.sensors().to_vec(),
        })
        .collect();
    Ok((outcome, Parts { bands, states }))
}

/// `method` on `world` and on each of the worlds `parts` (relit from it): the light model
/// along one set of photon paths when `together`, else one run after
/// another, the scene's outcome then counting the parts' seconds and rays too (its stats
/// with `seconds_parts`, theirs alone). The parts' outcomes are `None` when a method other than the light model was
/// stopped before they were all complete.
fn run_parts(
    world: &Arc<World>,
    method: &Method,
    parts: Vec<World>,
    together: bool,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<(Outcome, Option<Vec<Outcome>>), MethodError> {
    match method {
        Method::LightTrace(settings) if together => {
            let start = Instant::now();
            progress.phase("photons");
            let worlds: Vec<&World> = std::iter::once(world.as_ref()).chain(&parts).collect();
            let mut outcomes: Vec<Outcome> =
                trace_light_groups(&worlds, settings, progress, cancel)?
                    .into_iter()
                    .map(light_outcome)
                    .collect();
            let rest = outcomes.split_off(1);
            let mut outcome = outcomes.remove(0);
            outcome.seconds = start.elapsed().as_secs_f64();
            Ok((outcome, Some(rest)))
        }
        _ => {
            let mut outcome = run(world, method, progress, cancel)?;
            let light_model = matches!(method, Method::LightTrace(_));
            let mut outcomes = Vec::with_capacity(parts.len());
            for part in parts {
                let part = run(&Arc::new(part), method, progress, cancel)?;
                // The run's time and rays are the scene's and its parts' together; the parts'
                // seconds also on their own.
                outcome.seconds += part.seconds;
                if let (Some(m), Some(p)) = (&mut outcome.measurement, &part.measurement) {
                    m.stats.seconds += p.stats.seconds;
                    m.stats.rays += p.stats.rays;
                    let parts_seconds = m.stats.extra.get("seconds_parts").and_then(|v| v.as_f64());
                    m.stats.insert(
                        "seconds_parts",
                        parts_seconds.unwrap_or(0.0) + p.stats.seconds,
                    );
                }
                if !part.complete && !light_model {
                    return Ok((outcome, None));
                }
                outcomes.push(part);
            }
            Ok((outcome, Some(outcomes)))
        }
    }
}
