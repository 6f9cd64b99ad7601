//! Display of a radiosity solution (seed 000 §9.4, seed 001): camera rays hit the leaf
//! patches (as triangles, under a BVH) and show the radiance `B/π` of a Lambertian surface,
//! flat per leaf or smooth from the interpolated corner values ([`vertex_radiosity`]), with
//! the patch edges optionally drawn as black lines one pixel wide. Each side of a patch shows
//! its own radiosity. Surfaces that are not in the mesh (infinite planes) are not shown.

use super::interpolate::{CornerValues, vertex_radiosity};
use super::solution::Solution;
use super::system::RadiositySystem;
use crate::accel::{AccelKind, Accelerator, PrimHit, PrimitiveSet};
use crate::color::Rgb;
use crate::color::Rgb64;
use crate::geometry::{Aabb, Ray, Triangle};
use crate::measure::Film;
use crate::progress::{Cancel, ProgressListener};
use crate::radiosity::element::Side;
use crate::scene::Camera;
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Wireframe line half-width in pixels.
const LINE_HALF_WIDTH_PIXELS: f64 = 0.6;

/// How radiosity is shown across a patch (`--shading`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Shading {
    /// One colour per leaf patch.
    Flat,
    /// Corner values interpolated linearly over each triangle of the leaf.
    #[default]
    Smooth,
}

crate::choice::named_values!(Shading {
    Shading::Flat = "flat", "One colour per leaf patch";
    Shading::Smooth = "smooth", "Radiosity interpolated to the patch corners";
});

/// Image settings of the display.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DisplaySettings {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Flat or smooth.
    pub shading: Shading,
    /// Draw the leaf patch edges.
    pub wireframe: bool,
    /// Camera rays per pixel and axis (a regular grid; `n²` rays per pixel).
    pub samples_per_axis: u32,
}

/// The leaf patches as triangles: quads as the two triangles (0,1,2) and (0,2,3).
struct LeafTriangles {
    triangles: Vec<Triangle>,
    /// Per triangle: leaf index and the leaf's corner indices of its vertices.
    owners: Vec<(u32, [u8; 3])>,
}

impl LeafTriangles {
    fn new(system: &RadiositySystem) -> Self {
        let mut triangles = Vec::new();
        let mut owners = Vec::new();
        for (k, &leaf) in system.leaves.iter().enumerate() {
            let c = system.mesh.patch(leaf).corners();
            let splits: &[[u8; 3]] = if c.len() == 3 {
                &[[0, 1, 2]]
            } else {
                &[[0, 1, 2], [0, 2, 3]]
            };
            for &s in splits {
                let v = s.map(|i| c[i as usize].as_vec3());
                triangles.push(Triangle::new(v[0], v[1], v[2]));
                owners.push((k as u32, s));
            }
        }
        LeafTriangles { triangles, owners }
    }
}

impl PrimitiveSet for LeafTriangles {
    fn len(&self) -> usize {
        self.triangles.len()
    }

    fn bounds(&self, prim: u32) -> Aabb {
        Aabb::from_points(self.triangles[prim as usize].vertices())
    }

    fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<PrimHit> {
        self.triangles[prim as usize]
            .intersect(ray, t_max)
            .map(|(t, b1, b2)| PrimHit {
                t,
                prim,
                local: [b1, b2],
            })
    }
}

