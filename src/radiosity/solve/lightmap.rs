//! Lightmaps of a solution's textured surfaces, for export: what each side of each root
//! patch of a textured material looks like — `E(uv) + ρ(uv)·H` as the display shows it, the
//! texture taken at every texel and the irradiance interpolated over the mesh — baked into
//! one atlas per object and material.
//!
//! Every side of a root patch is a chart: the patch's plane mapped by an orthonormal basis
//! (its longest edge and the side's normal) over the patch's bounding rectangle, at the
//! texture's own density in scene units (so the lightmap is as sharp as the texture), at
//! least [`MIN_CHART`] and at most [`MAX_CHART`] texels on a side. Charts are packed in rows
//! with a gutter of [`GUTTER`] texels; texels outside the patch take the value at the
//! nearest point of the patch, so filtering never mixes in another chart.

use super::lookup::RadiosityLookup;
use super::system::RadiositySystem;
use crate::color::Rgb;
use crate::geometry::Ray;
use crate::measure::{Film, LightmappedSurface};
use crate::radiosity::element::Side;
use crate::radiosity::mesh::{Patch, PatchId, PatchMesh};
use crate::radiosity::surface::is_textured;
use crate::scene::Scene;
use glam::{DVec2, DVec3, Vec2};
use rayon::prelude::*;
use std::collections::BTreeMap;

/// Fewest texels on a chart's side.
const MIN_CHART: u32 = 8;
/// Most texels on a chart's side.
const MAX_CHART: u32 = 1024;
/// Texels around each chart that repeat its edge.
const GUTTER: u32 = 1;

/// One side of a root patch laid flat in its surface's lightmap.
#[derive(Clone, Copy, Debug)]
struct Chart {
    root: PatchId,
    side: Side,
    /// The plane's origin (the first corner of the patch's longest edge) and orthonormal
    /// axes.
    origin: DVec3,
    axes: [DVec3; 2],
    /// The patch's extent along the axes: lowest coordinates and size, scene units.
    low: DVec2,
    size: DVec2,
    /// Texels of the chart (without the gutter).
    texels: [u32; 2],
    /// Where the chart's gutter starts in the atlas, texels.
    at: [u32; 2],
}

impl Chart {
    /// The chart of side `side` of `root`, `density` texels per scene unit.
    fn new(mesh: &PatchMesh, root: PatchId, side: Side, density: f64) -> Chart {
        let patch = mesh.patch(root);
        // The longest edge sets the first axis (a quad may repeat a corner).
        let c = patch.corners();
        let k = (0..c.len())
            .max_by(|&i, &j| {
                let edge = |i: usize| c[i].distance_squared(c[(i + 1) % c.len()]);
                edge(i).total_cmp(&edge(j))
            })
            .unwrap_or(0);
        let origin = c[k];
        let first = (c[(k + 1) % c.len()] - origin).normalize();
        let axes = [first, side.normal(patch).cross(first)];
        let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
        for &c in patch.corners() {
            let p = DVec2::new((c - origin).dot(axes[0]), (c - origin).dot(axes[1]));
            (lo, hi) = (lo.min(p), hi.max(p));
        }
        let size = hi - lo;
        let texels = |extent: f64| ((extent * density).ceil() as u32).clamp(MIN_CHART, MAX_CHART);
        Chart {
            root,
            side,
            origin,
            axes,
            low: lo,
            size,
            texels: [texels(size.x), texels(size.y)],
            at: [0, 0],
        }
    }

    /// Texels it takes in the atlas, gutter included.
    fn span(&self) -> [u32; 2] {
        self.texels.map(|t| t + 2 * GUTTER)
    }

    /// Where point `p` of the patch lies in the atlas, texels from its top-left corner.
    fn atlas_position(&self, p: DVec3) -> DVec2 {
        let local = DVec2::new(
            (p - self.origin).dot(self.axes[0]),
            (p - self.origin).dot(self.axes[1]),
        );
        let unit = (local - self.low) / self.size;
        let texels = DVec2::new(f64::from(self.texels[0]), f64::from(self.texels[1]));
        DVec2::new(f64::from(self.at[0]), f64::from(self.at[1]))
            + DVec2::splat(f64::from(GUTTER))
            + unit * texels
    }

