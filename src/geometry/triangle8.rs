//! Eight triangles intersected at once with SIMD lanes (one AVX register per coordinate where
//! the CPU has AVX, two SSE registers otherwise). Every lane performs exactly the
//! floating-point operations of [`Triangle::intersect`] in the same order, so the answers are
//! bit-for-bit those of the scalar test.

use super::{Ray, Triangle};
use wide::{CmpGe, CmpGt, CmpLe, CmpLt, CmpNe, f32x8};

/// Number of triangles in a [`Triangle8`].
pub const TRIANGLE_LANES: usize = 8;

/// Eight triangles in structure-of-arrays form; unused lanes hold a degenerate triangle that
/// nothing hits.
#[derive(Clone, Copy, Debug)]
pub struct Triangle8 {
    p0: [f32x8; 3],
    e1: [f32x8; 3],
    e2: [f32x8; 3],
}

/// Lane results of [`Triangle8::intersect`].
#[derive(Clone, Copy, Debug)]
pub struct Hits8 {
    /// Bit `i` set when lane `i` is hit within `(0, t_max]`.
    pub mask: u32,
    /// Ray parameters.
    pub t: [f32; 8],
    /// Barycentrics of the second vertex.
    pub b1: [f32; 8],
    /// Barycentrics of the third vertex.
    pub b2: [f32; 8],
}

/// A ray's origin and direction, each coordinate in all eight lanes.
#[derive(Clone, Copy, Debug)]
pub struct Ray8 {
    origin: [f32x8; 3],
    dir: [f32x8; 3],
}

impl Ray8 {
    /// `ray` in every lane.
    #[inline(always)]
    pub fn new(ray: &Ray) -> Self {
        Ray8 {
            origin: ray.origin.to_array().map(f32x8::splat),
            dir: ray.dir.to_array().map(f32x8::splat),
        }
    }
}

impl Triangle8 {
    /// Packs up to eight triangles (lanes beyond `tris.len()` never hit).
    pub fn new(tris: &[Triangle]) -> Self {
        let degenerate = Triangle::new(glam::Vec3::ZERO, glam::Vec3::ZERO, glam::Vec3::ZERO);
        let lanes: [Triangle; 8] =
            std::array::from_fn(|i| tris.get(i).copied().unwrap_or(degenerate));
        let gather = |f: &dyn Fn(&Triangle) -> glam::Vec3| -> [f32x8; 3] {
            let v = lanes.map(|t| f(&t));
            [0, 1, 2].map(|axis| f32x8::new(v.map(|p| p[axis])))
        };
        Triangle8 {
            p0: gather(&|t| t.p0),
            e1: gather(&|t| t.e1),
            e2: gather(&|t| t.e2),
        }
    }

    /// Möller–Trumbore on all eight lanes.
    #[inline(always)]
    pub fn intersect(&self, ray: &Ray8, t_max: f32) -> Hits8 {
        let (d, o) = (&ray.dir, &ray.origin);
        let (e1, e2) = (&self.e1, &self.e2);
        let pvec = cross(d, e2);
        let det = dot(e1, &pvec);
        let inv_det = f32x8::ONE / det;
        let tvec = [o[0] - self.p0[0], o[1] - self.p0[1], o[2] - self.p0[2]];
        let b1 = dot(&tvec, &pvec) * inv_det;
        let qvec = cross(&tvec, e1);
        let b2 = dot(d, &qvec) * inv_det;
        let t = dot(e2, &qvec) * inv_det;
        let (zero, one) = (f32x8::ZERO, f32x8::ONE);
        let finite = det.abs().cmp_lt(f32x8::splat(f32::INFINITY));
        let ok = det.cmp_ne(zero)
            & finite
            & b1.cmp_ge(zero)
            & b1.cmp_le(one)
            & !b2.cmp_lt(zero)
            & !(b1 + b2).cmp_gt(one)
            & t.cmp_gt(zero)
            & t.cmp_le(f32x8::splat(t_max));
        Hits8 {
            mask: ok.move_mask() as u32,
            t: t.to_array(),
            b1: b1.to_array(),
            b2: b2.to_array(),
        }
    }
}

#[inline(always)]
fn cross(a: &[f32x8; 3], b: &[f32x8; 3]) -> [f32x8; 3] {
    [
        a[1] * b[2] - b[1] * a[2],
        a[2] * b[0] - b[2] * a[0],
        a[0] * b[1] - b[0] * a[1],
    ]
}

#[inline(always)]
fn dot(a: &[f32x8; 3], b: &[f32x8; 3]) -> f32x8 {
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
            let tris: Vec<Triangle> = (0..7)
                .map(|_| {
                    let p = Vec3::new(next(), next(), next());
                    Triangle::new(
                        p,
                        p + Vec3::new(next(), next(), next()) * 0.5,
                        p + Vec3::new(next(), next(), next()) * 0.5,
                    )
                })
                .collect();
            let packed = Triangle8::new(&tris);
            // Aim near a point of one of the triangles (inside or just outside its edges).
            let aim = &tris[(next().abs() * 3.49) as usize];
            let target = aim.point(0.4 + 0.5 * next(), 0.4 + 0.5 * next());
            let origin = Vec3::new(next(), next(), next()) * 3.0;
            let ray = Ray::new(origin, (target - origin).normalize_or(Vec3::X));
            let t_max = next().abs() * 8.0;
            let hits = packed.intersect(&Ray8::new(&ray), t_max);
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
            assert!(hits.mask & 0x80 == 0, "the padding lane never hits");
        }
        // Enough hits that the comparison means something.
        assert!(hit_lanes > 100, "only {hit_lanes} hits");
    }
}
