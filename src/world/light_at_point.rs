//! The irradiance a point, Lambertian, spot or directional light or the sky sends to one
//! point of a surface or to a sensor, with shadows: what every algorithm that evaluates such
//! lights at a point shares (radiosity's emitter-only links, sensor readings), and the
//! shadow test between two points that sensor readings share.

use super::World;
use crate::color::Rgb64;
use crate::geometry::{Frame, Ray, offset_origin};
use crate::sampling::hash64;
use crate::sampling::warp::{cosine_hemisphere, stratified};
use crate::scene::{LightKind, Sensor};
use glam::{DVec3, Vec2, Vec3};
use std::f64::consts::PI;

/// The irradiance (W·m⁻²) that `light` sends to the point `x` whose receiving side has the
/// unit normal `normal`, with shadows: `I·f·cos θ/d²` for point, Lambertian and spot lights
/// (`f` the falloff), `E·cos θ` for a directional light, and for a sky what
/// [`sky_irradiance`] estimates with `sky_per_axis²` stratified directions.
pub fn point_irradiance(
    world: &World,
    light: &LightKind,
    x: DVec3,
    normal: DVec3,
    sky_per_axis: u32,
) -> Rgb64 {
    match *light {
        LightKind::Sky { .. } | LightKind::CieSky { .. } => {
            sky_irradiance(world, light, &[(x, 1.0)], normal, sky_per_axis)
        }
        LightKind::Point { .. }
        | LightKind::Lambertian { .. }
        | LightKind::Spot { .. }
        | LightKind::Directional { .. } => {
            let Some(inc) = light.incidence(x.as_vec3()) else {
                return Rgb64::BLACK;
            };
            let cos = normal.dot(inc.wi.as_dvec3());
            if cos <= 0.0 || !sees_light(world, x, normal, light) {
                return Rgb64::BLACK;
            }
            inc.irradiance.to_f64() * cos
        }
    }
}

/// The irradiance (W·m⁻²) that the sky `light` sends to the weighted surface `points`
/// (weights summing to 1) whose receiving side has the unit normal `normal`, with shadows,
/// from `per_axis²` stratified cosine-distributed directions at every point
/// ([`sky_share`]): `π·L` times the open share for a uniform sky of radiance `L`; for a CIE
/// sky the irradiance an unoccluded surface of that orientation receives (a quadrature of
/// the sky's radiance) times the open share of the directions weighted by the sky's
/// radiance — exact wherever the sky is not occluded. Black for a light that is not a sky.
pub fn sky_irradiance(
    world: &World,
    light: &LightKind,
    points: &[(DVec3, f64)],
    normal: DVec3,
    per_axis: u32,
) -> Rgb64 {
    match *light {
        LightKind::Sky { radiance } => {
            radiance.to_f64() * (PI * sky_share(world, points, normal, per_axis, |_| 1.0))
        }
        LightKind::CieSky { .. } => {
            let Some(sky) = world.cie_sky(light) else {
                return Rgb64::BLACK;
            };
            let unshadowed = sky.irradiance_on(normal);
            if unshadowed.is_black() {
                return Rgb64::BLACK;
            }
            let weight = |dir: Vec3| sky.relative_radiance(dir.as_dvec3());
            unshadowed * sky_share(world, points, normal, per_axis, weight)
        }
        LightKind::Point { .. }
        | LightKind::Lambertian { .. }
        | LightKind::Spot { .. }
        | LightKind::Directional { .. } => Rgb64::BLACK,
    }
}

/// Sky directions per axis from each sensor (`n × n` cosine-weighted strata).
const SENSOR_SKY_DIRECTIONS_PER_AXIS: u32 = 32;

