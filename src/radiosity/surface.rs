//! What one side of a patch does with light: the radiosity it emits, the share it reflects and
//! the share it passes diffusely to the other side (translucency), from its material with
//! textures averaged over the patch (for the solvers) or taken at a point (for the display,
//! which shows the texture at full resolution).
//!
//! An alpha texture cuts a surface: over a patch, only the share it leaves in place
//! ([`coverage`]) emits and reflects, so a patch's emitted radiosity and reflectance are per
//! unit of its whole area, and what it receives is its irradiance times that share of its
//! area. Light passes the cut-away parts: the visibility rays do not stop there.

use super::element::Side;
use super::mesh::Patch;
use crate::color::Rgb64;
use crate::scene::{Coverage, Lobe, MaterialId, Scene, TextureId};
use glam::DVec2;
use std::f64::consts::PI;

/// How a texture enters a surface term: its mean over a patch, its value at a point, or how
/// much it varies over a patch. Over a patch, a material's alpha texture counts too: only
/// the share of the patch it leaves in place emits and reflects.
#[derive(Clone, Copy, Debug)]
pub enum TextureAt<'p> {
    /// The exact mean over the patch's UV polygon ([`crate::scene::Texture::polygon_stats`])
    /// times the share of the patch present ([`coverage`]).
    Patch(&'p Patch),
    /// The filtered value at this texture coordinate ([`crate::scene::Texture::color`]), a
    /// point where the surface is present.
    Point(DVec2),
    /// How much the texture times the presence varies across the patch: the largest less
    /// the smallest product its texels allow.
    Spread(&'p Patch),
}

impl TextureAt<'_> {
    /// The texture's colour here times the presence the alpha texture `alpha` leaves;
    /// without textures `[1, 1, 1]` (`[0, 0, 0]` for a spread).
    fn colour(self, scene: &Scene, texture: Option<TextureId>, alpha: Option<TextureId>) -> Rgb64 {
        let texture = texture.and_then(|t| scene.textures.get(t as usize));
        let rgb = |c: [f64; 4]| Rgb64::new(c[0], c[1], c[2]);
        match self {
            TextureAt::Point(uv) => {
                texture.map_or(Rgb64::WHITE, |t| t.color(uv.as_vec2()).to_f64())
            }
            TextureAt::Patch(patch) => {
                let mean = texture.map_or(Rgb64::WHITE, |t| rgb(t.polygon_stats(patch.uvs()).mean));
                mean * coverage_of(scene, alpha, patch).mean
            }
            TextureAt::Spread(patch) => {
                let (low, high) = texture.map_or((Rgb64::WHITE, Rgb64::WHITE), |t| {
                    let stats = t.polygon_stats(patch.uvs());
                    let wide = |c: [f32; 4]| rgb(c.map(f64::from));
                    (wide(stats.min), wide(stats.max))
                });
                let present = coverage_of(scene, alpha, patch);
                high * present.max - low * present.min
            }
        }
    }
}

/// The share of `patch` the alpha texture `alpha` of `scene` leaves in place (all of it
/// without one).
fn coverage_of(scene: &Scene, alpha: Option<TextureId>, patch: &Patch) -> Coverage {
    match alpha.and_then(|t| scene.textures.get(t as usize)) {
        Some(t) => t.coverage(patch.uvs()),
        None => Coverage {
            mean: 1.0,
            min: 1.0,
            max: 1.0,
        },
    }
}

/// The share of `patch`'s area its material's alpha texture leaves in place, in `[0, 1]`
/// (1 without one): only that share receives, emits and reflects light.
pub fn coverage(scene: &Scene, patch: &Patch) -> f64 {
    let alpha = scene.materials[patch.material as usize].alpha_texture;
    coverage_of(scene, alpha, patch).mean
}

