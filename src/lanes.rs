//! Sampling math on eight lanes at once (one AVX register per quantity where the CPU has
//! AVX): vectors, the concentric disc, cosine-weighted directions, the normal's frame and
//! ray origins off surfaces, for eight paths side by side. Every function performs the
//! floating-point operations of its one-lane counterpart in [`super::sampling`],
//! [`crate::geometry::Frame`] or [`crate::geometry`]'s ray spawning in the same order, so each
//! lane's answer is bit for bit the scalar one (tested).

use crate::geometry::{OFFSET_ABSOLUTE, OFFSET_RELATIVE};
use std::f32::consts::PI;
use wide::{CmpEq, CmpGe, CmpGt, f32x8};

/// Number of lanes.
pub const LANES: usize = 8;

/// Eight 3-vectors (directions, points or RGB colours), one per lane.
#[derive(Clone, Copy, Debug)]
pub struct Vec3x8 {
    /// First components.
    pub x: f32x8,
    /// Second components.
    pub y: f32x8,
    /// Third components.
    pub z: f32x8,
}

impl Vec3x8 {
    /// Per-lane dot product, `(x·x') + (y·y') + (z·z')` like [`Vec3::dot`].
    #[inline(always)]
    pub fn dot(&self, o: &Vec3x8) -> f32x8 {
        (self.x * o.x) + (self.y * o.y) + (self.z * o.z)
    }

    /// Per-lane difference.
    #[inline(always)]
    pub fn sub(&self, o: &Vec3x8) -> Vec3x8 {
        Vec3x8 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }

    /// Per-lane component-wise product.
    #[inline(always)]
    pub fn mul(&self, o: &Vec3x8) -> Vec3x8 {
        Vec3x8 {
            x: self.x * o.x,
            y: self.y * o.y,
            z: self.z * o.z,
        }
    }

