//! Emitter-only links (seed 000 §9.3.1): the irradiance that point, spot and directional
//! lights send to a patch. These lights only send; nothing is sent back to them.
//!
//! The irradiance (W·m⁻²) on the patch's front side is averaged over the area-weighted
//! receiver points of [`super::form_factor::receiver_points`], each with a shadow ray.

use super::form_factor::receiver_points;
use super::mesh::Patch;
use super::visibility::occluded_except;
use crate::color::Rgb;
use crate::geometry::{Ray, offset_origin};
use crate::scene::LightKind;
use crate::world::World;
use glam::DVec3;

/// Irradiance in W·m⁻² that `light` sends to the front side of `patch`, averaged over
/// `samples × samples` receiver points (the centroid for `samples ≤ 1`), with shadows from
/// every surface of `world`. Point lights give `I·cosθ/d²`, spot lights the same times their
/// falloff, directional lights `E·cosθ` when the way to infinity is free. `None` for a sky
/// light, which is not a link to a single emitter.
pub fn light_irradiance(
    world: &World,
    light: &LightKind,
    patch: &Patch,
    samples: u32,
) -> Option<Rgb> {
    if matches!(light, LightKind::Sky { .. }) {
        return None;
    }
    let mut total = Rgb::BLACK;
    for (x, weight) in receiver_points(patch, samples) {
        let e = point_irradiance(world, light, x, patch.normal);
        total += e * weight as f32;
    }
    Some(total)
}

/// Irradiance at surface point `x` with unit front normal `n` from a point, spot or
/// directional light (black for a sky light, behind the surface, or when blocked).
fn point_irradiance(world: &World, light: &LightKind, x: DVec3, n: DVec3) -> Rgb {
    let Some(inc) = light.incidence(x.as_vec3()) else {
        return Rgb::BLACK;
    };
    let cos = n.as_vec3().dot(inc.wi);
    if cos <= 0.0 {
        return Rgb::BLACK;
    }
    let origin = offset_origin(x.as_vec3(), n.as_vec3(), inc.wi);
    let t_max = if inc.distance.is_finite() {
        (x.as_vec3() + inc.wi * inc.distance - origin).length()
    } else {
        f32::INFINITY
    };
    if occluded_except(world, Ray::new(origin, inc.wi), t_max, &[]) {
        Rgb::BLACK
    } else {
        inc.irradiance * cos
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::AccelKind;
    use crate::radiosity::mesh::{MeshOptions, PatchMesh};
    use crate::scene::{Material, Scene, Shape};
    use glam::Vec3;

    fn floor_world(with_roof: bool) -> (World, PatchMesh) {
        let mut scene = Scene::empty("floor");
        let m = scene.add_material(Material::default());
        scene.add_object(
            "floor",
            Shape::Parallelogram {
                origin: Vec3::ZERO,
                edge_u: Vec3::Z,
                edge_v: Vec3::X,
            },
            m,
        );
        if with_roof {
            scene.add_object(
                "roof",
                Shape::Parallelogram {
                    origin: Vec3::new(-5.0, 1.0, -5.0),
                    edge_u: Vec3::X * 10.0,
                    edge_v: Vec3::Z * 10.0,
                },
                m,
            );
        }
        let mesh = PatchMesh::from_scene(&scene, &MeshOptions::default()).unwrap();
        (World::new(scene, AccelKind::Bvh).unwrap(), mesh)
    }

    #[test]
    fn point_light_gives_intensity_cos_over_distance_squared() {
        let (world, mesh) = floor_world(false);
        let floor = mesh.patch(0);
        assert!(floor.normal.y > 0.99);
        // Light 2 above and 2 to the side of the centroid (0.5, 0, 0.5): cosθ = 1/√2, d² = 8.
        let light = LightKind::Point {
            position: Vec3::new(2.5, 2.0, 0.5),
            intensity: Rgb::splat(8.0),
        };
        let e = light_irradiance(&world, &light, floor, 1).unwrap();
        assert!(
            (e.r - 8.0 * std::f32::consts::FRAC_1_SQRT_2 / 8.0).abs() < 1e-5,
            "{e:?}"
        );
        let below = LightKind::Point {
            position: Vec3::new(0.5, -1.0, 0.5),
            intensity: Rgb::splat(8.0),
        };
        assert_eq!(light_irradiance(&world, &below, floor, 2), Some(Rgb::BLACK));
    }

    #[test]
    fn directional_light_is_shadowed_by_a_roof() {
        let sun = LightKind::Directional {
            direction: Vec3::new(0.0, -1.0, -1.0).normalize(),
            irradiance: Rgb::splat(2.0),
        };
        let (open, mesh) = floor_world(false);
        let e = light_irradiance(&open, &sun, mesh.patch(0), 2).unwrap();
        assert!((e.g - 2.0 * std::f32::consts::FRAC_1_SQRT_2).abs() < 1e-5);
        let (roofed, mesh) = floor_world(true);
        assert_eq!(
            light_irradiance(&roofed, &sun, mesh.patch(0), 2),
            Some(Rgb::BLACK)
        );
    }

    #[test]
    fn spot_light_outside_its_cone_sends_nothing() {
        let (world, mesh) = floor_world(false);
        let spot = |direction: Vec3| LightKind::Spot {
            position: Vec3::new(0.5, 1.0, 0.5),
            direction,
            intensity: Rgb::splat(1.0),
            inner_degrees: 10.0,
            outer_degrees: 20.0,
        };
        let down = light_irradiance(&world, &spot(-Vec3::Y), mesh.patch(0), 1).unwrap();
        assert!((down.b - 1.0).abs() < 1e-6);
        let sideways = light_irradiance(&world, &spot(Vec3::X), mesh.patch(0), 1).unwrap();
        assert_eq!(sideways, Rgb::BLACK);
    }
}
