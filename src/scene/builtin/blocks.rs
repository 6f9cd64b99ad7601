//! `blocks` / `blocks:N`: a many-surface radiosity test scene, N small diffuse cubes (default
//! 1,000) hanging in a closed white room lit by a square ceiling lamp — light bounces many
//! times between thousands of small faces, the case clustering is for.
//!
//! - The room is a box 4 m wide (x), 3 m high (y) and 4 m deep (z), one object (`room`) of
//!   reflectance 0.7; the lamp (`lamp`) is a 1 m square 1 cm under the ceiling's centre,
//!   facing down, of radiance 10 W·sr⁻¹·m⁻² (31.4 W) and reflectance 0.8 on its back.
//! - The cubes (`block-<k>`), 12 cm on a side and axis-aligned, sit at the centres of the
//!   cells of a regular grid filling x, z ∈ [0.4, 3.6] m and y ∈ [0.3, 2.3] m (as many cells
//!   per axis as it takes to hold N), each moved within its cell by a fixed pseudo-random
//!   offset (`Pcg32::seed_from_u64(11)`); their reflectances take turns among a white, a
//!   red, a green and a blue diffuse material.
//! - The camera stands in a corner at eye height, looking across the room.

use crate::color::Rgb;
use crate::scene::{Camera, Material, Scene, Shape};
use glam::Vec3;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg32;

/// Number of cubes without a parameter.
pub const DEFAULT_BLOCKS: usize = 1000;
/// Largest number of cubes accepted.
pub const MAX_BLOCKS: usize = 1_000_000;

/// Side of every cube, metres.
const SIDE: f32 = 0.12;
/// The room's extent, metres.
const ROOM: Vec3 = Vec3::new(4.0, 3.0, 4.0);
/// The region the cube centres fill, metres.
const REGION: (Vec3, Vec3) = (Vec3::new(0.4, 0.3, 0.4), Vec3::new(3.6, 2.3, 3.6));
/// Seed of the offsets within the cells.
const SEED: u64 = 11;

/// Parses the `N` of `blocks:N` (default [`DEFAULT_BLOCKS`]).
pub fn parse_count(parameter: Option<&str>) -> Result<usize, String> {
    super::parse_count("blocks", "cube", parameter, DEFAULT_BLOCKS, MAX_BLOCKS)
}

/// The room with `blocks` cubes.
pub fn scene(blocks: usize) -> Scene {
    let mut scene = Scene::empty("blocks");
    let white = scene.add_material(Material::diffuse("white", Rgb::splat(0.7)));
    let lamp = scene.add_material(Material {
        emission: Rgb::splat(10.0),
        ..Material::diffuse("lamp", Rgb::splat(0.8))
    });
    let colours = [
        scene.add_material(Material::diffuse("block-white", Rgb::splat(0.75))),
        scene.add_material(Material::diffuse("block-red", Rgb::new(0.7, 0.15, 0.1))),
        scene.add_material(Material::diffuse("block-green", Rgb::new(0.15, 0.6, 0.15))),
        scene.add_material(Material::diffuse("block-blue", Rgb::new(0.1, 0.2, 0.65))),
    ];
    scene.add_object(
        "room",
        Shape::Box {
            min: Vec3::ZERO,
            max: ROOM,
        },
        white,
    );
    let y = ROOM.y - 0.01;
    scene.add_object(
        "lamp",
        Shape::Parallelogram {
            origin: Vec3::new(1.5, y, 1.5),
            edge_u: Vec3::X,
            edge_v: Vec3::Z,
        },
        lamp,
    );
    // Cells per axis: the y axis gets fewer, in proportion to the region's height.
    let (lo, hi) = REGION;
    let extent = hi - lo;
    let per_unit = (blocks as f32 / (extent.x * extent.y * extent.z)).cbrt();
    let cells = (extent * per_unit).ceil().max(Vec3::ONE);
    let (nx, ny) = (cells.x as usize, cells.y as usize);
    let cell = extent / cells;
    let mut rng = Pcg32::seed_from_u64(SEED);
    let slack = (cell - Vec3::splat(SIDE)).max(Vec3::ZERO) * 0.5;
    for k in 0..blocks {
        let index = Vec3::new(
            (k % nx) as f32,
            ((k / nx) % ny) as f32,
            (k / (nx * ny)) as f32,
        );
        let jitter = Vec3::new(
            rng.random_range(-1.0..=1.0),
            rng.random_range(-1.0..=1.0),
            rng.random_range(-1.0..=1.0),
        );
        let centre = lo + (index + Vec3::splat(0.5)) * cell + jitter * slack;
        scene.add_object(
            &format!("block-{k}"),
            Shape::Box {
                min: centre - Vec3::splat(SIDE / 2.0),
                max: centre + Vec3::splat(SIDE / 2.0),
            },
            colours[k % colours.len()],
        );
    }
    scene.camera = Camera::landscape(Vec3::new(0.15, 1.6, 0.15), Vec3::new(2.4, 1.2, 2.6), 70.0);
    scene
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubes_fill_the_region_inside_the_room_without_touching() {
        for n in [1, 10, 1000] {
            let s = scene(n);
            assert_eq!(s.objects.len(), n + 2);
            let boxes: Vec<(Vec3, Vec3)> = s.objects[2..]
                .iter()
                .map(|o| match o.shape {
                    Shape::Box { min, max } => (min, max),
                    _ => panic!("not a box"),
                })
                .collect();
            for &(min, max) in &boxes {
                assert!(min.cmpgt(Vec3::ZERO).all() && max.cmplt(ROOM - 0.1).all());
            }
            for (i, a) in boxes.iter().enumerate() {
                for b in &boxes[i + 1..] {
                    let apart = a.1.cmplt(b.0).any() || b.1.cmplt(a.0).any();
                    assert!(apart, "{n}: {a:?} and {b:?} overlap");
                }
            }
        }
        assert_eq!(scene(5).objects[4].name.as_deref(), Some("block-2"));
        assert_eq!(parse_count(None), Ok(DEFAULT_BLOCKS));
        assert!(parse_count(Some("0")).is_err() && parse_count(Some("x")).is_err());
    }
}