/// Renders `solution` (its display radiosity, ambient term included) through `camera` at
/// the settings' resolution as linear radiance, W·sr⁻¹·m⁻². `None` when the camera is
/// degenerate. Rows are rendered in parallel; `cancel` leaves the remaining rows black.
pub fn render_solution(
    system: &RadiositySystem,
    solution: &Solution,
    camera: &Camera,
    settings: &DisplaySettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Option<Film> {
    let rays = camera
        .with_resolution(settings.width, settings.height)
        .rays()?;
    let flat = solution.display_radiosity(system);
    let corners = Side::BOTH.map(|side| match settings.shading {
        Shading::Smooth => {
            let values: Vec<Rgb64> = (0..system.leaves.len())
                .map(|k| flat[RadiositySystem::element(k, side)])
                .collect();
            vertex_radiosity(&system.mesh, &system.leaves, &values)
        }
        Shading::Flat => Vec::new(),
    });
    let triangles = LeafTriangles::new(system);
    let accel = AccelKind::Bvh.build(&triangles);
    let view = Viewer {
        system,
        triangles: &triangles,
        accel: accel.as_ref(),
        flat: &flat,
        corners: &corners,
        settings,
        pixel_angle: 2.0 * (camera.fov_degrees.to_radians() as f64 * 0.5).tan()
            / settings.height as f64,
    };
    let n = settings.samples_per_axis.max(1);
    progress.start(settings.height as u64);
    let pixels: Vec<Rgb> = (0..settings.height)
        .into_par_iter()
        .flat_map_iter(|y| {
            let row: Vec<Rgb> = if cancel.is_requested() {
                vec![Rgb::BLACK; settings.width as usize]
            } else {
                (0..settings.width)
                    .map(|x| {
                        let mut sum = Rgb::BLACK;
                        for i in 0..n {
                            for j in 0..n {
                                let px = x as f32 + (i as f32 + 0.5) / n as f32;
                                let py = y as f32 + (j as f32 + 0.5) / n as f32;
                                sum += view.radiance(&rays.ray(px, py));
                            }
                        }
                        sum / (n * n) as f32
                    })
                    .collect()
            };
            progress.advance(1);
            row
        })
        .collect();
    progress.finish();
    Film::from_pixels(settings.width, settings.height, pixels)
}

/// What one camera ray sees.
struct Viewer<'a> {
    system: &'a RadiositySystem<'a>,
    triangles: &'a LeafTriangles,
    accel: &'a dyn Accelerator<LeafTriangles>,
    /// Display radiosity per element.
    flat: &'a [Rgb64],
    /// Smooth corner values per side, per leaf.
    corners: &'a [Vec<CornerValues>; 2],
    settings: &'a DisplaySettings,
    /// Angle one pixel subtends (radians, small-angle).
    pixel_angle: f64,
}

impl Viewer<'_> {
    fn radiance(&self, ray: &Ray) -> Rgb {
        let Some(hit) = self.accel.closest_hit(self.triangles, ray, f32::INFINITY) else {
            return Rgb::BLACK;
        };
        let (leaf, corner_ids) = self.triangles.owners[hit.prim as usize];
        let leaf = leaf as usize;
        let patch = self.system.mesh.patch(self.system.leaves[leaf]);
        let side = Side::hit_by(patch, ray.dir.as_dvec3());
        let [b1, b2] = hit.local.map(f64::from);
        if self.settings.wireframe {
            let p = self.triangles.triangles[hit.prim as usize]
                .point(hit.local[0], hit.local[1])
                .as_dvec3();
            let width = LINE_HALF_WIDTH_PIXELS * self.pixel_angle * hit.t as f64;
            if edge_distance(patch.corners(), p) < width {
                return Rgb::BLACK;
            }
        }
        let b: Rgb64 = match self.settings.shading {
            Shading::Flat => self.flat[RadiositySystem::element(leaf, side)],
            Shading::Smooth => {
                let c = &self.corners[side.index()][leaf];
                let w = [1.0 - b1 - b2, b1, b2];
                Rgb64::from(std::array::from_fn(|ch| {
                    (0..3).map(|v| w[v] * c[corner_ids[v] as usize][ch]).sum()
                }))
            }
        };
        b.map(|x| x / PI).to_f32()
    }
}

/// Distance from `p` to the nearest edge of the polygon `corners`.
fn edge_distance(corners: &[DVec3], p: DVec3) -> f64 {
    (0..corners.len())
        .map(|i| {
            let (a, b) = (corners[i], corners[(i + 1) % corners.len()]);
            let ab = b - a;
            let t = ((p - a).dot(ab) / ab.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
            p.distance(a + ab * t)
        })
        .fold(f64::INFINITY, f64::min)
}
