//! Optics of smooth surfaces: mirror and refracted directions and the Fresnel reflectance
//! of a dielectric.

use glam::Vec3;

/// Mirror direction of `w` (pointing away from the surface) about the unit normal `n`.
#[inline]
pub fn reflect(w: Vec3, n: Vec3) -> Vec3 {
    2.0 * w.dot(n) * n - w
}

/// Refracted direction of `w` (pointing away from the surface, on the side of `n`) for the
/// relative index `eta = n_incident / n_transmitted`; `None` under total internal reflection.
#[inline]
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
#[inline]
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
}
