//! `canopy` / `canopy:N`: a plant-modelling test scene of N small leaves (default 10,000) on a
//! square grid 10 cm apart, at heights from 0 to 45 cm and tilted in three ways, under a
//! uniform sky (radiance 0.2 W·sr⁻¹·m⁻²) and a sun (500 W·m⁻² from slightly south-east).
//! Every leaf is its own named object (`leaf-<row>-<column>`), 6 × 6 cm, reflecting
//! (0.1, 0.4, 0.1) diffusely and passing 10 % through diffusely (translucent, as real
//! leaves are) — the light model and radiosity report what each leaf absorbs.

use crate::color::Rgb;
use crate::scene::{Camera, Light, LightKind, Material, Scene, Shape};
use glam::Vec3;

/// Number of leaves without a parameter.
pub const DEFAULT_LEAVES: usize = 10_000;
/// Largest number of leaves accepted.
pub const MAX_LEAVES: usize = 4_000_000;

/// Parses the `N` of `canopy:N` (default [`DEFAULT_LEAVES`]).
pub fn parse_count(parameter: Option<&str>) -> Result<usize, String> {
    super::parse_count("canopy", "leaf", parameter, DEFAULT_LEAVES, MAX_LEAVES)
}

/// The canopy with `leaves` leaves: rows of ⌈√leaves⌉ leaves, as many rows as needed.
pub fn scene(leaves: usize) -> Scene {
    let mut scene = Scene::empty("canopy");
    let leaf = scene.add_material(Material {
        translucency: Rgb::splat(0.1),
        ..Material::diffuse("leaf", Rgb::new(0.1, 0.4, 0.1))
    });
    let side = (leaves as f64).sqrt().ceil() as usize;
    for k in 0..leaves {
        let (i, j) = (k / side, k % side);
        let origin = Vec3::new(
            i as f32 * 0.1,
            ((i * 7 + j * 13) % 10) as f32 * 0.05,
            j as f32 * 0.1,
        );
        let tilt = Vec3::new(0.02 * ((i + j) % 3) as f32, 0.03, 0.0);
        scene.add_object(
            &format!("leaf-{i}-{j}"),
            Shape::Parallelogram {
                origin,
                edge_u: Vec3::X * 0.06 + tilt,
                edge_v: Vec3::NEG_Z * 0.06,
            },
            leaf,
        );
    }
    scene.lights.push(Light {
        name: Some("sky".into()),
        kind: LightKind::Sky {
            radiance: Rgb::splat(0.2),
        },
    });
    scene.lights.push(Light {
        name: Some("sun".into()),
        kind: LightKind::Directional {
            direction: Vec3::new(0.3, -1.0, 0.2).normalize(),
            irradiance: Rgb::splat(500.0),
        },
    });
    let extent = side as f32 * 0.1;
    let centre = Vec3::new(extent / 2.0, 0.2, extent / 2.0);
    scene.camera = Camera::landscape(
        centre + Vec3::new(-0.6 * extent, 0.5 * extent, -0.6 * extent),
        centre,
        45.0,
    );
    scene
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn leaf_count_names_and_errors() {
        let s = scene(10);
        assert_eq!(s.objects.len(), 10);
        assert_eq!(s.objects[4].name.as_deref(), Some("leaf-1-0"));
        assert_eq!(parse_count(None), Ok(DEFAULT_LEAVES));
        assert_eq!(parse_count(Some("250")), Ok(250));
        assert!(parse_count(Some("0")).is_err() && parse_count(Some("x")).is_err());
    }
}
