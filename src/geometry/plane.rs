//! The infinite plane `z = 0` (object space of every plane); its front side faces `+z`.

use super::Ray;
use super::local_hit::LocalHit;
use glam::{Vec2, Vec3};

/// First stage: the `t ∈ (0, t_max]` where `ray` crosses `z = 0`.
pub fn intersect(ray: &Ray, t_max: f32) -> Option<f32> {
    if ray.dir.z == 0.0 {
        return None;
    }
    let t = -ray.origin.z / ray.dir.z;
    (t > 0.0 && t <= t_max).then_some(t)
}

/// Second stage at point `p`: `(u, v) = (x, y)`, one texture repeat per scene unit.
pub fn describe(p: Vec3) -> LocalHit {
    let p = Vec3::new(p.x, p.y, 0.0);
    LocalHit {
        p,
        n: Vec3::Z,
        uv: Vec2::new(p.x, p.y),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_from_both_sides_and_misses_parallel() {
        assert_eq!(
            intersect(&Ray::new(Vec3::new(1.0, 2.0, 3.0), -Vec3::Z), 10.0),
            Some(3.0)
        );
        assert_eq!(
            intersect(&Ray::new(Vec3::new(0.0, 0.0, -2.0), Vec3::Z), 10.0),
            Some(2.0)
        );
        assert!(intersect(&Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::X), 10.0).is_none());
        assert!(intersect(&Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::Z), 10.0).is_none());
    }
}
