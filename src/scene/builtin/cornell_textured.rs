//! `cornell-textured`: the measured Cornell box ([`super::cornell`]) with a checkerboard
//! floor and a striped back wall, for testing textured reflectance.
//!
//! Both textures are 64 × 64 texels generated in code, with linear texel values that are the
//! diffuse reflectance (no sRGB decoding), identical to the 8-bit images of the project's
//! textured Cornell box data (value/255):
//!
//! - floor, material `floor_checker`: 8 × 8 squares of 8 texels, 204/255 = 0.8 and
//!   51/255 = 0.2, texel (0, 0) = 0.8; texture coordinates u = x/0.556 m, v = z/0.5592 m;
//! - back wall, material `backwall_stripes`: 4 vertical stripes of 16 texels alternating
//!   grey 191/255 = 0.749 and blue (26, 26, 153)/255 = (0.102, 0.102, 0.6), starting grey at
//!   texel column 0; texture coordinates u = x/0.556 m, v = y/0.5488 m.
//!
//! The walls are slightly narrower than 0.556 m at some edges, so u ends at 0.988–0.994
//! there (as in the source data).

use super::cornell;
use crate::color::Rgb;
use crate::scene::{Material, Scene, Shape, Texture};
use glam::Vec2;

/// Texture size in texels (square).
const SIZE: u32 = 64;

/// Reflectance of the light checker squares.
const CHECKER_LIGHT: f32 = 204.0 / 255.0;
/// Reflectance of the dark checker squares.
const CHECKER_DARK: f32 = 51.0 / 255.0;
/// Side of a checker square, texels.
const CHECKER_SQUARE: u32 = 8;

/// Grey stripe reflectance.
const STRIPE_GREY: [f32; 3] = [191.0 / 255.0, 191.0 / 255.0, 191.0 / 255.0];
/// Blue stripe reflectance.
const STRIPE_BLUE: [f32; 3] = [26.0 / 255.0, 26.0 / 255.0, 153.0 / 255.0];
/// Width of a stripe, texels.
const STRIPE_WIDTH: u32 = 16;

/// Room width used for u (metres).
const U_SPAN: f32 = 0.556;
/// Room depth used for the floor's v (metres).
const FLOOR_V_SPAN: f32 = 0.5592;
/// Room height used for the back wall's v (metres).
const WALL_V_SPAN: f32 = 0.5488;

/// The 64 × 64 checkerboard floor texture.
pub fn checker_texture() -> Texture {
    Texture::from_fn("floor_checker", SIZE, SIZE, |x, y| {
        let v = if (x / CHECKER_SQUARE + y / CHECKER_SQUARE).is_multiple_of(2) {
            CHECKER_LIGHT
        } else {
            CHECKER_DARK
        };
        [v, v, v, 1.0]
    })
}

/// The 64 × 64 vertical-stripe back wall texture.
pub fn stripe_texture() -> Texture {
    Texture::from_fn("backwall_stripes", SIZE, SIZE, |x, _| {
        let [r, g, b] = if (x / STRIPE_WIDTH).is_multiple_of(2) {
            STRIPE_GREY
        } else {
            STRIPE_BLUE
        };
        [r, g, b, 1.0]
    })
}

/// Gives the polygon object `name` texture coordinates `uv(vertex)` and material `material`.
fn texture_object(
    scene: &mut Scene,
    name: &str,
    material: u32,
    uv: impl Fn(glam::Vec3) -> Vec2,
) -> Result<(), String> {
    let object = scene
        .objects
        .iter_mut()
        .find(|o| o.name.as_deref() == Some(name))
        .ok_or_else(|| format!("the Cornell box has no object '{name}'"))?;
    let Shape::Polygon { vertices, uvs } = &mut object.shape else {
        return Err(format!("the Cornell box object '{name}' is not a polygon"));
    };
    *uvs = Some(vertices.iter().map(|&p| uv(p)).collect());
    object.material = material;
    Ok(())
}

/// The textured Cornell box (see the module documentation).
pub fn scene() -> Result<Scene, String> {
    let mut scene = cornell::scene()?;
    scene.name = "cornell-textured".to_string();
    let checker = scene.add_texture(checker_texture());
    let stripes = scene.add_texture(stripe_texture());
    let floor = scene.add_material(Material {
        diffuse_texture: Some(checker),
        ..Material::diffuse("floor_checker", Rgb::WHITE)
    });
    let back = scene.add_material(Material {
        diffuse_texture: Some(stripes),
        ..Material::diffuse("backwall_stripes", Rgb::WHITE)
    });
    texture_object(&mut scene, "floor", floor, |p| {
        Vec2::new(p.x / U_SPAN, p.z / FLOOR_V_SPAN)
    })?;
    texture_object(&mut scene, "back_wall", back, |p| {
        Vec2::new(p.x / U_SPAN, p.y / WALL_V_SPAN)
    })?;
    Ok(scene)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checker_has_eight_texel_squares_starting_light() {
        let t = checker_texture();
        assert_eq!((t.width, t.height), (64, 64));
        assert!((t.texel(0, 0)[0] - 0.8).abs() < 1e-6);
        assert!((t.texel(7, 7)[0] - 0.8).abs() < 1e-6);
        assert!((t.texel(8, 0)[0] - 0.2).abs() < 1e-6);
        assert!((t.texel(8, 8)[0] - 0.8).abs() < 1e-6);
        assert!((t.mean_color().r - 0.5).abs() < 1e-6);
    }

    #[test]
    fn stripes_alternate_grey_and_blue_every_sixteen_texels() {
        let t = stripe_texture();
        assert!((t.texel(0, 0)[1] - 0.749).abs() < 1e-3);
        assert!((t.texel(15, 63)[2] - 0.749).abs() < 1e-3);
        let blue = t.texel(16, 0);
        assert!((blue[0] - 0.102).abs() < 1e-3 && (blue[2] - 0.6).abs() < 1e-6);
        let mean = t.mean_color();
        assert!((mean.r - 0.4255).abs() < 1e-3 && (mean.b - 0.6745).abs() < 1e-3);
    }

    #[test]
    fn floor_and_back_wall_use_the_textures_with_documented_uvs() {
        let scene = scene().unwrap();
        for (name, material, expected) in [
            (
                "floor",
                "floor_checker",
                [0.994245, 0.0, 0.0, 0.0, 0.0, 1.0, 0.988489, 1.0],
            ),
            (
                "back_wall",
                "backwall_stripes",
                [0.988489, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            ),
        ] {
            let object = scene
                .objects
                .iter()
                .find(|o| o.name.as_deref() == Some(name))
                .unwrap();
            let m = &scene.materials[object.material as usize];
            assert_eq!(m.name, material);
            assert!(m.diffuse_texture.is_some());
            let Shape::Polygon { uvs: Some(uvs), .. } = &object.shape else {
                panic!("{name} has no texture coordinates");
            };
            let flat: Vec<f32> = uvs.iter().flat_map(|uv| [uv.x, uv.y]).collect();
            for (g, e) in flat.iter().zip(expected) {
                assert!((g - e).abs() < 1e-5, "{name}: {flat:?}");
            }
        }
    }
}
