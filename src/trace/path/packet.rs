//! Eight camera samples path traced side by side. Every path goes from vertex to vertex as
//! [`PathTracer`]'s one-path loop takes it, with the same random numbers drawn in the same
//! order. At a vertex on a Lambertian surface whose light sample falls on an area light of
//! uniform radiance (most vertices of diffuse scenes) the light sample's weight and the
//! scattered direction are computed for all such paths of the packet at once, on SIMD lanes;
//! every other vertex takes the one-path code. Rays are traced one by one.
//!
//! The lanes repeat the one-path arithmetic operation for operation, so a packet's radiance
//! is bit for bit that of the paths traced alone (tested): the packet is only a faster way to
//! evaluate the same estimator.

use super::super::shading::ShadingPoint;
use super::super::shading::light_sampling::{UniformAreaPoint, toward_light};
use super::{Arrival, BounceNumbers, PathTracer, survive_roulette};
use crate::color::Rgb;
use crate::geometry::{Ray, offset_origin_lanes, spawn_ray_to_lanes};
use crate::lanes::{LANES, Real, Vec3x8};
use crate::sampling::Sampler;
use crate::sampling::mis::light_sample_weight;
use crate::sampling::warp::{cosine_about, cosine_hemisphere_pdf_lanes};
use crate::world::World;
use glam::Vec3;
use std::f32::consts::FRAC_1_PI;
use wide::f32x8;

/// One path of the packet.
#[derive(Clone, Copy)]
struct Path {
    ray: Ray,
    beta: Rgb,
    bounce: u32,
    arrival: Arrival,
    radiance: Rgb,
    alive: bool,
}

/// The vertices the lanes scatter, component by component: per lane a Lambertian shading
/// point, its light sample's point and the path's throughput.
#[derive(Clone, Copy, Default)]
struct LambertLanes {
    /// Bit `i` set when lane `i` holds a vertex.
    used: u32,
    /// Shading point (world).
    p: [[f32; LANES]; 3],
    /// Unit shading normal toward the viewer.
    n: [[f32; LANES]; 3],
    /// Unit geometric normal toward the viewer.
    ng: [[f32; LANES]; 3],
    /// Unit direction toward the viewer.
    wo: [[f32; LANES]; 3],
    /// Diffuse reflectance.
    rho: [[f32; LANES]; 3],
    /// Path throughput arriving at the vertex.
    beta: [[f32; LANES]; 3],
    /// The light sample's point (world) and unit front normal.
    light_p: [[f32; LANES]; 3],
    light_n: [[f32; LANES]; 3],
    /// The light's radiance toward its front and its back.
    light_front: [[f32; LANES]; 3],
    light_back: [[f32; LANES]; 3],
    /// Density of the light sample with respect to area, choice included (1/m²).
    light_pdf_area: [f32; LANES],
    /// Uniform numbers of the scattered direction.
    direction: [[f32; LANES]; 2],
}

/// Writes the components of `v` into lane `lane` of `lanes`.
fn put(lanes: &mut [[f32; LANES]; 3], lane: usize, v: [f32; 3]) {
    for (axis, value) in lanes.iter_mut().zip(v) {
        axis[lane] = value;
    }
}

/// Lane `lane` of a component array.
fn get(lanes: &[[f32; LANES]; 3], lane: usize) -> [f32; 3] {
    [lanes[0][lane], lanes[1][lane], lanes[2][lane]]
}

impl LambertLanes {
    /// Puts a vertex into lane `lane`.
    #[inline(always)]
    fn set(
        &mut self,
        lane: usize,
        sp: &ShadingPoint,
        light: &UniformAreaPoint,
        direction: [f32; 2],
        beta: Rgb,
    ) {
        self.used |= 1 << lane;
        put(&mut self.p, lane, sp.hit.p.to_array());
        put(&mut self.n, lane, sp.n.to_array());
        put(&mut self.ng, lane, sp.ng.to_array());
        put(&mut self.wo, lane, sp.wo.to_array());
        put(&mut self.rho, lane, sp.material.diffuse.to_array());
        put(&mut self.beta, lane, beta.to_array());
        put(&mut self.light_p, lane, light.p.to_array());
        put(&mut self.light_n, lane, light.n.to_array());
        put(&mut self.light_front, lane, light.radiance[0].to_array());
        put(&mut self.light_back, lane, light.radiance[1].to_array());
        self.light_pdf_area[lane] = light.pdf_area;
        (self.direction[0][lane], self.direction[1][lane]) = (direction[0], direction[1]);
    }
}

