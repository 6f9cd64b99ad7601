//! Four triangles intersected at once with SIMD lanes. Every lane performs exactly the
//! floating-point operations of [`Triangle::intersect`] in the same order, so the answers are
//! bit-for-bit those of the scalar test.

use super::{Ray, Triangle};
use glam::{BVec4A, Vec4};

/// Four triangles in structure-of-arrays form; unused lanes hold a degenerate triangle that
/// nothing hits.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct Triangle4 {
    p0: [Vec4; 3],
    e1: [Vec4; 3],
    e2: [Vec4; 3],
}

/// Lane results of [`Triangle4::intersect`].
#[derive(Clone, Copy, Debug)]
pub struct Hits4 {
    /// Bit `i` set when lane `i` is hit within `(0, t_max]`.
    pub mask: u32,
    /// Ray parameters.
    pub t: Vec4,
    /// Barycentrics of the second vertex.
    pub b1: Vec4,
    /// Barycentrics of the third vertex.
    pub b2: Vec4,
}

impl Triangle4 {
    /// Packs up to four triangles (lanes beyond `tris.len()` never hit).
    pub fn new(tris: &[Triangle]) -> Self {
        let lane = |i: usize| {
            tris.get(i).copied().unwrap_or(Triangle::new(
                glam::Vec3::ZERO,
                glam::Vec3::ZERO,
                glam::Vec3::ZERO,
            ))
        };
        let l = [lane(0), lane(1), lane(2), lane(3)];
        let gather = |f: &dyn Fn(&Triangle) -> glam::Vec3| -> [Vec4; 3] {
            let v = l.map(|t| f(&t));
            [
                Vec4::new(v[0].x, v[1].x, v[2].x, v[3].x),
                Vec4::new(v[0].y, v[1].y, v[2].y, v[3].y),
                Vec4::new(v[0].z, v[1].z, v[2].z, v[3].z),
            ]
        };
        Triangle4 {
            p0: gather(&|t| t.p0),
            e1: gather(&|t| t.e1),
            e2: gather(&|t| t.e2),
        }
    }

    /// Möller–Trumbore on all four lanes.
    #[inline(always)]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Hits4 {
        let d = [
            Vec4::splat(ray.dir.x),
            Vec4::splat(ray.dir.y),
            Vec4::splat(ray.dir.z),
        ];
        let o = [
            Vec4::splat(ray.origin.x),
            Vec4::splat(ray.origin.y),
            Vec4::splat(ray.origin.z),
        ];
        let (e1, e2) = (&self.e1, &self.e2);
        let pvec = cross(&d, e2);
        let det = dot(e1, &pvec);
        let inv_det = Vec4::ONE / det;
        let tvec = [o[0] - self.p0[0], o[1] - self.p0[1], o[2] - self.p0[2]];
        let b1 = dot(&tvec, &pvec) * inv_det;
        let qvec = cross(&tvec, e1);
        let b2 = dot(&d, &qvec) * inv_det;
        let t = dot(e2, &qvec) * inv_det;
        let finite = det.abs().cmplt(Vec4::INFINITY);
        let ok: BVec4A = det.cmpne(Vec4::ZERO)
            & finite
            & b1.cmpge(Vec4::ZERO)
            & b1.cmple(Vec4::ONE)
            & !b2.cmplt(Vec4::ZERO)
            & !(b1 + b2).cmpgt(Vec4::ONE)
            & t.cmpgt(Vec4::ZERO)
            & t.cmple(Vec4::splat(t_max));
        Hits4 {
            mask: ok.bitmask(),
            t,
            b1,
            b2,
        }
    }
}

#[inline(always)]
fn cross(a: &[Vec4; 3], b: &[Vec4; 3]) -> [Vec4; 3] {
    [
        a[1] * b[2] - b[1] * a[2],
        a[2] * b[0] - b[2] * a[0],
        a[0] * b[1] - b[0] * a[1],
    ]
}

#[inline(always)]
fn dot(a: &[Vec4; 3], b: &[Vec4; 3]) -> Vec4 {
    (a[0] * b[0]) + (a[1] * b[1]) + (a[2] * b[2])
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn lanes_agree_bit_for_bit_with_the_scalar_test() {
        let mut s = 12345u32;
        let mut next = || {
            s = s.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (s >> 8) as f32 / 16_777_216.0 * 4.0 - 2.0
        };
        let mut hit_lanes = 0;
        for _ in 0..2000 {
            let tris: Vec<Triangle> = (0..3)
                .map(|_| {
                    let p = Vec3::new(next(), next(), next());
                    Triangle::new(
                        p,
                        p + Vec3::new(next(), next(), next()) * 0.5,
                        p + Vec3::new(next(), next(), next()) * 0.5,
                    )
                })
                .collect();
            let packed = Triangle4::new(&tris);
            // Aim near a point of one of the triangles (inside or just outside its edges).
            let aim = &tris[(next().abs() * 1.49) as usize];
            let target = aim.point(0.4 + 0.5 * next(), 0.4 + 0.5 * next());
            let origin = Vec3::new(next(), next(), next()) * 3.0;
            let ray = Ray::new(origin, (target - origin).normalize_or(Vec3::X));
            let t_max = next().abs() * 8.0;
            let hits = packed.intersect(&ray, t_max);
            for (i, tri) in tris.iter().enumerate() {
                match tri.intersect(&ray, t_max) {
                    Some((t, b1, b2)) => {
                        hit_lanes += 1;
                        assert!(hits.mask & (1 << i) != 0);
                        assert_eq!((hits.t[i], hits.b1[i], hits.b2[i]), (t, b1, b2));
                    }
                    None => assert!(hits.mask & (1 << i) == 0),
                }
            }
            assert!(hits.mask & 8 == 0, "the padding lane never hits");
        }
        // Enough hits that the comparison means something.
        assert!(hit_lanes > 100, "only {hit_lanes} hits");
    }
}
