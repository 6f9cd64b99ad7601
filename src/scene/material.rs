//! Named, shared surface materials.

use super::TextureId;
use crate::color::Rgb;

/// How far a material's summed lobe weights may exceed 1 (rounding in hand-written
/// decimals) before it is refused for creating light.
pub const ENERGY_TOLERANCE: f32 = 1e-6;

/// Largest colour channel a scene may give (emission, light colours), from a scene file or an
/// imported one: far beyond any physical radiance in any units, and far enough below
/// `f32::MAX` that sums of many samples stay finite (`emission = 1e38` rendered infinite
/// pixels).
pub const MAX_COLOUR: f32 = 1e18;

/// Index of a material in [`super::Scene::materials`].
pub type MaterialId = u32;

/// The ways a material scatters light, each with an RGB weight in the material
/// ([`Material::lobe_weight`]); the order is the one samplers choose in. Each lobe's
/// scattering is in its own file of `world::lobes`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Lobe {
    /// Lambertian (diffuse) reflection, BRDF ρ/π.
    Lambert,
    /// Diffuse transmission (translucency), BTDF τ/π: light arriving on one side leaves the
    /// other side as from a Lambertian surface.
    Translucent,
    /// The normalised Phong lobe about the mirror direction (glossy reflection).
    Phong,
    /// Ideal mirror reflection.
    Mirror,
    /// A smooth dielectric: Fresnel reflection and Snell refraction.
    Dielectric,
}

impl Lobe {
    /// Every lobe, in the order samplers choose among them: those with a density first.
    pub const ALL: [Lobe; 5] = [
        Lobe::Lambert,
        Lobe::Translucent,
        Lobe::Phong,
        Lobe::Mirror,
        Lobe::Dielectric,
    ];

    /// True for lobes that scatter into single directions (no density): mirror and
    /// dielectric.
    pub fn is_delta(self) -> bool {
        match self {
            Lobe::Lambert | Lobe::Translucent | Lobe::Phong => false,
            Lobe::Mirror | Lobe::Dielectric => true,
        }
    }

    /// The lobe's position in [`Lobe::ALL`].
    pub fn index(self) -> usize {
        match self {
            Lobe::Lambert => 0,
            Lobe::Translucent => 1,
            Lobe::Phong => 2,
            Lobe::Mirror => 3,
            Lobe::Dielectric => 4,
        }
    }
}

/// A surface material. Its lobes add up: diffuse (Lambert) reflectance, diffuse
/// transmission (translucency), Phong glossy reflection, ideal mirror reflection and ideal
/// refraction; every lobe has an RGB weight in
/// `[0, 1]` and their sum per channel must not exceed 1 (energy conservation, checked when a
/// scene is loaded).
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Unique name.
    pub name: String,
    /// Diffuse reflectance ρ (Lambertian, BRDF ρ/π).
    pub diffuse: Rgb,
    /// Texture multiplied into `diffuse`.
    pub diffuse_texture: Option<TextureId>,
    /// Diffuse transmittance τ (translucency, BTDF τ/π): the fraction of the light arriving
    /// on either side that leaves the other side diffusely. Untextured.
    pub translucency: Rgb,
    /// Emitted radiance L in W·sr⁻¹·m⁻² (a Lambertian emitter's radiosity is π·L).
    pub emission: Rgb,
    /// Texture multiplied into `emission`.
    pub emission_texture: Option<TextureId>,
    /// Emit from both sides; otherwise only from the front face (counter-clockwise side).
    pub two_sided: bool,
    /// Phong specular weight (normalised lobe, reflects this fraction at normal incidence).
    pub specular: Rgb,
    /// Phong exponent.
    pub shininess: f32,
    /// Ideal mirror reflectance.
    pub mirror: Rgb,
    /// Ideal refraction weight (glass-like when non-zero, with Fresnel).
    pub transmission: Rgb,
    /// Index of refraction of the material behind the front face.
    pub ior: f32,
    /// Alpha texture: texels with alpha below ½ cut the surface away, for camera rays and
    /// shadows alike.
    pub alpha_texture: Option<TextureId>,
    /// Reflect only from the front face; the back face absorbs everything.
    pub one_sided: bool,
}

impl Default for Material {
    fn default() -> Self {
        Material {
            name: "default".to_string(),
            diffuse: Rgb::splat(0.8),
            diffuse_texture: None,
            translucency: Rgb::BLACK,
            emission: Rgb::BLACK,
            emission_texture: None,
            two_sided: false,
            specular: Rgb::BLACK,
            shininess: 50.0,
            mirror: Rgb::BLACK,
            transmission: Rgb::BLACK,
            ior: 1.5,
            alpha_texture: None,
            one_sided: false,
        }
    }
}

impl Material {
    /// A plain Lambertian material.
    pub fn diffuse(name: &str, rho: Rgb) -> Self {
        Material {
            name: name.to_string(),
            diffuse: rho,
            ..Material::default()
        }
    }

    /// A Lambertian emitter with reflectance `rho` and radiance `emission`.
    pub fn emitter(name: &str, rho: Rgb, emission: Rgb) -> Self {
        Material {
            emission,
            ..Material::diffuse(name, rho)
        }
    }

    /// True when the material emits light (or could, through an emission texture).
    pub fn is_emissive(&self) -> bool {
        !self.emission.is_black()
    }

    /// The weight of `lobe` (reflectance or transmittance per channel, in `[0, 1]`; the
    /// diffuse weight before its texture).
    pub fn lobe_weight(&self, lobe: Lobe) -> Rgb {
        match lobe {
            Lobe::Lambert => self.diffuse,
            Lobe::Translucent => self.translucency,
            Lobe::Phong => self.specular,
            Lobe::Mirror => self.mirror,
            Lobe::Dielectric => self.transmission,
        }
    }

    /// True when the material scatters by its diffuse lobes alone, Lambertian reflection and
    /// translucency (what radiosity models).
    pub fn is_diffuse(&self) -> bool {
        Lobe::ALL.iter().all(|&lobe| {
            matches!(lobe, Lobe::Lambert | Lobe::Translucent) || self.lobe_weight(lobe).is_black()
        })
    }

    /// Drops the lobes radiosity does not model (Phong, mirror, refraction): the light they
    /// would scatter is absorbed, as every radiosity solver counts it. The light model run on
    /// a scene made so solves what radiosity solves, to check a radiosity solution by.
    pub fn keep_diffuse_lobes(&mut self) {
        self.specular = Rgb::BLACK;
        self.mirror = Rgb::BLACK;
        self.transmission = Rgb::BLACK;
    }

    /// Largest per-channel sum of the reflected and transmitted fractions (must be ≤ 1, up
    /// to [`ENERGY_TOLERANCE`]).
    pub fn albedo_bound(&self) -> f32 {
        Lobe::ALL
            .iter()
            .fold(Rgb::BLACK, |sum, &lobe| sum + self.lobe_weight(lobe))
            .max_channel()
    }

    /// True when the material scatters and emits nothing (no lobe, no emission, no
    /// textures): a surface of it is a measuring patch, a black quad placed to read the light,
    /// whose light goes nowhere else.
    pub fn is_measuring(&self) -> bool {
        self.albedo_bound() == 0.0
            && self.diffuse_texture.is_none()
            && self.emission == Rgb::BLACK
            && self.emission_texture.is_none()
    }
}