/// What the lanes give back, component by component.
struct LambertScatter {
    /// Bit `i` set when lane `i`'s light sample carries light (its shadow ray decides).
    carries: u32,
    /// Radiance toward the viewer from the light sample, throughput applied.
    light: [[f32; LANES]; 3],
    /// The shadow ray toward the light sample: origin, unit direction, parameter limit.
    shadow_origin: [[f32; LANES]; 3],
    shadow_dir: [[f32; LANES]; 3],
    shadow_t_max: [f32; LANES],
    /// Bit `i` set when lane `i`'s scattered direction leaves on the viewer's side.
    leaves: u32,
    /// Origin of the scattered ray.
    origin: [[f32; LANES]; 3],
    /// Scattered direction.
    wi: [[f32; LANES]; 3],
    /// Throughput times the sample weight.
    beta: [[f32; LANES]; 3],
    /// Density of the scattered direction (1/sr).
    pdf: [f32; LANES],
}

impl PathTracer {
    /// The radiance along each of `rays` (at most eight), each path drawing its numbers from
    /// its own sampler in `samplers`; the same values as [`super::Integrator::radiance`]
    /// gives for each ray alone.
    pub(super) fn radiance_packet(
        &self,
        world: &World,
        rays: &[Ray],
        samplers: &mut [Sampler],
        out: &mut [Rgb],
    ) {
        let count = rays.len().min(LANES);
        let mut paths: [Path; LANES] = std::array::from_fn(|i| Path {
            ray: rays
                .get(i)
                .copied()
                .unwrap_or(Ray::new(Vec3::ZERO, Vec3::Z)),
            beta: Rgb::WHITE,
            bounce: 0,
            arrival: Arrival::CAMERA,
            radiance: Rgb::BLACK,
            alive: i < count,
        });
        let mut lambert = LambertLanes::default();
        loop {
            lambert.used = 0;
            for (lane, (path, sampler)) in paths.iter_mut().zip(&mut *samplers).enumerate() {
                if path.alive {
                    self.advance(world, path, sampler, &mut lambert, lane);
                }
            }
            if lambert.used != 0 {
                let scattered = scatter_lambert(&lambert);
                let mut used = lambert.used;
                while used != 0 {
                    let lane = used.trailing_zeros() as usize;
                    used &= used - 1;
                    let (path, sampler) = (&mut paths[lane], &mut samplers[lane]);
                    finish_lambert(self, world, path, &lambert, &scattered, lane, sampler);
                }
            }
            if !paths.iter().any(|p| p.alive) {
                break;
            }
        }
        for (o, path) in out.iter_mut().zip(&paths[..count]) {
            *o = path.radiance;
        }
    }

    /// Takes `path` to its next vertex and scatters it there with the one-path code, or, if
    /// the vertex is one the lanes handle, puts it into lane `lane` of `lambert`. Marks the
    /// path dead when it ends.
    fn advance(
        &self,
        world: &World,
        path: &mut Path,
        sampler: &mut Sampler,
        lambert: &mut LambertLanes,
        lane: usize,
    ) {
        let arrived = self.arrive(
            world,
            &path.ray,
            path.beta,
            path.bounce,
            &path.arrival,
            &mut path.radiance,
        );
        let Some((sp, choice)) = arrived else {
            path.alive = false;
            return;
        };
        if path.bounce == 0 && self.first_hit_paths > 1 {
            path.radiance += self.branch(world, &sp, &choice, path.beta, sampler);
            path.alive = false;
            return;
        }
        let u = BounceNumbers::draw(sampler, path.bounce);
        if choice.is_lambert_only()
            && sp.material.is_lambertian()
            && let Some(light) = self
                .lights
                .uniform_area_point(world, u.light_pick, u.light_point)
        {
            lambert.set(lane, &sp, &light, u.direction.to_array(), path.beta);
            return;
        }
        let (light, next) =
            self.scatter_once(world, &sp, &choice, path.beta, path.bounce, &u, sampler);
        path.radiance += light;
        match next {
            Some((ray, beta, arrival)) => {
                (path.ray, path.beta, path.arrival) = (ray, beta, arrival);
                path.bounce += 1;
            }
            None => path.alive = false,
        }
    }
}

