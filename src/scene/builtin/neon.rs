//! `neon`: a closed dark room lit only by a neon sign, to test emissive textures and light
//! that comes from an area light of complicated shape. There are no [`crate::scene::Light`]s
//! and no other emitters.
//!
//! - Room: x ∈ [−1.6, 1.6] m, y ∈ [0, 2.6] m, z ∈ [−2, 2] m; walls and ceiling reflect 0.5,
//!   the floor 0.45; every face points into the room.
//! - Sign: a 1.6 × 0.8 m quad 1 cm in front of the back wall (z = −1.99 m), centred 1.5 m
//!   above the floor, facing +z. Its emission texture is 128 × 64 texels (12.5 mm each),
//!   generated in code: the letters "GI" drawn as tubes 6 texels wide with a one-texel
//!   anti-aliased edge (texel value 1 on the tube, 0 elsewhere; about 15 % of the texels are
//!   lit). The texture multiplies the emitted radiance [`NEON_RADIANCE`] (hot pink). Between
//!   the letters the sign is a dark backing of reflectance 0.05.
//! - A box (0.6 × 0.7 × 0.6 m, turned 30° about y) and a glossy sphere (radius 0.4 m) stand
//!   on the floor in front of the sign to catch its light.
//! - Camera: from (0, 1.2, 1.8) m towards (0, 1.0, −2) m, 55° vertical field of view,
//!   640 × 480 pixels.

use crate::color::Rgb;
use crate::geometry::Transform;
use crate::scene::{Camera, Material, Object, Scene, Shape, Texture};
use glam::{Vec2, Vec3};

/// Emitted radiance of the lit neon tubes, W·sr⁻¹·m⁻² (multiplied by the texture).
pub const NEON_RADIANCE: Rgb = Rgb::new(40.0, 4.0, 24.0);

/// Emission texture width, texels.
const TEXTURE_WIDTH: u32 = 128;
/// Emission texture height, texels.
const TEXTURE_HEIGHT: u32 = 64;
/// Half the width of a neon tube, texels (fully lit within this distance of its centre line).
const TUBE_HALF_WIDTH: f32 = 2.5;

/// Room bounds, metres.
const ROOM_MIN: Vec3 = Vec3::new(-1.6, 0.0, -2.0);
/// Room bounds, metres.
const ROOM_MAX: Vec3 = Vec3::new(1.6, 2.6, 2.0);

/// Distance from `p` to the segment `a`–`b`.
fn segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
    p.distance(a + t * ab)
}

/// Distance from `p` to the circular arc around `center` of `radius` covering the angles
/// `from..to` (degrees, counter-clockwise from +x with y pointing up).
fn arc_distance(p: Vec2, center: Vec2, radius: f32, from: f32, to: f32) -> f32 {
    let d = p - center;
    let angle = d.y.atan2(d.x).to_degrees().rem_euclid(360.0);
    if (from..=to).contains(&angle) {
        (d.length() - radius).abs()
    } else {
        let end =
            |deg: f32| center + radius * Vec2::new(deg.to_radians().cos(), deg.to_radians().sin());
        p.distance(end(from)).min(p.distance(end(to)))
    }
}

/// Distance from `p` (texels, x right, y up from the bottom edge) to the centre line of the
/// letters "GI".
fn letters_distance(p: Vec2) -> f32 {
    // G: an open ring with its gap at the upper right, and a bar into the middle.
    let g_center = Vec2::new(44.0, 32.0);
    let g_arc = arc_distance(p, g_center, 20.0, 45.0, 360.0);
    let g_bar = segment_distance(p, Vec2::new(64.0, 32.0), Vec2::new(50.0, 32.0));
    // I: a stem with serifs.
    let i_stem = segment_distance(p, Vec2::new(92.0, 12.0), Vec2::new(92.0, 52.0));
    let i_top = segment_distance(p, Vec2::new(82.0, 52.0), Vec2::new(102.0, 52.0));
    let i_bottom = segment_distance(p, Vec2::new(82.0, 12.0), Vec2::new(102.0, 12.0));
    g_arc.min(g_bar).min(i_stem).min(i_top).min(i_bottom)
}

/// The 128 × 64 emission mask of the sign: 1 on the tubes, 0 elsewhere.
pub fn sign_texture() -> Texture {
    Texture::from_fn("neon_sign", TEXTURE_WIDTH, TEXTURE_HEIGHT, |x, y| {
        let p = Vec2::new(x as f32 + 0.5, (TEXTURE_HEIGHT - y) as f32 - 0.5);
        let v = (TUBE_HALF_WIDTH + 1.0 - letters_distance(p)).clamp(0.0, 1.0);
        [v, v, v, 1.0]
    })
}

