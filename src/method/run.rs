//! Running a method: the one entry point every front end calls.

use super::outcome::{Outcome, SolvedRadiosity};
use super::settings::{
    Antialias, FinalGatherSettings, ImageSize, LinkSelection, PathTraceSettings,
    RadiosityImageSettings, RadiositySettings, RayTraceSettings, SensorTraceSettings,
};
use super::{Method, MethodError, MethodKind};
use crate::choice::Choice;
use crate::light_model::{LightTraceOutput, LightTraceSettings, trace_light};
use crate::progress::{Cancel, ProgressListener};
use crate::radiosity::solve::hierarchical::{
    solve_hierarchical_keeping, solve_hierarchical_shooting,
};
use crate::radiosity::solve::{
    DisplaySettings, KeptLinks, LinkDisplay, RadiositySystem, SolveError, SolverKind,
    solve_matrix_keeping, solve_progressive,
};
use crate::sampling::SequenceKind;
use crate::scene::LightKind;
use crate::trace::{
    Integrator, PathTracer, ProgressiveSettings, RenderOutput, RenderSettings, SensorSettings,
    StandardRayTracer, SurfaceTraceSettings, render, render_progressive, sensor_readings,
    trace_surfaces,
};
use crate::world::World;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Runs `method` on `world` in the current rayon thread pool (install the run in a pool of
/// N threads to use N; the result is the same for any number). `progress` hears each phase
/// and its units of work, from several threads; `cancel`, set from any thread, stops the
/// work within one unit and keeps what is done (the outcome is then marked incomplete).
pub fn run(
    world: &Arc<World>,
    method: &Method,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<Outcome, MethodError> {
    run_with(world, method, progress, cancel, None)
}

/// [`run`] for a scene solved again and again as its objects move (the viewer): hierarchical
/// radiosity takes the patch links `kept` from the solve before wherever nothing moved
/// between their ends, and keeps this solve's for the next ([`KeptLinks`]); its outcome is
/// the same, bit for bit, as this call's with no links kept, in less time. The matrix
/// solver takes the couplings no move reached in the same way and starts its iteration from
/// the solution before: the same matrix entry for entry, the solution the same within the
/// solver's tolerance. Their rays are seeded by what the patches are rather than by their
/// indices, so they are as accurate as [`run`]'s and not the same bit for bit. The other
/// methods run as [`run`] runs them.
pub fn run_keeping(
    world: &Arc<World>,
    method: &Method,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
    kept: &mut KeptLinks,
) -> Result<Outcome, MethodError> {
    run_with(world, method, progress, cancel, Some(kept))
}

fn run_with(
    world: &Arc<World>,
    method: &Method,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
    kept: Option<&mut KeptLinks>,
) -> Result<Outcome, MethodError> {
    method.check()?;
    check_periodic(world, method)?;
    let start = Instant::now();
    let mut outcome = match method {
        Method::RayTrace(s) => ray_trace(world, s, progress, cancel)?,
        Method::PathTrace(s) => path_trace(world, s, progress, cancel)?,
        Method::RadiosityImage(s) => radiosity_image(world, s, progress, cancel)?,
        Method::FinalGather(s) => final_gather(world, s, progress, cancel)?,
        Method::SensorTrace(s) => sensor_trace(world, s),
        Method::LightTrace(s) => light_trace(world, s, progress, cancel)?,
        Method::SurfaceTrace(s) => surface_trace(world, s, progress, cancel)?,
        Method::Radiosity(s) => radiosity(world, s, progress, cancel, kept)?,
    };
    outcome.seconds = start.elapsed().as_secs_f64();
    Ok(outcome)
}

/// Whether `method` runs on `world` if its scene is periodic: the light model with any
/// lights (a plot's lamps light every plot, as their copies do); the ray tracers (images and
/// sensors), the radiosity solvers and their images under sun and sky only, since they light
/// by the plot's own lamps and would miss their copies.
pub(super) fn check_periodic(world: &World, method: &Method) -> Result<(), MethodError> {
    if world.field().is_none() {
        return Ok(());
    }
    let name = method.kind().name();
    match method {
        Method::LightTrace(_) => Ok(()),
        Method::RayTrace(_)
        | Method::PathTrace(_)
        | Method::SensorTrace(_)
        | Method::SurfaceTrace(_)
        | Method::Radiosity(_)
        | Method::RadiosityImage(_)
        | Method::FinalGather(_) => {
            let lamps = !world.lights.area.is_empty()
                || world
                    .lights
                    .delta
                    .iter()
                    .any(|l| !matches!(l, LightKind::Directional { .. }));
            if lamps {
                Err(MethodError::PeriodicLamps(name))
            } else {
                Ok(())
            }
        }
    }
}

/// An outcome with nothing in it yet.
pub(super) fn empty() -> Outcome {
    Outcome {
        image: None,
        subdivisions: Vec::new(),
        measurement: None,
        sensor_readings: Vec::new(),
        radiosity: None,
        summary: String::new(),
        complete: true,
        seconds: 0.0,
    }
}

/// A radiosity solve and its measurement: the solution's own, or, with
/// `surface_gather`, the final gather's at the reported surfaces (phase `gathering`; if
/// cancelled there, the solution's, the outcome marked incomplete).
fn radiosity(
    world: &Arc<World>,
    s: &RadiositySettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
    kept: Option<&mut KeptLinks>,
) -> Result<Outcome, MethodError> {
    // The solvers reflect diffusely only; the final gather traces rays and would otherwise
    // add the specular lobes' light at its first hits (the corridor of RenderPark's corpus:
    // +12 … +21 % on its gathered objects).
    let diffuse = world.diffuse().map_err(SolveError::from)?.map(Arc::new);
    let world = diffuse.as_ref().unwrap_or(world);
    let solved = solve_radiosity_keeping(world, s, progress, cancel, kept)?;
    let mut complete = !solved.solution.interrupted;
    let mut summary = solved.summary();
    let gathered = if s.surface_gather.is_on() && complete {
        progress.phase("gathering");
        let seed = s.system.visibility.seed;
        solved.gathered_measurement(s.surface_gather, seed, progress, cancel)
    } else {
        None
    };
    let measurement = match gathered {
        Some((measurement, phrase)) => {
            summary += &phrase;
            measurement
        }
        None => {
            let mut measurement = solved.measurement();
            if s.surface_gather.is_on() {
                // Asked for but cancelled (or the solve was): the solution's own values.
                complete = false;
                measurement.stats.insert("surface_gather_interrupted", true);
            }
            measurement
        }
    };
    Ok(Outcome {
        measurement: Some(measurement),
        summary,
        complete,
        radiosity: Some(solved),
        ..empty()
    })
}

/// Meshes and solves `world` by the radiosity solver of `settings` (progress phases: the
/// hierarchical solvers' own, [`solve_hierarchical_keeping`] and [`solve_hierarchical_shooting`],
/// `shooting` or `form factors`); cancelling keeps the state reached.
pub fn solve_radiosity(
    world: &Arc<World>,
    settings: &RadiositySettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<SolvedRadiosity, MethodError> {
    solve_radiosity_keeping(world, settings, progress, cancel, None)
}

/// [`solve_radiosity`], hierarchical radiosity and the matrix solver with the links `kept`
/// ([`run_keeping`]).
fn solve_radiosity_keeping(
    world: &Arc<World>,
    settings: &RadiositySettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
    kept: Option<&mut KeptLinks>,
) -> Result<SolvedRadiosity, MethodError> {
    settings.check()?;
    let unrolled = unrolled(world, settings.system.periodic_margin)?;
    let world = unrolled.as_ref().unwrap_or(world);
    let options = settings.system;
    let (system, solution) = match settings.solver {
        SolverKind::Hierarchical => solve_hierarchical_keeping(
            world,
            options,
            &settings.hierarchical,
            progress,
            cancel,
            kept,
        )?,
        SolverKind::HierarchicalShooting => solve_hierarchical_shooting(
            world,
            options,
            &settings.hierarchical,
            &settings.shooting,
            progress,
            cancel,
        )?,
        SolverKind::Matrix => {
            let system = match kept {
                Some(_) => {
                    RadiositySystem::with_progress_by_geometry(world, options, progress, cancel)?
                }
                None => RadiositySystem::with_progress(world, options, progress, cancel)?,
            };
            progress.phase("form factors");
            let solution = solve_matrix_keeping(&system, &settings.matrix, progress, cancel, kept)?;
            (system, solution)
        }
        SolverKind::Progressive => {
            let system = RadiositySystem::with_progress(world, options, progress, cancel)?;
            progress.phase("shooting");
            let solution = solve_progressive(&system, &settings.shooting, progress, cancel)?;
            (system, solution)
        }
    };
    Ok(SolvedRadiosity { system, solution })
}

/// A periodic `world` unrolled for radiosity ([`World::unrolled`]) with a margin of `margin`
/// scene units, by default none (every radiosity solver takes the light of the field beyond
/// the margin by rays, its far field); `None` for a world that is all there is.
fn unrolled(world: &Arc<World>, margin: Option<f32>) -> Result<Option<Arc<World>>, MethodError> {
    let unrolled = world
        .unrolled(margin.unwrap_or(0.0))
        .map_err(SolveError::from)?;
    Ok(unrolled.map(Arc::new))
}

/// The image size asked for, refusing a degenerate camera.
fn image_size(world: &World, size: ImageSize) -> Result<(u32, u32), MethodError> {
    let (width, height) = size.resolve(&world.scene.camera);
    match world.scene.camera.with_resolution(width, height).rays() {
        Some(_) if width > 0 && height > 0 => Ok((width, height)),
        _ => Err(MethodError::DegenerateCamera),
    }
}

/// Renders `integrator` in tiles.
fn render_tiles(
    world: &World,
    integrator: &dyn Integrator,
    (size, seed, antialias): (ImageSize, u64, &Antialias),
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<RenderOutput, MethodError> {
    let (width, height) = image_size(world, size)?;
    let settings = RenderSettings {
        width,
        height,
        antialias: antialias.mode,
        samples_per_pixel: antialias.samples_per_pixel,
        adaptive_threshold: antialias.threshold,
        seed,
        sequence: SequenceKind::Random,
    };
    progress.phase("rendering");
    render(world, integrator, &settings, progress, cancel).ok_or(MethodError::DegenerateCamera)
}

/// The standard ray tracer's image.
fn ray_trace(
    world: &World,
    s: &RayTraceSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<Outcome, MethodError> {
    let integrator = StandardRayTracer {
        max_depth: s.max_depth,
        light_samples: s.light_samples,
        shadows: s.shadows,
    };
    let output = render_tiles(
        world,
        &integrator,
        (s.size, s.seed, &s.antialias),
        progress,
        cancel,
    )?;
    Ok(Outcome {
        image: Some(output.film),
        subdivisions: output.subdivisions,
        summary: format!("{} camera samples", output.samples_traced),
        complete: output.complete,
        ..empty()
    })
}

/// The path tracer's image in progressive passes.
fn path_trace(
    world: &World,
    s: &PathTraceSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<Outcome, MethodError> {
    let (integrator, settings) = path_tracer(world, s)?;
    progress.phase("rendering");
    let output = render_progressive(world, &integrator, &settings, progress, cancel)
        .ok_or(MethodError::DegenerateCamera)?;
    Ok(Outcome {
        image: Some(output.film),
        summary: format!(
            "{} paths per pixel in {} passes",
            output.samples_per_pixel, output.passes
        ),
        complete: output.complete,
        ..empty()
    })
}

/// The path tracer of `s` and the settings of its progressive render on `world`, refusing
/// a degenerate camera.
pub(super) fn path_tracer(
    world: &World,
    s: &PathTraceSettings,
) -> Result<(PathTracer, ProgressiveSettings), MethodError> {
    let (width, height) = image_size(world, s.size)?;
    let integrator = PathTracer::new(world, s.max_depth, s.first_hit_paths);
    let settings = ProgressiveSettings {
        width,
        height,
        samples_per_pixel: s.samples_per_pixel,
        seed: s.seed,
        // A limit beyond what a duration holds is no limit.
        time_limit: s
            .time_limit
            .map(|t| Duration::try_from_secs_f64(t).unwrap_or(Duration::MAX)),
    };
    Ok((integrator, settings))
}

/// A radiosity solution shown through the camera.
fn radiosity_image(
    world: &Arc<World>,
    s: &RadiosityImageSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<Outcome, MethodError> {
    let (width, height) = image_size(world, s.size)?;
    let links = match &s.links {
        LinkSelection::None => LinkDisplay::None,
        LinkSelection::All => LinkDisplay::All,
        LinkSelection::Object(name) => {
            let objects = &world.scene.objects;
            let index = objects
                .iter()
                .position(|o| o.name.as_deref() == Some(name))
                .ok_or_else(|| MethodError::NoSuchObject {
                    name: name.clone(),
                    objects: objects.iter().filter_map(|o| o.name.clone()).collect(),
                })?;
            LinkDisplay::Object(index as u32)
        }
    };
    let mut radiosity = s.radiosity;
    radiosity.hierarchical.link_segments = links != LinkDisplay::None;
    let solved = solve_radiosity(world, &radiosity, progress, cancel)?;
    let settings = DisplaySettings {
        links,
        width,
        height,
        shading: s.shading,
        wireframe: s.wireframe,
        samples_per_axis: (s.samples_per_pixel.max(1) as f64).sqrt().ceil() as u32,
    };
    progress.phase("rendering");
    let film = solved
        .render(&world.scene.camera, &settings, progress, cancel)
        .ok_or(MethodError::DegenerateCamera)?;
    Ok(Outcome {
        image: Some(film),
        summary: format!(
            "{} patches by {} ({} iterations)",
            solved.system.leaves.len(),
            solved.solution.solver_name,
            solved.solution.iterations()
        ),
        complete: !solved.solution.interrupted && !cancel.is_requested(),
        radiosity: Some(solved),
        ..empty()
    })
}

/// Direct light ray-traced, indirect light gathered from the radiosity solution.
fn final_gather(
    world: &Arc<World>,
    s: &FinalGatherSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<Outcome, MethodError> {
    image_size(world, s.size)?;
    let solved = solve_radiosity(world, &s.radiosity, progress, cancel)?;
    let (system, solution) = (&solved.system, &solved.solution);
    let integrator = solved.final_gather(s.shading, s.light_samples, s.gather_rays);
    let output = render_tiles(
        world,
        &integrator,
        (s.size, s.seed, &s.antialias),
        progress,
        cancel,
    )?;
    let summary = format!(
        "{} camera samples, indirect light from {} patches by {}",
        output.samples_traced,
        system.leaves.len(),
        solution.solver_name
    );
    let complete = output.complete && !solution.interrupted;
    drop(integrator);
    Ok(Outcome {
        image: Some(output.film),
        subdivisions: output.subdivisions,
        summary,
        complete,
        radiosity: Some(solved),
        ..empty()
    })
}

/// The sensors' irradiance by rays from each sensor.
fn sensor_trace(world: &World, s: &SensorTraceSettings) -> Outcome {
    let settings = SensorSettings {
        samples: s.samples,
        paths: s.paths,
        seed: s.seed,
    };
    let tracer = PathTracer::new(world, 1000, 1);
    let integrator = s.path_tracing.then_some(&tracer as &dyn Integrator);
    let readings = sensor_readings(world, integrator, &settings);
    Outcome {
        summary: format!("{} sensors", readings.len()),
        sensor_readings: readings,
        ..empty()
    }
}

/// The light on every surface and at the sensors by rays from them.
fn surface_trace(
    world: &World,
    s: &SurfaceTraceSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<Outcome, MethodError> {
    progress.phase("points");
    let (measurement, complete) = trace_surfaces(world, s, progress, cancel)?;
    Ok(Outcome {
        summary: format!(
            "{}, {} points on {} surfaces in {:.2} s{}",
            MethodKind::SurfaceTrace.name(),
            measurement.stats.extra["points"],
            measurement.power.table().len(),
            measurement.stats.seconds,
            if complete { "" } else { " so far" }
        ),
        measurement: Some(measurement),
        complete,
        ..empty()
    })
}

/// The light model.
fn light_trace(
    world: &World,
    s: &LightTraceSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<Outcome, MethodError> {
    progress.phase("photons");
    Ok(light_outcome(trace_light(world, s, progress, cancel)?))
}

/// The outcome of a run of the light model.
pub(super) fn light_outcome(out: LightTraceOutput) -> Outcome {
    Outcome {
        measurement: Some(out.measurement()),
        summary: format!(
            "{}, {} of {} photons, {} rays in {:.2} s",
            crate::method::MethodKind::LightTrace.name(),
            out.photons_traced,
            out.photons,
            out.rays,
            out.seconds
        ),
        complete: out.complete(),
        ..empty()
    }
}
