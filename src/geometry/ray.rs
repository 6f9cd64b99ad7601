//! Rays and the robust offset used to start secondary rays on a surface. The offset and the
//! spawned rays are written once over [`Real`], for one ray or eight ([`offset_origin_lanes`],
//! [`spawn_ray_to_lanes`]).

use crate::lanes::{Real, V3};
use glam::Vec3;

/// A ray `origin + t·dir`. `dir` need not be unit length: rays carried into object space keep
/// the world-space parameter `t` by not renormalising their direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Start point (scene units).
    pub origin: Vec3,
    /// Direction; unit length for camera, shadow and scattered rays in world space.
    pub dir: Vec3,
}

impl Ray {
    /// A ray from `origin` along `dir`.
    #[inline]
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Ray { origin, dir }
    }

    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// Relative size of the offset that moves a ray origin off the surface it starts on.
pub const OFFSET_RELATIVE: f32 = 1.0 / 131_072.0;
/// Absolute floor of that offset, for points near the coordinate origin.
pub const OFFSET_ABSOLUTE: f32 = 1e-7;

/// Distance a new ray origin is moved off a surface point `p` so that floating-point error in
/// `p` cannot make the ray hit the surface it starts on. It scales with the magnitude of the
/// coordinates (the error of a computed hit point does too).
#[inline]
pub fn surface_offset(p: Vec3) -> f32 {
    surface_offset_lanes(V3::from(p))
}

/// [`surface_offset`] lane by lane.
#[inline(always)]
pub fn surface_offset_lanes<R: Real>(p: V3<R>) -> R {
    let largest = p.x.abs().max(p.y.abs().max(p.z.abs()));
    largest * R::splat(OFFSET_RELATIVE) + R::splat(OFFSET_ABSOLUTE)
}

/// The origin for a ray leaving surface point `p` (geometric normal `n`, any orientation) in
/// direction `dir`: `p` moved along `±n` to the side `dir` points into.
#[inline]
pub fn offset_origin(p: Vec3, n: Vec3, dir: Vec3) -> Vec3 {
    offset_origin_lanes(V3::from(p), V3::from(n), V3::from(dir)).into()
}

/// [`offset_origin`] lane by lane.
#[inline(always)]
pub fn offset_origin_lanes<R: Real>(p: V3<R>, n: V3<R>, dir: V3<R>) -> V3<R> {
    let offset = n.scale(surface_offset_lanes(p));
    V3::select(n.dot(dir).ge(R::splat(0.0)), p + offset, p - offset)
}

/// A ray leaving surface point `p` (geometric normal `n`) in direction `dir`.
#[inline]
pub fn spawn_ray(p: Vec3, n: Vec3, dir: Vec3) -> Ray {
    Ray::new(offset_origin(p, n, dir), dir)
}

/// A ray from surface point `p` (geometric normal `n`) towards `target`, with the parameter
/// range `(0, t_max)` that stops just short of the target. `dir` is unit length.
#[inline]
pub fn spawn_ray_to(p: Vec3, n: Vec3, target: Vec3) -> (Ray, f32) {
    let (origin, dir, t_max) = spawn_ray_to_lanes(V3::from(p), V3::from(n), V3::from(target));
    (Ray::new(origin.into(), dir.into()), t_max)
}

/// [`spawn_ray_to`] lane by lane: origin, unit direction and parameter limit.
#[inline(always)]
pub fn spawn_ray_to_lanes<R: Real>(p: V3<R>, n: V3<R>, target: V3<R>) -> (V3<R>, V3<R>, R) {
    let origin = offset_origin_lanes(p, n, target - p);
    let d = target - origin;
    let dist = d.dot(d).sqrt();
    let zero = R::splat(0.0);
    let dir = V3::select(dist.gt(zero), d.scale(R::splat(1.0) / dist), n);
    let t_max = (dist - surface_offset_lanes(target)).max(zero);
    (origin, dir, t_max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::{LANES, Vec3x8};

    #[test]
    fn eight_lanes_spawn_the_rays_one_lane_spawns_bit_for_bit() {
        let mut seed = 2024u32;
        let mut next = |scale: f32| {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            ((seed >> 8) as f32 / 16_777_216.0 * 2.0 - 1.0) * scale
        };
        for _ in 0..300 {
            let mut vec = |scale| Vec3::new(next(scale), next(scale), next(scale));
            let p: [Vec3; LANES] = std::array::from_fn(|_| vec(40.0));
            let n: [Vec3; LANES] = std::array::from_fn(|_| vec(1.0).normalize_or(Vec3::Y));
            // One lane aims at its own point (zero distance).
            let target: [Vec3; LANES] =
                std::array::from_fn(|i| if i == 3 { p[i] } else { vec(40.0) });
            let lanes = |v: &[Vec3; LANES]| Vec3x8::from_lanes(v);
            let (origin, dir, t_max) = spawn_ray_to_lanes(lanes(&p), lanes(&n), lanes(&target));
            let away = offset_origin_lanes(lanes(&p), lanes(&n), lanes(&target));
            for i in 0..LANES {
                let (ray, limit) = spawn_ray_to(p[i], n[i], target[i]);
                assert_eq!(
                    (origin.lane(i), dir.lane(i), t_max.as_array_ref()[i]),
                    (ray.origin, ray.dir, limit),
                    "lane {i}"
                );
                assert_eq!(away.lane(i), offset_origin(p[i], n[i], target[i]));
            }
        }
    }
}