/// The irradiance (W·m⁻²) that all point, Lambertian, spot and directional lights and the
/// sky of `world` send to `sensor` ([`point_irradiance`] of each, the sky with 32 × 32
/// directions): the part of every method's sensor reading that no photon or path needs.
pub fn non_surface_irradiance(world: &World, sensor: &Sensor) -> Rgb64 {
    let (x, normal) = (sensor.position.as_dvec3(), sensor.normal.as_dvec3());
    let skies: Vec<LightKind> = world.lights.sky.iter().flat_map(|s| s.lights()).collect();
    world
        .lights
        .delta
        .iter()
        .chain(&skies)
        .map(|light| point_irradiance(world, light, x, normal, SENSOR_SKY_DIRECTIONS_PER_AXIS))
        .fold(Rgb64::BLACK, |a, b| a + b)
}

/// True when the way from surface point `x` (unit normal `normal` of the receiving side)
/// to the point, Lambertian, spot or directional `light` is free.
pub fn sees_light(world: &World, x: DVec3, normal: DVec3, light: &LightKind) -> bool {
    let Some(inc) = light.incidence(x.as_vec3()) else {
        return false;
    };
    let origin = offset_origin(x.as_vec3(), normal.as_vec3(), inc.wi);
    let t_max = if inc.distance.is_finite() {
        (x.as_vec3() + inc.wi * inc.distance - origin).length()
    } else {
        f32::INFINITY
    };
    !world.occluded(&Ray::new(origin, inc.wi), t_max)
}

/// True when nothing lies between the points `x` (unit normal `nx`) and `y` (unit normal
/// `ny`); both ends are moved off the surfaces they may lie on first (a sensor's point is
/// moved along its normal as if it lay on one).
pub fn sees_point(world: &World, (x, nx): (Vec3, Vec3), (y, ny): (Vec3, Vec3)) -> bool {
    let start = offset_origin(x, nx, y - x);
    let end = offset_origin(y, ny, x - y);
    let d = end - start;
    let length = d.length();
    if length.is_nan() || length <= 0.0 {
        return true;
    }
    // The ray stops short of `end` by a share of its length: a hit computed after travelling
    // far is off by a share of that distance, more than the offset of an end lying near the
    // coordinate origin (a sensor at (0, 0, 0) on a floor read 5 % low without it).
    !world.occluded(
        &Ray::new(start, d / length),
        length * (1.0 - FAR_END_MARGIN),
    )
}

/// Share of a point-to-point shadow ray's length left out at its far end ([`sees_point`]).
const FAR_END_MARGIN: f32 = 1e-5;

/// The cosine-weighted share of the hemisphere over `normal` that reaches the sky, each
/// direction also weighted by `weight` (≥ 0; 1 for a uniform sky, the radiance for another),
/// averaged over the weighted `points` (weights summing to 1): `per_axis²` stratified
/// directions per point, jittered by a hash of the point's place in the list and the stratum
/// (deterministic); a point whose directions all weigh 0 adds nothing.
pub fn sky_share(
    world: &World,
    points: &[(DVec3, f64)],
    normal: DVec3,
    per_axis: u32,
    weight: impl Fn(Vec3) -> f64,
) -> f64 {
    let n = per_axis.max(1);
    let frame = Frame::from_normal(normal.as_vec3());
    let unit = |h: u64| (h >> 40) as f32 * (1.0 / 16_777_216.0);
    let mut share = 0.0;
    for (k, &(x, w)) in points.iter().enumerate() {
        let (mut open, mut total) = (0.0, 0.0);
        for s in 0..n * n {
            let h = hash64((k as u64) << 32 | s as u64);
            let jitter = Vec2::new(unit(h), unit(hash64(h)));
            let dir = frame.to_world(cosine_hemisphere(stratified(s, n, jitter)));
            let weight = weight(dir);
            if weight.is_nan() || weight <= 0.0 {
                continue;
            }
            total += weight;
            let origin = offset_origin(x.as_vec3(), normal.as_vec3(), dir);
            if !world.occluded(&Ray::new(origin, dir), f32::INFINITY) {
                open += weight;
            }
        }
        if total > 0.0 {
            share += w * open / total;
        }
    }
    share
}
