//! A fast, accurate angle from a sine-like and a cosine-like number, for the contour
//! integrals of form factors and solid angles, which take one angle per polygon edge and
//! spend most of their time in the C library's `atan2`.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};
use wide::{CmpEq, CmpGt, CmpLt, f64x4};

/// `tan(π/8)`: above it, the argument is reduced by `atan t = π/4 + atan((t − 1)/(t + 1))`.
const TAN_PI_8: f64 = 0.414_213_562_373_095_03;

/// `atan(u)/u` as a polynomial in `u²` on `|u| ≤ tan(π/8)`: a Chebyshev fit of degree 9 whose
/// relative error is about 1.3·10⁻¹⁵ there (checked by the tests below against `f64::atan2`).
const ATAN_OVER_U: [f64; 10] = [
    0.999_999_999_999_999_4,
    -0.333_333_333_332_333,
    0.199_999_999_796_742_88,
    -0.142_857_127_237_509_54,
    0.111_110_504_623_150_75,
    -0.090_895_541_534_918_79,
    0.076_737_529_968_237_97,
    -0.065_071_341_309_209_01,
    0.050_280_638_857_708_26,
    -0.025_356_038_184_693_834,
];

/// The angle in `[0, π]` (radians) whose sine and cosine are proportional to `y ≥ 0` and `x`
/// — `y.atan2(x)` for the upper half-plane — to a relative error below 10⁻¹⁴, also for tiny
/// angles and angles near π. Zero when both are zero; `y` must not be negative.
pub fn upper_angle(y: f64, x: f64) -> f64 {
    debug_assert!(y >= 0.0, "upper_angle needs y ≥ 0, got {y}");
    upper_angles(f64x4::splat(y), f64x4::splat(x)).as_array_ref()[0]
}

/// [`upper_angle`] of four pairs at once, lane by lane (one AVX register where the CPU has
/// AVX): the polygon contour integrals take their edges' angles four at a time.
pub fn upper_angles(y: f64x4, x: f64x4) -> f64x4 {
    let ax = x.abs();
    let small = y.fast_min(ax);
    let large = y.fast_max(ax);
    let t = small / large;
    let reduce = t.cmp_gt(f64x4::splat(TAN_PI_8));
    let u = reduce.blend((t - 1.0) / (t + 1.0), t);
    let base = reduce.blend(f64x4::splat(FRAC_PI_4), f64x4::ZERO);
    let u2 = u * u;
    let poly = ATAN_OVER_U
        .iter()
        .rev()
        .fold(f64x4::ZERO, |acc, &c| acc.mul_add(u2, f64x4::splat(c)));
    let angle = u.mul_add(poly, base);
    let angle = y.cmp_gt(ax).blend(FRAC_PI_2 - angle, angle);
    let angle = x.cmp_lt(f64x4::ZERO).blend(PI - angle, angle);
    // Both zero: t is NaN there.
    large.cmp_eq(f64x4::ZERO).blend(f64x4::ZERO, angle)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_atan2_to_relative_1e_14_over_the_upper_half_plane() {
        let mut worst: f64 = 0.0;
        for i in 0..=20_000 {
            let phi = PI * i as f64 / 20_000.0;
            for scale in [1e-9, 1.0, 3e7] {
                let (y, x) = (scale * phi.sin().max(0.0), scale * phi.cos());
                let exact = y.atan2(x);
                let fast = upper_angle(y, x);
                if exact > 0.0 {
                    worst = worst.max((fast / exact - 1.0).abs());
                } else {
                    assert_eq!(fast, 0.0);
                }
            }
        }
        assert!(worst < 1e-14, "worst relative error {worst:e}");
    }

    #[test]
    fn keeps_precision_for_tiny_and_near_pi_angles() {
        for tiny in [1e-300, 1e-20, 1e-8] {
            assert!((upper_angle(tiny, 1.0) / tiny - 1.0).abs() < 1e-14);
            // π − tiny as f64 holds only about 16 digits of π, so compare with atan2 there.
            assert!((upper_angle(tiny, -1.0) - tiny.atan2(-1.0)).abs() < 1e-15);
        }
        assert_eq!(upper_angle(0.0, 0.0), 0.0);
        assert_eq!(upper_angle(0.0, -2.0), PI);
        assert!((upper_angle(5.0, 0.0) - FRAC_PI_2).abs() < 1e-15);
    }

    #[test]
    fn lanes_are_independent() {
        let (y, x) = ([0.0, 1e-9, 3.0, 2.0], [0.0, -1.0, 0.5, -7.0]);
        let lanes = upper_angles(f64x4::from(y), f64x4::from(x)).to_array();
        for k in 0..4 {
            assert_eq!(lanes[k], upper_angle(y[k], x[k]), "lane {k}");
        }
    }
}
