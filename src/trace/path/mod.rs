//! Unbiased Monte Carlo path tracing (seed 002 §3.2): from each camera ray one path, or N
//! branching paths at the first hit, continued by sampling the material's lobes; at every
//! non-delta vertex one light is sampled (next-event estimation) and combined with the
//! emission that BSDF sampling finds by multiple importance sampling (power heuristic).
//! Russian roulette after [`ROULETTE_START`] scattering events, survival by the throughput's
//! largest channel capped at [`ROULETTE_MAX_SURVIVAL`] (its luminance would let one channel of
//! a path off a saturated wall grow past 1 and make colour fireflies; measured on the Cornell
//! box the largest channel gives 3 % less noise in the same time).
//!
//! Random numbers: the camera sample's Owen-scrambled Sobol dimensions drive the pixel
//! position (dimensions 0–1) and every decision at the first hit (light choice 2, lobe 3,
//! light point 4–5, direction 6–7: two sets of four, computed together), where
//! stratification pays most; roulette and all deeper bounces draw from the sample's PCG
//! stream, which costs a fraction of a Sobol draw per number. Both are keyed by seed, pixel
//! and sample index only, so every sample is the same whatever thread renders it.
//!
//! Path length counts scattering events: with `max_depth = 0` only emitters seen directly
//! contribute, with 1 direct light only, and so on; `u32::MAX` leaves the length to roulette.

mod packet;

use super::Integrator;
use super::shading::ShadingPoint;
use super::shading::bsdf::{LobeChoice, sample_bsdf};
use super::shading::light_sampling::{LightPicker, LightSample, ShadowTarget};
use crate::color::Rgb;
use crate::geometry::{Ray, spawn_ray};
use crate::lanes::LANES;
use crate::sampling::Sampler;
use crate::sampling::mis::{light_sample_weight, power_heuristic};
use crate::world::lobes::LocalView;
use crate::world::{SurfaceHit, World, emitted};
use glam::{Vec2, Vec3};

/// Scattering events a path has had before Russian roulette may end it (a path continuing
/// from its fifth hit is the first to face roulette, like Mitsuba's `rr_depth = 5`).
pub const ROULETTE_START: u32 = 5;
/// Largest survival probability of Russian roulette.
pub const ROULETTE_MAX_SURVIVAL: f32 = 0.95;

/// The path tracer; build it for a world with [`PathTracer::new`].
#[derive(Clone, Debug)]
pub struct PathTracer {
    /// Maximum number of scattering events per path (`u32::MAX`: unbounded, ended by Russian
    /// roulette).
    pub max_depth: u32,
    /// Paths branching from the first hit (seed 002 §3.2: N paths from the first hit, one
    /// path after that); at least 1.
    pub first_hit_paths: u32,
    /// Scattering events a path has had before Russian roulette may end it
    /// (`ROULETTE_START`, 5, unless set otherwise: 1 lets roulette end every path that
    /// continues, which pays where surfaces reflect little, a canopy of leaves).
    pub roulette_start: u32,
    pub(super) lights: LightPicker,
    /// Lobe probabilities per scene material, `None` where a texture changes them from point
    /// to point.
    lobes: Vec<Option<LobeChoice>>,
}

/// How the path arrived at the vertex being shaded: what multiple importance sampling of
/// emission found there needs.
#[derive(Clone, Copy, Debug)]
pub(super) struct Arrival {
    /// The previous vertex.
    pub from: Vec3,
    /// Unit shading normal at the previous vertex, toward its viewer.
    pub normal: Vec3,
    /// Density (1/sr) of the direction under BSDF sampling; unused for delta lobes.
    pub pdf: f32,
    /// Arrived by a delta lobe or from the camera: emission counts in full.
    pub delta: bool,
}

impl Arrival {
    /// The camera ray: nothing to weigh against.
    pub(super) const CAMERA: Arrival = Arrival {
        from: Vec3::ZERO,
        normal: Vec3::ZERO,
        pdf: 0.0,
        delta: true,
    };
}

/// The uniform numbers one bounce uses, always drawn in the same order so that every
/// sample index uses the same Sobol dimension for the same decision.
pub(super) struct BounceNumbers {
    /// Chooses the light (and its triangle).
    pub light_pick: f32,
    /// The point on the light.
    pub light_point: Vec2,
    /// Chooses the material's lobe.
    pub lobe: f32,
    /// The scattered direction.
    pub direction: Vec2,
}

impl BounceNumbers {
    /// The numbers of the bounce at vertex `bounce` (0 = first hit): Sobol dimensions at the
    /// first hit, the pseudo-random stream deeper down.
    pub(super) fn draw(sampler: &mut Sampler, bounce: u32) -> Self {
        if bounce == 0 {
            BounceNumbers {
                light_pick: sampler.next_1d(),
                lobe: sampler.next_1d(),
                light_point: sampler.next_2d(),
                direction: sampler.next_2d(),
            }
        } else {
            BounceNumbers {
                light_pick: sampler.random_1d(),
                lobe: sampler.random_1d(),
                light_point: sampler.random_2d(),
                direction: sampler.random_2d(),
            }
        }
    }
}

