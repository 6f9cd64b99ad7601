//! Eight triangles intersected at once with SIMD lanes (one AVX register per coordinate where
//! the CPU has AVX, two SSE registers otherwise). Every lane performs exactly the
//! floating-point operations of [`Triangle::intersect`] in the same order, so the answers are
//! bit-for-bit those of the scalar test; the division is left to the lanes that pass.

use super::triangle::{SIGN_BIT, ScaledHit, widen_t_max};
use super::{Ray, Triangle};
use wide::{CmpGe, CmpGt, CmpLe, f32x8};

/// Number of triangles in a [`Triangle8`].
pub const TRIANGLE_LANES: usize = 8;

/// Eight triangles in structure-of-arrays form; unused lanes hold a degenerate triangle that
/// nothing hits.
#[derive(Clone, Copy, Debug)]
pub struct Triangle8 {
    p0: [f32x8; 3],
    e1: [f32x8; 3],
    e2: [f32x8; 3],
    /// `e1 × e2`, unnormalised.
    n: [f32x8; 3],
}

/// Lane results of [`Triangle8::intersect`]: which lanes pass the division-free test, and
/// their products still to be divided by the determinant.
#[derive(Clone, Copy, Debug)]
pub struct Hits8 {
    /// Bit `i` set when lane `i` passes the test for `(0, t_max]` before the division (with a
    /// few ulps of slack on `t_max`, see [`Hits8::lane`]).
    pub mask: u32,
    det: f32x8,
    b1: f32x8,
    b2: f32x8,
    t: f32x8,
}

impl Hits8 {
    /// `(t, b1, b2)` of lane `lane` (a bit set in `mask`), `None` when the division puts `t`
    /// outside `(0, t_max]` (what [`Triangle::intersect`] returns for that triangle).
    #[inline(always)]
    pub fn lane(&self, lane: usize, t_max: f32) -> Option<(f32, f32, f32)> {
        ScaledHit {
            det: self.det.as_array_ref()[lane],
            b1: self.b1.as_array_ref()[lane],
            b2: self.b2.as_array_ref()[lane],
            t: self.t.as_array_ref()[lane],
        }
        .divide(t_max)
    }
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
            n: gather(&|t| t.normal_area2()),
        }
    }

    /// The division-free test of [`Triangle::intersect`] on all eight lanes.
    #[inline(always)]
    pub fn intersect(&self, ray: &Ray8, t_max: f32) -> Hits8 {
        let (d, o) = (&ray.dir, &ray.origin);
        let s = [self.p0[0] - o[0], self.p0[1] - o[1], self.p0[2] - o[2]];
        let det = dot(d, &self.n);
        let g = cross(&s, d);
        let b1 = dot(&self.e2, &g);
        let b2 = -dot(&self.e1, &g);
        let t = dot(&s, &self.n);
        let sign = det & f32x8::splat(f32::from_bits(SIGN_BIT));
        let abs_det = det.abs();
        let (b1s, b2s, ts) = (b1 ^ sign, b2 ^ sign, t ^ sign);
        let zero = f32x8::ZERO;
        let ok = b1s.cmp_ge(zero)
            & b2s.cmp_ge(zero)
            & (b1s + b2s).cmp_le(abs_det)
            & ts.cmp_gt(zero)
            & ts.cmp_le(f32x8::splat(widen_t_max(t_max)) * abs_det);
        Hits8 {
            mask: ok.move_mask() as u32,
            det,
            b1,
            b2,
            t,
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
                let lane = (hits.mask & (1 << i) != 0)
                    .then(|| hits.lane(i, t_max))
                    .flatten();
                let scalar = tri.intersect(&ray, t_max);
                hit_lanes += usize::from(scalar.is_some());
                assert_eq!(lane, scalar);
            }
            assert!(hits.mask & 0x80 == 0, "the padding lane never hits");
        }
        // Enough hits that the comparison means something.
        assert!(hit_lanes > 100, "only {hit_lanes} hits");
    }
}