/// Emitted radiosity `E = π·L` (W·m⁻²) of side `side` of a patch of `scene` with material
/// `material`, the emission texture taken `at` the patch or a point: the front emits, the
/// back only for a `two_sided` material.
pub fn emission_of(scene: &Scene, material: MaterialId, side: Side, at: TextureAt) -> Rgb64 {
    let m = &scene.materials[material as usize];
    if m.emission.is_black() || !(side == Side::Front || m.two_sided) {
        return Rgb64::BLACK;
    }
    PI * m.emission.to_f64() * at.colour(scene, m.emission_texture, m.alpha_texture)
}

/// Diffuse reflectance in `[0, 1]` of side `side` of a patch of `scene` with material
/// `material`, the diffuse texture taken `at` the patch or a point; 0 on the back of a
/// `one_sided` material: the weight of its Lambert lobe (radiosity ignores the others).
pub fn reflectance_of(scene: &Scene, material: MaterialId, side: Side, at: TextureAt) -> Rgb64 {
    let m = &scene.materials[material as usize];
    if m.one_sided && side == Side::Back {
        return Rgb64::BLACK;
    }
    (m.lobe_weight(Lobe::Lambert).to_f64() * at.colour(scene, m.diffuse_texture, m.alpha_texture))
        .map(|v| v.clamp(0.0, 1.0))
}

/// Diffuse transmittance in `[0, 1]` of a patch of `scene` (either side) with material
/// `material`, scaled by the share an alpha texture leaves in place `at` the patch or a
/// point: the weight of its translucent lobe, 0 for a `one_sided` material (its back
/// absorbs everything, so nothing passes through).
pub fn translucency_of(scene: &Scene, material: MaterialId, at: TextureAt) -> Rgb64 {
    let m = &scene.materials[material as usize];
    if m.one_sided || m.translucency.is_black() {
        return Rgb64::BLACK;
    }
    let presence = match at {
        TextureAt::Point(_) => 1.0,
        TextureAt::Patch(patch) => coverage_of(scene, m.alpha_texture, patch).mean,
        TextureAt::Spread(patch) => {
            let c = coverage_of(scene, m.alpha_texture, patch);
            c.max - c.min
        }
    };
    (m.lobe_weight(Lobe::Translucent).to_f64() * presence).map(|v| v.clamp(0.0, 1.0))
}

/// [`translucency_of`] `patch`, averaged over the patch.
pub fn translucency(scene: &Scene, patch: &Patch) -> Rgb64 {
    translucency_of(scene, patch.material, TextureAt::Patch(patch))
}

/// [`emission_of`] side `side` of `patch`, its texture averaged over the patch, W·m⁻².
pub fn emission(scene: &Scene, patch: &Patch, side: Side) -> Rgb64 {
    emission_of(scene, patch.material, side, TextureAt::Patch(patch))
}

/// [`reflectance_of`] side `side` of `patch`, its texture averaged over the patch.
pub fn reflectance(scene: &Scene, patch: &Patch, side: Side) -> Rgb64 {
    reflectance_of(scene, patch.material, side, TextureAt::Patch(patch))
}

/// Whether `material` of `scene` has a diffuse, emission or alpha texture (its surface
/// terms vary across a patch).
pub fn is_textured(scene: &Scene, material: MaterialId) -> bool {
    let m = &scene.materials[material as usize];
    m.diffuse_texture.is_some()
        || m.alpha_texture.is_some()
        || (m.emission_texture.is_some() && !m.emission.is_black())
}

/// The names of the materials of `scene`'s objects that reflect or pass light other than
/// diffusely (any lobe besides Lambert's), in order of first use: radiosity counts that light
/// as absorbed.
pub fn non_diffuse_materials(scene: &Scene) -> Vec<&str> {
    let mut names: Vec<&str> = Vec::new();
    for object in &scene.objects {
        for &id in object.materials() {
            let m = &scene.materials[id as usize];
            if !m.is_diffuse() && !names.contains(&m.name.as_str()) {
                names.push(&m.name);
            }
        }
    }
    names
}
