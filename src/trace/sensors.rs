//! Readings at point sensors by ray tracing from the sensor:
//! - direct light: point, Lambertian, spot and directional lights and the sky through
//!   [`crate::world::non_surface_irradiance`] (exact for the first four, stratified directions for
//!   the sky); every emitting surface by `samples` stratified points on it,
//!   `E = ⟨L·cos θₛ·cos θₗ / (d²·p_A)⟩` with a shadow ray each — what the standard ray
//!   tracer's direct light computes at a surface point;
//! - indirect light (with an integrator, the path tracer): `paths` cosine-distributed rays
//!   from the sensor, `E = π·⟨L − Lₑ⟩`, where `L` is the radiance the integrator returns along
//!   the ray and `Lₑ` what the surface it meets emits toward the sensor (counted above).
//!
//! Both carry the standard error of their mean (the strata treated as independent draws,
//! which overstates it). Deterministic: each sensor draws from its own stream of the seed.
//!
//! [`irradiance_sample`] is one draw of the same two estimates at any surface point, for
//! callers that spread their draws over many points (the final gather at reported surfaces).

use super::Integrator;
use crate::color::{Rgb, Rgb64};
use crate::geometry::{Frame, Ray, offset_origin};
use crate::measure::SensorReading;
use crate::sampling::mis::power_heuristic;
use crate::sampling::warp::{cosine_hemisphere, stratified};
use crate::sampling::{Moments, Sampler, SequenceKind};
use crate::scene::{LightKind, Sensor};
use crate::world::{
    SurfaceHit, World, emitted, non_surface_irradiance, point_irradiance, sees_point,
};
use glam::Vec3;
use rayon::prelude::*;
use std::f64::consts::PI;

/// How many rays a sensor reading spends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SensorSettings {
    /// Points sampled on each emitting surface per sensor.
    pub samples: u32,
    /// Cosine-distributed rays per sensor for the indirect light (with an integrator).
    pub paths: u32,
    /// Seed of all random numbers.
    pub seed: u64,
}

/// The reading of every sensor of `world`'s scene: direct light only without an
/// integrator (the standard ray tracer), direct plus indirect with one (the path tracer).
pub fn sensor_readings(
    world: &World,
    integrator: Option<&dyn Integrator>,
    settings: &SensorSettings,
) -> Vec<SensorReading> {
    world
        .scene
        .sensors
        .par_iter()
        .enumerate()
        .map(|(index, sensor)| {
            let (direct, direct_variance) = direct(world, sensor, index as u64, settings);
            let (indirect, indirect_variance) = match integrator {
                Some(integrator) => indirect(world, integrator, sensor, index as u64, settings),
                None => (Rgb64::BLACK, Rgb64::BLACK),
            };
            SensorReading {
                sensor: sensor.clone(),
                direct,
                indirect,
                standard_error: Some((direct_variance + indirect_variance).map(f64::sqrt)),
            }
        })
        .collect()
}

/// Direct irradiance at `sensor` (W·m⁻²) and the variance of its estimate.
fn direct(world: &World, sensor: &Sensor, index: u64, settings: &SensorSettings) -> (Rgb64, Rgb64) {
    let (x, n) = (sensor.position, sensor.normal);
    let mut total = non_surface_irradiance(world, sensor);
    let mut variance = Rgb64::BLACK;
    let per_axis = (settings.samples.max(1) as f64).sqrt().ceil() as u32;
    for light in 0..world.lights.area.len() {
        let mut sampler = Sampler::new(SequenceKind::Random, settings.seed, index, light as u32);
        let mut m = Moments::default();
        for k in 0..per_axis * per_axis {
            let u_pick = sampler.next_1d();
            let u = stratified(k, per_axis, sampler.next_2d());
            let s = world.lights.sample_area(&world.geometry, light, u_pick, u);
            m.add(area_sample(world, x, n, light, &s));
        }
        total += m.mean();
        variance += m.variance_of_mean();
    }
    (total, variance)
}

/// `L·cos θₛ·cos θₗ / (d²·p_A)` of the point `s` of area light `light` seen from the sensor
/// at `x` (unit normal `n`), 0 when it faces away or is hidden.
fn area_sample(
    world: &World,
    x: Vec3,
    n: Vec3,
    light: usize,
    s: &crate::world::AreaSample,
) -> Rgb64 {
    let d = s.p - x;
    let d2 = d.length_squared();
    if d2 <= 0.0 {
        return Rgb64::BLACK;
    }
    let wi = d / d2.sqrt();
    let (cos_x, cos_y) = (n.dot(wi), s.n.dot(-wi));
    if cos_x <= 0.0 || cos_y == 0.0 {
        return Rgb64::BLACK;
    }
    let le = world
        .lights
        .area_radiance(&world.scene, &world.geometry, light, s, cos_y > 0.0);
    if le.is_black() || !sees_point(world, (x, n), (s.p, s.n)) {
        return Rgb64::BLACK;
    }
    le.to_f64() * f64::from(cos_x * cos_y.abs() / (d2 * s.pdf_area))
}

