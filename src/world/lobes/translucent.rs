//! The translucent lobe (diffuse transmission): `f = τ/π` in every direction of the
//! hemisphere behind the surface, so light arriving on one side leaves the other as from a
//! Lambertian surface; sampled by the cosine about the reversed normal, so that
//! `f·|cos θ| / pdf = τ` exactly. It is the Lambertian lobe turned to the other side.

use super::lambert;
use glam::{Vec2, Vec3};

/// Density (1/sr) of [`sample`] for `cos θ` to the normal on the viewer's side (negative
/// behind the surface, where the lobe sends its light).
#[inline]
pub fn pdf(cos: f32) -> f32 {
    lambert::pdf(-cos)
}

/// A cosine-distributed direction behind the surface of unit normal `n` (the viewer's side)
/// from the uniform point `u`.
#[inline]
pub fn sample(n: Vec3, u: Vec2) -> Vec3 {
    lambert::sample(-n, u)
}

/// A photon's cosine-distributed direction through the surface of unit geometric normal `ng`
/// (on the side the photon arrived from).
#[inline]
pub fn sample_photon(ng: Vec3, u: Vec2) -> Vec3 {
    lambert::sample_photon(-ng, u)
}