/// The six inward-facing faces of the room as parallelograms, with their names.
fn room_faces() -> [(&'static str, Shape); 6] {
    let (lo, hi) = (ROOM_MIN, ROOM_MAX);
    let size = hi - lo;
    let (x, y, z) = (Vec3::X * size.x, Vec3::Y * size.y, Vec3::Z * size.z);
    let face = |origin: Vec3, edge_u: Vec3, edge_v: Vec3| Shape::Parallelogram {
        origin,
        edge_u,
        edge_v,
    };
    [
        ("floor", face(lo, z, x)),
        ("ceiling", face(Vec3::new(lo.x, hi.y, lo.z), x, z)),
        ("back_wall", face(lo, x, y)),
        ("front_wall", face(Vec3::new(lo.x, lo.y, hi.z), y, x)),
        ("left_wall", face(lo, y, z)),
        ("right_wall", face(Vec3::new(hi.x, lo.y, lo.z), z, y)),
    ]
}

/// The neon room (see the module documentation).
pub fn scene() -> Scene {
    let mut scene = Scene::empty("neon");
    scene.camera = Camera::landscape(Vec3::new(0.0, 1.2, 1.8), Vec3::new(0.0, 1.0, -2.0), 55.0);
    let wall = scene.add_material(Material::diffuse("wall", Rgb::splat(0.5)));
    let floor = scene.add_material(Material::diffuse("floor", Rgb::splat(0.45)));
    let box_material = scene.add_material(Material::diffuse("box", Rgb::splat(0.6)));
    let sphere_material = scene.add_material(Material {
        specular: Rgb::splat(0.35),
        shininess: 80.0,
        ..Material::diffuse("sphere", Rgb::splat(0.45))
    });
    let mask = scene.add_texture(sign_texture());
    let neon = scene.add_material(Material {
        emission_texture: Some(mask),
        ..Material::emitter("neon", Rgb::splat(0.05), NEON_RADIANCE)
    });

    for (name, shape) in room_faces() {
        let material = if name == "floor" { floor } else { wall };
        scene.add_object(name, shape, material);
    }
    scene.add_object(
        "sign",
        Shape::Parallelogram {
            origin: Vec3::new(-0.8, 1.1, ROOM_MIN.z + 0.01),
            edge_u: Vec3::new(1.6, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 0.8, 0.0),
        },
        neon,
    );
    let turn = Transform::rotate(Vec3::Y, 30.0).unwrap_or_default();
    scene.objects.push(Object {
        name: Some("box".to_string()),
        shape: Shape::Box {
            min: Vec3::new(-0.3, 0.0, -0.3),
            max: Vec3::new(0.3, 0.7, 0.3),
        },
        transform: turn.then(&Transform::translate(Vec3::new(-0.7, 0.0, -1.0))),
        material: box_material,
        per_face: false,
    });
    scene.add_object(
        "sphere",
        Shape::Sphere {
            center: Vec3::new(0.7, 0.4, -1.1),
            radius: 0.4,
        },
        sphere_material,
    );
    scene
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_sign_emits_and_its_texture_is_mostly_dark() {
        let s = scene();
        assert!(s.lights.is_empty());
        let emissive: Vec<&Material> = s.materials.iter().filter(|m| m.is_emissive()).collect();
        assert_eq!(emissive.len(), 1);
        let texture = &s.textures[emissive[0].emission_texture.unwrap() as usize];
        assert_eq!((texture.width, texture.height), (128, 64));
        let dark = texture.texels.iter().filter(|t| t[0] < 0.01).count();
        let dark_fraction = dark as f32 / texture.texels.len() as f32;
        assert!((0.75..0.95).contains(&dark_fraction), "{dark_fraction}");
        let lit = texture.texels.iter().filter(|t| t[0] > 0.99).count();
        assert!(lit > 600, "{lit} lit texels");
        let max = emissive[0].emission.max_channel();
        assert!((20.0..=50.0).contains(&max));
    }

    #[test]
    fn letters_are_where_they_are_drawn() {
        let t = sign_texture();
        // Row 32 from the top is the middle: G's left side at x ≈ 24, I's stem at x = 92.
        assert!(t.texel(23, 32)[0] > 0.99);
        assert!(t.texel(91, 32)[0] > 0.99);
        assert!(t.texel(44, 32)[0] < 0.01);
        assert!(t.texel(5, 5)[0] < 0.01);
        // The G's gap at the upper right (angle 22°, radius 20).
        assert!(t.texel(62, 24)[0] < 0.01);
    }

    #[test]
    fn room_faces_point_inwards_and_the_sign_faces_the_camera() {
        let s = scene();
        let centre = 0.5 * (ROOM_MIN + ROOM_MAX);
        for object in &s.objects {
            if let Shape::Parallelogram {
                origin,
                edge_u,
                edge_v,
            } = object.shape
            {
                let mid = origin + 0.5 * (edge_u + edge_v);
                let normal = edge_u.cross(edge_v);
                assert!(normal.dot(centre - mid) > 0.0, "{:?}", object.name);
                if object.name.as_deref() == Some("sign") {
                    assert!(normal.dot(s.camera.position - mid) > 0.0);
                }
            }
        }
        let cam = s.camera.position;
        assert!(cam.cmpgt(ROOM_MIN).all() && cam.cmplt(ROOM_MAX).all());
    }
}
