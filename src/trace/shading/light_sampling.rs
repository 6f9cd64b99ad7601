//! Next-event estimation: choosing one light in proportion to its power and sampling a
//! direction toward it.
//!
//! Power estimates (luminance, watts) used only to choose lights:
//! - area light: [`crate::world::AreaLight::power`], π·L·A per emitting side (texture mean
//!   applied);
//! - point, Lambertian, spot and directional lights: [`crate::scene::LightKind::power`] —
//!   4π·I, π·I₀, I times the spot's exact solid angle
//!   ([`crate::scene::LightKind::spot_solid_angle`]), E·πr² with r the radius of the bounding
//!   sphere of the bounded geometry;
//! - sky: π·L·πr² (the radiance through the scene's cross-section from one hemisphere).
//!
//! Area lights are sampled uniformly by area and their density turned into solid angle,
//! `pdf_ω = pdf_A·d²/|cos θ_y|`; the sky is sampled cosine-weighted about the shading normal.

use crate::color::Rgb;
use crate::geometry::Frame;
use crate::lanes::{Real, V3};
use crate::sampling::warp::cosine_hemisphere;
use crate::world::World;
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

/// Where a shadow ray toward a light sample ends.
#[derive(Clone, Copy, Debug)]
pub enum ShadowTarget {
    /// At this point (world).
    Point(Vec3),
    /// At infinity.
    Infinity,
}

/// Light arriving at a shading point from one sampled light.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit direction toward the light.
    pub wi: Vec3,
    /// Incident radiance divided by the sampling density (solid-angle density times the
    /// probability of choosing the light); for delta lights the normal irradiance divided by
    /// the choice probability. Multiply by `f·cos θ`.
    pub radiance_over_pdf: Rgb,
    /// Solid-angle density (1/sr) including the choice probability, for multiple importance
    /// sampling; 0 for delta lights.
    pub pdf: f32,
    /// Where the shadow ray ends.
    pub target: ShadowTarget,
}

/// A point sampled on an area light of uniform radiance, before anything about the shading
/// point is known.
#[derive(Clone, Copy, Debug)]
pub struct UniformAreaPoint {
    /// The point (world).
    pub p: Vec3,
    /// Unit front-side normal.
    pub n: Vec3,
    /// Radiance toward the front and toward the back (W·sr⁻¹·m⁻²).
    pub radiance: [Rgb; 2],
    /// Density with respect to area (1/m²), the probability of choosing the light included.
    pub pdf_area: f32,
}

/// A point on an area light as seen from a shading point, lane by lane.
#[derive(Clone, Copy, Debug)]
pub struct TowardLight<R> {
    /// Unit direction from the shading point to the light point.
    pub wi: V3<R>,
    /// Squared distance between them.
    pub dist2: R,
    /// Cosine at the light between its front normal and the way back (negative when the
    /// shading point is behind the light).
    pub cos_light: R,
}

/// How the light point `p` (unit front normal `n_light`) lies as seen from `x`.
#[inline(always)]
pub fn toward_light<R: Real>(x: V3<R>, p: V3<R>, n_light: V3<R>) -> TowardLight<R> {
    let d = p - x;
    let dist2 = d.dot(d);
    let wi = d.scale(R::splat(1.0) / dist2.sqrt());
    TowardLight {
        wi,
        dist2,
        cos_light: n_light.dot(-wi),
    }
}

impl<R: Real> TowardLight<R> {
    /// The solid-angle density (1/sr) of a light point drawn with area density `pdf_area`
    /// (1/m²): `pdf_area · d² / |cos θ_light|`.
    #[inline(always)]
    pub fn solid_angle_pdf(&self, pdf_area: R) -> R {
        pdf_area * self.dist2 / self.cos_light.abs()
    }
}

/// One entry of the light-choice distribution.
#[derive(Clone, Copy, Debug)]
enum Choice {
    Area(usize),
    Delta(usize),
    Sky,
}

/// Chooses lights in proportion to their power.
#[derive(Clone, Debug, Default)]
pub struct LightPicker {
    choices: Vec<Choice>,
    /// Cumulative probabilities of `choices` (last = 1).
    cdf: Vec<f32>,
    /// Probability of choosing each area light.
    area_probability: Vec<f32>,
    /// Probability of choosing the sky.
    sky_probability: f32,
}

impl LightPicker {
    /// The distribution over the lights of `world`.
    pub fn new(world: &World) -> Self {
        let lights = &world.lights;
        let (_, radius) = world.geometry.bounding_sphere();
        let cross_section = PI * radius * radius;
        let mut choices = Vec::new();
        let mut power = Vec::new();
        for (i, l) in lights.area.iter().enumerate() {
            choices.push(Choice::Area(i));
            power.push(l.power.luminance());
        }
        for (i, l) in lights.delta.iter().enumerate() {
            // Point, spot and directional lights by the power they send into the scene.
            let p = l.power(radius).map_or(0.0, |p| p.luminance());
            choices.push(Choice::Delta(i));
            power.push(p);
        }
        if let Some(sky) = &lights.sky {
            choices.push(Choice::Sky);
            power.push(sky.horizontal_luminance() * cross_section);
        }
        let power: Vec<f32> = power.into_iter().map(|p| p.max(0.0)).collect();
        let total: f32 = power.iter().sum();
        if total <= 0.0 || !total.is_finite() {
            return LightPicker::default();
        }
        let mut cdf = Vec::with_capacity(power.len());
        let mut acc = 0.0;
        let mut area_probability = vec![0.0; lights.area.len()];
        let mut sky_probability = 0.0;
        for (c, p) in choices.iter().zip(&power) {
            let probability = p / total;
            acc += probability;
            cdf.push(acc);
            match *c {
                Choice::Area(i) => area_probability[i] = probability,
                Choice::Sky => sky_probability = probability,
                Choice::Delta(_) => {}
            }
        }
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        LightPicker {
            choices,
            cdf,
            area_probability,
            sky_probability,
        }
    }

