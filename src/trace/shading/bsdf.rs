//! Sampling the scattering of a [`SurfaceMaterial`] for path tracing.
//!
//! A material is a mixture of lobes ([`Lobe`]: Lambert, translucent (diffuse transmission),
//! normalised Phong, ideal mirror and a smooth dielectric that reflects or refracts by
//! Fresnel). One lobe is chosen with
//! probability proportional to the luminance of its weight. Directions from the lobes with a
//! density are weighted by the full mixture of those lobes (`f·cos / pdf` with `pdf` the sum
//! over them of choice probability times lobe density), which is what [`LobeChoice::pdf`]
//! returns, so the density used by multiple importance sampling is the one the sampler
//! actually draws from. The delta lobes (mirror, dielectric) have no density and never take
//! part in multiple importance sampling.

use crate::color::Rgb;
use crate::scene::Material;
use crate::world::SurfaceMaterial;
use crate::world::lobes::{Lobe, LocalView};
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
    /// Per lobe of [`Lobe::ALL`], the probability of choosing it.
    probability: [f32; Lobe::ALL.len()],
    /// Per lobe, `1 / probability` (0 for a lobe never chosen).
    inverse: [f32; Lobe::ALL.len()],
}

impl LobeChoice {
    /// The lobe probabilities of `m`.
    pub fn new(m: &SurfaceMaterial) -> Self {
        Self::from_weights(Lobe::ALL.map(|lobe| lobe.weight(m)))
    }

    /// The lobe probabilities of a scene material without a diffuse texture (the same at
    /// every point of it).
    pub fn of_material(m: &Material) -> Self {
        Self::from_weights(Lobe::ALL.map(|lobe| m.lobe_weight(lobe)))
    }

    /// Probabilities from the lobe weights, in the order of [`Lobe::ALL`].
    fn from_weights(weights: [Rgb; Lobe::ALL.len()]) -> Self {
        let luminance = weights.map(|w| w.luminance().max(0.0));
        let total: f32 = luminance.iter().sum();
        if total <= 0.0 {
            return LobeChoice {
                probability: [0.0; Lobe::ALL.len()],
                inverse: [0.0; Lobe::ALL.len()],
            };
        }
        LobeChoice {
            probability: luminance.map(|l| l / total),
            inverse: luminance.map(|l| if l > 0.0 { total / l } else { 0.0 }),
        }
    }

    /// The probability of choosing `lobe`.
    #[inline]
    fn of(&self, lobe: Lobe) -> f32 {
        self.probability[lobe.index()]
    }

    /// True for a material whose only lobe is Lambert's, which it then chooses with
    /// probability exactly 1 (`d / d`), so [`sample_bsdf`]'s weight is the reflectance itself.
    pub fn is_lambert_only(&self) -> bool {
        Lobe::ALL.iter().all(|&lobe| {
            if lobe == Lobe::Lambert {
                self.of(lobe) > 0.0
            } else {
                self.of(lobe) <= 0.0
            }
        })
    }

    /// True when the material has a lobe with a density, so that light sampling can reach it.
    pub fn has_density(&self) -> bool {
        self.density_share() > 0.0
    }

    /// True when the material scatters nothing.
    pub fn is_black(&self) -> bool {
        self.probability.iter().sum::<f32>() <= 0.0
    }

    /// The probability of choosing a lobe with a density.
    #[inline]
    fn density_share(&self) -> f32 {
        Lobe::ALL
            .iter()
            .filter(|lobe| !lobe.is_delta())
            .map(|&lobe| self.of(lobe))
            .sum()
    }

    /// Density (1/sr) with which [`sample_bsdf`] produces the non-delta direction `wi` (on
    /// either side of the surface), for unit `wo` (toward the viewer) and unit normal `n` on
    /// the viewer's side.
    pub fn pdf(&self, m: &SurfaceMaterial, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        let cos = n.dot(wi);
        if cos == 0.0 || n.dot(wo) <= 0.0 {
            return 0.0;
        }
        // Directions behind the surface come only from the transmitting lobes.
        let behind = cos < 0.0;
        let mut pdf = 0.0;
        for lobe in Lobe::ALL {
            if !lobe.is_delta() && lobe.transmits() == behind && self.of(lobe) > 0.0 {
                pdf += self.of(lobe) * lobe.pdf(m, n, wo, wi);
            }
        }
        pdf
    }
}

