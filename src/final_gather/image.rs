//! The final gather's image (seed 000, requirement 5.0): the direct light from the ray
//! tracer and the indirect light from a radiosity solution.
//!
//! At the surface a camera ray meets, the light arriving straight from the lights and from
//! emitting surfaces is traced with exact shadows (`trace::direct::seen_directly`); the light arriving
//! after one or more reflections is gathered by cosine-distributed rays that read, where they
//! land, the radiance the solution reflects there (its radiosity without its own emission,
//! [`Solution::reflected_radiosity`], smooth across each leaf). Shadows and contact
//! shading are therefore as sharp as the ray tracer's, and the radiosity mesh no longer
//! shows in the image.

use crate::color::Rgb;
use crate::geometry::{Frame, Ray, spawn_ray};
use crate::radiosity::solve::{RadiosityLookup, RadiositySystem, Shading, Solution};
use crate::sampling::Sampler;
use crate::sampling::warp::{cosine_hemisphere, stratified};
use crate::trace::Integrator;
use crate::trace::direct::{ShadowMode, seen_at, seen_directly};
use crate::trace::shading::ShadingPoint;
use crate::world::{SurfaceHit, World};
use std::f32::consts::PI;

/// The final-gather integrator over a solved radiosity system.
pub struct FinalGather<'s> {
    /// The light each element reflects (W·m⁻²), found along gather rays.
    pub reflected: RadiosityLookup<'s>,
    /// Shadow rays per area light and for the sky at every camera hit.
    pub light_samples: u32,
    /// Gather rays per camera hit (rounded up to a square; stratified over the hemisphere).
    pub gather_rays: u32,
}

impl<'s> FinalGather<'s> {
    /// The final gather over `solution` of `system`: direct light with `light_samples` shadow
    /// rays per light, indirect light by `gather_rays` rays that read the light the solution
    /// reflects where they land (looked up by `shading`).
    pub fn over(
        system: &'s RadiositySystem,
        solution: &Solution,
        shading: Shading,
        light_samples: u32,
        gather_rays: u32,
    ) -> Self {
        FinalGather {
            reflected: RadiosityLookup::new(system, solution.reflected_radiosity(system), shading)
                .with_texture_detail(solution.display_irradiance(), false),
            light_samples,
            gather_rays,
        }
    }

    /// Radiance reflected toward the viewer (or passed through a translucent surface) from
    /// the indirect light at `sp`, W·sr⁻¹·m⁻²: the gather rays cover the hemisphere in front,
    /// and the one behind a translucent surface.
    fn indirect(&self, sp: &ShadingPoint, sampler: &mut Sampler) -> Rgb {
        let n_side = (self.gather_rays.max(1) as f32).sqrt().ceil() as u32;
        let mut total = Rgb::BLACK;
        for &sign in sp.material.hemispheres() {
            let frame = Frame::from_normal(sp.n * sign);
            let mut sum = Rgb::BLACK;
            for k in 0..n_side * n_side {
                let u = stratified(k, n_side, sampler.next_2d());
                let wi = frame.to_world(cosine_hemisphere(u));
                if sign * sp.ng.dot(wi) <= 0.0 {
                    continue;
                }
                if let Some(hit) = self.reflected.hit(&spawn_ray(sp.hit.p, sp.ng, wi)) {
                    // f·L·cos θ / p(ω), with p(ω) = cos θ / π.
                    sum += sp.material.eval(sp.n, sp.wo, wi) * hit.radiance * PI;
                }
            }
            total += sum / (n_side * n_side) as f32;
        }
        total
    }
}

impl FinalGather<'_> {
    /// Radiance toward the viewer from what the viewer sees directly (`seen`: its radiance
    /// and shading point, as `trace::direct` finds them) plus its indirect light.
    fn with_indirect(&self, seen: (Rgb, Option<ShadingPoint>), sampler: &mut Sampler) -> Rgb {
        match seen {
            (direct, Some(sp)) => direct + self.indirect(&sp, sampler),
            (direct, None) => direct,
        }
    }
}

impl Integrator for FinalGather<'_> {
    fn radiance(&self, world: &World, ray: &Ray, sampler: &mut Sampler) -> Rgb {
        let seen = seen_directly(world, ray, self.light_samples, ShadowMode::On, sampler);
        self.with_indirect(seen, sampler)
    }

    fn radiance_at(&self, world: &World, ray: &Ray, hit: SurfaceHit, sampler: &mut Sampler) -> Rgb {
        let seen = seen_at(
            world,
            hit,
            ray.dir,
            self.light_samples,
            ShadowMode::On,
            sampler,
        );
        self.with_indirect(seen, sampler)
    }
}
