//! Rays and the robust offset used to start secondary rays on a surface.

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
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Ray { origin, dir }
    }

    /// The point at parameter `t`.
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
pub fn surface_offset(p: Vec3) -> f32 {
    p.abs().max_element() * OFFSET_RELATIVE + OFFSET_ABSOLUTE
}

/// The origin for a ray leaving surface point `p` (geometric normal `n`, any orientation) in
/// direction `dir`: `p` moved along `±n` to the side `dir` points into.
pub fn offset_origin(p: Vec3, n: Vec3, dir: Vec3) -> Vec3 {
    let d = surface_offset(p);
    if n.dot(dir) >= 0.0 {
        p + n * d
    } else {
        p - n * d
    }
}

/// A ray leaving surface point `p` (geometric normal `n`) in direction `dir`.
pub fn spawn_ray(p: Vec3, n: Vec3, dir: Vec3) -> Ray {
    Ray::new(offset_origin(p, n, dir), dir)
}

/// A ray from surface point `p` (geometric normal `n`) towards `target`, with the parameter
/// range `(0, t_max)` that stops just short of the target. `dir` is unit length.
pub fn spawn_ray_to(p: Vec3, n: Vec3, target: Vec3) -> (Ray, f32) {
    let to = target - p;
    let origin = offset_origin(p, n, to);
    let d = target - origin;
    let dist = d.length();
    let dir = if dist > 0.0 { d * dist.recip() } else { n };
    let t_max = (dist - surface_offset(target)).max(0.0);
    (Ray::new(origin, dir), t_max)
}
