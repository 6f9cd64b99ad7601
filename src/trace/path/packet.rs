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
use super::super::shading::light_sampling::UniformAreaPoint;
use super::{Arrival, BounceNumbers, PathTracer, survive_roulette};
use crate::color::Rgb;
use crate::geometry::Ray;
use crate::lanes::{self, LANES, Vec3x8};
use crate::sampling::Sampler;
use crate::world::World;
use glam::Vec3;
use std::f32::consts::FRAC_1_PI;
use wide::{CmpGt, CmpNe, f32x8};

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

/// Lanes of a component array as a vector.
fn load(lanes: &[[f32; LANES]; 3]) -> Vec3x8 {
    Vec3x8 {
        x: f32x8::new(lanes[0]),
        y: f32x8::new(lanes[1]),
        z: f32x8::new(lanes[2]),
    }
}

/// Lane `lane` of a component array.
fn get(lanes: &[[f32; LANES]; 3], lane: usize) -> [f32; 3] {
    [lanes[0][lane], lanes[1][lane], lanes[2][lane]]
}

impl LambertLanes {
    /// Puts a vertex into lane `lane`.
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
                    finish_lambert(world, path, &lambert, &scattered, lane, sampler);
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
            && sp.material.specular.is_black()
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
fn finish_lambert(
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
        .then(|| survive_roulette(next_beta, path.bounce, sampler))
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
/// (unused lanes compute garbage that nobody reads), by the operations of
/// [`super::light_sampling::LightPicker::sample`], [`PathTracer`]'s next-event estimation
/// and [`super::bsdf_sampling::sample_bsdf`] for a Lambert lobe.
fn scatter_lambert(lambert: &LambertLanes) -> LambertScatter {
    let x = load(&lambert.p);
    let n = load(&lambert.n);
    let ng = load(&lambert.ng);
    let wo = load(&lambert.wo);
    let rho = load(&lambert.rho);
    let beta = load(&lambert.beta);
    let zero = f32x8::ZERO;
    let n_wo = n.dot(&wo);
    let viewer_side = n_wo.cmp_gt(zero);

    // The light sample (LightPicker::sample) and its next-event contribution.
    let light_p = load(&lambert.light_p);
    let d = light_p.sub(&x);
    let dist2 = d.dot(&d);
    let wi = d.scale(f32x8::ONE / dist2.sqrt());
    let cos_y = load(&lambert.light_n).dot(&wi.neg());
    let cos = n.dot(&wi);
    let front = cos_y.cmp_gt(zero);
    let le = Vec3x8::select(
        front,
        &load(&lambert.light_front),
        &load(&lambert.light_back),
    );
    let pdf = f32x8::new(lambert.light_pdf_area) * dist2 / cos_y.abs();
    let radiance_over_pdf = le.scale(f32x8::ONE / pdf);
    // A Lambert-only material chooses its lobe with probability 1 (exactly: d/d), so the
    // scalar code's factors p_d = 1/p_d = 1 leave every product unchanged and are left out.
    let bsdf_pdf = viewer_side.blend(cos.fast_max(zero) * f32x8::splat(FRAC_1_PI), zero);
    let (a2, b2) = (pdf * pdf, bsdf_pdf * bsdf_pdf);
    let sum = a2 + b2;
    let heuristic = sum.cmp_gt(zero).blend(a2 / sum, zero);
    let weight = pdf.cmp_gt(zero).blend(heuristic, f32x8::ONE);
    let f = rho.scale(f32x8::splat(FRAC_1_PI));
    let light = beta.mul(&f.mul(&radiance_over_pdf).scale(cos * weight));
    let carries = dist2.cmp_gt(zero)
        & cos_y.cmp_ne(zero)
        & cos.cmp_gt(zero)
        & (le.x.cmp_ne(zero) | le.y.cmp_ne(zero) | le.z.cmp_ne(zero))
        & ng.dot(&wi).cmp_gt(zero)
        & viewer_side
        & (f.x.cmp_ne(zero) | f.y.cmp_ne(zero) | f.z.cmp_ne(zero));

    // The scattered direction (sample_bsdf, Lambert lobe alone).
    let local = lanes::cosine_hemisphere(
        f32x8::new(lambert.direction[0]),
        f32x8::new(lambert.direction[1]),
    );
    let wi_b = lanes::to_world_about(&n, &local);
    let cos_b = n.dot(&wi_b);
    let leaves = cos_b.cmp_gt(zero) & ng.dot(&wi_b).cmp_gt(zero) & viewer_side;
    let next_beta = beta.mul(&rho);
    let pdf_b = cos_b.fast_max(zero) * f32x8::splat(FRAC_1_PI);
    let (shadow_origin, shadow_dir, shadow_t_max) = lanes::spawn_ray_to(&x, &ng, &light_p);
    LambertScatter {
        carries: carries.move_mask() as u32,
        light: store(&light),
        shadow_origin: store(&shadow_origin),
        shadow_dir: store(&shadow_dir),
        shadow_t_max: shadow_t_max.to_array(),
        leaves: leaves.move_mask() as u32,
        origin: store(&lanes::offset_origin(&x, &ng, &wi_b)),
        wi: store(&wi_b),
        beta: store(&next_beta),
        pdf: pdf_b.to_array(),
    }
}

/// A vector's lanes as a component array.
fn store(v: &Vec3x8) -> [[f32; LANES]; 3] {
    [v.x.to_array(), v.y.to_array(), v.z.to_array()]
}
