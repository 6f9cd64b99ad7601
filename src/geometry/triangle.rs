//! Ray–triangle intersection (Möller–Trumbore) on precomputed edges.

use super::Ray;
use glam::Vec3;

/// A triangle stored as one vertex and two edges, ready for intersection tests.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    /// First vertex.
    pub p0: Vec3,
    /// `p1 - p0`.
    pub e1: Vec3,
    /// `p2 - p0`.
    pub e2: Vec3,
}

impl Triangle {
    /// The triangle `(p0, p1, p2)`; its front side is where the vertices run counter-clockwise.
    pub fn new(p0: Vec3, p1: Vec3, p2: Vec3) -> Self {
        Triangle {
            p0,
            e1: p1 - p0,
            e2: p2 - p0,
        }
    }

    /// The three vertices.
    pub fn vertices(&self) -> [Vec3; 3] {
        [self.p0, self.p0 + self.e1, self.p0 + self.e2]
    }

    /// Unnormalised normal `e1 × e2`, pointing to the front side; its length is twice the area.
    pub fn normal_area2(&self) -> Vec3 {
        self.e1.cross(self.e2)
    }

    /// Area in squared scene units.
    pub fn area(&self) -> f32 {
        0.5 * self.normal_area2().length()
    }

    /// First stage: the hit parameter `t ∈ (0, t_max]` and barycentrics `(b1, b2)` of the
    /// vertices `p1` and `p2`, or `None` for a miss. Both sides are hit.
    #[inline(always)]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(f32, f32, f32)> {
        let pvec = ray.dir.cross(self.e2);
        let det = self.e1.dot(pvec);
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let inv_det = 1.0 / det;
        let tvec = ray.origin - self.p0;
        let b1 = tvec.dot(pvec) * inv_det;
        if !(0.0..=1.0).contains(&b1) {
            return None;
        }
        let qvec = tvec.cross(self.e1);
        let b2 = ray.dir.dot(qvec) * inv_det;
        if b2 < 0.0 || b1 + b2 > 1.0 {
            return None;
        }
        let t = self.e2.dot(qvec) * inv_det;
        (t > 0.0 && t <= t_max).then_some((t, b1, b2))
    }

    /// The point with barycentrics `(b1, b2)`, computed from the vertices (not from the ray,
    /// whose parameter carries more rounding error).
    pub fn point(&self, b1: f32, b2: f32) -> Vec3 {
        self.p0 + self.e1 * b1 + self.e2 * b2
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> Triangle {
        Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y)
    }

    #[test]
    fn hits_inside_from_both_sides() {
        let t = tri();
        let (th, b1, b2) = t
            .intersect(
                &Ray::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z),
                f32::INFINITY,
            )
            .unwrap();
        assert!((th - 1.0).abs() < 1e-6 && (b1 - 0.25).abs() < 1e-6 && (b2 - 0.25).abs() < 1e-6);
        assert!(
            t.intersect(
                &Ray::new(Vec3::new(0.25, 0.25, -1.0), Vec3::Z),
                f32::INFINITY
            )
            .is_some()
        );
        assert!(t.normal_area2().z > 0.0);
        assert!((t.area() - 0.5).abs() < 1e-6);
    }

    #[test]
    fn misses_outside_behind_and_beyond_t_max() {
        let t = tri();
        let down = -Vec3::Z;
        assert!(
            t.intersect(&Ray::new(Vec3::new(0.6, 0.6, 1.0), down), 10.0)
                .is_none()
        );
        assert!(
            t.intersect(&Ray::new(Vec3::new(0.25, 0.25, -1.0), down), 10.0)
                .is_none()
        );
        assert!(
            t.intersect(&Ray::new(Vec3::new(0.25, 0.25, 1.0), down), 0.5)
                .is_none()
        );
        // A ray in the triangle's plane never hits.
        assert!(
            t.intersect(&Ray::new(Vec3::new(-1.0, 0.2, 0.0), Vec3::X), 10.0)
                .is_none()
        );
    }
}
