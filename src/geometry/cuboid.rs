//! The unit cube `[0,1]³` (object space of every box).

use super::Ray;
use super::local_hit::LocalHit;
use glam::{Vec2, Vec3};

/// First stage: smallest `t ∈ (0, t_max]` where `ray` meets the cube's surface, with the
/// index of the face hit (`axis * 2 + side`, side 1 = the face at coordinate 1).
pub fn intersect(ray: &Ray, t_max: f32) -> Option<(f32, u32)> {
    let inv = ray.dir.recip();
    let t0 = -ray.origin * inv;
    let t1 = (Vec3::ONE - ray.origin) * inv;
    let near = t0.min(t1);
    let far = t0.max(t1);
    let (t_near, near_axis) = max_with_axis(near);
    let (t_far, far_axis) = min_with_axis(far);
    if t_near > t_far || t_far <= 0.0 {
        return None;
    }
    let (t, axis, exiting) = if t_near > 0.0 {
        (t_near, near_axis, false)
    } else {
        (t_far, far_axis, true)
    };
    if t > t_max {
        return None;
    }
    // Entering through the low face when moving up the axis; exiting through the high face.
    let positive = ray.dir[axis] > 0.0;
    let side = u32::from(positive == exiting);
    Some((t, axis as u32 * 2 + side))
}

fn max_with_axis(v: Vec3) -> (f32, usize) {
    let axis = if v.x >= v.y && v.x >= v.z {
        0
    } else if v.y >= v.z {
        1
    } else {
        2
    };
    (v[axis], axis)
}

fn min_with_axis(v: Vec3) -> (f32, usize) {
    let axis = if v.x <= v.y && v.x <= v.z {
        0
    } else if v.y <= v.z {
        1
    } else {
        2
    };
    (v[axis], axis)
}

/// Second stage at point `p` on face `face` (as returned by [`intersect`]). Each face is
/// parameterised by the two other coordinates in cyclic order.
pub fn describe(p: Vec3, face: u32) -> LocalHit {
    let axis = (face / 2) as usize;
    let side = face % 2;
    let mut p = p.clamp(Vec3::ZERO, Vec3::ONE);
    p[axis] = side as f32;
    let mut n = Vec3::ZERO;
    n[axis] = if side == 1 { 1.0 } else { -1.0 };
    let (ua, va) = ((axis + 1) % 3, (axis + 2) % 3);
    LocalHit {
        p,
        n,
        uv: Vec2::new(p[ua], p[va]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn enters_and_exits_through_the_right_faces() {
        let r = Ray::new(Vec3::new(0.5, 0.5, -1.0), Vec3::Z);
        let (t, face) = intersect(&r, f32::INFINITY).unwrap();
        assert!((t - 1.0).abs() < 1e-6);
        assert_eq!(describe(r.at(t), face).n, -Vec3::Z);
        let inside = Ray::new(Vec3::splat(0.5), Vec3::X);
        let (t, face) = intersect(&inside, f32::INFINITY).unwrap();
        assert!((t - 0.5).abs() < 1e-6);
        assert_eq!(describe(inside.at(t), face).n, Vec3::X);
        let back = Ray::new(Vec3::splat(0.5), -Vec3::Y);
        let (_, face) = intersect(&back, f32::INFINITY).unwrap();
        assert_eq!(describe(back.at(0.5), face).n, -Vec3::Y);
    }

    #[test]
    fn misses() {
        assert!(intersect(&Ray::new(Vec3::new(2.0, 0.5, -1.0), Vec3::Z), 100.0).is_none());
        assert!(intersect(&Ray::new(Vec3::new(0.5, 0.5, 2.0), Vec3::Z), 100.0).is_none());
        assert!(intersect(&Ray::new(Vec3::new(0.5, 0.5, -1.0), Vec3::Z), 0.5).is_none());
    }
}
