//! The unit sphere at the origin (object space of every sphere).

use super::Ray;
use super::local_hit::{LocalHit, quadratic_first_root};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// First stage: smallest `t ∈ (0, t_max]` where `ray` meets the unit sphere.
pub fn intersect(ray: &Ray, t_max: f32) -> Option<f32> {
    let a = ray.dir.length_squared();
    let b = 2.0 * ray.origin.dot(ray.dir);
    let c = ray.origin.length_squared() - 1.0;
    quadratic_first_root(a, b, c, t_max)
}

/// Second stage at point `p` on the sphere. `u` runs around the y axis, `v` from the south
/// pole (0) to the north pole (1).
pub fn describe(p: Vec3) -> LocalHit {
    let p = p.normalize_or(Vec3::Y);
    let phi = p.z.atan2(p.x);
    let theta = p.y.clamp(-1.0, 1.0).acos();
    let u = 0.5 + phi / (2.0 * PI);
    let v = 1.0 - theta / PI;
    LocalHit {
        p,
        n: p,
        uv: Vec2::new(u, v),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outside_and_inside() {
        let r = Ray::new(Vec3::new(0.0, 0.0, -3.0), Vec3::Z);
        assert!((intersect(&r, f32::INFINITY).unwrap() - 2.0).abs() < 1e-6);
        let inside = Ray::new(Vec3::ZERO, Vec3::X);
        assert!((intersect(&inside, f32::INFINITY).unwrap() - 1.0).abs() < 1e-6);
        assert!(intersect(&Ray::new(Vec3::new(0.0, 2.0, -3.0), Vec3::Z), 100.0).is_none());
        assert!(intersect(&Ray::new(Vec3::new(0.0, 0.0, 3.0), Vec3::Z), 100.0).is_none());
    }

    #[test]
    fn description_is_consistent() {
        let h = describe(Vec3::new(0.6, 0.0, 0.8));
        assert!((h.n.length() - 1.0).abs() < 1e-6);
        assert!((h.p - Vec3::new(0.6, 0.0, 0.8)).length() < 1e-6);
        assert!((describe(Vec3::Y).uv.y - 1.0).abs() < 1e-6);
    }
}
