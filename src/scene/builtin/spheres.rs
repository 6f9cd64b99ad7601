//! `spheres` / `spheres:N`: the octree test scene, N spheres of radius 0.3 scattered at
//! pseudo-random positions through a cube that the camera sees whole, lit by five point
//! lights inside the cube. No ground plane and no walls: the background is black.
//!
//! - The cube is centred on the origin with side `2·N^(1/3)` (at least 4), so the mean
//!   spacing between sphere centres stays near 2 whatever N is (about 1.4 % of the volume is
//!   filled).
//! - Sphere centres are uniform in the cube shrunk by the radius, drawn from
//!   `Pcg32::seed_from_u64(7)`, so every load gives the same scene; positions closer than
//!   0.1 to the surface of a sphere around a light are drawn again, so no light is hidden
//!   inside a sphere.
//! - The camera looks down −z at the cube's centre with a 60° field of view from
//!   `h·(1 + √3)` away (`h` half the side): the nearest face of the cube just fills the view,
//!   so every sphere centre is inside the view volume. 512 × 512 pixels.
//! - Five point lights: one at the centre and four at `(±h/2, ±h/2, ±h/2)` in a tetrahedral
//!   pattern, each of intensity `0.4·h²` W·sr⁻¹ (slightly tinted), so a surface at distance
//!   `h` receives about 0.4 W·m⁻² from each whatever the cube's size.
//! - Four materials, used in turn: red and blue Lambertian, green and white Phong.

use crate::color::Rgb;
use crate::scene::{Camera, Light, LightKind, Material, Scene, Shape};
use glam::Vec3;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg32;

/// Number of spheres when no count is given.
pub const DEFAULT_COUNT: u32 = 100;

/// Largest accepted number of spheres.
pub const MAX_COUNT: u32 = 10_000_000;

/// Radius of every sphere, scene units.
pub const SPHERE_RADIUS: f32 = 0.3;

/// Seed of the position generator.
const SEED: u64 = 7;

/// Vertical field of view, degrees.
const FOV_DEGREES: f32 = 60.0;

/// Light intensity per unit of squared half-side, W·sr⁻¹ per (scene unit)².
const INTENSITY_PER_HALF_SIDE_SQUARED: f32 = 0.4;

/// Clearance kept between a light and the surface of any sphere, scene units.
const LIGHT_CLEARANCE: f32 = 0.1;

/// Parses the parameter of `spheres:N`: `None` gives [`DEFAULT_COUNT`].
pub fn parse_count(parameter: Option<&str>) -> Result<u32, String> {
    let Some(text) = parameter else {
        return Ok(DEFAULT_COUNT);
    };
    let count: u64 = text.trim().parse().map_err(|_| {
        format!(
            "built-in scene 'spheres:{text}': '{text}' is not a whole number of spheres \
             (use spheres:N with 1 ≤ N ≤ {MAX_COUNT})"
        )
    })?;
    if count == 0 || count > MAX_COUNT as u64 {
        return Err(format!(
            "built-in scene 'spheres:{text}': the number of spheres must be between 1 and \
             {MAX_COUNT}"
        ));
    }
    Ok(count as u32)
}

/// Half the side of the cube holding `count` spheres.
fn half_side(count: u32) -> f32 {
    (count as f32).cbrt().max(2.0)
}

/// The five light positions for a cube of half-side `h`.
fn light_positions(h: f32) -> [Vec3; 5] {
    let q = 0.5 * h;
    [
        Vec3::ZERO,
        Vec3::new(q, q, q),
        Vec3::new(-q, -q, q),
        Vec3::new(-q, q, -q),
        Vec3::new(q, -q, -q),
    ]
}

