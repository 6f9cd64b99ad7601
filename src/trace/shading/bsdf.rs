//! Sampling the scattering of a [`SurfaceMaterial`] for path tracing.
//!
//! A material is a mixture of four lobes: Lambert (`diffuse`), normalised Phong (`specular`,
//! `shininess`), ideal mirror (`mirror`) and a smooth dielectric (`transmission`, `ior`, which
//! reflects or refracts by Fresnel). One lobe is chosen with probability proportional to the
//! luminance of its weight. Directions from the two non-delta lobes are weighted by the full
//! non-delta mixture (`f·cos / pdf` with `pdf` the sum over both lobes of choice probability
//! times lobe density), which is what [`LobeChoice::pdf`] returns, so the density used by
//! multiple importance sampling is the one the sampler actually draws from. The delta lobes
//! (mirror, dielectric) have no density and never take part in multiple importance sampling.

use crate::color::Rgb;
use crate::lanes::V3;
use crate::sampling::warp::{cosine_about, cosine_hemisphere_pdf};
use crate::scene::Material;
use crate::world::SurfaceMaterial;
use crate::world::optics::{fresnel_dielectric, phong_pdf, reflect, refract, sample_phong};
use glam::{Vec2, Vec3};

/// A scattered direction with its path weight.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    /// Unit direction the path continues in (away from the surface).
    pub wi: Vec3,
    /// Path-throughput factor `f·|cos θ| / pdf` (for delta lobes: the lobe weight divided by
    /// the probability of having chosen it).
    pub weight: Rgb,
    /// Density (1/sr) of `wi` under the non-delta mixture; 0 for delta lobes.
    pub pdf: f32,
    /// True when `wi` came from a delta lobe (mirror or dielectric).
    pub delta: bool,
}

/// The probabilities of choosing each lobe of a material, proportional to the luminance of
/// the lobe weights (they sum to 1 unless the material scatters nothing).
#[derive(Clone, Copy, Debug)]
pub struct LobeChoice {
    diffuse: f32,
    /// `1 / diffuse` (0 when there is no diffuse lobe).
    inverse_diffuse: f32,
    specular: f32,
    mirror: f32,
    transmission: f32,
}

impl LobeChoice {
    /// The lobe probabilities of `m`.
    pub fn new(m: &SurfaceMaterial) -> Self {
        Self::from_weights([m.diffuse, m.specular, m.mirror, m.transmission])
    }

    /// The lobe probabilities of a scene material without a diffuse texture (the same at
    /// every point of it).
    pub fn of_material(m: &Material) -> Self {
        Self::from_weights([m.diffuse, m.specular, m.mirror, m.transmission])
    }

    /// Probabilities from the lobe weights (diffuse, specular, mirror, transmission).
    fn from_weights(weights: [Rgb; 4]) -> Self {
        let [d, s, r, t] = weights.map(|w| w.luminance().max(0.0));
        let total = d + s + r + t;
        if total <= 0.0 {
            return LobeChoice {
                diffuse: 0.0,
                inverse_diffuse: 0.0,
                specular: 0.0,
                mirror: 0.0,
                transmission: 0.0,
            };
        }
        LobeChoice {
            diffuse: d / total,
            inverse_diffuse: if d > 0.0 { total / d } else { 0.0 },
            specular: s / total,
            mirror: r / total,
            transmission: t / total,
        }
    }

    /// True for a material with only a Lambert lobe, which it then chooses with probability
    /// exactly 1 (`d / d`), so [`sample_bsdf`]'s weight is the reflectance itself.
    pub fn is_lambert_only(&self) -> bool {
        self.diffuse > 0.0 && self.specular + self.mirror + self.transmission <= 0.0
    }

    /// True when the material has a lobe with a density (diffuse or Phong), so that light
    /// sampling can reach it.
    pub fn has_density(&self) -> bool {
        self.diffuse + self.specular > 0.0
    }

    /// True when the material scatters nothing.
    pub fn is_black(&self) -> bool {
        self.diffuse + self.specular + self.mirror + self.transmission <= 0.0
    }