impl PathTracer {
    /// A path tracer for `world` with at most `max_depth` scattering events per path and
    /// `first_hit_paths` branches at the first hit (0 is taken as 1).
    pub fn new(world: &World, max_depth: u32, first_hit_paths: u32) -> Self {
        PathTracer {
            max_depth,
            first_hit_paths: first_hit_paths.max(1),
            roulette_start: ROULETTE_START,
            lights: LightPicker::new(world),
            lobes: world
                .scene
                .materials
                .iter()
                .map(|m| {
                    m.diffuse_texture
                        .is_none()
                        .then(|| LobeChoice::of_material(m))
                })
                .collect(),
        }
    }

    /// Multiple-importance weight of emission found by BSDF sampling at `hit`.
    fn emission_weight(&self, world: &World, arrival: &Arrival, hit: &SurfaceHit) -> f32 {
        if arrival.delta {
            return 1.0;
        }
        match world.lights.area_light_of(hit.prim) {
            Some(light) => {
                let light_pdf = self
                    .lights
                    .area_pdf(world, light, arrival.from, hit.p, hit.ng);
                power_heuristic(arrival.pdf, light_pdf)
            }
            None => 1.0,
        }
    }

    /// Multiple-importance weight of sky radiance found by BSDF sampling along `dir`.
    fn sky_weight(&self, arrival: &Arrival, dir: Vec3) -> f32 {
        if arrival.delta {
            1.0
        } else {
            power_heuristic(arrival.pdf, self.lights.sky_pdf(arrival.normal, dir))
        }
    }

    /// The light sample of next-event estimation at `sp`, if the material can reflect it.
    fn sample_light(
        &self,
        world: &World,
        sp: &ShadingPoint,
        choice: &LobeChoice,
        numbers: &BounceNumbers,
    ) -> Option<LightSample> {
        if !choice.has_density() {
            return None;
        }
        let (pick, point) = (numbers.light_pick, numbers.light_point);
        let through = sp.material.is_translucent();
        self.lights
            .sample(world, sp.hit.p, sp.n, through, pick, point)
    }

    /// Radiance reflected toward the viewer at `sp` from the light sample `ls`, weighted
    /// against BSDF sampling: its shadow ray is traced here.
    fn next_event(
        &self,
        world: &World,
        sp: &ShadingPoint,
        choice: &LobeChoice,
        ls: &LightSample,
    ) -> Rgb {
        // The light must arrive on the side of the geometric surface the shading normal says
        // (in front, or behind through a translucent surface).
        let cos = sp.n.dot(ls.wi);
        if cos * sp.ng.dot(ls.wi) <= 0.0 {
            return Rgb::BLACK;
        }
        let f = sp.material.eval(sp.n, sp.wo, ls.wi);
        if f.is_black() {
            return Rgb::BLACK;
        }
        let visible = match ls.target {
            ShadowTarget::Point(p) => sp.sees(world, p),
            ShadowTarget::Infinity => sp.sees_along(world, ls.wi),
        };
        if !visible {
            return Rgb::BLACK;
        }
        let weight = light_sample_weight(ls.pdf, || choice.pdf(&sp.material, sp.n, sp.wo, ls.wi));
        f * ls.radiance_over_pdf * (cos.abs() * weight)
    }

    /// The vertex a path with throughput `beta`, `bounce` scattering events so far and
    /// arrival `arrival` reaches along `ray`: light it finds there (sky or emission, weighted
    /// against light sampling) is added to `radiance`; `None` when the path ends there (it
    /// escaped, reached its maximum length, or hit a surface that scatters nothing).
    #[inline(always)]
    pub(super) fn arrive(
        &self,
        world: &World,
        ray: &Ray,
        beta: Rgb,
        bounce: u32,
        arrival: &Arrival,
        radiance: &mut Rgb,
    ) -> Option<(ShadingPoint, LobeChoice)> {
        let Some(hit) = world.intersect(ray) else {
            if let Some(sky) = &world.lights.sky {
                *radiance += beta * sky.radiance(ray.dir) * self.sky_weight(arrival, ray.dir);
            }
            return None;
        };
        let le = emitted(&world.scene, &hit);
        if !le.is_black() {
            *radiance += beta * le * self.emission_weight(world, arrival, &hit);
        }
        if bounce >= self.max_depth {
            return None;
        }
        let sp = ShadingPoint::new(world, hit, ray.dir);
        if sp.material.is_black_from(hit.front_face) {
            return None;
        }
        let choice =
            self.lobes[hit.material as usize].unwrap_or_else(|| LobeChoice::new(&sp.material));
        if choice.is_black() {
            return None;
        }
        Some((sp, choice))
    }

