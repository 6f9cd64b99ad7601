//! The Lambertian lobe: `f = ρ/π` in every direction of the hemisphere, sampled by the
//! cosine, so that `f·cos θ / pdf = ρ` exactly.

use crate::color::Rgb;
use crate::geometry::Frame;
use crate::lanes::V3;
use crate::sampling::warp::{cosine_about, cosine_hemisphere, cosine_hemisphere_pdf};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// `f(wo, wi)` (1/sr) for reflectance `rho`.
#[inline]
pub fn eval(rho: Rgb) -> Rgb {
    rho * FRAC_1_PI
}

/// Density (1/sr) of [`sample`] at `cos θ` to the normal.
#[inline]
pub fn pdf(cos: f32) -> f32 {
    cosine_hemisphere_pdf(cos)
}

/// A cosine-distributed direction about the unit normal `n` from the uniform point `u`.
#[inline]
pub fn sample(n: Vec3, u: Vec2) -> Vec3 {
    cosine_about(V3::from(n), u.x, u.y).into()
}

/// A photon's cosine-distributed direction about the unit geometric normal `ng` (the light
/// model keeps every diffusely scattered photon on the surface's own side).
#[inline]
pub fn sample_photon(ng: Vec3, u: Vec2) -> Vec3 {
    Frame::from_normal(ng).to_world(cosine_hemisphere(u))
}