/// Completes the lanes' scattering of lane `lane` for `path`: Russian roulette and the next
/// ray, and the light sample's shadow ray.
#[inline(always)]
fn finish_lambert(
    tracer: &PathTracer,
    world: &World,
    path: &mut Path,
    lambert: &LambertLanes,
    scattered: &LambertScatter,
    lane: usize,
    sampler: &mut Sampler,
) {
    let bit = 1 << lane;
    let next_beta = Rgb::from(get(&scattered.beta, lane));
    let beta = (scattered.leaves & bit != 0)
        .then(|| survive_roulette(next_beta, (path.bounce, tracer.roulette_start), sampler))
        .flatten();
    if scattered.carries & bit != 0 {
        let shadow = Ray::new(
            Vec3::from(get(&scattered.shadow_origin, lane)),
            Vec3::from(get(&scattered.shadow_dir, lane)),
        );
        if !world.occluded(&shadow, scattered.shadow_t_max[lane]) {
            path.radiance += Rgb::from(get(&scattered.light, lane));
        }
    }
    let Some(beta) = beta else {
        path.alive = false;
        return;
    };
    path.ray = Ray::new(
        Vec3::from(get(&scattered.origin, lane)),
        Vec3::from(get(&scattered.wi, lane)),
    );
    path.beta = beta;
    path.arrival = Arrival {
        from: Vec3::from(get(&lambert.p, lane)),
        normal: Vec3::from(get(&lambert.n, lane)),
        pdf: scattered.pdf[lane],
        delta: false,
    };
    path.bounce += 1;
}

/// The light sample's contribution and the scattered direction of every vertex in `lambert`
/// (unused lanes compute garbage that nobody reads), by the functions the one-path code uses:
/// [`toward_light`] and [`light_sample_weight`] as in next-event estimation, [`cosine_about`]
/// as in [`crate::trace::shading::bsdf::sample_bsdf`] for a Lambert lobe.
#[inline(always)]
fn scatter_lambert(lambert: &LambertLanes) -> LambertScatter {
    let x = Vec3x8::load(&lambert.p);
    let n = Vec3x8::load(&lambert.n);
    let ng = Vec3x8::load(&lambert.ng);
    let wo = Vec3x8::load(&lambert.wo);
    let rho = Vec3x8::load(&lambert.rho);
    let beta = Vec3x8::load(&lambert.beta);
    let zero = f32x8::ZERO;
    let viewer_side = n.dot(wo).gt(zero);

    // The light sample (LightPicker::sample) and its next-event contribution.
    let light_p = Vec3x8::load(&lambert.light_p);
    let toward = toward_light(x, light_p, Vec3x8::load(&lambert.light_n));
    let (wi, cos_y) = (toward.wi, toward.cos_light);
    let cos = n.dot(wi);
    let le = Vec3x8::select(
        cos_y.gt(zero),
        Vec3x8::load(&lambert.light_front),
        Vec3x8::load(&lambert.light_back),
    );
    let pdf = toward.solid_angle_pdf(f32x8::new(lambert.light_pdf_area));
    let radiance_over_pdf = le.scale(f32x8::ONE / pdf);
    // A Lambert-only material chooses its lobe with probability 1 (exactly: d/d), so the
    // one-path code's factors p_d = 1/p_d = 1 leave every product unchanged and are left out.
    let weight = light_sample_weight(pdf, || {
        viewer_side.blend(cosine_hemisphere_pdf_lanes(cos), zero)
    });
    let f = rho.scale(f32x8::splat(FRAC_1_PI));
    let light = beta * (f * radiance_over_pdf).scale(cos * weight);
    let nonzero = |v: Vec3x8| v.x.ne(zero) | v.y.ne(zero) | v.z.ne(zero);
    let carries = toward.dist2.gt(zero)
        & cos_y.ne(zero)
        & cos.gt(zero)
        & nonzero(le)
        & ng.dot(wi).gt(zero)
        & viewer_side
        & nonzero(f);

    // The scattered direction (sample_bsdf, Lambert lobe alone).
    let wi_b = cosine_about(
        n,
        f32x8::new(lambert.direction[0]),
        f32x8::new(lambert.direction[1]),
    );
    let cos_b = n.dot(wi_b);
    let leaves = cos_b.gt(zero) & ng.dot(wi_b).gt(zero) & viewer_side;
    let (shadow_origin, shadow_dir, shadow_t_max) = spawn_ray_to_lanes(x, ng, light_p);
    LambertScatter {
        carries: carries.move_mask() as u32,
        light: light.store(),
        shadow_origin: shadow_origin.store(),
        shadow_dir: shadow_dir.store(),
        shadow_t_max: shadow_t_max.to_array(),
        leaves: leaves.move_mask() as u32,
        origin: offset_origin_lanes(x, ng, wi_b).store(),
        wi: wi_b.store(),
        beta: (beta * rho).store(),
        pdf: cosine_hemisphere_pdf_lanes(cos_b).to_array(),
    }
}