    /// Radiance carried back along `ray` by a path with throughput `beta` that has scattered
    /// `bounce` times so far and arrived as `arrival` says.
    fn follow(
        &self,
        world: &World,
        mut ray: Ray,
        mut beta: Rgb,
        mut bounce: u32,
        mut arrival: Arrival,
        sampler: &mut Sampler,
    ) -> Rgb {
        let mut radiance = Rgb::BLACK;
        loop {
            let Some((sp, choice)) =
                self.arrive(world, &ray, beta, bounce, &arrival, &mut radiance)
            else {
                return radiance;
            };
            if bounce == 0 && self.first_hit_paths > 1 {
                return radiance + self.branch(world, &sp, &choice, beta, sampler);
            }
            let u = BounceNumbers::draw(sampler, bounce);
            let (light, next) = self.scatter_once(world, &sp, &choice, beta, bounce, &u, sampler);
            radiance += light;
            let Some(next) = next else {
                return radiance;
            };
            (ray, beta, arrival) = next;
            bounce += 1;
        }
    }

    /// The mean radiance of [`Self::first_hit_paths`] paths branching from the first hit `sp`.
    pub(super) fn branch(
        &self,
        world: &World,
        sp: &ShadingPoint,
        choice: &LobeChoice,
        beta: Rgb,
        sampler: &mut Sampler,
    ) -> Rgb {
        let mut sum = Rgb::BLACK;
        for _ in 0..self.first_hit_paths {
            let u = BounceNumbers::draw(sampler, 0);
            let (light, next) = self.scatter_once(world, sp, choice, beta, 0, &u, sampler);
            sum += light;
            if let Some((ray, beta, arrival)) = next {
                sum += self.follow(world, ray, beta, 1, arrival, sampler);
            }
        }
        sum / self.first_hit_paths as f32
    }

    /// One scattering event at `sp` for a path with throughput `beta` and `bounce` events so
    /// far, driven by the numbers `u`: the light sampled there (its shadow ray traced) and the
    /// continued path (ray, throughput, arrival), `None` when it ends.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn scatter_once(
        &self,
        world: &World,
        sp: &ShadingPoint,
        choice: &LobeChoice,
        beta: Rgb,
        bounce: u32,
        u: &BounceNumbers,
        sampler: &mut Sampler,
    ) -> (Rgb, Option<(Ray, Rgb, Arrival)>) {
        // The light sample, the continuation and then the shadow ray: the two samplings are
        // independent chains of divisions and square roots that the processor can overlap
        // when they are next to each other.
        let light = self.sample_light(world, sp, choice, u);
        let next = self.continue_path(sp, choice, beta, bounce, u, sampler);
        let radiance = match &light {
            Some(ls) => beta * self.next_event(world, sp, choice, ls),
            None => Rgb::BLACK,
        };
        (radiance, next)
    }

    /// The scattered ray, its throughput after Russian roulette (its number drawn from
    /// `sampler`'s pseudo-random stream) and how it leaves `sp`; `None` when the path ends
    /// here.
    fn continue_path(
        &self,
        sp: &ShadingPoint,
        choice: &LobeChoice,
        beta: Rgb,
        bounce: u32,
        numbers: &BounceNumbers,
        sampler: &mut Sampler,
    ) -> Option<(Ray, Rgb, Arrival)> {
        let side = LocalView {
            n: sp.n,
            ng: sp.ng,
            wo: sp.wo,
            front_face: sp.hit.front_face,
        };
        let bs = sample_bsdf(&sp.material, choice, &side, numbers.lobe, numbers.direction)?;
        let beta = survive_roulette(beta * bs.weight, (bounce, self.roulette_start), sampler)?;
        let arrival = Arrival {
            from: sp.hit.p,
            normal: sp.n,
            pdf: bs.pdf,
            delta: bs.delta,
        };
        Some((spawn_ray(sp.hit.p, sp.ng, bs.wi), beta, arrival))
    }
}

/// The throughput `beta` of a path continuing after `bounce + 1` scattering events, after
/// Russian roulette from `start` events on (its number drawn from `sampler`'s pseudo-random
/// stream); `None` when the path carries nothing or roulette ends it.
pub(super) fn survive_roulette(
    beta: Rgb,
    (bounce, start): (u32, u32),
    sampler: &mut Sampler,
) -> Option<Rgb> {
    if beta.is_black() {
        return None;
    }
    if bounce + 1 < start {
        return Some(beta);
    }
    let survival = beta.max_channel().min(ROULETTE_MAX_SURVIVAL);
    if survival <= 0.0 || sampler.random_1d() >= survival {
        return None;
    }
    Some(beta / survival)
}

impl Integrator for PathTracer {
    fn radiance(&self, world: &World, ray: &Ray, sampler: &mut Sampler) -> Rgb {
        self.follow(world, *ray, Rgb::WHITE, 0, Arrival::CAMERA, sampler)
    }

    fn radiance_batch(
        &self,
        world: &World,
        rays: &[Ray],
        samplers: &mut [Sampler],
        out: &mut [Rgb],
    ) {
        let packets = rays.chunks(LANES).zip(samplers.chunks_mut(LANES));
        for ((rays, samplers), out) in packets.zip(out.chunks_mut(LANES)) {
            self.radiance_packet(world, rays, samplers, out);
        }
    }
}
