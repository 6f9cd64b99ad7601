//! Ray tracing: the scene flattened for ray queries ([`World`]), light sampling, the
//! integrators (the standard ray tracer and the path tracer), antialiasing, the tiled image
//! loop and the progressive one for Monte Carlo integrators.

pub mod antialias;
pub mod bsdf;
pub mod bsdf_sampling;
pub mod direct;
mod geometry;
mod lanes;
pub mod light_sampling;
mod lights;
pub mod lighttracer;
mod path_packet;
pub mod pathtracer;
pub mod photon_scatter;
pub mod photon_sources;
pub mod progressive;
pub mod render;
pub mod sampler;
pub mod sampling;
mod whitted;
mod world;

pub use geometry::{EMITTER_SEGMENTS, GeometryError, SceneGeometry, SurfaceHit};
pub use lights::{AreaLight, AreaSample, LightSet};
pub use pathtracer::PathTracer;
pub use whitted::StandardRayTracer;
pub use world::World;

use crate::color::Rgb;
use crate::geometry::Ray;
use sampler::Sampler;

/// A ray processor (seed 002 §4.3, `RayProcessor`): the radiance arriving along a camera ray.
pub trait Integrator: Sync {
    /// Radiance (W·sr⁻¹·m⁻²) arriving at the ray origin from direction `-ray.dir`.
    fn radiance(&self, world: &World, ray: &Ray, sampler: &mut Sampler) -> Rgb;

    /// [`Self::radiance`] along each of `rays`, ray `i` drawing from `samplers[i]`, into
    /// `out[i]` (the three slices are equally long). Integrators that trace several rays
    /// faster together than one by one override it; the values are the same.
    fn radiance_batch(
        &self,
        world: &World,
        rays: &[Ray],
        samplers: &mut [Sampler],
        out: &mut [Rgb],
    ) {
        for ((ray, sampler), o) in rays.iter().zip(samplers).zip(out) {
            *o = self.radiance(world, ray, sampler);
        }
    }
}
