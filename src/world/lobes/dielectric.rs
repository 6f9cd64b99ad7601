//! The smooth dielectric (glass, water): reflects the Fresnel share in the mirror direction
//! and refracts the rest by Snell's law (a delta lobe: no density). The index of refraction
//! is that behind the front face; entering through the front goes from air (1) into it.

use crate::world::optics::{fresnel_dielectric, reflect, refract};
use glam::Vec3;

/// The relative index `η = n_incident / n_transmitted` for light arriving from the front
/// (`front_face`) or the back of a material of index `ior`.
#[inline]
pub fn relative_index(front_face: bool, ior: f32) -> f32 {
    if front_face { 1.0 / ior } else { ior }
}

/// The branches of a dielectric seen from `wo` (unit, toward the viewer) about the unit
/// normal `n` with relative index `eta`: the mirror direction with the Fresnel reflectance,
/// and the refracted direction (`None` under total internal reflection, where the mirror
/// takes everything) with the rest.
#[inline]
pub fn branches(n: Vec3, wo: Vec3, eta: f32) -> (Vec3, f32, Option<Vec3>) {
    (
        reflect(wo, n),
        fresnel_dielectric(wo.dot(n), eta),
        refract(wo, n, eta),
    )
}

/// One of the branches chosen by the uniform number `u` with the Fresnel probability: the
/// direction and whether it is the refracted one.
#[inline]
pub fn choose(n: Vec3, wo: Vec3, eta: f32, u: f32) -> (Vec3, bool) {
    match branches(n, wo, eta) {
        (_, fresnel, Some(t)) if u >= fresnel => (t, true),
        (mirror, _, _) => (mirror, false),
    }
}
