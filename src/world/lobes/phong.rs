//! The normalised Phong lobe `(s+2)/(2π)·cosˢα` about the mirror direction (α its angle to
//! `wi`), sampled by `(s+1)/(2π)·cosˢα`: it reflects at most its weight for any incidence.

use crate::geometry::Frame;
use crate::world::optics::reflect;
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

/// The lobe's value (1/sr) for unit directions `wo` (toward the viewer) and `wi` about the
/// unit normal `n`, exponent `shininess`.
#[inline]
pub fn lobe(n: Vec3, wo: Vec3, wi: Vec3, shininess: f32) -> f32 {
    let cos_alpha = reflect(wo, n).dot(wi);
    if cos_alpha <= 0.0 {
        0.0
    } else {
        (shininess + 2.0) / (2.0 * PI) * cos_alpha.powf(shininess)
    }
}

/// A direction about the mirror direction of `wo` (unit, pointing away from the surface with
/// unit normal `n`) from the uniform point `u`, distributed as [`pdf`]; it may point below
/// the surface.
#[inline]
pub fn sample(n: Vec3, wo: Vec3, shininess: f32, u: Vec2) -> Vec3 {
    let cos_alpha = u.x.powf(1.0 / (shininess + 1.0));
    let sin_alpha = (1.0 - cos_alpha * cos_alpha).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    let local = Vec3::new(sin_alpha * phi.cos(), sin_alpha * phi.sin(), cos_alpha);
    Frame::from_normal(reflect(wo, n)).to_world(local)
}

/// Density (1/sr) of [`sample`] for `cos α` to the mirror direction.
#[inline]
pub fn pdf(cos_alpha: f32, shininess: f32) -> f32 {
    if cos_alpha <= 0.0 {
        0.0
    } else {
        (shininess + 1.0) * (0.5 * FRAC_1_PI) * cos_alpha.powf(shininess)
    }
}

/// A photon's direction from [`sample`] and its weight factor `(s+2)/(s+1)·cos θ` (the lobe
/// over its sampling density, times the cosine); `None` below the surface.
#[inline]
pub fn sample_photon(n: Vec3, wo: Vec3, shininess: f32, u: Vec2) -> Option<(Vec3, f32)> {
    let wi = sample(n, wo, shininess, u);
    let cos = wi.dot(n);
    (cos > 0.0).then(|| (wi, (shininess + 2.0) / (shininess + 1.0) * cos))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::warp::hemisphere_integral;

    #[test]
    fn the_lobe_reflects_at_most_its_weight() {
        // ∫ lobe·cos dω ≤ 1 at normal incidence (numerical quadrature over the hemisphere).
        let n = Vec3::Z;
        for s in [1.0, 10.0, 100.0] {
            let sum = hemisphere_integral(400, |wi| lobe(n, n, wi, s) as f64);
            assert!(sum <= 1.0 + 1e-3 && sum > 0.5, "s={s}: {sum}");
        }
    }
}
