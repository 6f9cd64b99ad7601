//! Warps from uniform points in `[0, 1)²` to the distributions the algorithms sample. The
//! warps the path tracer runs on eight lanes are written once over [`Real`] (`*_lanes`); the
//! one-point functions call them with `f32`.

use crate::geometry::to_world_about;
use crate::lanes::{Real, V3};
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

/// Barycentrics `(b1, b2)` of a point uniformly distributed over a triangle.
#[inline]
pub fn uniform_triangle(u: Vec2) -> (f32, f32) {
    let s = u.x.sqrt();
    (s * (1.0 - u.y), s * u.y)
}

/// A cosine-weighted direction about local `+z`; its density is `cos θ / π`.
#[inline]
pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    cosine_hemisphere_lanes(u.x, u.y).into()
}

/// [`cosine_hemisphere`] lane by lane, from the uniform numbers `(ux, uy)`.
#[inline(always)]
pub fn cosine_hemisphere_lanes<R: Real>(ux: R, uy: R) -> V3<R> {
    let (x, y) = concentric_disk_lanes(ux, uy);
    let z = (R::splat(1.0) - ((x * x) + (y * y)))
        .max(R::splat(0.0))
        .sqrt();
    V3::new(x, y, z)
}

/// A cosine-weighted direction about the unit normal `n` (world space), lane by lane: the
/// Lambert lobe's sampling.
#[inline(always)]
pub fn cosine_about<R: Real>(n: V3<R>, ux: R, uy: R) -> V3<R> {
    to_world_about(n, cosine_hemisphere_lanes(ux, uy))
}

/// Density (1/sr) of [`cosine_hemisphere`] for a direction with `cos θ`.
#[inline]
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    cosine_hemisphere_pdf_lanes(cos_theta)
}

/// [`cosine_hemisphere_pdf`] lane by lane.
#[inline(always)]
pub fn cosine_hemisphere_pdf_lanes<R: Real>(cos_theta: R) -> R {
    cos_theta.max(R::splat(0.0)) * R::splat(FRAC_1_PI)
}

/// A uniform direction on the unit sphere; its density is `1 / (4π)`.
#[inline]
pub fn uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A uniform point on the unit disc (Shirley–Chiu concentric map).
#[inline]
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let (x, y) = concentric_disk_lanes(u.x, u.y);
    Vec2::new(x, y)
}

/// [`concentric_disk`] lane by lane.
#[inline(always)]
pub fn concentric_disk_lanes<R: Real>(ux: R, uy: R) -> (R, R) {
    let (one, two, zero) = (R::splat(1.0), R::splat(2.0), R::splat(0.0));
    let (ox, oy) = (two * ux - one, two * uy - one);
    // The angle is π/4·(minor/major) from the major axis (x where |x| > |y|, else y): a sine
    // and cosine of an angle within ±π/4. The axes are picked by selects, not branches (the
    // choice is a coin toss no predictor can learn); the centre (major = 0) maps to itself.
    let x_major = ox.abs().gt(oy.abs());
    let major = R::select(x_major, ox, oy);
    let minor = R::select(x_major, oy, ox);
    let (sin, cos) = sin_cos_within_quarter(R::splat(PI / 4.0) * (minor / major));
    let (along, across) = (major * cos, major * sin);
    let centre = major.eq(zero);
    (
        R::select(centre, zero, R::select(x_major, along, across)),
        R::select(centre, zero, R::select(x_major, across, along)),
    )
}

/// Sine and cosine of `x` in `[−π/4, π/4]` by their Taylor polynomials (error below 4e-7,
/// about as large as single-precision rounding; several times cheaper than the library's
/// range-reducing `sin_cos`).
#[inline(always)]
fn sin_cos_within_quarter<R: Real>(x: R) -> (R, R) {
    const S: [f32; 4] = [-1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362_880.0];
    const C: [f32; 4] = [-1.0 / 2.0, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40_320.0];
    let ([s0, s1, s2, s3], [c0, c1, c2, c3]) = (S.map(R::splat), C.map(R::splat));
    let one = R::splat(1.0);
    let x2 = x * x;
    let sin = x * (one + x2 * (s0 + x2 * (s1 + x2 * (s2 + x2 * s3))));
    let cos = one + x2 * (c0 + x2 * (c1 + x2 * (c2 + x2 * c3)));
    (sin, cos)
}