/// One estimate of the irradiance at the surface point `x` (unit normal `n` of the side
/// that receives), W·m⁻², as `(direct, indirect)`: point, Lambertian, spot and directional
/// lights exactly (a shadow ray each; directional ones only when `directional`, false where
/// the caller counts them otherwise); each emitting surface by one point on it and by one
/// cosine-distributed ray, the two weighed by multiple importance sampling (the power
/// heuristic: a point on a large emitter right beside `x` would otherwise weigh without
/// bound); the sky where that ray meets nothing (direct, `π·L`); and the indirect light along
/// it, `π·(L − Lₑ)` of what `integrator` returns. Every random number comes from `sampler`:
/// the point on each emitting surface first, then the ray's direction, then the
/// integrator's.
pub fn irradiance_sample(
    world: &World,
    integrator: &dyn Integrator,
    (x, n): (Vec3, Vec3),
    directional: bool,
    sampler: &mut Sampler,
) -> (Rgb64, Rgb64) {
    let (xd, nd) = (x.as_dvec3(), n.as_dvec3());
    let mut direct = world
        .lights
        .delta
        .iter()
        .filter(|light| directional || !matches!(light, LightKind::Directional { .. }))
        .map(|light| point_irradiance(world, light, xd, nd, 1))
        .fold(Rgb64::BLACK, |a, b| a + b);
    let cosine_pdf = |cos: f32| cos.max(0.0) * std::f32::consts::FRAC_1_PI;
    for light in 0..world.lights.area.len() {
        let u_pick = sampler.next_1d();
        let s = world
            .lights
            .sample_area(&world.geometry, light, u_pick, sampler.next_2d());
        let d = s.p - x;
        let wi = d.normalize_or_zero();
        // A point seen edge-on (or `x` itself) brings nothing: no weight to find.
        let light_pdf = s.pdf_area * d.length_squared() / s.n.dot(wi).abs();
        if light_pdf.is_finite() && light_pdf > 0.0 {
            let weight = power_heuristic(light_pdf, cosine_pdf(n.dot(wi)));
            direct += area_sample(world, x, n, light, &s) * f64::from(weight);
        }
    }
    let dir = Frame::from_normal(n).to_world(cosine_hemisphere(sampler.next_2d()));
    let ray = Ray::new(offset_origin(x, n, dir), dir);
    let indirect = match world.intersect(&ray) {
        None => {
            direct += world
                .lights
                .sky
                .as_ref()
                .map_or(Rgb64::BLACK, |sky| sky.radiance(dir).to_f64() * PI);
            Rgb64::BLACK
        }
        Some(hit) => {
            let le = emitted(&world.scene, &hit);
            if let Some(light) = world.lights.area_light_of(hit.prim) {
                let distance2 = (hit.p - x).length_squared();
                let light_pdf = distance2 / (world.lights.area[light].area * hit.ng.dot(dir).abs());
                if light_pdf.is_finite() {
                    let weight = power_heuristic(cosine_pdf(n.dot(dir)), light_pdf);
                    direct += le.to_f64() * (PI * f64::from(weight));
                }
            }
            reflected_irradiance(world, integrator, (&ray, hit, le), sampler)
        }
    };
    (direct, indirect)
}

/// `π·(L − Lₑ)` along a cosine-distributed `ray` that met `hit`, whose surface emits `le`
/// toward it: what `integrator` returns, less the emission (counted as direct light), as
/// one estimate of the indirect irradiance at the ray's origin, W·m⁻².
fn reflected_irradiance(
    world: &World,
    integrator: &dyn Integrator,
    (ray, hit, le): (&Ray, SurfaceHit, Rgb),
    sampler: &mut Sampler,
) -> Rgb64 {
    let reflected = integrator.radiance_at(world, ray, hit, sampler) - le;
    reflected.to_f64().map(|c| c.max(0.0)) * PI
}

/// Indirect irradiance at `sensor` (W·m⁻²) and the variance of its estimate.
fn indirect(
    world: &World,
    integrator: &dyn Integrator,
    sensor: &Sensor,
    index: u64,
    settings: &SensorSettings,
) -> (Rgb64, Rgb64) {
    let frame = Frame::from_normal(sensor.normal);
    let per_axis = (settings.paths.max(1) as f64).sqrt().ceil() as u32;
    let mut m = Moments::default();
    for k in 0..per_axis * per_axis {
        let mut sampler = Sampler::new(SequenceKind::Random, settings.seed ^ PATH_KEY, index, k);
        let dir = frame.to_world(cosine_hemisphere(stratified(
            k,
            per_axis,
            sampler.next_2d(),
        )));
        let ray = Ray::new(offset_origin(sensor.position, sensor.normal, dir), dir);
        let Some(hit) = world.intersect(&ray) else {
            m.add(Rgb64::BLACK);
            continue;
        };
        let le = emitted(&world.scene, &hit);
        m.add(reflected_irradiance(
            world,
            integrator,
            (&ray, hit, le),
            &mut sampler,
        ));
    }
    (m.mean(), m.variance_of_mean())
}

/// Mixed into the seed of the indirect rays so they draw other numbers than the direct ones.
const PATH_KEY: u64 = 0x5EB5_0A7C_1D2E_3F41;
