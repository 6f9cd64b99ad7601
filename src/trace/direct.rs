//! Direct light at a surface point from every light of the scene, with shadow rays (or, with
//! shadows off, only self-shadowing by facing: seed 002 §4.4, `NoShadows`).

use super::shading::ShadingPoint;
use crate::color::Rgb;
use crate::geometry::{Frame, Ray};
use crate::sampling::Sampler;
use crate::sampling::warp::{cosine_hemisphere, stratified};
use crate::scene::Incidence;
use crate::world::{SurfaceHit, World, emitted};
use glam::Vec3;
use std::f32::consts::PI;

/// How shadows are decided (seed 002 §4.4: `Shadows` and `NoShadows` processors).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ShadowMode {
    /// Every object of the scene can block a light.
    #[default]
    On,
    /// Only the surface's own facing matters: lights behind it are ignored.
    Off,
}

crate::choice::named_values!(ShadowMode {
    ShadowMode::On = "on", "Shadows from every object";
    ShadowMode::Off = "off", "Only self-shadowing by facing: lights behind a surface are ignored";
});

impl ShadowMode {
    /// Whether light passes, given the shadow-ray test `unblocked` (run only with shadows on).
    fn lets_through(self, unblocked: impl FnOnce() -> bool) -> bool {
        self == ShadowMode::Off || unblocked()
    }
}

/// What a ray sees directly, W·sr⁻¹·m⁻²: the sky (or black) when it meets nothing, else
/// what the surface it meets emits toward it plus the direct light that surface reflects
/// ([`direct_light`]); with the shading point when the surface scatters light from the side
/// the ray meets, for integrators that go on from there.
pub fn seen_directly(
    world: &World,
    ray: &Ray,
    light_samples: u32,
    shadows: ShadowMode,
    sampler: &mut Sampler,
) -> (Rgb, Option<ShadingPoint>) {
    let Some(hit) = world.intersect(ray) else {
        let sky = world.lights.sky.as_ref();
        return (sky.map_or(Rgb::BLACK, |sky| sky.radiance(ray.dir)), None);
    };
    seen_at(world, hit, ray.dir, light_samples, shadows, sampler)
}

/// [`seen_directly`] where the ray travelling along `dir` has met the surface at `hit`.
pub fn seen_at(
    world: &World,
    hit: SurfaceHit,
    dir: Vec3,
    light_samples: u32,
    shadows: ShadowMode,
    sampler: &mut Sampler,
) -> (Rgb, Option<ShadingPoint>) {
    let emitted = emitted(&world.scene, &hit);
    let sp = ShadingPoint::new(world, hit, dir);
    if sp.material.is_black_from(hit.front_face) {
        return (emitted, None);
    }
    let radiance = emitted + direct_light(world, &sp, light_samples, shadows, sampler);
    (radiance, Some(sp))
}

/// Radiance reflected toward the viewer (or passed through a translucent surface) from
/// light arriving directly from all lights. Area lights and the sky each get `samples`
/// shadow rays (stratified and jittered).
pub fn direct_light(
    world: &World,
    sp: &ShadingPoint,
    samples: u32,
    shadows: ShadowMode,
    sampler: &mut Sampler,
) -> Rgb {
    let mut total = Rgb::BLACK;
    let x = sp.hit.p;
    // Light from behind passes a translucent surface; an opaque one only takes it in front.
    let through = sp.material.is_translucent();
    let arrives = |cos: f32| cos > 0.0 || (through && cos < 0.0);
    for light in &world.lights.delta {
        let Some(Incidence {
            wi,
            distance: dist,
            irradiance: irradiance_normal,
        }) = light.incidence(x)
        else {
            continue;
        };
        let cos = sp.n.dot(wi);
        if !arrives(cos) || irradiance_normal.is_black() {
            continue;
        }
        let visible = if dist.is_finite() {
            shadows.lets_through(|| sp.sees(world, x + wi * dist))
        } else {
            shadows.lets_through(|| sp.sees_along(world, wi))
        };
        if visible {
            total += sp.material.eval(sp.n, sp.wo, wi) * irradiance_normal * cos.abs();
        }
    }
    let n_side = (samples.max(1) as f32).sqrt().ceil() as u32;
    let count = n_side * n_side;
    for index in 0..world.lights.area.len() {
        let mut sum = Rgb::BLACK;
        for k in 0..count {
            let u_pick = sampler.next_1d();
            let u = stratified(k, n_side, sampler.next_2d());
            let s = world.lights.sample_area(&world.geometry, index, u_pick, u);
            let d = s.p - x;
            let dist2 = d.length_squared();
            if dist2 <= 0.0 {
                continue;
            }
            let wi = d / dist2.sqrt();
            let cos_x = sp.n.dot(wi);
            let cos_y = s.n.dot(-wi);
            if !arrives(cos_x) || cos_y == 0.0 {
                continue;
            }
            let le =
                world
                    .lights
                    .area_radiance(&world.scene, &world.geometry, index, &s, cos_y > 0.0);
            if le.is_black() || !shadows.lets_through(|| sp.sees(world, s.p)) {
                continue;
            }
            let geometric = (cos_x * cos_y).abs() / (dist2 * s.pdf_area);
            sum += sp.material.eval(sp.n, sp.wo, wi) * le * geometric;
        }
        total += sum / count as f32;
    }
    if let Some(sky) = &world.lights.sky {
        // The sky in front, and behind a translucent surface: `count` cosine-distributed
        // directions about the normal on each side, each weighted by the sky's radiance
        // (uniform, or a CIE sky's by direction: its smooth distribution needs no table).
        for &sign in sp.material.hemispheres() {
            let frame = Frame::from_normal(sp.n * sign);
            let mut sum = Rgb::BLACK;
            for k in 0..count {
                let u = stratified(k, n_side, sampler.next_2d());
                let wi = frame.to_world(cosine_hemisphere(u));
                if sign * sp.ng.dot(wi) > 0.0 && shadows.lets_through(|| sp.sees_along(world, wi)) {
                    // L·f·cos / (cos/π) = π·L·f.
                    sum += sp.material.eval(sp.n, sp.wo, wi) * sky.radiance(wi) * PI;
                }
            }
            total += sum / count as f32;
        }
    }
    total
}