/// Cell `index` of an `n × n` stratification of `[0, 1)²`, jittered by `u`.
#[inline]
pub fn stratified(index: u32, n: u32, u: Vec2) -> Vec2 {
    let cell = Vec2::new((index % n) as f32, (index / n) as f32);
    (cell + u) / n as f32
}

/// `∫ f(ω)·cos θ dω` over the hemisphere about `+z`, by the midpoint rule on a `steps × steps`
/// grid in (θ, φ); for checking reflectance functions in tests.
#[cfg(test)]
pub(crate) fn hemisphere_integral(steps: u32, f: impl Fn(Vec3) -> f64) -> f64 {
    let (d_theta, d_phi) = (PI / 2.0 / steps as f32, 2.0 * PI / steps as f32);
    let mut sum = 0.0f64;
    for i in 0..steps {
        let theta = (i as f32 + 0.5) * d_theta;
        for j in 0..steps {
            let phi = (j as f32 + 0.5) * d_phi;
            let w = Vec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            );
            sum += f(w) * (w.z * theta.sin() * d_theta * d_phi) as f64;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn warps_stay_in_their_domain() {
        for i in 0..64 {
            let u = Vec2::new((i % 8) as f32 / 8.0 + 0.03, (i / 8) as f32 / 8.0 + 0.07);
            let (b1, b2) = uniform_triangle(u);
            assert!(b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0);
            let d = cosine_hemisphere(u);
            assert!(d.z >= 0.0 && (d.length() - 1.0).abs() < 1e-5);
            assert!((uniform_sphere(u).length() - 1.0).abs() < 1e-5);
            assert!(concentric_disk(u).length() <= 1.0 + 1e-6);
        }
    }

    #[test]
    fn eight_lanes_warp_as_one_lane_does_bit_for_bit() {
        use crate::lanes::{LANES, Vec3x8};
        use wide::f32x8;
        let mut seed = 2024u32;
        let u: Vec<f32> = (0..2 * LANES * 500)
            .map(|i| {
                seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                // Exact 0.5 now and then: the disc's centre.
                if i % 97 == 0 {
                    0.5
                } else {
                    (seed >> 8) as f32 / 16_777_216.0
                }
            })
            .collect();
        for chunk in u.chunks(2 * LANES) {
            let ux: [f32; LANES] = std::array::from_fn(|i| chunk[2 * i]);
            let uy: [f32; LANES] = std::array::from_fn(|i| chunk[2 * i + 1]);
            let lanes: Vec3x8 = cosine_hemisphere_lanes(f32x8::new(ux), f32x8::new(uy));
            for i in 0..LANES {
                let one = cosine_hemisphere(Vec2::new(ux[i], uy[i]));
                assert_eq!(lanes.lane(i), one, "lane {i}: u = ({}, {})", ux[i], uy[i]);
            }
        }
    }

    #[test]
    fn quarter_sine_and_cosine_match_the_library() {
        for i in 0..=1000 {
            let x = (i as f32 / 500.0 - 1.0) * (PI / 4.0);
            let (sin, cos) = sin_cos_within_quarter::<f32>(x);
            assert!(
                (sin - x.sin()).abs() < 4e-7,
                "sin {x}: {sin} vs {}",
                x.sin()
            );
            assert!(
                (cos - x.cos()).abs() < 4e-7,
                "cos {x}: {cos} vs {}",
                x.cos()
            );
        }
    }

    #[test]
    fn cosine_hemisphere_mean_cosine_is_two_thirds() {
        // E[cos θ] under the density cos θ/π is 2/3.
        let n = 64;
        let mean: f32 = (0..n * n)
            .map(|i| cosine_hemisphere(stratified(i, n, Vec2::splat(0.5))).z)
            .sum::<f32>()
            / (n * n) as f32;
        assert!((mean - 2.0 / 3.0).abs() < 2e-3, "{mean}");
    }
}
