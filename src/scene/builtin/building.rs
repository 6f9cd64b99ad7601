//! `building` / `building:N`: a storey of N furnished offices (default 100, about 10⁵
//! triangles), for radiosity on scenes the size of real buildings without large files.
//!
//! - The offices stand in a grid of ⌈√N⌉ columns (x) and as many rows (z) as it takes,
//!   4 m × 3 m × 4 m inside, 0.2 m apart; each is closed, its floor, ceiling and walls tiled
//!   in squares of 0.5 m as pairs of triangles (every surface a mesh of triangles, as a
//!   modelling program writes it).
//! - In each office: two desks (a top on four legs), four chairs (a seat, a back, four legs),
//!   a shelf against the back wall (a case and three boards), placed with a fixed
//!   pseudo-random jitter (`Pcg32::seed_from_u64(17)`), and a Lambertian downlight 5 cm
//!   under the ceiling's centre of intensity 0.5 W·sr⁻¹ (π/2 W).
//! - Reported surfaces: `floors`, `ceilings`, `walls`, `desks`, `chairs`, `shelves`, each
//!   one object holding that part of every office; materials: floor 0.3, ceiling 0.8,
//!   walls 0.7, desks a wood (0.5, 0.35, 0.2), chairs (0.2, 0.2, 0.25), shelves 0.6.
//! - Sensors: one facing up 0.75 m above the floor at each office's centre.
//! - The camera looks into the first office from a corner.

use crate::color::Rgb;
use crate::scene::{Camera, Light, LightKind, Material, PolygonMesh, Scene, Sensor, Shape};
use glam::Vec3;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg32;
use std::sync::Arc;

/// Offices without a parameter.
pub const DEFAULT_OFFICES: usize = 100;
/// Most offices accepted.
pub const MAX_OFFICES: usize = 10_000;

/// An office's inside, metres.
const OFFICE: Vec3 = Vec3::new(4.0, 3.0, 4.0);
/// The gap between offices, metres.
const GAP: f32 = 0.2;
/// Side of a floor, ceiling or wall tile, metres.
const TILE: f32 = 0.5;
/// Seed of the furniture's jitter.
const SEED: u64 = 17;

/// Parses the `N` of `building:N` (default [`DEFAULT_OFFICES`]).
pub fn parse_count(parameter: Option<&str>) -> Result<usize, String> {
    super::parse_count(
        "building",
        "office",
        parameter,
        DEFAULT_OFFICES,
        MAX_OFFICES,
    )
}

/// Triangles of one reported surface, gathered over every office.
#[derive(Default)]
struct Part {
    positions: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
}

impl Part {
    /// The parallelogram `origin + s·u + t·v`, `s, t ∈ [0, 1]`, as `nu × nv` tiles of two
    /// triangles each, facing `u × v`.
    fn tiled(&mut self, origin: Vec3, u: Vec3, v: Vec3, (nu, nv): (u32, u32)) {
        let first = self.positions.len() as u32;
        for j in 0..=nv {
            for i in 0..=nu {
                let (s, t) = (i as f32 / nu as f32, j as f32 / nv as f32);
                self.positions.push(origin + s * u + t * v);
            }
        }
        let at = |i: u32, j: u32| first + j * (nu + 1) + i;
        for j in 0..nv {
            for i in 0..nu {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                self.triangles.push([a, b, c]);
                self.triangles.push([a, c, d]);
            }
        }
    }

    /// The six faces of the box from `min` to `max`, two triangles each, facing out.
    fn cuboid(&mut self, min: Vec3, max: Vec3) {
        let size = max - min;
        let (x, y, z) = (Vec3::X * size.x, Vec3::Y * size.y, Vec3::Z * size.z);
        for (origin, u, v) in [
            (min, z, y),
            (min + x, y, z),
            (min, x, z),
            (min + y, z, x),
            (min, y, x),
            (min + z, x, y),
        ] {
            self.tiled(origin, u, v, (1, 1));
        }
    }

    /// The part as a mesh shape.
    fn shape(self) -> Shape {
        Shape::Mesh(Arc::new(PolygonMesh::from_triangles(
            self.positions,
            &self.triangles,
        )))
    }
}

