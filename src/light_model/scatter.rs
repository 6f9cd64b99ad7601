//! What happens to a photon at a surface: absorbed, or scattered by one of the material's lobes
//! ([`Lobe`]: Lambert, translucent, normalised Phong, ideal mirror, smooth dielectric with
//! Fresnel), chosen at random so that the expected outgoing power is exactly the material's.
//!
//! The lobe k is chosen with probability `pₖ = Σ_c Φ_c·wₖ_c / Σ_c Φ_c` (Φ the photon's RGB
//! power, wₖ the lobe's RGB weight) and the photon continues with `Φ·wₖ/pₖ`; with probability
//! `1 − Σₖ pₖ` it is absorbed (Russian roulette by the material's albedo). A photon carrying
//! several groups' powers (one path for several relit worlds, `trace.rs`) chooses by the sums
//! over the groups' channels, `pₖ = Σ_g Σ_c Φᵍ_c·wᵍₖ_c / Σ_g Σ_c Φᵍ_c`, each group's power
//! continuing with `Φᵍ·wᵍₖ/pₖ`; the groups differ only in their lobes' weights, so the
//! direction is drawn once. The channel sum
//! of the power is kept by every choice except the Phong lobe, whose sampled direction
//! carries the factor `(s+2)/(s+1)·cos θ` (normalised lobe over its sampling density).
//! Diffuse directions are cosine-distributed about the geometric normal (reversed for the
//! translucent lobe, which passes the photon through); mirror, Phong and
//! refraction directions use the shading normal, and a direction that would leave on the
//! wrong side of the geometric normal is absorbed.

use crate::color::{Rgb, Rgb64};
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::world::lobes::{Lobe, LocalView};
use crate::world::{SurfaceHit, SurfaceMaterial};
use glam::Vec3;

