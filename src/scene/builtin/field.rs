//! `field` / `field:N`: a homogeneous canopy standing for a whole field — N square leaves
//! 5 × 5 cm (default 160,000) with leaf area index 1, on a periodic plot (repeated without end
//! in x and z) whose side is √N·5 cm (20 m by default), under a sun and a uniform sky. Helios'
//! homogeneous-canopy radiation benchmark rebuilt (its 20 × 20 m, LAI 1, 5 cm leaves, 3 m
//! height, laterally periodic), and the canopy of Beer's law: leaf centres uniformly random
//! over the plot (`Pcg32::seed_from_u64(3)`) at heights from 4 cm to 3 m, leaf normals
//! uniform over the sphere (a spherical Fibonacci set, so that the leaves' projected area in
//! every direction is half their area to within 1/N: leaf angle distribution *spherical*,
//! G = ½), each leaf turned about its normal at random.
//!
//! Leaves reflect 10 % and pass 5 % through diffusely (grey: read every channel as PAR),
//! each its own object `leaf-<k>`; the ground, a quad covering the plot, reflects 15 %. The
//! sun (800 W·m⁻² on a surface facing it) stands 30° from the zenith in the south; the sky is
//! the CIE sky of uniform luminance (type 5) sending 200 W·m⁻² onto the ground.

use crate::color::Rgb;
use crate::scene::{Camera, CieSkyType, Light, LightKind, Material, Periodic, Scene, Shape};
use glam::Vec3;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg32;
use std::f32::consts::PI;

/// Number of leaves without a parameter (Helios' benchmark: 20 × 20 m at LAI 1).
pub const DEFAULT_LEAVES: usize = 160_000;
/// Largest number of leaves accepted.
pub const MAX_LEAVES: usize = 4_000_000;

/// Parses the `N` of `field:N` (default [`DEFAULT_LEAVES`]).
pub fn parse_count(parameter: Option<&str>) -> Result<usize, String> {
    super::parse_count("field", "leaf", parameter, DEFAULT_LEAVES, MAX_LEAVES)
}

/// What a homogeneous canopy is made of.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldSpec {
    /// Number of leaves (≥ 1).
    pub leaves: usize,
    /// Leaf area index: one-sided leaf area per unit ground area (> 0).
    pub lai: f32,
    /// Side of a square leaf, metres.
    pub leaf_side: f32,
    /// Height of the highest leaf centres, metres; the lowest are one leaf diagonal up.
    pub height: f32,
    /// Seed of the leaves' positions and turns.
    pub seed: u64,
}

impl Default for FieldSpec {
    /// Helios' benchmark: 160,000 leaves of 5 cm, LAI 1, 3 m high, seed 3.
    fn default() -> Self {
        FieldSpec {
            leaves: DEFAULT_LEAVES,
            lai: 1.0,
            leaf_side: 0.05,
            height: 3.0,
            seed: 3,
        }
    }
}

impl FieldSpec {
    /// The side of the square plot, metres: `leaf_side · √(leaves / lai)`.
    pub fn plot_side(&self) -> f32 {
        self.leaf_side * (self.leaves as f32 / self.lai).sqrt()
    }
}

/// The default field with `leaves` leaves (`field:N`).
pub fn scene(leaves: usize) -> Scene {
    field(&FieldSpec {
        leaves,
        ..FieldSpec::default()
    })
}