    /// Solid-angle density (1/sr, choice probability included) with which [`Self::sample`]
    /// picks the point `p` (unit front normal `n_light`) of area light `light`, as seen from
    /// `x`.
    pub fn area_pdf(&self, world: &World, light: usize, x: Vec3, p: Vec3, n_light: Vec3) -> f32 {
        let d = p - x;
        let dist2 = d.length_squared();
        let cos_y = n_light.dot(d).abs() / dist2.sqrt();
        if cos_y <= 0.0 {
            return 0.0;
        }
        self.area_probability[light] / world.lights.area[light].area * dist2 / cos_y
    }

    /// Solid-angle density (1/sr, choice probability included) of sampling the sky in
    /// direction `wi` from a point with unit shading normal `n`.
    pub fn sky_pdf(&self, n: Vec3, wi: Vec3) -> f32 {
        self.sky_probability * n.dot(wi).max(0.0) * FRAC_1_PI
    }

    /// The light `u_pick` chooses, its probability, and what remains of `u_pick` after the
    /// choice, rescaled to `[0, 1)`.
    #[inline]
    fn choose(&self, u_pick: f32) -> Option<(Choice, f32, f32)> {
        let index = self
            .cdf
            .partition_point(|&c| c <= u_pick)
            .min(self.cdf.len().checked_sub(1)?);
        let below = if index == 0 { 0.0 } else { self.cdf[index - 1] };
        let probability = self.cdf[index] - below;
        if probability <= 0.0 {
            return None;
        }
        let u_prim = ((u_pick - below) / probability).clamp(0.0, 1.0 - f32::EPSILON / 2.0);
        Some((self.choices[index], probability, u_prim))
    }

    /// The point [`Self::sample`] draws from the same numbers when they choose an area light
    /// that emits the same radiance everywhere; `None` for any other choice.
    pub fn uniform_area_point(
        &self,
        world: &World,
        u_pick: f32,
        u: Vec2,
    ) -> Option<UniformAreaPoint> {
        let (Choice::Area(light), probability, u_prim) = self.choose(u_pick)? else {
            return None;
        };
        let radiance = world.lights.area[light].uniform_radiance()?;
        let s = world.lights.sample_area(&world.geometry, light, u_prim, u);
        Some(UniformAreaPoint {
            p: s.p,
            n: s.n,
            radiance,
            pdf_area: probability * s.pdf_area,
        })
    }

    /// Samples one light for the shading point `x` with unit shading normal `n` (toward the
    /// viewer), from uniform numbers `u_pick` (chooses the light; what remains of it after the
    /// choice, rescaled to `[0, 1)`, chooses the light's triangle) and `u` (the point). `None`
    /// when the sample carries no light (behind the point unless `through` — a surface that
    /// passes light diffusely — back of a one-sided emitter, outside a spot cone). The sky is
    /// sampled in front of the point only ([`Self::sky_pdf`] is 0 behind it), so the sky seen
    /// through a translucent surface comes from scattering alone.
    pub fn sample(
        &self,
        world: &World,
        x: Vec3,
        n: Vec3,
        through: bool,
        u_pick: f32,
        u: Vec2,
    ) -> Option<LightSample> {
        let arrives = |wi: Vec3| through || n.dot(wi) > 0.0;
        let (choice, probability, u_prim) = self.choose(u_pick)?;
        match choice {
            Choice::Area(light) => {
                let s = world.lights.sample_area(&world.geometry, light, u_prim, u);
                let toward = toward_light(V3::from(x), V3::from(s.p), V3::from(s.n));
                let (wi, cos_y) = (Vec3::from(toward.wi), toward.cos_light);
                if toward.dist2 <= 0.0 || cos_y == 0.0 || n.dot(wi) == 0.0 || !arrives(wi) {
                    return None;
                }
                let le = world.lights.area_radiance(
                    &world.scene,
                    &world.geometry,
                    light,
                    &s,
                    cos_y > 0.0,
                );
                if le.is_black() {
                    return None;
                }
                let pdf = toward.solid_angle_pdf(probability * s.pdf_area);
                Some(LightSample {
                    wi,
                    radiance_over_pdf: le / pdf,
                    pdf,
                    target: ShadowTarget::Point(s.p),
                })
            }
            Choice::Sky => {
                let sky = world.lights.sky.as_ref()?;
                let wi = Frame::from_normal(n).to_world(cosine_hemisphere(u));
                let pdf = self.sky_pdf(n, wi);
                if pdf <= 0.0 {
                    return None;
                }
                Some(LightSample {
                    wi,
                    radiance_over_pdf: sky.radiance(wi) / pdf,
                    pdf,
                    target: ShadowTarget::Infinity,
                })
            }
            Choice::Delta(light) => {
                let inc = world.lights.delta[light].incidence(x)?;
                if inc.irradiance.is_black() || n.dot(inc.wi) == 0.0 || !arrives(inc.wi) {
                    return None;
                }
                let target = if inc.distance.is_finite() {
                    ShadowTarget::Point(x + inc.wi * inc.distance)
                } else {
                    ShadowTarget::Infinity
                };
                Some(LightSample {
                    wi: inc.wi,
                    radiance_over_pdf: inc.irradiance / probability,
                    pdf: 0.0,
                    target,
                })
            }
        }
    }
}
