//! Ray tracing: images of a scene by integrators that follow rays from the camera.
//!
//! - integrators: the standard (Whitted-style) ray tracer ([`StandardRayTracer`], with the
//!   direct light of `direct.rs`) and the path tracer ([`PathTracer`], one path at a time or
//!   eight side by side);
//! - shading: what an integrator evaluates at a surface point — the shading point, the
//!   sampled BSDF and the choice of a light for next-event estimation;
//! - render: the image loops that drive an integrator over the camera's pixels — tiles with
//!   antialiasing ([`render()`]) and progressive passes for Monte Carlo integrators
//!   ([`render_progressive`]), whose exact per-pixel sums let a render run in batches of its
//!   samples ([`render_samples`], [`PixelSums`]);
//! - sensors: the irradiance at the scene's point sensors by rays from the sensor
//!   ([`sensor_readings`]: direct light as the standard ray tracer computes it, indirect light
//!   from an integrator);
//! - surfaces: the light on every reported surface by rays from points spread over it
//!   ([`trace_surfaces`], the `surface-trace` method).

pub(crate) mod direct;
mod path;
mod render;
mod sensors;
pub(crate) mod shading;
mod surfaces;
mod whitted;

pub use direct::ShadowMode;
pub use path::PathTracer;
pub use render::{
    AntialiasMode, PixelSums, ProgressiveOutput, ProgressiveSettings, RenderOutput, RenderSettings,
    RenderedSamples, render, render_progressive, render_samples,
};
pub use sensors::{SensorSettings, irradiance_sample, sensor_readings};
pub use surfaces::{SEGMENTS, SurfaceTraceSettings, trace_surfaces};
pub use whitted::StandardRayTracer;

use crate::color::Rgb;
use crate::geometry::Ray;
use crate::sampling::Sampler;
use crate::world::{SurfaceHit, World};

/// A ray processor (seed 002 §4.3, `RayProcessor`): the radiance arriving along a camera ray.
pub trait Integrator: Sync {
    /// Radiance (W·sr⁻¹·m⁻²) arriving at the ray origin from direction `-ray.dir`.
    fn radiance(&self, world: &World, ray: &Ray, sampler: &mut Sampler) -> Rgb;

    /// [`Self::radiance`] along `ray`, whose first hit `hit` the caller has found already.
    /// Integrators that can start from it override this (the value is the same).
    fn radiance_at(
        &self,
        world: &World,
        ray: &Ray,
        _hit: SurfaceHit,
        sampler: &mut Sampler,
    ) -> Rgb {
        self.radiance(world, ray, sampler)
    }

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
