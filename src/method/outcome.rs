//! What a method produced, in one shape for every method: an image, a measurement of the
//! surfaces and sensors, a radiosity solution — whichever the method makes — with whether
//! it ran to the end and one phrase on the work done.

use crate::final_gather::{FinalGather, SurfaceGather, gather_surfaces};
use crate::measure::{Film, LitMesh, Measurement, Photometric, SensorReading, ValueImage};
use crate::progress::{Cancel, ProgressListener};
use crate::radiosity::solve::{
    DisplaySettings, Probe, RadiositySystem, Shading, Solution, render_solution, value_image,
};
use crate::scene::Camera;
use crate::world::World;

/// What [`super::run`] hands back. Owned: it can be kept, sent to another thread and read
/// after the world it was computed on is gone elsewhere.
pub struct Outcome {
    /// The image, for the methods that render one (linear radiance, W·sr⁻¹·m⁻², per pixel).
    pub image: Option<Film>,
    /// Adaptive antialiasing subdivisions per pixel (ray tracer and final gather with
    /// adaptive antialiasing; empty otherwise).
    pub subdivisions: Vec<u32>,
    /// Power per reported surface (W) and the sensors' irradiance, for the light model and
    /// the radiosity solvers.
    pub measurement: Option<Measurement>,
    /// The sensors' readings, for the ray-traced sensor method (the others' are in
    /// `measurement`).
    pub sensor_readings: Vec<SensorReading>,
    /// The radiosity solution, for the radiosity solvers, radiosity images and final gather:
    /// display it, export it, gather from it.
    pub radiosity: Option<SolvedRadiosity>,
    /// One phrase on the work done (`64 paths per pixel in 7 passes`).
    pub summary: String,
    /// False when the work was cancelled (or a time or round limit stopped it short of its
    /// goal); what was done is kept.
    pub complete: bool,
    /// Wall-clock seconds of the run.
    pub seconds: f64,
}

impl Outcome {
    /// The sensors' readings, whichever part of the outcome holds them.
    pub fn sensors(&self) -> &[SensorReading] {
        match &self.measurement {
            Some(m) => &m.sensors,
            None => &self.sensor_readings,
        }
    }
}

/// A radiosity solution with the system it solves (which owns a share of the world): the
/// patches, their radiosity and everything a solution hands on.
pub struct SolvedRadiosity {
    /// The patches, their emission, reflectance and light-link irradiance.
    pub system: RadiositySystem,
    /// Radiosity and irradiance per element, convergence and timing.
    pub solution: Solution,
}

impl SolvedRadiosity {
    /// The world it was solved on.
    pub fn world(&self) -> &World {
        self.system.world()
    }

    /// One phrase on the solve: patches, form factors, iterations, the last convergence
    /// value and the time per phase.
    pub fn summary(&self) -> String {
        let (system, solution) = (&self.system, &self.solution);
        let last = solution.convergence.last().copied().unwrap_or(0.0);
        format!(
            "{} patches ({} sides), {} form factors, {} iterations, {} {last:.3e}{}; \
             {:.2} s setup, {:.2} s form factors, {:.2} s iterations",
            system.leaves.len(),
            system.len(),
            system.form_factor_count(),
            solution.iterations(),
            solution.solver.convergence_measure(),
            if solution.interrupted {
                " (interrupted)"
            } else if !solution.converged {
                " (not converged)"
            } else {
                ""
            },
            solution.seconds.setup,
            solution.seconds.form_factors,
            solution.seconds.iterations,
        )
    }

    /// The power per reported surface and the sensors' irradiance.
    pub fn measurement(&self) -> Measurement {
        self.solution.measurement(&self.system)
    }

    /// The measurement with the irradiance of the reported surfaces `gather` selects
    /// measured anew by a final gather over the solution (its points drawn from `seed`), as
    /// [`super::run`] reports a radiosity method asking for one, and a phrase on the gather;
    /// `None` when `cancel`led. `progress` hears the gather's points.
    pub fn gathered_measurement(
        &self,
        gather: SurfaceGather,
        seed: u64,
        progress: &dyn ProgressListener,
        cancel: &Cancel,
    ) -> Option<(Measurement, String)> {
        let (system, solution) = (&self.system, &self.solution);
        let gathered = gather_surfaces(system, solution, gather, seed, progress, cancel)?;
        let phrase = format!(
            "; final gather at {} surfaces, {} points, {:.2} s",
            gathered.surfaces, gathered.points, gathered.seconds
        );
        Some((solution.measurement_with(system, &gathered), phrase))
    }

    /// The leaf patches as a mesh with radiosity per vertex (and per-patch lightmaps when
    /// `lightmaps`), for export.
    pub fn lit_mesh(&self, lightmaps: bool) -> LitMesh {
        self.solution.lit_mesh(&self.system, lightmaps)
    }

    /// The final-gather integrator over the solution: direct light ray-traced with
    /// `light_samples` shadow rays per light, indirect light gathered by `gather_rays` rays
    /// that read the light the solution reflects where they land (looked up by `shading`).
    /// Render it with `trace::render`, or ask it for the radiance along any ray.
    pub fn final_gather(
        &self,
        shading: Shading,
        light_samples: u32,
        gather_rays: u32,
    ) -> FinalGather<'_> {
        FinalGather::over(
            &self.system,
            &self.solution,
            shading,
            light_samples,
            gather_rays,
        )
    }

    /// The solution shown through `camera` as `settings` ask; `None` for a degenerate camera.
    pub fn render(
        &self,
        camera: &Camera,
        settings: &DisplaySettings,
        progress: &dyn ProgressListener,
        cancel: &Cancel,
    ) -> Option<Film> {
        render_solution(
            &self.system,
            &self.solution,
            camera,
            settings,
            progress,
            cancel,
        )
    }

    /// A probe reading the solution along any ray (illuminance and luminance where it meets
    /// a surface), looked up by `shading`.
    pub fn probe(&self, shading: Shading) -> Probe<'_> {
        Probe::new(&self.system, &self.solution, shading)
    }

    /// `quantity` (lux or cd·m⁻²) per pixel through `camera` at the resolution, rays per
    /// pixel and shading of `settings` (for a false-colour image); `None` for a degenerate
    /// camera.
    pub fn value_image(
        &self,
        camera: &Camera,
        settings: &DisplaySettings,
        quantity: Photometric,
        progress: &dyn ProgressListener,
        cancel: &Cancel,
    ) -> Option<ValueImage> {
        value_image(
            &self.system,
            &self.solution,
            camera,
            settings,
            quantity,
            progress,
            cancel,
        )
    }
}