/// Samples a continuation direction at a surface point seen as `view`, from the uniform
/// numbers `u_lobe` (chooses the lobe) and `u` (the direction). `None` when the path is
/// absorbed (the chosen direction leaves through the wrong side of the surface).
pub fn sample_bsdf(
    m: &SurfaceMaterial,
    choice: &LobeChoice,
    view: &LocalView,
    u_lobe: f32,
    u: Vec2,
) -> Option<BsdfSample> {
    let LocalView { n, ng, wo, .. } = *view;
    let non_delta = choice.density_share();
    if u_lobe < non_delta {
        // The lobes with a density, in order; the last one takes what rounding leaves over.
        let mut cumulative = 0.0;
        let mut chosen = None;
        for lobe in Lobe::ALL.into_iter().filter(|lobe| !lobe.is_delta()) {
            cumulative += choice.of(lobe);
            chosen = Some(lobe);
            if u_lobe < cumulative {
                break;
            }
        }
        let lobe = chosen?;
        let (wi, _) = lobe.sample(m, view, u, 0.0);
        // The direction must leave on the lobe's side of both the shading and the geometric
        // surface (behind both for the translucent lobe).
        let sign = if lobe.transmits() { -1.0 } else { 1.0 };
        let cos = sign * n.dot(wi);
        if cos <= 0.0 || sign * ng.dot(wi) <= 0.0 || n.dot(wo) <= 0.0 {
            return None;
        }
        let alone = Lobe::ALL
            .iter()
            .all(|&other| other == lobe || other.is_delta() || choice.of(other) <= 0.0);
        if alone && lobe.samples_its_weight() {
            // f·cos/pdf = weight/p exactly, a constant the processor need not wait for a
            // division to know.
            return Some(BsdfSample {
                wi,
                weight: lobe.weight(m) * choice.inverse[lobe.index()],
                pdf: choice.of(lobe) * lobe.pdf(m, n, wo, wi),
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
    // The delta lobes, in order: the first whose interval holds `u_lobe`, else the last one
    // with any probability; `u_lobe` rescaled to the chosen interval chooses within it.
    let mut start = non_delta;
    let mut rest = u_lobe - non_delta;
    let mut chosen = None;
    for lobe in Lobe::ALL.into_iter().filter(|lobe| lobe.is_delta()) {
        let p = choice.of(lobe);
        if p <= 0.0 {
            continue;
        }
        chosen = Some((lobe, p, rest));
        if u_lobe < start + p {
            break;
        }
        start += p;
        rest -= p;
    }
    let (lobe, p, rest) = chosen?;
    let (wi, factor) = lobe.sample(m, view, u, rest / p);
    let weight = lobe.weight(m) / p;
    // A delta direction on the wrong side of the geometric surface would pass through it.
    let reflected = n.dot(wi) > 0.0;
    (reflected == (ng.dot(wi) > 0.0)).then_some(BsdfSample {
        wi,
        weight: weight * factor,
        pdf: 0.0,
        delta: true,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::warp::hemisphere_integral;
    use crate::sampling::{Sampler, SequenceKind};
    use crate::world::optics::fresnel_dielectric;

    fn material(diffuse: f32, specular: f32, shininess: f32) -> SurfaceMaterial {
        SurfaceMaterial {
            diffuse: Rgb::splat(diffuse),
            translucency: Rgb::BLACK,
            specular: Rgb::splat(specular),
            shininess,
            mirror: Rgb::BLACK,
            transmission: Rgb::BLACK,
            ior: 1.5,
            one_sided: false,
        }
    }

    fn side(wo: Vec3) -> LocalView {
        LocalView {
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

    /// A translucent material sends the share τ/(ρ + τ) of its samples behind the surface,
    /// each carrying `f·|cos|/pdf = ρ + τ` (both lobes are cosine-shaped), and the density
    /// it reports is the one `pdf` gives on either side.
    #[test]
    fn translucent_lobe_samples_behind_the_surface() {
        let m = SurfaceMaterial {
            translucency: Rgb::splat(0.5),
            ..material(0.3, 0.0, 1.0)
        };
        let choice = LobeChoice::new(&m);
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let count = 4096;
        let mut behind = 0;
        for k in 0..count {
            let mut sampler = Sampler::new(SequenceKind::Sobol, 3, 0, k);
            let (u_lobe, u) = (sampler.next_1d(), sampler.next_2d());
            let Some(bs) = sample_bsdf(&m, &choice, &side(wo), u_lobe, u) else {
                continue;
            };
            if bs.wi.z < 0.0 {
                behind += 1;
            }
            assert!((bs.weight.g - 0.8).abs() < 1e-5, "{:?}", bs.weight);
            let pdf = choice.pdf(&m, Vec3::Z, wo, bs.wi);
            assert!((pdf - bs.pdf).abs() <= 1e-4 * pdf, "{pdf} vs {}", bs.pdf);
            let f = m.eval(Vec3::Z, wo, bs.wi).g;
            let expected = if bs.wi.z < 0.0 { 0.5 } else { 0.3 } / std::f32::consts::PI;
            assert!((f - expected).abs() < 1e-6, "{f} vs {expected}");
        }
        // Stratified lobe choices: the share behind is exact to a few samples.
        let share = behind as f32 / count as f32;
        assert!((share - 0.625).abs() < 4.0 / count as f32, "{share}");
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