/// The fate of a photon arriving along the unit direction `dir` at `hit` and carrying, for
/// each of the scenes `scenes` (one geometry, other materials), the power `powers[g]` (W per
/// channel): the unit direction it leaves in, `powers` then holding what it carries on; `None`
/// when absorbed. `materials` is scratch space (it holds the scenes' materials at `hit`).
pub fn scatter_photon(
    scenes: &[&Scene],
    hit: &SurfaceHit,
    dir: Vec3,
    powers: &mut [Rgb64],
    materials: &mut Vec<SurfaceMaterial>,
    sampler: &mut Sampler,
) -> Option<Vec3> {
    materials.clear();
    materials.extend(scenes.iter().map(|scene| SurfaceMaterial::at(scene, hit)));
    if materials.iter().all(|m| m.is_black_from(hit.front_face)) {
        return None;
    }
    let total: f64 = powers
        .iter()
        .map(|p| p.to_array().iter().sum::<f64>())
        .sum();
    if total <= 0.0 {
        return None;
    }
    let side = if hit.front_face { 1.0 } else { -1.0 };
    let view = LocalView {
        n: hit.ns * side,
        ng: hit.ng * side,
        wo: -dir,
        front_face: hit.front_face,
    };
    let weighted =
        |power: &Rgb64, w: Rgb| power.r * w.r as f64 + power.g * w.g as f64 + power.b * w.b as f64;
    let u = sampler.next_1d() as f64;
    let mut cumulative = 0.0;
    let mut chosen = None;
    for lobe in Lobe::ALL {
        let p = powers
            .iter()
            .zip(materials.iter())
            .map(|(power, m)| weighted(power, lobe.weight(m)))
            .sum::<f64>()
            / total;
        cumulative += p;
        if p > 0.0 && u < cumulative {
            chosen = Some((lobe, p));
            break;
        }
    }
    let (lobe, p) = chosen?;
    let u2 = sampler.next_2d();
    let (out, factor) = lobe.sample_photon(&materials[0], &view, u2, sampler)?;
    let ng = view.ng;
    let transmitted = lobe.transmits() && out.dot(ng) < 0.0;
    if (out.dot(ng) <= 0.0) != transmitted {
        return None;
    }
    let scale = factor as f64 / p;
    for (power, m) in powers.iter_mut().zip(materials.iter()) {
        *power = *power * lobe.weight(m).to_f64() * scale;
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::SequenceKind;
    use crate::scene::{Material, Shape};
    use crate::world::SceneGeometry;

    /// The hit of a ray coming straight down onto an upward unit quad with material `m`.
    /// Where a photon of `power` arriving along `dir` at `hit` of `scene` goes, and with what.
    fn scatter(
        scene: &Scene,
        hit: &SurfaceHit,
        dir: Vec3,
        power: Rgb64,
        sampler: &mut Sampler,
    ) -> Option<(Vec3, Rgb64)> {
        let mut powers = [power];
        let out = scatter_photon(&[scene], hit, dir, &mut powers, &mut Vec::new(), sampler)?;
        Some((out, powers[0]))
    }

    fn hit_on_quad(m: Material) -> (Scene, SurfaceHit) {
        let mut scene = Scene::empty("q");
        let id = scene.add_material(m);
        scene.add_object(
            "quad",
            Shape::Parallelogram {
                origin: Vec3::new(-0.5, 0.0, 0.5),
                edge_u: Vec3::X,
                edge_v: Vec3::NEG_Z,
            },
            id,
        );
        let g = SceneGeometry::new(&scene).unwrap();
        let mut hit = g.point_on_triangle(0, 0.25, 0.25);
        hit.front_face = true;
        (scene, hit)
    }

    #[test]
    fn mean_outgoing_power_equals_the_albedo() {
        let m = Material {
            diffuse: Rgb::new(0.5, 0.2, 0.1),
            specular: Rgb::new(0.1, 0.1, 0.1),
            shininess: 20.0,
            mirror: Rgb::new(0.1, 0.3, 0.2),
            ..Material::default()
        };
        let (scene, hit) = hit_on_quad(m);
        let n = 200_000;
        let mut sum = [0.0f64; 3];
        let mut sum_sq = [0.0f64; 3];
        for i in 0..n {
            let mut s = Sampler::new(SequenceKind::Random, 3, i, 0);
            if let Some((dir, power)) = scatter(&scene, &hit, -Vec3::Y, Rgb64::WHITE, &mut s) {
                assert!(dir.y > 0.0);
                for c in 0..3 {
                    sum[c] += power[c];
                    sum_sq[c] += power[c] * power[c];
                }
            }
        }
        // At normal incidence the Phong factor (s+2)/(s+1)·cos α has mean 1 under the
        // sampling density ∝ cosˢα (E[cos α] = (s+1)/(s+2)): the lobe reflects its weight.
        let phong = 1.0;
        let expected = [
            0.5 + 0.1 * phong + 0.1,
            0.2 + 0.1 * phong + 0.3,
            0.1 + 0.1 * phong + 0.2,
        ];
        for c in 0..3 {
            let mean = sum[c] / n as f64;
            let sigma = ((sum_sq[c] / n as f64 - mean * mean) / n as f64).sqrt();
            assert!(
                (mean - expected[c]).abs() < 5.0 * sigma,
                "{c}: {mean} vs {}",
                expected[c]
            );
        }
    }

    /// A translucent leaf sends photons back with power ρ and through with power τ on
    /// average, the ones through cosine-distributed about the far side's normal (mean
    /// cosine 2/3).
    #[test]
    fn translucent_photons_pass_through_diffusely() {
        let m = Material {
            translucency: Rgb::splat(0.5),
            ..Material::diffuse("leaf", Rgb::splat(0.3))
        };
        let (scene, hit) = hit_on_quad(m);
        let n = 100_000;
        let (mut back, mut through, mut cos_through) = (0.0, 0.0, 0.0);
        for i in 0..n {
            let mut s = Sampler::new(SequenceKind::Random, 3, i, 0);
            if let Some((dir, power)) = scatter(&scene, &hit, -Vec3::Y, Rgb64::WHITE, &mut s) {
                if dir.y > 0.0 {
                    back += power.g;
                } else {
                    through += power.g;
                    cos_through += f64::from(-dir.y) * power.g;
                }
            }
        }
        let n = n as f64;
        // Each photon carries ρ + τ = 0.8 when it goes on: binomial shares of 0.3/0.8 and
        // 0.5/0.8 of a 0.8 survival.
        let sigma = 0.8 * (0.25 * 0.75 / n).sqrt();
        assert!((back / n - 0.3).abs() < 5.0 * sigma, "{}", back / n);
        assert!((through / n - 0.5).abs() < 5.0 * sigma, "{}", through / n);
        let mean_cos = cos_through / through;
        assert!((mean_cos - 2.0 / 3.0).abs() < 0.01, "{mean_cos}");
    }

    #[test]
    fn glass_reflects_the_fresnel_fraction_and_refracts_the_rest() {
        let m = Material {
            diffuse: Rgb::BLACK,
            transmission: Rgb::WHITE,
            ior: 1.5,
            ..Material::default()
        };
        let (scene, hit) = hit_on_quad(m);
        let n = 100_000;
        let mut reflected = 0;
        for i in 0..n {
            let mut s = Sampler::new(SequenceKind::Random, 5, i, 0);
            let (dir, power) =
                scatter(&scene, &hit, -Vec3::Y, Rgb64::new(1.0, 2.0, 3.0), &mut s).unwrap();
            assert!((power.r - 1.0).abs() < 1e-12 && (power.b - 3.0).abs() < 1e-12);
            if dir.y > 0.0 {
                reflected += 1;
            } else {
                assert!((dir + Vec3::Y).length() < 1e-5);
            }
        }
        // F = 0.04 at normal incidence; binomial σ = √(0.04·0.96/n) = 6.2e-4.
        let f = reflected as f64 / n as f64;
        assert!((f - 0.04).abs() < 5.0 * 6.2e-4, "{f}");
    }
}