    /// Density (1/sr) with which [`sample_bsdf`] produces the non-delta direction `wi`, for
    /// unit `wo` (toward the viewer) and unit normal `n` on the viewer's side.
    pub fn pdf(&self, m: &SurfaceMaterial, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        let cos = n.dot(wi);
        if cos <= 0.0 || n.dot(wo) <= 0.0 {
            return 0.0;
        }
        let mut pdf = self.diffuse * cosine_hemisphere_pdf(cos);
        if self.specular > 0.0 {
            pdf += self.specular * phong_pdf(reflect(wo, n).dot(wi), m.shininess);
        }
        pdf
    }
}

/// The local view of a surface point that scattering needs.
#[derive(Clone, Copy, Debug)]
pub struct ViewSide {
    /// Unit shading normal turned toward the viewer.
    pub n: Vec3,
    /// Unit geometric normal turned toward the viewer.
    pub ng: Vec3,
    /// Unit direction toward the viewer.
    pub wo: Vec3,
    /// Whether the viewer is on the material's front side (decides the refraction indices).
    pub front_face: bool,
}

/// Samples a continuation direction at a surface point seen as `side`, from the uniform
/// numbers `u_lobe` (chooses the lobe) and `u` (the direction). `None` when the path is
/// absorbed (the chosen direction leaves through the wrong side of the surface).
pub fn sample_bsdf(
    m: &SurfaceMaterial,
    choice: &LobeChoice,
    side: &ViewSide,
    u_lobe: f32,
    u: Vec2,
) -> Option<BsdfSample> {
    let ViewSide {
        n,
        ng,
        wo,
        front_face,
    } = *side;
    let non_delta = choice.diffuse + choice.specular;
    if u_lobe < non_delta {
        let wi = if u_lobe < choice.diffuse {
            cosine_about(V3::from(n), u.x, u.y).into()
        } else {
            sample_phong(n, wo, m.shininess, u)
        };
        let cos = n.dot(wi);
        if cos <= 0.0 || ng.dot(wi) <= 0.0 || n.dot(wo) <= 0.0 {
            return None;
        }
        if choice.specular <= 0.0 {
            // Lambert alone: f·cos/pdf = (ρ/π)·cos / (p_d·cos/π) = ρ/p_d, a constant the
            // processor need not wait for a division to know.
            return Some(BsdfSample {
                wi,
                weight: m.diffuse * choice.inverse_diffuse,
                pdf: choice.diffuse * cosine_hemisphere_pdf(cos),
                delta: false,
            });
        }
        let pdf = choice.pdf(m, n, wo, wi);
        if pdf <= 0.0 {
            return None;
        }
        return Some(BsdfSample {
            wi,
            weight: m.eval(n, wo, wi) * (cos / pdf),
            pdf,
            delta: false,
        });
    }
    let mirror_dir = reflect(wo, n);
    let delta = |wi: Vec3, weight: Rgb| {
        // A delta direction on the wrong side of the geometric surface would pass through it.
        let reflected = n.dot(wi) > 0.0;
        (reflected == (ng.dot(wi) > 0.0)).then_some(BsdfSample {
            wi,
            weight,
            pdf: 0.0,
            delta: true,
        })
    };
    if u_lobe < non_delta + choice.mirror || choice.transmission <= 0.0 {
        if choice.mirror <= 0.0 {
            return None;
        }
        return delta(mirror_dir, m.mirror / choice.mirror);
    }
    // Dielectric: reflect with the Fresnel probability, refract otherwise; the Fresnel factor
    // and its probability cancel. Refracted radiance is scaled by (η_i/η_t)² (radiance is
    // compressed into the smaller solid angle of the denser medium).
    let eta = if front_face { 1.0 / m.ior } else { m.ior };
    let weight = m.transmission / choice.transmission;
    let u_fresnel = (u_lobe - non_delta - choice.mirror) / choice.transmission;
    let fresnel = fresnel_dielectric(wo.dot(n), eta);
    match refract(wo, n, eta) {
        Some(t) if u_fresnel >= fresnel => delta(t, weight * (eta * eta)),
        _ => delta(mirror_dir, weight),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::warp::hemisphere_integral;
    use crate::sampling::{Sampler, SequenceKind};

    fn material(diffuse: f32, specular: f32, shininess: f32) -> SurfaceMaterial {
        SurfaceMaterial {
            diffuse: Rgb::splat(diffuse),
            specular: Rgb::splat(specular),
            shininess,
            mirror: Rgb::BLACK,
            transmission: Rgb::BLACK,
            ior: 1.5,
            one_sided: false,
        }
    }

    fn side(wo: Vec3) -> ViewSide {
        ViewSide {
            n: Vec3::Z,
            ng: Vec3::Z,
            wo,
            front_face: true,
        }
    }

    /// Mean of `f·cos/pdf` over many samples estimates the directional albedo; it must match
    /// the albedo from quadrature of `eval` (which does not use the sampler at all).
    #[test]
    fn sampled_weights_match_quadrature_albedo() {
        let n = Vec3::Z;
        let wo = Vec3::new(0.5, 0.0, 0.866_025_4);
        for (d, s, e) in [(0.6, 0.0, 1.0), (0.3, 0.5, 20.0), (0.0, 0.9, 200.0)] {
            let m = material(d, s, e);
            let choice = LobeChoice::new(&m);
            let count = 1 << 15;
            let mut sum = 0.0f64;
            let mut sum2 = 0.0f64;
            for k in 0..count {
                let mut sampler = Sampler::new(SequenceKind::Sobol, 3, 0, k);
                let u_lobe = sampler.next_1d();
                let u = sampler.next_2d();
                if let Some(bs) = sample_bsdf(&m, &choice, &side(wo), u_lobe, u) {
                    let w = bs.weight.r as f64;
                    sum += w;
                    sum2 += w * w;
                    // The reported density is the one eval/pdf is consistent with.
                    let pdf = choice.pdf(&m, n, wo, bs.wi);
                    assert!((pdf - bs.pdf).abs() <= 1e-4 * pdf, "{pdf} vs {}", bs.pdf);
                }
            }
            let mean = sum / count as f64;
            let std_err = ((sum2 / count as f64 - mean * mean).max(0.0) / count as f64).sqrt();
            // Quadrature of ∫ f cos dω on a fine (θ, φ) grid.
            let albedo = hemisphere_integral(600, |wi| m.eval(n, wo, wi).r as f64);
            // 5 standard errors of the Monte Carlo mean plus 0.5 % for the quadrature.
            let tolerance = 5.0 * std_err + 0.005 * albedo;
            assert!(
                (mean - albedo).abs() < tolerance,
                "d={d} s={s} e={e}: sampled {mean} vs quadrature {albedo} (±{tolerance})"
            );
        }
    }

    #[test]
    fn dielectric_reflects_by_fresnel_and_refracts_the_rest() {
        let m = SurfaceMaterial {
            transmission: Rgb::WHITE,
            ..material(0.0, 0.0, 1.0)
        };
        let choice = LobeChoice::new(&m);
        assert!(!choice.has_density());
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let fresnel = fresnel_dielectric(0.8, 1.0 / 1.5);
        let count = 4096;
        let reflected = (0..count)
            .filter_map(|k| {
                let u_lobe = (k as f32 + 0.5) / count as f32;
                sample_bsdf(&m, &choice, &side(wo), u_lobe, Vec2::splat(0.5))
            })
            .filter(|bs| bs.wi.z > 0.0)
            .count();
        // Stratified u_lobe: the fraction is exact to 1/count.
        let fraction = reflected as f32 / count as f32;
        assert!(
            (fraction - fresnel).abs() <= 1.0 / count as f32,
            "{fraction} vs {fresnel}"
        );
        let t = sample_bsdf(&m, &choice, &side(wo), 0.99, Vec2::ZERO).unwrap();
        assert!(t.delta && t.wi.z < 0.0);
        assert!((t.weight.r - 1.0 / 2.25).abs() < 1e-6, "{:?}", t.weight);
    }
}
