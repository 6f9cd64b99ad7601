//! A view of a radiosity solution rendered by final gathering through a camera of its own
//! (the viewer's *render this view*): the solution's world with that camera, sharing its
//! geometry, and the final-gather integrator over the solution, made once and rendered pass
//! after pass.

use super::outcome::SolvedRadiosity;
use crate::final_gather::FinalGather;
use crate::measure::Film;
use crate::progress::{Cancel, NoProgress};
use crate::radiosity::solve::Shading;
use crate::sampling::SequenceKind;
use crate::scene::Camera;
use crate::trace::{AntialiasMode, RenderSettings, render};
use crate::world::{GeometryError, World};

/// A solution seen through a camera by final gathering ([`SolvedRadiosity::final_gather`]).
pub struct FinalGatherView<'s> {
    world: World,
    integrator: FinalGather<'s>,
}

impl SolvedRadiosity {
    /// The view of this solution's scene through `camera` (at its size), rendered by final
    /// gathering: direct light ray-traced with `light_samples` shadow rays per light, the
    /// indirect light gathered by `gather_rays` rays per camera sample from the solution
    /// looked up by `shading`.
    pub fn final_gather_view(
        &self,
        camera: &Camera,
        shading: Shading,
        light_samples: u32,
        gather_rays: u32,
    ) -> Result<FinalGatherView<'_>, GeometryError> {
        let solved_on = self.world();
        let mut scene = solved_on.scene.clone();
        scene.camera = camera.clone();
        Ok(FinalGatherView {
            world: solved_on.relit(scene)?,
            integrator: self.final_gather(shading, light_samples, gather_rays),
        })
    }
}

impl FinalGatherView<'_> {
    /// One pass: `samples_per_pixel` jittered camera samples per pixel, drawn with `seed`
    /// (passes of different seeds average to the image of their samples together), as linear
    /// radiance, W·sr⁻¹·m⁻². `None` for a degenerate camera or when `cancel` stopped it.
    pub fn render(&self, samples_per_pixel: u32, seed: u64, cancel: &Cancel) -> Option<Film> {
        let camera = &self.world.scene.camera;
        let settings = RenderSettings {
            width: camera.width,
            height: camera.height,
            antialias: AntialiasMode::Stochastic,
            samples_per_pixel,
            adaptive_threshold: 0.0,
            seed,
            sequence: SequenceKind::Random,
        };
        let output = render(
            &self.world,
            &self.integrator,
            &settings,
            &NoProgress,
            cancel,
        )?;
        output.complete.then_some(output.film)
    }
}