/// The field `spec` describes, lit and framed as the module says.
pub fn field(spec: &FieldSpec) -> Scene {
    let mut scene = Scene::empty("field");
    let leaf = scene.add_material(Material {
        translucency: Rgb::splat(0.05),
        ..Material::diffuse("leaf", Rgb::splat(0.1))
    });
    let soil = scene.add_material(Material::diffuse("soil", Rgb::splat(0.15)));
    let side = spec.plot_side();
    let mut rng = Pcg32::seed_from_u64(spec.seed);
    let half = 0.5 * spec.leaf_side;
    let lowest = spec.leaf_side * std::f32::consts::SQRT_2;
    let golden = (5.0f64.sqrt() - 1.0) / 2.0;
    for k in 0..spec.leaves {
        // The k-th point of the spherical Fibonacci set: equal-area bands in cos θ.
        let cos = 1.0 - (2.0 * k as f64 + 1.0) / spec.leaves as f64;
        let phi = 2.0 * std::f64::consts::PI * (k as f64 * golden).fract();
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let normal = Vec3::new(
            (sin * phi.cos()) as f32,
            cos as f32,
            (sin * phi.sin()) as f32,
        );
        let (a, b) = normal.any_orthonormal_pair();
        let turn = rng.random_range(0.0..2.0 * PI);
        let (s, c) = turn.sin_cos();
        let (u, v) = (a * c + b * s, b * c - a * s);
        let centre = Vec3::new(
            rng.random_range(0.0..side),
            rng.random_range(lowest..spec.height.max(lowest)),
            rng.random_range(0.0..side),
        );
        scene.add_object(
            &format!("leaf-{k}"),
            Shape::Parallelogram {
                origin: centre - (u + v) * half,
                edge_u: u * spec.leaf_side,
                edge_v: v * spec.leaf_side,
            },
            leaf,
        );
    }
    scene.add_object(
        "ground",
        Shape::Parallelogram {
            origin: Vec3::new(0.0, 0.0, side),
            edge_u: Vec3::X * side,
            edge_v: Vec3::NEG_Z * side,
        },
        soil,
    );
    scene.periodic = Some(Periodic {
        x: [0.0, side],
        z: [0.0, side],
    });
    let zenith = 30f32.to_radians();
    let toward_sun = Vec3::new(0.0, zenith.cos(), zenith.sin());
    scene.lights.push(Light {
        name: Some("sun".into()),
        kind: LightKind::Directional {
            direction: -toward_sun,
            irradiance: Rgb::splat(800.0),
        },
    });
    scene.lights.push(Light {
        name: Some("sky".into()),
        kind: LightKind::CieSky {
            sky: CieSkyType::Uniform,
            sun: toward_sun,
            diffuse_horizontal: Rgb::splat(200.0),
        },
    });
    let centre = Vec3::new(0.5 * side, 0.5 * spec.height, 0.5 * side);
    scene.camera = Camera::landscape(
        centre + Vec3::new(-0.45 * side, 2.0 * spec.height, -0.45 * side),
        centre,
        50.0,
    );
    scene
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn leaf_area_index_plot_and_leaf_angles() {
        let spec = FieldSpec {
            leaves: 2000,
            lai: 2.0,
            ..FieldSpec::default()
        };
        let s = field(&spec);
        assert_eq!(s.objects.len(), 2001);
        let plot = s.periodic.expect("periodic");
        let leaf_area: f32 = s.objects[..2000]
            .iter()
            .map(|o| match o.shape {
                Shape::Parallelogram { edge_u, edge_v, .. } => edge_u.cross(edge_v).length(),
                _ => 0.0,
            })
            .sum();
        assert!(
            (leaf_area / plot.area() - 2.0).abs() < 1e-4,
            "{}",
            leaf_area / plot.area()
        );
        // Spherical leaf angles: the mean |n·d| is ½ in every direction d.
        for d in [Vec3::Y, Vec3::X, Vec3::new(0.3, 0.8, -0.5).normalize()] {
            let mean: f32 = s.objects[..2000]
                .iter()
                .map(|o| match o.shape {
                    Shape::Parallelogram { edge_u, edge_v, .. } => {
                        edge_u.cross(edge_v).normalize().dot(d).abs()
                    }
                    _ => 0.0,
                })
                .sum::<f32>()
                / 2000.0;
            assert!((mean - 0.5).abs() < 2e-3, "{d}: {mean}");
        }
        assert_eq!(parse_count(None), Ok(DEFAULT_LEAVES));
        assert!(parse_count(Some("0")).is_err());
    }
}