    /// The point of the patch's plane at the centre of chart texel `(i, j)` (gutter
    /// included).
    fn texel_point(&self, i: u32, j: u32) -> DVec3 {
        let unit = DVec2::new(
            (f64::from(i) + 0.5 - f64::from(GUTTER)) / f64::from(self.texels[0]),
            (f64::from(j) + 0.5 - f64::from(GUTTER)) / f64::from(self.texels[1]),
        );
        let local = self.low + unit * self.size;
        self.origin + self.axes[0] * local.x + self.axes[1] * local.y
    }
}

/// The lightmapped surfaces of `system`'s textured materials with the charts of their root
/// patches, baked from `solution`; and per leaf (in the order of `system.leaves`) and side,
/// its surface and where its corners lie in that surface's lightmap (`[0, 1]²`, `(0, 0)` at
/// the bottom left).
pub(super) struct Lightmaps {
    pub surfaces: Vec<LightmappedSurface>,
    /// Per leaf and side (`2k + s`): the surface index and the corners' lightmap coordinates.
    pub corners: Vec<Option<(u32, Vec<Vec2>)>>,
}

impl Lightmaps {
    /// No lightmaps: every leaf side shown by its corners' radiosity.
    pub fn none(system: &RadiositySystem) -> Lightmaps {
        Lightmaps {
            surfaces: Vec::new(),
            corners: vec![None; 2 * system.leaves.len()],
        }
    }
}

/// Bakes the lightmaps of `system`'s textured surfaces from `lookup`, the display radiosity
/// of a solution looked up smooth with its texture detail.
pub(super) fn bake(system: &RadiositySystem, lookup: &RadiosityLookup) -> Lightmaps {
    let scene = &system.world().scene;
    let mesh = &system.mesh;
    // Textured roots grouped by object and material, in order.
    let mut groups: BTreeMap<(u32, u32), Vec<PatchId>> = BTreeMap::new();
    for &root in &mesh.roots {
        let patch = mesh.patch(root);
        if is_textured(scene, patch.material) {
            groups
                .entry((patch.object, patch.material))
                .or_default()
                .push(root);
        }
    }
    let mut surfaces = Vec::new();
    let mut chart_of: BTreeMap<(PatchId, usize), (u32, Chart, [u32; 2])> = BTreeMap::new();
    for ((object, material), roots) in groups {
        let mut charts: Vec<Chart> = roots
            .iter()
            .flat_map(|&root| {
                let density = texel_density(scene, mesh.patch(root));
                Side::BOTH.map(|side| Chart::new(mesh, root, side, density))
            })
            .collect();
        let size = pack(&mut charts);
        let lightmap = render(mesh, lookup, &charts, size);
        let surface = surfaces.len() as u32;
        for chart in charts {
            chart_of.insert((chart.root, chart.side.index()), (surface, chart, size));
        }
        let m = &scene.materials[material as usize];
        surfaces.push(LightmappedSurface {
            name: scene.object_name(object as usize),
            base_texture: m.diffuse_texture,
            alpha_texture: m.alpha_texture,
            lightmap,
        });
    }
    let corners = system
        .leaves
        .iter()
        .flat_map(|&leaf| Side::BOTH.map(move |side| (leaf, side)))
        .map(|(leaf, side)| {
            let patch = mesh.patch(leaf);
            let (surface, chart, size) = chart_of.get(&(root_of(mesh, leaf), side.index()))?;
            let size = DVec2::new(f64::from(size[0]), f64::from(size[1]));
            let uvs = patch
                .corners()
                .iter()
                .map(|&c| {
                    let t = chart.atlas_position(c) / size;
                    Vec2::new(t.x as f32, 1.0 - t.y as f32)
                })
                .collect();
            Some((*surface, uvs))
        })
        .collect();
    Lightmaps { surfaces, corners }
}

/// The root above `patch`.
fn root_of(mesh: &PatchMesh, mut patch: PatchId) -> PatchId {
    while let Some(parent) = mesh.patch(patch).parent {
        patch = parent;
    }
    patch
}

