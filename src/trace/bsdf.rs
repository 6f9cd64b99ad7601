//! Materials evaluated at a surface point: textures applied, emission, and the reflection
//! functions (Lambert plus a normalised Phong lobe) with their mirror and refraction parts.

use super::SurfaceHit;
use crate::color::Rgb;
use crate::scene::{Material, Scene};
use glam::Vec3;
use std::f32::consts::{FRAC_1_PI, PI};

/// A material at one surface point, with textures applied.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceMaterial {
    /// Diffuse reflectance ρ.
    pub diffuse: Rgb,
    /// Phong lobe weight.
    pub specular: Rgb,
    /// Phong exponent.
    pub shininess: f32,
    /// Ideal mirror reflectance.
    pub mirror: Rgb,
    /// Ideal refraction weight.
    pub transmission: Rgb,
    /// Index of refraction behind the front face.
    pub ior: f32,
    /// The back face absorbs everything.
    pub one_sided: bool,
}

impl SurfaceMaterial {
    /// The material of `hit`, textures applied.
    pub fn at(scene: &Scene, hit: &SurfaceHit) -> Self {
        let m = &scene.materials[hit.material as usize];
        let diffuse = match m.diffuse_texture {
            Some(t) => m.diffuse * scene.textures[t as usize].color(hit.uv),
            None => m.diffuse,
        };
        SurfaceMaterial {
            diffuse,
            specular: m.specular,
            shininess: m.shininess,
            mirror: m.mirror,
            transmission: m.transmission,
            ior: m.ior,
            one_sided: m.one_sided,
        }
    }

    /// True when the hit side reflects nothing (back of a one-sided material).
    pub fn is_black_from(&self, front_face: bool) -> bool {
        self.one_sided && !front_face
    }

    /// The non-delta reflection function `f(wo, wi)` (1/sr) for unit directions `wo` (toward
    /// the viewer) and `wi` (toward the light) on the side of the unit normal `n`.
    pub fn eval(&self, n: Vec3, wo: Vec3, wi: Vec3) -> Rgb {
        if n.dot(wi) <= 0.0 || n.dot(wo) <= 0.0 {
            return Rgb::BLACK;
        }
        let mut f = self.diffuse * FRAC_1_PI;
        if !self.specular.is_black() {
            f += self.specular * phong_lobe(n, wo, wi, self.shininess);
        }
        f
    }
}

/// Normalised Phong lobe `(s+2)/(2π)·cosˢα`, α the angle between `wi` and the mirror
/// direction of `wo`. Reflects at most the lobe weight for any incidence.
pub fn phong_lobe(n: Vec3, wo: Vec3, wi: Vec3, shininess: f32) -> f32 {
    let cos_alpha = reflect(wo, n).dot(wi);
    if cos_alpha <= 0.0 {
        0.0
    } else {
        (shininess + 2.0) / (2.0 * PI) * cos_alpha.powf(shininess)
    }
}

/// Radiance emitted by `hit` back along the ray that found it (front face only unless the
/// material is two-sided), emission texture applied.
pub fn emitted(scene: &Scene, hit: &SurfaceHit) -> Rgb {
    emitted_toward(
        scene,
        &scene.materials[hit.material as usize],
        hit.uv,
        hit.front_face,
    )
}

/// Radiance emitted by material `m` at texture coordinate `uv` toward the front
/// (`front = true`) or back side.
pub fn emitted_toward(scene: &Scene, m: &Material, uv: glam::Vec2, front: bool) -> Rgb {
    if m.emission.is_black() || !(front || m.two_sided) {
        return Rgb::BLACK;
    }
    match m.emission_texture {
        Some(t) => m.emission * scene.textures[t as usize].color(uv),
        None => m.emission,
    }
}

/// Mirror direction of `w` (pointing away from the surface) about the unit normal `n`.
pub fn reflect(w: Vec3, n: Vec3) -> Vec3 {
    2.0 * w.dot(n) * n - w
}

/// Refracted direction of `w` (pointing away from the surface, on the side of `n`) for the
/// relative index `eta = n_incident / n_transmitted`; `None` under total internal reflection.
pub fn refract(w: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = w.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((-w * eta + n * (eta * cos_i - cos_t)).normalize())
}

/// Unpolarised Fresnel reflectance of a dielectric interface for incidence cosine `cos_i`
/// and relative index `eta = n_incident / n_transmitted` (1 under total internal reflection).
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    0.5 * (r_s * r_s + r_p * r_p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trace::sampling::hemisphere_integral;

    #[test]
    fn fresnel_reference_values() {
        // Normal incidence on glass (n = 1.5): ((1 - 1.5)/(1 + 1.5))² = 0.04.
        assert!((fresnel_dielectric(1.0, 1.0 / 1.5) - 0.04).abs() < 1e-6);
        // Grazing incidence reflects everything; beyond the critical angle inside glass too.
        assert!((fresnel_dielectric(0.0, 1.0 / 1.5) - 1.0).abs() < 1e-6);
        assert_eq!(fresnel_dielectric(0.3, 1.5), 1.0);
    }

    #[test]
    fn refraction_obeys_snell() {
        let n = Vec3::Z;
        let w = Vec3::new(0.6, 0.0, 0.8);
        let t = refract(w, n, 1.0 / 1.5).unwrap();
        let sin_i = 0.6;
        let sin_t = (1.0 - t.z * t.z).sqrt();
        assert!((sin_i - 1.5 * sin_t).abs() < 1e-5 && t.z < 0.0 && t.x < 0.0);
        assert!(refract(Vec3::new(0.9, 0.0, 0.436), n, 1.5).is_none());
    }

    #[test]
    fn phong_lobe_reflects_at_most_its_weight() {
        // ∫ lobe·cos dω ≤ 1 at normal incidence (numerical quadrature over the hemisphere).
        let n = Vec3::Z;
        for s in [1.0, 10.0, 100.0] {
            let sum = hemisphere_integral(400, |wi| phong_lobe(n, n, wi, s) as f64);
            assert!(sum <= 1.0 + 1e-3 && sum > 0.5, "s={s}: {sum}");
        }
    }
}