    /// Every lane scaled by its factor in `s`.
    #[inline(always)]
    pub fn scale(&self, s: f32x8) -> Vec3x8 {
        Vec3x8 {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }

    /// Per-lane negation.
    #[inline(always)]
    pub fn neg(&self) -> Vec3x8 {
        Vec3x8 {
            x: -self.x,
            y: -self.y,
            z: -self.z,
        }
    }

    /// Per lane `a` where `mask` is set, `b` elsewhere.
    #[inline(always)]
    pub fn select(mask: f32x8, a: &Vec3x8, b: &Vec3x8) -> Vec3x8 {
        Vec3x8 {
            x: mask.blend(a.x, b.x),
            y: mask.blend(a.y, b.y),
            z: mask.blend(a.z, b.z),
        }
    }
}

/// Eight-lane [`super::sampling::concentric_disk`].
#[inline(always)]
pub fn concentric_disk(ux: f32x8, uy: f32x8) -> (f32x8, f32x8) {
    let (two, one) = (f32x8::splat(2.0), f32x8::ONE);
    let (ox, oy) = (two * ux - one, two * uy - one);
    let x_major = ox.abs().cmp_gt(oy.abs());
    let major = x_major.blend(ox, oy);
    let minor = x_major.blend(oy, ox);
    let (sin, cos) = sin_cos_within_quarter(f32x8::splat(PI / 4.0) * (minor / major));
    let (along, across) = (major * cos, major * sin);
    let centre = major.cmp_eq(f32x8::ZERO);
    (
        centre.blend(f32x8::ZERO, x_major.blend(along, across)),
        centre.blend(f32x8::ZERO, x_major.blend(across, along)),
    )
}

/// Eight-lane `sin_cos_within_quarter` of [`super::sampling`] (same polynomials).
#[inline(always)]
fn sin_cos_within_quarter(x: f32x8) -> (f32x8, f32x8) {
    const S: [f32; 4] = [-1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362_880.0];
    const C: [f32; 4] = [-1.0 / 2.0, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40_320.0];
    let [s0, s1, s2, s3] = S.map(f32x8::splat);
    let [c0, c1, c2, c3] = C.map(f32x8::splat);
    let one = f32x8::ONE;
    let x2 = x * x;
    let sin = x * (one + x2 * (s0 + x2 * (s1 + x2 * (s2 + x2 * s3))));
    let cos = one + x2 * (c0 + x2 * (c1 + x2 * (c2 + x2 * c3)));
    (sin, cos)
}

/// Eight-lane [`super::sampling::cosine_hemisphere`]: local directions about `+z`.
#[inline(always)]
pub fn cosine_hemisphere(ux: f32x8, uy: f32x8) -> Vec3x8 {
    let (x, y) = concentric_disk(ux, uy);
    let z = (f32x8::ONE - ((x * x) + (y * y)))
        .fast_max(f32x8::ZERO)
        .sqrt();
    Vec3x8 { x, y, z }
}

/// Eight-lane `Frame::from_normal(n).to_world(v)`: the local direction `v` of each lane
/// turned into world space about that lane's unit normal `n`.
#[inline(always)]
pub fn to_world_about(n: &Vec3x8, v: &Vec3x8) -> Vec3x8 {
    let one = f32x8::ONE;
    let sign_bit = f32x8::splat(-0.0);
    let sign = (n.z & sign_bit) | one;
    let a = -(one / (sign + n.z));
    let b = n.x * n.y * a;
    let s = Vec3x8 {
        x: one + sign * n.x * n.x * a,
        y: sign * b,
        z: -(sign * n.x),
    };
    let t = Vec3x8 {
        x: b,
        y: sign + n.y * n.y * a,
        z: -n.y,
    };
    Vec3x8 {
        x: s.x * v.x + t.x * v.y + n.x * v.z,
        y: s.y * v.x + t.y * v.y + n.y * v.z,
        z: s.z * v.x + t.z * v.y + n.z * v.z,
    }
}

/// Eight-lane [`crate::geometry::surface_offset`].
#[inline(always)]
fn surface_offset(p: &Vec3x8) -> f32x8 {
    let largest = p.x.abs().fast_max(p.y.abs().fast_max(p.z.abs()));
    largest * f32x8::splat(OFFSET_RELATIVE) + f32x8::splat(OFFSET_ABSOLUTE)
}

/// Eight-lane [`crate::geometry::offset_origin`]: per lane the surface point `p` moved off
/// its surface (geometric normal `n`) to the side `dir` points into.
#[inline(always)]
pub fn offset_origin(p: &Vec3x8, n: &Vec3x8, dir: &Vec3x8) -> Vec3x8 {
    let d = surface_offset(p);
    let offset = n.scale(d);
    let ahead = n.dot(dir).cmp_ge(f32x8::ZERO);
    Vec3x8::select(
        ahead,
        &Vec3x8 {
            x: p.x + offset.x,
            y: p.y + offset.y,
            z: p.z + offset.z,
        },
        &p.sub(&offset),
    )
}

/// Eight-lane [`crate::geometry::spawn_ray_to`]: per lane the origin, unit direction and
/// parameter limit of a ray from surface point `p` (geometric normal `n`) that stops just
/// short of `target`.
#[inline(always)]
pub fn spawn_ray_to(p: &Vec3x8, n: &Vec3x8, target: &Vec3x8) -> (Vec3x8, Vec3x8, f32x8) {
    let origin = offset_origin(p, n, &target.sub(p));
    let d = target.sub(&origin);
    let dist = d.dot(&d).sqrt();
    let dir = Vec3x8::select(dist.cmp_gt(f32x8::ZERO), &d.scale(f32x8::ONE / dist), n);
    let t_max = (dist - surface_offset(target)).fast_max(f32x8::ZERO);
    (origin, dir, t_max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Frame;
    use crate::sampling::warp as sampling;
    use glam::{Vec2, Vec3};

    impl Vec3x8 {
        /// The vectors `v[0..8]` as lanes.
        fn from_lanes(v: &[Vec3; LANES]) -> Self {
            Vec3x8 {
                x: f32x8::new(v.map(|p| p.x)),
                y: f32x8::new(v.map(|p| p.y)),
                z: f32x8::new(v.map(|p| p.z)),
            }
        }

        /// The vector of lane `i`.
        fn lane(&self, i: usize) -> Vec3 {
            Vec3::new(
                self.x.as_array_ref()[i],
                self.y.as_array_ref()[i],
                self.z.as_array_ref()[i],
            )
        }
    }

    /// Deterministic uniform numbers in `[0, 1)`, including exact 0.5 (the disc's centre).
    fn uniforms(n: usize) -> Vec<f32> {
        let mut s = 2024u32;
        (0..n)
            .map(|i| {
                s = s.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                if i % 97 == 0 {
                    0.5
                } else {
                    (s >> 8) as f32 / 16_777_216.0
                }
            })
            .collect()
    }

    #[test]
    fn cosine_directions_match_the_scalar_ones_bit_for_bit() {
        let u = uniforms(2 * LANES * 500);
        for chunk in u.chunks(2 * LANES) {
            let ux: [f32; LANES] = std::array::from_fn(|i| chunk[2 * i]);
            let uy: [f32; LANES] = std::array::from_fn(|i| chunk[2 * i + 1]);
            let lanes = cosine_hemisphere(f32x8::new(ux), f32x8::new(uy));
            for i in 0..LANES {
                let scalar = sampling::cosine_hemisphere(Vec2::new(ux[i], uy[i]));
                assert_eq!(
                    lanes.lane(i),
                    scalar,
                    "lane {i}: u = ({}, {})",
                    ux[i],
                    uy[i]
                );
            }
        }
    }

    #[test]
    fn spawned_rays_match_the_scalar_ones_bit_for_bit() {
        let u = uniforms(9 * LANES * 300);
        for chunk in u.chunks(9 * LANES) {
            let vec = |i: usize, k: usize, scale: f32| {
                (Vec3::new(chunk[9 * i + k], chunk[9 * i + k + 1], chunk[9 * i + k + 2]) * 2.0
                    - Vec3::ONE)
                    * scale
            };
            let p: [Vec3; LANES] = std::array::from_fn(|i| vec(i, 0, 40.0));
            let n: [Vec3; LANES] = std::array::from_fn(|i| vec(i, 3, 1.0).normalize_or(Vec3::Y));
            // One lane aims at its own point (zero distance).
            let target: [Vec3; LANES] =
                std::array::from_fn(|i| if i == 3 { p[i] } else { vec(i, 6, 40.0) });
            let lanes = |v: &[Vec3; LANES]| Vec3x8::from_lanes(v);
            let (origin, dir, t_max) = spawn_ray_to(&lanes(&p), &lanes(&n), &lanes(&target));
            let away = offset_origin(&lanes(&p), &lanes(&n), &lanes(&target));
            for i in 0..LANES {
                let (ray, limit) = crate::geometry::spawn_ray_to(p[i], n[i], target[i]);
                assert_eq!(
                    (origin.lane(i), dir.lane(i), t_max.as_array_ref()[i]),
                    (ray.origin, ray.dir, limit),
                    "lane {i}"
                );
                assert_eq!(
                    away.lane(i),
                    crate::geometry::offset_origin(p[i], n[i], target[i])
                );
            }
        }
    }

    #[test]
    fn world_directions_match_the_frame_bit_for_bit() {
        let u = uniforms(6 * LANES * 500);
        for chunk in u.chunks(6 * LANES) {
            let normals: [Vec3; LANES] = std::array::from_fn(|i| {
                let v =
                    Vec3::new(chunk[6 * i], chunk[6 * i + 1], chunk[6 * i + 2]) * 2.0 - Vec3::ONE;
                // Include normals along ±z, where the frame switches its sign.
                match i {
                    0 => Vec3::Z,
                    1 => -Vec3::Z,
                    _ => v.normalize_or(Vec3::X),
                }
            });
            let local: [Vec3; LANES] = std::array::from_fn(|i| {
                Vec3::new(chunk[6 * i + 3], chunk[6 * i + 4], chunk[6 * i + 5])
            });
            let lanes = to_world_about(&Vec3x8::from_lanes(&normals), &Vec3x8::from_lanes(&local));
            for i in 0..LANES {
                let scalar = Frame::from_normal(normals[i]).to_world(local[i]);
                assert_eq!(lanes.lane(i), scalar, "lane {i}: n = {:?}", normals[i]);
            }
        }
    }
}