/// The scene with `count` spheres (1 ≤ `count` ≤ [`MAX_COUNT`], see [`parse_count`]).
pub fn scene(count: u32) -> Scene {
    let h = half_side(count);
    let mut scene = Scene::empty(&format!("spheres:{count}"));
    scene.camera = Camera {
        position: Vec3::new(0.0, 0.0, h * (1.0 + 3f32.sqrt())),
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        fov_degrees: FOV_DEGREES,
        width: 512,
        height: 512,
    };
    let materials = [
        scene.add_material(Material::diffuse("red", Rgb::new(0.75, 0.15, 0.12))),
        scene.add_material(Material {
            specular: Rgb::splat(0.3),
            shininess: 40.0,
            ..Material::diffuse("green_glossy", Rgb::new(0.15, 0.55, 0.2))
        }),
        scene.add_material(Material::diffuse("blue", Rgb::new(0.12, 0.2, 0.7))),
        scene.add_material(Material {
            specular: Rgb::splat(0.4),
            shininess: 120.0,
            ..Material::diffuse("white_glossy", Rgb::splat(0.55))
        }),
    ];

    let lights = light_positions(h);
    let tints = [
        Rgb::new(1.0, 1.0, 1.0),
        Rgb::new(1.0, 0.9, 0.8),
        Rgb::new(0.8, 0.9, 1.0),
        Rgb::new(1.0, 1.0, 0.85),
        Rgb::new(0.9, 1.0, 0.9),
    ];
    let intensity = INTENSITY_PER_HALF_SIDE_SQUARED * h * h;
    for (i, (&position, &tint)) in lights.iter().zip(&tints).enumerate() {
        scene.lights.push(Light {
            name: Some(format!("lamp-{i}")),
            kind: LightKind::Point {
                position,
                intensity: tint * intensity,
            },
        });
    }

    let mut rng = Pcg32::seed_from_u64(SEED);
    let extent = h - SPHERE_RADIUS;
    let keep_out = SPHERE_RADIUS + LIGHT_CLEARANCE;
    scene.objects.reserve(count as usize);
    for i in 0..count {
        let center = loop {
            let p = Vec3::new(
                rng.random_range(-extent..extent),
                rng.random_range(-extent..extent),
                rng.random_range(-extent..extent),
            );
            if lights.iter().all(|l| l.distance(p) > keep_out) {
                break p;
            }
        };
        scene.add_object(
            &format!("sphere-{i}"),
            Shape::Sphere {
                center,
                radius: SPHERE_RADIUS,
            },
            materials[i as usize % materials.len()],
        );
    }
    scene
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thousand_spheres_five_lights_deterministic() {
        let a = scene(1000);
        assert_eq!(a.objects.len(), 1000);
        assert_eq!(a.lights.len(), 5);
        assert!(
            a.objects
                .iter()
                .all(|o| matches!(o.shape, Shape::Sphere { radius, .. } if radius == 0.3))
        );
        assert_eq!(a, scene(1000));
    }

    #[test]
    fn spheres_and_lights_are_inside_the_view_and_clear_of_each_other() {
        let s = scene(1000);
        let rays = s.camera.rays().unwrap();
        let half_fov = (s.camera.fov_degrees / 2.0).to_radians().tan();
        let forward = (s.camera.look_at - s.camera.position).normalize();
        assert!((rays.ray(256.0, 256.0).dir - forward).length() < 1e-6);
        let lights: Vec<Vec3> = s
            .lights
            .iter()
            .map(|l| match l.kind {
                LightKind::Point { position, .. } => position,
                _ => panic!("not a point light"),
            })
            .collect();
        let in_view = |p: Vec3| {
            let d = p - s.camera.position;
            let depth = d.dot(forward);
            depth > 0.0 && d.x.abs() <= half_fov * depth && d.y.abs() <= half_fov * depth
        };
        for object in &s.objects {
            let Shape::Sphere { center, .. } = object.shape else {
                panic!("not a sphere");
            };
            assert!(in_view(center), "{center}");
            for l in &lights {
                assert!(l.distance(center) > 0.4 - 1e-5);
            }
        }
        assert!(lights.iter().all(|&l| in_view(l)));
    }

    #[test]
    fn region_grows_with_count() {
        // Half-side N^(1/3): 10 for N = 1000, and at least 2.
        assert!((half_side(1000) - 10.0).abs() < 1e-4);
        assert_eq!(half_side(1), 2.0);
        let far = scene(1000).camera.position.z;
        assert!((far - 10.0 * (1.0 + 3f32.sqrt())).abs() < 1e-3);
    }

    #[test]
    fn counts_are_parsed_and_bad_ones_rejected() {
        assert_eq!(parse_count(None), Ok(100));
        assert_eq!(parse_count(Some("1000")), Ok(1000));
        assert_eq!(parse_count(Some("10000000")), Ok(10_000_000));
        assert!(
            parse_count(Some("abc"))
                .unwrap_err()
                .contains("not a whole number")
        );
        assert!(
            parse_count(Some("0"))
                .unwrap_err()
                .contains("between 1 and")
        );
        assert!(parse_count(Some("10000001")).is_err());
        assert!(parse_count(Some("-5")).is_err());
        assert!(parse_count(Some("")).is_err());
    }
}
