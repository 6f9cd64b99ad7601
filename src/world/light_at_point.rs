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
    // An unrolled periodic world's own surfaces end at its margin; the light comes over the
    // endless field.
    !world
        .plot_world()
        .occluded(&Ray::new(origin, inc.wi), t_max)
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
/// over the weighted `points` (weights summing to 1), from `per_axis²` directions per point
/// (`SkyDirections`: stratified over all the points together, drawn anew for every set of
/// points; deterministic). The open weight and the whole weight are summed over all points
/// before they are divided: a point may have a single direction (a patch's 8 × 8 points have
/// one each), and one whose directions all fall where the weight is 0 (under the horizon of
/// a CIE sky) tells nothing of the share; counting it as closed read a vertical leaf's sky
/// light half as large as it is.
pub fn sky_share(
    world: &World,
    points: &[(DVec3, f64)],
    normal: DVec3,
    per_axis: u32,
    weight: impl Fn(Vec3) -> f64,
) -> f64 {
    let frame = Frame::from_normal(normal.as_vec3());
    let directions = SkyDirections::new(points, per_axis);
    // The sky is seen over the endless field of an unrolled periodic world.
    let world = world.plot_world();
    let (mut open_sum, mut total_sum) = (0.0, 0.0);
    for (k, &(x, w)) in points.iter().enumerate() {
        let (mut open, mut total) = (0.0, 0.0);
        for s in 0..directions.per_point {
            let dir = frame.to_world(cosine_hemisphere(directions.sample(k, s)));
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
        open_sum += w * open;
        total_sum += w * total;
    }
    if total_sum > 0.0 {
        open_sum / total_sum
    } else {
        0.0
    }
}

/// The sky directions of a set of points, as points of the unit square (to be warped to the
/// cosine-weighted hemisphere): `per_axis²` for each point. When the count over all points
/// is a square (a patch's 8 × 8 points with one direction each), the directions are the
/// jittered strata of one grid of that size dealt out to the points in a scrambled order, so
/// that the points together cover the hemisphere evenly; else each point's are a stratified
/// grid of their own. The jitter and the order are drawn from a hash of the first point's
/// place, so that each set of points (each patch) has directions of its own: with the same
/// directions everywhere the whole ground of a periodic field took its sky light from the
/// same 64 directions, 3 % too much (the black field of `tests/field.rs`).
struct SkyDirections {
    /// Directions per point.
    per_point: u32,
    /// Per axis of the per-point grid.
    per_axis: u32,
    /// Per axis of the shared grid; 0 when each point has its own.
    shared_side: u64,
    /// A multiplier coprime with the shared grid's cells, dealing them out.
    step: u64,
    /// Seed of the jitter and the deal.
    seed: u64,
}

impl SkyDirections {
    fn new(points: &[(DVec3, f64)], per_axis: u32) -> SkyDirections {
        let per_axis = per_axis.max(1);
        let per_point = per_axis * per_axis;
        let count = points.len() as u64 * u64::from(per_point);
        let side = (count as f64).sqrt().round() as u64;
        let shared_side = if points.len() > 1 && side * side == count {
            side
        } else {
            0
        };
        let seed = points.first().map_or(0, |&(x, _)| {
            x.to_array()
                .iter()
                .fold(0x5851_F42D_4C95_7F2D, |h, c| hash64(h ^ c.to_bits()))
        });
        // A deal step near the golden ratio of the cells, coprime with their number.
        let mut step = ((count as f64 * 0.618_034) as u64).max(1);
        while count > 1 && gcd(step, count) != 1 {
            step += 1;
        }
        SkyDirections {
            per_point,
            per_axis,
            shared_side,
            step,
            seed,
        }
    }

    /// Direction `s` of point `k`, a point of the unit square.
    fn sample(&self, k: usize, s: u32) -> Vec2 {
        let unit = |h: u64| (h >> 40) as f32 * (1.0 / 16_777_216.0);
        let j = k as u64 * u64::from(self.per_point) + u64::from(s);
        let h = hash64(self.seed ^ j);
        let jitter = Vec2::new(unit(h), unit(hash64(h)));
        if self.shared_side > 0 {
            let cells = self.shared_side * self.shared_side;
            let cell = (j * self.step % cells + self.seed % cells) % cells;
            stratified(cell as u32, self.shared_side as u32, jitter)
        } else {
            stratified(s, self.per_axis, jitter)
        }
    }
}

/// The greatest common divisor of `a` and `b`.
fn gcd(mut a: u64, mut b: u64) -> u64 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}
