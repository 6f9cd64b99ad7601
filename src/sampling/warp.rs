//! Warps from uniform points in `[0, 1)²` to the distributions the integrators sample.

use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

/// Barycentrics `(b1, b2)` of a point uniformly distributed over a triangle.
pub fn uniform_triangle(u: Vec2) -> (f32, f32) {
    let s = u.x.sqrt();
    (s * (1.0 - u.y), s * u.y)
}

/// A cosine-weighted direction about local `+z`; its density is `cos θ / π`.
pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = concentric_disk(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    Vec3::new(d.x, d.y, z)
}

/// Density of [`cosine_hemisphere`] for a direction with `cos θ`.
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    cos_theta.max(0.0) * FRAC_1_PI
}

/// A uniform direction on the unit sphere; its density is `1 / (4π)`.
pub fn uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A uniform point on the unit disc (Shirley–Chiu concentric map).
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    // The angle is π/4·(minor/major) from the major axis (x where |x| > |y|, else y): a sine
    // and cosine of an angle within ±π/4. The axes are picked by selects, not branches (the
    // choice is a coin toss no predictor can learn).
    let x_major = o.x.abs() > o.y.abs();
    let (major, minor) = if x_major { (o.x, o.y) } else { (o.y, o.x) };
    if major == 0.0 {
        return Vec2::ZERO;
    }
    let (sin, cos) = sin_cos_within_quarter((PI / 4.0) * (minor / major));
    let (along, across) = (major * cos, major * sin);
    if x_major {
        Vec2::new(along, across)
    } else {
        Vec2::new(across, along)
    }
}

/// Sine and cosine of `x` in `[−π/4, π/4]` by their Taylor polynomials (error below 4e-7,
/// about as large as single-precision rounding; several times cheaper than the library's
/// range-reducing `sin_cos`).
fn sin_cos_within_quarter(x: f32) -> (f32, f32) {
    const S: [f32; 4] = [-1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362_880.0];
    const C: [f32; 4] = [-1.0 / 2.0, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40_320.0];
    let x2 = x * x;
    let sin = x * (1.0 + x2 * (S[0] + x2 * (S[1] + x2 * (S[2] + x2 * S[3]))));
    let cos = 1.0 + x2 * (C[0] + x2 * (C[1] + x2 * (C[2] + x2 * C[3])));
    (sin, cos)
}

/// Cell `index` of an `n × n` stratification of `[0, 1)²`, jittered by `u`.
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
    fn quarter_sine_and_cosine_match_the_library() {
        for i in 0..=1000 {
            let x = (i as f32 / 500.0 - 1.0) * (PI / 4.0);
            let (sin, cos) = sin_cos_within_quarter(x);
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
