//! Scenes more than one test file builds.

use glam::Vec3;
use strahl::color::Rgb;
use strahl::scene::{Light, LightKind, Material, Periodic, Scene, Shape};

/// A plot of 2 × 2 m with a black ground and a black horizontal 1 × 1 m leaf at height 1
/// centred on the plot's corner (a quarter of it in the plot, three quarters beyond its
/// sides), under a vertical sun of 10 W·m⁻².
pub fn corner_leaf() -> Scene {
    let mut scene = Scene::empty("corner");
    let black = scene.add_material(Material::diffuse("black", Rgb::BLACK));
    let square = |origin: Vec3, side: f32| Shape::Parallelogram {
        origin,
        edge_u: Vec3::Z * side,
        edge_v: Vec3::X * side,
    };
    scene.add_object("leaf", square(Vec3::new(-0.5, 1.0, -0.5), 1.0), black);
    scene.add_object("ground", square(Vec3::ZERO, 2.0), black);
    scene.periodic = Some(Periodic::new([0.0, 2.0], [0.0, 2.0]).unwrap());
    scene.lights.push(Light {
        name: Some("sun".into()),
        kind: LightKind::Directional {
            direction: -Vec3::Y,
            irradiance: Rgb::splat(10.0),
        },
    });
    scene
}
