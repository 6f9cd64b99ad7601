//! What one side of a patch does with light: the radiosity it emits and the share it
//! reflects, from its material with textures averaged over the patch.

use super::element::Side;
use super::mesh::Patch;
use crate::color::Rgb64;
use crate::scene::{Scene, Texture};
use glam::Vec2;
use std::f64::consts::PI;

/// Texture samples per axis when averaging a texture over a patch.
const TEXTURE_SAMPLES: u32 = 4;

/// Emitted radiosity `E = π·L` (W·m⁻²) of side `side` of `patch`, the emission texture
/// averaged over the patch: the front emits, the back only for a `two_sided` material.
pub fn emission(scene: &Scene, patch: &Patch, side: Side) -> Rgb64 {
    let m = &scene.materials[patch.material as usize];
    if m.emission.is_black() || !(side == Side::Front || m.two_sided) {
        return Rgb64::BLACK;
    }
    PI * m.emission.to_f64() * texture_mean(texture(scene, m.emission_texture), patch)
}

/// Diffuse reflectance in `[0, 1]` of side `side` of `patch`, the diffuse texture averaged over
/// the patch; 0 on the back of a `one_sided` material. Specular, mirror and transmission
/// parts are ignored.
pub fn reflectance(scene: &Scene, patch: &Patch, side: Side) -> Rgb64 {
    let m = &scene.materials[patch.material as usize];
    if m.one_sided && side == Side::Back {
        return Rgb64::BLACK;
    }
    let tex = texture_mean(texture(scene, m.diffuse_texture), patch);
    (m.diffuse.to_f64() * tex).map(|v| v.clamp(0.0, 1.0))
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

fn texture(scene: &Scene, id: Option<u32>) -> Option<&Texture> {
    id.and_then(|t| scene.textures.get(t as usize))
}

/// Mean colour of `texture` over `patch` (its UV polygon sampled on a `4 × 4` grid of the
/// patch's parameter domain, equal weights: area-weighted for triangles and parallelograms);
/// `[1, 1, 1]` without a texture.
fn texture_mean(texture: Option<&Texture>, patch: &Patch) -> Rgb64 {
    let Some(texture) = texture else {
        return Rgb64::WHITE;
    };
    let n = TEXTURE_SAMPLES;
    let mut sum = Rgb64::BLACK;
    for a in 0..n {
        for b in 0..n {
            let (s, t) = ((a as f64 + 0.5) / n as f64, (b as f64 + 0.5) / n as f64);
            let uv = patch.uv_at(s, t);
            sum += texture.color(Vec2::new(uv.x as f32, uv.y as f32)).to_f64();
        }
    }
    sum.map(|v| v / (n * n) as f64)
}
