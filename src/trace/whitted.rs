//! The standard ray tracer (seed 002 §2.2, §3.1, §4.3, `DefaultRayTracer`): direct light with
//! shadows on every surface, ideal mirror reflection and ideal refraction with Fresnel,
//! recursion to a fixed depth; indirect diffuse light is ignored.

use super::Integrator;
use super::direct::{ShadowMode, seen_directly};
use crate::color::Rgb;
use crate::geometry::{Ray, spawn_ray};
use crate::sampling::Sampler;
use crate::world::World;
use crate::world::lobes::{Lobe, LocalView};

/// Settings of the standard ray tracer.
#[derive(Clone, Debug)]
pub struct StandardRayTracer {
    /// Reflection/refraction recursion depth (0 = no reflections or refractions).
    pub max_depth: u32,
    /// Shadow rays per area light and for the sky, per camera sample.
    pub light_samples: u32,
    /// Shadow mode.
    pub shadows: ShadowMode,
}

impl Default for StandardRayTracer {
    fn default() -> Self {
        StandardRayTracer {
            max_depth: 6,
            light_samples: 16,
            shadows: ShadowMode::On,
        }
    }
}

impl StandardRayTracer {
    fn trace(&self, world: &World, ray: &Ray, depth: u32, sampler: &mut Sampler) -> Rgb {
        let (mut radiance, sp) =
            seen_directly(world, ray, self.light_samples, self.shadows, sampler);
        let Some(sp) = sp else {
            return radiance;
        };
        if depth >= self.max_depth {
            return radiance;
        }
        let hit = sp.hit;
        let m = sp.material;
        let follow = |dir, weight: Rgb, sampler: &mut Sampler| {
            if weight.is_black() {
                return Rgb::BLACK;
            }
            weight * self.trace(world, &spawn_ray(hit.p, sp.ng, dir), depth + 1, sampler)
        };
        let view = LocalView {
            n: sp.n,
            ng: sp.ng,
            wo: sp.wo,
            front_face: hit.front_face,
        };
        // Every branch of every delta lobe (mirror, dielectric), in lobe order.
        for lobe in Lobe::ALL {
            if lobe.weight(&m).is_black() {
                continue;
            }
            for (dir, weight) in lobe.branches(&m, &view).into_iter().flatten() {
                radiance += follow(dir, weight, sampler);
            }
        }
        radiance
    }
}

impl Integrator for StandardRayTracer {
    fn radiance(&self, world: &World, ray: &Ray, sampler: &mut Sampler) -> Rgb {
        self.trace(world, ray, 0, sampler)
    }
}