/// Texels per scene unit of the material textures on `patch`: the largest over its edges of
/// how many texels the edge spans over its length (1 when no texture is found).
fn texel_density(scene: &Scene, patch: &Patch) -> f64 {
    let m = &scene.materials[patch.material as usize];
    let Some(texture) = [m.diffuse_texture, m.emission_texture, m.alpha_texture]
        .into_iter()
        .flatten()
        .find_map(|t| scene.textures.get(t as usize))
    else {
        return 1.0;
    };
    let scale = DVec2::new(f64::from(texture.width), f64::from(texture.height));
    let (corners, uvs) = (patch.corners(), patch.uvs());
    let n = corners.len();
    (0..n)
        .map(|i| {
            let j = (i + 1) % n;
            let length = corners[i].distance(corners[j]);
            ((uvs[j] - uvs[i]) * scale).length() / length
        })
        .filter(|d| d.is_finite())
        .fold(1.0, f64::max)
}

/// Places `charts` in rows (tallest first) in an atlas whose width is a power of two at
/// least the square root of their total area; returns the atlas size in texels, the height
/// rounded up to a power of two too (what every viewer samples best).
fn pack(charts: &mut [Chart]) -> [u32; 2] {
    let area: u64 = charts
        .iter()
        .map(|c| u64::from(c.span()[0]) * u64::from(c.span()[1]))
        .sum();
    let widest = charts.iter().map(|c| c.span()[0]).max().unwrap_or(1);
    let width = ((area as f64).sqrt().ceil() as u32)
        .max(widest)
        .next_power_of_two();
    let mut order: Vec<usize> = (0..charts.len()).collect();
    order.sort_by_key(|&k| std::cmp::Reverse(charts[k].span()[1]));
    let (mut x, mut y, mut row) = (0, 0, 0);
    for k in order {
        let [w, h] = charts[k].span();
        if x + w > width {
            (x, y, row) = (0, y + row, 0);
        }
        charts[k].at = [x, y];
        x += w;
        row = row.max(h);
    }
    [width, (y + row).max(1).next_power_of_two()]
}

/// The atlas of `charts`, `size` texels: every texel the radiance the display shows at its
/// point of the chart's patch (the nearest point of the patch for texels outside it).
fn render(mesh: &PatchMesh, lookup: &RadiosityLookup, charts: &[Chart], size: [u32; 2]) -> Film {
    let mut film = Film::new(size[0], size[1]);
    let baked: Vec<Vec<(u32, u32, Rgb)>> = charts
        .par_iter()
        .map(|chart| {
            let patch = mesh.patch(chart.root);
            let normal = chart.side.normal(patch);
            let reach = 1e-4 * chart.size.max_element();
            let [w, h] = chart.span();
            let mut texels = Vec::with_capacity((w * h) as usize);
            for j in 0..h {
                for i in 0..w {
                    let p = nearest_point(patch.corners(), normal, chart.texel_point(i, j));
                    let ray = Ray::new((p + normal * reach).as_vec3(), (-normal).as_vec3());
                    // Under a cut-out, the surface's own radiance (not what lies behind it):
                    // a viewer filtering the lightmap mixes it into the texels beside.
                    let radiance = lookup
                        .hit_even_where_cut(&ray)
                        .map_or(Rgb::BLACK, |hit| hit.radiance);
                    texels.push((chart.at[0] + i, chart.at[1] + j, radiance));
                }
            }
            texels
        })
        .collect();
    for (x, y, radiance) in baked.into_iter().flatten() {
        film.set(x, y, radiance);
    }
    film
}

/// The point of the convex polygon `corners` (unit normal `normal`) nearest to `p`, a point
/// of its plane.
fn nearest_point(corners: &[DVec3], normal: DVec3, p: DVec3) -> DVec3 {
    let n = corners.len();
    let centroid = corners.iter().sum::<DVec3>() / n as f64;
    let mut nearest: Option<(f64, DVec3)> = None;
    for i in 0..n {
        let (a, b) = (corners[i], corners[(i + 1) % n]);
        // Outside an edge (either winding): the nearest point lies on such an edge.
        let outward = (b - a).cross(normal);
        let outward = if outward.dot(centroid - a) > 0.0 {
            -outward
        } else {
            outward
        };
        if outward.dot(p - a) > 0.0 {
            let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
            let q = a + (b - a) * t;
            let d = q.distance_squared(p);
            if nearest.is_none_or(|(best, _)| d < best) {
                nearest = Some((d, q));
            }
        }
    }
    nearest.map_or(p, |(_, q)| q)
}
