//! What one side of a patch does with light: the radiosity it emits and the share it
//! reflects, from its material with textures averaged over the patch (for the solvers) or
//! taken at a point (for the display, which shows the texture at full resolution).

use super::element::Side;
use super::mesh::Patch;
use crate::color::Rgb64;
use crate::scene::{MaterialId, Scene, TextureId};
use glam::DVec2;
use std::f64::consts::PI;

/// How a texture enters a surface term: its mean over a patch, its value at a point, or how
/// much it varies over a patch.
#[derive(Clone, Copy, Debug)]
pub enum TextureAt<'p> {
    /// The exact mean over the patch's UV polygon ([`crate::scene::Texture::polygon_stats`]).
    Patch(&'p Patch),
    /// The filtered value at this texture coordinate ([`crate::scene::Texture::color`]).
    Point(DVec2),
    /// The largest less the smallest texel under the patch's UV polygon: the term becomes
    /// how much it varies across the patch.
    Spread(&'p Patch),
}

impl TextureAt<'_> {
    /// The texture's colour here; without a texture `[1, 1, 1]` (`[0, 0, 0]` for a spread).
    fn colour(self, scene: &Scene, texture: Option<TextureId>) -> Rgb64 {
        let Some(texture) = texture.and_then(|t| scene.textures.get(t as usize)) else {
            return match self {
                TextureAt::Spread(_) => Rgb64::BLACK,
                _ => Rgb64::WHITE,
            };
        };
        let rgb = |c: [f64; 4]| Rgb64::new(c[0], c[1], c[2]);
        match self {
            TextureAt::Patch(patch) => rgb(texture.polygon_stats(patch.uvs()).mean),
            TextureAt::Point(uv) => texture.color(uv.as_vec2()).to_f64(),
            TextureAt::Spread(patch) => {
                let stats = texture.polygon_stats(patch.uvs());
                rgb(std::array::from_fn(|c| {
                    f64::from(stats.max[c] - stats.min[c])
                }))
            }
        }
    }
}

/// Emitted radiosity `E = π·L` (W·m⁻²) of side `side` of a patch of `scene` with material
/// `material`, the emission texture taken `at` the patch or a point: the front emits, the
/// back only for a `two_sided` material.
pub fn emission_of(scene: &Scene, material: MaterialId, side: Side, at: TextureAt) -> Rgb64 {
    let m = &scene.materials[material as usize];
    if m.emission.is_black() || !(side == Side::Front || m.two_sided) {
        return Rgb64::BLACK;
    }
    PI * m.emission.to_f64() * at.colour(scene, m.emission_texture)
}

/// Diffuse reflectance in `[0, 1]` of side `side` of a patch of `scene` with material
/// `material`, the diffuse texture taken `at` the patch or a point; 0 on the back of a
/// `one_sided` material. Specular, mirror and transmission parts are ignored.
pub fn reflectance_of(scene: &Scene, material: MaterialId, side: Side, at: TextureAt) -> Rgb64 {
    let m = &scene.materials[material as usize];
    if m.one_sided && side == Side::Back {
        return Rgb64::BLACK;
    }
    (m.diffuse.to_f64() * at.colour(scene, m.diffuse_texture)).map(|v| v.clamp(0.0, 1.0))
}

/// [`emission_of`] side `side` of `patch`, its texture averaged over the patch, W·m⁻².
pub fn emission(scene: &Scene, patch: &Patch, side: Side) -> Rgb64 {
    emission_of(scene, patch.material, side, TextureAt::Patch(patch))
}

/// [`reflectance_of`] side `side` of `patch`, its texture averaged over the patch.
pub fn reflectance(scene: &Scene, patch: &Patch, side: Side) -> Rgb64 {
    reflectance_of(scene, patch.material, side, TextureAt::Patch(patch))
}

/// Whether `material` of `scene` has a diffuse or emission texture (its surface terms vary
/// across a patch).
pub fn is_textured(scene: &Scene, material: MaterialId) -> bool {
    let m = &scene.materials[material as usize];
    m.diffuse_texture.is_some() || (m.emission_texture.is_some() && !m.emission.is_black())
}

/// The names of the materials of `scene`'s objects that reflect or pass light other than
/// diffusely (specular, mirror or transmission parts), in order of first use: radiosity
/// counts that light as absorbed.
pub fn non_diffuse_materials(scene: &Scene) -> Vec<&str> {
    let mut names: Vec<&str> = Vec::new();
    for object in &scene.objects {
        let m = &scene.materials[object.material as usize];
        let diffuse_only =
            m.specular.is_black() && m.mirror.is_black() && m.transmission.is_black();
        if !diffuse_only && !names.contains(&m.name.as_str()) {
            names.push(&m.name);
        }
    }
    names
}