/// The storey of `offices` offices.
pub fn scene(offices: usize) -> Scene {
    let mut scene = Scene::empty("building");
    let materials = [
        ("floors", Rgb::splat(0.3)),
        ("ceilings", Rgb::splat(0.8)),
        ("walls", Rgb::splat(0.7)),
        ("desks", Rgb::new(0.5, 0.35, 0.2)),
        ("chairs", Rgb::new(0.2, 0.2, 0.25)),
        ("shelves", Rgb::splat(0.6)),
    ];
    let mut parts: [Part; 6] = Default::default();
    let [floors, ceilings, walls, desks, chairs, shelves] = &mut parts;
    let columns = (offices as f64).sqrt().ceil() as usize;
    let mut rng = Pcg32::seed_from_u64(SEED);
    let mut jitter = |range: f32| rng.random_range(-range..=range);
    let (x, y, z) = (Vec3::X * OFFICE.x, Vec3::Y * OFFICE.y, Vec3::Z * OFFICE.z);
    let tiles = |size: f32| (size / TILE).round() as u32;
    let (nx, ny, nz) = (tiles(OFFICE.x), tiles(OFFICE.y), tiles(OFFICE.z));
    for k in 0..offices {
        let o = Vec3::new(
            (k % columns) as f32 * (OFFICE.x + GAP),
            0.0,
            (k / columns) as f32 * (OFFICE.z + GAP),
        );
        // Every face of the office facing into it.
        floors.tiled(o, z, x, (nz, nx));
        ceilings.tiled(o + y, x, z, (nx, nz));
        walls.tiled(o, x, y, (nx, ny));
        walls.tiled(o + z, y, x, (ny, nx));
        walls.tiled(o, y, z, (ny, nz));
        walls.tiled(o + x, z, y, (nz, ny));
        // Two desks side by side facing the back wall, each with two chairs.
        for d in 0..2 {
            let corner = o + Vec3::new(0.6 + 1.5 * d as f32 + jitter(0.1), 0.0, 1.4 + jitter(0.2));
            let (width, depth, height) = (1.2, 0.7, 0.72);
            desks.cuboid(
                corner + Vec3::new(0.0, height - 0.03, 0.0),
                corner + Vec3::new(width, height, depth),
            );
            for (lx, lz) in [
                (0.0, 0.0),
                (width - 0.05, 0.0),
                (0.0, depth - 0.05),
                (width - 0.05, depth - 0.05),
            ] {
                let leg = corner + Vec3::new(lx, 0.0, lz);
                desks.cuboid(leg, leg + Vec3::new(0.05, height - 0.03, 0.05));
            }
            for c in 0..2 {
                let seat = corner
                    + Vec3::new(
                        0.15 + 0.5 * c as f32 + jitter(0.05),
                        0.0,
                        depth + 0.15 + jitter(0.1),
                    );
                chairs.cuboid(
                    seat + Vec3::new(0.0, 0.42, 0.0),
                    seat + Vec3::new(0.42, 0.46, 0.42),
                );
                chairs.cuboid(
                    seat + Vec3::new(0.0, 0.46, 0.38),
                    seat + Vec3::new(0.42, 0.9, 0.42),
                );
                for (lx, lz) in [(0.0, 0.0), (0.38, 0.0), (0.0, 0.38), (0.38, 0.38)] {
                    let leg = seat + Vec3::new(lx, 0.0, lz);
                    chairs.cuboid(leg, leg + Vec3::new(0.04, 0.42, 0.04));
                }
            }
        }
        // A shelf against the back wall (z = 4 m), 5 cm off it.
        let shelf = o + Vec3::new(1.0 + jitter(0.5), 0.0, OFFICE.z - 0.45);
        shelves.cuboid(shelf, shelf + Vec3::new(1.6, 0.05, 0.4));
        shelves.cuboid(
            shelf + Vec3::new(0.0, 1.95, 0.0),
            shelf + Vec3::new(1.6, 2.0, 0.4),
        );
        for b in 1..4 {
            let h = 0.5 * b as f32;
            shelves.cuboid(
                shelf + Vec3::new(0.0, h, 0.0),
                shelf + Vec3::new(1.6, h + 0.03, 0.4),
            );
        }
        scene.lights.push(Light {
            name: Some(format!("lamp-{k}")),
            kind: LightKind::Lambertian {
                position: o + Vec3::new(OFFICE.x / 2.0, OFFICE.y - 0.05, OFFICE.z / 2.0),
                direction: Vec3::NEG_Y,
                intensity: Rgb::splat(0.5),
            },
        });
        scene.sensors.push(Sensor {
            name: format!("office-{k}"),
            position: o + Vec3::new(OFFICE.x / 2.0, 0.75, OFFICE.z / 2.0),
            normal: Vec3::Y,
        });
    }
    for ((name, reflectance), part) in materials.into_iter().zip(parts) {
        let material = scene.add_material(Material::diffuse(name, reflectance));
        scene.add_object(name, part.shape(), material);
    }
    scene.camera = Camera::landscape(Vec3::new(0.2, 1.6, 0.2), Vec3::new(2.4, 1.0, 3.0), 70.0);
    scene
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hundred_offices_make_about_a_hundred_thousand_triangles() {
        let s = scene(DEFAULT_OFFICES);
        let names: Vec<&str> = s.objects.iter().filter_map(|o| o.name.as_deref()).collect();
        assert_eq!(
            names,
            ["floors", "ceilings", "walls", "desks", "chairs", "shelves"]
        );
        let triangles: usize = s
            .objects
            .iter()
            .map(|o| match &o.shape {
                Shape::Mesh(mesh) => mesh.face_sizes.len(),
                _ => panic!("not a mesh"),
            })
            .sum();
        // Per office: 2 × (64 + 64 + 4 × 48) tiles' triangles, 2 desks of 5 boxes, 4 chairs
        // of 6 and a shelf of 5, 12 triangles a box.
        assert_eq!(triangles, 100 * (2 * (64 + 64 + 192) + 12 * (10 + 24 + 5)));
        assert_eq!((s.lights.len(), s.sensors.len()), (100, 100));
        assert_eq!(parse_count(None), Ok(DEFAULT_OFFICES));
        assert!(parse_count(Some("0")).is_err());
    }

    #[test]
    fn the_furniture_stays_inside_its_office() {
        let s = scene(4);
        for o in &s.objects {
            let Shape::Mesh(mesh) = &o.shape else {
                panic!("not a mesh")
            };
            for p in &mesh.positions {
                // Offices at x, z ∈ {0, 4.2}: every point within one of them.
                let inside = |c: f32, size: f32| {
                    (0.0..=size).contains(&c) || (size + GAP..=2.0 * size + GAP).contains(&c)
                };
                assert!(inside(p.x, OFFICE.x) && inside(p.z, OFFICE.z), "{p}");
                assert!((0.0..=OFFICE.y).contains(&p.y), "{p}");
            }
        }
    }
}
