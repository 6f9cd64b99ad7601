//! Ray–triangle intersection on precomputed edges.
//!
//! The test is Möller–Trumbore's algebra rearranged around the unnormalised normal
//! `N = e1 × e2` (as in Embree's variant): with `s = p0 − o` and `g = s × d`, the ray meets
//! the plane where `det·t = s·N` and `det·b1 = e2·g`, `det·b2 = −e1·g`, `det = d·N`. Whether
//! the ray hits is decided on these products, their signs flipped by the sign of `det`, with no
//! division; the one division, `1/det`, is left for a hit. Eight-lane blocks
//! ([`super::Triangle8`]) perform the same operations in the same order, so both agree bit for
//! bit.

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
        let n = self.normal_area2();
        let s = self.p0 - ray.origin;
        let det = ray.dir.dot(n);
        let g = s.cross(ray.dir);
        let scaled = ScaledHit {
            det,
            b1: self.e2.dot(g),
            b2: -self.e1.dot(g),
            t: s.dot(n),
        };
        if !scaled.passes(widen_t_max(t_max)) {
            return None;
        }
        scaled.divide(t_max)
    }

    /// The point with barycentrics `(b1, b2)`, computed from the vertices (not from the ray,
    /// whose parameter carries more rounding error).
    pub fn point(&self, b1: f32, b2: f32) -> Vec3 {
        self.p0 + self.e1 * b1 + self.e2 * b2
    }
}

/// A candidate hit before the division: the determinant `det = d·N` and the hit parameter and
/// barycentrics multiplied by it.
#[derive(Clone, Copy, Debug)]
pub(super) struct ScaledHit {
    /// `d·N`.
    pub det: f32,
    /// `det·b1`.
    pub b1: f32,
    /// `det·b2`.
    pub b2: f32,
    /// `det·t`.
    pub t: f32,
}

/// `x` with its sign flipped where `det` is negative (exact: only the sign bit changes).
#[inline(always)]
fn signed_by(x: f32, det: f32) -> f32 {
    f32::from_bits(x.to_bits() ^ (det.to_bits() & SIGN_BIT))
}

/// The sign bit of an `f32`.
pub(super) const SIGN_BIT: u32 = 0x8000_0000;

/// `t_max` for the division-free test, widened by a few ulps more than the rounding of
/// `t = (det·t)·(1/det)` and of the products, so that every hit whose divided `t` lies within
/// `t_max` passes and the exact bound is applied after the division. (Without the slack, two
/// triangles hit at the same `t` could be told apart by which was tested first.)
#[inline(always)]
pub(super) fn widen_t_max(t_max: f32) -> f32 {
    t_max * (1.0 + 8.0 * f32::EPSILON)
}

impl ScaledHit {
    /// The division-free test: `b1, b2 ≥ 0`, `b1 + b2 ≤ 1` and `0 < t ≤ t_max`, each multiplied
    /// by `|det|`, with `t_max` already widened by [`widen_t_max`]. A zero or non-finite
    /// determinant never passes.
    #[inline(always)]
    pub fn passes(&self, wide_t_max: f32) -> bool {
        let abs_det = self.det.abs();
        let (b1, b2) = (signed_by(self.b1, self.det), signed_by(self.b2, self.det));
        let t = signed_by(self.t, self.det);
        b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= abs_det && t > 0.0 && t <= wide_t_max * abs_det
    }

    /// `(t, b1, b2)` with the determinant divided out, `None` when rounding puts `t` outside
    /// `(0, t_max]` (or `det` was infinite).
    #[inline(always)]
    pub fn divide(&self, t_max: f32) -> Option<(f32, f32, f32)> {
        let inv_det = 1.0 / self.det;
        let t = self.t * inv_det;
        (t > 0.0 && t <= t_max).then_some((t, self.b1 * inv_det, self.b2 * inv_det))
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
    fn a_hit_at_t_is_found_again_with_t_max_equal_to_t() {
        // Order-independence of closest hits needs this: a triangle tested after another hit
        // at the same parameter must still report its hit.
        let mut s = 977u32;
        let mut next = || {
            s = s.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (s >> 8) as f32 / 16_777_216.0 * 2.0 - 1.0
        };
        let mut hits = 0;
        for _ in 0..20_000 {
            let tri = Triangle::new(
                Vec3::new(next(), next(), next()) * 50.0,
                Vec3::new(next(), next(), next()) * 50.0,
                Vec3::new(next(), next(), next()) * 50.0,
            );
            let origin = Vec3::new(next(), next(), next()) * 300.0;
            let target = tri.point(0.5 + 0.5 * next(), 0.25 + 0.25 * next());
            let ray = Ray::new(origin, (target - origin).normalize_or(Vec3::X));
            if let Some((t, b1, b2)) = tri.intersect(&ray, f32::INFINITY) {
                hits += 1;
                assert_eq!(tri.intersect(&ray, t), Some((t, b1, b2)));
                assert_eq!(tri.intersect(&ray, t.next_down()), None);
            }
        }
        assert!(hits > 5_000, "only {hits} hits");
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
